"""Stroke matching: which stroke of one key morphs into which stroke of the other, and which way.

Two keys rarely list their strokes in the same order with the same count: the animator adds a
line, redraws an eye first, draws a loop the other way round, and between the keys the character
moves, turns and grows. Blender's own interpolation pairs strokes by index and drops the surplus;
:func:`match_strokes` keeps that pairing when it fits the drawings and otherwise solves an optimal
assignment on a cost that does not care how each stroke moved.

The cost of a pair
------------------
Every stroke is resampled to ``MATCH_SAMPLES`` points at uniform arc length (on its chords).
With complex coordinates and samples centred on their own centroid, the best similarity (turn and
scale) taking stroke ``i`` onto stroke ``j`` leaves the normalised residual

    e_ij = 1 - |<a_i, b_j>|^2 / (|a_i|^2 |b_j|^2)   (in [0, 1]: 0 when the shapes are similar),

minimised over B's direction (open strokes) or B's cyclic shift (loops, all at once by FFT). The
cost adds where the strokes lie and how their sizes differ, each relative to the strokes' *own*
sizes (``r``, the RMS distance of the samples from their centroid), once the keys' overall motion
``G`` (a similarity) is taken out:

    cost_ij = W_SHAPE sqrt(e_ij) + W_PLACE |G(c_i) - c_j| / (|G| r_i + r_j)
              + W_SCALE |log(r_j / (|G| r_i))| / log 4 + W_TURN |arg G| / pi
              (+ MATCH_CYCLIC_PENALTY if mixed).

So a stroke turned by any angle, scaled from 1/4 to 4 times or moved by a few of its own sizes
still pairs, and a small stroke is not paired with a big one across the drawing. ``G`` is found by
alternating (assign, fit ``G`` to the paired centroids) from a few starting guesses: no motion,
the shift of the keys' ink, the turn on which similar strokes' fits agree (found without pairing
them: a drawing turned far and redrawn in another order), and the drawing order's motion where
the order accounts for how the drawing moved.

Pairs near each other
---------------------
Most pairs of a drawing of many strokes could never be formed. At each motion the pairs whose
place term alone stays below ``MATCH_NEAR_COST`` are priced and solved first; the solve's dual
potentials certify it for every pair (``u_i + v_j`` at most what each pair left out costs), or
the strokes that break the certificate get all their pairs priced. Where that does not settle
a motion, every pair that may cost less than ``MATCH_MAX_COST`` is priced where those are few
(key A moved across key B), else the whole table (its open fits by matrix products, once: the
faster where most pairs may form, and the ones read from then on). Either way the assignment
is an optimal one of the whole table.

A drawing of thousands of strokes (a table of more than ``costs.MATCH_WHOLE_MOST`` pairs) is
never priced whole: each stroke gets a bounded list of candidates (:mod:`.candidates`), the
strokes the potentials do not certify are widened a few times (``MATCH_WIDENINGS``), the
solve walks the lists' entries only, and a motion whose costs say it cannot beat the best so
far is not solved. Memory and time then grow with the strokes, not their pairs; the assignment
is the optimal one among the candidates (the whole table's wherever certified).

Direction
---------
An open stroke of B runs the way in which more of its ends coincide with its partner's (a
shoulder stays put); then the way that fits with the smaller residual plus
``DIRECTION_TURN (turn / pi)^2``, the turn measured from the keys' overall turn ``arg G`` (a
reading that needs a half turn more than the drawing must fit clearly better); between equal
ones, the way it was drawn. A loop of B runs the other way when its orientation (the sign of
its area) differs.

Unmatched strokes
-----------------
A pair costing ``MATCH_MAX_COST`` or more is never formed by the assignment, except that a
stroke alone in both keys always pairs. The strokes it leaves over pair when their shapes agree,
however far they travel (:mod:`.travelling`; ``Matching.travelled``); the rest stay unmatched
(they appear or disappear, see :func:`~ballmorph_core.inbetween`).
"""

from dataclasses import dataclass, field

import numpy as np

from ...geometry.similarity import Similarity
from ...options import MATCHINGS, check_option
from ..strokes import as_written
from .certified import padded_total
from .costs import CostTable
from .descriptors import MATCH_SAMPLES, KeyDescriptors
from .motion_search import MATCH_ROUNDOFF, best_assignment
from .travelling import pair_leftovers

