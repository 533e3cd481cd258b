"""Stroke matching: which stroke of one key morphs into which stroke of the other.

Two keys rarely list their strokes in the same order with the same count: the animator adds a
line, redraws an eye first, draws a loop the other way round. Blender's own interpolation pairs
strokes by index and drops the surplus; :func:`match_strokes` keeps that pairing when it fits
the drawings and otherwise solves an optimal assignment on a shape distance.

Shape distance
--------------
Every stroke is resampled to ``MATCH_SAMPLES`` points at uniform arc length (on its
chords: the samples only describe the shape). The cost of pairing stroke ``i`` of key A with
stroke ``j`` of key B is the root-mean-square distance between corresponding samples,

    cost_ij = sqrt(mean_k |a_ik - (b_jk - tau)|^2) / scale  (+ MATCH_CYCLIC_PENALTY if mixed),

minimised over B's direction (open strokes) or over B's direction and cyclic shift (when both are
loops). ``tau`` is the keys' overall translation (the character moved between the keys) and
``scale`` the drawing size: the smaller of the two keys' bounding-box diagonals, so a far-off
stroke that exists in one key only does not loosen every threshold. Loops start anywhere, so a
loop pair's cost carries up to about half a sample spacing of phase error (the samples of the
two loops need not line up); the thresholds are far above it.

The root-mean-square (rather than plain mean) distance is chosen because it splits exactly into
a shape part and a position part: with ``~`` marking samples centred on their stroke's own
centroid ``c``,

    mean_k |a_k - b_k + tau|^2 = mean_k |~a_k - ~b_k|^2 + |c_a - c_b + tau|^2,

and reversing or cyclically shifting ``b`` changes neither centroid. So the expensive part
(directions and shifts: Gram matrices, ``S_a x S_b x m`` work, chunked) is computed once, and
trying another overall translation costs only ``S_a x S_b`` operations. It is also the criterion
of :func:`~ballmorph_core.morphs.linear.best_cyclic_alignment`, which decides the direction of
loop pairs, so the reported flag agrees with the alignment the loop morphs use.

Overall motion
--------------
``tau`` is estimated by alternating (assign, fit ``tau`` to the pairs by least squares) from
three starting guesses: no motion, the difference of the keys' ink centroids, and the
difference of the coordinate-wise medians of the stroke centroids (robust to a minority of
strokes present in one key only). The guess whose assignment has the lowest total is kept.
Scale changes between keys are not modelled: the two keys of a tight in-between are drawn at
the same size, and a size estimate is easily upset by a stroke present in one key only.

Unmatched strokes
-----------------
The assignment is rectangular and a pair costing ``MATCH_MAX_COST`` or more is never formed.
This is the classic padding with dummy rows and columns (every stroke may instead take a dummy
partner costing ``MATCH_MAX_COST / 2``, so a real pair is worth forming only below
``MATCH_MAX_COST``), solved without enlarging the matrix: clipping the costs at
``MATCH_MAX_COST``, solving the rectangular problem and dropping the clipped pairs has the same
optimum. What becomes of an unmatched stroke (appear or disappear at the middle of the
in-between range, or hold) is the caller's choice (:func:`~ballmorph_core.inbetween.inbetween`).
"""

from dataclasses import dataclass, field

import numpy as np

from .. import tolerances as tol
from ..errors import InvalidCurveError
from ..geometry.polyline import as_curve, curve_length, resample
from ..geometry.ragged import Ragged, budget_slices
from ..morphs.linear import best_cyclic_alignment
from ..options import MATCHINGS, check_option
from .assignment import solve_assignment

__all__ = ["Matching", "match_strokes"]

