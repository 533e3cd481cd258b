"""Segment intersections between polylines and within one polyline.

Candidate segment pairs come from a uniform grid (:func:`~.spatial.box_pair_chunks`, run by run so
memory stays bounded), so the cost grows with the number of segments and crossings, not with their
product; a search that only needs to know whether there is one, or whether there are too many,
stops early. :func:`batch_crossings` finds the crossings of many curve pairs at once (the drawing
pipeline's batches); :func:`crossings` is a batch of one. :func:`matched_hits` is a cheap first
look for pairs lying along each other: some of their hits, without the grid.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from .polyline import edges, scale_of
from .ragged import Ragged, budget_slices, group_argmin
from .spatial import PAIR_BUDGET, box_overlap, box_pair_chunks

__all__ = [
    "Crossings",
    "batch_crossings",
    "matched_hits",
    "crossings",
    "self_crossings",
    "is_simple",
    "simple_curves",
    "segment_hits",
]

#: Two segments whose directions differ by less than this sine may lie along each other.
_PARALLEL_SINE = 1e-3

#: Consecutive edges of a curve the grid boxes together: its work goes by boxes, and the edges
#: of two overlapping runs are few to test against each other.
_EDGES_PER_BOX = 6

#: :func:`simple_curves` takes curves in batches of about this many points (memory, not speed).
SIMPLE_BATCH_POINTS = 50_000

#: :func:`matched_hits` tests a segment of A changing sides against this many segments of B on
#: either side of the matched one (the match is off by a few edges where the curves stray).
_MATCH_REACH = 2


@dataclass
class Crossings:
    """Intersection points between curves, sorted by pair, then along the first curve.

    Attributes
    ----------
    pair : ndarray of int, shape (K,)
        The curve pair of each crossing (0 for a single pair).
    points : ndarray, shape (K, 2)
    s_a, s_b : ndarray, shape (K,)
        Arc-length position of each point on the first and on the second curve.
    edge_a, edge_b : ndarray of int, shape (K,)
        The segments that meet there (first-vertex index within each curve).
    crowded : ndarray of bool, shape (C,) or None
        From :func:`batch_crossings`: pairs whose search stopped at its hit budget (their
        crossings are not listed).
    """

    pair: np.ndarray
    points: np.ndarray
    s_a: np.ndarray
    s_b: np.ndarray
    edge_a: np.ndarray
    edge_b: np.ndarray
    crowded: np.ndarray = None

    def __len__(self):
        return len(self.s_a)


def _boxes(a0, a1):
    return np.concatenate([np.minimum(a0, a1), np.maximum(a0, a1)], axis=1)


def _edge_boxes(rg, e):
    """Boxes of the edges of ``rg`` starting at vertices ``e`` (K,), as the four columns
    ``xmin, ymin, xmax, ymax`` :func:`~.spatial.box_pair_chunks` takes (no (K, 4) rows)."""
    # Rows gathered, then split (np.take of a column view would copy the whole column first).
    (x0, y0), (dx, dy) = np.take(rg.pts, e, axis=0).T, np.take(rg.edge, e, axis=0).T
    x1, y1 = x0 + dx, y0 + dy
    return np.minimum(x0, x1), np.minimum(y0, y1), np.maximum(x0, x1), np.maximum(y0, y1)


def _arc_length(rg, e, frac):
    """Arc length along its curve of the point at fraction ``frac`` of edge ``e`` of ``rg``
    (global first-vertex indices), shape (K,)."""
    return rg.s[e] + frac * rg.length_of_edge[e]


def _hits_of(A, B, ga, gb, scale):
    """:func:`segment_hits` of the edges of A and B starting at vertices ``ga`` and ``gb`` (K,)."""
    return segment_hits(
        np.take(A.pts, ga, axis=0),
        np.take(A.edge, ga, axis=0),
        np.take(B.pts, gb, axis=0),
        np.take(B.edge, gb, axis=0),
        scale,
    )


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
    slack_a = tol.COINCIDENT * scale / np.maximum(la, tol.TINY)
    slack_b = tol.COINCIDENT * scale / np.maximum(lb, tol.TINY)
    ok = ~parallel & (sa >= -slack_a) & (sa <= 1 + slack_a) & (sb >= -slack_b) & (sb <= 1 + slack_b)
    return ok, np.clip(sa, 0, 1), np.clip(sb, 0, 1)


def _first_of_each(pair, s_a, s_b, scale):
    """Indices keeping one crossing seen from two segments sharing a vertex (sorted)."""
    quantum = tol.SHARED_ENDPOINT * scale[pair]
    key = np.stack([pair, np.round(s_a / quantum), np.round(s_b / quantum)], axis=1)
    _, first = np.unique(key, axis=0, return_index=True)
    return np.sort(first)


def _runs_of_edges(rg, e):
    """Where, in the edges ``e`` of ``rg`` (every edge of some curves, curve by curve, shape (K,)),
    runs of up to :data:`_EDGES_PER_BOX` consecutive edges of one curve start, shape (G,)."""
    # A curve's edges start at its consecutive vertices, from its first.
    return np.flatnonzero((e - rg.offsets[rg.owner[e]]) % _EDGES_PER_BOX == 0)


def _run_boxes(boxes, starts):
    """The boxes (four columns) of runs of boxes starting at ``starts`` (G,), as four columns."""
    x0, y0, x1, y1 = boxes
    lows = (np.minimum.reduceat(c, starts) for c in (x0, y0))
    highs = (np.maximum.reduceat(c, starts) for c in (x1, y1))
    return (*lows, *highs)


def _edges_of_runs(run_a, run_b, starts_a, starts_b, n_a, n_b):
    """Every pair of an edge of run ``run_a[k]`` and one of run ``run_b[k]`` (K,): indices
    ``i, j`` into the edges whose runs start at ``starts_a`` and ``starts_b`` (of ``n_a`` and
    ``n_b`` edges), shape (M,) each."""
    steps = np.arange(_EDGES_PER_BOX)
    i = (starts_a[run_a][:, None, None] + steps[:, None]).repeat(_EDGES_PER_BOX, axis=2).reshape(-1)
    j = (starts_b[run_b][:, None, None] + steps).repeat(_EDGES_PER_BOX, axis=1).reshape(-1)
    # A curve's last run may be shorter: only the steps within it.
    end_a, end_b = np.r_[starts_a[1:], n_a][run_a], np.r_[starts_b[1:], n_b][run_b]
    inside = i < end_a.repeat(_EDGES_PER_BOX * _EDGES_PER_BOX)
    inside &= j < end_b.repeat(_EDGES_PER_BOX * _EDGES_PER_BOX)
    return i[inside], j[inside]


def _candidates(A, B, wanted, scale, max_hits):
    """Segment pairs of curve c of A and curve c of B whose boxes overlap, run by run.

    The grid pairs up the boxes of runs of consecutive edges (a fraction as many boxes as
    edges); the edges of overlapping runs are then tested box against box.

    Returns
    -------
    ga, gb : ndarray of int, shape (K,)
        Global first-vertex indices of each segment, sorted by ``ga`` then ``gb``.
    crowded : ndarray of bool, shape (C,)
        Pairs left out once their segments met more than ``max_hits`` times (none without it).
    hits : tuple of ndarray, shape (K,) each
        :func:`segment_hits` of each pair ``(ok, s, u)``: tested run by run (the hit budget
        counts them), so not again.
    """
    wanted = np.ones(len(A), dtype=bool) if wanted is None else wanted
    ea = np.flatnonzero((A.nxt >= 0) & wanted[A.owner])
    eb = np.flatnonzero((B.nxt >= 0) & wanted[B.owner])
    crowded, hits = np.zeros(len(A), dtype=bool), np.zeros(len(A), dtype=np.int64)
    if not len(ea) or not len(eb):
        return _no_candidates(crowded)
    boxes_a, boxes_b = _edge_boxes(A, ea), _edge_boxes(B, eb)
    starts_a, starts_b = _runs_of_edges(A, ea), _runs_of_edges(B, eb)
    owner_a, owner_b = A.owner[ea[starts_a]], B.owner[eb[starts_b]]
    active = np.ones(len(starts_a), dtype=bool)
    found = []
    # Each pair of runs is tested as up to _EDGES_PER_BOX ** 2 pairs of edges: the same memory.
    budget = PAIR_BUDGET // _EDGES_PER_BOX**2
    runs = box_pair_chunks(_run_boxes(boxes_a, starts_a), _run_boxes(boxes_b, starts_b), budget=budget, active=active)
    for run_a, run_b in runs:
        same = np.take(owner_a, run_a) == np.take(owner_b, run_b)
        i, j = _edges_of_runs(run_a[same], run_b[same], starts_a, starts_b, len(ea), len(eb))
        keep = box_overlap(boxes_a, boxes_b, i, j)
        # Each pair once (an edge is in one run), sorted by i then j: runs of runs follow A.
        code = np.sort(i[keep] * len(eb) + j[keep])
        ga, gb = np.take(ea, code // len(eb)), np.take(eb, code % len(eb))
        pair = A.owner[ga]
        found.append((ga, gb, *_hits_of(A, B, ga, gb, scale[pair])))
        if max_hits is None:
            continue
        hits += np.bincount(pair[found[-1][2]], minlength=len(A))
        # Enough is known of these pairs: their remaining segments are not searched.
        crowded |= hits > max_hits
        active &= ~crowded[owner_a]
    if not found:
        return _no_candidates(crowded)
    ga, gb, ok, sa, sb = (np.concatenate(column) for column in zip(*found))
    keep = ~crowded[A.owner[ga]]
    return ga[keep], gb[keep], crowded, (ok[keep], sa[keep], sb[keep])


def _no_candidates(crowded):
    """:func:`_candidates`' answer without a candidate."""
    empty = np.zeros(0, np.int64)
    return empty, empty, crowded, (np.zeros(0, bool), np.zeros(0), np.zeros(0))


