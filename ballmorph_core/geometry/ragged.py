"""Many polylines at once: one flat point array plus offsets (Blender's curves layout).

Drawings hold hundreds of strokes. Looping over them in Python and calling numpy on each small
array spends the time in call overhead, so the hot paths (resampling, normals, the ball-map)
work on a :class:`Ragged` batch instead: every per-curve quantity is computed for all curves by
the same few numpy calls. Edges are indexed by their first vertex (edge ``i`` runs from vertex
``i`` to ``nxt[i]``); an open curve's last vertex starts no edge.
"""

from functools import cached_property

import numpy as np

from .. import tolerances as tol
from .spline import catmull_rom
from .vectors import norms, unit_left

__all__ = ["Ragged", "ragged_arange", "budget_slices", "group_argmin"]

#: (point, edge) pairs tested at once by :meth:`Ragged.contains` (memory bound).
_EDGE_BUDGET = 2_000_000


def _rows(a, index):
    """``a[index]`` for an integer index array: np.take, which gathers (N, 2) rows several
    times faster than fancy indexing does (numpy 1.26)."""
    return np.take(a, index, axis=0)


def ragged_arange(counts):
    """Concatenated ``arange(c)`` for every count, and the owner of each entry.

    Parameters
    ----------
    counts : ndarray of int, shape (G,)

    Returns
    -------
    owner : ndarray of int, shape (sum(counts),)
        Group index of each entry.
    local : ndarray of int, shape (sum(counts),)
        Position of each entry inside its group.

    Examples
    --------
    >>> owner, local = ragged_arange(np.array([2, 0, 3]))
    >>> owner.tolist(), local.tolist()
    ([0, 0, 2, 2, 2], [0, 1, 0, 1, 2])
    """
    counts = np.asarray(counts, dtype=np.int64)
    owner = np.repeat(np.arange(len(counts)), counts)
    starts = np.cumsum(counts) - counts
    local = np.arange(int(counts.sum()), dtype=np.int64) - np.repeat(starts, counts)
    return owner, local


def budget_slices(costs, budget):
    """Consecutive runs of items whose summed cost stays within a memory budget.

    Parameters
    ----------
    costs : array_like of int, shape (G,)
        What each item costs (for example the candidate pairs it expands to).
    budget : int
        Most cost per run; an item costing more still gets a run of its own.

    Yields
    ------
    slice
        Runs covering ``0..G`` in order.

    Examples
    --------
    >>> [(s.start, s.stop) for s in budget_slices([3, 3, 3, 9, 1], 6)]
    [(0, 2), (2, 3), (3, 4), (4, 5)]
    """
    ends = np.cumsum(np.asarray(costs, dtype=np.int64))
    start = 0
    while start < len(ends):
        base = ends[start - 1] if start else 0
        stop = max(start + 1, int(np.searchsorted(ends, base + budget, side="right")))
        yield slice(start, stop)
        start = stop


def group_argmin(values, owner, n_groups):
    """Index of the first minimum of ``values`` within each group (groups contiguous), shape (n_groups,).

    Groups without entries get 0.
    """
    starts = np.flatnonzero(np.r_[True, owner[1:] != owner[:-1]])
    mins = np.minimum.reduceat(values, starts)
    counts = np.diff(np.r_[starts, len(values)])
    hit = np.flatnonzero(values == np.repeat(mins, counts))
    # Hits come group by group (in order): each group's first is where its owner changes.
    first = hit[np.r_[True, owner[hit][1:] != owner[hit][:-1]]] if len(hit) else hit
    out = np.zeros(n_groups, dtype=np.int64)
    out[owner[first]] = first
    return out


