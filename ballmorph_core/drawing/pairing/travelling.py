"""Strokes that travel far: the strokes the assignment leaves over, paired by their shapes.

The cost of :mod:`.matching` counts how far a stroke moves relative to its *own* size, once the
drawing's overall motion is taken out: a ball of radius 0.09 thrown 4.2 across an unchanged
landscape has moved some forty of its sizes, and no pair that far apart is formed. Yet once the
exact and confident pairs are made, what is left over says more than the distance: a ball
left in each key, a bird left in each key, are the same stroke gone somewhere else. So the
strokes left over are paired again on their shapes alone (the similarity-free fit, the size
change relative to the drawing's scale, a loop with an open stroke counting against), however
far they travel:

    cost_ij = W_SHAPE sqrt(e_ij) + W_SCALE |log(r_j / (|G| r_i))| / log 4  (+ MATCH_CYCLIC_PENALTY),

formed where the shapes agree (``sqrt(e_ij) <= TRAVEL_SHAPE_FIT`` and the size changes less
than ``TRAVEL_SCALE`` times the drawing's). Where exactly one stroke is left in each key and
the keys have as many strokes, the two pair whatever their shapes: a stroke alone in both keys
always pairs, and so does a stroke alone among what is left (nothing else can become it, and
a pop at the middle is the worst the animator can see).
"""

import numpy as np

from ... import tolerances as tol
from .assignment import solve_assignment

__all__ = ["TRAVEL_SCALE", "TRAVEL_SHAPE_FIT", "pair_leftovers"]

#: Leftover strokes' shapes agree (see ``tolerances.SHAPES_AGREE``).
TRAVEL_SHAPE_FIT = tol.SHAPES_AGREE
#: ... and the stroke grows or shrinks by less than this factor more than the drawing does.
TRAVEL_SCALE = 3.0


def pair_leftovers(table, motion, left_a, left_b, equal_counts):
    """Pairs among the strokes left over, by shape however far they travel.

    Parameters
    ----------
    table : costs.CostTable
        The pair costs of the two keys (its shape fits are made here for the leftovers' pairs).
    motion : (complex, complex)
        The drawing's overall motion ``z -> a z + b``: its scale is the one sizes compare at.
    left_a, left_b : ndarray of int, shape (L_a,), (L_b,)
        The strokes with points and no partner, of each key.
    equal_counts : bool
        Whether the keys have as many strokes (then one stroke left in each always pairs).

    Returns
    -------
    rows, cols : ndarray of int, shape (K,)
        The new pairs: stroke ``rows[k]`` of key A with stroke ``cols[k]`` of key B.
    """
    left_a, left_b = np.asarray(left_a, np.int64), np.asarray(left_b, np.int64)
    none = np.zeros(0, np.int64), np.zeros(0, np.int64)
    if not (len(left_a) and len(left_b)):
        return none
    if equal_counts and len(left_a) == len(left_b) == 1:
        return left_a, left_b
    rows, cols = np.repeat(left_a, len(left_b)), np.tile(left_b, len(left_a))
    # The cheap test first (sizes), the shape fits only for pairs it keeps.
    size = _size_change(table, motion, rows, cols)
    keep = size <= np.log(TRAVEL_SCALE)
    rows, cols = rows[keep], cols[keep]
    if not len(rows):
        return none
    shape = table.shapes(rows, cols)
    agree = shape <= TRAVEL_SHAPE_FIT
    rows, cols = rows[agree], cols[agree]
    cost = table.unplaced_costs(motion[0], rows, cols)
    if not len(rows):
        return none
    # The optimal assignment among the pairs that agree (the others cost more than any of them).
    ia, ra = np.unique(rows, return_inverse=True)
    ib, rb = np.unique(cols, return_inverse=True)
    worst = 2.0 * float(cost.max()) + 1.0
    grid = np.full((len(ia), len(ib)), worst)
    grid[ra, rb] = cost
    r, c = solve_assignment(grid)
    formed = grid[r, c] < worst
    return ia[r[formed]], ib[c[formed]]


def _size_change(table, motion, rows, cols):
    """``|log(r_j / (|a| r_i))|`` of pairs ``(rows[k], cols[k])``, shape (K,): how much more the
    stroke grows or shrinks than the drawing (0 between two dots; a dot with a stroke: inf)."""
    ra, rb = table.ra[rows] * max(abs(motion[0]), tol.TINY), table.rb[cols]
    dots = (ra <= 0) & (rb <= 0)
    with np.errstate(divide="ignore"):
        change = np.abs(np.log(np.maximum(rb, tol.TINY) / np.maximum(ra, tol.TINY)))
    return np.where(dots, 0.0, np.where((ra <= 0) | (rb <= 0), np.inf, change))
