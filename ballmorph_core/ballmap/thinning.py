"""Symmetric sampling (the paper's approach 3): both one-way maps joined and thinned.

Both curves are sampled densely, each sample is mapped to the other curve, the union of the
pairs is ordered along the (monotone) correspondence graph and thinned so that between
consecutive kept pairs one of the two contacts has moved by the spacing and the other by at
most the spacing. Every kept pair is an exact ball-map contact; swapping P and Q gives the same
pairs. The composite ball-morph thins its chained correspondence the same way.
"""

import numpy as np

from .. import tolerances as tol
from ..geometry.ragged import ragged_arange
from .onemap import OneWayMap
from .report import Violation

__all__ = ["symmetric_samples", "chain_order", "running_backsteps", "uniform_picks"]

#: The forward (P -> Q) and backward (Q -> P) maps may disagree by this many dense spacings
#: before the pair counts as not b-compatible there (a disk touching a curve at two places makes
#: them disagree by much more).
MAP_DISAGREEMENT = 1.0


def _segments(chain, n_chains):
    """Start index of each chain's run in a chain-sorted array, shape (C + 1,)."""
    return np.searchsorted(chain, np.arange(n_chains + 1))


def _onto_forward_laps(fwd, bwd, sp, sq):
    """The backward pairs of loops moved into the forward map's unwrapped frame (OneWayMap).

    Interpolates the forward graph (with one extra node closing each loop's lap) to find, for
    each backward pair, the lap of the forward pair it sits between.
    """
    n_chains = len(sp.rg)
    len_p, len_q, closed = sp.rg.length, sq.rg.length, sp.rg.closed
    cf, cb = fwd.chain, bwd.chain
    first = sp.rg.offsets[:-1]
    gx = np.concatenate([fwd.s_src, fwd.s_src[first] + len_p])
    gy = np.concatenate([fwd.s_dst, fwd.s_dst[first] + len_q])
    gc = np.concatenate([cf, np.arange(n_chains)])
    # Chains shifted apart by a gap of their own size (not of 1.0, which swamps a tiny drawing's
    # positions in round-off), so one interpolation serves them all.
    gap = float(len_p.max(initial=0.0)) or 1.0
    base = np.concatenate([[0.0], np.cumsum(len_p + gap)])[:-1]
    order = np.argsort(gx + base[gc], kind="stable")
    wraps = closed[cb] & (len_p[cb] > 0)  # loops of zero length (degenerate chains) do not wrap
    sp_b = np.where(wraps, np.mod(bwd.s_src, np.where(wraps, len_p[cb], 1.0)), bwd.s_src)
    ref = np.interp(sp_b + base[cb], (gx + base[gc])[order], gy[order])
    # Whole laps to add (loops only; a zero-length chain has none).
    laps = np.divide(ref - bwd.s_dst, len_q[cb], out=np.zeros_like(ref), where=closed[cb] & (len_q[cb] > 0))
    bwd.s_src, bwd.s_dst = sp_b, bwd.s_dst + len_q[cb] * np.round(laps)
    return bwd


def chain_order(chain, key):
    """``np.lexsort((key, chain))``: the rows by chain, then by key, ties in row order.

    One stable sort of ``chain + key j`` (numpy orders complex numbers by their real parts,
    then their imaginary ones): rows that come in a few runs already in order (both one-way
    maps, chain after chain) take one merge of the runs instead of lexsort's two full sorts,
    a tenth of the time. A NaN key (never from finite curves) sorts a complex number last
    whatever its chain, so such keys take lexsort itself.

    Parameters
    ----------
    chain : ndarray of int, shape (K,)
        Below 2**53 (exact as floats).
    key : ndarray, shape (K,)

    Returns
    -------
    ndarray of int, shape (K,)
    """
    if np.isnan(key).any():
        return np.lexsort((key, chain))
    z = np.empty(len(key), dtype=np.complex128)
    z.real, z.imag = chain, key
    return np.argsort(z, kind="stable")


