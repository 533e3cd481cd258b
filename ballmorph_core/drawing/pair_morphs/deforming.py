"""Pairs that change shape where they lie (issue 38): the route of the tangent-aligned morph.

Loops that overlap and whose registration explains little of their difference
(:mod:`.carrier_choice`: no carrier) changed their *shape* in place: a glyph's outline grown
bolder, a blob bulging out. Their outlines cross where one grows past the other, and those
crossings come from the change of shape, not from a motion: cutting the pair into lenses there
pins the crossing points, which a designer's in-between moves (by a median of 25/1000 em on
Inter's outlines). These pairs take the tangent-aligned correspondence instead
(:mod:`~ballmorph_core.morphs.tangent_aligned`): every part of P goes to the part of Q that runs
the same way, straight, and material slides through the crossings. A pair that moved (its
carrier explains it) keeps the ball route: its crossings come from the motion. Open strokes
whose registration explains as little take this route too, between their common parts (their
ends settled as any open pair's, :mod:`.ends`): straight paths between matched points never
leave the keys' convex hull (a C-shaped arc against an S ended to ended crossed itself in 4 of
9 in-betweens, its common parts in none).

Nested loops get no carrier (the ball-morph follows them as drawn, the paper's configuration 1).
Those a similarity registration explains (a glyph's counter shrinking as its strokes grow
bolder: the fit leaves under ``SCREEN`` of their distance, 0-19 % on the glyphs measured) are
the same shape changing in place too, and take this route: the ball-morph of a counter shrinking
inside the Thin one left 10-16/1000 em against the designer's 2-3 (Dosis, League Spartan 'e',
'B', 'R'). Dissimilar nested loops (a notched disk inside a pear: 49 %) keep the ball-morph.
"""

import numpy as np

from ... import tolerances as tol
from ...geometry.intersections import simple_curves
from ...morphs.tangent_aligned import METHOD, tangent_morphs
from ...morphs.tangent_dp import tangent_warps
from .carrier_choice import SCREEN
from .registration import Fits, Motions, fit_pairs, identity_residual, moved_curves, stretch_fits
from .registration import motions as registered_motions

__all__ = [
    "DEFORMING_NOTE",
    "SQUASHED",
    "LARGE_TURN",
    "deforms",
    "similar_in_place",
    "squashes_in_place",
    "tangent_morphs",
]

#: The ``shape_change`` of a loop squashed in place instead of turned (:func:`squashes_in_place`).
SQUASHED = np.inf

#: A carrier turning a loop by more than this (radians) is weighed against squashing it in place.
LARGE_TURN = np.radians(30.0)

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
    return ~np.isnan(shape_change) & ~motions.moving


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


