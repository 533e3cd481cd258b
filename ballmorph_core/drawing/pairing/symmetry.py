"""The smallest turn the keys allow: which way a loop runs when its area cannot say.

A loop's direction is the sign of its area: a loop of key B drawn the other way round is read
backwards before it morphs. A figure eight (one cyclic stroke crossing itself) has two lobes
whose areas cancel: its sign is round-off, and a figure eight read backwards is itself turned by
half a turn. Read the wrong way it fits just as well, and turns 180 degrees more than the
drawing: at the middle in-between it stands upright.

So a loop whose area is small beside its size (``|area| <= UNORIENTED_AREA r^2``, ``r`` the RMS
distance of its samples from their centroid: a circle's is ``pi r^2``, a 30:1 sliver's
``0.2 r^2``, a figure eight's about 0) runs the way whose best cyclic fit costs less, its
residual plus ``DIRECTION_TURN (turn / pi)^2``, the turn measured from the drawing's (as open
strokes are read, see :mod:`.matching`); between readings within ``EQUAL_FIT``, the way it was
drawn. Round-off never decides: a tie is a tie.
"""

import numpy as np

from ... import tolerances as tol

__all__ = ["UNORIENTED_AREA", "loop_reversals", "unoriented"]

#: A loop whose area is at most this times its squared size (RMS radius) has no direction its
#: area can tell (lobes that cancel: a figure eight).
UNORIENTED_AREA = 0.1


def unoriented(area, size):
    """Which loops' areas (shape (K,)) cannot tell their direction, given their sizes (RMS
    radii, shape (K,)): shape (K,)."""
    return np.abs(area) <= UNORIENTED_AREA * np.square(size)


def loop_reversals(a, b, turn, direction_turn, equal_fit):
    """Whether each loop of B should be read backwards to morph into its loop of A.

    Parameters
    ----------
    a, b : ndarray of complex, shape (K, m)
        The pairs' loop samples, each centred on its centroid.
    turn : float
        The drawing's turn (radians).
    direction_turn : float
        The weight of a turn away from the drawing's (per half turn, squared).
    equal_fit : float
        Readings whose costs differ by less are equal: the drawn one is kept.

    Returns
    -------
    ndarray of bool, shape (K,)
    """
    if not len(a):
        return np.zeros(0, bool)
    fa = np.conj(np.fft.fft(a, axis=1))
    norm_a = np.sum(np.abs(a) ** 2, axis=1)
    costs = []
    for read in (b, np.concatenate([b[:, :1], b[:, :0:-1]], axis=1)):
        corr = np.fft.ifft(fa * np.fft.fft(read, axis=1), axis=1)
        norms = np.maximum(norm_a * np.sum(np.abs(read) ** 2, axis=1), tol.TINY)
        e = np.clip(1.0 - np.abs(corr) ** 2 / norms[:, None], 0.0, 1.0)
        away = np.angle(corr * np.exp(-1j * turn)) / np.pi
        costs.append(np.min(e + direction_turn * away**2, axis=1))
    return costs[1] < costs[0] - equal_fit
