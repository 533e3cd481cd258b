"""Crossing or overlapping curves cut into quasi-disjoint stroke pairs (paper section 3.2).

Crossing loops (configuration 3) and crossing strokes (configuration 4) decompose at their
intersection points into a chain of lens-shaped pairs of strokes that share both endpoints
(configuration 2); portions where P and Q coincide (overlaps) stay static. Each lens is then
ball-morphed on its own and the pieces are joined again, so the intersection points stay fixed
during the morph, as the paper requires of every morph it compares.

:func:`find_events` finds the crossings and overlaps of every pair of a batch at once and
whether they come in the same order along both curves; :func:`cut_chains` cuts the pairs into
their pieces.
"""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...ballmap.topology import PairSetup
from ...geometry.intersections import batch_crossings, matched_hits
from ...geometry.projection import nearest_within

__all__ = ["Events", "Chains", "find_events", "cross", "cut_chains", "MAX_HITS_PER_POINT"]

#: Crossings in the same order along both curves cut them into lenses, and every lens holds a
#: vertex of P or Q (two straight pieces meet once), so such a pair has at most ``n_P + n_Q + 1``
#: crossings, each seen by at most four segment pairs. A pair whose segments meet more than this
#: many times per point (twice that) is tangled: its crossings are not all enumerated (a
#: scribble's million), it goes to its fallback and the note says why.
MAX_HITS_PER_POINT = 8

#: Why a tangled pair is not cut into lenses.
_TANGLED = "the curves cross in a different order along each one (tangled) and do not cut into lenses"


@dataclass
class Events:
    """Where the curves of each pair cross or overlap, sorted by pair and along P.

    Attributes
    ----------
    pair : ndarray of int, shape (E,)
    s_p0, s_p1, s_q0, s_q1 : ndarray, shape (E,)
        Arc-length start and end of each event on P and on Q (equal for a crossing).
    overlap : ndarray of bool, shape (E,)
    count : ndarray of int, shape (C,)
        Events per pair (for a crowded pair: more than this less one, none of them listed).
    agree : ndarray of bool, shape (C,)
        The events come in the same order along both curves (cyclically for loops): the pair
        cuts into lenses. Otherwise it is tangled (paper Fig. 8 and 9, right).
    crowded : ndarray of bool, shape (C,)
        Pairs meeting too often to cut into lenses (see ``MAX_HITS_PER_POINT``): tangled, their
        events not searched to the end.
    """

    pair: np.ndarray
    s_p0: np.ndarray
    s_p1: np.ndarray
    s_q0: np.ndarray
    s_q1: np.ndarray
    overlap: np.ndarray
    count: np.ndarray
    agree: np.ndarray
    crowded: np.ndarray = None

    def take(self, rows):
        """The events at ``rows`` (count, agree and crowded unchanged)."""
        return Events(
            *(getattr(self, name)[rows] for name in ("pair", "s_p0", "s_p1", "s_q0", "s_q1", "overlap")),
            self.count,
            self.agree,
            self.crowded,
        )

    def why_tangled(self, c):
        """Why pair ``c`` (tangled: not ``agree``) does not cut into lenses, for its note."""
        if self.crowded is not None and self.crowded[c]:
            return (
                f"the curves meet more than {self.count[c] - 1} times, more than lenses between "
                f"their points allow ({MAX_HITS_PER_POINT} per point), so they are tangled and do "
                "not cut into lenses"
            )
        return _TANGLED


def _runs(near, closed):
    """Runs of consecutive True of one curve's samples (cyclic for a loop), at least two long,
    as (first, last) with ``last >= first`` (past the end for a run wrapping a loop's start)."""
    idx = np.flatnonzero(near)
    n = len(near)
    if closed:
        runs = []
        for s0 in idx[~near[(idx - 1) % n]]:
            k = s0
            while near[(k + 1) % n]:
                k += 1
            runs.append((s0, k))
    else:
        breaks = np.flatnonzero(np.diff(idx) > 1)
        runs = list(zip(idx[np.r_[0, breaks + 1]], idx[np.r_[breaks, len(idx) - 1]]))
    return [(a, b) for a, b in runs if b - a >= 1]


