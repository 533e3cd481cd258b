"""The cost of a stroke pair (shape, place, scale, turn, see :mod:`.matching`) priced for the
pairs that may form, and the direction rule of each pair."""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...geometry.guards import least, ratio
from ...geometry.ragged import budget_slices
from ...geometry.spatial import box_pairs
from .assignment import SparseCosts
from .descriptors import complex_samples, dot_spread
from .shape_fits import CHUNK, LoopFits, open_shapes, pair_shapes, shared_ends, sq_norms
from .symmetry import loop_reversals, unoriented

__all__ = ["CostTable", "Priced"]


#: Weights of the cost's shape, place and scale terms, and the cost at which a pair is never
#: formed. A similar shape moved by four of its own sizes and grown three times still pairs.
W_SHAPE, W_PLACE, W_SCALE = 1.5, 0.2, 0.3
MATCH_MAX_COST = 1.5


#: Added to the cost of a pair where one stroke is cyclic and the other is not.
MATCH_CYCLIC_PENALTY = 0.1


#: A direction whose fit needs a half turn must fit better than the other by this much of the
#: residual ``e`` (quadratic in the turn): a hook turned 170 degrees (``e`` 0.5 read backwards)
#: keeps its turn, an arch flipped about its chord (``e`` 0.33 read forward) is not a half turn.
DIRECTION_TURN = 0.45


#: Directions whose costs differ by less than this are equally good: the drawn one is kept.
DIRECTION_TIE = 1e-4


#: Cost of each pair per half turn of the keys' overall motion: between motions that fit
#: equally (a symmetric drawing), the one that turns less.
W_TURN = 0.1


#: Shape term of a dot paired with a stroke (it grows out of the dot or shrinks into it).
DOT_SHAPE = 0.5


#: A table of more pairs than this (two keys of about 256 strokes each) is *bounded*: never laid
#: out whole (no (S_a, S_b) array), its fits kept pair by pair, its motions solved on each
#: stroke's bounded list of candidates (:mod:`.candidates`). Up to it, the whole table may be
#: priced where most pairs may form (the faster there).
MATCH_WHOLE_MOST = 1 << 16


class _SparseFits:
    """The shape terms fitted so far of a bounded table, pair by pair (sorted pair codes): what
    a whole table's ``shape`` and ``_unfitted`` arrays say, for the pairs asked.

    Parameters
    ----------
    dot_a, dot_b : ndarray of bool, shape (S_a,), (S_b,)
        The dots of each key (their pairs' shape terms are fixed, never fitted).
    """

    def __init__(self, dot_a, dot_b):
        self.dot_a, self.dot_b = dot_a, dot_b
        self.code, self.value = np.zeros(0, np.int64), np.zeros(0)

    def _found(self, rows, cols):
        """Where pairs ``(rows[k], cols[k])`` sit among the codes, and whether they are there."""
        want = np.asarray(rows, np.int64) * len(self.dot_b) + cols
        at = np.minimum(np.searchsorted(self.code, want), max(len(self.code) - 1, 0))
        found = self.code[at] == want if len(self.code) else np.zeros(len(want), bool)
        return at, found

    def unfitted(self, rows, cols):
        """Whether each pair's shape term is still to fit, shape (K,)."""
        return ~(self.dot_a[rows] | self.dot_b[cols] | self._found(rows, cols)[1])

    def values(self, rows, cols):
        """Each pair's shape term (a dot's fixed one; 0 where not fitted), shape (K,)."""
        at, found = self._found(rows, cols)
        out = np.where(self.dot_a[rows] != self.dot_b[cols], DOT_SHAPE, 0.0)
        out[found] = self.value[at[found]]
        return out

    def store(self, rows, cols, values):
        """Keep the fitted terms ``values`` (shape (K,)) of pairs not stored yet."""
        code = np.concatenate([self.code, np.asarray(rows, np.int64) * len(self.dot_b) + cols])
        self.code, first = np.unique(code, return_index=True)
        self.value = np.concatenate([self.value, values])[first]


