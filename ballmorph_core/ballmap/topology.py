"""Topological configurations (paper section 3.2) and b-compatibility reports (3.3-3.4).

``classify`` names the configuration of a pair of curves; ``orient_pair`` checks that a pair is
in configuration 1 or 2, orients it the paper's way and says on which side of each curve the gap
lies; ``CompatibilityReport`` says where maximal disks fail (touch a curve twice / the medial
axis bifurcates), not just yes or no.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..errors import IncompatibleCurvesError
from ..geometry.intersections import Crossings, crossings, is_simple
from ..geometry.polyline import as_curve, orient_clockwise, points_in_loop, scale_of, signed_area
from ..geometry.spatial import PointTree

__all__ = [
    "CONFIGURATIONS",
    "classify",
    "PairSetup",
    "orient_pair",
    "shared_endpoints",
    "crossing_order_agrees",
]

CONFIGURATIONS = (
    "disjoint-loops",
    "quasi-disjoint-strokes",
    "crossing-loops",
    "crossing-strokes",
    "invalid",
)


def shared_endpoints(P, Q):
    """How two strokes share their endpoints.

    Returns
    -------
    str
        ``'same'`` (P[0]~Q[0] and P[-1]~Q[-1]), ``'reversed'`` (P[0]~Q[-1] and P[-1]~Q[0]) or
        ``'none'``.
    """
    eps = tol.SHARED_ENDPOINT * scale_of(P, Q)
    same = np.linalg.norm(P[0] - Q[0]) <= eps and np.linalg.norm(P[-1] - Q[-1]) <= eps
    if same:
        return "same"
    rev = np.linalg.norm(P[0] - Q[-1]) <= eps and np.linalg.norm(P[-1] - Q[0]) <= eps
    return "reversed" if rev else "none"


def _interior_crossings(P, Q, closed):
    """Crossings, minus a stroke pair's shared endpoints."""
    cx = crossings(P, closed, Q, closed)
    if closed or len(cx) == 0:
        return cx
    eps = tol.SHARED_ENDPOINT * scale_of(P, Q)
    at_end = (np.linalg.norm(cx.points - P[0], axis=1) <= eps) | (np.linalg.norm(cx.points - P[-1], axis=1) <= eps)
    keep = ~at_end
    return Crossings(*(values[keep] for values in (cx.pair, cx.points, cx.s_a, cx.s_b, cx.edge_a, cx.edge_b)))


def crossing_order_agrees(cx, closed):
    """True when the crossings come in the same order along both curves.

    Then P and Q split at the crossings into a chain of quasi-disjoint stroke pairs (lenses),
    which is our operational test of the paper's valid configurations 3 and 4 (a single
    component of i(P) & i(Q) for loops; a connected o(P u Q) for strokes). Loops must both be
    oriented clockwise first; the order along a loop is cyclic.
    """
    if len(cx) <= 1:
        return True
    rank_b = np.argsort(np.argsort(cx.s_b, kind="stable"), kind="stable")
    if not closed:
        return bool(np.all(np.diff(rank_b) > 0))
    shift = (rank_b - rank_b[0]) % len(rank_b)
    return bool(np.array_equal(shift, np.arange(len(rank_b))))


def classify(P, Q, closed=False):
    """Topological configuration of two curves (paper section 3.2).

    Parameters
    ----------
    P, Q : array_like, shape (N, 2) and (M, 2)
    closed : bool
        Loops (True) or strokes (False).

    Returns
    -------
    str
        One of ``'disjoint-loops'`` (configuration 1: disjoint loops, one inside the other),
        ``'quasi-disjoint-strokes'`` (2: strokes meeting only at both shared endpoints),
        ``'crossing-loops'`` (3), ``'crossing-strokes'`` (4) or ``'invalid'`` (self-
        intersecting input, loops side by side, strokes without shared endpoints, or crossings
        in an order that cannot be split into lens pairs).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    >>> circle = np.c_[np.cos(t), np.sin(t)]
    >>> classify(circle, 2 * circle, closed=True)
    'disjoint-loops'
    >>> classify(circle, circle + [0.5, 0], closed=True)
    'crossing-loops'
    >>> classify(circle, circle + [5, 0], closed=True)
    'invalid'
    """
    P = as_curve(P, "P", closed)
    Q = as_curve(Q, "Q", closed)
    if not (is_simple(P, closed) and is_simple(Q, closed)):
        return "invalid"
    if closed:
        P, Q = orient_clockwise(P), orient_clockwise(Q)
        cx = _interior_crossings(P, Q, True)
        if len(cx) == 0:
            nested = points_in_loop(P[:1], Q)[0] or points_in_loop(Q[:1], P)[0]
            return "disjoint-loops" if nested else "invalid"
        return "crossing-loops" if crossing_order_agrees(cx, True) else "invalid"
    how = shared_endpoints(P, Q)
    if how == "none":
        return "invalid"
    if how == "reversed":
        Q = Q[::-1]
    cx = _interior_crossings(P, Q, False)
    if len(cx) == 0:
        loop = np.concatenate([P, Q[-2:0:-1]])
        return "quasi-disjoint-strokes" if is_simple(loop, True) else "invalid"
    return "crossing-strokes" if crossing_order_agrees(cx, False) else "invalid"