def _overlaps(R, Q, scale, spacing, wanted):
    """Stretches of each wanted R lying on its Q: rows (pair, sP0, sP1, sQ0, sQ1)."""
    idx = np.flatnonzero(wanted)
    if not len(idx):
        return np.zeros((0, 5))
    # Only the wanted pairs' curves are searched (a search over every Q would build for all).
    sub, sub_q = R.take(idx), Q.take(idx)
    counts = np.round(sub.length / spacing[idx]).astype(np.int64) + np.where(sub.closed, 0, 1)
    dense = sub.resample(counts, smooth=False)
    # Dense arc lengths rescaled onto R's own (resampling along R keeps them proportional).
    s_dense = dense.s * (sub.length / np.maximum(dense.length, tol.TINY))[dense.owner]
    eps = tol.OVERLAP * scale[idx][dense.owner]
    dist, edge, frac = nearest_within(dense.pts, dense.owner, sub_q, eps)
    near = dist <= eps
    s_q = sub_q.s[edge] + frac * sub_q.length_of_edge[edge]
    rows = []
    for c in np.unique(dense.owner[near]):
        sl = slice(dense.offsets[c], dense.offsets[c + 1])
        pair, closed, n = idx[c], bool(sub.closed[c]), sl.stop - sl.start
        near_c, s_c, q_c = near[sl], s_dense[sl], s_q[sl]
        if closed and near_c.all():
            rows.append((pair, 0.0, R.length[pair], q_c[0], q_c[0] + Q.length[pair]))
            continue
        for a, b in _runs(near_c, closed):
            q0, q1 = q_c[a % n], q_c[b % n]
            # On loops an overlap may run past either curve's start: its end is one lap on.
            q1 += Q.length[pair] if closed and q1 < q0 else 0.0
            rows.append((pair, s_c[a % n], s_c[b % n] + (R.length[pair] if closed and b >= n else 0.0), q0, q1))
    return np.array(rows, dtype=np.float64).reshape(-1, 5)


def _orders_agree(events, closed, n_pairs, end_eps):
    """Per pair: the events' order along Q is their order along P (cyclically for loops)."""
    pair = events.pair
    start = np.searchsorted(pair, np.arange(n_pairs))
    count = np.bincount(pair, minlength=n_pairs)
    rank_p = np.arange(len(pair)) - start[pair]
    rank_q = np.empty(len(pair), dtype=np.int64)
    order_q = np.lexsort((events.s_q0, pair))
    rank_q[order_q] = np.arange(len(pair)) - start[pair[order_q]]
    shift = (rank_q - rank_p) % np.maximum(count[pair], 1)
    cyclic_ok = shift == shift[start[pair]] if len(pair) else shift == 0
    back = np.r_[False, (np.diff(events.s_q0) < -end_eps[pair][1:]) & (pair[1:] == pair[:-1])]
    ok = np.where(closed[pair], cyclic_ok, ~back)
    return np.bincount(pair[~ok], minlength=n_pairs) == 0


def _interior(R, pair, s_p, end_eps):
    """Which meetings at arc lengths ``s_p`` along R are events: on a loop every one, on a
    stroke those away from its ends (shared endpoints are not events), shape (K,) of bool."""
    return R.closed[pair] | ((s_p > end_eps[pair]) & (s_p < R.length[pair] - end_eps[pair]))


def cross(R, Q, scale, wanted):
    """Wanted pairs whose curves cross or touch somewhere but at a stroke pair's shared ends
    (or meet too often to count), shape (C,) of bool: all the near route asks of a pair, without
    the overlap analysis of :func:`find_events` (a pair that crosses has events there too).
    """
    end_eps = tol.SHARED_ENDPOINT * scale
    # Near pairs mostly cross where they lie along each other: one such hit answers for a pair
    # (whatever its count), so only the others are searched on the grid.
    pair, s_a = matched_hits(R, Q, scale, wanted)
    found = np.bincount(pair[_interior(R, pair, s_a, end_eps)], minlength=len(R)) > 0
    rest = wanted & ~found
    if not rest.any():
        return found
    cx = batch_crossings(R, Q, scale, rest, max_hits=MAX_HITS_PER_POINT * (R.n + Q.n))
    inside = _interior(R, cx.pair, cx.s_a, end_eps)
    return found | (np.bincount(cx.pair[inside], minlength=len(R)) > 0) | cx.crowded