@dataclass
class Priced:
    """The pairs priced at one motion of key A, and what those left out cost at least.

    Attributes
    ----------
    rows, cols : ndarray of int, shape (K,)
        Pair ``k`` is stroke ``rows[k]`` of key A with stroke ``cols[k]`` of key B.
    costs : ndarray, shape (K,)
        Exact below ``MATCH_MAX_COST``, at least that elsewhere.
    size : tuple of int
        ``(S_a, S_b)``.
    floor_a, floor_b : ndarray, shape (S_a,), (S_b,)
        A pair left out costs at least the larger of its strokes' floors, at most
        ``MATCH_MAX_COST`` (a stroke's floor is that once all its pairs are priced that may
        cost less).
    """

    rows: np.ndarray
    cols: np.ndarray
    costs: np.ndarray
    size: tuple
    floor_a: np.ndarray
    floor_b: np.ndarray

    def table(self):
        """Every pair's cost clipped at ``MATCH_MAX_COST``, those left out at that, shape
        (S_a, S_b) (:class:`~.assignment.SparseCosts`): never below the clipped costs, equal
        to them on the pairs priced."""
        return SparseCosts(self.size, self.rows, self.cols, np.minimum(self.costs, MATCH_MAX_COST), MATCH_MAX_COST)

    def cheapest(self):
        """Each stroke's cheapest pair priced, clipped at its floor: never above its cheapest
        pair's cost clipped at ``MATCH_MAX_COST``; shapes (S_a,), (S_b,)."""
        out = []
        for side, floor in ((self.rows, self.floor_a), (self.cols, self.floor_b)):
            cheapest = floor.copy()
            np.minimum.at(cheapest, side, self.costs)
            out.append(cheapest)
        return out

    def least_total(self):
        """:func:`_least_total` of the whole table, from the pairs priced and the floors
        (float): never above it, so never above any matching's total at this motion."""
        cheapest_a, cheapest_b = self.cheapest()
        return 0.5 * (float(cheapest_a.sum()) + float(cheapest_b.sum()))

    def uncertified(self, u, v):
        """The strokes whose pairs must all be priced before potentials ``u``, ``v`` (shapes
        (S_a,), (S_b,)) of a solve of :meth:`table` can certify it: masks, shapes (S_a,),
        (S_b,), none when they do.

        The solve's potentials hold on its table (``u_i + v_j`` at most each entry), so they
        hold on every pair of a stroke whose pairs are all priced: those left out cost
        ``MATCH_MAX_COST`` or more, the table's entry. Between the other strokes, a pair
        left out costs at least ``level``, and a split ``u_i <= t``, ``v_j <= level - t``
        certifies every such pair: of a few splits, the one leaving the fewest strokes over
        their bound."""
        open_a, open_b = self.floor_a < MATCH_MAX_COST, self.floor_b < MATCH_MAX_COST
        if not (open_a.any() and open_b.any()):
            return np.zeros(len(u), bool), np.zeros(len(v), bool)
        level = float(min(self.floor_a[open_a].min(), self.floor_b[open_b].min()))
        top_u, top_v = float(u[open_a].max()), float(v[open_b].max())
        best = None
        for t in (0.5 * level, level - max(top_v, 0.0), max(top_u, 0.0)):
            over = (u > t) & open_a, (v > level - t) & open_b
            if best is None or over[0].sum() + over[1].sum() < best[0].sum() + best[1].sum():
                best = over
        return best


