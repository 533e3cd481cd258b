"""Aligned interpolation: straight paths between points matched by a monotone alignment.

The fallback for pairs that lie over each other but that no ball-morph can follow (curves
crossing in a different order along each one, a key whose stroke crosses itself). Linear
interpolation matches them by arc length, so a part drawn longer in one key (a glyph's stem
grown bolder, a stroke redrawn with a longer hook) drags every point after it along the
other curve. Here the match is the monotone one that keeps matched points closest: dynamic
time warping of uniform samples, minimising the summed squared distance of matched samples
(each step advancing along one curve or both). Loops are aligned from the cyclic shift and
direction of least travel (as linear interpolation aligns them), both ends pinned there.

The alignment runs on at most ``ALIGN_SAMPLES`` samples per curve (its cost grows with their
product), for a batch of pairs at once; the morph's own samples then follow the aligned map
between arc lengths.
"""

from dataclasses import dataclass

import numpy as np

from ..geometry.ragged import Ragged
from .base import PathMorph
from .linear import best_cyclic_alignment, sample_count
from .paths import LinearPaths

__all__ = ["METHOD", "ALIGN_SAMPLES", "WARP_SMOOTHING", "align", "aligned_morphs", "aligned_morph"]

#: The morph's name in reports.
METHOD = "aligned-interpolation"

#: Samples per curve of the alignment (at most): 256 x 256 cells a pair.
ALIGN_SAMPLES = 256

#: Steps of the warp its fractions are averaged over (odd): about 2 % of a warp of 256 x 256.
WARP_SMOOTHING = 9

#: Alignment cells held at once (pairs are aligned in chunks of about this many cells: the
#: anti-diagonal tables of cost and total, float64, hold twice that each, about 16 MB in all,
#: seven pairs of 256 x 256).
_CELL_BUDGET = 500_000


def align(ps, qs):
    """The monotone alignments of pairs of sample sequences, both ends pinned.

    Parameters
    ----------
    ps, qs : list of ndarray
        G pairs: ``ps[g]`` shape (N_g, 2), ``qs[g]`` shape (M_g, 2); ``ps[g][0]`` goes to
        ``qs[g][0]`` and ``ps[g][-1]`` to ``qs[g][-1]``.

    Returns
    -------
    list of (ndarray of int, ndarray of int)
        Per pair, the matched sample indices ``i, j`` (shape (L_g,) each), non-decreasing, from
        (0, 0) to (N_g - 1, M_g - 1), each step advancing ``i`` or ``j`` or both by one.
    """
    out, start = [], 0
    while start < len(ps):
        stop, cells = start, 0
        while stop < len(ps) and (stop == start or cells + len(ps[stop]) * len(qs[stop]) <= _CELL_BUDGET):
            cells += len(ps[stop]) * len(qs[stop])
            stop += 1
        out += _align_chunk(ps[start:stop], qs[start:stop])
        start = stop
    return out


def _align_chunk(ps, qs):
    """:func:`align` of a few pairs, in one table of anti-diagonals (padding cells cost inf)."""
    g = len(ps)
    n, m = np.array([len(p) for p in ps]), np.array([len(q) for q in qs])
    big_n, big_m = int(n.max()), int(m.max())
    diagonals = big_n + big_m - 1
    # cost[d, :, i]: the squared distance of cell (i, d - i), the cells of anti-diagonal d side
    # by side, so that each diagonal's predecessors are slices of the two before it.
    i = np.arange(big_n)[None, :]
    j = np.arange(diagonals)[:, None] - i
    cost = np.full((diagonals, g, big_n), np.inf)
    cells = {}  # (N_g, M_g) -> its cells (d, i, j): most pairs share the size ALIGN_SAMPLES
    for k, (p, q) in enumerate(zip(ps, qs)):
        if (len(p), len(q)) not in cells:
            d, ii = np.nonzero((j >= 0) & (j < len(q)) & (i < len(p)))
            cells[len(p), len(q)] = d, ii, j[d, ii]
        d, ii, jj = cells[len(p), len(q)]
        full = np.sum(np.square(p[:, None, :] - q[None, :, :]), axis=2)
        cost[d, k, ii] = full[ii, jj]
    # total[d + 2, :, i + 1]: the least cost of a warp to cell (i, d - i). Row 0 column 0 is the
    # corner before the start, so cell (0, 0) costs what a diagonal step into it does (every
    # warp pays it: the same optimum); the rest of the border is unreachable.
    total = np.full((diagonals + 2, g, big_n + 1), np.inf)
    total[0, :, 0] = 0.0
    step = np.zeros((diagonals, g, big_n), dtype=np.int8)
    for d in range(diagonals):
        c = cost[d]
        # Steps 0, 1, 2 come from (i - 1, j - 1), (i - 1, j), (i, j - 1); a step along both
        # curves counts its cell twice, so a diagonal walk costs what two single steps cost.
        # Ties go to the first (as argmin would).
        both, along_p, along_q = total[d, :, :-1] + 2.0 * c, total[d + 1, :, :-1] + c, total[d + 1, :, 1:] + c
        low = np.minimum(np.minimum(both, along_p), along_q)
        step[d] = np.where(both == low, 0, np.where(along_p == low, 1, 2))
        total[d + 2, :, 1:] = low
    # Walk every warp back from its far corner at once.
    di, dj = np.array([1, 1, 0]), np.array([1, 0, 1])
    at_i, at_j = n - 1, m - 1
    rows = np.arange(g)
    trail_i, trail_j = [at_i], [at_j]
    while (at_i > 0).any() or (at_j > 0).any():
        moving = (at_i > 0) | (at_j > 0)
        code = step[at_i + at_j, rows, at_i]
        at_i = np.where(moving, at_i - di[code], at_i)
        at_j = np.where(moving, at_j - dj[code], at_j)
        trail_i.append(np.where(moving, at_i, -1))
        trail_j.append(np.where(moving, at_j, -1))
    trail_i, trail_j = np.array(trail_i)[::-1], np.array(trail_j)[::-1]
    out = []
    for k in range(g):
        keep = trail_i[:, k] >= 0
        out.append((trail_i[keep, k], trail_j[keep, k]))
    return out


