"""All stroke pairs of a drawing through the ball-morph in one numpy pass (the fast path).

:func:`~ballmorph_core.pair.morph_pair` treats one pair at a time and knows every fallback.
A character drawing has hundreds of pairs, and most of them take the same road: register by
a similarity, split at the crossings of the registered curves into lens-shaped stroke pairs,
ball-morph every lens, move along the carrier. :func:`morph_pairs` does exactly that for all
pairs at once (batched registration, one crossing search, one batched ball-map over every lens
of every pair, one path evaluation per frame) and hands back the pairs that need anything else
(tangled crossings, incompatible lenses, a single touching point, non-ball methods) so the
caller sends them through :func:`~ballmorph_core.pair.morph_pair`. Both roads give the same
in-betweens; the tests check that they agree.

Everything but the last step is independent of the in-between times: :func:`plan_pairs`
computes it once and returns a :class:`BatchPlan`, whose :meth:`BatchPlan.frames` evaluates the
paths and the carrier at any times (the operator keeps plans so that a redo with another frame
count or easing only re-evaluates them).
"""

from dataclasses import dataclass, field

import numpy as np

from .. import tolerances as tol
from ..ballmap.correspondence import ball_maps
from ..ballmap.topology import PairSetup
from ..geometry.intersections import segment_hits
from ..geometry.ragged import Ragged
from ..geometry.similarity import as_complex, from_complex
from ..geometry.spatial import box_pairs
from ..morphs.paths import BallPaths
from .registration import carrier_at, similarities

__all__ = ["BatchPlan", "BatchResult", "plan_pairs", "morph_pairs"]


@dataclass
class BatchResult:
    """Frames of every pair the fast path handled, concatenated.

    Attributes
    ----------
    done : ndarray of bool, shape (C,)
        Pairs handled here (the others need :func:`~ballmorph_core.pair.morph_pair`).
    offsets : ndarray of int, shape (C + 1,)
        Pair ``c``'s samples are ``offsets[c]:offsets[c + 1]`` (empty when not done).
    frames : ndarray, shape (T, K, 2)
    u_p, u_q : ndarray, shape (K,)
        Arc-length fractions along P and Q as given.
    used : list of str
    notes : list of list of str
    """

    done: np.ndarray
    offsets: np.ndarray
    frames: np.ndarray
    u_p: np.ndarray
    u_q: np.ndarray
    used: list = field(default_factory=list)
    notes: list = field(default_factory=list)

    @classmethod
    def empty(cls, n, n_times):
        return cls(
            np.zeros(n, dtype=bool),
            np.zeros(n + 1, dtype=np.int64),
            np.zeros((n_times, 0, 2)),
            np.zeros(0),
            np.zeros(0),
            [""] * n,
            [[] for _ in range(n)],
        )

    def pair(self, c):
        """``(frames (T, K, 2), u_p, u_q)`` of pair ``c``."""
        sl = slice(self.offsets[c], self.offsets[c + 1])
        return self.frames[:, sl], self.u_p[sl], self.u_q[sl]


@dataclass
class BatchPlan:
    """The time-independent part of the fast path: correspondences, paths and carriers.

    Attributes
    ----------
    done, offsets, u_p, u_q, used, notes
        As in :class:`BatchResult`.
    paths : BallPaths or None
        One path per sample (K samples), None when no pair was done.
    pair_of : ndarray of int, shape (K,)
        The pair of each sample.
    a, b : ndarray of complex, shape (C,)
        Each pair's registration ``z -> a z + b`` of P onto Q.
    moving : ndarray of bool, shape (C,)
        Pairs whose carrier is not the identity.
    centre : ndarray of complex, shape (C,)
        Centre of each Q (the scaling centre of a 'RIGID' carrier).
    carrier : {'SIMILARITY', 'RIGID', 'NONE'}
    """

    done: np.ndarray
    offsets: np.ndarray
    u_p: np.ndarray
    u_q: np.ndarray
    used: list
    notes: list
    paths: object = None
    pair_of: np.ndarray = None
    a: np.ndarray = None
    b: np.ndarray = None
    moving: np.ndarray = None
    centre: np.ndarray = None
    carrier: str = "SIMILARITY"

    @classmethod
    def empty(cls, n):
        nothing = BatchResult.empty(n, 0)
        return cls(nothing.done, nothing.offsets, nothing.u_p, nothing.u_q, nothing.used, nothing.notes)

    def frames(self, times):
        """Every sample at every time.

        Parameters
        ----------
        times : array_like, shape (T,)

        Returns
        -------
        BatchResult
        """
        times = np.asarray(times, dtype=np.float64).reshape(-1)
        frames = np.empty((len(times), len(self.u_p), 2))
        # Carrier: C_t = S^-(1-t), undoing the registration progressively (identity if none).
        kind = self.carrier if self.carrier != "NONE" else "SIMILARITY"
        for ti, t in enumerate(times if self.paths is not None else ()):
            z = self.paths.at(t)
            if self.moving.any():
                ca, cb = carrier_at(self.a, self.b, kind, self.centre, t)
                ca, cb = np.where(self.moving, ca, 1.0), np.where(self.moving, cb, 0.0)
                z = from_complex(ca[self.pair_of] * as_complex(z) + cb[self.pair_of])
            frames[ti] = z
        return BatchResult(self.done, self.offsets, frames, self.u_p, self.u_q, self.used, self.notes)


