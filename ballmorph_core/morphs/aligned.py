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
product); the morph's own samples then follow the aligned map between arc lengths.
"""

import numpy as np

from ..geometry.ragged import Ragged
from .base import PathMorph
from .linear import best_cyclic_alignment, sample_count
from .paths import LinearPaths

__all__ = ["METHOD", "ALIGN_SAMPLES", "align", "aligned_morph"]

#: The morph's name in reports.
METHOD = "aligned-interpolation"

#: Samples per curve of the alignment (at most): 256 x 256 cells, about 5 ms.
ALIGN_SAMPLES = 256

#: The three steps of the warp: along both curves (its cost counted twice, so a diagonal walk
#: costs what two single steps cost) or along one.
_STEPS = ((1, 1, 2.0), (1, 0, 1.0), (0, 1, 1.0))


def align(p, q):
    """The monotone alignment of two sample sequences with both ends pinned.

    Parameters
    ----------
    p, q : ndarray, shape (N, 2), (M, 2)
        ``p[0]`` goes to ``q[0]`` and ``p[-1]`` to ``q[-1]``.

    Returns
    -------
    i, j : ndarray of int, shape (L,)
        The matched sample indices, non-decreasing, from (0, 0) to (N - 1, M - 1), each step
        advancing ``i`` or ``j`` or both by one.
    """
    n, m = len(p), len(q)
    cost = np.sum(np.square(p[:, None, :] - q[None, :, :]), axis=2)
    total = np.full((n, m), np.inf)
    step = np.zeros((n, m), dtype=np.int8)
    total[0, 0] = cost[0, 0]
    # Cells of one anti-diagonal depend only on the two before it: each is one vector step.
    for d in range(1, n + m - 1):
        i = np.arange(max(0, d - m + 1), min(n - 1, d) + 1)
        j = d - i
        best = np.full(len(i), np.inf)
        for k, (di, dj, weight) in enumerate(_STEPS):
            ok = (i >= di) & (j >= dj)
            came = np.full(len(i), np.inf)
            came[ok] = total[i[ok] - di, j[ok] - dj] + weight * cost[i[ok], j[ok]]
            better = came < best
            best[better], step[i[better], j[better]] = came[better], k
        total[i, j] = best
    path = [(n - 1, m - 1)]
    while path[-1] != (0, 0):
        a, b = path[-1]
        di, dj, _ = _STEPS[step[a, b]]
        path.append((a - di, b - dj))
    i, j = np.array(path[::-1]).T
    return i, j


def _uniform(curve, closed, count):
    """``count`` uniform arc-length samples of a curve (a loop's first one repeated at the end)."""
    rg = Ragged.from_list([curve], [closed])
    s = np.linspace(0.0, rg.length[0], count)
    return rg, s, rg.point_at(np.zeros(count, dtype=np.int64), s, smooth=True)


def aligned_morph(P, Q, closed, spacing):
    """The aligned interpolation of two curves (see the module docstring).

    Parameters
    ----------
    P, Q : ndarray, shape (N, 2), (M, 2)
        Validated curves; a stroke Q runs the way P does.
    closed : bool
    spacing : float or None
        Sample spacing of the morph (the longer curve's count, as linear interpolation).

    Returns
    -------
    PathMorph
        Method :data:`METHOD`.
    """
    count = sample_count(P, Q, closed, spacing, "symmetric")
    k = min(ALIGN_SAMPLES, max(count, 3))
    rp, sp, xp = _uniform(P, closed, k + closed)
    rq, sq, xq = _uniform(Q, closed, k + closed)
    shift, backwards = 0, False
    if closed:
        shift, backwards = best_cyclic_alignment(xp[:-1], xq[:-1])
    # Q's samples in the order P meets them: from its shift, forwards or backwards.
    order = (shift + (-1 if backwards else 1) * np.arange(k + closed)) % k if closed else np.arange(k)
    i, j = align(xp, xq[order])
    # Along the warp both fractions grow; their sum grows strictly: the morph's samples are
    # spread evenly over it.
    fp, fq = i / (len(xp) - 1), j / (len(xq) - 1)
    walk = fp + fq
    w = np.linspace(0.0, walk[-1], count, endpoint=not closed)
    u_p, t_q = np.interp(w, walk, fp), np.interp(w, walk, fq)
    u_q = (shift / k + (-1.0 if backwards else 1.0) * t_q) % 1.0 if closed else t_q
    if not closed:
        u_p[-1], u_q[-1] = 1.0, 1.0
    zero = np.zeros(count, dtype=np.int64)
    p = rp.point_at(zero, u_p * rp.length[0], smooth=True)
    q = rq.point_at(zero, u_q * rq.length[0], smooth=True)
    return PathMorph(METHOD, closed, LinearPaths(p, q), u_p, u_q)
