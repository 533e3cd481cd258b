"""Ball-morphs (paper section 4): the ball-map correspondence with one of the five paths."""

import numpy as np

from ..ballmap.correspondence import ball_map, ball_maps
from ..ballmap.topology import orient_pairs
from ..errors import BallMorphError, IncompatibleCurvesError
from ..geometry.polyline import as_curve, curve_length, resolve_spacing
from ..options import SAMPLINGS, check_option
from .base import PathMorph, register
from .paths import BallPaths

__all__ = ["BallMorph", "ball_morphs"]


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


def _morph(corr, kind):
    """The ball-morph of ``kind`` ('circular', ...) along a correspondence (BallMorph)."""
    closed = corr.closed
    p, m, q = (_in_input_order(corr, v) for v in (corr.p, corr.centers, corr.q))
    u_p = input_fractions(corr.s_p, corr.dense_p, closed, corr.setup.reversed_p)
    u_q = input_fractions(corr.s_q, corr.dense_q, closed, corr.setup.reversed_q)
    u_p, u_q = _in_input_order(corr, u_p), _in_input_order(corr, u_q)
    return BallMorph(f"{kind}-ball", closed, BallPaths(p, m, q, kind), u_p, u_q, corr)


def _builder(kind):
    def build(P, Q, closed, spacing, sampling, check=True):
        return _morph(ball_map(P, Q, closed=closed, spacing=spacing, sampling=sampling, check=check), kind)

    return build


def ball_morphs(pairs, kind, sampling="symmetric", check=True):
    """Ball-morphs of many curve pairs at once: ``make_morph(P, Q, f"{kind}-ball", ...)`` of
    each, with every ball-map in one batch (:func:`~ballmorph_core.ballmap.ball_maps`).

    A composite ball-morph builds dozens of small ones (its extension stages, its central
    morph); one at a time, each pays the ball-map's fixed cost.

    Parameters
    ----------
    pairs : list of (array_like, array_like, bool, float or None)
        Each pair's P (N, 2), Q (M, 2), whether they are loops and its spacing.
    kind : str
        The path ('circular', 'linear', 'parabolic', 'hat', 'tangent').
    sampling : {'symmetric', 'p', 'q'}
    check : bool
        A pair that is not b-compatible gets an IncompatibleCurvesError (the one
        :func:`~ballmorph_core.ballmap.ball_map` raises) instead of its morph.

    Returns
    -------
    list of BallMorph or BallMorphError
        Per pair, its morph or the error its own ``make_morph`` raises (bad curves, another
        configuration, not b-compatible). The batch's length tolerance is its smallest pair's
        (as the pipeline's ball route), a coincidence threshold of 1e-9 of a pair's size.
    """
    sampling = check_option("sampling", sampling, SAMPLINGS)
    out, valid, where = [None] * len(pairs), [], []
    for k, (P, Q, closed, spacing) in enumerate(pairs):
        try:
            # As make_morph and then ball_map validate them (each curve twice: the same values).
            P, Q = (as_curve(as_curve(c, name, closed), name, closed) for c, name in ((P, "P"), (Q, "Q")))
            valid.append((P, Q, closed, resolve_spacing(P, Q, closed, spacing)))
        except BallMorphError as exc:
            out[k] = exc
            continue
        where.append(k)
    setups, spacings, mapped = [], [], []
    for k, (_, _, _, spacing), setup in zip(where, valid, orient_pairs([v[:3] for v in valid])):
        if isinstance(setup, BallMorphError):
            out[k] = setup
        else:
            setups.append(setup)
            spacings.append(spacing)
            mapped.append(k)
    for k, corr in zip(mapped, ball_maps(setups, spacings, sampling, check=False)):
        report = corr.report
        failed = check and report.violations
        out[k] = IncompatibleCurvesError(report.describe(), report) if failed else _morph(corr, kind)
    return out


for _kind in ("circular", "linear", "parabolic", "hat", "tangent"):
    register(f"{_kind}-ball")(_builder(_kind))