class CostTable:
    """Pair costs of two keys, for any overall motion (see the module notes).

    A pair's shape term (the fit of its samples, the bulk of a cost) is fitted only once a
    cost asked for may fall below ``MATCH_MAX_COST`` (the other terms alone say when it
    cannot): a pair never formed needs no exact cost. Costs come two ways: the pairs near
    each other (:meth:`priced`, each stroke's neighbours: what a drawing of many small strokes
    needs), or the whole table (:meth:`costs`; once asked for, every open pair is fitted at
    once by matrix products, the fastest where most pairs may be formed).

    Attributes
    ----------
    counts : tuple of int
        ``(S_a, S_b)``.
    bounded : bool
        Whether the table has more than ``MATCH_WHOLE_MOST`` pairs: then it is never laid out
        whole (``shape`` is None, :meth:`costs` needs pairs) and its fits are kept pair by pair.
    shape : ndarray, shape (S_a, S_b), or None
        ``sqrt(e_ij)``, the similarity-free shape difference; 0 where not fitted yet (None for
        a bounded table).
    whole : bool
        Whether the whole table's open fits are made (then they are the ones read).
    """

    def __init__(self, key_a, key_b):
        ca, cb = key_a.centroids(), key_b.centroids()
        self.ca, self.cb = complex_samples(ca), complex_samples(cb)
        self.ra, self.rb = key_a.sizes(), key_b.sizes()
        self._valid = key_a.valid, key_b.valid
        self._loop = key_a.loop, key_b.loop
        self.dot_spread = dot_spread(key_a, key_b)
        self.size = max(key_a.diagonal, key_b.diagonal)  # the drawing's, for the guards
        self._least = least(self.size)
        self.prior_turn = 1.0 + 0j  # the turn motions are charged from (the hints' when given)
        self.priced_most = 0  # the most pairs priced at one motion (see Matching.priced)
        self._open = key_a.open, key_b.open
        # The open reads centred: how every pair but two loops is fitted.
        self._centred = [
            complex_samples(k.open) - complex_samples(k.open.mean(axis=1))[:, None] for k in (key_a, key_b)
        ]
        self._norms = [sq_norms(c) for c in self._centred]
        dot_a, dot_b = self.ra <= 0, self.rb <= 0
        self.counts = key_a.count, key_b.count
        self.bounded = key_a.count * key_b.count > MATCH_WHOLE_MOST
        if self.bounded:
            # Too many pairs to lay out: the fits are kept pair by pair.
            self.shape, self._sparse = None, _SparseFits(dot_a, dot_b)
        else:
            self.shape = np.zeros((key_a.count, key_b.count))
            self.shape[dot_a[:, None] != dot_b[None, :]] = DOT_SHAPE
            # A dot's shape term is fixed; every other pair's is fitted when first needed.
            self._unfitted = ~(dot_a[:, None] | dot_b[None, :])
        self.whole, self._fits, self._turns = False, None, None
        self._signs = None  # the loops' areas' signs (0 for open strokes), when both keys have loops
        la, lb = np.flatnonzero(key_a.loop), np.flatnonzero(key_b.loop)
        if la.size and lb.size:
            ra = complex_samples(key_a.ring[la]) - self.ca[la, None]
            rb = complex_samples(key_b.ring[lb]) - self.cb[lb, None]
            # A loop drawn the other way (its area's sign) is read backwards before fitting; a
            # loop whose area cannot tell (a figure eight: the sign is round-off) as drawn.
            flat_a, flat_b = unoriented(key_a.areas()[la], self.ra[la]), unoriented(key_b.areas()[lb], self.rb[lb])
            sign_a = np.where(flat_a, 0.0, np.sign(key_a.areas()[la]))
            sign_b = np.where(flat_b, 0.0, np.sign(key_b.areas()[lb]))
            self._loop_fits = LoopFits(ra, rb, sign_a, sign_b)
            self._rings = ra, rb
            # Each stroke's row among the loops (-1 for open strokes).
            self._loop_row = np.full(key_a.count, -1), np.full(key_b.count, -1)
            self._loop_row[0][la], self._loop_row[1][lb] = np.arange(len(la)), np.arange(len(lb))
            self._signs = np.zeros(key_a.count), np.zeros(key_b.count)
            self._signs[0][la], self._signs[1][lb] = sign_a, sign_b

    @property
    def valid_strokes(self):
        """Which strokes of each key have points: masks, shapes (S_a,), (S_b,)."""
        return self._valid

    def valid(self, rows, cols):
        """Whether both strokes of pairs ``(rows[k], cols[k])`` have points, shape (K,)."""
        return self._valid[0][rows] & self._valid[1][cols]

    def _fit_whole(self):
        """Fit every open (and mixed) pair at once, by matrix products (once); never for a
        bounded table."""
        if self.whole:
            return
        if self.bounded:
            raise RuntimeError(f"a table of {self.counts[0]} x {self.counts[1]} strokes is never laid out whole")
        self.whole = True
        n_a, n_b = self.shape.shape
        if self._loop[0].all() and self._loop[1].all():
            # Every pair is a loop pair: its shape is its loop fit (or a dot's), its direction
            # its loops' orientations; the open reads' fits would never be read.
            e_f = e_r = turn_f = turn_r = np.zeros((n_a, n_b))
        else:
            e_f, e_r, turn_f, turn_r = open_shapes(*self._centred)
        self._fits, self._turns = (e_f, e_r), (turn_f, turn_r)
        loops = self._loop[0][:, None] & self._loop[1][None, :]
        shape = np.minimum(e_f, e_r)
        np.sqrt(shape, out=shape)
        # Every pair but two loops' and a dot's (its shape term is fixed).
        np.copyto(self.shape, shape, where=~(loops | (self.ra[:, None] <= 0) | (self.rb[None, :] <= 0)))
        self._unfitted &= loops

    def _pair_fits(self, rows, cols):
        """Open fits of pairs ``(rows[k], cols[k])`` (shapes (K,)): ``e_fwd, e_rev, turn_fwd,
        turn_rev``, shapes (K,), the whole table's where it is fitted."""
        if self.whole:
            return (*(e[rows, cols] for e in self._fits), *(t[rows, cols] for t in self._turns))
        (a, b), (na, nb), out = self._centred, self._norms, np.empty((4, len(rows)))
        for sl in budget_slices(np.full(len(rows), a.shape[1]), CHUNK):
            i, j = rows[sl], cols[sl]
            out[:, sl] = pair_shapes(np.take(a, i, axis=0), np.take(b, j, axis=0), na[i], nb[j])
        return tuple(out)

    def _fit(self, rows, cols):
        """Fit the pairs ``(rows[k], cols[k])`` (shapes (K,)) not fitted yet: two loops by their
        loop fit, any other pair by its open reads."""
        todo = self._unfitted_at(rows, cols)
        if not todo.any():
            return
        rows, cols = rows[todo], cols[todo]
        loops = self._loop[0][rows] & self._loop[1][cols]
        e = np.empty(len(rows))
        if loops.any():
            e[loops] = self._loop_fits.residuals(self._loop_row[0][rows[loops]], self._loop_row[1][cols[loops]])
        if not loops.all():
            e_f, e_r = self._pair_fits(rows[~loops], cols[~loops])[:2]
            e[~loops] = np.minimum(e_f, e_r)
        if self.bounded:
            self._sparse.store(rows, cols, np.sqrt(e))
            return
        self.shape[rows, cols] = np.sqrt(e)
        self._unfitted[rows, cols] = False

    def _unfitted_at(self, rows, cols):
        """Whether the shape terms of pairs ``(rows[k], cols[k])`` are still to fit, shape (K,)."""
        return self._sparse.unfitted(rows, cols) if self.bounded else self._unfitted[rows, cols]

    def _shape_at(self, rows, cols):
        """The shape terms of pairs ``(rows[k], cols[k])`` as they are (0 where not fitted), shape (K,)."""
        return self._sparse.values(rows, cols) if self.bounded else self.shape[rows, cols]

    def shapes(self, rows, cols):
        """``sqrt(e)`` of pairs ``(rows[k], cols[k])`` (shapes (K,)), fitted where not yet, shape (K,)."""
        self._fit(rows, cols)
        return self._shape_at(rows, cols)

    def unplaced_costs(self, a, rows, cols):
        """Costs of pairs ``(rows[k], cols[k])`` (shapes (K,)) without the place and turn terms,
        sizes compared at the scale of ``a`` (complex), shape (K,): how well their shapes agree
        wherever they are (:mod:`.travelling`)."""
        return self._costs(a, 0j, rows, cols, placed=False)

    def directions(self, turn, rows, cols):
        """Whether B's stroke runs opposite to A's in pairs ``(rows[k], cols[k])`` (shapes (K,)),
        given the drawing's turn (radians), shape (K,): the direction sharing more ends; then the
        better fit, a turn away from the drawing's counting against it; then the drawn direction
        (always, next to a dot)."""
        e_f, e_r, *turns = self._pair_fits(rows, cols)
        away = [np.angle(np.exp(1j * (t - turn))) / np.pi for t in turns]
        cost_f, cost_r = e_f + DIRECTION_TURN * away[0] ** 2, e_r + DIRECTION_TURN * away[1] ** 2
        reverse = cost_r < cost_f - DIRECTION_TIE
        open_a, open_b = self._open
        shared_f, shared_r = shared_ends(open_a[rows], open_b[cols], self.ra[rows] + self.rb[cols])
        reverse = np.where(shared_f > shared_r, False, np.where(shared_r > shared_f, True, reverse))
        if self._signs is not None:
            sign_a, sign_b = self._signs[0][rows], self._signs[1][cols]
            loops = self._loop[0][rows] & self._loop[1][cols]
            reverse[loops] = (sign_a * sign_b < 0)[loops]
            # Where an area cannot tell (a zero sign), the smallest turn the fits allow does.
            flat = loops & ((sign_a == 0) | (sign_b == 0))
            if flat.any():
                i, j = self._loop_row[0][rows[flat]], self._loop_row[1][cols[flat]]
                ring_a, ring_b = self._rings
                reverse[flat] = loop_reversals(ring_a[i], ring_b[j], turn, DIRECTION_TURN, DIRECTION_TIE)
        # A dot has no direction: its partner keeps the one it was drawn in.
        return reverse & (self.ra[rows] > 0) & (self.rb[cols] > 0)

    def near(self, a, b, level=MATCH_MAX_COST, only_a=None, only_b=None):
        """The pairs whose place term alone stays below the cost ``level`` with key A moved by
        ``z -> a z + b`` (complex), and perhaps a few more: ``rows, cols``, shapes (K,), sorted
        by row then column. Only the strokes of masks ``only_a``, ``only_b`` (shapes (S_a,),
        (S_b,)) when given; strokes with no points are left out (their pairs cost inf).

        The place term is at least ``level`` once the centroids are ``level / W_PLACE`` spreads
        apart, and a pair's spread ``max(|a| r_i + r_j, dot_spread)`` is at most the sum of the
        strokes' halves ``max(|a| r_i, dot_spread / 2) + max(r_j, dot_spread / 2)``: boxes of
        those half-widths (grown by margins far above the round-off) around the moved
        centroids of A and the centroids of B overlap for every pair that may cost less."""
        moved = a * self.ca + b
        ia, ib = (np.flatnonzero(v if k is None else v & k) for v, k in zip(self._valid, (only_a, only_b)))
        za, zb = moved[ia], self.cb[ib]
        scale, half_dot, reach = max(abs(a), tol.TINY), 0.5 * self.dot_spread, level / W_PLACE * (1.0 + 1e-6)
        # Round-off of the centroids' coordinates, far below any half-width that matters.
        slack = 1e-12 * max(np.abs(za).max(initial=0.0), np.abs(zb).max(initial=0.0))
        half_a = reach * np.maximum(scale * self.ra[ia], half_dot) + slack
        half_b = reach * np.maximum(self.rb[ib], half_dot) + slack
        boxes = [(z.real - h, z.imag - h, z.real + h, z.imag + h) for z, h in ((za, half_a), (zb, half_b))]
        i, j = box_pairs(*boxes)
        return ia[i], ib[j]

    def turn_term(self, a):
        """The cost every pair pays for the turn of ``a`` (complex) from the prior turn (float)."""
        return W_TURN * abs(np.angle(a * np.conj(self.prior_turn))) / np.pi

    def place_terms(self, a, b, rows, cols):
        """The place terms of pairs ``(rows[k], cols[k])`` (shapes (K,)) with key A moved by
        ``z -> a z + b`` (complex), shape (K,): each pair's cost is at least its term (the
        same operations as :meth:`costs`, whose other terms are not negative)."""
        scale = max(abs(a), tol.TINY)
        spread = np.add(scale * self.ra[rows], self.rb[cols])
        np.maximum(spread, self.dot_spread, out=spread)
        place = np.abs((a * self.ca + b)[rows] - self.cb[cols])
        place /= spread
        place *= W_PLACE
        return place

    def priced(self, a, b, level, pairs=None):
        """The pairs that may cost less than ``level`` (at most ``MATCH_MAX_COST``) with key A
        moved by ``z -> a z + b`` (complex), and their costs (:class:`Priced`); ``pairs``:
        those pairs, ``(rows, cols)`` as :meth:`near` gives them, when already found."""
        level = min(level, MATCH_MAX_COST)
        rows, cols = self.near(a, b, level) if pairs is None else pairs
        floors = np.full(len(self.ra), level), np.full(len(self.rb), level)
        self.priced_most = max(self.priced_most, len(rows))
        return Priced(rows, cols, self.costs(a, b, rows, cols, exact=False), self.counts, *floors)

    def widened(self, priced, a, b, wide_a, wide_b):
        """``priced`` (at motion ``z -> a z + b``) and every pair of the strokes of masks
        ``wide_a``, ``wide_b`` (shapes (S_a,), (S_b,)) that may cost less than
        ``MATCH_MAX_COST`` (:class:`Priced`)."""
        n_b = len(self.rb)
        runs = self.near(a, b, only_a=wide_a), self.near(a, b, only_b=wide_b)
        code = np.concatenate([i * n_b + j for i, j in runs])
        code = np.setdiff1d(code, priced.rows * n_b + priced.cols)
        rows, cols = code // n_b, code % n_b
        self.priced_most = max(self.priced_most, len(priced.rows) + len(rows))
        return Priced(
            np.concatenate([priced.rows, rows]),
            np.concatenate([priced.cols, cols]),
            np.concatenate([priced.costs, self.costs(a, b, rows, cols, exact=False)]),
            priced.size,
            np.where(wide_a, MATCH_MAX_COST, priced.floor_a),
            np.where(wide_b, MATCH_MAX_COST, priced.floor_b),
        )

    def costs(self, a, b, rows=None, cols=None, exact=True):
        """Pair costs with key A moved by ``z -> a z + b`` (complex), shape (S_a, S_b): exact
        where below ``MATCH_MAX_COST``, elsewhere at least that (those of pairs not fitted,
        bounds from the other terms); with ``rows`` and ``cols`` (shapes (K,)) the costs of
        pairs ``(rows[k], cols[k])`` only, shape (K,), exact (or, with ``exact_fit`` False, as
        the whole table's). Elementwise: a pair's cost is the same whichever pairs are asked,
        once the whole table's open fits are made (:meth:`_fit_whole`, which the whole table
        makes).

        A cost with its shape term left out is a bound of the cost: the term is not negative
        and every rounded sum after it grows with it."""
        if rows is not None and exact:
            self._fit(rows, cols)
            return self._costs(a, b, rows, cols)
        if rows is None:
            self._fit_whole()
            self.priced_most = self.ra.size * self.rb.size
        c = self._costs(a, b, rows, cols)
        # The pairs whose bound may fall below the limit: fitted, then priced exactly.
        may = (self._unfitted if rows is None else self._unfitted_at(rows, cols)) & (c < MATCH_MAX_COST)
        if may.any():
            fit = np.nonzero(may) if rows is None else (rows[may], cols[may])
            self._fit(*fit)
            c[may] = self._costs(a, b, *fit)
        return c

    def _costs(self, a, b, rows=None, cols=None, placed=True):
        """:meth:`costs` from the shape terms as they are (fitted or not); without the place and
        turn terms unless ``placed``."""
        scale = max(abs(a), tol.TINY)
        moved = a * self.ca + b
        if rows is None:
            ra, rb, za, zb = self.ra[:, None], self.rb[None, :], moved[:, None], self.cb[None, :]
            shape = self.shape
            (loop_a, loop_b), (valid_a, valid_b) = ((f[0][:, None], f[1][None, :]) for f in (self._loop, self._valid))
        else:
            ra, rb, za, zb = self.ra[rows], self.rb[cols], moved[rows], self.cb[cols]
            shape = self._shape_at(rows, cols)
            (loop_a, loop_b), (valid_a, valid_b) = ((f[0][rows], f[1][cols]) for f in (self._loop, self._valid))
        mixed, valid = loop_a != loop_b, valid_a & valid_b
        # The terms of the module notes, each full-size result worked on in place (the same
        # operations in the same order as the plain formula: a drawing of thousands of strokes
        # holds three (S_a, S_b) arrays here instead of a dozen).
        near = scale * ra
        spread = np.add(near, rb)
        np.maximum(spread, self.dot_spread, out=spread)
        place = np.abs(za - zb)
        place /= spread
        # The ratio (1 where a stroke is a dot: that term is 0 then).
        size = np.divide(rb, near, out=np.ones_like(spread), where=(near > self._least) & (rb > self._least))
        np.log(size, out=size)
        np.abs(size, out=size)
        size /= np.log(4.0)
        np.copyto(size, 0.0, where=~((ra > 0) & (rb > 0)))
        c = np.multiply(shape, W_SHAPE)
        if placed:
            place *= W_PLACE
            c += place
        size *= W_SCALE
        c += size
        # + MATCH_CYCLIC_PENALTY * mixed: the others add 0.0, which leaves these sums of terms
        # that are not negative as they are.
        np.add(c, MATCH_CYCLIC_PENALTY, out=c, where=mixed)
        if placed:
            c += self.turn_term(a)
        np.copyto(c, np.inf, where=~valid)
        return c

    def fit_motion(self, rows, cols):
        """Least-squares similarity of the paired centroids (weighted by size): ``(a, b)`` complex."""
        keep = self.valid(rows, cols)
        rows, cols = rows[keep], cols[keep]
        if not len(rows):
            return 1.0 + 0j, 0j
        w = np.maximum(self.ra[rows] + self.rb[cols], tol.TINY)
        za, zb = self.ca[rows], self.cb[cols]
        ma, mb = np.sum(w * za) / w.sum(), np.sum(w * zb) / w.sum()
        if len(rows) < 2:
            return 1.0 + 0j, mb - ma
        da, db = za - ma, zb - mb
        # Centroids of A that do not spread (at the keys' size) fix no turn nor scale.
        spread = np.sum(w * np.abs(da) ** 2)
        a = complex(ratio(np.sum(w * np.conj(da) * db), spread, least(self.size, 2) * w.sum(), 1.0 + 0j))
        return a, mb - a * ma

    def explained(self, rows, cols, motion):
        """The share of the spread of B's paired centroids that ``motion`` (complex ``a, b``)
        accounts for: 1 - (weighted squared misses of A's moved centroids) / (weighted squared
        distances of B's from their mean), weighted as :meth:`fit_motion`; 1 when they do not
        spread (float)."""
        keep = self.valid(rows, cols)
        rows, cols = rows[keep], cols[keep]
        w = np.maximum(self.ra[rows] + self.rb[cols], tol.TINY)
        zb = self.cb[cols]
        spread = np.sum(w * np.abs(zb - np.sum(w * zb) / max(w.sum(), tol.TINY)) ** 2)
        misses = np.sum(w * np.abs(motion[0] * self.ca[rows] + motion[1] - zb) ** 2)
        return 1.0 - ratio(misses, spread, least(self.size, 2) * w.sum(), 0.0)
