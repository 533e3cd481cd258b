"""Open strokes whose registered ends do not meet: overhangs and end gaps.

After registration an open stroke P and its partner Q rarely share their endpoints: the animator
drew one a little longer, started an outline elsewhere, opened a circle's gap. A ball-map needs
strokes that share both ends, so each end is settled first:

* an *overhang*: where one curve's end lies along the other (a longer stroke, an outline started
  further on), the other curve's part beyond it does not morph into anything: it slides along
  itself into (or grows out of) that end, so an outline stays on itself and a widening gap opens
  along the circle;
* an *end gap*: what is left between the two ends is closed by displacing the registered P's
  common part (by the two gaps, blended along it), and the in-betweens undo that displacement
  as ``1 - t``, so at ``t = 0`` they are P and at ``t = 1`` exactly Q.

The common parts (P displaced, Q) then share both ends and go through the crossings and the
ball-map as any stroke pair.

Ends within ``tolerances.NEAR_SHARED_END`` of each other (of the pair's size) are meant to be
shared (a rope pinned at both ends, redrawn a hair off its pins): such an end gap is no overhang,
and it is not undone as ``1 - t`` either (the in-betweens' ends would then sweep across the pins
and consecutive in-betweens cross there). Both common parts meet halfway instead, P displaced by
half the gap and Q by minus half: every in-between's end is the pins' midpoint, between the
keys' ends, and consecutive in-betweens meet there without crossing.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ... import tolerances as tol
from ...geometry.projection import nearest_within
from ...geometry.ragged import Ragged, ragged_arange
from ...morphs.base import PathMorph

__all__ = ["ALONG", "Ends", "settle_ends", "overhang_morph"]

#: An end lies along the other curve when it is within this fraction of the pair's size of it.
ALONG = 0.05


@dataclass
class Ends:
    """How each pair's registered curves meet at their ends, and their common parts.

    Attributes
    ----------
    keep_p, keep_q : ndarray, shape (C, 2)
        Arc-length range of R (the registered P) and of Q in their common part (the whole curves
        for pairs not settled).
    gap : ndarray, shape (C, 2, 2)
        The end gaps ``(Q's first - R's first, Q's last - R's last)`` of the common parts.
    common_p, common_q : Ragged
        The common parts, R's displaced by the gaps so both share their ends.
    u : ndarray, shape (N,)
        Fraction along R's common part (before the displacement) of each vertex of ``common_p``.
    """

    keep_p: np.ndarray
    keep_q: np.ndarray
    gap: np.ndarray
    common_p: Ragged
    common_q: Ragged
    u: np.ndarray

    @property
    def settled(self):
        """Pairs whose curves were trimmed or displaced, shape (C,) of bool."""
        whole_p = (self.keep_p[:, 0] == 0) & (self.keep_p[:, 1] == self.common_p.length)
        return np.any(self.gap != 0, axis=(1, 2)) | ~whole_p | (self.keep_q[:, 0] > 0)

    def _fraction(self, pair, s):
        """Fraction along R's common part (before the displacement) at arc lengths ``s`` of
        ``common_p``, shape (K,)."""
        edge, frac = self.common_p.locate(pair, s)
        nxt = np.maximum(self.common_p.nxt[edge], 0)
        return self.u[edge] + frac * (self.u[nxt] - self.u[edge])

    def on_p(self, pair, s):
        """Arc lengths on R of arc lengths ``s`` on the common parts of ``pair`` (same shapes)."""
        pair, s = np.broadcast_arrays(np.asarray(pair, dtype=np.int64), np.asarray(s, dtype=np.float64))
        return self._on_p(pair, self._fraction(pair.ravel(), s.ravel()).reshape(s.shape))

    def place(self, pair, s):
        """:meth:`on_p` and :meth:`offsets` of the same samples, from one location on the
        common parts: arc lengths on R, shape (K,), and offsets, shape (K, 2)."""
        pair = np.asarray(pair, dtype=np.int64)
        u = self._fraction(pair, np.asarray(s, dtype=np.float64))
        return self._on_p(pair, u), self._offsets(pair, u)

    def _on_p(self, pair, u):
        return self.keep_p[pair, 0] + u * (self.keep_p[pair, 1] - self.keep_p[pair, 0])

    def _offsets(self, pair, u):
        return -((1 - u)[:, None] * self.gap[pair, 0] + u[:, None] * self.gap[pair, 1])

    def on_q(self, pair, s):
        """Arc lengths on Q of arc lengths ``s`` on the common parts of ``pair``."""
        return self.keep_q[pair, 0] + np.asarray(s)

    def offsets(self, pair, s):
        """What undoes the displacement at arc lengths ``s`` along the common parts, shape (K, 2).

        Added as ``(1 - t)`` times this to the in-between samples there, they start on R.

        Parameters
        ----------
        pair : ndarray of int, shape (K,)
        s : ndarray, shape (K,)
            Arc lengths along ``common_p``.
        """
        pair = np.asarray(pair, dtype=np.int64)
        if not len(pair):
            return np.zeros((0, 2))
        return self._offsets(pair, self._fraction(pair, np.asarray(s, dtype=np.float64)))


def _ends_onto(A, B, reach, rows):
    """Where the first and the last ends of curves ``rows`` of A lie along B: arc length on B,
    distance (shapes (2, K): first ends, then last; ``reach`` per curve of A), both ends in one
    search of the stretches of B's edges that may lie within reach (:func:`_reachable`)."""
    ends = np.take(A.pts, np.r_[A.offsets[rows], A.offsets[rows + 1] - 1], axis=0)
    first, count = (np.concatenate(v) for v in _reachable(ends.reshape(2, -1, 2), rows, B, reach[rows]))
    curve, r = np.r_[rows, rows], np.r_[reach[rows], reach[rows]]
    dist, edge, frac = np.full(len(ends), np.inf), np.zeros(len(ends), np.int64), np.zeros(len(ends))
    some = np.flatnonzero(count >= 2)
    if len(some):
        # Each query searches its own stretch, a curve of its own: the same edges (the same
        # differences of the same points), the same arithmetic and, in the same order, the
        # same ties as a search of its whole curve.
        start = B.offsets[curve[some]] + first[some]
        owner, local = ragged_arange(count[some])
        vertex = start[owner] + local  # the stretches' vertices in B
        stretch = Ragged(
            np.take(B.pts, vertex, axis=0),
            np.r_[0, np.cumsum(count[some])],
            B.closed[curve[some]] & (count[some] == B.n[curve[some]]),
        )
        d, e, f = nearest_within(ends[some], np.arange(len(some)), stretch, r[some])
        found = np.isfinite(d)
        dist[some], frac[some] = d, f
        edge[some[found]] = vertex[e[found]]
    return (B.s[edge] + frac * B.length_of_edge[edge]).reshape(2, -1), dist.reshape(2, -1)


