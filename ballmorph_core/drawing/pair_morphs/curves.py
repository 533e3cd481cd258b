"""A stroke pair's curves as the pair pipeline receives them (:class:`PairCurves`), and its
first step, *prepare*: each pair's curves validated, or left to move point by point."""

from dataclasses import dataclass, field

import numpy as np

from ...errors import InvalidCurveError
from ...geometry.polyline import already_clean, as_curve, curve_length, resolve_spacing

__all__ = ["PairCurves", "prepare", "prepare_pairs"]


@dataclass
class PairCurves:
    """One stroke pair as the pipeline receives it, and what *prepare* made of it.

    Attributes
    ----------
    xy_a, xy_b : ndarray, shape (N, 2), (M, 2)
        The strokes' points (the second running the same way as the first).
    u_a, u_b : ndarray, shape (N,), (M,)
        Their points' arc-length fractions.
    closed_a, closed_b : bool
    P, Q : ndarray or None
        Validated curves (None: too few distinct points).
    closed : bool
        Whether the pair is morphed as loops.
    notes : list of str
    """

    xy_a: np.ndarray
    u_a: np.ndarray
    closed_a: bool
    xy_b: np.ndarray
    u_b: np.ndarray
    closed_b: bool
    P: np.ndarray = None
    Q: np.ndarray = None
    closed: bool = False
    notes: list = field(default_factory=list)
    #: Set for the pieces of a pair cut at its hints (:mod:`.hints`): the pair's own carrier
    #: (Motions of one pair), shared by its pieces so they stay joined, and ends that are the
    #: hinted points (moved, never trimmed).
    motion: object = None
    #: Set for the pairs of a group that moves together (:mod:`..pairing.groups`): the group's
    #: GroupMotion, which a stroke without an orientation of its own rides.
    group: object = None

    @property
    def lengths(self):
        """Lengths of P and Q, shape (2,)."""
        return np.array([curve_length(self.P, self.closed), curve_length(self.Q, self.closed)])


def prepare(pair, method, spacing, clean=False):
    """Step 1: validate a pair's curves (in place); False when it can only move point by point.

    ``clean``: both curves are known to be valid as they are (:func:`prepare_pairs`): copied.
    """
    pair.closed = pair.closed_a and pair.closed_b
    if pair.closed_a != pair.closed_b:
        pair.notes.append("one key's stroke is cyclic and the other's is not: morphed as open strokes")
    try:
        if clean:
            pair.P, pair.Q = (np.array(xy, dtype=np.float64, copy=True) for xy in (pair.xy_a, pair.xy_b))
        else:
            pair.P, pair.Q = as_curve(pair.xy_a, "P", pair.closed), as_curve(pair.xy_b, "Q", pair.closed)
    except InvalidCurveError as exc:
        pair.notes.append(f"too few distinct points ({exc})")
        pair.P = pair.Q = None
        return False
    if spacing is not None:
        try:
            resolve_spacing(pair.P, pair.Q, pair.closed, spacing)
        except InvalidCurveError as exc:
            pair.notes.append(f"{method} failed ({exc})")
            pair.P = pair.Q = None
            return False
    return True


def prepare_pairs(pairs, method, spacing):
    """Step 1 for every pair: the pairs that are ready (list of int).

    Curves a drawing's batch shows need no cleaning skip the per-curve validation.
    """
    closed = [p.closed_a and p.closed_b for p in pairs]
    clean = already_clean([p.xy_a for p in pairs], closed) & already_clean([p.xy_b for p in pairs], closed)
    return [c for c, pair in enumerate(pairs) if prepare(pair, method, spacing, bool(clean[c]))]
