"""What a stroke without an orientation of its own rides (issue 39): a circle or a dot fits any
turn, so it takes the turn of the group it lies in (:mod:`..pairing.groups`: a valve on a
wheel), else the drawing's where the drawing turns and some stroke of it shows the turn.
:func:`.registration.motions` turns such pairs' carriers as they ride."""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...geometry.orientation import orientation_free
from ...geometry.ragged import Ragged

__all__ = ["Rides", "turning"]


def turning(drawing):
    """Whether the drawing's motion (a Similarity or None) turns: by more than ``tol.TURN_AGREE``
    (less does not count as turning), at a scale within ``1 / MAX_STRETCH .. MAX_STRETCH`` (tolerances)
    (beyond, the matching's fit is degenerate: its centroids coincide, its turn is noise)."""
    return (
        drawing is not None
        and abs(drawing.turn) > tol.TURN_AGREE
        and 1 / tol.MAX_STRETCH <= drawing.scale <= tol.MAX_STRETCH
    )


@dataclass
class Rides:
    """What the pairs of a batch ride on: the motion a pair with no orientation of its own (a
    circle, a dot) takes instead of its own fit's turn, and the group a pair belongs to (see
    :mod:`..pairing.groups`).

    Attributes
    ----------
    a : ndarray of complex, shape (C,)
        The turn and scale a rider takes (``z -> a z + b``, its centroid onto its partner's):
        its group's, else the drawing's where the drawing turns (:func:`turning`) and some
        stroke of it has an orientation (shows the turn); NaN where the pair keeps its own fit.
    group : ndarray of complex, shape (C,)
        The turn and scale of the group the pair belongs to (NaN: none).
    pivot : ndarray, shape (C, 2)
        The group's pivot in key A: pairs turning with their group turn about it (NaN: none).
    witnessed : bool
        Whether some stroke of the drawing has an orientation of its own (shows its turn).
    """

    a: np.ndarray
    group: np.ndarray
    pivot: np.ndarray
    witnessed: bool = True

    @classmethod
    def none(cls, n):
        return cls(np.full(n, np.nan, complex), np.full(n, np.nan, complex), np.full((n, 2), np.nan))

    @classmethod
    def of_drawing(cls, P, drawing):
        """The loops of ``P`` (Ragged) with no orientation of their own riding the drawing's
        turn, where it turns (no group; nothing checks that some stroke shows the turn)."""
        rides = cls.none(len(P))
        if turning(drawing) and len(P):
            rides.a[orientation_free(P)] = drawing.a
        return rides

    @classmethod
    def of_pairs(cls, pairs, ready, dots, drawing):
        """Every pair's ride (Rides over ``pairs``, a list of PairCurves): the ready loops with
        no orientation of their own (``orientation_free``, asked once) and the ``dots``
        ride their group's motion (``PairCurves.group``) where it turns, else the drawing's
        where it turns and some ready stroke is open or oriented: circles and dots alone fit
        any turn (two dots fit a similarity exactly), so nothing shows the drawing turning."""
        rides = cls.none(len(pairs))
        loops = [c for c in ready if pairs[c].closed]
        riders = list(dots)
        witnessed = len(loops) < len(ready)
        if loops:
            free = orientation_free(Ragged.from_list([pairs[c].P for c in loops], np.ones(len(loops), bool)))
            riders += [c for c, f in zip(loops, free) if f]
            witnessed |= not free.all()
        for c in riders:
            group = pairs[c].group
            if group is not None:
                if abs(group.motion.turn) > tol.TURN_AGREE:
                    rides.a[c] = _on_arc(pairs[c], group)
            elif witnessed and turning(drawing):
                rides.a[c] = drawing.a
        for c, pair in enumerate(pairs):
            if pair.group is not None:
                rides.group[c], rides.pivot[c] = pair.group.motion.a, pair.group.pivot
        rides.witnessed = bool(witnessed)
        return rides

    def take(self, rows):
        """The rides of some pairs (Rides)."""
        return Rides(self.a[rows], self.group[rows], self.pivot[rows], self.witnessed)


def _on_arc(pair, group):
    """The turn and scale a rider takes from its group (GroupMotion): the group's, its turn made
    the rider's own about the group's pivot where the two agree within ``tol.TURN_AGREE`` (a valve
    drawn a little off where the wheel took it still keeps its distance from the hub)."""
    curves = (pair.xy_a, pair.xy_b) if pair.P is None else (pair.P, pair.Q)
    ca, cb = (Ragged.from_list([xy], [pair.P is not None and pair.closed]).centroids()[0] for xy in curves)
    pivot = complex(*group.pivot)
    za, zb = complex(*ca) - pivot, complex(*cb) - (group.motion.a * pivot + group.motion.b)
    if abs(za) <= tol.ROUNDOFF * (abs(pivot) + 1.0) or abs(zb) <= 0.0:
        return group.motion.a
    off = np.angle(zb / za / np.exp(1j * group.motion.turn))
    if abs(off) > tol.TURN_AGREE:
        return group.motion.a
    return group.motion.scale * np.exp(1j * (group.motion.turn + off))
