"""Ball-morphs (paper section 4): the ball-map correspondence with one of the five paths."""

import numpy as np

from ..ballmap import ball_map
from ..trajectories import BallPaths
from .base import PathMorph, register

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


def _builder(kind):
    def build(P, Q, closed, spacing, sampling, check=True):
        corr = ball_map(P, Q, closed=closed, spacing=spacing, sampling=sampling, check=check)
        p, m, q = (_in_input_order(corr, v) for v in (corr.p, corr.centers, corr.q))
        return BallMorph(f"{kind}-ball", closed, BallPaths(p, m, q, kind), corr)

    return build


for _kind in ("circular", "linear", "parabolic", "hat", "tangent"):
    register(f"{_kind}-ball")(_builder(_kind))
