"""Which pairs get a carrier motion (the *register* step's choice, issue 11).

A carrier is for a pair that *moved*: turned, swung, travelled, grew. The ball-morph alone
follows two kinds of pairs as they are drawn, and they get none:

- pairs the paper's configurations take directly: strokes sharing both endpoints (within
  ``tolerances.NEAR_SHARED_END``: the ends settle the rest, see :mod:`.ends`), loops one
  inside the other without crossing (configurations 2 and 1);
- loops that overlap (at least ``OVERLAPPING`` of one lies inside the other) and whose
  registration explains little of their difference: the closest-point distance between the
  registered loops is still more than ``SHAPE_CHANGE`` of what it was before. Such a pair
  changed its *shape* where it lies (a glyph's outline growing bolder, a blob bulging out on
  one side), and a carrier would only bend every point's path by a turn and a scale that
  belong to no motion of the drawing. Loops side by side keep their carrier however badly it
  fits: the ball-morph cannot take one onto the other without it.
- open strokes whose registration explains as little (the same letter in two handwriting
  styles): a carrier fitted to them turned by 53-68 degrees and scaled by 0.35-0.66, a motion
  the pair does not share, and its in-betweens crossed themselves and left the keys' box by 13 %
  (issue 38). Without one they take the tangent-aligned route (:mod:`.deforming`): straight
  paths between matched points stay within the keys' convex hull.
"""

import numpy as np

from ... import tolerances as tol
from ...geometry.intersections import batch_crossings, simple_curves
from ...geometry.projection import NearestEdges
from .pair_plans import PairNote
from .registration import Motions, fit_pairs, identity_residual, motions, moved_curves

__all__ = [
    "SHAPE_CHANGE",
    "OVERLAPPING",
    "carrier_motions",
    "note_shape_changes",
    "handled_directly",
    "closest_distance",
    "closest_distances",
    "inside_fraction",
    "shape_changes",
]

#: A loop's registration that leaves more than this fraction of the loops' closest-point
#: distance explains little of it: the loops changed shape rather than moved (no carrier).
#: A moved, turned or scaled copy leaves about nothing; a glyph's outline at another weight
#: leaves 75-140 % (its registration only shrinks it into the middle of the bolder stroke).
SHAPE_CHANGE = 0.5

#: A fit whose RMS sample residual is below this fraction of the samples' distance as drawn
#: (both by the best cyclic shift) explains the change: a cheap screen before the closest-point
#: distances. On the glyphs and scenes measured the closest-point ratio is never below about
#: 0.7 of the samples' one where it exceeds ``SHAPE_CHANGE``, so this keeps a margin of 1.4.
SCREEN = 0.25

#: Loops overlap when at least this fraction of one's outline lies inside the other.
OVERLAPPING = 0.5

#: Uniform samples per curve for the closest-point distances and the overlap.
DISTANCE_SAMPLES = 128


#: Pairs measured at a time by :func:`closest_distance`.
CLOSEST_BATCH = 256


def handled_directly(P, Q, scale):
    """Pairs the ball-morph follows as they are drawn: strokes sharing both endpoints, loops
    one inside the other without crossing (paper configurations 2 and 1), shape (C,) of bool.

    Parameters
    ----------
    P, Q : Ragged
        The pairs' curves, as drawn.
    scale : ndarray, shape (C,)
    """
    n, closed = len(P), P.closed
    end_eps = tol.NEAR_SHARED_END * scale  # ends meant to be shared are (issue 39)
    first = np.linalg.norm(P.pts[P.offsets[:-1]] - Q.pts[Q.offsets[:-1]], axis=1) <= end_eps
    last = np.linalg.norm(P.pts[P.offsets[1:] - 1] - Q.pts[Q.offsets[1:] - 1], axis=1) <= end_eps
    # A loop inside another has its box inside the other's: a cheap necessary test first.
    bp, bq = P.boxes(), Q.boxes()
    p_in_q = np.all(bp[:, :2] >= bq[:, :2], axis=1) & np.all(bp[:, 2:] <= bq[:, 2:], axis=1)
    q_in_p = np.all(bq[:, :2] >= bp[:, :2], axis=1) & np.all(bq[:, 2:] <= bp[:, 2:], axis=1)
    nested = closed & (p_in_q | q_in_p)
    ask = np.flatnonzero(nested)
    nested[ask] = P.contains(np.take(Q.pts, Q.offsets[ask], axis=0), ask) | Q.contains(
        np.take(P.pts, P.offsets[ask], axis=0), ask
    )
    if nested.any():
        cx = batch_crossings(P, Q, scale, nested)
        nested &= np.bincount(cx.pair, minlength=n) == 0
    return (~closed & first & last) | nested


