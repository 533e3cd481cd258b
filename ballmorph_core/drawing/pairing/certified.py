"""The assignment of a cost table, solved on the pairs near each other first and certified by
the solve's dual potentials, else on every pair that may form (see :mod:`.matching`); a bounded
table's (``costs.MATCH_WHOLE_MOST``) on each stroke's bounded list of candidates, widened only
for the strokes the potentials do not certify (:mod:`.candidates`)."""

import numpy as np

from .assignment import solve_assignment
from .candidates import CandidateLists
from .costs import MATCH_MAX_COST

__all__ = ["assign_at", "padded_total"]


#: A motion's assignment is first solved on the pairs whose place term alone stays below this
#: (each stroke's neighbours), and kept when its dual potentials certify it.
MATCH_NEAR_COST = 0.1


#: ... and its strokes whose potentials do not certify it get all their pairs priced, while
#: they stay within this share of the strokes (beyond, the whole table is priced).
MATCH_NEAR_SHARE = 1 / 16


#: A bounded table's solve at one motion is made again, its uncertified strokes' candidates
#: widened, at most this many times; then it is the optimal one among the candidates (where
#: strokes crowd each other, as a guessed turn taking the drawing over itself).
MATCH_WIDENINGS = 2


#: ... and where they do not settle it, every pair that may cost less than MATCH_MAX_COST is
#: priced when those are at most this share of the table (else the whole table is, its open
#: fits by matrix products: the faster where more pairs may form).
MATCH_SPARSE_SHARE = 1 / 8


def _assign_within(costs):
    """Optimal pairs among those cheaper than MATCH_MAX_COST (rows, cols, each shape (K,))."""
    if not np.any(costs < MATCH_MAX_COST):
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    rows, cols = solve_assignment(np.minimum(costs, MATCH_MAX_COST))
    keep = costs[rows, cols] < MATCH_MAX_COST
    return rows[keep], cols[keep]


def assign_at(table, motion, beat=None):
    """Optimal pairs among those cheaper than MATCH_MAX_COST with key A moved by ``motion``
    (complex ``a, b``): rows, cols, each shape (K,); None when no matching at this motion
    totals less than ``beat`` (float).

    The pairs near each other are tried first (:func:`_assign_near`); where they do not settle
    the motion, the whole table is priced.
    """
    if table.bounded:
        return _assign_bounded(table, motion, beat)
    solved = _assign_near(table, motion, beat)
    if solved is not _UNSETTLED:
        return solved
    costs = table.costs(*motion)
    if beat is not None and _least_total(costs) >= beat:
        return None
    return _assign_within(costs)


#: What :func:`_assign_near` returns when the pairs near each other do not settle a motion.
_UNSETTLED = object()


def _assign_near(table, motion, beat=None):
    """:func:`assign_at` from the pairs near each other, or ``_UNSETTLED`` (the whole table is needed).

    The pairs whose place term alone stays below ``MATCH_NEAR_COST`` are priced, and their
    solve is the solve on every pair when its dual potentials certify it: ``u_i + v_j`` at
    most what each pair left out costs (:func:`~.assignment.solve_assignment`), so a solve on
    every pair would find nothing cheaper. The strokes whose potentials could break that get
    all their pairs priced, and the solve is made again: while they stay within
    ``MATCH_NEAR_SHARE`` of the strokes (beyond, each stroke's pairs are most of the table).
    Where the pairs near each other do not settle the motion: :func:`_assign_every`.
    """
    priced = table.priced(*motion, MATCH_NEAR_COST)
    most = MATCH_NEAR_SHARE * (len(priced.floor_a) + len(priced.floor_b))
    # A stroke of the smaller key (the solve's rows, whose potentials are at least their
    # pair's cost) with no pair priced below the floor breaks the certificate: where many
    # do, most pairs are needed anyway.
    cheapest = priced.cheapest()[0 if len(priced.floor_a) <= len(priced.floor_b) else 1]
    if np.count_nonzero(cheapest >= MATCH_NEAR_COST) <= most:
        solved = _settle(table, motion, priced, beat, most)
        if solved is not _UNSETTLED:
            return solved
    return _assign_every(table, motion, beat, len(priced.rows))


def _settle(table, motion, priced, beat, most):
    """The solve of the pairs ``priced`` (:class:`Priced`) at ``motion``, widened until its
    dual potentials certify it (see :func:`_assign_near`): rows, cols; None when no matching
    totals less than ``beat``; ``_UNSETTLED`` when more than ``most`` strokes would need all
    their pairs priced, or when none priced may form while others left out still may."""
    while True:
        if beat is not None and priced.least_total() >= beat:
            return None
        if not np.any(priced.costs < MATCH_MAX_COST):
            # Every pair that may form is priced (each left out has a stroke whose floor is
            # the limit) and none does: no pair.
            if np.all(priced.floor_a >= MATCH_MAX_COST) or np.all(priced.floor_b >= MATCH_MAX_COST):
                return np.zeros(0, np.int64), np.zeros(0, np.int64)
            return _UNSETTLED
        clipped = priced.table()
        rows, cols, u, v = solve_assignment(clipped, duals=True)
        wide_a, wide_b = priced.uncertified(u, v)
        if not (wide_a.any() or wide_b.any()):
            keep = clipped.at(rows, cols) < MATCH_MAX_COST
            return rows[keep], cols[keep]
        # Strokes already widened keep their pairs: only the new ones are searched.
        full = np.count_nonzero(priced.floor_a >= MATCH_MAX_COST) + np.count_nonzero(priced.floor_b >= MATCH_MAX_COST)
        if full + np.count_nonzero(wide_a) + np.count_nonzero(wide_b) > most:
            return _UNSETTLED
        priced = table.widened(priced, *motion, wide_a, wide_b)


