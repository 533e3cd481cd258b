"""Ball-morphs (paper section 4): the ball-map correspondence with one of the five paths."""

import numpy as np

from ..ballmap.correspondence import ball_map
from ..geometry.polyline import curve_length
from .base import PathMorph, register
from .paths import BallPaths

__all__ = ["BallMorph"]


class BallMorph(PathMorph):
    """A ball-morph: each ball-map contact pair travels along its path inside its maximal disk.

    Samples are ordered along P as it was given (a loop given counter-clockwise is not turned
    clockwise in the output), so a stroke keeps its drawing direction.

    Attributes
    ----------
    correspondence : Correspondence
        The ball-map, in the oriented frame (loops clockwise).
    """


def _in_input_order(corr, values):
    if not corr.setup.reversed_p:
        return values
    if corr.closed:
        return np.concatenate([values[:1], values[:0:-1]])
    return values[::-1]


def input_fractions(s, dense, closed, reversed_):
    """Arc-length fractions along a curve as given, from positions on its oriented dense copy.

    Parameters
    ----------
    s : ndarray, shape (K,)
        Arc length on the oriented dense polyline (unwrapped for loops).
    dense : ndarray, shape (M, 2)
    closed, reversed_ : bool

    Returns
    -------
    ndarray, shape (K,)
        In [0, 1] (loops: [0, 1), from the first vertex; oriented loops keep it, see
        :func:`~ballmorph_core.curves.orient_clockwise`).
    """
    u = s / curve_length(dense, closed)
    if closed:
        u = np.mod(-u if reversed_ else u, 1.0)
    elif reversed_:
        u = 1.0 - u
    return np.clip(u, 0.0, 1.0)


def _builder(kind):
    def build(P, Q, closed, spacing, sampling, check=True):
        corr = ball_map(P, Q, closed=closed, spacing=spacing, sampling=sampling, check=check)
        p, m, q = (_in_input_order(corr, v) for v in (corr.p, corr.centers, corr.q))
        u_p = input_fractions(corr.s_p, corr.dense_p, closed, corr.setup.reversed_p)
        u_q = input_fractions(corr.s_q, corr.dense_q, closed, corr.setup.reversed_q)
        u_p, u_q = _in_input_order(corr, u_p), _in_input_order(corr, u_q)
        return BallMorph(f"{kind}-ball", closed, BallPaths(p, m, q, kind), u_p, u_q, corr)

    return build


for _kind in ("circular", "linear", "parabolic", "hat", "tangent"):
    register(f"{_kind}-ball")(_builder(_kind))