__all__ = ["Matching", "match_strokes", "pair_direction"]


#: 'auto' keeps the drawing order (pairing by index) when the counts agree, every index pair
#: costs less than MATCH_INDEX_MAX_COST, and the index pairing's total is within
#: MATCH_INDEX_FACTOR of the optimal assignment's.
MATCH_INDEX_MAX_COST = 0.75
MATCH_INDEX_FACTOR = 1.25


@dataclass
class Matching:
    """How the strokes of two keys are paired.

    Attributes
    ----------
    pairs : list of (int, int, bool)
        ``(i, j, reverse)``: stroke ``i`` of key A morphs into stroke ``j`` of key B, sorted by
        ``i``. ``reverse`` is True when B's stroke runs opposite to A's, so the caller reverses
        B's stroke before morphing.
    unmatched_a, unmatched_b : list of int
        Strokes with no partner, sorted.
    method : str
        ``'index'`` (paired by drawing order) or ``'assignment'`` (optimal assignment).
    reason : str
        Why, in a short sentence for the animator.
    costs : list of float
        The cost of each pair (see the module notes); ``inf`` for a pair involving a stroke
        with no points.
    drawing : Similarity
        The keys' overall motion: key B is about ``drawing(key A)``.
    travelled : list of (int, int)
        The pairs ``(i, j)`` made by the drawing's motion: left over by the assignment (too far
        apart for it), paired because their shapes agree (:mod:`.travelling`).
    priced : int
        The most pairs priced at one motion of the search (``S_a * S_b`` where the whole table
        was): above ``costs.MATCH_WHOLE_MOST`` pairs, at most ``MATCH_CANDIDATES_MOST`` per
        stroke of each key (:mod:`.candidates`), in practice a few dozen.
    """

    pairs: list
    unmatched_a: list
    unmatched_b: list
    method: str
    reason: str
    costs: list = field(default_factory=list)
    drawing: Similarity = field(default_factory=Similarity)
    travelled: list = field(default_factory=list)
    priced: int = 0


def _matching(key_a, key_b, table, rows, cols, motion, method, reason):
    costs = table.costs(*motion, rows, cols)
    order = np.argsort(rows, kind="stable")
    rows, cols, costs = rows[order], cols[order], costs[order]
    reverse = table.directions(float(np.angle(motion[0])), rows, cols) & table.valid(rows, cols)
    return Matching(
        pairs=[(int(i), int(j), bool(flip)) for i, j, flip in zip(rows, cols, reverse)],
        unmatched_a=sorted(set(range(key_a.count)) - {int(i) for i in rows}),
        unmatched_b=sorted(set(range(key_b.count)) - {int(j) for j in cols}),
        method=method,
        reason=reason,
        costs=[float(c) for c in costs],
        drawing=Similarity(complex(motion[0]), complex(motion[1])),
    )


def pair_direction(stroke_a, stroke_b, closed_a, closed_b, turn=0.0):
    """Whether the second stroke should run the other way to morph into the first (bool), by
    the rules of :func:`match_strokes` (a pair the caller formed, e.g. by hints)."""
    key_a = KeyDescriptors([stroke_a], [closed_a], "stroke_a", "closed_a", MATCH_SAMPLES)
    key_b = KeyDescriptors([stroke_b], [closed_b], "stroke_b", "closed_b", MATCH_SAMPLES)
    first = np.zeros(1, np.int64)
    return bool(CostTable(key_a, key_b).directions(turn, first, first)[0])