def _crossings_of(A, B, ga, gb, hits, scale):
    """The crossings among candidate segment pairs whose :func:`segment_hits` are ``hits``
    (see :func:`batch_crossings`)."""
    ok, sa, sb = hits
    ga, gb, sa, sb = ga[ok], gb[ok], sa[ok], sb[ok]
    pair = A.owner[ga]
    s_a, s_b = _arc_length(A, ga, sa), _arc_length(B, gb, sb)
    slack = tol.COINCIDENT * scale[pair]
    s_a = np.where(A.closed[pair] & (s_a >= A.length[pair] - slack), 0.0, s_a)
    s_b = np.where(B.closed[pair] & (s_b >= B.length[pair] - slack), 0.0, s_b)
    first = _first_of_each(pair, s_a, s_b, scale)
    ga, gb, sa, pair, s_a, s_b = ga[first], gb[first], sa[first], pair[first], s_a[first], s_b[first]
    order = np.lexsort((s_a, pair))
    ga, gb, sa, pair, s_a, s_b = ga[order], gb[order], sa[order], pair[order], s_a[order], s_b[order]
    points = A.pts[ga] + sa[:, None] * A.edge[ga]
    return Crossings(pair, points, s_a, s_b, ga - A.offsets[pair], gb - B.offsets[pair])