def running_backsteps(s, chain):
    """How far each position lies behind the running maximum of its chain's earlier positions.

    Exact at any scale: the running maximum is taken of the positions' ranks (integers, the
    chains shifted apart by the count), not of the positions shifted by a length, whose
    round-off would be that length's and not the chain's own.

    Parameters
    ----------
    s : ndarray, shape (K,)
        Positions, grouped by ``chain`` (non-decreasing).
    chain : ndarray of int, shape (K,)

    Returns
    -------
    ndarray, shape (K,)
        0 where the sequence is monotone.
    """
    order = np.argsort(s, kind="stable")
    rank = np.empty(len(s), dtype=np.int64)
    rank[order] = np.arange(len(s))
    shift = np.asarray(chain, dtype=np.int64) * len(s)
    return np.take(s, np.take(order, np.maximum.accumulate(rank + shift) - shift)) - s


def uniform_picks(sp_, sq_, chain, n_chains, len_p, len_q, closed, spacing):
    """Rows of a monotone correspondence kept at a uniform spacing along it.

    The correspondence graph of each chain is parametrised by ``tau``, the cumulative larger of
    the two contacts' steps; the row nearest each multiple of a uniform step (the spacing,
    rounded so it divides the chain's ``tau``, a loop's closing step included) is kept.

    Parameters
    ----------
    sp_, sq_ : ndarray, shape (K,)
        Contact positions on P and Q, monotone within each chain.
    chain : ndarray of int, shape (K,)
    n_chains : int
    len_p, len_q : ndarray, shape (C,)
    closed : ndarray of bool, shape (C,)
    spacing : ndarray, shape (C,)

    Returns
    -------
    ndarray of int
        Sorted indices of the kept rows.
    """
    seg = _segments(chain, n_chains)
    starts, ends = seg[:-1], seg[1:] - 1
    tau = np.cumsum(_larger_steps(sp_, sq_, starts))
    # Rows by take (in range: 'wrap' skips the bounds check; fancy indexing costs twice as much).
    tau -= np.take(tau[starts], chain, mode="wrap")
    closing = np.maximum(len_p - (sp_[ends] - sp_[starts]), len_q - (sq_[ends] - sq_[starts]))
    total = tau[ends] + np.where(closed, closing, 0.0)
    count = np.maximum(np.round(total / spacing).astype(np.int64), np.where(closed, 3, 1))
    owner, local = ragged_arange(count + np.where(closed, 0, 1))
    targets = local * np.take(total / count, owner, mode="wrap")
    # The node nearest each multiple of the uniform step, within its chain.
    tbase = np.concatenate([[0.0], np.cumsum(total + 1.0)])[:-1]
    g = tau + np.take(tbase, chain, mode="wrap")
    want = targets + np.take(tbase, owner, mode="wrap")
    first, last = (np.take(v, owner, mode="wrap") for v in (starts, ends))
    hi = np.clip(np.searchsorted(g, want), first + 1, np.maximum(last, first + 1))
    hi = np.minimum(hi, len(g) - 1)
    lo = np.maximum(hi - 1, first)
    g_lo, g_hi = (np.take(g, v, mode="wrap") for v in (lo, hi))
    return _sorted_unique(np.where(want - g_lo <= g_hi - want, lo, hi))


def _larger_steps(sp_, sq_, starts):
    """The larger of each row's two steps from the row before, 0 at the chains' first rows
    (``starts``), shape (K,): np.diff's differences, without its copy of the rows."""
    # Kept buffers from np.empty (np.zeros' calloc maps fresh pages for large arrays).
    step, other = np.empty(len(sp_)), np.empty(len(sq_))
    for v, d in ((sp_, step), (sq_, other)):
        d[:1] = 0.0
        np.subtract(v[1:], v[:-1], out=d[1:])
        np.abs(d, out=d)
    np.maximum(step, other, out=step)
    step[starts] = 0.0
    return step