#: Stroke matching (ballmorph_core.matching). Costs are root-mean-square distances between
#: corresponding arc-length samples of two strokes, once the keys' overall motion is removed,
#: relative to the drawing size (the smaller of the two keys' bounding-box diagonals).
#: Samples per stroke in the matching descriptor.
MATCH_SAMPLES = 32
#: A pair costing this much or more is never formed: both strokes stay unmatched (they appear
#: or disappear) rather than morphing across the drawing. Equivalent to padding the
#: assignment with dummy partners costing half of this each.
MATCH_MAX_COST = 0.5
#: Added to the cost of a pair where one stroke is cyclic and the other is not.
MATCH_CYCLIC_PENALTY = 0.1
#: 'AUTO' keeps the drawing order (pairing by index) when the counts agree, every index pair
#: costs less than MATCH_INDEX_MAX_COST, and the index pairing's total is within
#: MATCH_INDEX_FACTOR of the optimal assignment's.
MATCH_INDEX_MAX_COST = 0.25
MATCH_INDEX_FACTOR = 1.25
#: Per pair, totals closer than this are equal (round-off of the Gram-matrix cost evaluation).
MATCH_ROUNDOFF = 1e-6
#: Alternations of (assign strokes, re-fit the keys' overall translation) per starting guess.
MATCH_MOTION_ITERATIONS = 3

# Elements per block when a product would otherwise allocate S_a x S_b x m at once (memory only).
_CHUNK = 2_000_000


@dataclass
class Matching:
    """How the strokes of two keys are paired.

    Attributes
    ----------
    pairs : list of (int, int, bool)
        ``(i, j, reverse)``: stroke ``i`` of key A morphs into stroke ``j`` of key B, sorted by
        ``i``. ``reverse`` is True when B's stroke runs opposite to A's, so the caller reverses
        B's stroke before morphing. Open strokes (and mixed pairs, which are morphed as open
        strokes along their vertex order): reversing B's point order makes the two run the same
        way. Two loops: B's loop has the opposite orientation (the direction found by
        :func:`~ballmorph_core.morphs.linear.best_cyclic_alignment`; for simple loops the signs
        of their signed areas differ).
    unmatched_a, unmatched_b : list of int
        Strokes with no partner, sorted.
    method : str
        ``'index'`` (paired by drawing order) or ``'assignment'`` (optimal assignment).
    reason : str
        Why, in a short sentence for the animator.
    costs : list of float
        The cost of each pair (root-mean-square distance over the drawing size, see the module
        notes); ``inf`` for a pair involving a stroke with no points.
    motion : ndarray, shape (2,)
        The keys' overall translation used (key B is about key A moved by ``motion``).
    """

    pairs: list
    unmatched_a: list
    unmatched_b: list
    method: str
    reason: str
    costs: list = field(default_factory=list)
    motion: np.ndarray = field(default_factory=lambda: np.zeros(2))


def _clean(points, name, closed):
    """Distinct points of one stroke: shape (K, 2) with K >= 2, (1, 2) for a dot, None if empty.

    A loop with fewer than three distinct points is kept as the open polyline it is.
    """
    try:
        return as_curve(points, name, closed)
    except InvalidCurveError as exc:
        error = exc
    try:
        arr = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise error from None
    if arr.size == 0 and (arr.ndim == 1 or arr.shape[-1] == 2):
        return None
    if arr.ndim != 2 or arr.shape[1] != 2 or not np.all(np.isfinite(arr)):
        raise error
    if closed and len(arr) > 1:
        try:
            return as_curve(arr, name, False)
        except InvalidCurveError:
            pass
    return arr[:1].copy()  # every point coincides: a dot