def _bbox_scale(rg):
    """Bounding-box diagonal of every curve of a batch, shape (C,)."""
    starts = rg.offsets[:-1]
    lo = np.minimum.reduceat(rg.pts, starts, axis=0)
    hi = np.maximum.reduceat(rg.pts, starts, axis=0)
    return np.linalg.norm(hi - lo, axis=1)


def _default_spacing(P, Q):
    """:func:`~ballmorph_core.curves.default_spacing` of every pair at once, shape (C,)."""
    owner = np.concatenate([P.owner[P.nxt >= 0], Q.owner[Q.nxt >= 0]])
    length = np.concatenate([P.length_of_edge[P.nxt >= 0], Q.length_of_edge[Q.nxt >= 0]])
    order = np.lexsort((length, owner))
    owner, length = owner[order], length[order]
    start = np.searchsorted(owner, np.arange(len(P) + 1))
    count = np.diff(start)
    lo = start[:-1] + (count - 1) // 2
    hi = start[:-1] + count // 2
    median = 0.5 * (length[np.minimum(lo, len(length) - 1)] + length[np.minimum(hi, len(length) - 1)])
    longest = np.maximum(P.length, Q.length)
    return np.clip(median, longest / tol.DEFAULT_SAMPLES_MAX, longest / tol.DEFAULT_SAMPLES_MIN)


def _crossings(P, Q, scale, wanted):
    """Crossings of every wanted P with its Q: pair index, arc length on P and on Q (sorted)."""
    ea = np.flatnonzero((P.nxt >= 0) & wanted[P.owner])
    eb = np.flatnonzero((Q.nxt >= 0) & wanted[Q.owner])
    a0, da = P.pts[ea], P.edge[ea]
    b0, db = Q.pts[eb], Q.edge[eb]
    boxes_a = np.concatenate([np.minimum(a0, a0 + da), np.maximum(a0, a0 + da)], axis=1)
    boxes_b = np.concatenate([np.minimum(b0, b0 + db), np.maximum(b0, b0 + db)], axis=1)
    i, j = box_pairs(boxes_a, boxes_b)
    same = P.owner[ea[i]] == Q.owner[eb[j]]
    i, j = i[same], j[same]
    pair = P.owner[ea[i]]
    ok, sa, sb = segment_hits(a0[i], da[i], b0[j], db[j], scale[pair])
    i, j, sa, sb, pair = i[ok], j[ok], sa[ok], sb[ok], pair[ok]
    s_p = P.s[ea[i]] + sa * P.length_of_edge[ea[i]]
    s_q = Q.s[eb[j]] + sb * Q.length_of_edge[eb[j]]
    # One crossing seen from two segments sharing a vertex: keep one.
    quantum = tol.SHARED_ENDPOINT * scale[pair]
    key = np.stack([pair, np.round(s_p / quantum), np.round(s_q / quantum)], axis=1)
    _, first = np.unique(key, axis=0, return_index=True)
    pair, s_p, s_q = pair[first], s_p[first], s_q[first]
    order = np.lexsort((s_p, pair))
    return pair[order], s_p[order], s_q[order]


def morph_pairs(pairs, times, kind="circular", carrier="SIMILARITY", spacing=None):
    """Morph many stroke pairs at once: ``plan_pairs(...).frames(times)``.

    Parameters
    ----------
    pairs : list of tuple
        See :func:`plan_pairs`.
    times : ndarray, shape (T,)
    kind, carrier, spacing
        See :func:`plan_pairs`.

    Returns
    -------
    BatchResult
    """
    return plan_pairs(pairs, kind, carrier, spacing).frames(times)


