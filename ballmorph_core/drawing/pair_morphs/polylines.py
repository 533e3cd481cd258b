"""Polylines: strokes made of straight edges between corners (a house, a zig-zag, hatching).

A ball-morph bends straight edges into arcs and rounds corners; Grease Pencil's POLY strokes
drawn point by point should stay polylines. When both strokes of a pair are polylines with the
same number of corners, the pair is morphed corner to corner: each corner travels straight to
its partner (on the carrier), and each edge stays the straight segment between its corners,
with as many points as the denser key has on it.

A stroke is a polyline when its vertices either turn by more than ``STRAIGHT`` (corners) or not
at all, with at most ``FEW`` corners or most vertices on straight runs (a coarse circle of 30
points turning 12 degrees at each is a curve, not a 30-gon; nor is a curve that happens to have
an inflection vertex).
"""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...geometry.ragged import Ragged, ragged_arange
from ...morphs.base import PathMorph
from ...morphs.paths import LinearPaths

__all__ = ["STRAIGHT", "RUN_OFF", "FEW", "Corners", "corners", "corners_of", "polyline_morph"]

#: A vertex turning by at most this (radians) lies on a straight edge (float32 keys: about 1e-7).
STRAIGHT = 1e-4
#: ... and lies within this fraction of the stroke's size of the line through its corners (a
#: dense smooth curve turns less than STRAIGHT at every vertex, yet is no straight run).
RUN_OFF = 1e-6
#: A polyline has at most this many corners, or most of its vertices on straight runs.
FEW = 12


@dataclass
class Corners:
    """The corners of a polyline.

    Attributes
    ----------
    index : ndarray of int, shape (K,)
        Corner vertices in order (a stroke's ends included).
    u : ndarray, shape (N,)
        Arc-length fraction of every vertex.
    """

    index: np.ndarray
    u: np.ndarray


def _straight(rg):
    """Vertices turning by at most ``STRAIGHT``, shape (N,) of bool (an open stroke's ends turn).

    ``|atan2(cross, dot)| <= STRAIGHT`` is ``dot > 0`` and ``|cross| <= tan(STRAIGHT) dot``:
    plain products, so a vertex is judged alike whatever batch it comes in (vectorised arctan2
    may round a lane of a batch differently from the same value alone).
    """
    # The edges into and out of each vertex (zero past an open stroke's ends).
    d1 = rg.edge
    d0 = np.where((rg.prv >= 0)[:, None], np.take(rg.edge, np.maximum(rg.prv, 0), axis=0), 0.0)
    cross = d0[:, 0] * d1[:, 1] - d0[:, 1] * d1[:, 0]
    dot = d0[:, 0] * d1[:, 0] + d0[:, 1] * d1[:, 1]
    return (dot > 0) & (np.abs(cross) <= _TAN_STRAIGHT * dot)


_TAN_STRAIGHT = float(np.tan(STRAIGHT))


def _off_runs(rg, corner):
    """Largest distance of a vertex from the line through the corners around it, per curve,
    shape (C,) (curves with a corner: an open curve's ends are; a loop's run on past its start)."""
    idx = np.arange(len(rg.pts))
    first, last = rg.offsets[:-1], rg.offsets[1:] - 1
    lower, upper = np.repeat(first, rg.n), np.repeat(last, rg.n)
    before = np.maximum.accumulate(np.where(corner, idx, -1))
    after = np.minimum.accumulate(np.where(corner, idx, len(idx))[::-1])[::-1]
    # A loop's vertices before its first corner lie after its last one, and the other way round.
    c = np.r_[np.flatnonzero(corner), len(idx)]
    first_corner = c[np.searchsorted(c, first)]
    last_corner = c[np.maximum(np.searchsorted(c, last, side="right") - 1, 0)]
    before = np.where(before < lower, np.repeat(last_corner, rg.n), before)
    after = np.where(after > upper, np.repeat(first_corner, rg.n), after)
    # A curve without corners (its runs are never asked for): every vertex on itself.
    ok = (before >= lower) & (before <= upper) & (after >= lower) & (after <= upper)
    before, after = np.where(ok, before, idx), np.where(ok, after, idx)
    a, b, p = rg.pts[before], rg.pts[after], rg.pts
    d = b - a
    length = np.maximum(np.linalg.norm(d, axis=1), tol.TINY)
    cross = d[:, 0] * (p - a)[:, 1] - d[:, 1] * (p - a)[:, 0]
    off = np.zeros(len(rg))
    np.maximum.at(off, rg.owner, np.abs(cross / length))
    return off