def _to_segments(points, a0, d):
    """Distance from each point to its segment ``a0 + s d``, shape (K,)."""
    dd = np.einsum("ij,ij->i", d, d)
    f = np.clip(np.divide(np.einsum("ij,ij->i", points - a0, d), dd, out=np.zeros_like(dd), where=dd > 0), 0.0, 1.0)
    return np.linalg.norm(a0 + f[:, None] * d - points, axis=1)


def _lying_along(A, B, ga, gb, reach):
    """Pairs with two candidate segments nearly parallel and within ``reach`` of each other: the
    only pairs whose curves may overlap, shape (C,) of bool."""
    da, db = np.take(A.edge, ga, axis=0), np.take(B.edge, gb, axis=0)
    sine = np.abs(da[:, 0] * db[:, 1] - da[:, 1] * db[:, 0]) / np.maximum(
        A.length_of_edge[ga] * B.length_of_edge[gb], tol.TINY
    )
    # Only the nearly parallel ones (few) are measured.
    parallel = np.flatnonzero(sine <= _PARALLEL_SINE)
    ga, gb, da, db = ga[parallel], gb[parallel], da[parallel], db[parallel]
    a0, b0 = A.pts[ga], B.pts[gb]
    gap = np.minimum.reduce(
        [
            _to_segments(b0, a0, da),
            _to_segments(b0 + db, a0, da),
            _to_segments(a0, b0, db),
            _to_segments(a0 + da, b0, db),
        ]
    )
    along = gap <= reach[A.owner[ga]]
    return np.bincount(A.owner[ga][along], minlength=len(A)) > 0