def find_events(R, Q, scale, spacing, wanted):
    """Crossings and overlaps of every wanted pair (see the module docstring).

    Parameters
    ----------
    R, Q : Ragged
        The (registered) first curves and the second curves, same closed flags.
    scale : ndarray, shape (C,)
        Size of each pair (the unit of its tolerances).
    spacing : ndarray, shape (C,)
        Sampling used to find overlaps.
    wanted : ndarray of bool, shape (C,)

    Returns
    -------
    Events
        A stroke pair's shared endpoints are not events; nor are crossings within an overlap.
        A pair meeting too often (``crowded``) has no events listed and does not agree.
    """
    n, closed = len(R), R.closed
    end_eps = tol.SHARED_ENDPOINT * scale
    max_hits = MAX_HITS_PER_POINT * (R.n + Q.n)
    # Overlaps need nearly parallel segments close together: only those pairs are searched.
    cx, along = batch_crossings(R, Q, scale, wanted, overlap_reach=tol.OVERLAP * scale, max_hits=max_hits)
    pair, s_p, s_q = cx.pair, cx.s_a, cx.s_b
    interior = _interior(R, pair, s_p, end_eps)
    pair, s_p, s_q = pair[interior], s_p[interior], s_q[interior]
    over = _overlaps(R, Q, scale, spacing, wanted & along)
    o_pair = over[:, 0].astype(np.int64)
    for row in over:  # rare: only pairs drawn partly on top of each other
        lap = np.where(closed[pair] & (s_p < row[1] - end_eps[pair]), R.length[pair], 0.0)  # a loop's overlap may wrap
        inside = (pair == row[0]) & (s_p + lap >= row[1] - end_eps[pair]) & (s_p + lap <= row[2] + end_eps[pair])
        pair, s_p, s_q = pair[~inside], s_p[~inside], s_q[~inside]
    all_pair = np.concatenate([pair, o_pair])
    sp0, sp1 = np.concatenate([s_p, over[:, 1]]), np.concatenate([s_p, over[:, 2]])
    sq0, sq1 = np.concatenate([s_q, over[:, 3]]), np.concatenate([s_q, over[:, 4]])
    order = np.lexsort((sp0, all_pair))
    events = Events(
        all_pair[order],
        sp0[order],
        sp1[order],
        sq0[order],
        sq1[order],
        np.r_[np.zeros(len(pair), bool), np.ones(len(o_pair), bool)][order],
        np.where(cx.crowded, max_hits + 1, np.bincount(all_pair, minlength=n)),
        np.ones(n, dtype=bool),
        cx.crowded,
    )
    events.agree = _orders_agree(events, closed, n, end_eps) & ~cx.crowded
    return events


@dataclass
class Chains:
    """The pieces a batch of pairs is cut into, grouped by pair, in order along P.

    Attributes
    ----------
    pair : ndarray of int, shape (H,)
    setups : list of PairSetup
        Each piece oriented for the ball-map (a lens: a stroke pair sharing its endpoints; a
        whole pair: nested loops or strokes sharing their endpoints).
    range_p, range_q : ndarray, shape (H, 2)
        Arc-length start and end of each piece on its pair's P and Q (loops may pass 1 lap).
    static : ndarray of bool, shape (H,)
        Overlaps: the piece of P stays where it is.
    """

    pair: np.ndarray
    setups: list
    range_p: np.ndarray
    range_q: np.ndarray
    static: np.ndarray

    def __len__(self):
        return len(self.pair)

    def keeping(self, keep):
        """The chains ``keep`` (shape (H,) of bool) marks, in their order (a Chains)."""
        rows = np.flatnonzero(keep)
        setups = [self.setups[k] for k in rows]
        return Chains(self.pair[rows], setups, self.range_p[rows], self.range_q[rows], self.static[rows])


