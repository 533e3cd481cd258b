"""Split crossing or overlapping curves into quasi-disjoint stroke pairs (paper section 3.2).

Crossing loops (configuration 3) and crossing strokes (configuration 4) decompose at their
intersection points into a chain of lens-shaped pairs of strokes that share both endpoints
(configuration 2); portions where P and Q coincide (overlaps) stay static. Each lens is then
ball-morphed on its own and the pieces are joined again, so the intersection points stay fixed
during the morph, as the paper requires of every morph it compares.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..errors import IncompatibleCurvesError
from ..geometry.intersections import crossings
from ..geometry.polyline import cumulative_length, resample, scale_of, subcurve
from ..geometry.projection import distances_to_polyline

__all__ = ["Piece", "split_pair"]


@dataclass
class Piece:
    """One piece of a split pair.

    Attributes
    ----------
    P, Q : ndarray, shape (n, 2), (m, 2)
        Stroke pieces sharing both endpoints (exactly).
    kind : str
        ``'gap'`` (to be morphed) or ``'overlap'`` (P and Q coincide: static).
    range_p, range_q : tuple of float
        Arc-length start and end on P and on Q (for loops the end may exceed the length).
    """

    P: np.ndarray
    Q: np.ndarray
    kind: str
    range_p: tuple
    range_q: tuple


def _overlap_runs(P, Q, closed, spacing, eps):
    """Stretches of P lying on Q: list of (sP0, sP1, sQ0, sQ1)."""
    dense = resample(P, closed, spacing=spacing, smooth=False)
    s_dense = cumulative_length(dense, closed)[: len(dense)]
    # Rescale the dense arc lengths onto P's own (resampling along P keeps them proportional).
    s_dense *= cumulative_length(P, closed)[-1] / max(cumulative_length(dense, closed)[-1], 1e-300)
    dist, s_q = distances_to_polyline(dense, Q, closed, eps)
    near = dist <= eps
    if not near.any():
        return []
    if closed and near.all():
        return [(0.0, cumulative_length(P, True)[-1], s_q[0], s_q[0] + cumulative_length(Q, True)[-1])]
    # Runs of consecutive near samples (cyclic for loops), at least two samples long.
    idx = np.flatnonzero(near)
    if closed:
        start = idx[~near[(idx - 1) % len(near)]]
        runs = []
        for s0 in start:
            k = s0
            while near[(k + 1) % len(near)]:
                k += 1
            runs.append((s0, k))
    else:
        breaks = np.flatnonzero(np.diff(idx) > 1)
        runs = list(zip(idx[np.r_[0, breaks + 1]], idx[np.r_[breaks, len(idx) - 1]]))
    n = len(dense)
    out = []
    length_p = cumulative_length(P, closed)[-1]
    for a, b in runs:
        if b - a < 1:
            continue
        sp0, sp1 = s_dense[a % n], s_dense[b % n] + (length_p if closed and b >= n else 0.0)
        out.append((sp0, sp1, s_q[a % n], s_q[b % n]))
    return out


def split_pair(P, Q, closed, spacing):
    """Split a crossing or overlapping pair into pieces (see the module docstring).

    Parameters
    ----------
    P, Q : ndarray, shape (N, 2), (M, 2)
        Consistently oriented: strokes starting at the same point and ending at the same
        point, loops both clockwise.
    closed : bool
    spacing : float
        Sampling used to find overlaps.

    Returns
    -------
    list of Piece
        In order along P. Empty if the curves neither cross nor overlap.

    Raises
    ------
    IncompatibleCurvesError
        If the crossings and overlaps do not come in the same order along both curves (then the
        pair does not decompose into lenses: paper Fig. 8 and 9, right).
    """
    scale = scale_of(P, Q)
    eps = tol.OVERLAP * scale
    len_p, len_q = cumulative_length(P, closed)[-1], cumulative_length(Q, closed)[-1]
    overlaps = _overlap_runs(P, Q, closed, spacing, eps)
    cx = crossings(P, closed, Q, closed)
    events = []  # (sP0, sP1, sQ0, sQ1, kind)
    for sp0, sp1, sq0, sq1 in overlaps:
        events.append((sp0, sp1, sq0, sq1, "overlap"))
    end_eps = tol.SHARED_ENDPOINT * scale
    for sp, sq in zip(cx.s_a, cx.s_b):
        if not closed and (sp <= end_eps or sp >= len_p - end_eps):
            continue  # the shared endpoints are not splits
        if any(a - end_eps <= sp <= b + end_eps for a, b, *_ in overlaps):
            continue
        events.append((sp, sp, sq, sq, "cross"))
    if not events:
        return []
    events.sort(key=lambda e: e[0])
    sq_order = np.array([e[2] for e in events])
    if closed:
        rank = np.argsort(np.argsort(sq_order))
        ok = np.array_equal((rank - rank[0]) % len(rank), np.arange(len(rank)))
    else:
        ok = bool(np.all(np.diff(sq_order) >= -end_eps))
    if not ok:
        raise IncompatibleCurvesError(
            "the curves cross in a different order along each one (tangled), so they do not "
            "split into lens-shaped stroke pairs"
        )
    if not closed:
        events = [(0.0, 0.0, 0.0, 0.0, "start"), *events, (len_p, len_p, len_q, len_q, "end")]
    pieces = []
    n_ev = len(events)
    for k in range(n_ev if closed else n_ev - 1):
        cur, nxt = events[k], events[(k + 1) % n_ev]
        if cur[4] == "overlap":
            pieces.append(_piece(P, Q, closed, cur[0], cur[1], cur[2], cur[3], "overlap"))
        sp0, sq0 = cur[1], cur[3]
        sp1, sq1 = nxt[0], nxt[2]
        if closed:
            # The next event, one lap on if it lies behind (or is this one: the whole loop).
            if sp1 <= sp0 + end_eps:
                sp1 += len_p
            if sq1 <= sq0 + end_eps:
                sq1 += len_q
        if sp1 - sp0 > end_eps or sq1 - sq0 > end_eps:
            pieces.append(_piece(P, Q, closed, sp0, sp1, sq0, sq1, "gap"))
    return pieces


def _piece(P, Q, closed, sp0, sp1, sq0, sq1, kind):
    p = subcurve(P, closed, sp0, sp1)
    q = subcurve(Q, closed, sq0, sq1)
    q[0], q[-1] = p[0], p[-1]  # share the endpoints exactly
    return Piece(p, q, kind, (sp0, sp1), (sq0, sq1))
