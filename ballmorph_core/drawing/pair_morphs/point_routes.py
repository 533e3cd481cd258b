"""The routes that keep the keys' own points (before the ball route): pairs whose points match one
for one under a similarity (:mod:`.exact_fit`) and polylines with as many corners
(:mod:`.polylines`), each on its carrier, each returning what it planned (:class:`.Planned`) and
guarded so that a failure sends its pairs on; and dots, moved straight or riding on their
group's or the drawing's turn (:class:`.riding.Rides`)."""

import numpy as np

from ... import tolerances as tol
from ...geometry.polyline import pair_scales
from ...geometry.ragged import Ragged
from ...geometry.similarity import from_complex
from ...morphs.base import PathMorph
from ...morphs.paths import LinearPaths
from ..strokes import Route
from .carrier_choice import carrier_motions, note_shape_changes
from .exact_fit import exact_fit, may_be_exact
from .fallbacks import point_motion
from .pair_plans import Planned, whole_segment
from .polylines import corners_of, polyline_morph
from .registration import Fits, motions, riding_fits, similarity_matrices

__all__ = ["guarded", "dot_route", "own_points_route", "polyline_route"]


def guarded(route, pairs, ready, carrier, drawing, rides):
    """A route for the pairs it takes (what it planned, and the other ready pairs); should it
    fail (a bug), it takes none of them and every ready pair goes on to the ball route, which
    has its own pair-by-pair isolation."""
    try:
        return route(pairs, ready, carrier, drawing, rides)
    except Exception:  # the ball route plans them instead, and reports anything it cannot do
        return Planned.nothing(), ready


def _taken(pairs, found, route, segments, motion, notes=()):
    """What a route that keeps the keys' points planned for the pairs ``found`` (ints): their
    whole-pair ``segments`` on their carriers ``motion``."""
    index = np.asarray(found, dtype=np.int64)
    return Planned(
        index,
        (route,) * len(index),
        np.array([pairs[c].closed for c in index], dtype=bool),
        np.array([pairs[c].lengths for c in index], dtype=np.float64).reshape(-1, 2),
        tuple(segments),
        tuple(notes),
        motion,
    )


def polyline_route(pairs, ready, carrier, drawing, rides):
    """Pairs of polylines with as many corners (see :mod:`.polylines`): corner to corner, edges
    straight, on the carrier.

    Returns
    -------
    planned : Planned
        What it planned for the pairs it took.
    rest : list of int
        The other ready pairs.
    """
    found, rest = [], []
    closed = [pairs[c].closed for c in ready]
    of_p, of_q = corners_of([pairs[c].P for c in ready], closed), corners_of([pairs[c].Q for c in ready], closed)
    for c, ca, cb in zip(ready, of_p, of_q):
        if ca is None or cb is None or len(ca.index) != len(cb.index):
            rest.append(c)
        else:
            found.append((c, ca, cb))
    if not found:
        return Planned.nothing(), rest
    index = np.array([c for c, _, _ in found])
    P = Ragged.from_list([pairs[c].P for c in index], [pairs[c].closed for c in index])
    Q = Ragged.from_list([pairs[c].Q for c in index], P.closed)
    scale = pair_scales(P, Q)
    motion, shape_change = carrier_motions(P, Q, carrier, scale, drawing, rides.take(index))
    segments = []
    for k, (c, ca, cb) in enumerate(found):
        pair = pairs[c]

        def register_a(pts, k=k):
            return pts @ motion.A[k].T + motion.b[k] if motion.moving[k] else pts

        morph = polyline_morph(pair.P, ca, pair.Q, cb, pair.closed, register_a)
        segments.append(whole_segment(c, morph, pair.lengths))
    notes = note_shape_changes(index, motion, shape_change)
    return _taken(pairs, index, Route.POLYLINE, segments, motion, notes), rest