def _assign_every(table, motion, beat=None, near=0):
    """:func:`assign_at` from every pair that may cost less than ``MATCH_MAX_COST`` (the
    others would be clipped to it: the solve is the whole table's, certified at once), where
    those are at most ``MATCH_SPARSE_SHARE`` of the table; else ``_UNSETTLED``. At a motion
    that takes the strokes far from their partners (a drawing moved across itself), few pairs
    may form.

    ``near`` (int): how many pairs :func:`_assign_near` found within ``MATCH_NEAR_COST``. A
    stroke's reach grows with the level, the pairs within it with its square: where that many
    would be most of the table, they are not listed (the benchmark's 400 open strokes: 96,000
    pairs, 47 ms to list, then priced whole anyway).
    """
    limit = MATCH_SPARSE_SHARE * len(table.ra) * len(table.rb)
    if near * (MATCH_MAX_COST / MATCH_NEAR_COST) ** 2 > limit:
        return _UNSETTLED
    rows, cols = table.near(*motion)
    if len(rows) > limit:
        return _UNSETTLED
    return _settle(table, motion, table.priced(*motion, MATCH_MAX_COST, (rows, cols)), beat, 0)


def _assign_bounded(table, motion, beat=None):
    """:func:`assign_at` for a bounded table: never laid out whole.

    Each stroke's candidates (:class:`~.candidates.CandidateLists`, from ``MATCH_NEAR_COST``)
    are priced, those of strokes with none below their floor widened first; then the solve on
    them is made again, the strokes whose potentials do not certify it widened
    (:func:`_unsafe`), until it is certified, or its uncertified strokes' lists are as long as
    they may be (then it is the optimal assignment among the candidates).
    """
    lists = CandidateLists(table, motion, MATCH_NEAR_COST)
    lists.widen_bare(beat)
    for widening in range(MATCH_WIDENINGS + 1):
        priced = lists.priced()
        if beat is not None and priced.least_total() >= beat:
            return None
        if not np.any(priced.costs < MATCH_MAX_COST):
            return np.zeros(0, np.int64), np.zeros(0, np.int64)
        clipped = priced.table()
        rows, cols, u, v = solve_assignment(clipped, duals=True, walk_entries=True)
        unsafe, needed = _unsafe(priced, u, v)
        # Widening one key's unsafe strokes prices every pair between the two sets: the fewer.
        sides = sorted((0, 1), key=lambda side: np.count_nonzero(unsafe[side]))
        if widening == MATCH_WIDENINGS or not (unsafe[0].any() and unsafe[1].any()):
            break
        if not any(lists.widen(s, unsafe[s], needed[s]) for s in sides):
            break
    keep = clipped.at(rows, cols) < MATCH_MAX_COST
    return rows[keep], cols[keep]


def _unsafe(priced, u, v):
    """The strokes whose pairs left out ``u``, ``v`` (a solve's potentials of :meth:`~.costs.Priced.table`,
    shapes (S_a,), (S_b,)) may not certify: masks, shapes (S_a,), (S_b,); and the floors that
    would make each stroke safe, shapes (S_a,), (S_b,).

    A pair left out costs at least the larger of its strokes' floors. A stroke of A with
    ``u_i + max v <= floor_i`` (the largest over B's strokes whose floors are below
    ``MATCH_MAX_COST``: the others' pairs are all priced) is safe: each of its pairs left out
    holds the certificate; so is a stroke of B the same way. A pair left out between two
    unsafe strokes may not hold it.
    """
    open_a, open_b = priced.floor_a < MATCH_MAX_COST, priced.floor_b < MATCH_MAX_COST
    top_u, top_v = float(u[open_a].max(initial=-np.inf)), float(v[open_b].max(initial=-np.inf))
    needed = u + top_v, v + top_u
    return (open_a & (needed[0] > priced.floor_a), open_b & (needed[1] > priced.floor_b)), needed


def padded_total(pair_costs, n_a, n_b):
    """Total of a matching with every unmatched stroke paying MATCH_MAX_COST / 2 (float)."""
    unmatched = n_a + n_b - 2 * len(pair_costs)
    return float(np.sum(pair_costs)) + 0.5 * MATCH_MAX_COST * unmatched


def _least_total(costs):
    """No matching at this motion totals less (float) than this (``costs`` the table, shape
    (S_a, S_b)): a pair's cost is split half to each of its strokes and an unmatched stroke
    pays MATCH_MAX_COST / 2, so each stroke pays at least half its cheapest pair, or that.
    (The table bounds the exact costs from below, and so does this the exact total.)"""
    # The least of each row and column, then clipped: the same values as the least of the
    # clipped table, without a copy of the (S_a, S_b) table.
    rows, cols = costs.min(axis=1, initial=MATCH_MAX_COST), costs.min(axis=0, initial=MATCH_MAX_COST)
    return 0.5 * (float(rows.sum()) + float(cols.sum()))
