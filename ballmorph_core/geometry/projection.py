"""Closest points on polylines, for many query points at once.

:class:`NearestEdges` is the one search: every query against the edges of its own curve of a
batch, within a reach, through a k-d tree over the edges (long edges cut into pieces, so a
scribble's edges spanning the whole drawing do not make every query a candidate of every
edge); built once, it answers batch after batch (a fit iterating over the same curves).
It needs no reach to be quick: a query's bound shrinks to the nearest far corner of its
curve's boxes as it descends, so :class:`PolylineProjector` asks it with none.
"""

import numpy as np

from .. import tolerances as tol
from .ragged import Ragged, ragged_arange
from .spatial import PointTree

__all__ = ["NearestEdges", "nearest_within", "PolylineProjector", "distances_to_polyline"]

#: Queries searched at once: a query far from its curve has a large reach and, until its bound
#: shrinks, many candidates; this bounds the candidates held at once.
_QUERY_CHUNK = 20_000

#: Boxes are small only if edges are: a scribble's edges each span the whole drawing, so edges
#: are searched as pieces no longer than the side of one square per edge of the curves'
#: bounding box, but never more than this many pieces per edge on average.
_PIECES_PER_EDGE = 8

#: Pieces per leaf of the k-d tree.
_LEAF_PIECES = 8


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
    piece = max(np.sqrt(width * height / n), max(width, height) / n, length.sum() / (_PIECES_PER_EDGE * n), 1e-300)
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
    far corner as it descends.
    """

    def __init__(self, curves):
        self.curves = curves
        self.e = np.flatnonzero(curves.nxt >= 0)
        self.a, self.d = curves.pts[self.e], curves.edge[self.e]
        if len(self.e) == 0:
            return
        boxes, self.piece_edge = _pieces(self.a, self.d)
        # Edges come curve after curve, and so do their pieces.
        groups = np.searchsorted(curves.owner[self.e[self.piece_edge]], np.arange(len(curves.offsets)))
        self.tree = PointTree(boxes[:, :2], _LEAF_PIECES, highs=boxes[:, 2:], groups=groups)
        self.extent = float(np.abs(boxes).max())

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
        points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        owner = np.asarray(owner, dtype=np.int64).reshape(-1)
        dist, edge, frac = np.full(len(points), np.inf), np.zeros(len(points), np.int64), np.zeros(len(points))
        if len(points) == 0 or len(self.e) == 0:
            return dist, edge, frac
        # No edge of a curve lies farther than the far corner of its bounding box: a bound for any reach.
        box = self.curves.boxes()[owner]
        corner = np.maximum(np.abs(box[:, :2] - points), np.abs(box[:, 2:] - points))
        reach = np.minimum(reach, np.hypot(corner[:, 0], corner[:, 1]) * (1.0 + 1e-9) + 1e-300)
        a, d = self.a, self.d
        # Distances computed at these coordinates err by round-off: no candidate is lost to it.
        slack = tol.ROUNDOFF * max(self.extent, float(np.abs(points).max()))
        for start in range(0, len(points), _QUERY_CHUNK):
            rows = np.arange(start, min(start + _QUERY_CHUNK, len(points)))
            x = points[rows]
            i, p = self.tree.nearest_candidates(x, reach[rows], owner[rows], slack)
            if not len(i):
                continue
            j = self.piece_edge[p]
            ee = np.einsum("ij,ij->i", d[j], d[j])
            f = np.divide(np.einsum("ij,ij->i", x[i] - a[j], d[j]), ee, out=np.zeros_like(ee), where=ee > 0)
            f = np.clip(f, 0, 1)
            d2 = np.sum(np.square(a[j] + f[:, None] * d[j] - x[i]), axis=1)
            # Candidates come query by query: keep each query's least distance, then the lowest
            # edge at it (pieces of one edge repeat it: any of them).
            run = np.flatnonzero(np.r_[True, i[1:] != i[:-1]])
            run_size = np.diff(np.r_[run, len(i)])
            best = d2 == np.repeat(np.minimum.reduceat(d2, run), run_size)
            best &= j == np.repeat(np.minimum.reduceat(np.where(best, j, len(a)), run), run_size)
            first = np.flatnonzero(best)
            first = first[np.r_[True, i[first][1:] != i[first][:-1]]]
            # Every edge within the bound is a candidate, so the best one is the closest.
            first = first[d2[first] <= np.square(reach[rows][i[first]])]
            hit = rows[i[first]]
            dist[hit], edge[hit], frac[hit] = np.sqrt(d2[first]), self.e[j[first]], f[first]
        return dist, edge, frac


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