def _matched_edges(A, B, searched, va):
    """The edge of B at the same fraction of its length as each vertex ``va`` of A (loops: from
    B's vertex nearest A's first, their starts need not match), global indices, shape (K,).
    ``va`` are the vertices of the ``searched`` pairs (bool, shape (C,)), whose B have edges."""
    pair = A.owner[va]
    t = A.s[va] * (B.length[pair] / np.maximum(A.length[pair], tol.TINY))
    loops = np.flatnonzero((B.closed & searched)[B.owner])
    if len(loops):
        owner = B.owner[loops]
        d = np.take(B.pts, loops, axis=0) - np.take(A.pts, A.offsets[owner], axis=0)
        nearest = loops[group_argmin(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1], owner, len(A))]
        start = np.where(B.closed[pair], B.s[nearest[pair]], 0.0)
        t += start
        t -= np.where(t >= B.length[pair], B.length[pair], 0.0)
    g, base = B.global_s()
    first = B.offsets[pair]
    last = first + np.maximum(B.n_edges[pair] - 1, 0)
    return np.clip(np.searchsorted(g, t + base[pair], side="right") - 1, first, last)


def matched_hits(A, B, scale, wanted):
    """Some hits of curve ``c`` of A with curve ``c`` of B, found cheaply where the curves lie
    along each other (a near pair: matching fractions of their lengths lie close).

    Every vertex of A is put on one side of B's edge at its fraction of the length; where
    consecutive vertices change sides, A's edge is tested against B's few edges around
    there. Each hit is one :func:`batch_crossings` finds too (their boxes overlap, the same
    :func:`segment_hits`), so a hit proves that a pair meets; a pair without one may still meet
    (curves far from matching each other).

    Parameters
    ----------
    A, B : Ragged
        As many curves each.
    scale : ndarray, shape (C,)
    wanted : ndarray of bool, shape (C,)

    Returns
    -------
    pair : ndarray of int, shape (K,)
        The pair of each hit.
    s_a : ndarray, shape (K,)
        Its arc length along A, as :func:`batch_crossings` finds it (before a loop's end is put
        at its start).
    """
    searched = wanted & (B.n_edges > 0)
    va = np.flatnonzero(searched[A.owner])
    pair = A.owner[va]
    e = _matched_edges(A, B, searched, va)
    w = np.take(A.pts, va, axis=0) - np.take(B.pts, e, axis=0)
    d = np.take(B.edge, e, axis=0)
    left = d[:, 0] * w[:, 1] > d[:, 1] * w[:, 0]
    # va holds whole curves, so a vertex's successor is the next row, a loop's last its first.
    after = np.arange(1, len(va) + 1)
    ends = np.flatnonzero(np.r_[pair[1:] != pair[:-1], True]) if len(va) else after
    after[ends] = np.searchsorted(pair, pair[ends])
    turn = np.flatnonzero((left != left[after]) & (np.take(A.nxt, va) >= 0))
    reach = np.arange(-_MATCH_REACH, _MATCH_REACH + 1)
    ga = np.repeat(va[turn], len(reach))
    pair = np.repeat(pair[turn], len(reach))
    first, n_edges = B.offsets[pair], B.n_edges[pair]
    local = np.repeat(e[turn], len(reach)) - first + np.tile(reach, len(turn))
    local = np.where(B.closed[pair], local % np.maximum(n_edges, 1), np.clip(local, 0, n_edges - 1))
    gb = first + local
    ok, sa, _ = _hits_of(A, B, ga, gb, scale[pair])
    # The grid's own boxes and overlap test (touching counts): only its candidates.
    ok &= box_overlap(_edge_boxes(A, ga), _edge_boxes(B, gb))
    return pair[ok], _arc_length(A, ga[ok], sa[ok])


def batch_crossings(A, B, scale, wanted=None, overlap_reach=None, max_hits=None):
    """Points where curve ``c`` of ``A`` meets curve ``c`` of ``B`` (crossing or touching), for every c.

    Parameters
    ----------
    A, B : Ragged
        As many curves each.
    scale : ndarray, shape (C,)
        Length scale of each pair's tolerances.
    wanted : ndarray of bool, shape (C,), optional
        Pairs to search (default all).
    overlap_reach : ndarray, shape (C,), optional
        Also say which pairs have nearly parallel segments within this distance of each other.
    max_hits : ndarray of int, shape (C,), optional
        Stop searching a pair once its segments met more than this many times (counted before
        joining the hits of segments that share a vertex): its crossings are left out and
        ``crowded`` says so. Without it every crossing is found.

    Returns
    -------
    Crossings
        Collinear overlapping segments are not reported: an overlap is a stretch, not a point.
        On a loop, a crossing within round-off of its end is put at its start. ``crowded``,
        shape (C,), marks the pairs cut short by ``max_hits``.
    maybe_overlapping : ndarray of bool, shape (C,)
        Only with ``overlap_reach``: the pairs whose curves may overlap somewhere (never a
        crowded pair).
    """
    ga, gb, crowded, hits = _candidates(A, B, wanted, scale, max_hits)
    found = _crossings_of(A, B, ga, gb, hits, scale)
    found.crowded = crowded
    if overlap_reach is None:
        return found
    return found, _lying_along(A, B, ga, gb, overlap_reach)