class _Key:
    """Matching descriptors of the strokes of one key.

    Attributes
    ----------
    loop : ndarray of bool, shape (S,)
        The cyclic flags as given.
    open : ndarray, shape (S, m, 2)
        Arc-length samples along each stroke's vertices, closing edge excluded (how a loop is
        morphed when its partner is open); a dot repeats its point.
    ring : ndarray, shape (S, m, 2)
        For loops, samples around the whole loop; for open strokes the same as ``open``.
    valid : ndarray of bool, shape (S,)
        False for strokes with no points.
    length : ndarray, shape (S,)
    diagonal : float
        Bounding-box diagonal of all the key's points (0 when none).
    """

    def __init__(self, strokes, closed, name, closed_name, m):
        strokes = list(strokes)
        s = len(strokes)
        closed = np.asarray(closed, dtype=bool).reshape(-1)
        if len(closed) != s:
            raise InvalidCurveError(f"{closed_name}: expected one flag per stroke ({s}), got {len(closed)}")
        self.count = s
        self.loop = closed
        self.open = np.zeros((s, m, 2))
        self.ring = np.zeros((s, m, 2))
        self.valid = np.zeros(s, bool)
        self.length = np.zeros(s)
        if self._batched(strokes, closed, m):
            return
        lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
        for i, points in enumerate(strokes):
            clean = _clean(points, f"{name}[{i}]", bool(closed[i]))
            if clean is None:
                continue
            self.valid[i] = True
            lo, hi = np.minimum(lo, clean.min(axis=0)), np.maximum(hi, clean.max(axis=0))
            if len(clean) == 1:
                self.open[i] = self.ring[i] = clean[0]
                continue
            self.open[i] = resample(clean, False, count=m, smooth=False)
            self.ring[i] = resample(clean, True, count=m, smooth=False) if closed[i] else self.open[i]
            self.length[i] = curve_length(clean, bool(closed[i]))
        self.diagonal = float(np.linalg.norm(hi - lo)) if self.valid.any() else 0.0

    def _batched(self, strokes, closed, m):
        """All descriptors at once for well-formed keys (finite points); False to go one by one."""
        try:
            arrays = [np.asarray(p, dtype=np.float64) for p in strokes]
        except (TypeError, ValueError):
            return False
        if any(a.ndim != 2 or a.shape[1] != 2 for a in arrays if a.size):
            return False  # the per-stroke road names the malformed stroke
        arrays = [a.reshape(-1, 2) for a in arrays]
        sizes = np.array([len(a) for a in arrays], dtype=np.int64)
        pts = np.concatenate(arrays) if arrays else np.zeros((0, 2))
        if not np.all(np.isfinite(pts)):
            return False  # the per-stroke road names the bad stroke
        self.valid = sizes > 0
        if not self.valid.any():
            self.diagonal = 0.0
            return True
        self.diagonal = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))
        offsets = np.concatenate([[0], np.cumsum(sizes)])
        line = Ragged(pts, offsets, np.zeros(len(sizes), dtype=bool))
        # Dots (one point, or all points the same) repeat their point.
        dot = self.valid & (line.length <= tol.COINCIDENT * max(self.diagonal, 1e-300))
        first = pts[np.minimum(offsets[:-1], max(len(pts) - 1, 0))]
        self.open[dot] = self.ring[dot] = first[dot][:, None, :]
        keep = np.flatnonzero(self.valid & ~dot)
        if len(keep):
            idx = np.concatenate([np.arange(offsets[i], offsets[i + 1]) for i in keep])
            sub = np.concatenate([[0], np.cumsum(sizes[keep])])
            opened = Ragged(pts[idx], sub, np.zeros(len(keep), dtype=bool))
            looped = Ragged(pts[idx], sub, closed[keep])
            self.open[keep] = opened.resample(np.full(len(keep), m), smooth=False).pts.reshape(-1, m, 2)
            ring = looped.resample(np.full(len(keep), m), smooth=False).pts.reshape(-1, m, 2)
            self.ring[keep] = np.where(closed[keep][:, None, None], ring, self.open[keep])
            self.length[keep] = looped.length
        return True

    def centroids(self):
        """Sample centroid of each stroke's own descriptor (ring for loops), shape (S, 2)."""
        return np.where(self.loop[:, None], self.ring.mean(axis=1), self.open.mean(axis=1))

    def ink_centroid(self):
        """Length-weighted mean of the stroke centroids, shape (2,) (dots weigh in if no ink)."""
        ctr, w = self.centroids()[self.valid], self.length[self.valid]
        if w.sum() <= 0:
            w = np.ones(len(ctr))
        return (w[:, None] * ctr).sum(axis=0) / w.sum()

    def median_centroid(self):
        """Coordinate-wise median of the stroke centroids, shape (2,)."""
        return np.median(self.centroids()[self.valid], axis=0)