@dataclass
class PairSetup:
    """A pair of curves oriented the paper's way, with the side of the gap.

    Attributes
    ----------
    P, Q : ndarray, shape (N, 2), (M, 2)
        Oriented copies (loops clockwise; a stroke Q reversed to start where P starts).
    closed : bool
    side_p, side_q : float
        +1 if the gap lies to the left of the oriented curve, -1 if to the right.
    reversed_p, reversed_q : bool
        Whether the oriented copy runs backwards relative to the input.
    coincident : bool
        P and Q are the same curve (within ``tolerances.OVERLAP``): the morph is static.
    """

    P: np.ndarray
    Q: np.ndarray
    closed: bool
    side_p: float
    side_q: float
    reversed_p: bool = False
    reversed_q: bool = False
    coincident: bool = False

    def swapped(self):
        """The same pair with P and Q exchanged (PairSetup)."""
        return PairSetup(
            self.Q, self.P, self.closed, self.side_q, self.side_p, self.reversed_q, self.reversed_p, self.coincident
        )


def _coincident(P, Q, closed):
    eps = tol.OVERLAP * scale_of(P, Q)
    for a, b in ((P, Q), (Q, P)):
        tree = PointTree(b)
        qi, _ = tree.within(a, np.full(len(a), eps), first_only=True)
        if len(np.unique(qi)) < len(a):
            return False
    return True


def orient_pair(P, Q, closed):
    """Check a pair is in configuration 1 or 2, orient it and find the gap.

    Parameters
    ----------
    P, Q : ndarray, shape (N, 2), (M, 2)
        Validated curves (see :func:`~ballmorph_core.curves.as_curve`).
    closed : bool

    Returns
    -------
    PairSetup

    Raises
    ------
    IncompatibleCurvesError
        If the pair is in another configuration; the message names it and what to do.
    """
    if closed:
        Pc, Qc = orient_clockwise(P), orient_clockwise(Q)
        rp, rq = signed_area(P) > 0, signed_area(Q) > 0
        if _coincident(Pc, Qc, True):
            return PairSetup(Pc, Qc, True, 1.0, 1.0, rp, rq, coincident=True)
        config = classify(Pc, Qc, True)
        if config != "disjoint-loops":
            raise IncompatibleCurvesError(
                f"the loops are {config!r}, not disjoint nested loops (paper configuration 1): "
                "split crossing loops at their intersections or register them first"
            )
        # Clockwise loops have their inside on the right: the inner loop's gap side is its
        # outside (left), the outer loop's gap side its inside (right).
        p_inner = bool(points_in_loop(Pc[:1], Qc)[0])
        return PairSetup(Pc, Qc, True, 1.0 if p_inner else -1.0, -1.0 if p_inner else 1.0, rp, rq)
    how = shared_endpoints(P, Q)
    if how == "none":
        raise IncompatibleCurvesError(
            "the strokes do not share both endpoints (paper configuration 2 needs them): "
            "use a carrier motion to register them first"
        )
    Qo = Q[::-1].copy() if how == "reversed" else Q
    if _coincident(P, Qo, False):
        return PairSetup(P, Qo, False, 1.0, 1.0, False, how == "reversed", coincident=True)
    config = classify(P, Qo, False)
    if config != "quasi-disjoint-strokes":
        raise IncompatibleCurvesError(
            f"the strokes are {config!r}, not quasi-disjoint (paper configuration 2): "
            "split them at their crossings first"
        )
    loop = np.concatenate([P, Qo[-2:0:-1]])
    ccw = signed_area(loop) > 0
    # Walking P then Q backwards goes around the gap: it lies left of P and right of Q when
    # that walk is counter-clockwise.
    return PairSetup(P, Qo, False, 1.0 if ccw else -1.0, -1.0 if ccw else 1.0, False, how == "reversed")
