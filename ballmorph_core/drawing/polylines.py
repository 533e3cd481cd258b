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

from ..geometry.ragged import Ragged
from ..morphs.base import PathMorph
from ..morphs.paths import LinearPaths

__all__ = ["STRAIGHT", "RUN_OFF", "FEW", "Corners", "corners", "may_have_corners", "polyline_morph"]

#: A vertex turning by at most this (radians) lies on a straight edge (float32 keys: about 1e-7).
STRAIGHT = 1e-4
#: ... and lies within this fraction of the stroke's size of the line through its corners (a
#: dense smooth curve turns less than STRAIGHT at every vertex, yet is no straight run).
RUN_OFF = 1e-6
#: A polyline has at most this many corners, or most of its vertices on straight runs.
FEW = 12
#: :func:`may_have_corners` counts corners at STRAIGHT give or take this fraction of it, so
#: round-off never makes it drop a curve :func:`corners` would take.
CORNER_MARGIN = 1e-6


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


def _turns(xy, closed):
    """Turning angle at every vertex, shape (N,) (an open stroke's ends turn by pi)."""
    prev = np.roll(xy, 1, axis=0) if closed else np.r_[xy[:1], xy[:-1]]
    nxt = np.roll(xy, -1, axis=0) if closed else np.r_[xy[1:], xy[-1:]]
    d0, d1 = xy - prev, nxt - xy
    cross = d0[:, 0] * d1[:, 1] - d0[:, 1] * d1[:, 0]
    turn = np.abs(np.arctan2(cross, np.einsum("ij,ij->i", d0, d1)))
    if not closed:
        turn[[0, -1]] = np.pi
    return turn


def _off_runs(xy, corner, closed):
    """Largest distance of a vertex from the line through the corners around it (float)."""
    n = len(xy)
    idx = np.arange(n)
    c = np.flatnonzero(corner)
    if closed:  # unroll once so every vertex has a corner before and after it
        idx = np.arange(c[0], c[0] + n + 1)
    at = corner[idx % n]
    before = np.maximum.accumulate(np.where(at, idx, idx[0]))
    after = np.minimum.accumulate(np.where(at, idx, idx[-1])[::-1])[::-1]
    a, b, p = xy[before % n], xy[after % n], xy[idx % n]
    d = b - a
    length = np.maximum(np.linalg.norm(d, axis=1), 1e-300)
    cross = d[:, 0] * (p - a)[:, 1] - d[:, 1] * (p - a)[:, 0]
    return float(np.abs(cross / length).max(initial=0.0))


def corners(xy, closed):
    """The corners of a stroke if it is a polyline (see the module docstring), else None.

    Parameters
    ----------
    xy : ndarray, shape (N, 2)
        Distinct consecutive points.
    closed : bool

    Returns
    -------
    Corners or None
    """
    if len(xy) < 2 or np.any(np.linalg.norm(np.diff(xy, axis=0), axis=1) == 0):
        return None
    turn = _turns(xy, closed)
    straight = turn <= STRAIGHT
    corner = ~straight
    count = int(corner.sum())
    if count < (3 if closed else 2) or not (count <= FEW or count <= len(xy) // 3):
        return None
    if _off_runs(xy, corner, closed) > RUN_OFF * float(np.ptp(xy, axis=0).max()):
        return None  # a dense curve turns too little at each vertex to show corners
    edges = np.linalg.norm((np.roll(xy, -1, axis=0) if closed else xy[1:]) - xy[: len(xy) if closed else -1], axis=1)
    s = np.r_[0.0, np.cumsum(edges)]
    return Corners(np.flatnonzero(corner), s[: len(xy)] / s[-1])


def may_have_corners(curves, closed):
    """Which curves :func:`corners` may find a polyline in, all at once: those whose count of
    vertices turning by more than ``STRAIGHT`` (within ``CORNER_MARGIN`` either way) could pass
    its corner-count test. The others are not polylines; only these need :func:`corners`.

    Parameters
    ----------
    curves : list of ndarray, shape (N_i, 2)
        Distinct consecutive points, at least two.
    closed : array_like of bool, shape (C,)

    Returns
    -------
    ndarray of bool, shape (C,)
    """
    rg = Ragged.from_list(curves, closed)
    idx = np.arange(len(rg.pts))
    prev = np.take(rg.pts, np.where(rg.prv >= 0, rg.prv, idx), axis=0)
    nxt = np.take(rg.pts, np.where(rg.nxt >= 0, rg.nxt, idx), axis=0)
    d0, d1 = rg.pts - prev, nxt - rg.pts
    cross = d0[:, 0] * d1[:, 1] - d0[:, 1] * d1[:, 0]
    turn = np.abs(np.arctan2(cross, np.einsum("ij,ij->i", d0, d1)))
    end = (rg.prv < 0) | (rg.nxt < 0)  # an open stroke's ends are corners
    most = np.bincount(rg.owner[end | (turn > STRAIGHT * (1.0 - CORNER_MARGIN))], minlength=len(rg))
    least = np.bincount(rg.owner[end | (turn > STRAIGHT * (1.0 + CORNER_MARGIN))], minlength=len(rg))
    return (most >= np.where(rg.closed, 3, 2)) & ((least <= FEW) | (least <= rg.n // 3))


def _edges(c, n, closed):
    """(first corner, next corner) vertex index of every edge, the next one past n for a loop."""
    nxt = np.r_[c[1:], c[0] + n] if closed else c[1:]
    return c[: len(nxt)], nxt


def _along(xy, u, first, last, f, closed):
    """Points and fractions at fractions ``f`` (M,) of the straight edge from vertex ``first`` to ``last``."""
    n = len(xy)
    a, b = xy[first % n], xy[last % n]
    ua, ub = u[first % n] + (1.0 if first >= n else 0.0), u[last % n] + (1.0 if last >= n else 0.0)
    return a + f[:, None] * (b - a), ua + f * (ub - ua)


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
    p, q, u_p, u_q = [], [], [], []
    for e in range(len(a0)):
        count = max(a1[e] - a0[e], b1[e] - b0[e])  # points on the edge, its last corner excluded
        last = e == len(a0) - 1 and not closed
        f = np.arange(count + (1 if last else 0)) / count
        pa, fa = _along(xy_a, ca.u, a0[e], a1[e], f, closed)
        pb, fb = _along(xy_b, cb.u, b0[e], b1[e], f, closed)
        p.append(pa), q.append(pb), u_p.append(fa), u_q.append(np.mod(fb, 1.0) if closed else fb)
    p, q = np.concatenate(p), np.concatenate(q)
    return PathMorph("polyline", closed, LinearPaths(motion_a(p), q), np.concatenate(u_p), np.concatenate(u_q))