def _open_shape(a, b):
    """Shape part of the open-stroke cost for every pair.

    Parameters
    ----------
    a : ndarray, shape (S_a, m, 2)
    b : ndarray, shape (S_b, m, 2)
        Samples centred on their own centroids.

    Returns
    -------
    sq : ndarray, shape (S_a, S_b)
        ``min(mean_k |a_k - b_k|^2, mean_k |a_k - b_(m-1-k)|^2)``.
    reverse : ndarray of bool, shape (S_a, S_b)
        Where the reversed direction is the smaller.
    """
    m = a.shape[1]
    fa, fb, fr = a.reshape(len(a), 2 * m), b.reshape(len(b), 2 * m), b[:, ::-1].reshape(len(b), 2 * m)
    norms = (fa * fa).sum(axis=1)[:, None] + (fb * fb).sum(axis=1)[None, :]
    # Gram expansion |x - y|^2 = |x|^2 + |y|^2 - 2 x.y: two matrix products instead of S_a x S_b x m.
    fwd = norms - 2.0 * fa @ fb.T
    bwd = norms - 2.0 * fa @ fr.T
    return np.maximum(np.minimum(fwd, bwd), 0.0) / m, bwd < fwd


def _loop_shape(a, b):
    """Shape part of the loop cost: minimum over B's cyclic shift and direction.

    Parameters
    ----------
    a : ndarray, shape (L_a, m, 2)
    b : ndarray, shape (L_b, m, 2)
        Loop samples centred on their own centroids.

    Returns
    -------
    ndarray, shape (L_a, L_b)
        ``min over shift s, direction d of mean_k |a_k - b^d_(k+s)|^2`` (``b^d`` reversed keeping
        its first sample, as :func:`~ballmorph_core.curves.reverse` does).
    """
    m = a.shape[1]
    shifts = (np.arange(m)[:, None] + np.arange(m)[None, :]) % m  # [s, k] -> k + s
    backwards = np.concatenate([b[:, :1], b[:, :0:-1]], axis=1)
    # Every shifted copy of every B loop, both directions, as rows: (L_b * 2 * m, 2 m).
    copies = np.stack([b[:, shifts], backwards[:, shifts]], axis=1).reshape(-1, 2 * m)
    fa = a.reshape(len(a), 2 * m)
    best = np.empty((len(a), len(b)))
    for sl in budget_slices(np.full(len(a), len(copies)), _CHUNK):
        best[sl] = (fa[sl] @ copies.T).reshape(sl.stop - sl.start, len(b), 2 * m).max(axis=2)
    norms = (fa * fa).sum(axis=1)[:, None] + (b * b).sum(axis=(1, 2))[None, :]
    return np.maximum(norms - 2.0 * best, 0.0) / m


class _CostTable:
    """Pair costs of two keys, for any overall translation (see the module notes).

    Attributes
    ----------
    shape : ndarray, shape (S_a, S_b)
        Translation-free squared part.
    offset : ndarray, shape (S_a, S_b, 2)
        ``c_a - c_b`` (stroke centroids of the descriptors each pair uses).
    reverse_open : ndarray of bool, shape (S_a, S_b)
        Direction of open and mixed pairs.
    """

    def __init__(self, key_a, key_b, scale):
        self.scale = scale
        ca, cb = key_a.centroids(), key_b.centroids()
        both_loops = key_a.loop[:, None] & key_b.loop[None, :]
        self.mixed = key_a.loop[:, None] != key_b.loop[None, :]
        self.valid = key_a.valid[:, None] & key_b.valid[None, :]
        oa, ob = key_a.open.mean(axis=1), key_b.open.mean(axis=1)
        self.shape, self.reverse_open = _open_shape(key_a.open - oa[:, None], key_b.open - ob[:, None])
        self.offset = oa[:, None, :] - ob[None, :, :]
        la, lb = np.flatnonzero(key_a.loop), np.flatnonzero(key_b.loop)
        if la.size and lb.size:
            ring_a = key_a.ring[la] - ca[la, None]
            ring_b = key_b.ring[lb] - cb[lb, None]
            self.shape[np.ix_(la, lb)] = _loop_shape(ring_a, ring_b)
            self.offset[both_loops] = (ca[:, None, :] - cb[None, :, :])[both_loops]

    def costs(self, motion):
        """Pair costs with key B moved back by ``motion`` (shape (2,)), shape (S_a, S_b)."""
        d = self.offset + motion
        c = np.sqrt(self.shape + (d * d).sum(axis=2)) / self.scale + MATCH_CYCLIC_PENALTY * self.mixed
        return np.where(self.valid, c, np.inf)

    def fit_motion(self, rows, cols):
        """Least-squares overall translation for given pairs, shape (2,) (zero if none)."""
        keep = self.valid[rows, cols]
        if not keep.any():
            return np.zeros(2)
        return -self.offset[rows[keep], cols[keep]].mean(axis=0)