def _uniform(curve, closed, count):
    """A curve as a batch of one, and ``count`` uniform arc-length samples of it, shape
    (count, 2) (a loop's first one repeated at the end)."""
    rg = Ragged.from_list([curve], [closed])
    s = np.linspace(0.0, rg.length[0], count)
    return rg, rg.point_at(np.zeros(count, dtype=np.int64), s, smooth=True)


@dataclass
class _Setup:
    """One pair ready to align.

    Attributes
    ----------
    count : int
        Samples of the morph.
    rp, rq : Ragged
        P and Q, batches of one.
    xp, xq : ndarray, shape (k + closed, 2)
        Their alignment samples, Q's in the order P meets them.
    shift : int
    backwards : bool
        Loops: Q's sample ``shift`` meets P's first, and Q is met backwards.
    k : int
        Alignment samples per curve (a loop's first not repeated).
    """

    count: int
    rp: Ragged
    rq: Ragged
    xp: np.ndarray
    xq: np.ndarray
    shift: int
    backwards: bool
    k: int

    @classmethod
    def of(cls, P, Q, closed, spacing):
        """The setup of curves P, Q (shapes (N, 2), (M, 2)) at ``spacing``."""
        count = sample_count(P, Q, closed, spacing, "symmetric")
        k = min(ALIGN_SAMPLES, max(count, 3))
        rp, xp = _uniform(P, closed, k + closed)
        rq, xq = _uniform(Q, closed, k + closed)
        shift, backwards = 0, False
        if closed:
            shift, backwards = best_cyclic_alignment(xp[:-1], xq[:-1])
        # Q's samples in the order P meets them: from its shift, forwards or backwards.
        order = (shift + (-1 if backwards else 1) * np.arange(k + closed)) % k if closed else np.arange(k)
        return cls(count, rp, rq, xp, xq[order], shift, backwards, k)


def _smoothed(f):
    """A warp's fractions along one curve (non-decreasing, shape (L,)) averaged over
    ``WARP_SMOOTHING`` steps, its ends kept: still non-decreasing, without the staircase a warp
    makes where one curve waits for the other (each stair a small kink in the in-betweens)."""
    if len(f) <= 2:
        return f
    pad = WARP_SMOOTHING // 2
    padded = np.concatenate([np.full(pad, f[0]), f, np.full(pad, f[-1])])
    sums = np.cumsum(np.r_[0.0, padded])
    out = (sums[2 * pad + 1 :] - sums[: -2 * pad - 1]) / (2 * pad + 1)
    out[0], out[-1] = f[0], f[-1]
    return out


def _morph(setup, closed, i, j):
    """The PathMorph of one pair from its _Setup and its warp ``(i, j)``."""
    count, rp, rq, shift, k = setup.count, setup.rp, setup.rq, setup.shift, setup.k
    # Along the warp both fractions grow; their sum grows strictly: the morph's samples are
    # spread evenly over it.
    fp, fq = _smoothed(i / (len(setup.xp) - 1)), _smoothed(j / (len(setup.xq) - 1))
    walk = fp + fq
    w = np.linspace(0.0, walk[-1], count, endpoint=not closed)
    u_p, t_q = np.interp(w, walk, fp), np.interp(w, walk, fq)
    u_q = (shift / k + (-1.0 if setup.backwards else 1.0) * t_q) % 1.0 if closed else t_q
    if not closed:
        u_p[-1], u_q[-1] = 1.0, 1.0
    zero = np.zeros(count, dtype=np.int64)
    p = rp.point_at(zero, u_p * rp.length[0], smooth=True)
    q = rq.point_at(zero, u_q * rq.length[0], smooth=True)
    return PathMorph(METHOD, closed, LinearPaths(p, q), u_p, u_q)


def aligned_morphs(pairs, spacing):
    """The aligned interpolations of several curve pairs, aligned together.

    Parameters
    ----------
    pairs : list of (ndarray, ndarray, bool)
        Validated curves P (N, 2) and Q (M, 2) (a stroke Q running the way P does) and whether
        they are loops.
    spacing : list of float or None
        Each pair's sample spacing (the longer curve's count, as linear interpolation).

    Returns
    -------
    list of PathMorph
        Method :data:`METHOD`.
    """
    setups = [_Setup.of(P, Q, closed, h) for (P, Q, closed), h in zip(pairs, spacing)]
    warps = align([s.xp for s in setups], [s.xq for s in setups])
    return [_morph(s, closed, i, j) for s, (_, _, closed), (i, j) in zip(setups, pairs, warps)]


def aligned_morph(P, Q, closed, spacing):
    """:func:`aligned_morphs` of one pair (PathMorph)."""
    return aligned_morphs([(P, Q, closed)], [spacing])[0]
