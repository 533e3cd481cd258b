"""Closest points on polylines, for many query points at once.

:class:`NearestEdges` is the one search: every query against the edges of its own curve of a
batch, within a reach, through a k-d tree over the edges (long edges cut into pieces, so a
scribble's edges spanning the whole drawing do not make every query a candidate of every
edge); built once, it answers batch after batch (a fit iterating over the same curves).
It needs no reach to be quick: a query's bound shrinks to the nearest far corner of its
curve's boxes as it descends, so :class:`PolylineProjector` asks it with none. A search asking
few queries per curve (each stroke's two ends) measures every edge of their curves instead,
and builds no tree.
"""

from functools import cached_property

import numpy as np

from .. import tolerances as tol
from .ragged import Ragged, ragged_arange
from .spatial import PointTree

__all__ = ["NearestEdges", "FollowedQueries", "nearest_within", "PolylineProjector", "distances_to_polyline"]

#: Queries searched at once: a query far from its curve has a large reach and, until its bound
#: shrinks, many candidates; this bounds the candidates held at once.
_QUERY_CHUNK = 20_000

#: Boxes are small only if edges are: a scribble's edges each span the whole drawing, so edges
#: are searched as pieces no longer than the side of one square per edge of the curves'
#: bounding box, but never more than this many pieces per edge on average.
_PIECES_PER_EDGE = 8

#: Pieces per leaf of the k-d tree.
_LEAF_PIECES = 8

#: Candidates a followed query keeps at most (one with more searches the tree every time).
_KEPT = 32

#: Candidates per query up to which :func:`_least` steps through the queries' runs side by side
#: (few steps, over ever fewer runs: a followed query measures one or two), not reduceat and a
#: sort of the ties.
_SHORT_RUNS = 8

#: A reach at most this fraction of its curve's bounding-box diagonal lies within the box's far
#: corner from anywhere (which is at least half the diagonal away), round-off and all: the far
#: corner would not cut it.
_UNCUT_DIAGONAL = 0.49

#: A search whose queries' curves hold at most this many edges per edge of the batch measures
#: every one of them: fewer pairs than building the tree sorts (about one query per curve).
_DIRECT_PAIRS_PER_EDGE = 2


def _pieces(a, d):
    """Boxes of the edges ``a + s d``, long ones cut into pieces (see ``_PIECES_PER_EDGE``).

    Parameters
    ----------
    a, d : ndarray, shape (E, 2)

    Returns
    -------
    boxes : ndarray, shape (M, 4)
        ``(xmin, ymin, xmax, ymax)`` of every piece (cut pieces widened by round-off, so
        together they hold their edge).
    edge : ndarray of int, shape (M,)
        The edge (row of ``a``) of each piece.
    """
    lo, hi = np.minimum(a, a + d), np.maximum(a, a + d)
    corner_lo, corner_hi = lo.min(axis=0), hi.max(axis=0)
    width, height = corner_hi - corner_lo
    n = len(a)
    length = np.hypot(d[:, 0], d[:, 1])
    piece = max(np.sqrt(width * height / n), max(width, height) / n, length.sum() / (_PIECES_PER_EDGE * n), tol.TINY)
    count = np.maximum(np.ceil(length / piece), 1).astype(np.int64)
    if (count == 1).all():
        return np.concatenate([lo, hi], axis=1), np.arange(n)
    edge, k = ragged_arange(count)
    t0, t1 = k / count[edge], (k + 1) / count[edge]
    p0, p1 = a[edge] + t0[:, None] * d[edge], a[edge] + t1[:, None] * d[edge]
    pad = np.where(count[edge] > 1, tol.ROUNDOFF * (np.abs(corner_lo).max() + np.abs(corner_hi).max()), 0.0)[:, None]
    boxes = np.concatenate([np.minimum(p0, p1) - pad, np.maximum(p0, p1) + pad], axis=1)
    # Uncut edges keep their exact boxes.
    whole = count[edge] == 1
    boxes[whole] = np.concatenate([lo, hi], axis=1)[edge[whole]]
    return boxes, edge