def own_points_route(pairs, ready, carrier, drawing, rides):
    """Pairs whose points match one for one under a similarity (see :mod:`.exact_fit`): the key's
    own points, moved by the carrier (a loop that rides a turn matched at the turn it rides).

    Returns
    -------
    planned : Planned
        What it planned for the pairs it took.
    rest : list of int
        The other ready pairs.
    """
    rest, found = [], []
    turn = 0.0 if drawing is None else drawing.turn
    maybe = may_be_exact(
        [pairs[c].xy_a for c in ready], [pairs[c].xy_b for c in ready], [pairs[c].closed for c in ready]
    )
    for c, tried in zip(ready, maybe):
        pair = pairs[c]
        own = turn if np.isnan(rides.a[c]) else float(np.angle(rides.a[c]))
        fit = exact_fit(pair.xy_a, pair.xy_b, pair.closed, similarity=carrier != "none", turn=own) if tried else None
        if fit is None:
            rest.append(c)
        else:
            found.append((c, fit))
    if not found:
        return Planned.nothing(), rest
    index = np.array([c for c, _ in found])
    P = Ragged.from_list([pairs[c].xy_a for c in index], [pairs[c].closed for c in index])
    a = np.array([fit.a for _, fit in found])
    b = np.array([fit.b for _, fit in found])
    Q = Ragged.from_list([pairs[c].xy_b for c in index], P.closed)
    scale = pair_scales(P, Q)
    still = (np.abs(a - 1.0) <= tol.IDENTITY) & (np.abs(b) <= tol.IDENTITY * scale)
    fits = Fits(similarity_matrices(a), from_complex(b), np.zeros(len(index)))
    kind = "rigid" if carrier == "rigid" else "similarity"
    motion = motions(P, fits, kind, scale, ~still & (carrier != "none"), drawing, rides=rides.take(index))
    segments = []
    for k, (c, fit) in enumerate(found):
        pair = pairs[c]
        moved = pair.xy_a @ motion.A[k].T + motion.b[k] if motion.moving[k] else pair.xy_a
        order = (np.arange(len(pair.xy_b)) + fit.shift) % len(pair.xy_b)
        morph = PathMorph("own points", pair.closed, LinearPaths(moved, pair.xy_b[order]), pair.u_a, pair.u_b[order])
        segments.append(whole_segment(c, morph, pair.lengths))
    return _taken(pairs, index, Route.OWN_POINTS, segments, motion), rest


def dot_route(pairs, dots, carrier, drawing, rides):
    """Pairs with no shape to fit (strokes of fewer than two distinct points: dots): straight
    point motion, on the turn they ride (``rides``: their group's, or the drawing's when it
    turns and shows it; see :func:`.registration.riding_fits`; pivoting where the drawing or the
    group does, a dot on a turning wheel rides its arc; with carrier 'none', as the paper's
    comparison morphs' dots, straight and ``rides`` unused). What it planned (:class:`.Planned`)."""
    if not dots:
        return Planned.nothing()
    xy = [pairs[c].xy_a for c in dots], [pairs[c].xy_b for c in dots]
    motion = None
    if carrier == "none":
        moving = np.zeros(len(dots), bool)
    else:
        P, Q = (Ragged.from_list(side, np.zeros(len(dots), bool)) for side in xy)
        ridden = rides.take(np.asarray(dots))
        fits, moving = riding_fits(P, Q, ridden.a)
        # The reach of a pivot: the drawing's size (a dot has none of its own).
        every = np.concatenate([pair.xy_a for pair in pairs])
        size = np.full(len(dots), float(np.linalg.norm(every.max(axis=0) - every.min(axis=0))))
        kind = "rigid" if carrier == "rigid" else "similarity"
        motion = motions(P, fits, kind, size, moving, drawing, rides=ridden)
    segments = []
    for k, c in enumerate(dots):
        pair = pairs[c]
        start = pair.xy_a @ motion.A[k].T + motion.b[k] if moving[k] else pair.xy_a
        segments.append(whole_segment(c, point_motion(start, pair.u_a, pair.xy_b, pair.u_b), (1.0, 1.0)))
    n = len(dots)
    return Planned(
        np.asarray(dots, dtype=np.int64),
        (Route.DOT,) * n,
        np.zeros(n, bool),
        np.ones((n, 2)),
        tuple(segments),
        motions=motion,
    )
