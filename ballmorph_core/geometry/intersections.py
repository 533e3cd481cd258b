"""Segment intersections between polylines and within one polyline.

Candidate segment pairs come from a uniform grid (:func:`spatial.box_pairs`), so the cost grows
with the number of segments and crossings, not with their product.
"""

import numpy as np

from .. import tolerances as tol
from .polyline import cumulative_length, edges, scale_of
from .spatial import box_pairs

__all__ = ["Crossings", "crossings", "self_crossings", "is_simple", "segment_hits"]


class Crossings:
    """Intersection points between two polylines, sorted along the first.

    Attributes
    ----------
    points : ndarray, shape (K, 2)
    s_a, s_b : ndarray, shape (K,)
        Arc-length position of each point on the first and on the second curve.
    edge_a, edge_b : ndarray of int, shape (K,)
        The segments that meet there.
    """

    def __init__(self, points, s_a, s_b, edge_a, edge_b):
        order = np.argsort(s_a, kind="stable")
        self.points = points[order]
        self.s_a, self.s_b = s_a[order], s_b[order]
        self.edge_a, self.edge_b = edge_a[order], edge_b[order]

    def __len__(self):
        return len(self.s_a)


def _boxes(a0, a1):
    return np.concatenate([np.minimum(a0, a1), np.maximum(a0, a1)], axis=1)


def segment_hits(a0, da, b0, db, scale):
    """Proper and touching intersections of segment pairs (vectorised).

    Parameters
    ----------
    a0, da, b0, db : ndarray, shape (K, 2)
        Segments ``a0 + s da`` and ``b0 + u db``.
    scale : float or ndarray, shape (K,)
        Length scale of the tolerances.

    Returns
    -------
    ok : ndarray of bool, shape (K,)
        The segments meet (parallel ones never count: an overlap is not a point).
    s, u : ndarray, shape (K,)
        Where, along each segment, in [0, 1].
    """
    denom = da[:, 0] * db[:, 1] - da[:, 1] * db[:, 0]
    w = b0 - a0
    with np.errstate(divide="ignore", invalid="ignore"):
        sa = (w[:, 0] * db[:, 1] - w[:, 1] * db[:, 0]) / denom
        sb = (w[:, 0] * da[:, 1] - w[:, 1] * da[:, 0]) / denom
    la = np.linalg.norm(da, axis=1)
    lb = np.linalg.norm(db, axis=1)
    parallel = np.abs(denom) <= tol.COINCIDENT * la * lb
    slack_a = tol.COINCIDENT * scale / np.maximum(la, 1e-300)
    slack_b = tol.COINCIDENT * scale / np.maximum(lb, 1e-300)
    ok = ~parallel & (sa >= -slack_a) & (sa <= 1 + slack_a) & (sb >= -slack_b) & (sb <= 1 + slack_b)
    return ok, np.clip(sa, 0, 1), np.clip(sb, 0, 1)


def _dedupe(s_a, s_b, scale):
    """Drop repeats of one crossing reported by two segments sharing a vertex."""
    if len(s_a) == 0:
        return np.zeros(0, dtype=np.int64)
    q = tol.SHARED_ENDPOINT * scale
    key = np.round(s_a / q).astype(np.int64) * 4_000_003 + np.round(s_b / q).astype(np.int64)
    _, first = np.unique(key, return_index=True)
    return np.sort(first)


def crossings(a, closed_a, b, closed_b):
    """Points where two polylines meet (crossing or touching).

    Parameters
    ----------
    a : ndarray, shape (N, 2)
    closed_a : bool
    b : ndarray, shape (M, 2)
    closed_b : bool

    Returns
    -------
    Crossings
        Collinear overlapping segments are not reported here: an overlap is a stretch, not a
        point (see :mod:`~ballmorph_core.compat`).
    """
    scale = scale_of(a, b)
    ea, eb = edges(a, closed_a), edges(b, closed_b)
    a0, b0 = a[: len(ea)], b[: len(eb)]
    i, j = box_pairs(_boxes(a0, a0 + ea), _boxes(b0, b0 + eb))
    ok, sa, sb = segment_hits(a0[i], ea[i], b0[j], eb[j], scale)
    i, j, sa, sb = i[ok], j[ok], sa[ok], sb[ok]
    cum_a, cum_b = cumulative_length(a, closed_a), cumulative_length(b, closed_b)
    s_a = cum_a[i] + sa * (cum_a[i + 1] - cum_a[i])
    s_b = cum_b[j] + sb * (cum_b[j + 1] - cum_b[j])
    if closed_a:
        s_a = np.where(s_a >= cum_a[-1] - tol.COINCIDENT * scale, 0.0, s_a)
    if closed_b:
        s_b = np.where(s_b >= cum_b[-1] - tol.COINCIDENT * scale, 0.0, s_b)
    keep = _dedupe(s_a, s_b, scale)
    pts = a0[i] + sa[:, None] * ea[i]
    return Crossings(pts[keep], s_a[keep], s_b[keep], i[keep], j[keep])


def self_crossings(curve, closed):
    """Points where a polyline meets itself, other than at the joints of adjacent edges.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool

    Returns
    -------
    Crossings
        ``s_a`` and ``s_b`` are the two arc-length positions of each self-intersection; edge
        indices refer to the polyline without repeated consecutive points.
    """
    scale = scale_of(curve)
    # Repeated points (a fan of trajectories leaving one corner) are not crossings.
    step = np.linalg.norm(np.diff(curve, axis=0), axis=1)
    curve = curve[np.r_[True, step > tol.COINCIDENT * scale]]
    if closed and len(curve) > 1 and np.linalg.norm(curve[-1] - curve[0]) <= tol.COINCIDENT * scale:
        curve = curve[:-1]
    e = edges(curve, closed)
    n = len(e)
    c0 = curve[:n]
    i, j = box_pairs(_boxes(c0, c0 + e))
    adjacent = (j - i == 1) | (closed & (i == 0) & (j == n - 1))
    i, j = i[~adjacent], j[~adjacent]
    ok, sa, sb = segment_hits(c0[i], e[i], c0[j], e[j], scale)
    # Also catch a collinear fold-back between adjacent edges (a spike): that is a self-overlap.
    i, j, sa, sb = i[ok], j[ok], sa[ok], sb[ok]
    cum = cumulative_length(curve, closed)
    s_a = cum[i] + sa * (cum[i + 1] - cum[i])
    s_b = cum[j] + sb * (cum[j + 1] - cum[j])
    keep = _dedupe(s_a, s_b, scale)
    pts = c0[i] + sa[:, None] * e[i]
    return Crossings(pts[keep], s_a[keep], s_b[keep], i[keep], j[keep])


def is_simple(curve, closed):
    """True when the polyline does not meet itself (no crossing, no fold-back spike)."""
    if len(self_crossings(curve, closed)):
        return False
    e = edges(curve, closed)
    # Repeated points (within round-off) are one point, not a fold.
    e = e[np.linalg.norm(e, axis=1) > tol.COINCIDENT * scale_of(curve)]
    prev = np.roll(e, 1, axis=0) if closed else e[:-1]
    nxt = e if closed else e[1:]
    cross = prev[:, 0] * nxt[:, 1] - prev[:, 1] * nxt[:, 0]
    dot = np.einsum("ij,ij->i", prev, nxt)
    lens = np.linalg.norm(prev, axis=1) * np.linalg.norm(nxt, axis=1)
    spike = (np.abs(cross) <= tol.COINCIDENT * lens) & (dot < 0)
    return not bool(spike.any())