class NearestEdges:
    """The edges of a batch of curves, ready for :meth:`within` to be asked again and again.

    Parameters
    ----------
    curves : Ragged

    Notes
    -----
    A k-d tree over the pieces of :func:`_pieces`, one root per curve (a query meets only its
    own curve's edges), split at the pieces' centres: its boxes stay small even where the
    curve's runs of edges do not (a scribble's), and a query's reach shrinks to the nearest
    far corner as it descends. It is built at the first search with more queries per curve
    than ``_DIRECT_PAIRS_PER_EDGE`` allows measuring every edge for.
    """

    def __init__(self, curves):
        self.curves = curves
        self.e = np.flatnonzero(curves.nxt >= 0)
        self.a, self.d = curves.pts[self.e], curves.edge[self.e]
        # What _closest gathers per candidate, coordinate by coordinate (single-value gathers
        # are faster than of (x, y) rows): a's x and y, d's x and y, |d|^2, shape (5, E).
        self.columns = np.stack([*self.a.T, *self.d.T, self.d[:, 0] * self.d[:, 0] + self.d[:, 1] * self.d[:, 1]])
        # Edges come curve after curve: curve c's are e[first_edge[c]:first_edge[c + 1]].
        self.first_edge = np.searchsorted(curves.owner[self.e], np.arange(len(curves.offsets)))

    @cached_property
    def _curve_boxes(self):
        """Each curve's bounding box, shape (C, 4) (asked batch after batch)."""
        return self.curves.boxes()

    @cached_property
    def _uncut(self):
        """The reach each curve's far corner cuts from nowhere (see ``_UNCUT_DIAGONAL``), shape (C,)."""
        box = self._curve_boxes
        return _UNCUT_DIAGONAL * np.hypot(box[:, 2] - box[:, 0], box[:, 3] - box[:, 1])

    @cached_property
    def _index(self):
        """The k-d tree over the pieces (see Notes), each piece's edge and the largest coordinate
        of their boxes; built when a search first needs them."""
        boxes, piece_edge = _pieces(self.a, self.d)
        # Edges come curve after curve, and so do their pieces.
        groups = np.searchsorted(self.curves.owner[self.e[piece_edge]], np.arange(len(self.curves.offsets)))
        return (
            PointTree(boxes[:, :2], _LEAF_PIECES, highs=boxes[:, 2:], groups=groups),
            piece_edge,
            float(np.abs(boxes).max()),
        )

    @property
    def tree(self):
        """The k-d tree over the pieces (a PointTree with one group per curve)."""
        return self._index[0]

    @property
    def piece_edge(self):
        """The edge (row of ``a``) of each of the tree's pieces, ndarray of int, shape (M,)."""
        return self._index[1]

    @property
    def most_pieces(self):
        """The most pieces (see :func:`_pieces`) any one curve's edges are cut into (0 without edges)."""
        if not len(self.e):
            return 0
        starts, ends, _ = self.tree.levels[0]
        return int((ends - starts).max())

    def within(self, points, owner, reach):
        """The closest point of each query's curve, among edges within ``reach`` of the query.

        Parameters
        ----------
        points : ndarray, shape (K, 2)
        owner : ndarray of int, shape (K,)
            The curve each query is projected on.
        reach : float or ndarray, shape (K,)
            May be infinite.

        Returns
        -------
        dist : ndarray, shape (K,)
            ``inf`` where the curve lies farther than the reach.
        edge : ndarray of int, shape (K,)
            Global first-vertex index of the closest edge (ties: the lower one); 0 where none.
        frac : ndarray, shape (K,)
            The closest point is ``curves.pts[edge] + frac * curves.edge[edge]``.
        """
        points, owner, reach = self._bounded(points, owner, reach)
        out = _empty(len(points))
        counts = np.diff(self.first_edge)[owner]
        if counts.sum() <= _DIRECT_PAIRS_PER_EDGE * len(self.e):
            # Every edge of the query's curve: the closest within reach is among them.
            i, k = ragged_arange(counts)
            self._closest(out, np.arange(len(points)), points, i, self.first_edge[owner[i]] + k, reach)
            return out
        slack = self._slack(points)
        for rows in self._chunks(len(points)):
            i, p = self.tree.nearest_candidates(points[rows], reach[rows], owner[rows], slack)
            self._closest(out, rows, points[rows], i, self.piece_edge[p], reach[rows])
        return out

    def _bounded(self, points, owner, reach):
        """Queries as arrays, each reach cut to its curve's far corner."""
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        owner = np.asarray(owner, dtype=np.int64).reshape(-1)
        if len(points) == 0 or len(self.e) == 0:
            return points, owner, np.zeros(len(points))
        # No edge of a curve lies farther than the far corner of its bounding box: a bound for any
        # reach, though not for the short ones (an iterative fit's): only the others are cut.
        reach = np.broadcast_to(np.asarray(reach, dtype=np.float64), owner.shape)
        far = np.flatnonzero(~(reach <= np.take(self._uncut, owner, mode="wrap")))
        if len(far) == len(owner):
            return points, owner, self._far_corner_cut(points, owner, reach)
        reach = reach.copy()
        cut = (np.take(v, far, axis=0, mode="wrap") for v in (points, owner, reach))
        reach[far] = self._far_corner_cut(*cut)
        return points, owner, reach

    def _far_corner_cut(self, points, owner, reach):
        """Reaches cut to their curve's far corner, shape (K,) (arguments as :meth:`_bounded` makes them)."""
        box = np.take(self._curve_boxes, owner, axis=0, mode="wrap")
        corner = np.maximum(np.abs(box[:, :2] - points), np.abs(box[:, 2:] - points))
        return np.minimum(reach, np.hypot(corner[:, 0], corner[:, 1]) * (1.0 + 1e-9) + tol.TINY)

    def _slack(self, points):
        """The tree's round-off slack for ``points`` (shape (K, 2), K > 0): distances computed
        at these coordinates err by round-off, and no candidate is lost to it."""
        return tol.ROUNDOFF * max(self._index[2], float(np.abs(points).max()))

    def _chunks(self, n):
        """Runs of at most ``_QUERY_CHUNK`` of ``n`` queries (none without edges to search)."""
        if len(self.e) == 0:
            return
        for start in range(0, n, _QUERY_CHUNK):
            yield np.arange(start, min(start + _QUERY_CHUNK, n))

    def _closest(self, out, rows, x, i, j, reach):
        """The closest of each query's candidate edges, written into ``out`` where within its reach.

        Parameters
        ----------
        out : tuple of ndarray
            ``(dist, edge, frac)`` as :meth:`within` returns them.
        rows : ndarray of int, shape (K,)
            The rows of ``out`` the queries fill.
        x : ndarray, shape (K, 2)
        i, j : ndarray of int, shape (M,)
            Candidates, sorted by query: query ``i`` (row of ``x``), edge ``j`` (row of ``self.a``).
        reach : ndarray, shape (K,)

        Returns
        -------
        d2 : ndarray, shape (M,)
            Each candidate's squared distance from its query.
        """
        if not len(i):
            return np.zeros(0)
        # Indices are in range: mode="wrap" skips the bounds checks (2-3x faster gathers).
        ax, ay, dx, dy, ee = np.take(self.columns, j, axis=1, mode="wrap")
        xx, xy = np.take(x[:, 0], i, mode="wrap"), np.take(x[:, 1], i, mode="wrap")
        # f = ((xx - ax) dx + (xy - ay) dy) / ee where ee > 0, else 0 (the same operations in
        # place: every full-size temporary is a fresh mapping, page-faulted anew).
        f = np.subtract(xx, ax)
        f *= dx
        t = np.subtract(xy, ay)
        t *= dy
        f += t
        np.divide(f, ee, out=f, where=ee > 0)
        np.copyto(f, 0.0, where=ee <= 0)
        np.clip(f, 0, 1, out=f)
        # The foot minus the query, coordinate by coordinate.
        ax += np.multiply(f, dx, out=t)
        ax -= xx
        ay += np.multiply(f, dy, out=t)
        ay -= xy
        d2 = np.square(ax, out=ax)
        d2 += np.square(ay, out=ay)
        first = _least(d2, i, j)
        owner = np.take(i, first, mode="wrap")
        # Every edge within the bound is a candidate, so the best one is the closest.
        d2_first = np.take(d2, first, mode="wrap")
        within = d2_first <= np.square(np.take(reach, owner, mode="wrap"))
        first, hit = first[within], np.take(rows, owner[within], mode="wrap")
        out[0][hit] = np.sqrt(d2_first[within])
        out[1][hit] = np.take(self.e, np.take(j, first, mode="wrap"), mode="wrap")
        out[2][hit] = np.take(f, first, mode="wrap")
        return d2