def _sorted_unique(picks):
    """``np.unique(picks)`` (ndarray of int, shape (K,)): without its sort where the picks come in
    order already (nearest nodes of increasing targets do, chain after chain)."""
    if not np.all(picks[1:] >= picks[:-1]):
        return np.unique(picks)
    first = np.ones(len(picks), dtype=bool)
    np.not_equal(picks[1:], picks[:-1], out=first[1:])
    return picks[first]


def _report_disagreements(allp, order, back_p, back_q, sp, sq, dense_spacing, reports):
    """A Violation for every pair stepping back by more than MAP_DISAGREEMENT dense spacings.

    ``back_p``, ``back_q`` (shape (K,)) are the steps back of the rows of ``allp`` taken in
    ``order``; a violation's sample is its place in that order.
    """
    len_p, len_q, closed = sp.rg.length, sq.rg.length, sp.rg.closed
    h = dense_spacing[allp.chain[order]]
    for k in np.flatnonzero(np.maximum(back_p, back_q) > MAP_DISAGREEMENT * h):
        row = order[k]
        c = allp.chain[row]
        curve = "P" if back_p[k] >= back_q[k] else "Q"
        reports[c].violations.append(
            Violation(
                driver="P+Q",
                sample=int(k),
                p=allp.src[row],
                q=allp.dst[row],
                s_p=float(np.mod(allp.s_src[row], len_p[c]) if closed[c] else allp.s_src[row]),
                s_q=float(np.mod(allp.s_dst[row], len_q[c]) if closed[c] else allp.s_dst[row]),
                witness_curve=curve,
                witness=allp.src[row] if curve == "P" else allp.dst[row],
                depth=float(max(back_p[k], back_q[k])),
            )
        )


def symmetric_samples(fwd, bwd, sp, sq, spacing, dense_spacing, reports):
    """Thin the union of both one-way maps into symmetric samples (OneWayMap, P -> Q).

    Per chain, the union ordered by ``s_p + s_q`` must be a monotone chain. Pairs that step back
    by round-off are dropped; a pair that steps back by more than ``MAP_DISAGREEMENT`` dense
    spacings means the forward and backward maps disagree: a maximal disk touches a curve at two
    places (paper section 3.4), reported.

    Parameters
    ----------
    fwd, bwd : OneWayMap
        P -> Q and Q -> P maps of the same chains.
    sp, sq : Sides
    spacing, dense_spacing : ndarray, shape (C,)
        Output and dense sample spacing per chain.
    reports : list of CompatibilityReport
    """
    len_p, len_q = sp.rg.length, sq.rg.length
    bwd = bwd.flipped()  # now read from P to Q like fwd
    if sp.rg.closed.any():
        bwd = _onto_forward_laps(fwd, bwd, sp, sq)
    allp = OneWayMap.concatenate([fwd, bwd])
    # Only the positions and chains are read in order before the thinning: the other fields
    # are taken once, for the kept rows.
    order = chain_order(allp.chain, allp.s_src + allp.s_dst)
    s_p, s_q, chain = (np.take(v, order) for v in (allp.s_src, allp.s_dst, allp.chain))
    back_p = running_backsteps(s_p, chain)
    back_q = running_backsteps(s_q, chain)
    _report_disagreements(allp, order, back_p, back_q, sp, sq, dense_spacing, reports)
    # In range: take's 'wrap' mode skips the bounds check.
    lp, lq = (np.take(v, chain, mode="wrap") for v in (len_p, len_q))
    steady = np.flatnonzero((back_p <= tol.ROUNDOFF * lp) & (back_q <= tol.ROUNDOFF * lq))
    sp_, sq_, chain_ = (np.take(v, steady) for v in (s_p, s_q, chain))
    keep = uniform_picks(sp_, sq_, chain_, len(sp.rg), len_p, len_q, sp.rg.closed, spacing)
    return allp.take(order[steady[keep]])