def plan_pairs(pairs, kind="circular", carrier="SIMILARITY", spacing=None):
    """Correspondences, paths and carriers of many stroke pairs at once (see the module docstring).

    Parameters
    ----------
    pairs : list of tuple
        ``(P, Q, closed)``: validated curves (see :func:`~ballmorph_core.curves.as_curve`),
        Q running the same way as P.
    kind : str
        Ball-morph path: 'circular', 'linear', 'parabolic', 'hat' or 'tangent'.
    carrier : {'SIMILARITY', 'RIGID', 'NONE'}
    spacing : float, optional
        Sample spacing for every pair (default: each pair's
        :func:`~ballmorph_core.curves.default_spacing`).

    Returns
    -------
    BatchPlan
    """
    if not pairs:
        return BatchPlan.empty(0)
    closed = np.array([c for _, _, c in pairs], dtype=bool)
    P = Ragged.from_list([p for p, _, _ in pairs], closed)
    Q = Ragged.from_list([q for _, q, _ in pairs], closed)
    n = len(P)
    if carrier == "NONE":
        a, b, residual = np.ones(n, dtype=complex), np.zeros(n, dtype=complex), np.full(n, np.inf)
    else:
        a, b, residual = similarities(P, Q)
    R = Ragged(from_complex(a[P.owner] * as_complex(P.pts) + b[P.owner]), P.offsets, closed)  # registered P
    scale = np.maximum(_bbox_scale(R), _bbox_scale(Q))
    scale = np.where(scale > 0, scale, 1.0)
    eps = tol.COINCIDENT * scale
    # Sample where the morph happens: between the registered P (Q's size) and Q.
    h = _default_spacing(R, Q) if spacing is None else np.full(n, float(spacing))
    # Registered curves that coincide with their target: the carrier alone is the morph.
    coincident = residual <= tol.OVERLAP * scale
    pair, s_p, s_q = _crossings(R, Q, scale, ~coincident)
    # A stroke pair's shared endpoints are not crossings.
    end_tol = tol.SHARED_ENDPOINT * scale[pair]
    interior = closed[pair] | ((s_p > end_tol) & (s_p < R.length[pair] - end_tol))
    pair, s_p, s_q = pair[interior], s_p[interior], s_q[interior]
    count = np.bincount(pair, minlength=n)
    eligible = np.ones(n, dtype=bool)
    if carrier == "NONE":
        # Without a carrier, strokes must already share their endpoints.
        shared = np.linalg.norm(R.pts[R.offsets[:-1]] - Q.pts[Q.offsets[:-1]], axis=1) <= tol.SHARED_ENDPOINT * scale
        shared &= (
            np.linalg.norm(R.pts[R.offsets[1:] - 1] - Q.pts[Q.offsets[1:] - 1], axis=1) <= tol.SHARED_ENDPOINT * scale
        )
        eligible &= closed | shared
    # Crossings must come in the same order along both curves (else the pair is tangled).
    start = np.searchsorted(pair, np.arange(n))
    rank_q = np.empty(len(pair), dtype=np.int64)
    order_q = np.lexsort((s_q, pair))
    rank_q[order_q] = np.arange(len(pair)) - start[pair[order_q]]
    rank_p = np.arange(len(pair)) - start[pair]
    shift = (rank_q - rank_p) % np.maximum(count[pair], 1)
    first_shift = shift[start[pair]] if len(pair) else shift
    agree = np.where(closed[pair], shift == first_shift, rank_q == rank_p)
    eligible &= np.bincount(pair[~agree], minlength=n) == 0
    eligible &= ~(closed & (count == 1))  # a loop touching its target once: general road
    # Nested loops without crossings (configuration 1) are one chain; others need the general road.
    nested = Q.contains(R.pts[R.offsets[:-1]], np.arange(n)) | R.contains(Q.pts[Q.offsets[:-1]], np.arange(n))
    eligible &= ~(closed & (count == 0) & ~nested) | coincident
    # Lenses: stretches between consecutive crossings (strokes also from and to their ends).
    lens_pair, l_p0, l_p1, l_q0, l_q1 = [], [], [], [], []
    for_lens = eligible & ~coincident & ~(closed & (count == 0))
    idx = np.flatnonzero(for_lens)
    if len(idx):
        sel = for_lens[pair]
        cp, cs_p, cs_q = pair[sel], s_p[sel], s_q[sel]
        opened = idx[~closed[idx]]
        # Strokes: add their start and end as boundaries.
        bp = np.concatenate([cp, opened, opened])
        bs_p = np.concatenate([cs_p, np.zeros(len(opened)), R.length[opened]])
        bs_q = np.concatenate([cs_q, np.zeros(len(opened)), Q.length[opened]])
        o = np.lexsort((bs_p, bp))
        bp, bs_p, bs_q = bp[o], bs_p[o], bs_q[o]
        nxt = np.arange(1, len(bp) + 1)
        last = np.r_[bp[1:] != bp[:-1], True]
        first_of = np.searchsorted(bp, bp)
        # Loops: the last crossing's lens wraps to the first; strokes: the end starts none.
        nxt = np.where(last, first_of, nxt)
        keep = ~(last & ~closed[bp])
        lens_pair = bp[keep]
        l_p0, l_q0 = bs_p[keep], bs_q[keep]
        l_p1, l_q1 = bs_p[nxt[keep]], bs_q[nxt[keep]]
        wrap = closed[lens_pair]
        l_p1 = np.where(wrap & (l_p1 <= l_p0), l_p1 + R.length[lens_pair], l_p1)
        l_q1 = np.where(wrap & (l_q1 <= l_q0), l_q1 + Q.length[lens_pair], l_q1)
    lens_pair = np.asarray(lens_pair, dtype=np.int64)
    # Chains: every lens, plus nested or coincident curves whole; grouped by pair, in order.
    whole = np.flatnonzero(eligible & ((closed & (count == 0)) | coincident))
    setups, chain_pair, range_p, range_q = [], [], [], []
    if len(lens_pair):
        pieces_p = R.pieces(lens_pair, np.asarray(l_p0), np.asarray(l_p1))
        pieces_q = Q.pieces(lens_pair, np.asarray(l_q0), np.asarray(l_q1))
        # Share the endpoints exactly.
        pieces_q.pts[pieces_q.offsets[:-1]] = pieces_p.pts[pieces_p.offsets[:-1]]
        pieces_q.pts[pieces_q.offsets[1:] - 1] = pieces_p.pts[pieces_p.offsets[1:] - 1]
        # The gap lies left of P when P then Q backwards turns counter-clockwise.
        area = _open_area(pieces_p) - _open_area(pieces_q)
        flat = np.abs(area) <= tol.OVERLAP * scale[lens_pair] * np.maximum(pieces_p.length, 1e-300)
        side = np.where(area > 0, 1.0, -1.0)
        for k in range(len(lens_pair)):
            setups.append(
                PairSetup(
                    pieces_p.curve(k), pieces_q.curve(k).copy(), False, side[k], -side[k], coincident=bool(flat[k])
                )
            )
        chain_pair += list(lens_pair)
        range_p += list(zip(l_p0, l_p1))
        range_q += list(zip(l_q0, l_q1))
    if len(whole):
        areas = R.signed_areas()
        p_inner = Q.contains(R.pts[R.offsets[:-1]], np.arange(n))
    for c in whole:
        if coincident[c]:
            setups.append(PairSetup(R.curve(c), Q.curve(c), bool(closed[c]), 1.0, 1.0, coincident=True))
        else:
            # Nested loops: left normals point inside a counter-clockwise loop.
            ccw = 1.0 if areas[c] > 0 else -1.0
            side_p = -ccw if p_inner[c] else ccw
            setups.append(PairSetup(R.curve(c), Q.curve(c), True, side_p, -side_p))
        chain_pair.append(c)
        range_p.append((0.0, R.length[c]))
        range_q.append((0.0, Q.length[c]))
    result = BatchPlan.empty(n)
    if not setups:
        return result
    chain_pair = np.asarray(chain_pair, dtype=np.int64)
    order = np.argsort(chain_pair, kind="stable")
    setups = [setups[k] for k in order]
    chain_pair, range_p, range_q = chain_pair[order], np.asarray(range_p)[order], np.asarray(range_q)[order]
    # In batches of about BALLMAP_BATCH_POINTS input points (whole pairs: each pair's chains
    # share one tolerance), which bounds the ball-map's temporaries on huge drawings.
    starts = np.cumsum([0] + [len(s.P) + len(s.Q) for s in setups])[:-1] // tol.BALLMAP_BATCH_POINTS
    first_of_pair = np.r_[True, chain_pair[1:] != chain_pair[:-1]]
    batch_of = np.maximum.accumulate(np.where(first_of_pair, starts, 0))
    corrs = []
    for number in np.unique(batch_of):
        members = np.flatnonzero(batch_of == number)
        owners = chain_pair[members]
        corrs += ball_maps([setups[i] for i in members], h[owners], "symmetric", check=False, eps=eps[owners])
    failed = np.zeros(n, dtype=bool)
    failed[[c for corr, c in zip(corrs, chain_pair) if corr.report.violations]] = True
    good = np.flatnonzero(~failed[chain_pair])
    if not len(good):
        return result
    corrs = [corrs[k] for k in good]
    chain_pair, range_p, range_q = chain_pair[good], range_p[good], range_q[good]
    sizes = np.array([len(corr) for corr in corrs])
    chain_of = np.repeat(np.arange(len(corrs)), sizes)
    pair_of = chain_pair[chain_of]
    # Arc lengths on the dense chains -> fractions along the whole curves.
    dense_p = Ragged.from_list([corr.dense_p for corr in corrs], [corr.closed for corr in corrs])
    dense_q = Ragged.from_list([corr.dense_q for corr in corrs], [corr.closed for corr in corrs])
    s_p = np.concatenate([corr.s_p for corr in corrs])
    s_q = np.concatenate([corr.s_q for corr in corrs])
    span_p, span_q = np.diff(range_p, axis=1)[:, 0], np.diff(range_q, axis=1)[:, 0]
    u_p = range_p[chain_of, 0] + s_p / np.maximum(dense_p.length, 1e-300)[chain_of] * span_p[chain_of]
    u_q = range_q[chain_of, 0] + s_q / np.maximum(dense_q.length, 1e-300)[chain_of] * span_q[chain_of]
    u_p /= R.length[pair_of]
    u_q /= Q.length[pair_of]
    # A lens starts where the previous one ended: drop the repeat; a loop made of lenses ends
    # where it starts: drop its last sample.
    first = np.r_[0, np.cumsum(sizes)[:-1]]
    last = np.cumsum(sizes) - 1
    new_pair = np.r_[True, chain_pair[1:] != chain_pair[:-1]]
    end_of_pair = np.r_[chain_pair[1:] != chain_pair[:-1], True]
    keep = np.ones(len(chain_of), dtype=bool)
    keep[first[~new_pair]] = False
    lensed_loop = closed[chain_pair] & (count[chain_pair] > 1) & ~coincident[chain_pair]
    keep[last[end_of_pair & lensed_loop]] = False
    paths = BallPaths(
        np.concatenate([corr.p for corr in corrs])[keep],
        np.concatenate([corr.centers for corr in corrs])[keep],
        np.concatenate([corr.q for corr in corrs])[keep],
        kind,
    )
    pair_of, u_p, u_q = pair_of[keep], u_p[keep], u_q[keep]
    cyc = closed[pair_of]
    u_p = np.where(cyc, np.mod(u_p, 1.0), np.clip(u_p, 0.0, 1.0))
    u_q = np.where(cyc, np.mod(u_q, 1.0), np.clip(u_q, 0.0, 1.0))
    moving = (carrier != "NONE") & ~((np.abs(a - 1) <= tol.IDENTITY) & (np.abs(b) <= tol.IDENTITY * scale))
    done = np.zeros(n, dtype=bool)
    done[chain_pair] = True
    lenses = np.bincount(chain_pair, minlength=n)
    for c in np.flatnonzero(done):
        result.used[c] = f"{kind}-ball on a {carrier.lower()} carrier" if moving[c] else f"{kind}-ball"
        if lenses[c] > 1:
            result.notes[c] = [f"split at {lenses[c]} crossing/overlap pieces"]
    result.done = done
    result.offsets = np.concatenate([[0], np.cumsum(np.bincount(pair_of, minlength=n))])
    result.u_p, result.u_q = u_p, u_q
    result.paths, result.pair_of, result.a, result.b = paths, pair_of, a, b
    result.moving, result.centre, result.carrier = moving, as_complex(Q.centroids()), carrier
    return result


def _open_area(pieces):
    """Half the shoelace sum along open pieces, without a closing chord, shape (C,).

    For two pieces sharing both endpoints, ``_open_area(P) - _open_area(Q)`` is the signed area
    of the loop P followed by Q backwards.
    """
    a = pieces.pts
    nxt = pieces.nxt
    has = nxt >= 0
    cross = np.where(has, a[:, 0] * a[np.maximum(nxt, 0), 1] - a[:, 1] * a[np.maximum(nxt, 0), 0], 0.0)
    area = np.zeros(len(pieces))
    np.add.at(area, pieces.owner, cross)
    return 0.5 * area