def match_strokes(strokes_a, strokes_b, closed_a, closed_b, mode="auto", motion=None):
    """Pair the strokes of two keys.

    Parameters
    ----------
    strokes_a, strokes_b : sequence of array_like, each shape (n_i, 2), or Ragged
        The strokes of each key in the drawing plane, in drawing order. A stroke may have one
        point, repeated points or no point at all; a stroke with no point is never paired by
        'auto'. A Ragged (its closed flags those of ``closed_a``, ``closed_b``) is read as it is.
    closed_a, closed_b : array_like of bool, shape (S_a,), (S_b,)
        Cyclic flags.
    mode : {'auto', 'index'}
        'index' pairs stroke ``i`` with stroke ``i`` for ``i < min(S_a, S_b)`` (what Blender's
        interpolation does) and leaves the extra strokes unmatched. 'auto' does the same when
        the counts agree and the drawing order fits (every index pair costs less than
        ``MATCH_INDEX_MAX_COST`` and their total is within ``MATCH_INDEX_FACTOR`` of the
        optimal assignment's), which keeps the animator's order when it is right; otherwise it
        returns the optimal assignment, where no pair costs ``MATCH_MAX_COST`` or more.
        Either way each pair's direction is chosen (see the module notes).
    motion : (complex, complex), optional
        A guess of the keys' overall motion ``z -> a z + b`` tried first, its turn the one
        motions are charged from (the animator's hints say how the drawing moves).

    Returns
    -------
    Matching

    Raises
    ------
    InvalidCurveError
        For a malformed stroke (named ``strokes_a[i]``), flags of the wrong length, or an
        unknown ``mode``.

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
    key_a = KeyDescriptors(strokes_a, closed_a, "strokes_a", "closed_a", MATCH_SAMPLES)
    key_b = KeyDescriptors(strokes_b, closed_b, "strokes_b", "closed_b", MATCH_SAMPLES)
    table = CostTable(key_a, key_b)
    if motion is not None and abs(motion[0]) > 0:
        table.prior_turn = motion[0] / abs(motion[0])
    n_a, n_b = key_a.count, key_b.count
    index = np.arange(min(n_a, n_b))
    if mode == "index":
        extra = f"; {abs(n_a - n_b)} extra stroke(s) of key {'A' if n_a > n_b else 'B'} unmatched" if n_a != n_b else ""
        motion = table.fit_motion(index, index)
        return _matching(
            key_a, key_b, table, index, index, motion, "index", f"paired by drawing order (mode 'index'){extra}"
        )
    if n_a == n_b == 0:
        return _matching(key_a, key_b, table, index, index, (1.0 + 0j, 0j), "index", "neither key has strokes")
    total, rows, cols, motion = best_assignment(table, key_a, key_b, motion)
    rows, cols, travelled = _with_travellers(key_a, key_b, table, rows, cols, motion)
    if n_a != n_b:
        reason = f"stroke counts differ ({n_a} vs {n_b}): optimal assignment"
        matching = _matching(key_a, key_b, table, rows, cols, motion, "assignment", reason)
    else:
        matching = _order_or_assignment(key_a, key_b, table, total, rows, cols, motion)
    # (The drawing order, when kept, may not be the pairs travelling made.)
    matching.travelled = sorted(set(travelled) & {(i, j) for i, j, _ in matching.pairs})
    matching.priced = table.priced_most
    return matching


def _with_travellers(key_a, key_b, table, rows, cols, motion):
    """The assignment's pairs and those :func:`.travelling.pair_leftovers` makes of the strokes it
    leaves over: rows, cols (shapes (K,)), and the new pairs (list of (int, int))."""
    left_a = np.setdiff1d(np.flatnonzero(key_a.valid), rows)
    left_b = np.setdiff1d(np.flatnonzero(key_b.valid), cols)
    new_a, new_b = pair_leftovers(table, motion, left_a, left_b, key_a.count == key_b.count)
    travelled = list(zip(new_a.tolist(), new_b.tolist()))
    return np.concatenate([rows, new_a]).astype(np.int64), np.concatenate([cols, new_b]).astype(np.int64), travelled


def _order_or_assignment(key_a, key_b, table, total, rows, cols, motion):
    """Equal counts: the drawing order when it fits (see :func:`match_strokes`), else the assignment."""
    n_a, n_b = key_a.count, key_b.count
    index = np.arange(n_a)
    index_motion = table.fit_motion(index, index)
    if len(rows) == n_a and np.array_equal(np.sort(rows), index) and np.array_equal(cols[np.argsort(rows)], index):
        # The optimal assignment is the drawing order itself: keep it, however far strokes moved.
        reason = "same stroke count and the optimal assignment is the drawing order"
        return _matching(key_a, key_b, table, index, index, motion, "index", reason)
    index_costs = table.costs(*index_motion, index, index)
    worst = int(np.argmax(index_costs))
    index_total = padded_total(index_costs, n_a, n_b)
    if index_costs[worst] >= MATCH_INDEX_MAX_COST:
        reason = (
            f"drawing order does not fit: stroke {as_written(worst)} -> {as_written(worst)} "
            f"costs {index_costs[worst]:.3g} "
            f"(limit {MATCH_INDEX_MAX_COST:g}): optimal assignment"
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