def squashes_in_place(P, Q, motions, scale, drawing=None, rides=None):
    """Loops whose carrier turns them a lot where squashing them in place travels less: the
    motion of least travel among those that fit (issue 38).

    A tall dot that becomes a wide one fits a 90-degree turn; squashed in place each point
    travels less, and an animator squashes it. Asked of loops whose carrier turns by more than
    ``LARGE_TURN``. Two squashes are weighed against the turn, the least travel winning: the
    stretch without turn (:func:`~.registration.stretch_fits`, where it explains the pair: its
    residual under ``SCREEN`` of their distance) and the tangent-aligned correspondence (where
    neither loop crosses itself: a rounded rectangle's corners stay corners). A stretch as good
    as exact (residual within ``EQUAL_FIT`` of the pair's size: an ellipse squashed, any loop
    stretched along any axis) is the pair's own deformation, and no correspondence is sought.
    Travels are RMS over P's vertices (and, for the correspondence, Q's and their matches).

    Parameters
    ----------
    P, Q : Ragged
        The pairs' curves, as drawn.
    motions : Motions
        Their carriers.
    scale : ndarray, shape (C,)
    drawing : Similarity, optional
    rides : Rides, optional
        What each pair rides (see :func:`~.registration.motions`).

    Returns
    -------
    stretched : ndarray of int
        Pairs whose carrier becomes the stretch.
    stretch : Motions
        Their carriers.
    squashed : ndarray of int
        Pairs left without a carrier (the tangent-aligned route).
    warps : dict
        Pair -> its TangentWarp (of the curves as drawn: the route's own, computed once).
    """
    rows = np.flatnonzero(P.closed & motions.moving & (np.abs(motions.theta) > LARGE_TURN))
    none = np.zeros(0, dtype=np.int64)
    if not len(rows):
        return none, Motions.identity(0, motions.kind), none, {}
    Pr, Qr = P.take(rows), Q.take(rows)
    turned = _carried_travel(Pr, motions.A[rows], motions.b[rows])
    fits = stretch_fits(Pr, Qr)
    # The stretch is a carrier like the turn, weighed where it explains the pair: a loop
    # crossing itself too (its moments are its lobes' signed areas'; the residual judges them).
    explains = fits.residual <= SCREEN * identity_residual(Pr, Qr)
    stretched = np.where(explains, _carried_travel(Pr, fits.A, fits.b), np.inf)
    # A stretch as good as exact is the pair's own deformation: no correspondence is sought.
    exact = explains & (fits.residual <= tol.EQUAL_FIT * scale[rows])
    matched = np.full(len(rows), np.inf)
    ask = np.flatnonzero(~exact)
    if len(ask):
        # A loop crossing itself (a figure eight) keeps its carrier and the fallback that says so.
        curves = [c for k in ask for c in (Pr.curve(k), Qr.curve(k))]
        ask = ask[simple_curves(curves, np.ones(len(curves), dtype=bool)).reshape(-1, 2).all(axis=1)]
    warps = {}
    if len(ask):
        matched[ask], found = _matched_travel(Pr.take(ask), Qr.take(ask))
        warps = dict(zip(ask, found))
    # The least travel of the three: turned by the registration, stretched, matched part to part.
    by_stretch = (stretched < turned) & (stretched <= matched)
    by_tangent = ~by_stretch & (matched < turned)
    warps = {int(rows[k]): w for k, w in warps.items() if by_tangent[k]}
    keep = np.flatnonzero(by_stretch)
    stretch = Motions.identity(0, motions.kind)
    if len(keep):
        sub = Fits(fits.A[keep], fits.b[keep], fits.residual[keep])
        moving = np.ones(len(keep), dtype=bool)
        ridden = None if rides is None else rides.take(rows[keep])
        stretch = registered_motions(Pr.take(keep), sub, motions.kind, scale[rows[keep]], moving, drawing, rides=ridden)
    return rows[keep], stretch, rows[by_tangent], warps


def _carried_travel(P, A, b):
    """RMS distance each vertex of the curves P travels under ``z -> A z + b``, shape (C,)."""
    moved = moved_curves(P, A, b).pts
    return np.sqrt(np.bincount(P.owner, np.sum(np.square(moved - P.pts), axis=1)) / np.maximum(P.n, 1))


def _matched_travel(P, Q):
    """RMS travel of the tangent-aligned correspondence of loops P and Q, shape (C,), and their
    warps (list of TangentWarp)."""
    warps = tangent_warps([P.curve(k) for k in range(len(P))], [Q.curve(k) for k in range(len(P))], P.closed)
    out = np.zeros(len(P))
    for k, warp in enumerate(warps):
        vp = P.s[P.offsets[k] : P.offsets[k + 1]] / max(float(P.length[k]), tol.TINY)
        vq = Q.s[Q.offsets[k] : Q.offsets[k + 1]] / max(float(Q.length[k]), tol.TINY)
        u_p, u_q = warp.through(vp, vq)
        at = np.full(len(u_p), k, dtype=np.int64)
        p, q = P.point_at(at, u_p * P.length[k]), Q.point_at(at, u_q * Q.length[k])
        out[k] = np.sqrt(np.mean(np.sum(np.square(q - p), axis=1)))
    return out, warps
