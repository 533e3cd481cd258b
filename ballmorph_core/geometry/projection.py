"""Closest points on a polyline, for many query points at once."""

import numpy as np

from .. import tolerances as tol
from .polyline import cumulative_length, edges, scale_of
from .ragged import budget_slices
from .spatial import PointTree

__all__ = ["PolylineProjector", "distances_to_polyline"]

#: Candidate (query, vertex) pairs held at once (memory bound).
_PAIR_BUDGET = 2_000_000


class PolylineProjector:
    """Closest points on one polyline.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool

    Notes
    -----
    A k-d tree over the vertices gives each query's distance ``d`` to its nearest vertex (a
    pruned walk, all queries at once); then every vertex within ``sqrt(d^2 + (e/2)^2)`` (``e``
    the longest edge) is fetched in one batched disk query. The closest point lies on an edge
    with an endpoint among them, so only those edges are tested: the cost grows with the number
    of vertices nearly as close as the nearest, not with ``K x N``.
    """

    def __init__(self, curve, closed):
        self.curve = np.asarray(curve, dtype=np.float64)
        self.closed = bool(closed)
        self.edges = edges(self.curve, closed)
        self.n_edges = len(self.edges)
        self._half_edge = 0.5 * float(np.linalg.norm(self.edges, axis=1).max(initial=0.0))
        self._slack = tol.COINCIDENT * scale_of(self.curve)
        self._tree = PointTree(self.curve)

    def nearest(self, points):
        """Edge and fraction along it of the closest point, for each query.

        Parameters
        ----------
        points : ndarray, shape (K, 2)

        Returns
        -------
        edge : ndarray of int, shape (K,)
        frac : ndarray, shape (K,)
            The closest point is ``curve[edge] + frac * edges[edge]``; ties go to the lower edge.
        """
        x = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        edge, frac = np.zeros(len(x), dtype=np.int64), np.zeros(len(x))
        # Queries nearly equidistant to much of the curve (a small loop at the centre of a round
        # one) fetch many vertices each: chunking bounds the memory of the candidates.
        for sl in budget_slices(np.full(len(x), len(self.curve)), _PAIR_BUDGET):
            edge[sl], frac[sl] = self._nearest(x[sl])
        return edge, frac

    def _nearest(self, x):
        radius = np.sqrt(self._tree.nearest_d2(x) + self._half_edge**2)
        qi, vi = self._tree.within(x, radius * (1.0 + 1e-9) + self._slack)
        # Both edges at each vertex found (a stroke's end vertices have one).
        qi = np.repeat(qi, 2)
        ei = np.stack([vi - 1, vi], axis=1).ravel()
        if self.closed:
            ei = np.mod(ei, self.n_edges)
        else:
            ok = (ei >= 0) & (ei < self.n_edges)
            qi, ei = qi[ok], ei[ok]
        a, e = self.curve[ei], self.edges[ei]
        ee = np.einsum("ij,ij->i", e, e)
        f = np.divide(np.einsum("ij,ij->i", x[qi] - a, e), ee, out=np.zeros_like(ee), where=ee > 0)
        f = np.clip(f, 0.0, 1.0)
        d2 = np.sum(np.square(a + f[:, None] * e - x[qi]), axis=1)
        order = np.lexsort((ei, d2, qi))
        qs = qi[order]
        first = order[np.r_[True, qs[1:] != qs[:-1]]]
        if len(first) != len(x):  # cannot happen: the bounding vertex is always found
            raise RuntimeError("closest-point search missed a query")
        return ei[first], f[first]

    def foot(self, edge, frac):
        """Points at (edge, fraction), shape (K, 2)."""
        return self.curve[edge] + frac[:, None] * self.edges[edge]


def distances_to_polyline(points, curve, closed, reach=np.inf):
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
    if not len(points):
        return np.zeros(0), np.zeros(0)
    projector = PolylineProjector(curve, closed)
    edge, frac = projector.nearest(points)
    dist = np.linalg.norm(points - projector.foot(edge, frac), axis=1)
    cum = cumulative_length(projector.curve, closed)
    s = cum[edge] + frac * (cum[edge + 1] - cum[edge])
    far = dist > reach
    return np.where(far, np.inf, dist), np.where(far, 0.0, s)
