"""A bounded table (issue 41): matching thousands of strokes prices a bounded list of candidates
per stroke, never the whole table, and pairs as the whole table does."""

import bench_drawings
import numpy as np
import pytest

from ballmorph_core.drawing.pairing import candidates, certified, costs
from ballmorph_core.drawing.pairing.assignment import SparseCosts, solve_assignment
from ballmorph_core.drawing.pairing.descriptors import MATCH_SAMPLES, KeyDescriptors
from ballmorph_core.drawing.pairing.matching import match_strokes


def test_two_thousand_strokes_price_a_bounded_list_per_stroke(monkeypatch):
    # The benchmark's moving drawing at 2,000 strokes: no (S_a, S_b) array is made, and no
    # motion prices more than a few pairs per stroke (2.8 here; the whole table: 2,000).
    key_a, key_b = bench_drawings.make_keys("open", 2000, 20)
    monkeypatch.setattr(costs.CostTable, "_fit_whole", lambda table: pytest.fail("the whole table was fitted"))
    flags = [False] * 2000
    m = match_strokes(key_a, key_b, flags, flags)
    assert m.pairs == [(i, i, False) for i in range(2000)]
    assert 2000 * 2000 > costs.MATCH_WHOLE_MOST
    assert 0 < m.priced <= candidates.MATCH_CANDIDATES_MOST * (2000 + 2000)
    assert m.priced / 2000 <= 16, m.priced


@pytest.mark.parametrize("seed", range(4))
def test_the_bounded_search_pairs_as_the_whole_table(seed, monkeypatch):
    # Reordered hatch lines, moved: forced through the bounded path (every table bounded), the
    # pairs are the ones the whole-table path makes.
    a, b, perm = bench_drawings.reordered_hatching(150, seed)
    b = [s + [0.05 * seed, -0.03] for s in b]
    flags = [False] * 150
    whole = match_strokes(a, b, flags, flags)
    monkeypatch.setattr(costs, "MATCH_WHOLE_MOST", 0)
    bounded = match_strokes(a, b, flags, flags)
    assert bounded.pairs == whole.pairs == sorted((int(p), j, False) for j, p in enumerate(perm))
    assert bounded.priced < 150 * 150 / 4


def test_walking_the_entries_solves_as_the_dense_table():
    # The sparse search (each row's entries only, the fill's columns as one) finds an optimal
    # assignment with potentials that certify it on the whole table.
    rng = np.random.default_rng(0)
    for _ in range(200):
        n_rows, n_cols = (int(k) for k in rng.integers(1, 25, 2))
        rows, cols = np.nonzero(rng.random((n_rows, n_cols)) < rng.uniform(0.05, 0.9))
        values = np.round(rng.uniform(0.0, 1.5, len(rows)), int(rng.integers(1, 4)))
        dense = np.full((n_rows, n_cols), 1.5)
        dense[rows, cols] = values
        r, c, u, v = solve_assignment(SparseCosts((n_rows, n_cols), rows, cols, values, 1.5), True, True)
        want = solve_assignment(dense)
        assert dense[r, c].sum() == pytest.approx(dense[want].sum(), abs=1e-9)
        assert len(set(c.tolist())) == len(c) == min(n_rows, n_cols)
        assert np.all(u[:, None] + v[None, :] <= dense + 1e-9)
        np.testing.assert_allclose(u[r] + v[c], dense[r, c], atol=1e-9)


def test_a_widened_stroke_floor_bounds_every_pair_left_out():
    # Each stroke's floor is at most the cost of every pair its list and its partner's left out.
    a, b, _ = bench_drawings.reordered_hatching(300, 5)
    flags = [False] * 300
    keys = [KeyDescriptors(k, flags, "k", "c", MATCH_SAMPLES) for k in (a, b)]
    table = costs.CostTable(*keys)
    motion = (np.exp(0.3j), 0.4 + 0.2j)
    lists = candidates.CandidateLists(table, motion, certified.MATCH_NEAR_COST)
    lists.widen(0, np.arange(300) % 3 == 0)
    priced = lists.priced()
    rows, cols = np.repeat(np.arange(300), 300), np.tile(np.arange(300), 300)
    out = np.ones((300, 300), bool)
    out[priced.rows, priced.cols] = False
    every = table.costs(*motion, rows, cols).reshape(300, 300)
    bound = np.maximum(priced.floor_a[:, None], priced.floor_b[None, :])
    assert np.all(every[out] >= bound[out])