def _assign_within(costs):
    """Optimal pairs among those cheaper than MATCH_MAX_COST (rows, cols, each shape (K,))."""
    if not np.any(costs < MATCH_MAX_COST):
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    rows, cols = solve_assignment(np.minimum(costs, MATCH_MAX_COST))
    keep = costs[rows, cols] < MATCH_MAX_COST
    return rows[keep], cols[keep]


def _padded_total(pair_costs, n_a, n_b):
    """Total of a matching with every unmatched stroke paying MATCH_MAX_COST / 2 (float)."""
    unmatched = n_a + n_b - 2 * len(pair_costs)
    return float(np.sum(pair_costs)) + 0.5 * MATCH_MAX_COST * unmatched


def _best_assignment(table, key_a, key_b):
    """Alternate assignment and motion fit from each starting guess; keep the cheapest.

    Returns
    -------
    total : float
    rows, cols : ndarray of int
    motion : ndarray, shape (2,)
    """
    guesses = [np.zeros(2)]
    if key_a.valid.any() and key_b.valid.any():
        guesses += [
            key_b.ink_centroid() - key_a.ink_centroid(),
            key_b.median_centroid() - key_a.median_centroid(),
        ]
    best, tried = None, []
    for motion in guesses:
        for _ in range(MATCH_MOTION_ITERATIONS):
            # A motion already evaluated (the previous pairs refit to the same motion, or another
            # guess led here) would give the same assignment: this guess has converged.
            if any(np.linalg.norm(motion - t) <= MATCH_ROUNDOFF * table.scale for t in tried):
                break
            tried.append(motion)
            costs = table.costs(motion)
            rows, cols = _assign_within(costs)
            total = _padded_total(costs[rows, cols], key_a.count, key_b.count)
            if best is None or total < best[0]:
                best = (total, rows, cols, motion)
            if not len(rows):
                break
            motion = table.fit_motion(rows, cols)
    return best


def _reverse_flag(key_a, key_b, table, i, j):
    """Whether B's stroke j runs opposite to A's stroke i (see :class:`Matching`)."""
    if not table.valid[i, j]:
        return False
    if key_a.loop[i] and key_b.loop[j]:
        return bool(best_cyclic_alignment(key_a.ring[i], key_b.ring[j])[1])
    return bool(table.reverse_open[i, j])


def _matching(key_a, key_b, table, rows, cols, motion, method, reason):
    costs = table.costs(motion)[rows, cols]
    return Matching(
        pairs=[(int(i), int(j), _reverse_flag(key_a, key_b, table, i, j)) for i, j in zip(rows, cols)],
        unmatched_a=sorted(set(range(key_a.count)) - {int(i) for i in rows}),
        unmatched_b=sorted(set(range(key_b.count)) - {int(j) for j in cols}),
        method=method,
        reason=reason,
        costs=[float(c) for c in costs],
        motion=np.asarray(motion, dtype=np.float64),
    )