def crossings(a, closed_a, b, closed_b):
    """Points where two polylines meet (crossing or touching), sorted along ``a`` (Crossings).

    Parameters
    ----------
    a : ndarray, shape (N, 2)
    closed_a : bool
    b : ndarray, shape (M, 2)
    closed_b : bool
    """
    A, B = Ragged.from_list([a], [closed_a]), Ragged.from_list([b], [closed_b])
    return batch_crossings(A, B, np.array([scale_of(a, b)]))


class _SelfHits:
    """One polyline's segments without repeated points, and its self-intersections run by run.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool
    """

    def __init__(self, curve, closed):
        self.scale = scale_of(curve)
        # Repeated points (a fan of trajectories leaving one corner) are not crossings.
        step = np.linalg.norm(np.diff(curve, axis=0), axis=1)
        curve = curve[np.r_[True, step > tol.COINCIDENT * self.scale]]
        if closed and len(curve) > 1 and np.linalg.norm(curve[-1] - curve[0]) <= tol.COINCIDENT * self.scale:
            curve = curve[:-1]
        self.closed = closed
        self.rg = Ragged.from_list([curve], [closed])
        self.e = np.flatnonzero(self.rg.nxt >= 0)
        self.c0, self.ev = self.rg.pts[self.e], self.rg.edge[self.e]

    def runs(self):
        """Hits of non-adjacent segments, run after run of candidate pairs (bounded memory):
        ``(i, j, sa, sb)``, segment indices ``i < j`` and where along each, in [0, 1]."""
        n, c0, ev = len(self.e), self.c0, self.ev
        for i, j in box_pair_chunks(_boxes(c0, c0 + ev)):
            adjacent = (j - i == 1) | (self.closed & (i == 0) & (j == n - 1))
            i, j = i[~adjacent], j[~adjacent]
            ok, sa, sb = segment_hits(c0[i], ev[i], c0[j], ev[j], self.scale)
            yield i[ok], j[ok], sa[ok], sb[ok]


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
    hits = _SelfHits(curve, closed)
    runs = list(hits.runs())
    i, j, sa, sb = (np.concatenate([r[k] for r in runs]) if runs else np.zeros(0) for k in range(4))
    i, j = i.astype(np.int64), j.astype(np.int64)
    rg, e, c0, ev = hits.rg, hits.e, hits.c0, hits.ev
    s_a = rg.s[e[i]] + sa * rg.length_of_edge[e[i]]
    s_b = rg.s[e[j]] + sb * rg.length_of_edge[e[j]]
    pair = np.zeros(len(i), dtype=np.int64)
    first = _first_of_each(pair, s_a, s_b, np.array([hits.scale]))
    i, j, sa, s_a, s_b = i[first], j[first], sa[first], s_a[first], s_b[first]
    order = np.argsort(s_a, kind="stable")
    return Crossings(
        pair[first][order], (c0[i] + sa[:, None] * ev[i])[order], s_a[order], s_b[order], i[order], j[order]
    )


def is_simple(curve, closed):
    """True when the polyline does not meet itself (no crossing, no fold-back spike).

    Stops at the first run of candidate segment pairs holding a crossing: a scribble's
    million self-crossings are not enumerated to answer no.
    """
    return bool(simple_curves([curve], [closed])[0])


def simple_curves(curves, closed):
    """:func:`is_simple` of many polylines at once: every curve's segments searched together.

    Parameters
    ----------
    curves : list of ndarray, shape (N_i, 2)
    closed : array_like of bool, shape (C,)

    Returns
    -------
    ndarray of bool, shape (C,)
        Each curve's own answer: its tolerances are its own size's, and a pair of segments is
        tested only within one curve. A curve found to meet itself is searched no further.
    """
    closed = np.asarray(closed, dtype=bool).reshape(-1)
    sizes = [len(curve) for curve in curves]
    if sum(sizes) > SIMPLE_BATCH_POINTS:
        # Curves a batch at a time (10,000 strokes at once held 150 MiB of segment boxes and
        # candidate pairs): each curve's answer is its own.
        runs = budget_slices(sizes, SIMPLE_BATCH_POINTS)
        return np.concatenate([_simple_batch(curves[run], closed[run]) for run in runs])
    return _simple_batch(curves, closed)


