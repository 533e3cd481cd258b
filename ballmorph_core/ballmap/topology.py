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
from ..geometry.intersections import Crossings, batch_crossings, simple_curves
from ..geometry.polyline import as_curve, orient_clockwise, points_in_loop, scale_of, signed_area
from ..geometry.ragged import Ragged
from ..geometry.spatial import PointTree

__all__ = [
    "CONFIGURATIONS",
    "classify",
    "classify_pairs",
    "PairSetup",
    "orient_pair",
    "orient_pairs",
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


def _interior_crossings(pairs):
    """Crossings of each pair ``(P, Q, closed)``, minus a stroke pair's shared endpoints, every
    pair searched in one batch (list of Crossings, each its pair's alone: ``pair`` 0)."""
    if not pairs:
        return []
    closed = [c for _, _, c in pairs]
    A = Ragged.from_list([P for P, _, _ in pairs], closed)
    B = Ragged.from_list([Q for _, Q, _ in pairs], closed)
    found = batch_crossings(A, B, np.array([scale_of(P, Q) for P, Q, _ in pairs]))
    bounds = np.searchsorted(found.pair, np.arange(len(pairs) + 1))
    out = []
    for k, (P, Q, loop) in enumerate(pairs):
        keep = np.arange(bounds[k], bounds[k + 1])
        if not loop and len(keep):
            eps = tol.SHARED_ENDPOINT * scale_of(P, Q)
            points = found.points[keep]
            at_end = (np.linalg.norm(points - P[0], axis=1) <= eps) | (np.linalg.norm(points - P[-1], axis=1) <= eps)
            keep = keep[~at_end]
        fields = (found.points, found.s_a, found.s_b, found.edge_a, found.edge_b)
        out.append(Crossings(np.zeros(len(keep), np.int64), *(values[keep] for values in fields)))
    return out


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
    return classify_pairs([(P, Q, closed)])[0]


def classify_pairs(pairs):
    """:func:`classify` of many validated pairs ``(P, Q, closed)`` at once (list of str): the
    curves' self-crossings, and then the pairs' crossings, each searched in one batch."""
    out = [None] * len(pairs)
    curves = [c for P, Q, _ in pairs for c in (P, Q)]
    simple = simple_curves(curves, np.repeat([c for _, _, c in pairs], 2)).reshape(-1, 2).all(axis=1)
    ready = []
    for k, ((P, Q, closed), ok) in enumerate(zip(pairs, simple)):
        if not ok:
            out[k] = "invalid"
        elif closed:
            ready.append((k, orient_clockwise(P), orient_clockwise(Q), True))
        else:
            how = shared_endpoints(P, Q)
            if how == "none":
                out[k] = "invalid"
            else:
                ready.append((k, P, Q[::-1] if how == "reversed" else Q, False))
    gaps = []  # strokes meeting only at their ends: whether P then Q backwards is simple
    for (k, P, Q, closed), cx in zip(ready, _interior_crossings([r[1:] for r in ready])):
        if len(cx) and closed:
            out[k] = "crossing-loops" if crossing_order_agrees(cx, True) else "invalid"
        elif len(cx):
            out[k] = "crossing-strokes" if crossing_order_agrees(cx, False) else "invalid"
        elif closed:
            nested = points_in_loop(P[:1], Q)[0] or points_in_loop(Q[:1], P)[0]
            out[k] = "disjoint-loops" if nested else "invalid"
        else:
            gaps.append((k, np.concatenate([P, Q[-2:0:-1]])))
    for (k, _), ok in zip(gaps, simple_curves([loop for _, loop in gaps], np.ones(len(gaps), bool))):
        out[k] = "quasi-disjoint-strokes" if ok else "invalid"
    return out


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
    (setup,) = orient_pairs([(P, Q, closed)])
    if isinstance(setup, IncompatibleCurvesError):
        raise setup
    return setup


def orient_pairs(pairs):
    """:func:`orient_pair` of many validated pairs ``(P, Q, closed)`` at once, classified
    together (:func:`classify_pairs`).

    Returns
    -------
    list of PairSetup or IncompatibleCurvesError
        Per pair, its setup or the error :func:`orient_pair` raises for it.
    """
    out, asked = [None] * len(pairs), []
    for k, (P, Q, closed) in enumerate(pairs):
        if closed:
            Pc, Qc = orient_clockwise(P), orient_clockwise(Q)
            rp, rq = signed_area(P) > 0, signed_area(Q) > 0
            if _coincident(Pc, Qc, True):
                out[k] = PairSetup(Pc, Qc, True, 1.0, 1.0, rp, rq, coincident=True)
            else:
                asked.append((k, Pc, Qc, True, (rp, rq)))
            continue
        how = shared_endpoints(P, Q)
        if how == "none":
            out[k] = IncompatibleCurvesError(
                "the strokes do not share both endpoints (paper configuration 2 needs them): "
                "use a carrier motion to register them first"
            )
            continue
        Qo = Q[::-1].copy() if how == "reversed" else Q
        if _coincident(P, Qo, False):
            out[k] = PairSetup(P, Qo, False, 1.0, 1.0, False, how == "reversed", coincident=True)
        else:
            asked.append((k, P, Qo, False, how == "reversed"))
    for (k, P, Q, closed, turned), config in zip(asked, classify_pairs([a[1:4] for a in asked])):
        out[k] = _oriented(P, Q, closed, turned, config)
    return out


def _oriented(P, Q, closed, turned, config):
    """The PairSetup of a pair that :func:`orient_pairs` classified as ``config``, or the
    IncompatibleCurvesError of one in the wrong configuration (``turned``: loops, whether each
    was counter-clockwise; strokes, whether Q was reversed)."""
    if closed:
        if config != "disjoint-loops":
            return IncompatibleCurvesError(
                f"the loops are {config!r}, not disjoint nested loops (paper configuration 1): "
                "split crossing loops at their intersections or register them first"
            )
        # Clockwise loops have their inside on the right: the inner loop's gap side is its
        # outside (left), the outer loop's gap side its inside (right).
        p_inner = bool(points_in_loop(P[:1], Q)[0])
        return PairSetup(P, Q, True, 1.0 if p_inner else -1.0, -1.0 if p_inner else 1.0, *turned)
    if config != "quasi-disjoint-strokes":
        return IncompatibleCurvesError(
            f"the strokes are {config!r}, not quasi-disjoint (paper configuration 2): "
            "split them at their crossings first"
        )
    loop = np.concatenate([P, Q[-2:0:-1]])
    ccw = signed_area(loop) > 0
    # Walking P then Q backwards goes around the gap: it lies left of P and right of Q when
    # that walk is counter-clockwise.
    return PairSetup(P, Q, False, 1.0 if ccw else -1.0, -1.0 if ccw else 1.0, False, turned)