def match_strokes(strokes_a, strokes_b, closed_a, closed_b, mode="auto"):
    """Pair the strokes of two keys.

    Parameters
    ----------
    strokes_a, strokes_b : sequence of array_like, each shape (n_i, 2)
        The strokes of each key in the drawing plane, in drawing order. A stroke may have one
        point, repeated points or no point at all; a stroke with no point is never paired by
        'auto'.
    closed_a, closed_b : array_like of bool, shape (S_a,), (S_b,)
        Cyclic flags.
    mode : {'auto', 'index'}
        'index' pairs stroke ``i`` with stroke ``i`` for ``i < min(S_a, S_b)`` (what Blender's
        interpolation does) and leaves the extra strokes unmatched. 'auto' does the same when
        the counts agree and the drawing order fits (every index pair costs less than
        ``MATCH_INDEX_MAX_COST`` and their total is within ``MATCH_INDEX_FACTOR`` of the
        optimal assignment's), which keeps the animator's order when it is right; otherwise it
        returns the optimal assignment, where no pair costs ``MATCH_MAX_COST`` or more.
        Either way each pair's direction is checked.

    Returns
    -------
    Matching

    Raises
    ------
    InvalidCurveError
        For a malformed stroke (named ``strokes_a[i]``), flags of the wrong length, or an
        unknown ``mode``.

    Notes
    -----
    The cost is described in the module notes. Work: ``O(S_a S_b m)`` for the costs (``m`` is
    ``MATCH_SAMPLES``, times ``m`` again for loop pairs' shifts), plus the assignment.

    Examples
    --------
    >>> import numpy as np
    >>> line = np.array([[0.0, 0.0], [1.0, 0.0]])
    >>> hook = np.array([[0.0, 1.0], [0.5, 1.5], [1.0, 1.0]])
    >>> m = match_strokes([line, hook], [hook[::-1], line], [False, False], [False, False])
    >>> m.pairs, m.method
    ([(0, 1, False), (1, 0, True)], 'assignment')
    """
    mode = check_option("mode", mode, MATCHINGS)
    m = MATCH_SAMPLES
    key_a = _Key(strokes_a, closed_a, "strokes_a", "closed_a", m)
    key_b = _Key(strokes_b, closed_b, "strokes_b", "closed_b", m)
    diagonals = [d for d in (key_a.diagonal, key_b.diagonal) if d > 0]
    table = _CostTable(key_a, key_b, min(diagonals) if diagonals else 1.0)
    n_a, n_b = key_a.count, key_b.count
    index = np.arange(min(n_a, n_b))

    if mode == "index":
        extra = f"; {abs(n_a - n_b)} extra stroke(s) of key {'A' if n_a > n_b else 'B'} unmatched" if n_a != n_b else ""
        motion = table.fit_motion(index, index)
        reason = f"paired by drawing order (mode 'index'){extra}"
        return _matching(key_a, key_b, table, index, index, motion, "index", reason)
    if n_a == n_b == 0:
        return _matching(key_a, key_b, table, index, index, np.zeros(2), "index", "neither key has strokes")

    total, rows, cols, motion = _best_assignment(table, key_a, key_b)
    if n_a != n_b:
        reason = f"stroke counts differ ({n_a} vs {n_b}): optimal assignment"
        return _matching(key_a, key_b, table, rows, cols, motion, "assignment", reason)

    return _order_or_assignment(key_a, key_b, table, total, rows, cols, motion)


def _order_or_assignment(key_a, key_b, table, total, rows, cols, motion):
    """Equal counts: the drawing order when it fits (see :func:`match_strokes`), else the assignment."""
    n_a, n_b = key_a.count, key_b.count
    index = np.arange(n_a)
    index_motion = table.fit_motion(index, index)
    if len(rows) == n_a and np.array_equal(np.sort(rows), index) and np.array_equal(cols[np.argsort(rows)], index):
        # The optimal assignment is the drawing order itself: keep it, however far strokes moved.
        reason = "same stroke count and the optimal assignment is the drawing order"
        return _matching(key_a, key_b, table, index, index, index_motion, "index", reason)
    index_costs = table.costs(index_motion)[index, index]
    worst = int(np.argmax(index_costs))
    index_total = _padded_total(index_costs, n_a, n_b)
    if index_costs[worst] >= MATCH_INDEX_MAX_COST:
        reason = (
            f"drawing order does not fit: stroke {worst} -> {worst} costs {index_costs[worst]:.3g} of the "
            f"drawing size (limit {MATCH_INDEX_MAX_COST:g}): optimal assignment"
        )
    elif index_total > MATCH_INDEX_FACTOR * total + MATCH_ROUNDOFF * n_a:
        reason = (
            f"drawing order costs {index_total:.3g} against {total:.3g} for the optimal assignment "
            f"(limit {MATCH_INDEX_FACTOR:g} times): optimal assignment"
        )
    else:
        reason = "same stroke count and the drawing order fits"
        return _matching(key_a, key_b, table, index, index, index_motion, "index", reason)
    return _matching(key_a, key_b, table, rows, cols, motion, "assignment", reason)