def _simple_batch(curves, closed):
    """:func:`simple_curves` of one batch of curves (list of ndarray, flags)."""
    parts = [_Prepared(curve, bool(loop)) for curve, loop in zip(curves, closed)]
    simple = np.ones(len(parts), dtype=bool)
    if not parts:
        return simple
    scale = np.array([part.scale for part in parts])
    simple &= ~_spikes(parts)
    # Hits of non-adjacent segments of one curve, on the curves without repeated points.
    rg = Ragged.from_list([part.curve for part in parts], closed)
    e = np.flatnonzero(rg.nxt >= 0)
    owner = rg.owner[e]
    local, n = e - rg.offsets[owner], rg.n_edges[owner]
    c0, ev = rg.pts[e], rg.edge[e]
    active = simple[owner]
    for i, j in box_pair_chunks(_apart(_boxes(c0, c0 + ev), owner, len(parts)), active=active):
        mine = owner[i] == owner[j]
        i, j = i[mine], j[mine]
        adjacent = (local[j] - local[i] == 1) | (closed[owner[i]] & (local[i] == 0) & (local[j] == n[i] - 1))
        i, j = i[~adjacent], j[~adjacent]
        ok, _, _ = segment_hits(c0[i], ev[i], c0[j], ev[j], scale[owner[i]])
        met = np.unique(owner[i[ok]])
        simple[met] = False
        active[np.isin(owner, met)] = False  # read before the next run: searched no further
    return simple


def _apart(boxes, owner, n):
    """Boxes (K, 4) of ``n`` curves (``owner``, shape (K,)), each curve's moved to a square of
    its own on a grid, so that only boxes of one curve overlap. Rounding is monotonic, so two
    boxes of a curve that overlapped still do (a few that only nearly touched may now touch:
    more candidates, never fewer)."""
    lo = np.full((n, 2), np.inf)
    hi = np.full((n, 2), -np.inf)
    np.minimum.at(lo, owner, boxes[:, :2])
    np.maximum.at(hi, owner, boxes[:, 2:])
    used = np.isfinite(lo[:, 0])
    size = float(np.max(hi[used] - lo[used], initial=0.0))
    pitch = 2.0 * size if size > 0 else 1.0
    side = int(np.ceil(np.sqrt(n)))
    corner = np.c_[np.arange(n) % side, np.arange(n) // side] * pitch
    shift = np.where(used[:, None], corner - lo, 0.0)[owner]
    return boxes + np.concatenate([shift, shift], axis=1)


class _Prepared:
    """One curve as :func:`simple_curves` reads it: its size, the curve without repeated
    points (for crossings), and its consecutive non-zero edges (for fold-back spikes)."""

    def __init__(self, curve, closed):
        curve = np.asarray(curve, dtype=np.float64).reshape(-1, 2)
        self.scale = scale_of(curve) if len(curve) else 1.0
        eps = tol.COINCIDENT * self.scale
        # Repeated points (a fan of trajectories leaving one corner) are not crossings.
        step = np.linalg.norm(np.diff(curve, axis=0), axis=1)
        self.curve = curve[np.r_[True, step > eps]] if len(curve) else curve
        if closed and len(self.curve) > 1 and np.linalg.norm(self.curve[-1] - self.curve[0]) <= eps:
            self.curve = self.curve[:-1]
        # Repeated points (within round-off) are one point, not a fold.
        e = edges(curve, closed) if len(curve) else np.zeros((0, 2))
        e = e[np.linalg.norm(e, axis=1) > eps]
        self.prev = np.roll(e, 1, axis=0) if closed else e[:-1]
        self.next = e if closed else e[1:]


def _spikes(parts):
    """Curves that fold back on themselves (two consecutive edges antiparallel), shape (C,) of bool."""
    counts = np.array([len(part.prev) for part in parts])
    prev = np.concatenate([part.prev for part in parts])
    nxt = np.concatenate([part.next for part in parts])
    cross = prev[:, 0] * nxt[:, 1] - prev[:, 1] * nxt[:, 0]
    dot = np.einsum("ij,ij->i", prev, nxt)
    lens = np.linalg.norm(prev, axis=1) * np.linalg.norm(nxt, axis=1)
    spike = (np.abs(cross) <= tol.COINCIDENT * lens) & (dot < 0)
    return np.bincount(np.repeat(np.arange(len(parts)), counts)[spike], minlength=len(parts)) > 0