#: Both vertices of an edge within reach ``r`` of a point lie within ``r`` plus its length of
#: it: the stretch searched runs from the first to the last vertex within this many times
#: ``r`` plus the curve's longest edge (a margin for round-off, however large the coordinates).
_STRETCH_MARGIN = 2.0


def _reachable(points, curves, B, reach):
    """The stretch of its curve of B each query searches (see ``_STRETCH_MARGIN``): it holds
    every edge within reach (a loop's closing edge only in a stretch of the whole loop).

    Parameters
    ----------
    points : ndarray, shape (J, K, 2)
        ``J`` queries per curve.
    curves : ndarray of int, shape (K,)
        Their curves of B (with points).
    B : Ragged
    reach : ndarray, shape (K,)

    Returns
    -------
    first, count : ndarray of int, shape (J, K)
        The stretch's first vertex (local to its curve) and its vertex count (below 2 when
        no edge lies within reach).
    """
    n = B.n[curves]
    if len(curves) == len(B) and np.array_equal(curves, np.arange(len(B))):  # every curve: B's own arrays
        owner, local = B.owner, np.arange(len(B.pts)) - np.repeat(B.offsets[:-1], n)
        x, y, lengths = B.pts[:, 0], B.pts[:, 1], B.length_of_edge
    else:
        owner, local = ragged_arange(n)
        v = B.offsets[curves][owner] + local
        x, y, lengths = np.take(B.pts[:, 0], v), np.take(B.pts[:, 1], v), np.take(B.length_of_edge, v)
    longest = np.maximum.reduceat(lengths, np.cumsum(n) - n)
    span = reach + longest
    bound = _STRETCH_MARGIN * span + tol.ROUNDOFF * (np.abs(points).max(axis=(0, 2)) + span)
    bound2 = np.repeat(np.square(bound), n)
    first, count = np.zeros(points.shape[:2], np.int64), np.zeros(points.shape[:2], np.int64)
    for j, p in enumerate(points):
        dx, dy = x - np.repeat(p[:, 0], n), y - np.repeat(p[:, 1], n)
        near = np.flatnonzero(dx * dx + dy * dy <= bound2)
        if not len(near):
            continue
        # Near vertices come curve by curve, in order: each curve's first and last of them.
        k = owner[near]
        opens, closes = np.r_[True, k[1:] != k[:-1]], np.r_[k[1:] != k[:-1], True]
        q = k[opens]
        first[j, q] = local[near[opens]]
        count[j, q] = local[near[closes]] - first[j, q] + 1
    return first, count