def closest_distance(P, Q):
    """Symmetric RMS closest-point distance between each P and its Q, shape (C,).

    Uniform samples of each curve are projected on the other curve (the nearest point of its
    edges), both ways: unlike a sample-to-sample distance it does not depend on where the
    curves start or how their lengths are shared out.

    Parameters
    ----------
    P, Q : Ragged
        Same number of curves.
    """
    return _distances_to(Q, (P,))[0]


def closest_distances(P, M, Q):
    """:func:`closest_distance` of P and of M (P registered) to the same Q, ``(before, after)``
    shape (C,) each: Q's samples and edges made once for both."""
    return _distances_to(Q, (P, M))


def _distances_to(Q, curves):
    """:func:`closest_distance` of each of ``curves`` (tuple of Ragged, as many curves as Q) to
    Q, a tuple of arrays shape (C,)."""
    n = len(Q)
    if n > CLOSEST_BATCH:
        # A few hundred pairs at a time: the projection's tables grow with the batch (5,000
        # strokes at once held 110 MiB); each pair's distance is its own.
        parts = [np.arange(start, min(start + CLOSEST_BATCH, n)) for start in range(0, n, CLOSEST_BATCH)]
        each = [_distances_to(Q.take(rows), tuple(a.take(rows) for a in curves)) for rows in parts]
        return tuple(np.concatenate(x) for x in zip(*each))
    q_samples = Q.resample(np.full(n, DISTANCE_SAMPLES), smooth=False)
    on_q = NearestEdges(Q)
    out = []
    for a in curves:
        samples = a.resample(np.full(n, DISTANCE_SAMPLES), smooth=False)
        to_q, _, _ = on_q.within(samples.pts, samples.owner, np.inf)
        to_a, _, _ = NearestEdges(a).within(q_samples.pts, q_samples.owner, np.inf)
        out.append(np.sqrt((_mean_square(to_q, samples.owner, n) + _mean_square(to_a, q_samples.owner, n)) / 2.0))
    return tuple(out)


def _mean_square(dist, owner, n):
    """Mean square of the distances of each curve's samples, shape (n,)."""
    return np.bincount(owner, np.square(dist), minlength=n) / np.bincount(owner, minlength=n)


def inside_fraction(P, Q):
    """Fraction of each loop P's outline (uniform samples) inside its loop Q, shape (C,)."""
    samples = P.resample(np.full(len(P), DISTANCE_SAMPLES), smooth=False)
    inside = Q.contains(samples.pts, samples.owner)
    return np.bincount(samples.owner, inside, minlength=len(P)) / np.bincount(samples.owner, minlength=len(P))