class FollowedQueries:
    """Closest edges of queries that move a little from call to call (an iterative fit), the
    same answers as :meth:`NearestEdges.within`, mostly without descending its tree.

    Each query keeps the candidates of its last tree search, taken ``margin`` wider than that
    search needed, with their distances from where it was then: they hold every edge within
    ``held`` of that point. Moved by ``m``, a query finds every edge within ``held - m`` of
    where it is among them: while its closest kept edge lies that near, or its whole reach
    does, its kept candidates answer, and only those of them that lay within its reach plus
    ``m`` need measuring.

    Parameters
    ----------
    search : NearestEdges
    owner : ndarray of int, shape (K,)
        The curve each query is projected on.
    margin : ndarray, shape (K,)
        How much wider than needed each tree search takes its candidates.
    """

    def __init__(self, search, owner, margin):
        self.search, self.owner = search, np.asarray(owner, dtype=np.int64)
        self.margin = np.broadcast_to(np.asarray(margin, dtype=np.float64), self.owner.shape)
        n = len(self.owner)
        self.at, self.held = np.zeros((n, 2)), np.full(n, -np.inf)
        # A query's candidates are pieces of its own curve: it never keeps more than the most
        # pieces a curve has (short strokes: far fewer than _KEPT).
        self.width = min(_KEPT, search.most_pieces)
        # Each query's kept edges (rows of search.a) and their distances from `at`: the first
        # `count` slots of its row (the others are never read, so never written either).
        self.kept, self.kept_d = np.empty((n, self.width), np.int64), np.empty((n, self.width))
        self.count = np.zeros(n, np.int64)

    def within(self, rows, points, reach):
        """:meth:`NearestEdges.within` of queries ``rows`` (ndarray of int, shape (K,)) now at
        ``points``, shape (K, 2), within ``reach``, shape (K,)."""
        search = self.search
        # Rows are in range: mode="wrap" skips the bounds checks (2-3x faster gathers).
        points, owner, reach = search._bounded(points, np.take(self.owner, rows, mode="wrap"), reach)
        out = _empty(len(points))
        if not len(points) or not len(search.e):
            return out
        slack = search._slack(points)
        step = points - np.take(self.at, rows, axis=0, mode="wrap")
        np.square(step, out=step)
        moved = np.sqrt(step[:, 0] + step[:, 1])
        # Every edge not kept lies farther than this from where the query is now.
        room = np.take(self.held, rows, mode="wrap") - moved - 2.0 * slack
        tried = np.flatnonzero(room >= 0.0)
        cut = np.fmin(np.take(reach, tried, mode="wrap"), np.take(room, tried, mode="wrap"))
        # A kept edge that lay farther than cut + moved from the query then lies farther than
        # cut now: only the others can answer.
        asked = np.take(rows, tried, mode="wrap")
        # Only the kept slots, query after query (most queries keep a few of the width): slot s
        # of query i is flat position asked[i] width + s of the tables.
        count = np.take(self.count, asked, mode="wrap")
        i, slot = ragged_arange(count)
        at = np.repeat(asked * self.width, count) + slot
        near = np.take(self.kept_d, at, mode="wrap")
        near = np.flatnonzero(near <= np.repeat(cut + np.take(moved, tried, mode="wrap") + 2.0 * slack, count))
        i, j = np.take(i, near, mode="wrap"), np.take(self.kept, np.take(at, near, mode="wrap"), mode="wrap")
        search._closest(out, tried, np.take(points, tried, axis=0, mode="wrap"), i, j, cut)
        # Settled: a kept edge within the room is closer than any other edge, and with the
        # whole reach in the room nothing outside it is within reach either.
        settled = np.zeros(len(points), bool)
        settled[tried] = np.isfinite(np.take(out[0], tried, mode="wrap")) | (cut == np.take(reach, tried, mode="wrap"))
        fresh = np.flatnonzero(~settled)
        for chunk in search._chunks(len(fresh)):
            f = fresh[chunk]
            x, margin = points[f], np.take(self.margin, rows[f], mode="wrap")
            i, p = search.tree.nearest_candidates(x, reach[f], owner[f], slack + margin)
            j = np.take(search.piece_edge, p, mode="wrap")
            d2 = search._closest(out, f, x, i, j, reach[f])
            held = np.fmin(reach[f], out[0][f]) + margin - slack
            self._keep(rows[f], x, i, j, d2, held, slack)
        return out

    def _keep(self, new, x, i, j, d2, held, slack):
        """Queries ``new`` at ``x`` keep their candidates ``(i, j)`` (see
        :meth:`NearestEdges._closest`) at squared distances ``d2``, which hold every edge within
        ``held`` of ``x``; a query with more than the tables' width (``_KEPT`` then) keeps its
        nearest, and holds less."""
        count = np.bincount(i, minlength=len(new))
        over = count > self.width
        if over.any():
            # The nearest `width` of those; the rest lie at least as far as the first one dropped.
            many = over[i]
            order = np.flatnonzero(many)[np.lexsort((d2[many], i[many]))]
            rank = np.arange(len(order)) - np.repeat(np.cumsum(count[over]) - count[over], count[over])
            dropped = order[rank == self.width]
            held[over] = np.fmin(held[over], np.sqrt(d2[dropped]) - slack)
            keep = np.ones(len(i), bool)
            keep[order[rank >= self.width]] = False
            i, j, d2 = i[keep], j[keep], d2[keep]
            count = np.minimum(count, self.width)
        # Flat positions in the (n, width) tables: row new[i], slot = rank within its query.
        start = np.cumsum(count) - count
        at = np.take(new * self.width - start, i, mode="wrap") + np.arange(len(i))
        self.kept.reshape(-1)[at] = j
        self.kept_d.reshape(-1)[at] = np.sqrt(d2)
        self.at[new], self.held[new], self.count[new] = x, held, count