def _along(s_on_other, dist, length_other, end_tol, which):
    """Whether an end lies along the other curve's interior, and how deep (a fraction of its length)."""
    depth = s_on_other if which == 0 else length_other - s_on_other
    return np.isfinite(dist) & (depth > end_tol), depth / np.maximum(length_other, tol.TINY)


def _trims(R, Q, scale, trim, pin):
    """The common parts' arc-length ranges on R and Q, shapes (C, 2) each (``pin``: the pairs
    whose ends meant to be shared are, shape (C,))."""
    n = len(R)
    keep_p, keep_q = np.c_[np.zeros(n), R.length], np.c_[np.zeros(n), Q.length]
    # An end within NEAR_SHARED_END of the other's, as drawn, is meant to be shared: a gap to
    # close, not an overhang to slide.
    end_tol, reach = np.where(pin, tol.NEAR_SHARED_END, tol.SHARED_ENDPOINT) * scale, ALONG * scale
    rows = np.flatnonzero(trim)  # only their ends are searched (none for loops)
    if len(rows):
        on_q, on_r = _ends_onto(R, Q, reach, rows), _ends_onto(Q, R, reach, rows)
    for which in (0, 1):
        if not len(rows):
            break
        (s_q, d_q), (s_r, d_r) = (tuple(v[which] for v in found) for found in (on_q, on_r))
        # R's end along Q: Q overhangs; Q's end along R: R overhangs.
        q_over, q_depth = _along(s_q, d_q, Q.length[rows], end_tol[rows], which)
        r_over, r_depth = _along(s_r, d_r, R.length[rows], end_tol[rows], which)
        # Both ends along the other (the strokes overlap there): the shallower trim.
        trim_q = q_over & (~r_over | (q_depth <= r_depth))
        trim_r = r_over & ~trim_q
        keep_q[rows[trim_q], which] = s_q[trim_q]
        keep_p[rows[trim_r], which] = s_r[trim_r]
    # A trim that leaves no common part would morph nothing: keep those pairs whole.
    empty = (keep_p[:, 1] - keep_p[:, 0] <= end_tol) | (keep_q[:, 1] - keep_q[:, 0] <= end_tol)
    keep_p[empty], keep_q[empty] = np.c_[np.zeros(n), R.length][empty], np.c_[np.zeros(n), Q.length][empty]
    return keep_p, keep_q