def shape_changes(P, Q, fits, ask):
    """Overlapping loops whose registration explains little of their difference (see
    ``OVERLAPPING`` and ``SHAPE_CHANGE``).

    Parameters
    ----------
    P, Q : Ragged
        The pairs' curves, as drawn.
    fits : Fits
        Each P's registration onto its Q.
    ask : ndarray of bool, shape (C,)
        The pairs to consider (the others are False).

    Returns
    -------
    changed : ndarray of bool, shape (C,)
    kept : ndarray, shape (C,)
        The fraction of the distance the registration leaves (NaN where not asked).
    """
    kept = np.full(len(P), np.nan)
    rows = np.flatnonzero(ask)
    # The cheap screen first: a fit that removes most of the samples' own distance explains
    # the change (the closest-point ratio is then below SHAPE_CHANGE too). The registered
    # curve's own uniform samples, not P's moved: an affine fit shares arc length out anew.
    M = moved_curves(P, fits.A, fits.b)  # the registered curves, for the screen and the distances
    if len(rows):
        Pr, Qr = P.take(rows), Q.take(rows)
        rows = rows[identity_residual(M.take(rows), Qr) > SCREEN * identity_residual(Pr, Qr)]
    # Open strokes asked only when neither crosses itself: such a pair keeps its carrier and
    # the fallback that says so (asked after the screen: the test of every curve's edges
    # against each other took half the planning of 400 open strokes of 500 points).
    strokes = rows[~P.closed[rows]]
    if len(strokes):
        curves = [c for k in strokes for c in (P.curve(k), Q.curve(k))]
        tangled = ~simple_curves(curves, np.zeros(len(curves), dtype=bool)).reshape(-1, 2).all(axis=1)
        rows = np.setdiff1d(rows, strokes[tangled])
    if len(rows):
        Pr, Qr = P.take(rows), Q.take(rows)
        before, after = closest_distances(Pr, M.take(rows), Qr)
        kept[rows] = np.divide(after, before, out=np.zeros(len(rows)), where=before > 0)
        rows = rows[kept[rows] > SHAPE_CHANGE]
    # Loops side by side keep their carrier (the costliest test, for the few loops left).
    loops = rows[P.closed[rows]]
    if len(loops):
        Pr, Qr = P.take(loops), Q.take(loops)
        apart = loops[np.maximum(inside_fraction(Pr, Qr), inside_fraction(Qr, Pr)) < OVERLAPPING]
        rows = np.setdiff1d(rows, apart)
    changed = np.zeros(len(P), dtype=bool)
    changed[rows] = True
    return changed, kept


def carrier_motions(P, Q, carrier, scale, drawing=None, rides=None):
    """The carrier of every pair (see the module docstring).

    Parameters
    ----------
    P, Q : Ragged
        The pairs' curves, as drawn (each Q running the way its P does).
    carrier : {'similarity', 'rigid', 'none'}
    scale : ndarray, shape (C,)
    drawing : Similarity, optional
        The keys' overall motion (symmetric shapes turn with it).
    rides : Rides, optional
        What each pair rides (see :func:`.registration.motions`).

    Returns
    -------
    motions : Motions
    shape_change : ndarray, shape (C,)
        For loops left without a carrier because they change shape, the fraction of their
        distance the registration left; NaN for the other pairs.
    """
    n, kind = len(P), "rigid" if carrier == "rigid" else "similarity"
    kept = np.full(n, np.nan)
    if carrier == "none":
        return Motions.identity(n, kind), kept
    turn, size = (0.0, 1.0) if drawing is None else (drawing.turn, drawing.scale)
    fits = fit_pairs(P, Q, turn=turn, scale=size)
    still = (np.abs(fits.A - np.eye(2)).max(axis=(1, 2)) <= tol.IDENTITY) & (
        np.linalg.norm(fits.b, axis=1) <= tol.IDENTITY * scale
    )
    ask = ~handled_directly(P, Q, scale) & ~still
    changed, kept = shape_changes(P, Q, fits, ask)
    kept[~changed] = np.nan
    return motions(P, fits, kind, scale, ask & ~changed, drawing, rides=rides), kept


def note_shape_changes(index, motion, shape_change):
    """Why each pair that changes shape got no carrier, as notes of its report.

    Parameters
    ----------
    index : ndarray of int, shape (C,)
        The batch's pairs in the drawing.
    motion : Motions
    shape_change : ndarray, shape (C,)
        From :func:`carrier_motions`.

    Returns
    -------
    tuple of PairNote
    """
    notes = []
    for c in np.flatnonzero(~np.isnan(shape_change) & ~motion.moving):
        if np.isinf(shape_change[c]):
            text = "no carrier: squashed in place it travels less than turned by its registration"
        else:
            text = (
                f"no carrier: its registration leaves {shape_change[c]:.0%} of the curves' distance"
                " (they change shape, they do not move)"
            )
        notes.append(PairNote(int(index[c]), text))
    return tuple(notes)