def _boundaries(R, Q, events, lensed):
    """The events of the lensed pairs, plus every stroke's start and end (sorted), as Events."""
    keep = events.take(lensed[events.pair])
    opened = np.flatnonzero(lensed & ~R.closed)
    zeros = np.zeros(len(opened))
    pair = np.concatenate([keep.pair, opened, opened])
    cols = [
        (keep.s_p0, zeros, R.length[opened]),
        (keep.s_p1, zeros, R.length[opened]),
        (keep.s_q0, zeros, Q.length[opened]),
        (keep.s_q1, zeros, Q.length[opened]),
    ]
    sp0, sp1, sq0, sq1 = (np.concatenate(c) for c in cols)
    overlap = np.r_[keep.overlap, np.zeros(2 * len(opened), bool)]
    # Stroke starts sort first, ends last (an event never sits on a stroke's shared endpoint).
    where = np.concatenate([keep.s_p0, np.full(len(opened), -np.inf), np.full(len(opened), np.inf)])
    order = np.lexsort((where, pair))
    return Events(pair[order], sp0[order], sp1[order], sq0[order], sq1[order], overlap[order], None, None)


def _gaps(R, Q, b, end_eps):
    """Gap pieces between consecutive boundaries: (pair, order key, sP0, sP1, sQ0, sQ1)."""
    if not len(b.pair):
        return np.zeros(0, np.int64), np.zeros(0, np.int64), *(np.zeros(0) for _ in range(4))
    closed = R.closed[b.pair]
    nxt = np.arange(1, len(b.pair) + 1)
    last = np.r_[b.pair[1:] != b.pair[:-1], True]
    first_of = np.searchsorted(b.pair, b.pair)
    # Loops: the last event's gap wraps to the first; strokes: the end starts no gap.
    nxt = np.where(last, first_of, nxt)
    keep = ~(last & ~closed)
    k = np.flatnonzero(keep)
    pair, sp0, sq0 = b.pair[k], b.s_p1[k], b.s_q1[k]
    sp1, sq1 = b.s_p0[nxt[k]], b.s_q0[nxt[k]]
    loop, eps = closed[k], end_eps[pair]
    # A gap after an overlap that ran past a loop's start starts on the first lap.
    sp0 = np.where(loop & (sp0 >= R.length[pair]), sp0 - R.length[pair], sp0)
    sq0 = np.where(loop & (sq0 >= Q.length[pair]), sq0 - Q.length[pair], sq0)
    # The next event, one lap on if it lies behind (or is this one: the whole loop).
    sp1 = np.where(loop & (sp1 <= sp0 + eps), sp1 + R.length[pair], sp1)
    sq1 = np.where(loop & (sq1 <= sq0 + eps), sq1 + Q.length[pair], sq1)
    real = (sp1 - sp0 > eps) | (sq1 - sq0 > eps)
    return pair[real], 2 * (k - first_of[k])[real] + 1, sp0[real], sp1[real], sq0[real], sq1[real]


def _open_area(pieces):
    """Half the shoelace sum along open pieces, without a closing chord, shape (C,).

    For two pieces sharing both endpoints, ``_open_area(P) - _open_area(Q)`` is the signed area
    of the loop P followed by Q backwards.
    """
    # A piece's vertices are consecutive rows: each with the next, but a piece's last.
    x, y = pieces.pts[:, 0], pieces.pts[:, 1]
    cross = np.zeros(len(x))
    np.subtract(x[:-1] * y[1:], y[:-1] * x[1:], out=cross[:-1])
    cross[pieces.offsets[1:] - 1] = 0.0
    # Per-piece sums in vertex order (bincount adds as np.add.at does, at a fraction of its cost).
    return 0.5 * np.bincount(pieces.owner, weights=cross, minlength=len(pieces))


