"""Pairs the keys' own points carry: a stroke the same in both keys, or moved by a similarity.

A stroke that did not change (the house in the background) or that only moved, turned or grew
(point for point: the same points, moved together) needs no correspondence: its points are the
correspondence. Such a pair is written with the key's own points, moved by the carrier (the
identity for a stroke that did not change), instead of being resampled and ball-mapped: an
unchanged stroke comes back bit for bit, a polyline keeps its corners, the point count stays.

A pair is *exact* when both strokes have the same number of points and the least-squares
similarity taking the first's points onto the second's (for loops, over every start of the
second) leaves no point farther than ``EXACT`` times the pair's size or coordinates (the
float32 rounding Blender stores points with).
"""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...geometry.procrustes import cyclic_correlation, similarity_fit
from ...geometry.similarity import as_complex

__all__ = ["EXACT", "ExactFit", "exact_fit", "may_be_exact"]

#: Largest point residual of an exact pair, relative to its size or its coordinates' magnitude
#: (float32 keys round at about 6e-8 of the magnitude).
EXACT = 1e-6


#: :func:`may_be_exact` keeps a pair whose least-squares residual is within this fraction of its
#: squared size of the exact limit: far above the round-off of the closed form it uses.
MAY_BE_EXACT_SLACK = 1e-9


@dataclass
class ExactFit:
    """A pair whose points match one for one under a similarity ``z -> a z + b``.

    Attributes
    ----------
    a, b : complex
    shift : int
        For loops: point ``i`` of the first stroke goes to point ``(i + shift) % n`` of the
        second (0 for strokes).
    """

    a: complex
    b: complex
    shift: int = 0


def _procrustes(za, zb):
    """Least-squares similarity ``za -> zb`` and its largest point residual."""
    a, b = similarity_fit(za, zb)
    return a, b, float(np.abs(a * za + b - zb).max())


def exact_fit(xy_a, xy_b, closed, similarity=True, turn=0.0):
    """The similarity that carries one stroke's points onto the other's, if there is one.

    Parameters
    ----------
    xy_a, xy_b : ndarray, shape (N, 2), (M, 2)
        The two strokes' points (the second running the same way as the first).
    closed : bool
    similarity : bool
        Allow any similarity; otherwise only the identity (no carrier to move the points).
    turn : float
        The drawing's turn (radians): of the starts that fit a symmetric loop (a regular
        polygon fits at every vertex), the one turning closest to it.

    Returns
    -------
    ExactFit or None
        None unless both strokes have the same point count and the fit leaves every point
        within ``EXACT`` (of the pair's size and coordinate magnitude).
    """
    if len(xy_a) != len(xy_b) or len(xy_a) < 2:
        return None
    za, zb = as_complex(xy_a), as_complex(xy_b)
    magnitude = max(float(np.abs(np.r_[za, zb]).max()), float(np.ptp(xy_a, axis=0).max()), tol.TINY)
    limit = EXACT * magnitude
    shifts = np.zeros(1, np.int64)
    if closed:
        # Starts of the second loop where the first's start may land: the shifts maximising the
        # centred cross-correlation (every vertex of a regular polygon), the smallest turn first.
        pa, pb = za - za.mean(), zb - zb.mean()
        corr = cyclic_correlation(pa, pb)
        best = np.flatnonzero(np.abs(corr) >= np.abs(corr).max() * (1.0 - EXACT))
        off = np.abs(np.angle(corr[best] * np.exp(-1j * turn)))
        # Two fits at most: the closest turn, and the best correlation (which it usually is).
        shifts = np.unique([best[np.argmin(off)], int(np.argmax(np.abs(corr)))])
        shifts = shifts[np.argsort(np.abs(np.angle(corr[shifts] * np.exp(-1j * turn))), kind="stable")]
    for shift in shifts:
        target = np.roll(zb, -int(shift))
        if not similarity:
            if float(np.abs(za - target).max()) <= limit:
                return ExactFit(1.0 + 0j, 0j, int(shift))
            continue
        a, b, worst = _procrustes(za, target)
        if worst <= limit:
            return ExactFit(a, b, int(shift))
    return None


def may_be_exact(xy_a, xy_b, closed):
    """Which pairs :func:`exact_fit` may fit, every pair of a drawing at once (a cheap necessary
    condition: the others need not be tried one by one).

    A fit within ``EXACT`` at every point leaves a summed squared residual of at most ``N``
    times the limit squared, and no similarity (nor the identity) leaves less than the
    least-squares one: ``sum |pb|^2 - |sum conj(pa) pb|^2 / sum |pa|^2`` for centred points,
    at its best start for loops (the cross-correlation's largest magnitude, by FFT for all
    starts and all loops of a point count at once).

    Parameters
    ----------
    xy_a, xy_b : list of ndarray, shapes (N_i, 2), (M_i, 2)
    closed : array_like of bool, shape (C,)

    Returns
    -------
    ndarray of bool, shape (C,)
    """
    closed = np.asarray(closed, dtype=bool).reshape(-1)
    n = np.array([len(a) for a in xy_a], dtype=np.int64)
    maybe = np.zeros(len(n), dtype=bool)
    same = (n == np.array([len(b) for b in xy_b], dtype=np.int64)) & (n >= 2)
    for k, loop in {(int(n[c]), bool(closed[c])) for c in np.flatnonzero(same)}:
        group = np.flatnonzero(same & (n == k) & (closed == loop))
        a = np.stack([xy_a[c] for c in group]).astype(np.float64)
        za, zb = as_complex(a), as_complex(np.stack([xy_b[c] for c in group]).astype(np.float64))
        magnitude = np.maximum(
            np.maximum(np.abs(za).max(axis=1), np.abs(zb).max(axis=1)), np.ptp(a, axis=1).max(axis=1)
        )
        limit = EXACT * np.maximum(magnitude, tol.TINY)
        pa, pb = za - za.mean(axis=1, keepdims=True), zb - zb.mean(axis=1, keepdims=True)
        norm_a, norm_b = (np.abs(pa) ** 2).sum(axis=1), (np.abs(pb) ** 2).sum(axis=1)
        if loop:
            corr = np.abs(cyclic_correlation(pa, pb)).max(axis=1)
        else:
            corr = np.abs((np.conj(pa) * pb).sum(axis=1))
        residual = norm_b - corr**2 / np.where(norm_a > 0, norm_a, 1.0)
        slack = MAY_BE_EXACT_SLACK * (norm_a + norm_b)
        maybe[group] = (norm_a <= 0) | (residual <= k * limit**2 + slack)
    return maybe