class Ragged:
    """A batch of polylines.

    Parameters
    ----------
    pts : ndarray, shape (N, 2)
        All vertices, curve after curve.
    offsets : ndarray of int, shape (C + 1,)
        Curve ``c`` owns ``pts[offsets[c]:offsets[c + 1]]``.
    closed : ndarray of bool, shape (C,)

    Attributes
    ----------
    n : ndarray of int, shape (C,)
        Vertices per curve.
    owner : ndarray of int, shape (N,)
        Curve of each vertex.
    nxt, prv : ndarray of int, shape (N,)
        Next and previous vertex along the curve (-1 past an open curve's end).
    edge : ndarray, shape (N, 2)
        Edge vectors by first vertex (zero where no edge starts).
    length_of_edge : ndarray, shape (N,)
    s : ndarray, shape (N,)
        Arc length of each vertex from its curve's first vertex.
    length : ndarray, shape (C,)
        Curve lengths (a loop's includes its closing edge).
    n_edges : ndarray of int, shape (C,)
    """

    def __init__(self, pts, offsets, closed):
        self.pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
        self.offsets = np.asarray(offsets, dtype=np.int64)
        self.closed = np.asarray(closed, dtype=bool).reshape(-1)
        n_pts = len(self.pts)
        self.n = np.diff(self.offsets)
        self.owner = np.repeat(np.arange(len(self.n)), self.n)
        first, last = self.offsets[:-1], self.offsets[1:] - 1
        self.nxt = np.arange(1, n_pts + 1)
        self.prv = np.arange(-1, n_pts - 1)
        nonempty = self.n > 0
        self.nxt[last[nonempty]] = np.where(self.closed[nonempty], first[nonempty], -1)
        self.prv[first[nonempty]] = np.where(self.closed[nonempty], last[nonempty], -1)
        # Built for every internal batch (often per pair): plain ufuncs in place, no
        # np.linalg.norm or np.add.at (the same sums, in the same order, at a fraction of their
        # call and allocation cost).
        self.edge = _rows(self.pts, np.maximum(self.nxt, 0))
        self.edge -= self.pts
        self.edge[last[nonempty & ~self.closed]] = 0.0  # an open curve's last vertex starts no edge
        ex, ey = self.edge[:, 0], self.edge[:, 1]
        self.length_of_edge = norms(ex, ey)
        csum = np.cumsum(self.length_of_edge)
        csum -= self.length_of_edge
        base = np.zeros(len(self.n))
        base[nonempty] = csum[first[nonempty]]
        csum -= base[self.owner]
        self.s = csum
        self.length = self._sums(self.length_of_edge)
        self.n_edges = np.where(self.closed, self.n, np.maximum(self.n - 1, 0))

    def __len__(self):
        return len(self.n)

    @classmethod
    def from_list(cls, curves, closed):
        """Batch a list of (n_i, 2) arrays with their closed flags."""
        sizes = [len(c) for c in curves]
        pts = (
            np.concatenate([np.asarray(c, dtype=np.float64).reshape(-1, 2) for c in curves])
            if curves
            else np.zeros((0, 2))
        )
        return cls(pts, np.concatenate([[0], np.cumsum(sizes)]), np.broadcast_to(closed, (len(curves),)))

    def take(self, curves):
        """Curves ``curves`` (ndarray of int, shape (K,)) as a new batch, in that order."""
        curves = np.asarray(curves, dtype=np.int64)
        counts = self.n[curves]
        owner, local = ragged_arange(counts)
        pts = _rows(self.pts, self.offsets[curves][owner] + local)
        return Ragged(pts, np.concatenate([[0], np.cumsum(counts)]), self.closed[curves])

    def curve(self, c):
        """Vertices of curve ``c``, shape (n_c, 2) (a view)."""
        return self.pts[self.offsets[c] : self.offsets[c + 1]]

    def global_s(self):
        """Arc lengths made increasing across the batch: curve ``c`` is shifted by ``base[c]``.

        Returns
        -------
        g : ndarray, shape (N,)
        base : ndarray, shape (C,)
            Shift of each curve (each curve's range is followed by a gap of the longest
            curve's length: of the batch's own size, so its round-off is too at any scale).

        Computed once and shared: read them, never write them.
        """
        return self._global_s

    @cached_property
    def _global_s(self):
        """:meth:`global_s`, which every locate needs: made once (not to be written to)."""
        gap = float(np.max(self.length, initial=0.0)) or 1.0
        base = np.concatenate([[0.0], np.cumsum(self.length + gap)])[:-1]
        return self.s + base[self.owner], base

    def locate(self, curve, s):
        """Edge (global first-vertex index) and fraction at arc lengths ``s`` on given curves.

        Parameters
        ----------
        curve : ndarray of int, shape (K,)
        s : ndarray, shape (K,)
            Positions, clipped to [0, length] (loops: taken modulo the length).

        Returns
        -------
        edge : ndarray of int, shape (K,)
        frac : ndarray, shape (K,)
        """
        curve, s = np.broadcast_arrays(np.asarray(curve), np.asarray(s, dtype=np.float64))
        return self.locator(curve).locate(s)

    def locator(self, curve):
        """:meth:`locate` and :meth:`point_at` on fixed curves (ndarray of int, shape (K,)), at
        arc lengths given later, again and again (_Locator)."""
        return _Locator(self, np.asarray(curve))

    def point_at(self, curve, s, smooth=False):
        """Points at arc lengths ``s`` of given curves, shape (K, 2).

        With ``smooth`` the point lies on the centripetal Catmull-Rom spline through the
        vertices instead of on the straight edge.
        """
        return self._point_at(*self.locate(curve, s), smooth)

    def _point_at(self, i, frac, smooth=False):
        """:meth:`point_at` at edges ``i`` and fractions ``frac`` along them (K,)."""
        if not smooth:
            return _rows(self.pts, i) + frac[:, None] * _rows(self.edge, i)
        j = np.maximum(self.nxt[i], 0)
        p1, p2 = _rows(self.pts, i), _rows(self.pts, j)
        h = self.prv[i]
        k = self.nxt[j]
        # Past an open curve's ends the missing neighbour is mirrored (only there).
        p0, p3 = _rows(self.pts, np.maximum(h, 0)), _rows(self.pts, np.maximum(k, 0))
        start, end = h < 0, k < 0
        p0[start] = 2 * p1[start] - p2[start]
        p3[end] = 2 * p2[end] - p1[end]
        return catmull_rom(p0, p1, p2, p3, frac)

    def resample(self, counts, smooth=True):
        """Every curve resampled at uniform arc length.

        Parameters
        ----------
        counts : ndarray of int, shape (C,)
            Samples per curve (for an open curve both endpoints included, at least 2; a loop
            at least 3, its first vertex not repeated).
        smooth : bool
            Place the samples on the centripetal Catmull-Rom spline through the vertices.

        Returns
        -------
        Ragged
        """
        counts = np.maximum(np.asarray(counts, dtype=np.int64), np.where(self.closed, 3, 2))
        owner, local = ragged_arange(counts)
        step = self.length / np.where(self.closed, counts, counts - 1)
        s = local * step[owner]
        pts = self.point_at(owner, s, smooth=smooth)
        offsets = np.concatenate([[0], np.cumsum(counts)])
        # Open curves keep their exact endpoints.
        is_open = ~self.closed
        pts[offsets[:-1][is_open]] = self.pts[self.offsets[:-1][is_open]]
        pts[offsets[1:][is_open] - 1] = self.pts[self.offsets[1:][is_open] - 1]
        return Ragged(pts, offsets, self.closed)

    def boxes(self):
        """Bounding box ``(xmin, ymin, xmax, ymax)`` of every curve, shape (C, 4) (NaN for a
        curve without points)."""
        filled = self.n > 0
        out = np.full((len(self.n), 4), np.nan)
        if filled.any():
            # The filled curves' starts: each one's run of points ends where the next one starts.
            starts = self.offsets[:-1][filled]
            out[filled] = np.concatenate(
                [np.minimum.reduceat(self.pts, starts), np.maximum.reduceat(self.pts, starts)], axis=1
            )
        return out

    def centroids(self):
        """Arc-length centroid of every curve (the vertex mean for a dot), shape (C, 2)."""
        mid = self.pts + 0.5 * self.edge
        weighted = mid * self.length_of_edge[:, None]
        total = np.stack([self._sums(weighted[:, 0]), self._sums(weighted[:, 1])], axis=1)
        plain = np.stack([self._sums(self.pts[:, 0]), self._sums(self.pts[:, 1])], axis=1)
        plain /= np.maximum(self.n, 1)[:, None]
        has_length = self.length > 0
        return np.where(has_length[:, None], total / np.where(has_length, self.length, 1.0)[:, None], plain)

    def _sums(self, values):
        """Per-curve sums of per-vertex values (in vertex order, as np.add.at adds), shape (C,)."""
        return np.bincount(self.owner, weights=values, minlength=len(self.n))

    def signed_areas(self):
        """Shoelace area of every curve closed by its chord, shape (C,) (counter-clockwise > 0)."""
        nxt = np.where(self.nxt >= 0, self.nxt, self.offsets[:-1][self.owner])
        a, b = self.pts, _rows(self.pts, nxt)
        cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
        return 0.5 * self._sums(cross)

    def pieces(self, curve, s0, s1):
        """Stretches of curves between arc lengths, as a new batch of open curves.

        Parameters
        ----------
        curve : ndarray of int, shape (K,)
        s0, s1 : ndarray, shape (K,)
            Start and end of each stretch; on a loop ``s1`` may pass its length (the stretch
            then runs on past the first vertex).

        Returns
        -------
        Ragged
            Stretch ``k`` is the point at ``s0``, the vertices strictly between, the point at
            ``s1``.
        """
        n = self.n[curve]
        length = self.length[curve]
        closed = self.closed[curve]
        g, base = self.global_s()
        # Vertices passed before s0, and before s1 (counting a second lap for loops). A vertex
        # within round-off of a boundary is the boundary point itself: leave it out, whatever
        # the batch's offsets did to the last bits.
        tiny = tol.COINCIDENT * np.max(self.length, initial=0.0)
        lo = np.searchsorted(g, s0 + base[curve] + tiny, side="right") - self.offsets[curve]
        lap = closed & (s1 > length)
        s1_in = np.where(lap, s1 - length, s1)
        hi = np.searchsorted(g, s1_in + base[curve] - tiny, side="left") - self.offsets[curve] + np.where(lap, n, 0)
        inner = np.maximum(hi - lo, 0)
        # Every stretch's rows gathered at once, its two end rows then written over (a masked
        # scatter of the vertices into place cost several times the gather): the rows before
        # and after its vertices, which the clip keeps in range.
        owner, local = ragged_arange(inner + 2)
        k_local = lo[owner] + local - 1
        k_local = np.where(closed[owner], np.mod(k_local, np.maximum(n[owner], 1)), k_local)
        pts = np.take(self.pts, self.offsets[curve][owner] + k_local, axis=0, mode="clip")
        offsets = np.concatenate([[0], np.cumsum(inner + 2)])
        pts[offsets[:-1]] = self.point_at(curve, s0)
        pts[offsets[1:] - 1] = self.point_at(curve, np.where(lap, s1_in, s1))
        return Ragged(pts, offsets, np.zeros(len(curve), dtype=bool))

    def vertex_normals(self):
        """Unit left normals at the vertices, orthogonal to the chord of the two neighbours
        (one-sided at an open curve's ends), shape (N, 2)."""
        nxt = np.where(self.nxt >= 0, self.nxt, np.arange(len(self.pts)))
        prv = np.where(self.prv >= 0, self.prv, np.arange(len(self.pts)))
        chord = _rows(self.pts, nxt) - _rows(self.pts, prv)
        return unit_left(chord)

    def edge_normals(self):
        """Unit left normals of the edges by first vertex (zero where no edge), shape (N, 2)."""
        return unit_left(self.edge)

    def contains(self, points, curves):
        """Even-odd test: whether each point lies inside its curve (closed by its last edge).

        Parameters
        ----------
        points : ndarray, shape (K, 2)
        curves : ndarray of int, shape (K,)
            The curve each point is tested against.

        Returns
        -------
        ndarray of bool, shape (K,)
        """
        e_start = self.offsets[:-1][curves]
        counts = self.n[curves]  # every vertex starts an edge (the last one closes the curve)
        hits = np.zeros(len(points), dtype=np.int64)
        for sl in budget_slices(counts, _EDGE_BUDGET):
            owner, local = ragged_arange(counts[sl])
            e = e_start[sl][owner] + local
            a = _rows(self.pts, e)
            b = _rows(self.pts, np.where(self.nxt[e] >= 0, self.nxt[e], e_start[sl][owner]))
            pt = _rows(points[sl], owner)
            straddle = (a[:, 1] > pt[:, 1]) != (b[:, 1] > pt[:, 1])
            with np.errstate(divide="ignore", invalid="ignore"):
                x = a[:, 0] + (pt[:, 1] - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
            hits[sl] = np.bincount(owner[straddle & (pt[:, 0] < x)], minlength=sl.stop - sl.start)
        return hits % 2 == 1


class _Locator:
    """:meth:`Ragged.locate` on fixed curves: what depends on the curves alone is gathered once,
    so paths sliding along curves (the overhangs) locate their samples frame after frame at the
    cost of the search and the edges only.

    Parameters
    ----------
    rg : Ragged
    curve : ndarray of int, shape (K,)
    """

    def __init__(self, rg, curve):
        self._rg = rg
        self._length = rg.length[curve]
        self._loops = np.flatnonzero(rg.closed[curve])
        self._base = rg.global_s()[1][curve]
        self._first, self._last = rg.offsets[curve], rg.offsets[curve + 1] - 1
        self._edged = rg.n[curve] > 1

    def locate(self, s):
        """:meth:`Ragged.locate` at arc lengths ``s`` (K,) of the curves."""
        rg, length, loops = self._rg, self._length, self._loops
        s = np.asarray(s, dtype=np.float64)
        # Loops wrap round, open curves stop at their ends (rows by index: open curves skip the mod).
        wrapped = np.mod(s[loops], np.maximum(length[loops], tol.TINY)) if len(loops) else None
        s = np.clip(s, 0.0, length)
        if wrapped is not None:
            s[loops] = wrapped
        i = np.searchsorted(rg.global_s()[0], s + self._base, side="right") - 1
        i = np.clip(i, self._first, self._last)
        # An open curve's last vertex starts no edge: use the last edge at fraction 1.
        no_edge = rg.nxt[i] < 0
        i = np.where(no_edge & self._edged, i - 1, i)
        seg = rg.length_of_edge[i]
        frac = np.divide(s - rg.s[i], seg, out=np.zeros_like(s), where=seg > 0)
        return i, np.clip(frac, 0.0, 1.0)

    def point_at(self, s):
        """:meth:`Ragged.point_at` (on the edges) at arc lengths ``s`` (K,) of the curves."""
        return self._rg._point_at(*self.locate(s))
