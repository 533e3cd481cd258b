"""A stroke pair's curves as the pair pipeline receives them (:class:`PairCurves`), and its
first step, *prepare*: each pair's curves validated, or left to move point by point."""

from dataclasses import dataclass, field, replace

import numpy as np

from ...errors import InvalidCurveError
from ...geometry.polyline import already_clean, as_curve, curve_length, resolve_spacing

__all__ = ["PairCurves", "Prepared", "prepare", "prepare_pairs"]


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
    """Step 1 for one pair: its curves validated.

    ``clean``: both curves are known to be valid as they are (:func:`prepare_pairs`): copied.

    Returns
    -------
    prepared : PairCurves
        ``pair`` with its curves ``P``, ``Q`` (None when it can only move point by point), its
        ``closed`` flag and its notes set (``pair`` itself is left as it is).
    ready : bool
        False when it can only move point by point.
    """
    closed = pair.closed_a and pair.closed_b
    notes = list(pair.notes)
    if pair.closed_a != pair.closed_b:
        notes.append("one key's stroke is cyclic and the other's is not: morphed as open strokes")
    try:
        if clean:
            P, Q = (np.array(xy, dtype=np.float64, copy=True) for xy in (pair.xy_a, pair.xy_b))
        else:
            P, Q = as_curve(pair.xy_a, "P", closed), as_curve(pair.xy_b, "Q", closed)
    except InvalidCurveError as exc:
        notes.append(f"too few distinct points ({exc})")
        return replace(pair, P=None, Q=None, closed=closed, notes=notes), False
    if spacing is not None:
        try:
            resolve_spacing(P, Q, closed, spacing)
        except InvalidCurveError as exc:
            notes.append(f"{method} failed ({exc})")
            return replace(pair, P=None, Q=None, closed=closed, notes=notes), False
    return replace(pair, P=P, Q=Q, closed=closed, notes=notes), True


@dataclass(frozen=True)
class Prepared:
    """What step 1 made of every pair.

    Attributes
    ----------
    pairs : list of PairCurves
        Every pair, prepared (see :func:`prepare`).
    ready : list of int
        The pairs whose curves are valid (the others move point by point).
    """

    pairs: list
    ready: list


def prepare_pairs(pairs, method, spacing):
    """Step 1 for every pair (a Prepared; ``pairs`` are left as they are).

    Curves a drawing's batch shows need no cleaning skip the per-curve validation.
    """
    closed = [p.closed_a and p.closed_b for p in pairs]
    clean = already_clean([p.xy_a for p in pairs], closed) & already_clean([p.xy_b for p in pairs], closed)
    prepared = [prepare(pair, method, spacing, bool(clean[c])) for c, pair in enumerate(pairs)]
    return Prepared([pair for pair, _ in prepared], [c for c, (_, ready) in enumerate(prepared) if ready])
