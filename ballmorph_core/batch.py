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
"""

from dataclasses import dataclass, field

import numpy as np

from . import tolerances as tol
from .ballmap import ball_maps
from .compat import PairSetup
from .intersections import segment_hits
from .ragged import Ragged
from .registration import carrier_at, similarities
from .spatial import box_pairs
from .trajectories import BallPaths

__all__ = ["BatchOutcome", "morph_pairs"]


@dataclass
class BatchOutcome:
    """Frames of one pair from the fast path.

    Attributes
    ----------
    frames : ndarray, shape (T, K, 2)
    u_p, u_q : ndarray, shape (K,)
        Arc-length fractions along P and Q as given.
    closed : bool
    used : str
    notes : list of str
    """

    frames: np.ndarray
    u_p: np.ndarray
    u_q: np.ndarray
    closed: bool
    used: str
    notes: list = field(default_factory=list)


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


def _inside(points, curves, owner):
    """Even-odd test of one point per pair against that pair's loop (vectorised), shape (C,)."""
    e = np.flatnonzero(curves.nxt >= 0)
    a, b = curves.pts[e], curves.pts[e] + curves.edge[e]
    pt = points[curves.owner[e]]
    straddle = (a[:, 1] > pt[:, 1]) != (b[:, 1] > pt[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        x = a[:, 0] + (pt[:, 1] - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
    hits = straddle & (pt[:, 0] < x)
    count = np.bincount(curves.owner[e][hits], minlength=len(curves))
    return count % 2 == 1


def morph_pairs(pairs, times, kind="circular", carrier="SIMILARITY", spacing=None):
    """Morph many stroke pairs at once (see the module docstring).

    Parameters
    ----------
    pairs : list of tuple
        ``(P, Q, closed)``: validated curves (see :func:`~ballmorph_core.curves.as_curve`),
        Q running the same way as P.
    times : ndarray, shape (T,)
    kind : str
        Ball-morph path: 'circular', 'linear', 'parabolic', 'hat' or 'tangent'.
    carrier : {'SIMILARITY', 'RIGID', 'NONE'}
    spacing : float, optional
        Sample spacing for every pair (default: each pair's
        :func:`~ballmorph_core.curves.default_spacing`).

    Returns
    -------
    list
        Per pair a :class:`BatchOutcome`, or None where the pair needs the general road.
    """
    out = [None] * len(pairs)
    if not pairs:
        return out
    times = np.asarray(times, dtype=np.float64)
    closed = np.array([c for _, _, c in pairs], dtype=bool)
    P = Ragged.from_list([p for p, _, _ in pairs], closed)
    Q = Ragged.from_list([q for _, q, _ in pairs], closed)
    n = len(P)
    if carrier == "NONE":
        a, b, residual = np.ones(n, dtype=complex), np.zeros(n, dtype=complex), np.full(n, np.inf)
    else:
        a, b, residual = similarities(P, Q)
    zp = a[P.owner] * (P.pts[:, 0] + 1j * P.pts[:, 1]) + b[P.owner]
    R = Ragged(np.stack([zp.real, zp.imag], axis=1), P.offsets, closed)  # registered P
    scale = np.maximum(_bbox_scale(R), _bbox_scale(Q))
    scale = np.where(scale > 0, scale, 1.0)
    eps = tol.COINCIDENT * scale
    h = _default_spacing(P, Q) if spacing is None else np.full(n, float(spacing))
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
    nested = _inside(R.pts[R.offsets[:-1]], Q, R.owner) | _inside(Q.pts[Q.offsets[:-1]], R, Q.owner)
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
    # Chains: every lens, plus nested loops and coincident loops whole.
    whole = np.flatnonzero(eligible & ((closed & (count == 0)) | coincident))
    chains_p, chains_q, chain_pair = [], [], []
    setups = []
    if len(lens_pair):
        pieces_p = R.pieces(lens_pair, np.asarray(l_p0), np.asarray(l_p1))
        pieces_q = Q.pieces(lens_pair, np.asarray(l_q0), np.asarray(l_q1))
        # Share the endpoints exactly.
        pieces_q.pts[pieces_q.offsets[:-1]] = pieces_p.pts[pieces_p.offsets[:-1]]
        pieces_q.pts[pieces_q.offsets[1:] - 1] = pieces_p.pts[pieces_p.offsets[1:] - 1]
        # The gap lies left of P when P then Q backwards turns counter-clockwise.
        area = _open_area(pieces_p) - _open_area(pieces_q)
        for k in range(len(lens_pair)):
            c = lens_pair[k]
            flat = abs(area[k]) <= tol.OVERLAP * scale[c] * max(pieces_p.length[k], 1e-300)
            side = 1.0 if area[k] > 0 else -1.0
            setups.append(PairSetup(pieces_p.curve(k), _fixed(pieces_q, k), False, side, -side, coincident=flat))
            chain_pair.append(c)
            chains_p.append((l_p0[k], l_p1[k]))
            chains_q.append((l_q0[k], l_q1[k]))
    for c in whole:
        rp, rq = R.curve(c), Q.curve(c)
        if coincident[c]:
            setups.append(PairSetup(rp, rq, bool(closed[c]), 1.0, 1.0, coincident=True))
        else:
            # Nested loops: left normals point inside a counter-clockwise loop.
            ccw = 1.0 if R.signed_areas()[c] > 0 else -1.0
            p_inner = bool(_inside(R.pts[[R.offsets[c]]], Ragged.from_list([rq], [True]), None)[0])
            side_p = -ccw if p_inner else ccw
            setups.append(PairSetup(rp, rq, True, side_p, -side_p))
        chain_pair.append(c)
        chains_p.append((0.0, R.length[c]))
        chains_q.append((0.0, Q.length[c]))
    if not setups:
        return out
    chain_pair = np.asarray(chain_pair)
    corrs = ball_maps(setups, h[chain_pair], "symmetric", check=False, eps=eps[chain_pair])
    failed = np.zeros(n, dtype=bool)
    for corr, c in zip(corrs, chain_pair):
        if corr.report.violations:
            failed[c] = True
    # Paths of every sample of every good chain, evaluated once per frame.
    good = [k for k, c in enumerate(chain_pair) if not failed[c]]
    if not good:
        return out
    p_all = np.concatenate([corrs[k].p for k in good])
    m_all = np.concatenate([corrs[k].centers for k in good])
    q_all = np.concatenate([corrs[k].q for k in good])
    paths = BallPaths(p_all, m_all, q_all, kind)
    frames_all = np.stack([paths.at(t) for t in times])  # (T, K, 2)
    sizes = [len(corrs[k]) for k in good]
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    centres = Q.centroids()
    by_pair = {}
    for pos, k in enumerate(good):
        by_pair.setdefault(int(chain_pair[k]), []).append((pos, k))
    for c, items in by_pair.items():
        frames, u_p, u_q = [], [], []
        for j, (pos, k) in enumerate(items):
            sl = slice(offsets[pos] + (1 if j > 0 else 0), offsets[pos + 1])
            corr = corrs[k]
            dense_len_p = max(float(np.sum(np.linalg.norm(np.diff(corr.dense_p, axis=0), axis=1))), 1e-300)
            dense_len_q = max(float(np.sum(np.linalg.norm(np.diff(corr.dense_q, axis=0), axis=1))), 1e-300)
            if corr.closed:
                dense_len_p += float(np.linalg.norm(corr.dense_p[0] - corr.dense_p[-1]))
                dense_len_q += float(np.linalg.norm(corr.dense_q[0] - corr.dense_q[-1]))
            (p0, p1), (q0, q1) = chains_p[k], chains_q[k]
            lo = 1 if j > 0 else 0
            u_p.append(p0 + corr.s_p[lo:] / dense_len_p * (p1 - p0))
            u_q.append(q0 + corr.s_q[lo:] / dense_len_q * (q1 - q0))
            frames.append(frames_all[:, sl])
        frames = np.concatenate(frames, axis=1)
        u_p = np.concatenate(u_p) / R.length[c]
        u_q = np.concatenate(u_q) / Q.length[c]
        if closed[c] and len(items) and items[0] is not None and not (coincident[c] or count[c] == 0):
            frames, u_p, u_q = frames[:, :-1], u_p[:-1], u_q[:-1]  # the loop's last point is its first
        u_p = np.mod(u_p, 1.0) if closed[c] else np.clip(u_p, 0.0, 1.0)
        u_q = np.mod(u_q, 1.0) if closed[c] else np.clip(u_q, 0.0, 1.0)
        # Carrier: C_t = S^-(1-t), undoing the registration progressively.
        if carrier != "NONE" and not (abs(a[c] - 1) <= 1e-9 and abs(b[c]) <= 1e-9 * scale[c]):
            centre = complex(*centres[c])
            moved = []
            for ti, t in enumerate(times):
                ca, cb = carrier_at(a[c], b[c], carrier, centre, t)
                z = ca * (frames[ti, :, 0] + 1j * frames[ti, :, 1]) + cb
                moved.append(np.stack([z.real, z.imag], axis=1))
            frames = np.stack(moved)
            used = f"{kind}-ball on a {carrier.lower()} carrier"
        else:
            used = f"{kind}-ball"
        notes = []
        if count[c] and not closed[c] or (closed[c] and count[c] > 1):
            notes.append(f"split at {len(items)} crossing/overlap pieces")
        out[c] = BatchOutcome(frames, u_p, u_q, bool(closed[c]), used, notes)
    return out


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


def _fixed(pieces, k):
    return pieces.curve(k).copy()
