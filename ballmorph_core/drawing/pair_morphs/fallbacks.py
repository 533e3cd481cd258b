"""The fallback step: what a stroke pair gets when the morph it asked for cannot follow it.

A chain (lens or whole pair) that is not b-compatible gets the composite ball-morph (paper
section 7), unless its in-betweens stray far outside the chains; whatever still fails, and
every pair whose curves lie over each other but cannot be cut into lenses (crossing in another
order, or crossing themselves), gets aligned interpolation (:mod:`~..morphs.aligned`: matched
points kept close, straight paths); the other pairs no ball-morph can follow get linear
interpolation (uniform arc-length correspondence, straight paths). Neither ever fails on two
curves. A stroke with fewer than two distinct points moves straight, point by point. Every
fallback says why, for the animator's report.
"""

from typing import NamedTuple

import numpy as np

from ... import tolerances as tol
from ...errors import BallMorphError, IncompatibleCurvesError
from ...geometry.intersections import is_simple, simple_curves
from ...geometry.polyline import as_curve
from ...morphs import make_morph
from ...morphs.aligned import METHOD as ALIGNED_METHOD
from ...morphs.aligned import aligned_morphs
from ...morphs.base import PathMorph
from ...morphs.composite import build_composites
from ...morphs.linear import sample_counts, uniform_correspondences
from ...morphs.paths import LinearPaths

__all__ = [
    "FALLBACK_METHOD",
    "ALIGNED_METHOD",
    "STRAIGHT_POINT_MOTION",
    "BALL_METHODS",
    "short",
    "FailingChain",
    "chain_fallbacks",
    "linear_fallback",
    "aligned_fallbacks",
    "arc_length_morphs",
    "unsplittable",
    "comparison_morph",
    "point_motion",
]

#: The last resort: uniform arc-length correspondence and straight paths never fail.
FALLBACK_METHOD = "linear-interpolation"

#: The name of the point-by-point motion of strokes too short (or too broken) to morph.
STRAIGHT_POINT_MOTION = "straight point motion"

#: A composite ball-morph whose in-betweens (at ``CHECK_TIMES``) leave the box of its two
#: chains by more than this fraction of the box's diagonal is not followed: a ball-morph's paths
#: stay inside the gap between the chains, and one this far out is relative blending gone
#: astray (a lens pairing a sliver of one outline with the whole of the other), not a morph.
#: Nor is one whose in-betweens cross themselves where neither chain does (a bridging disk at
#: a lens end where the chains meet tangentially).
STRAY_REACH = 0.25

#: The times a composite ball-morph's in-betweens are checked at.
CHECK_TIMES = (0.125, 0.25, 0.5, 0.75, 0.875)

#: Methods that need the paper's configurations and so take the ball route (carrier, splitting).
BALL_METHODS = ("circular-ball", "linear-ball", "parabolic-ball", "hat-ball", "tangent-ball")


def short(text, limit=160):
    """``text`` cut to ``limit`` characters for a report."""
    text = str(text)
    return text if len(text) <= limit else text[: limit - 3] + "..."


class FailingChain(NamedTuple):
    """A chain the ball-map cannot follow: its curves (``closed``: loops), the sample spacing,
    which chain it is for the note ('lens 2/4', 'loops', 'stroke') and why the ball-morph did
    not apply."""

    P: np.ndarray
    Q: np.ndarray
    closed: bool
    spacing: float
    where: str
    reason: str


def chain_fallbacks(chains, kind):
    """The composite ball-morph of each chain that is not b-compatible, else aligned
    interpolation: their composite ball-morphs built together
    (:func:`composite_morphs`), and those not followed aligned together.

    Parameters
    ----------
    chains : list of FailingChain
    kind : str

    Returns
    -------
    list of (Morph, str)
        Each chain's morph and note.
    """
    built = composite_morphs([(ch.P, ch.Q, ch.closed, ch.spacing) for ch in chains], kind)
    whys = _not_followed(built, chains)
    out, failed = [None] * len(chains), []
    for k, (chain, morph, why) in enumerate(zip(chains, built, whys)):
        if why is None:
            out[k] = morph, f"{chain.where}: not b-compatible, composite ball-morph used ({short(chain.reason)})"
        else:
            failed.append((k, why))
    curves = [(chains[k].P, chains[k].Q, chains[k].closed) for k, _ in failed]
    for (k, why), morph in zip(failed, aligned_morphs(curves, [chains[k].spacing for k, _ in failed])):
        out[k] = morph, f"{chains[k].where}: {ALIGNED_METHOD} used ({short(why)})"
    return out


def composite_morphs(pairs, kind):
    """``make_morph(P, Q, 'composite-ball', closed=closed, spacing=spacing, kind=kind)`` of
    every pair ``(P, Q, closed, spacing)``, built together: list of Morph or the BallMorphError
    each raises (see :func:`~..morphs.composite.build_composites`)."""
    out, valid, where = [None] * len(pairs), [], []
    for k, (P, Q, closed, spacing) in enumerate(pairs):
        try:
            valid.append((as_curve(P, "P", closed), as_curve(Q, "Q", closed), closed, spacing, "symmetric"))
        except BallMorphError as exc:
            out[k] = exc
            continue
        where.append(k)
    for k, morph in zip(where, build_composites(valid, kind)):
        out[k] = morph
    return out