def settle_ends(R, Q, scale, opened, trim=None, pin=None):
    """The common parts and end gaps of every open pair (see the module docstring).

    Parameters
    ----------
    R, Q : Ragged
        The registered first curves and the second curves.
    scale : ndarray, shape (C,)
        Size of each pair.
    opened : ndarray of bool, shape (C,)
        The pairs to settle (open strokes on the ball route); the others stay whole.
    trim : ndarray of bool, shape (C,), optional
        The settled pairs whose overhangs may be trimmed (default: all); the others are only
        displaced (pieces cut at hints: their ends are the hinted points).
    pin : ndarray of bool, shape (C,), optional
        The pairs whose ends within ``tolerances.NEAR_SHARED_END`` are meant to be shared (of
        those trimmed): pairs taken as drawn, without a carrier (default: none). After a
        registration, ends that nearly meet say how well it fits, not where the animator
        pinned them.

    Returns
    -------
    Ends
    """
    n = len(R)
    trim = opened if trim is None else opened & trim
    pin = trim & (np.zeros(n, bool) if pin is None else pin)
    keep_p, keep_q = _trims(R, Q, scale, trim, pin)
    if not opened.any():  # a drawing of loops: every pair stays exactly as it is
        return Ends(keep_p, keep_q, np.zeros((n, 2, 2)), R, Q, R.s / np.maximum(R.length, tol.TINY)[R.owner])
    idx = np.arange(n)
    part_p, part_q = R.pieces(idx, keep_p[:, 0], keep_p[:, 1]), Q.pieces(idx, keep_q[:, 0], keep_q[:, 1])
    first = part_q.pts[part_q.offsets[:-1]] - part_p.pts[part_p.offsets[:-1]]
    last = part_q.pts[part_q.offsets[1:] - 1] - part_p.pts[part_p.offsets[1:] - 1]
    gap = np.where(opened[:, None, None], np.stack([first, last], axis=1), 0.0)
    # Ends already shared need no displacement.
    width = np.linalg.norm(gap, axis=2)[..., None]
    gap = np.where(width <= tol.SHARED_ENDPOINT * scale[:, None, None], 0.0, gap)
    # Ends meant to be shared (untrimmed: not an overhang's; not a hinted piece's, whose ends
    # are the hinted points) meet halfway, for good.
    whole_ends = np.stack([(keep_p[:, 0] == 0) & (keep_q[:, 0] == 0), _untrimmed(keep_p, keep_q, R, Q)], axis=1)
    whole_ends &= pin[:, None]
    pinned = np.where((width <= tol.NEAR_SHARED_END * scale[:, None, None]) & whole_ends[..., None], 0.5 * gap, 0.0)
    part_q = _displaced(part_q, part_q.s / np.maximum(part_q.length, tol.TINY)[part_q.owner], -pinned)
    # R meets Q halfway at those ends; beyond that (the other gaps) it is displaced by what
    # the in-betweens undo as 1 - t.
    moved_by, gap = gap - pinned, gap - 2 * pinned
    u = part_p.s / np.maximum(part_p.length, tol.TINY)[part_p.owner]
    common_p = _displaced(part_p, u, moved_by, R.closed)
    # The pieces are open curves: of open pairs they are the common parts as they come.
    common_q = Ragged(part_q.pts, part_q.offsets, Q.closed) if Q.closed.any() else part_q
    whole = ~opened
    if whole.any():  # loops (and pairs not settled) stay exactly as they are
        common_p, common_q = _merge(common_p, R, whole), _merge(common_q, Q, whole)
        u = common_p.s / np.maximum(common_p.length, tol.TINY)[common_p.owner]
    return Ends(keep_p, keep_q, gap, common_p, common_q, u)


def _untrimmed(keep_p, keep_q, R, Q):
    """Pairs whose last ends are both kept (no overhang there), shape (C,)."""
    return (keep_p[:, 1] == R.length) & (keep_q[:, 1] == Q.length)


def _displaced(part, u, gap, closed=None):
    """Curves ``part`` (Ragged) displaced by ``(1 - u) gap_first + u gap_last`` (``u``: each
    vertex's fraction along its curve, shape (N,); ``gap``: shape (C, 2, 2)), coordinate by
    coordinate (1-D gathers of the pairs' gaps, not (N, 2) rows of them: the same values,
    several times faster); the same ``part`` where no gap is and ``closed`` is not given."""
    if closed is None and not np.any(gap):
        return part
    moved, rest = np.empty_like(part.pts), 1 - u
    for k in range(2):
        shift = rest * np.take(gap[:, 0, k], part.owner)
        shift += u * np.take(gap[:, 1, k], part.owner)
        np.add(part.pts[:, k], shift, out=moved[:, k])
    return Ragged(moved, part.offsets, part.closed if closed is None else closed)


def _merge(parts, whole, keep):
    """``parts`` with the curves ``keep`` replaced by those of ``whole`` (Ragged)."""
    counts = np.where(keep, whole.n, parts.n)
    owner, local = ragged_arange(counts)
    mine = keep[owner]
    pts = np.empty((len(owner), 2))
    pts[mine] = np.take(whole.pts, whole.offsets[owner[mine]] + local[mine], axis=0)
    pts[~mine] = np.take(parts.pts, parts.offsets[owner[~mine]] + local[~mine], axis=0)
    return Ragged(pts, np.concatenate([[0], np.cumsum(counts)]), whole.closed)