def corners(xy, closed):
    """The corners of a stroke if it is a polyline (see the module docstring), else None (one
    stroke of :func:`corners_of`).

    Parameters
    ----------
    xy : ndarray, shape (N, 2)
        Distinct consecutive points.
    closed : bool

    Returns
    -------
    Corners or None
    """
    return corners_of([xy], [closed])[0]


def corners_of(curves, closed):
    """The corners of every stroke that is a polyline (see the module docstring), else None,
    all strokes at once.

    Parameters
    ----------
    curves : list of ndarray, shape (N_i, 2)
    closed : array_like of bool, shape (C,)

    Returns
    -------
    list of (Corners or None)
        None also for a stroke of fewer than two points or with a repeated point (a loop's
        last point repeating its first included: :func:`~ballmorph_core.geometry.polyline.as_curve` drops it).
    """
    rg = Ragged.from_list(curves, closed)
    out = [None] * len(rg)
    if not len(rg.pts):
        return out
    corner = ~_straight(rg)
    count = np.bincount(rg.owner[corner], minlength=len(rg))
    repeated = np.bincount(rg.owner[(rg.length_of_edge == 0) & (rg.nxt >= 0)], minlength=len(rg)) > 0
    some = (rg.n >= 2) & ~repeated & (count >= np.where(rg.closed, 3, 2)) & ((count <= FEW) | (count <= rg.n // 3))
    if not some.any():
        return out
    box = rg.boxes()
    size = np.maximum(box[:, 2] - box[:, 0], box[:, 3] - box[:, 1])
    # A dense curve turns too little at each vertex to show corners.
    some &= ~(_off_runs(rg, corner) > RUN_OFF * size)
    for c in np.flatnonzero(some):
        # Each stroke's own running sum (the batch's arc lengths are one sum, shifted per curve).
        start = rg.offsets[c]
        s = np.r_[0.0, np.cumsum(rg.length_of_edge[start : start + rg.n_edges[c]])]
        out[c] = Corners(np.flatnonzero(corner[start : rg.offsets[c + 1]]), s[: rg.n[c]] / s[-1])
    return out


def _edges(c, n, closed):
    """(first corner, next corner) vertex index of every edge, the next one past n for a loop."""
    nxt = np.r_[c[1:], c[0] + n] if closed else c[1:]
    return c[: len(nxt)], nxt


def polyline_morph(xy_a, ca, xy_b, cb, closed, motion_a):
    """Corner-to-corner morph of two polylines with as many corners (PathMorph ``'polyline'``).

    Parameters
    ----------
    xy_a, xy_b : ndarray, shape (N, 2), (M, 2)
        The strokes (the second running the same way).
    ca, cb : Corners
        Their corners, as many on each.
    closed : bool
    motion_a : callable
        ``(K, 2) -> (K, 2)``: the registration taking the first stroke onto the second (the
        carrier undoes it); the paths run from the registered first stroke.

    Returns
    -------
    PathMorph
        For loops the second's corners start at the one that makes the corners travel least.
    """
    ka = len(ca.index)
    shift = 0
    if closed:
        ra, rb = motion_a(xy_a[ca.index]), xy_b[cb.index]
        travel = [np.sum((ra - np.roll(rb, -s, axis=0)) ** 2) for s in range(ka)]
        shift = int(np.argmin(travel))
    idx_b = np.roll(cb.index, -shift)
    if closed and shift:
        idx_b = np.where(np.arange(ka) >= ka - shift, idx_b + len(xy_b), idx_b)  # unwrap past the start
    a0, a1 = _edges(ca.index, len(xy_a), closed)
    b0, b1 = _edges(np.asarray(idx_b), len(xy_b), closed)
    # Points on each edge (its last corner excluded, but for an open stroke's last edge).
    count = np.maximum(a1 - a0, b1 - b0)
    extra = np.zeros(len(count), np.int64)
    if not closed:
        extra[-1] = 1
    edge, k = ragged_arange(count + extra)
    f = k / count[edge]
    p, u_p = _along(xy_a, ca.u, a0[edge], a1[edge], f)
    q, u_q = _along(xy_b, cb.u, b0[edge], b1[edge], f)
    return PathMorph("polyline", closed, LinearPaths(motion_a(p), q), u_p, np.mod(u_q, 1.0) if closed else u_q)


def _along(xy, u, first, last, f):
    """Points and arc-length fractions at fractions ``f`` (M,) of the straight edges from vertex
    ``first`` to ``last`` (shape (M,) each; a loop's past ``n`` run on into its next lap)."""
    n = len(xy)
    a, b = xy[first % n], xy[last % n]
    ua, ub = u[first % n] + np.where(first >= n, 1.0, 0.0), u[last % n] + np.where(last >= n, 1.0, 0.0)
    return a + f[:, None] * (b - a), ua + f * (ub - ua)