def _least(d2, i, j):
    """Each query's least candidate: the least ``d2``, ties to the lowest edge ``j`` (pieces of
    one edge repeat it: any of them), for the candidates ``(i, j)`` of :meth:`NearestEdges._closest`.

    Returns
    -------
    first : ndarray of int, shape (Q,)
        Rows of the candidates, one for each query that has any.
    """
    run = np.flatnonzero(np.concatenate(([True], i[1:] != i[:-1])))
    length = np.diff(run, append=len(i))
    longest = int(length.max())
    if longest <= _SHORT_RUNS:
        # Each run's best so far against its next candidate, for the runs that have one.
        first, longer = run.copy(), np.flatnonzero(length > 1)
        for step in range(1, longest):
            longer = longer[np.take(length, longer, mode="wrap") > step]
            now, then = np.take(run, longer, mode="wrap") + step, np.take(first, longer, mode="wrap")
            d_now, d_then = np.take(d2, now, mode="wrap"), np.take(d2, then, mode="wrap")
            better = (d_now < d_then) | (
                (d_now == d_then) & (np.take(j, now, mode="wrap") < np.take(j, then, mode="wrap"))
            )
            first[longer[better]] = now[better]
        return first
    least = np.empty(int(i[-1]) + 1)
    least[np.take(i, run, mode="wrap")] = np.minimum.reduceat(d2, run)
    first = np.flatnonzero(d2 == np.take(least, i, mode="wrap"))
    owner = np.take(i, first, mode="wrap")
    again = owner[1:] == owner[:-1]
    if again.any():
        # Ties (a foot on a shared vertex, pieces of one edge): among the queries that have
        # them, the lowest edge first, then the first of each query.
        tied = np.concatenate((again, [False])) | np.concatenate(([False], again))
        some = first[tied]
        some = some[np.lexsort((j[some], owner[tied]))]
        first = np.concatenate((first[~tied], some[np.concatenate(([True], i[some][1:] != i[some][:-1]))]))
    return first


