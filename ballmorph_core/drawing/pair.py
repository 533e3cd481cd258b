"""Morph one stroke pair of a real drawing.

Real keys rarely meet the paper's assumptions: strokes do not share endpoints, outlines cross
their previous position, parts are not b-compatible. :func:`morph_pair` composes what the
paper offers for that:

1. a carrier motion (section 1.4, :mod:`~ballmorph_core.registration`) registers P onto Q;
2. if the registered P and Q coincide, the in-between is the carrier alone;
3. nested loops or strokes sharing both endpoints get the requested morph;
4. crossing or overlapping curves (configurations 3 and 4) are split at their intersections
   into lens-shaped stroke pairs (:mod:`~ballmorph_core.splitting`), each morphed on its own,
   overlaps static, intersection points fixed;
5. a pair (or lens) that is not b-compatible gets the composite ball-morph (section 7);
6. whatever still fails gets linear interpolation, and every fallback is reported.
"""

from dataclasses import dataclass, field

import numpy as np

from .. import tolerances as tol
from ..ballmap.topology import classify, shared_endpoints
from ..errors import BallMorphError, IncompatibleCurvesError
from ..geometry.intersections import is_simple
from ..geometry.polyline import (
    coarsen,
    curve_length,
    default_spacing,
    orient_clockwise,
    resolve_spacing,
    reverse,
    scale_of,
    signed_area,
)
from ..morphs import make_morph
from ..morphs.base import Morph, PathMorph
from ..morphs.combine import CarriedMorph, PiecewiseMorph
from ..morphs.paths import LinearPaths
from ..options import check_option
from .registration import CARRIERS, Carrier, centre_of, registration
from .splitting import split_pair

__all__ = ["PairOutcome", "morph_pair", "FALLBACK", "BALL_METHODS"]

#: The last resort: uniform arc-length correspondence and straight paths never fail.
FALLBACK = "linear-interpolation"

#: Methods that need the paper's configurations and so go through carrier + splitting.
BALL_METHODS = ("circular-ball", "linear-ball", "parabolic-ball", "hat-ball", "tangent-ball")


@dataclass
class PairOutcome:
    """A pair's morph and how it was obtained.

    Attributes
    ----------
    morph : Morph
    notes : list of str
        Fallbacks and splits, for the animator's report (empty when the requested morph applied
        directly).
    used : str
        Short summary of the methods used.
    """

    morph: object
    notes: list = field(default_factory=list)
    used: str = ""


def _static(curve, closed):
    u = np.linspace(0.0, 1.0, len(curve), endpoint=not closed)
    if len(curve) > 1:
        seg = np.linalg.norm(np.diff(np.vstack([curve, curve[:1]]) if closed else curve, axis=0), axis=1)
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        u = cum[: len(curve)] / cum[-1] if cum[-1] > 0 else u
    return PathMorph("static", closed, LinearPaths(curve, curve), u, u.copy())


def _fallbacks(P, Q, closed, method, spacing, notes, where, reason=None):
    """The requested morph, else the composite ball-morph (ball methods), else linear."""
    if reason is None:
        try:
            return make_morph(P, Q, method, closed=closed, spacing=spacing)
        except IncompatibleCurvesError as exc:
            reason = str(exc)
    if method in BALL_METHODS and "composite-ball" in _methods():
        try:
            morph = make_morph(P, Q, "composite-ball", closed=closed, spacing=spacing, kind=method[: -len("-ball")])
            notes.append(f"{where}: not b-compatible, composite ball-morph used ({_short(reason)})")
            return morph
        except BallMorphError as exc:
            reason = str(exc)
    notes.append(f"{where}: {FALLBACK} used ({_short(reason)})")
    return make_morph(P, Q, FALLBACK, closed=closed, spacing=spacing)


def _methods():
    from ..morphs import METHODS

    return METHODS