def _not_followed(built, chains):
    """Why each chain's composite ball-morph is not followed (str), or None: it failed (its
    error), its in-betweens (at ``CHECK_TIMES``) stray outside the chains' box, or they cross
    themselves where neither chain does (every curve's self-crossings searched in one batch)."""
    whys, asked = [None] * len(built), []
    for k, ((P, Q, closed, *_), morph) in enumerate(zip(chains, built)):  # FailingChain unpacked
        if isinstance(morph, BallMorphError):
            whys[k] = str(morph)
            continue
        try:
            frames = morph.frames(CHECK_TIMES)
        except BallMorphError as exc:
            whys[k] = str(exc)
            continue
        out = _outside(frames, P, Q)
        if out > STRAY_REACH:
            whys[k] = f"composite ball-morph: its in-betweens leave the chains' box by {out:.2f} of its diagonal"
        else:
            asked.append((k, [P, Q, *frames], closed))
    curves = [c for _, group, _ in asked for c in group]
    simple = iter(simple_curves(curves, np.repeat([closed for _, _, closed in asked], [len(g) for _, g, _ in asked])))
    for k, group, _ in asked:
        p, q, *frames = (next(simple) for _ in group)
        if p and q and not all(frames):
            whys[k] = "composite ball-morph: its in-betweens cross themselves where neither chain does"
    return whys


def _outside(frames, P, Q):
    """How far in-betweens (shape (T, K, 2)) reach outside the box of P and Q, in diagonals of
    that box (0 when they stay inside)."""
    ends = np.concatenate([P, Q])
    lo, hi = ends.min(axis=0), ends.max(axis=0)
    frames = np.asarray(frames).reshape(-1, 2)
    beyond = np.maximum(np.maximum(lo - frames, frames - hi), 0.0).max(initial=0.0)
    return float(beyond / max(float(np.hypot(*(hi - lo))), tol.TINY))


def aligned_fallbacks(pairs, spacing, reasons):
    """Aligned interpolation for pairs whose curves lie over each other but that no ball-morph
    can follow (see :mod:`~ballmorph_core.morphs.aligned`), aligned together.

    Parameters
    ----------
    pairs : list of (ndarray, ndarray, bool)
        Each pair's P (N, 2), Q (M, 2) and whether they are loops.
    spacing : array_like, shape (G,)
    reasons : list of str
        Why each pair takes it.

    Returns
    -------
    morphs : list of PathMorph
    notes : list of str
    """
    return aligned_morphs(pairs, list(spacing)), [f"{reason}: {ALIGNED_METHOD} used" for reason in reasons]


def linear_fallback(P, Q, closed, spacing, reason):
    """Linear interpolation for a pair no ball-morph can follow: ``(morph, note)``."""
    return make_morph(P, Q, FALLBACK_METHOD, closed=closed, spacing=spacing), f"{reason}: {FALLBACK_METHOD} used"


def arc_length_morphs(R, Q, spacing):
    """Registered curves that nearly coincide, matched by arc length with straight paths
    between them (the carrier does the motion): one ``'arc-length'`` PathMorph per pair.

    Loops are aligned by the cyclic shift that moves their samples least, in the direction they
    have (the stroke matching made it the same). Every pair is resampled and aligned at once.

    Parameters
    ----------
    R, Q : Ragged
        Curve ``c`` of each is a pair (the same closed flags).
    spacing : ndarray, shape (C,)

    Returns
    -------
    list of PathMorph
    """
    closed = R.closed
    found = uniform_correspondences(R, Q, sample_counts(R, Q, spacing), match_orientation=True)
    morphs = []
    for c, (lo, hi) in enumerate(zip(found.offsets[:-1], found.offsets[1:])):
        paths = LinearPaths(found.p[lo:hi], found.q[lo:hi])
        morphs.append(PathMorph("arc-length", bool(closed[c]), paths, found.u_p[lo:hi], found.u_q[lo:hi]))
    return morphs


def unsplittable(P, Q, closed, why, simple=None):
    """Why a pair cannot be cut into lenses, for the note: a stroke crossing itself, else ``why``
    (``simple``: whether P and Q are simple, when the caller asked :func:`simple_curves` for
    many pairs at once)."""
    simple = (is_simple(P, closed), is_simple(Q, closed)) if simple is None else simple
    for which, ok in zip(("first", "second"), simple):
        if not ok:
            return f"the {which} key's stroke crosses itself, which no ball-morph can follow"
    return why


def comparison_morph(P, Q, closed, method, spacing):
    """One of the paper's comparison morphs, else linear interpolation: ``(morph, notes)``.

    A morph that does not apply to the pair (:class:`IncompatibleCurvesError`) or fails is
    replaced by linear interpolation, and the note says why.
    """
    try:
        return make_morph(P, Q, method, closed=closed, spacing=spacing), []
    except IncompatibleCurvesError as exc:
        note = f"{method} does not apply ({short(exc)}): {FALLBACK_METHOD} used"
    except Exception as exc:  # a bug in one morph must not stop the other pairs
        note = f"{method} failed ({type(exc).__name__}: {exc})"
    return make_morph(P, Q, FALLBACK_METHOD, closed=closed, spacing=spacing), [note]


def point_motion(xy_a, u_a, xy_b, u_b):
    """Straight point motion between strokes with fewer than two distinct points (PathMorph).

    Parameters
    ----------
    xy_a, xy_b : ndarray, shape (N, 2), (M, 2)
        The two strokes (one point or more).
    u_a, u_b : ndarray, shape (N,), (M,)
        Their points' arc-length fractions.
    """
    k = max(len(xy_a), len(xy_b))
    u = np.linspace(0.0, 1.0, k)

    def along(xy, frac):
        if len(xy) == 1:
            return np.repeat(xy, k, axis=0)
        return np.column_stack([np.interp(u, frac, xy[:, c]) for c in range(2)])

    return PathMorph(STRAIGHT_POINT_MOTION, False, LinearPaths(along(xy_a, u_a), along(xy_b, u_b)), u, u.copy())