def _empty(n):
    """``(dist, edge, frac)`` of ``n`` queries that found nothing."""
    return np.full(n, np.inf), np.zeros(n, np.int64), np.zeros(n)


def nearest_within(points, owner, curves, reach):
    """:meth:`NearestEdges.within` of a search built for this one call (same parameters)."""
    return NearestEdges(curves).within(points, owner, reach)


class PolylineProjector:
    """Closest points on one polyline, whatever their distance.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool

    Attributes
    ----------
    curves : Ragged
        The polyline as a batch of one (its ``edge`` vectors, ``s`` arc lengths).
    n_edges : int
    """

    def __init__(self, curve, closed):
        self.curves = Ragged.from_list([np.asarray(curve, dtype=np.float64)], [bool(closed)])
        self.n_edges = int(self.curves.n_edges[0])
        self._search = NearestEdges(self.curves)

    def nearest(self, points):
        """Edge and fraction along it of the closest point, for each query.

        Parameters
        ----------
        points : ndarray, shape (K, 2)

        Returns
        -------
        edge : ndarray of int, shape (K,)
        frac : ndarray, shape (K,)
            The closest point is ``curve[edge] + frac * (curve[edge + 1] - curve[edge])``.
        """
        x = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        _, edge, frac = self._search.within(x, np.zeros(len(x), dtype=np.int64), np.inf)
        return edge, frac

    def foot(self, edge, frac):
        """Points at (edge, fraction), shape (K, 2)."""
        return self.curves.pts[edge] + frac[:, None] * self.curves.edge[edge]


def distances_to_polyline(points, curve, closed, reach):
    """Distance from points to a polyline and the arc length of the closest point on it.

    Parameters
    ----------
    points : ndarray, shape (K, 2)
    curve : ndarray, shape (N, 2)
    closed : bool
    reach : float
        Points farther than this from the curve get ``inf``.

    Returns
    -------
    dist : ndarray, shape (K,)
    s : ndarray, shape (K,)
        Arc length of the closest point (0 where ``dist`` is inf).
    """
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    curves = Ragged.from_list([np.asarray(curve, dtype=np.float64)], [bool(closed)])
    dist, edge, frac = nearest_within(points, np.zeros(len(points), dtype=np.int64), curves, reach)
    return dist, np.where(np.isfinite(dist), curves.s[edge] + frac * curves.length_of_edge[edge], 0.0)
