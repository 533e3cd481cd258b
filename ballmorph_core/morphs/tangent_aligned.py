"""Tangent-aligned interpolation: straight paths between points the tangent warp matches.

The route of loops that change shape where they lie (issue 38): the correspondence of
:mod:`.tangent_dp` (each part of P goes to the part of Q running the same way), then every point
moves straight to its match. Material slides through the points where the two outlines cross
(nothing is pinned there), as it does between a designer's weights.
"""

import numpy as np

from .. import tolerances as tol
from ..geometry.ragged import Ragged
from .base import PathMorph
from .paths import LinearPaths
from .tangent_dp import tangent_warps

__all__ = ["METHOD", "tangent_morphs", "tangent_morph"]

#: The morph's name in reports.
METHOD = "tangent-aligned"


def _vertex_fractions(rg, c):
    """Arc-length fractions of curve ``c``'s vertices, shape (n,) (a loop's end left out)."""
    s = rg.s[rg.offsets[c] : rg.offsets[c + 1]]
    return s / max(float(rg.length[c]), tol.TINY)


def _morph(P, Q, closed, warp):
    """The PathMorph of one pair from its TangentWarp: every vertex of both curves with its
    match on the other (the keys' corners stay corners). The warp is not smoothed: averaging
    its steps moved the matches of corners off each other (Dosis 's': 4.6 against 3.4 /1000 em)."""
    rg = Ragged.from_list([P, Q], [closed, closed])
    u_p, u_q = warp.through(_vertex_fractions(rg, 0), _vertex_fractions(rg, 1))
    if closed:
        u_p, u_q = u_p[:-1], u_q[:-1]  # the closing knot repeats the first
    p = rg.point_at(np.zeros(len(u_p), dtype=np.int64), u_p * rg.length[0])
    q = rg.point_at(np.ones(len(u_q), dtype=np.int64), u_q * rg.length[1])
    return PathMorph(METHOD, closed, LinearPaths(p, q), u_p, u_q)


def tangent_morphs(pairs, warps=None):
    """The tangent-aligned interpolations of several curve pairs, warped together.

    Parameters
    ----------
    pairs : list of (ndarray, ndarray, bool)
        Validated curves P (N, 2) and Q (M, 2) (Q running the way P does) and whether they
        are loops.
    warps : list of TangentWarp or None, optional
        Warps already made of some pairs' very curves (None: made here).

    Returns
    -------
    list of PathMorph
        Method :data:`METHOD`; their samples are the curves' own vertices and their matches.
    """
    warps = list(warps) if warps is not None else [None] * len(pairs)
    missing = [g for g, w in enumerate(warps) if w is None]
    made = tangent_warps([pairs[g][0] for g in missing], [pairs[g][1] for g in missing], [pairs[g][2] for g in missing])
    for g, w in zip(missing, made):
        warps[g] = w
    return [_morph(P, Q, closed, w) for (P, Q, closed), w in zip(pairs, warps)]


def tangent_morph(P, Q, closed):
    """:func:`tangent_morphs` of one pair (PathMorph)."""
    return tangent_morphs([(np.asarray(P, float), np.asarray(Q, float), bool(closed))])[0]
