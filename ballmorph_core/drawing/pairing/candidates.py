"""Bounded candidate lists: the pairs a bounded table prices at one motion (see :mod:`.certified`).

A drawing of thousands of strokes is never priced whole (``costs.MATCH_WHOLE_MOST``). At each
motion every stroke gets a list of its nearest pairs by place term, below its own *level* and at
most its own *length*; a pair left out of both its strokes' lists costs at least the larger of
their *floors* (a stroke's level, or the place term of the first pair its list left out). Only
the strokes whose floors leave the solve uncertified are searched again, wider: their level
times ``MATCH_LEVEL_GROWTH`` (up to ``MATCH_MAX_COST``, where a floor proves every pair left out
unformable) and their length doubled, up to ``MATCH_CANDIDATES_MOST``. So a motion prices at
most ``MATCH_CANDIDATES_MOST`` pairs per stroke of each key, however many strokes crowd together.
"""

import numpy as np

from ... import tolerances as tol
from ...geometry.spatial import box_pair_chunks
from .costs import MATCH_MAX_COST, W_PLACE, Priced

__all__ = ["MATCH_CANDIDATES", "MATCH_CANDIDATES_MOST", "MATCH_LEVEL_GROWTH", "MATCH_LEVEL_MARGIN", "CandidateLists"]


#: The length of a stroke's first list of candidates (its nearest pairs below the first level).
MATCH_CANDIDATES = 16

#: A widened stroke's level grows this many times (up to MATCH_MAX_COST), its list's length twice.
MATCH_LEVEL_GROWTH = 2.0

#: ... and to this many times the floor its certificate needs, where more than that.
MATCH_LEVEL_MARGIN = 1.25

#: The longest list of candidates of a stroke: a stroke whose list is that long and still leaves
#: the solve uncertified keeps it (the solve is then the optimal one among the candidates).
MATCH_CANDIDATES_MOST = 128


def _nearest_per_stroke(owner, place, most):
    """Of entries owned by strokes ``owner`` (shape (K,)) with place terms ``place`` (shape
    (K,)), the ``most[owner]`` smallest of each stroke (mask, shape (K,)), and for the entries
    just past each list (mask, shape (K,)): the first one left out."""
    order = np.lexsort((place, owner))
    owner_sorted = owner[order]
    start = np.r_[0, np.flatnonzero(owner_sorted[1:] != owner_sorted[:-1]) + 1]
    rank = np.arange(len(order)) - np.repeat(start, np.diff(np.r_[start, len(order)]))
    keep, first_out = np.zeros(len(order), bool), np.zeros(len(order), bool)
    keep[order] = rank < most[owner_sorted]
    first_out[order] = rank == most[owner_sorted]
    return keep, first_out


