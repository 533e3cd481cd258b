"""Pairs that change shape where they lie (issue 38): the road of the tangent-aligned morph.

Loops that overlap and whose registration explains little of their difference
(:mod:`.carrier_choice`: no carrier) changed their *shape* in place: a glyph's outline grown
bolder, a blob bulging out. Their outlines cross where one grows past the other, and those
crossings come from the change of shape, not from a motion: cutting the pair into lenses there
pins the crossing points, which a designer's in-between moves (by a median of 25/1000 em on
Inter's outlines). These pairs take the tangent-aligned correspondence instead
(:mod:`~ballmorph_core.morphs.tangent_aligned`): every part of P goes to the part of Q that runs
the same way, straight, and material slides through the crossings. A pair that moved (its
carrier explains it) keeps the ball road: its crossings come from the motion. Open strokes
whose registration explains as little take this road too, between their common parts (their
ends settled as any open pair's, :mod:`.ends`): straight paths between matched points never
leave the keys' convex hull (a C-shaped arc against an S ended to ended crossed itself in 4 of
9 in-betweens, its common parts in none).

Nested loops get no carrier (the ball-morph follows them as drawn, the paper's configuration 1).
Those a similarity registration explains (a glyph's counter shrinking as its strokes grow
bolder: the fit leaves under ``SCREEN`` of their distance, 0-19 % on the glyphs measured) are
the same shape changing in place too, and take this road: the ball-morph of a counter shrinking
inside the Thin one left 10-16/1000 em against the designer's 2-3 (Dosis, League Spartan 'e',
'B', 'R'). Dissimilar nested loops (a notched disk inside a pear: 49 %) keep the ball-morph.
"""

import numpy as np

from ..morphs.tangent_aligned import METHOD, tangent_morphs
from .carrier_choice import SCREEN
from .registration import fit_pairs, identity_residual

__all__ = ["DEFORMING_NOTE", "deforms", "similar_in_place", "tangent_morphs"]

#: What the report says of such a pair.
DEFORMING_NOTE = f"the curves change shape where they lie: {METHOD} correspondence, straight paths"


def deforms(motions, shape_change):
    """The pairs that change shape where they lie, shape (C,) of bool.

    Parameters
    ----------
    motions : Motions
        The pairs' carriers.
    shape_change : ndarray, shape (C,)
        From :func:`~.carrier_choice.carrier_motions`: finite for overlapping loops and open
        strokes whose registration left more than ``SHAPE_CHANGE`` of their distance (NaN
        otherwise).
    """
    return np.isfinite(shape_change) & ~motions.moving


def similar_in_place(P, Q, ask):
    """Of the pairs ``ask`` (nested loops without a carrier), those a similarity registration
    explains (its residual under ``SCREEN`` of their distance), shape (C,) of bool.

    Parameters
    ----------
    P, Q : Ragged
        The pairs' curves, as drawn.
    ask : ndarray of bool, shape (C,)
    """
    out = np.zeros(len(P), dtype=bool)
    rows = np.flatnonzero(ask)
    if len(rows):
        Pr, Qr = P.take(rows), Q.take(rows)
        out[rows] = fit_pairs(Pr, Qr).residual <= SCREEN * identity_residual(Pr, Qr)
    return out