def _short(text, limit=160):
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _shape_morph(P, Q, closed, method, spacing, notes):
    """Morph between (registered) P and Q, splitting or falling back as needed."""
    try:
        return make_morph(P, Q, method, closed=closed, spacing=spacing)
    except IncompatibleCurvesError as exc:
        first_error = str(exc)
    if method not in BALL_METHODS:
        notes.append(f"{method} does not apply ({_short(first_error)}): {FALLBACK} used")
        return make_morph(P, Q, FALLBACK, closed=closed, spacing=spacing)
    # Orient consistently (loops clockwise keeping their first vertex; strokes same start).
    Po, Qo = P, Q
    rev_p = rev_q = False
    if closed:
        rev_p, rev_q = signed_area(P) > 0, signed_area(Q) > 0
        Po, Qo = orient_clockwise(P), orient_clockwise(Q)
    else:
        how = shared_endpoints(P, Q)
        if how == "reversed":
            Qo, rev_q = Q[::-1].copy(), True
        elif how == "none":
            notes.append(f"the strokes do not share endpoints and no carrier is used: {FALLBACK} used")
            return make_morph(P, Q, FALLBACK, closed=closed, spacing=spacing)
    config = classify(Po, Qo, closed)
    if config in ("disjoint-loops", "quasi-disjoint-strokes"):
        return _fallbacks(P, Q, closed, method, spacing, notes, "loops" if closed else "stroke", first_error)
    try:
        pieces = split_pair(Po, Qo, closed, spacing / 2)
    except IncompatibleCurvesError as exc:
        pieces, first_error = [], str(exc)
    if not pieces:
        if not (is_simple(P, closed) and is_simple(Q, closed)):
            which = "the first key's" if not is_simple(P, closed) else "the second key's"
            notes.append(f"{which} stroke crosses itself, which no ball-morph can follow: {FALLBACK} used")
        else:
            notes.append(f"curves are {config!r} and cannot be split into lenses: {FALLBACK} used")
        return make_morph(P, Q, FALLBACK, closed=closed, spacing=spacing)
    morphs = []
    for k, piece in enumerate(pieces):
        if piece.kind == "overlap":
            morphs.append(_static(piece.P, False))
        else:
            morphs.append(_fallbacks(piece.P, piece.Q, False, method, spacing, notes, f"lens {k + 1}/{len(pieces)}"))
    len_p, len_q = curve_length(Po, closed), curve_length(Qo, closed)
    ranges_p = np.array([pc.range_p for pc in pieces]) / len_p
    ranges_q = np.array([pc.range_q for pc in pieces]) / len_q
    notes.append(f"split at {len(pieces)} crossing/overlap pieces ({config})")
    morph = PiecewiseMorph(morphs, ranges_p, ranges_q, closed)
    return _reorder(morph, closed, rev_p, rev_q)


def _reorder(morph, closed, rev_p, rev_q):
    """Express fractions along the curves as given and keep P's drawing direction."""
    if rev_q:
        morph.u_q = np.mod(-morph.u_q, 1.0) if closed else 1.0 - morph.u_q
    if not rev_p:
        return morph
    morph.u_p = np.mod(-morph.u_p, 1.0) if closed else 1.0 - morph.u_p
    return _Reversed(morph, closed)


class _Reversed(Morph):
    """The same morph with its samples in the opposite order (P's drawing direction)."""

    def __init__(self, inner, closed):
        super().__init__(closed)
        self.inner = inner
        self.method = inner.method
        self.u_p = reverse(inner.u_p[:, None], closed)[:, 0]
        self.u_q = reverse(inner.u_q[:, None], closed)[:, 0]

    def _frame(self, t):
        return reverse(self.inner(t), self.closed)

    def __len__(self):
        return len(self.inner)


def morph_pair(P, Q, closed, method="circular-ball", carrier="SIMILARITY", spacing=None):
    """Morph a stroke pair of a real drawing (see the module docstring).

    Parameters
    ----------
    P, Q : ndarray, shape (N, 2), (M, 2)
        Validated curves in the drawing plane, same direction (the caller flips Q if needed).
    closed : bool
    method : str
        Requested morph (a name of :data:`~ballmorph_core.METHODS`).
    carrier : {'SIMILARITY', 'RIGID', 'NONE'}
        Carrier motion; 'NONE' is the paper's pure morph (strokes must then share endpoints).
    spacing : float, optional

    Returns
    -------
    PairOutcome
    """
    check_option("carrier", carrier, CARRIERS)
    notes = []
    scale = scale_of(P, Q)
    if spacing is not None:
        spacing = resolve_spacing(P, Q, closed, spacing)
    # Curves drawn far more densely than they will be sampled are resampled first, each at its
    # own default spacing (the keys may differ in size a lot).
    P = coarsen(P, closed, spacing or default_spacing(P, closed=closed))
    Q = coarsen(Q, closed, spacing or default_spacing(Q, closed=closed))
    sim = None
    if carrier != "NONE" and method in BALL_METHODS:
        sim = registration(P, Q, closed)
        if sim.is_identity(scale, tol.IDENTITY):
            sim = None
    registered = P if sim is None else sim(P)
    # One spacing for the whole pair (its lenses and fallbacks), from the curves that are
    # actually morphed: the registered P has Q's size.
    spacing = resolve_spacing(registered, Q, closed, spacing)
    inner = _shape_morph(registered, Q, closed, method, spacing, notes)
    if sim is None:
        return PairOutcome(inner, notes, inner.method)
    morph = CarriedMorph(inner, Carrier(sim, carrier, centre_of(Q, closed)))
    return PairOutcome(morph, notes, f"{inner.method} on a {carrier.lower()} carrier")