def _piece_setups(R, Q, pair, sp0, sp1, sq0, sq1, scale):
    """Lens setups: pieces sharing their endpoints exactly, the gap's side from their area."""
    pieces_p, pieces_q = R.pieces(pair, sp0, sp1), Q.pieces(pair, sq0, sq1)
    pieces_q.pts[pieces_q.offsets[:-1]] = pieces_p.pts[pieces_p.offsets[:-1]]
    pieces_q.pts[pieces_q.offsets[1:] - 1] = pieces_p.pts[pieces_p.offsets[1:] - 1]
    # The gap lies left of P when P then Q backwards turns counter-clockwise.
    area = _open_area(pieces_p) - _open_area(pieces_q)
    flat = np.abs(area) <= tol.OVERLAP * scale[pair] * np.maximum(pieces_p.length, tol.TINY)
    side = np.where(area > 0, 1.0, -1.0)
    return [
        PairSetup(pieces_p.curve(k), pieces_q.curve(k).copy(), False, side[k], -side[k], coincident=bool(flat[k]))
        for k in range(len(pair))
    ]


def _whole_setups(R, Q, whole, coincident):
    """Setups of pairs morphed whole: coincident curves, or nested loops (inner gap side outward)."""
    setups = []
    if not len(whole):
        return setups
    # Only the whole pairs' areas and starts (each curve's own sums and tests: the same values).
    areas = np.zeros(len(R))
    areas[whole] = R.take(whole).signed_areas()
    p_inner = np.zeros(len(R), dtype=bool)
    p_inner[whole] = Q.contains(R.pts[R.offsets[whole]], whole)
    for c in whole:
        if coincident[c]:
            setups.append(PairSetup(R.curve(c), Q.curve(c), bool(R.closed[c]), 1.0, 1.0, coincident=True))
            continue
        # Left normals point inside a counter-clockwise loop.
        ccw = 1.0 if areas[c] > 0 else -1.0
        side_p = -ccw if p_inner[c] else ccw
        setups.append(PairSetup(R.curve(c), Q.curve(c), True, side_p, -side_p))
    return setups


def cut_chains(R, Q, events, lensed, whole, coincident, scale):
    """Cut pairs into the pieces their ball-maps run on (Chains).

    Parameters
    ----------
    R, Q : Ragged
    events : Events
        From :func:`find_events`.
    lensed : ndarray of bool, shape (C,)
        Pairs cut at their events (strokes also at their ends).
    whole : ndarray of int
        Pairs morphed whole (nested loops without crossings, coincident curves).
    coincident : ndarray of bool, shape (C,)
    scale : ndarray, shape (C,)
    """
    b = _boundaries(R, Q, events, lensed)
    end_eps = tol.SHARED_ENDPOINT * scale
    g_pair, g_key, gp0, gp1, gq0, gq1 = _gaps(R, Q, b, end_eps)
    o = np.flatnonzero(b.overlap)
    o_pair = b.pair[o]
    o_key = 2 * (o - np.searchsorted(b.pair, o_pair))
    pair = np.concatenate([g_pair, o_pair, whole])
    key = np.concatenate([g_key, o_key, np.zeros(len(whole), np.int64)])
    range_p = np.concatenate(
        [np.c_[gp0, gp1], np.c_[b.s_p0[o], b.s_p1[o]], np.c_[np.zeros(len(whole)), R.length[whole]]]
    )
    range_q = np.concatenate(
        [np.c_[gq0, gq1], np.c_[b.s_q0[o], b.s_q1[o]], np.c_[np.zeros(len(whole)), Q.length[whole]]]
    )
    setups = _piece_setups(R, Q, g_pair, gp0, gp1, gq0, gq1, scale)
    if len(o):
        overlap_p = R.pieces(o_pair, b.s_p0[o], b.s_p1[o])
        setups += [
            PairSetup(overlap_p.curve(k), overlap_p.curve(k), False, 1.0, 1.0, coincident=True) for k in range(len(o))
        ]
    setups += _whole_setups(R, Q, whole, coincident)
    static = np.r_[np.zeros(len(g_pair), bool), np.ones(len(o), bool), np.zeros(len(whole), bool)]
    order = np.lexsort((key, pair))
    return Chains(pair[order], [setups[k] for k in order], range_p[order], range_q[order], static[order])