class _SlidingPaths:
    """Points sliding along curves at constant speed into (or out of) one point of them, all
    carried by ``t`` times a vector (the displacement of the end they are attached to).

    Parameters
    ----------
    curves : list of ndarray, shape (n_i, 2)
        Open curves, batched only if these paths are evaluated on their own: the layout joins
        the overhangs of a drawing and evaluates their joined batch only.
    curve : ndarray of int, shape (K,)
        Each point's curve.
    s, attach : ndarray, shape (K,)
        Each point's arc length at ``t = 0`` (``t = 1`` when growing) and where it joins.
    towards : ndarray, shape (K, 2)
    grow : ndarray of bool, shape (K,)
        Growing runs the shrinking backwards in time.
    """

    def __init__(self, curves, curve, s, attach, towards, grow):
        self._curves, self._curve, self._s, self._attach = curves, curve, s, attach
        self._towards, self._grow = towards, grow

    @cached_property
    def _locator(self):
        """Where the points' arc lengths lie on their curves, found frame after frame."""
        return Ragged.from_list(self._curves, False).locator(self._curve)

    @cached_property
    def _span(self):
        """How far each point slides, ``attach - s`` (K,): the same at every time."""
        return self._attach - self._s

    @classmethod
    def join(cls, parts):
        """Many of them (``(paths, kept points)`` each, the points as indices) as one: one
        evaluation for them all."""
        curves = [c for paths, _ in parts for c in paths._curves]
        first = np.cumsum([0] + [len(paths._curves) for paths, _ in parts[:-1]])
        # Every part's columns joined, then their kept points taken at once (hundreds of parts).
        sizes = np.array([len(paths._s) for paths, _ in parts], dtype=np.int64)
        kept = np.concatenate([keep + start for (_, keep), start in zip(parts, np.cumsum(sizes) - sizes)])
        curve = np.concatenate([paths._curve for paths, _ in parts]) + np.repeat(first, sizes)
        columns = [
            np.concatenate([getattr(paths, name) for paths, _ in parts])
            for name in ("_s", "_attach", "_towards", "_grow")
        ]
        return cls(curves, curve[kept], *(np.take(column, kept, axis=0) for column in columns))

    def __len__(self):
        return len(self._s)

    def at(self, t):
        t = float(t)
        time = np.where(self._grow, 1.0 - t, t)
        along = self._s + time * self._span
        points = self._locator.point_at(along)
        return points + np.where(self._grow, t - 1.0, t)[:, None] * self._towards

    @property
    def start(self):
        return self.at(0.0)

    @property
    def end(self):
        return self.at(1.0)

    def lengths(self):
        return np.abs(self._span)


def _even(start, stop, count):
    """``np.linspace(start, stop, count)`` of finite floats, ``count >= 2``, by its own
    arithmetic (``i * step + start``, the last one ``stop``) without its checks, which cost ten
    times that: a drawing makes two for every overhang."""
    values = np.arange(count, dtype=np.float64)
    span = stop - start
    step = span / (count - 1)
    if step == 0.0:
        # A span that underflows when divided (subnormal): numpy divides first, then scales.
        values /= count - 1
        values *= span
    else:
        values *= step
    values += start
    values[-1] = stop
    return values


def overhang_morph(curve, s0, s1, attach, towards, grow, spacing):
    """The part of an open curve between arc lengths ``s0`` and ``s1`` sliding along itself
    into (``grow=False``) or out of (``grow=True``) the point at arc length ``attach``.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
        The registered P for a shrinking overhang, Q for a growing one.
    s0, s1 : float
        The overhang's arc-length range.
    attach : float
        Where it joins the common part (``s0`` or ``s1``).
    towards : ndarray, shape (2,)
        The end gap there (the common part's end moves by ``t`` times it).
    grow : bool
    spacing : float
        Sample spacing.

    Returns
    -------
    PathMorph
        ``'overhang'``: samples in order along the curve; ``u_p``/``u_q`` are fractions along
        the overhang.
    """
    count = max(int(np.ceil((s1 - s0) / max(spacing, tol.TINY))) + 1, 2)
    s, u = _even(s0, s1, count), _even(0.0, 1.0, count)
    # Filled in place rather than by np.full and np.broadcast_to (a drawing makes hundreds of
    # overhangs: their Python wrappers cost several times the filling).
    columns = np.empty(count), np.empty((count, 2)), np.empty(count, dtype=bool)
    columns[0].fill(float(attach))
    columns[1][:] = towards
    columns[2].fill(bool(grow))
    paths = _SlidingPaths([curve], np.zeros(count, np.int64), s, *columns)
    return PathMorph("overhang", False, paths, u, u.copy())