class CandidateLists:
    """The candidate lists of a bounded table at one motion, widened stroke by stroke.

    Parameters
    ----------
    table : costs.CostTable
    motion : (complex, complex)
        Key A moved by ``z -> a z + b``.
    level : float
        Every stroke's first level (its list holds pairs whose place term is below it).

    Attributes
    ----------
    levels, lengths, floors : list of two ndarray, shapes (S_a,), (S_b,)
        Each stroke's level, its list's longest length and its floor (``MATCH_MAX_COST`` for a
        stroke with no points: its pairs cost inf).
    rows, cols, costs : ndarray, shape (K,)
        The pairs priced (each once) and their costs (``CostTable.costs``, ``exact=False``).
    """

    def __init__(self, table, motion, level):
        self.table, self.motion = table, motion
        self.turn = table.turn_term(motion[0])
        counts = len(table.ra), len(table.rb)
        valid = table.valid_strokes
        self.levels = [np.where(v, min(level, MATCH_MAX_COST), MATCH_MAX_COST) for v in valid]
        self.lengths = [np.full(n, MATCH_CANDIDATES) for n in counts]
        self.floors = [np.full(n, MATCH_MAX_COST) for n in counts]
        self.rows, self.cols, self.costs = np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
        for side in (0, 1):
            self._search(side, np.flatnonzero(valid[side]))

    def priced(self):
        """The pairs priced and the floors (:class:`~.costs.Priced`)."""
        counts = len(self.floors[0]), len(self.floors[1])
        return Priced(self.rows, self.cols, self.costs, counts, *self.floors)

    def widenable(self, side):
        """Which strokes of key ``side`` (0 for A) a wider search may raise the floor of, shape (S,)."""
        floors, levels = self.floors[side], self.levels[side]
        truncated = floors < np.minimum(levels + self.turn, MATCH_MAX_COST)
        longer = truncated & (self.lengths[side] < MATCH_CANDIDATES_MOST)
        return (floors < MATCH_MAX_COST) & ((levels < MATCH_MAX_COST) | longer)

    def widen(self, side, strokes, needed=None):
        """Search the strokes ``strokes`` (mask, shape (S,)) of key ``side`` again, wider (see
        the module notes), at least up to the levels ``needed`` (shape (S,)) where given (with
        ``MATCH_LEVEL_MARGIN``); returns whether any could be (bool)."""
        strokes = np.flatnonzero(strokes & self.widenable(side))
        if not len(strokes):
            return False
        level = self.levels[side][strokes] * MATCH_LEVEL_GROWTH
        if needed is not None:
            level = np.maximum(level, (needed[strokes] - self.turn) * MATCH_LEVEL_MARGIN)
        self.levels[side][strokes] = np.minimum(level, MATCH_MAX_COST)
        self.lengths[side][strokes] = np.minimum(self.lengths[side][strokes] * 2, MATCH_CANDIDATES_MOST)
        self._search(side, strokes)
        return True

    def widen_bare(self, beat=None):
        """Widen the strokes that have no pair priced below their floor until they have one or
        cannot be widened (nothing to solve for them before), or until the pairs priced say no
        matching at this motion totals less than ``beat`` (float)."""
        while True:
            priced = self.priced()
            if beat is not None and priced.least_total() >= beat:
                return
            cheapest = priced.cheapest()
            bare = [(c >= f) for c, f in zip(cheapest, self.floors)]
            if not (self.widen(0, bare[0]) | self.widen(1, bare[1])):
                return

    def _search(self, side, strokes):
        """List the pairs of ``strokes`` (indices into key ``side``) at their levels and lengths:
        price the new ones, set the strokes' floors."""
        table, (a, b) = self.table, self.motion
        rows, cols, place = self._within(side, strokes)
        own = rows if side == 0 else cols
        keep, first_out = _nearest_per_stroke(own, place, self.lengths[side])
        floors = self.levels[side].copy()
        floors[own[first_out]] = place[first_out]
        # Every cost at this motion adds the turn term to its place term (and more, not negative).
        self.floors[side][strokes] = np.minimum(floors[strokes] + self.turn, MATCH_MAX_COST)
        rows, cols = rows[keep], cols[keep]
        n_b = len(table.rb)
        code = np.setdiff1d(rows * n_b + cols, self.rows * n_b + self.cols)
        rows, cols = code // n_b, code % n_b
        self.rows, self.cols = np.concatenate([self.rows, rows]), np.concatenate([self.cols, cols])
        self.costs = np.concatenate([self.costs, table.costs(a, b, rows, cols, exact=False)])
        table.priced_most = max(table.priced_most, len(self.rows))

    def _within(self, side, strokes):
        """The pairs of ``strokes`` of key ``side`` whose place terms are below the strokes'
        levels: rows, cols (A's and B's strokes), place terms, shapes (K,). The boxes of
        :meth:`~.costs.CostTable.near`, each stroke's grown by its own level (the other key's
        by the largest), are searched in runs: a run's pairs are cut to the strokes' lengths
        before the next (memory: the runs' budget and the lists, whatever crowds)."""
        table, (a, b) = self.table, self.motion
        moved = [a * table.ca + b, table.cb]
        spreads = [max(abs(a), tol.TINY) * table.ra, table.rb]
        levels = self.levels[side][strokes]
        other = np.flatnonzero(table.valid_strokes[1 - side])
        half_dot = 0.5 * table.dot_spread
        every = np.concatenate([moved[0], moved[1]])
        slack = 1e-12 * float(np.abs(every).max(initial=0.0))
        boxes = []
        for index, reach in ((strokes, levels), (other, np.full(len(other), levels.max(initial=0.0)))):
            s = side if index is strokes else 1 - side
            z = moved[s][index]
            half = reach / W_PLACE * (1.0 + 1e-6) * np.maximum(spreads[s][index], half_dot) + slack
            boxes.append((z.real - half, z.imag - half, z.real + half, z.imag + half))
        out = []
        for i, j in box_pair_chunks(*boxes):
            own, far = strokes[i], other[j]
            rows, cols = (own, far) if side == 0 else (far, own)
            place = table.place_terms(a, b, rows, cols)
            near = place < self.levels[side][own]
            rows, cols, place, own = rows[near], cols[near], place[near], own[near]
            # Cut each stroke's pairs to its length (and the first left out, for its floor).
            keep, first_out = _nearest_per_stroke(own, place, self.lengths[side] + 1)
            out.append((rows[keep], cols[keep], place[keep]))
        if not out:
            return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
        return tuple(np.concatenate(parts) for parts in zip(*out))
