"""Stroke matching between two keys: index pairing, optimal assignment, reversal, unmatched."""

import itertools
import time

import bench_drawings
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from shapes import circle

from ballmorph_core.drawing.pairing import certified, costs, descriptors, matching, motion_search, shape_fits
from ballmorph_core.drawing.pairing.assignment import SparseCosts, solve_assignment
from ballmorph_core.drawing.pairing.certified import _assign_within, _least_total, padded_total
from ballmorph_core.drawing.pairing.matching import match_strokes
from ballmorph_core.drawing.pairing.shape_fits import _backwards, _loop_shapes
from ballmorph_core.errors import InvalidCurveError
from ballmorph_core.geometry.polyline import resample, reverse, signed_area
from ballmorph_core.geometry.ragged import Ragged


def _shift(matching):
    """The translation of a matching's drawing motion, shape (2,)."""
    return np.array([matching.drawing.b.real, matching.drawing.b.imag])


def face():
    """A small drawing: (strokes, cyclic flags). Two eyes share a shape and differ by place."""
    x = np.linspace(-0.4, 0.4, 30)
    hx = np.linspace(-0.8, 0.8, 40)
    head = circle(1.0, 64) * [1.0, 1.2]
    strokes = [
        head,
        circle(0.15, 24, centre=(-0.4, 0.3)),
        circle(0.15, 24, centre=(0.4, 0.3)),
        np.c_[x, -0.5 - 0.2 * np.sin(np.pi * (x + 0.4) / 0.8)],
        np.array([[0.0, 0.1], [0.1, -0.15], [0.0, -0.2]]),
        np.c_[hx, 1.25 + 0.1 * np.sin(6 * hx)],
    ]
    return strokes, np.array([True, True, True, False, False, False])


def identity_pairs(n):
    return [(i, i, False) for i in range(n)]


def test_identical_drawings_pair_by_index():
    strokes, closed = face()
    m = match_strokes(strokes, strokes, closed, closed)
    assert m.method == "index"
    assert m.pairs == identity_pairs(len(strokes))
    assert m.unmatched_a == m.unmatched_b == []
    assert max(m.costs) < 1e-6
    np.testing.assert_allclose(_shift(m), 0.0, atol=1e-12)


def test_permuted_strokes_are_recovered():
    strokes, closed = face()
    perm = np.array([3, 0, 5, 2, 1, 4])  # B's stroke j is A's stroke perm[j]; eyes swapped too
    shift = np.array([0.3, -0.2])
    m = match_strokes(strokes, [strokes[p] + shift for p in perm], closed, closed[perm])
    assert m.method == "assignment"
    assert "drawing order" in m.reason
    expected = sorted((int(p), j, False) for j, p in enumerate(perm))
    assert m.pairs == expected
    assert m.unmatched_a == m.unmatched_b == []
    np.testing.assert_allclose(_shift(m), shift, atol=1e-9)


@pytest.mark.parametrize("mode", ["AUTO", "INDEX"])
def test_reversed_open_stroke_is_detected(mode):
    strokes, closed = face()
    flipped = [s[::-1] if i == 3 else s for i, s in enumerate(strokes)]
    m = match_strokes(strokes, flipped, closed, closed, mode=mode)
    assert m.method == "index"
    assert m.pairs == [(i, i, i == 3) for i in range(len(strokes))]
    assert max(m.costs) < 1e-6  # the reversed stroke matches exactly once flipped


def test_loop_in_opposite_orientation_from_another_vertex():
    strokes, closed = face()
    head = strokes[0]
    backwards = np.roll(reverse(head, True), 17, axis=0)
    rolled = np.roll(head, 17, axis=0)
    m = match_strokes(strokes, [backwards, *strokes[1:]], closed, closed)
    assert m.method == "index"
    assert m.pairs[0] == (0, 0, True)
    assert all(not r for _, _, r in m.pairs[1:])
    # Started between two of B's samples: the cost is at most about half a sample spacing.
    half_spacing = 0.5 * 7.0 / descriptors.MATCH_SAMPLES / np.hypot(2.0, 2.4)  # perimeter ~6.9
    assert 0 < m.costs[0] < half_spacing
    # The flag means opposite orientation: reversing B's loop restores A's.
    assert np.sign(signed_area(backwards)) != np.sign(signed_area(head))
    assert np.sign(signed_area(reverse(backwards, True))) == np.sign(signed_area(head))
    # Same orientation from another vertex: matched, not reversed.
    m = match_strokes(strokes, [rolled, *strokes[1:]], closed, closed)
    assert m.pairs == identity_pairs(len(strokes))


@pytest.mark.parametrize("shift", [(0.0, 0.0), (0.3, -0.2)])
@pytest.mark.parametrize("new", ["far", "different"])
def test_extra_stroke_in_second_key_is_unmatched(shift, new):
    strokes, closed = face()
    a = [strokes[i] for i in (0, 1, 3, 4)]
    ca = closed[[0, 1, 3, 4]]
    if new == "far":
        extra = circle(0.3, 20, centre=(6.0, 5.0))[:15]  # an open arc far from the face
    else:
        x = np.linspace(-0.5, 0.5, 11)
        extra = np.c_[x, -0.5 + 0.15 * (-1.0) ** np.arange(11)]  # a zigzag over the mouth
    b = [s + shift for s in (a[0], a[1], extra, a[2], a[3])]
    cb = np.array([ca[0], ca[1], False, ca[2], ca[3]])
    m = match_strokes(a, b, ca, cb)
    assert m.method == "assignment"
    assert "4 vs 5" in m.reason
    assert m.pairs == [(0, 0, False), (1, 1, False), (2, 3, False), (3, 4, False)]
    assert m.unmatched_a == []
    assert m.unmatched_b == [2]
    np.testing.assert_allclose(_shift(m), shift, atol=1e-9)


def test_translated_and_deformed_drawing_keeps_index_pairing():
    strokes, closed = face()
    rng = np.random.default_rng(7)
    move = np.array([3.0, -2.0])  # more than the drawing's own size

    def deform(s, c):
        s = resample(s, c, count=len(s) + 7)  # other point counts, as a redrawn key would have
        warp = 0.04 * np.c_[np.sin(2 * s[:, 1]), np.cos(3 * s[:, 0])]
        return s + warp + move + rng.normal(0.0, 0.005, s.shape)

    b = [deform(s, c) for s, c in zip(strokes, closed)]
    m = match_strokes(strokes, b, closed, closed)
    assert m.method == "index", m.reason
    assert m.pairs == identity_pairs(len(strokes))
    assert 0 < max(m.costs) < matching.MATCH_INDEX_MAX_COST
    np.testing.assert_allclose(_shift(m), move, atol=0.05)


def hatching(*heights):
    """The face plus horizontal hatch lines at the given heights (open strokes)."""
    strokes, closed = face()
    x = np.linspace(-0.5, 0.5, 20)
    return [*strokes, *(np.c_[x, np.full_like(x, y)] for y in heights)], np.r_[closed, [False] * len(heights)]


def test_drawing_order_is_kept_only_when_nearly_optimal():
    a, closed = hatching(0.0, 0.02)
    # Swapped hatch lines: every index pair is close, but the order is clearly wrong.
    b, _ = hatching(0.02, 0.0)
    m = match_strokes(a, b, closed, closed)
    assert m.method == "assignment"
    assert "optimal assignment" in m.reason and "limit 1.25 times" in m.reason
    assert m.pairs[-2:] == [(6, 7, False), (7, 6, False)]
    # Redrawn lines where swapping is better by less than MATCH_INDEX_FACTOR: the animator's
    # drawing order wins.
    b, _ = hatching(0.0105, 0.0095)
    m = match_strokes(a, b, closed, closed)
    assert m.method == "index", m.reason
    assert m.pairs == identity_pairs(8)


def test_stroke_far_from_anything_is_not_forced():
    strokes, closed = face()
    a = strokes[:4]
    b = [*strokes[:3], strokes[3] + [8.0, 0.0]]  # the mouth jumped far away; nothing else moved
    m = match_strokes(a, b, closed[:4], closed[:4])
    # Too far for the assignment, but the one stroke left in each key: paired by the drawing's
    # motion (issue 39), and said so.
    assert m.pairs == identity_pairs(4), m.reason
    assert m.travelled == [(3, 3)]
    assert m.unmatched_a == m.unmatched_b == []
    # With the far stroke in the first key only (counts differing), nothing becomes it.
    m = match_strokes(b, a[:3], closed[:4], closed[:3])
    assert m.pairs == identity_pairs(3)
    assert m.unmatched_a == [3]


def test_index_mode_pairs_by_order_and_leaves_extras():
    strokes, closed = face()
    a = strokes[:3]
    b = [strokes[0], reverse(strokes[2], True), strokes[1], strokes[3], strokes[4]]
    m = match_strokes(a, b, closed[:3], closed[:5], mode="INDEX")
    assert m.method == "index"
    # Pair 1 (left eye -> right eye, reversed loop) is kept: INDEX never reorders.
    assert m.pairs == [(0, 0, False), (1, 1, True), (2, 2, False)]
    assert m.unmatched_a == []
    assert m.unmatched_b == [3, 4]
    auto = match_strokes(a, b, closed[:3], closed[:5])
    assert auto.pairs == [(0, 0, False), (1, 2, False), (2, 1, True)]


def test_mixed_cyclic_pair_pays_the_penalty():
    loop = circle(1.0, 40)
    m = match_strokes([loop], [loop], [True], [False])
    assert m.pairs == [(0, 0, False)]
    assert m.costs[0] == pytest.approx(costs.MATCH_CYCLIC_PENALTY, abs=1e-3)


def test_degenerate_strokes_and_empty_keys():
    line = np.array([[0.0, 0.0], [1.0, 0.5]])
    dot = np.array([[0.2, 0.9]])
    for mode in ("AUTO", "INDEX"):
        m = match_strokes([], [], [], [], mode=mode)
        assert (m.pairs, m.unmatched_a, m.unmatched_b, m.method) == ([], [], [], "index")
        m = match_strokes([line], [], [False], [], mode=mode)
        assert (m.pairs, m.unmatched_a, m.unmatched_b) == ([], [0], [])
        m = match_strokes([], [dot], [], [True], mode=mode)
        assert (m.pairs, m.unmatched_a, m.unmatched_b) == ([], [], [0])
    # Dots (one point, or one point repeated), a two-point "loop", duplicated points.
    a = [dot, line, np.repeat(dot + 0.5, 4, axis=0), np.array([[0.0, 1.0], [0.5, 1.0]])]
    b = [dot + 0.01, np.repeat(line, 3, axis=0), np.array([[0.7, 1.4]]), np.array([[0.0, 1.0], [0.5, 1.0], [0.0, 1.0]])]
    m = match_strokes(a, b, [True, False, False, True], [False, False, False, True])
    assert [p[:2] for p in m.pairs] == [(0, 0), (1, 1), (2, 2), (3, 3)]
    assert m.pairs[1][2] is False
    # A stroke with no point at all is never paired by AUTO, and does not crash INDEX.
    empty = np.zeros((0, 2))
    m = match_strokes([line, empty], [line, empty], [False, False], [False, False])
    assert m.pairs == [(0, 0, False)]
    assert m.unmatched_a == m.unmatched_b == [1]
    m = match_strokes([line, empty], [line, empty], [False, False], [False, False], mode="INDEX")
    assert m.pairs == identity_pairs(2)
    assert m.costs[1] == np.inf


def test_invalid_input_is_named():
    line = np.array([[0.0, 0.0], [1.0, 0.0]])
    with pytest.raises(InvalidCurveError, match="mode='NEAREST'"):
        match_strokes([line], [line], [False], [False], mode="NEAREST")
    with pytest.raises(InvalidCurveError, match="closed_b"):
        match_strokes([line], [line], [False], [False, True])
    with pytest.raises(InvalidCurveError, match=r"strokes_b\[1\]"):
        match_strokes([line], [line, np.array([[0.0, 0.0], [np.nan, 1.0]])], [False], [False, False])
    with pytest.raises(InvalidCurveError, match=r"strokes_a\[0\]"):
        match_strokes([np.zeros((3, 3))], [line], [False], [False])
    with pytest.raises(InvalidCurveError, match="cost"):
        solve_assignment([[0.0, np.inf]])


def _brute_force(cost):
    r, c = cost.shape
    if r > c:
        return _brute_force(cost.T)
    return min(sum(cost[i, p[i]] for i in range(r)) for p in itertools.permutations(range(c), r))


def _matrix(data, low, high):
    r = data.draw(st.integers(1, 5), label="rows")
    c = data.draw(st.integers(1, 5), label="cols")
    values = st.integers(low, high).map(float) | st.floats(low, high, allow_nan=False)
    return np.array(data.draw(st.lists(values, min_size=r * c, max_size=r * c)), dtype=float).reshape(r, c)


@given(st.data())
def test_solver_agrees_with_brute_force(data):
    cost = _matrix(data, -50, 50)  # integer draws make many ties
    given_cost = cost.copy()
    rows, cols = solve_assignment(cost)
    assert np.array_equal(cost, given_cost)  # read, never written (the solver keeps no copy)
    k = min(cost.shape)
    assert len(rows) == len(set(rows.tolist())) == len(set(cols.tolist())) == k
    assert np.all(np.diff(rows) > 0)
    assert cost[rows, cols].sum() == pytest.approx(_brute_force(cost), abs=1e-9)


@given(st.data())
def test_solver_duals_certify_the_assignment(data):
    # u_i + v_j <= c_ij everywhere, equal on the pairs assigned, 0 on the larger side's rows
    # or columns left out: their sum is the optimum (strong duality).
    cost = _matrix(data, -50, 50)
    rows, cols, u, v = solve_assignment(cost, duals=True)
    assert all(np.array_equal(x, y) for x, y in zip((rows, cols), solve_assignment(cost)))
    assert u.shape == (cost.shape[0],) and v.shape == (cost.shape[1],)
    slack = cost - u[:, None] - v[None, :]
    assert slack.min() >= -1e-9
    np.testing.assert_allclose(slack[rows, cols], 0.0, atol=1e-9)
    left_rows = np.setdiff1d(np.arange(cost.shape[0]), rows)
    left_cols = np.setdiff1d(np.arange(cost.shape[1]), cols)
    assert np.all(u[left_rows] == 0.0) and np.all(v[left_cols] == 0.0)
    assert u.sum() + v.sum() == pytest.approx(_brute_force(cost), abs=1e-9)


@given(st.data())
def test_a_sparse_table_solves_as_the_dense_table_it_stands_for(data):
    # Its rows are laid out one at a time with the dense table's values: the same assignment
    # and potentials, bit for bit (ties to the fill value, empty and full rows, more rows than
    # columns, entries listed in any order).
    r = data.draw(st.integers(1, 7), label="rows")
    c = data.draw(st.integers(1, 7), label="cols")
    fill = data.draw(st.sampled_from([1.5, 2.0]), label="fill")
    kept = np.array(data.draw(st.lists(st.booleans(), min_size=r * c, max_size=r * c)), dtype=bool).reshape(r, c)
    values = st.sampled_from([0.0, 0.5, 1.0, 1.5, 2.0]) | st.floats(0.0, 2.0, allow_nan=False)
    dense = np.array(data.draw(st.lists(values, min_size=r * c, max_size=r * c)), dtype=float).reshape(r, c)
    dense[~kept] = fill
    rows, cols = np.nonzero(kept)
    order = np.random.default_rng(data.draw(st.integers(0, 99), label="order")).permutation(len(rows))
    sparse = SparseCosts((r, c), rows[order], cols[order], dense[rows, cols][order], fill)
    for got, want in zip(solve_assignment(sparse, duals=True), solve_assignment(dense, duals=True)):
        assert np.array_equal(got, want)
    picks = np.arange(r).repeat(c), np.tile(np.arange(c), r)
    assert np.array_equal(sparse.at(*picks), dense[picks])


@given(st.data())
def test_thresholded_assignment_agrees_with_brute_force(data):
    limit = costs.MATCH_MAX_COST
    cost = _matrix(data, 0, 1) * 2 * limit
    rows, cols = _assign_within(cost)
    assert np.all(cost[rows, cols] < limit)
    got = padded_total(cost[rows, cols], *cost.shape)
    # Every partial matching: each row takes a column or nobody (None).
    r, c = cost.shape
    best = np.inf
    for choice in itertools.product([None, *range(c)], repeat=r):
        taken = [j for j in choice if j is not None]
        if len(taken) != len(set(taken)) or any(j is not None and cost[i, j] >= limit for i, j in enumerate(choice)):
            continue
        best = min(best, padded_total([cost[i, j] for i, j in enumerate(choice) if j is not None], r, c))
    assert got == pytest.approx(best, abs=1e-9)
    # The bound the matching skips a last solve by: never above the best matching.
    assert _least_total(cost) <= best + 1e-12


def test_least_total_is_reached_where_strokes_pick_each_other():
    # Every stroke's cheapest pair is its own diagonal one (or none under the limit): the
    # bound is that matching's total, the unmatched strokes paying half the limit each.
    limit = costs.MATCH_MAX_COST
    cost = np.array([[0.2, 0.9, 5.0], [0.7, 0.4, 3.0], [9.0, 2.0, 1.6], [2.0, 2.0, 2.0]])
    assert _least_total(cost) == pytest.approx(padded_total([0.2, 0.4], 4, 3))
    assert _least_total(np.zeros((0, 3))) == pytest.approx(1.5 * limit)


def test_a_guess_s_last_solve_is_skipped_only_where_it_cannot_win(monkeypatch):
    # The drawing order fitted to reordered look-alike strokes crowds key A together (tried
    # here whatever it accounts for): its guess's tables are far behind the best matching,
    # and the last of them is not solved.
    monkeypatch.setattr(motion_search, "MATCH_ORDER_EXPLAINS", -np.inf)
    a, b, perm = bench_drawings.reordered_hatching(60, 4)
    flags = [False] * 60
    solves = []

    def counted(cost, **options):
        solves.append(np.shape(cost))
        return solve_assignment(cost, **options)

    monkeypatch.setattr(certified, "solve_assignment", counted)
    m = match_strokes(a, b, flags, flags)
    skipped = len(solves)
    assert m.pairs == sorted((int(p), j, False) for j, p in enumerate(perm))
    solves.clear()
    monkeypatch.setattr(certified, "_least_total", lambda cost: -np.inf)
    monkeypatch.setattr(costs.Priced, "least_total", lambda priced: -np.inf)
    unbounded = match_strokes(a, b, flags, flags)
    assert skipped < len(solves)
    assert (unbounded.pairs, unbounded.costs, unbounded.method) == (m.pairs, m.costs, m.method)
    assert unbounded.drawing == m.drawing


@pytest.mark.parametrize("seed", range(4))
def test_loop_shapes_match_explicit_shifts_and_similarities(seed):
    """The FFT residual is the best similarity fit over every cyclic shift, found one by one."""
    rng = np.random.default_rng(seed)
    m = 12
    a = rng.normal(size=(3, m)) + 1j * rng.normal(size=(3, m))
    b = rng.normal(size=(4, m)) + 1j * rng.normal(size=(4, m))
    a -= a.mean(axis=1, keepdims=True)
    b -= b.mean(axis=1, keepdims=True)
    got = _loop_shapes(a, b)
    for i in range(3):
        for j in range(4):
            residuals = []
            for shift in range(m):
                q = np.roll(b[j], -shift)
                k = np.vdot(a[i], q) / np.vdot(a[i], a[i])  # least-squares similarity a -> q
                residuals.append(np.sum(np.abs(k * a[i] - q) ** 2) / np.sum(np.abs(q) ** 2))
            assert got[i, j] == pytest.approx(min(residuals), rel=1e-9, abs=1e-12)


@given(st.integers(0, 2**32 - 1))
def test_each_loop_pair_is_fitted_in_the_direction_it_needs(seed):
    """Blocks by area sign give exactly the values of both directions for every pair and a
    choice after: backwards where the loops run opposite ways (a zero area is neither)."""
    rng = np.random.default_rng(seed)
    la, lb, m = rng.integers(1, 7), rng.integers(1, 7), 8
    a = rng.normal(size=(la, m)) + 1j * rng.normal(size=(la, m))
    b = rng.normal(size=(lb, m)) + 1j * rng.normal(size=(lb, m))
    sign_a, sign_b = rng.integers(-1, 2, la).astype(float), rng.integers(-1, 2, lb).astype(float)
    flip = sign_a[:, None] * sign_b[None, :] < 0
    want = np.where(flip, _loop_shapes(a, _backwards(b)), _loop_shapes(a, b))
    np.testing.assert_array_equal(_loop_shapes(a, b, sign_a, sign_b), want)


def test_turned_and_scaled_strokes_pair_whatever_the_angle():
    """The shape term ignores turn and scale: a drawing whose strokes each turn by up to 170
    degrees and grow 1.5 times keeps its pairs."""
    strokes, closed = face()
    rng = np.random.default_rng(5)
    turned = []
    for s in strokes:
        centre = s.mean(axis=0)
        angle = rng.uniform(-np.pi * 17 / 18, np.pi * 17 / 18)
        rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
        turned.append(centre + 1.5 * (s - centre) @ rot.T)
    m = match_strokes(strokes, turned, closed, closed)
    assert [p[:2] for p in m.pairs] == [p[:2] for p in identity_pairs(len(strokes))]
    assert max(m.costs) < matching.MATCH_INDEX_MAX_COST + costs.W_TURN


def test_flipped_arch_is_not_a_half_turn():
    """An arch flipped about its chord maps onto itself read backwards by a half turn, exactly:
    it keeps the drawn direction all the same (its ends stay put, or it moved and flipped)."""
    x = np.linspace(0.0, 1.0, 40)
    up, down = np.c_[x, 0.3 * np.sin(np.pi * x)], np.c_[x, -0.3 * np.sin(np.pi * x)]
    assert match_strokes([up], [down], [False], [False]).pairs == [(0, 0, False)]
    assert match_strokes([up], [down[::-1]], [False], [False]).pairs == [(0, 0, True)]
    assert match_strokes([up], [down + [0.0, 2.0]], [False], [False]).pairs == [(0, 0, False)]


@pytest.mark.parametrize("angle", [90.0, 150.0, 170.0, -170.0])
def test_hook_keeps_its_turn_however_far_it_turns(angle):
    """Read backwards, a hook turned by nearly a half turn needs only a small turn but fits
    badly: the true turn wins."""
    t = np.linspace(0.0, 1.0, 40)
    hook = np.c_[t, 0.2 * np.sin(np.pi * t)]
    hook = np.r_[hook, hook[-1] + 0.15 * np.c_[np.cos(np.linspace(0, -2.5, 10)) - 1, np.sin(np.linspace(0, -2.5, 10))]]
    a = np.radians(angle)
    turned = hook @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]]) + [3.0, 1.0]
    assert match_strokes([hook], [turned], [False], [False]).pairs == [(0, 0, False)]
    assert match_strokes([hook], [turned[::-1]], [False], [False]).pairs == [(0, 0, True)]


def test_dot_pairs_with_the_short_stroke_grown_out_of_it():
    dot = np.array([[15.0, 0.0]])
    dash = np.array([[15.0, 0.0], [15.5, 0.3]])
    far = np.c_[np.linspace(0, 1, 9), np.zeros(9)] + [0.0, 5.0]
    m = match_strokes([far, dot], [far, dash], [False, False], [False, False])
    assert m.pairs == identity_pairs(2)


def test_a_dot_grows_into_its_dash_in_the_dash_s_drawn_direction():
    far = np.c_[np.linspace(0, 1, 9), np.zeros(9)] + [0.0, 5.0]
    for x in (15.0, -3.0, 0.1, 0.7, 1e3):
        for angle in np.linspace(0.0, 6.0, 7):
            dot = np.array([[x, 0.3 * x]])
            dash = dot + [[0.0, 0.0], [0.6 * np.cos(angle), 0.6 * np.sin(angle)]]
            m = match_strokes([far, dot], [far, dash], [False] * 2, [False] * 2)
            assert m.pairs == identity_pairs(2), (x, angle)


def test_four_hundred_strokes_timing():
    rng = np.random.default_rng(3)
    strokes, closed = [], []
    for k in range(400):
        centre = rng.uniform(0.0, 10.0, 2)
        if k % 3 == 0:
            strokes.append(circle(rng.uniform(0.1, 0.4), int(rng.integers(8, 40)), centre=centre))
            closed.append(True)
        else:
            steps = rng.normal(0.0, 0.04, (int(rng.integers(2, 30)), 2)) + rng.normal(0.0, 0.1, 2)
            strokes.append(centre + np.cumsum(steps, axis=0))
            closed.append(False)
    closed = np.array(closed)
    perm = rng.permutation(400)
    b = [strokes[p] + [0.5, 0.2] + rng.normal(0.0, 0.005, strokes[p].shape) for p in perm]
    start = time.perf_counter()
    m = match_strokes(strokes, b, closed, closed[perm])
    elapsed = time.perf_counter() - start
    print(f"\nmatch_strokes 400 x 400 strokes: {elapsed:.3f} s ({m.method})")
    assert m.pairs == sorted((int(p), j, False) for j, p in enumerate(perm))


@given(st.integers(0, 2**32 - 1))
def test_the_batched_key_descriptors_are_the_stroke_by_stroke_ones(seed):
    """Keys read at once (every stroke kept, or with dots and empty strokes left out of the
    resampling) describe each stroke as reading them one by one does."""
    rng = np.random.default_rng(seed)
    sizes = rng.choice([0, 1, 2, 5, 9], size=rng.integers(1, 6))
    strokes = [np.cumsum(rng.normal(size=(n, 2)), axis=0) for n in sizes]
    closed = rng.random(len(sizes)) < 0.5
    batched = descriptors.KeyDescriptors(strokes, closed, "s", "c", 8)
    with pytest.MonkeyPatch.context() as one_by_one:
        one_by_one.setattr(descriptors.KeyDescriptors, "_batched", lambda *args: False)
        single = descriptors.KeyDescriptors(strokes, closed, "s", "c", 8)
    for name in ("valid", "open", "ring", "length", "diagonal"):
        np.testing.assert_allclose(getattr(batched, name), getattr(single, name), rtol=1e-12, atol=1e-12)


def _random_keys(seed):
    """Two keys of random walks (some loops, a dot, a two-point stroke): (strokes, flags) twice."""
    rng = np.random.default_rng(seed)
    keys = []
    for count in rng.integers(2, 12, 2):
        strokes = [np.cumsum(rng.normal(size=(int(rng.integers(3, 30)), 2)), axis=0) for _ in range(count)]
        strokes[0] = strokes[0][:1]  # a dot
        strokes[-1] = strokes[-1][:2]
        keys.append((strokes, rng.random(count) < 0.5))
    return keys


@pytest.mark.parametrize("seed", range(8))
def test_a_ragged_batch_matches_like_the_list_of_its_strokes(seed):
    (sa, ca), (sb, cb) = _random_keys(seed)
    listed = match_strokes(sa, sb, ca, cb)
    batched = match_strokes(Ragged.from_list(sa, ca), Ragged.from_list(sb, cb), ca, cb)
    assert batched.pairs == listed.pairs and batched.costs == listed.costs
    assert (batched.unmatched_a, batched.unmatched_b) == (listed.unmatched_a, listed.unmatched_b)
    assert batched.drawing == listed.drawing


def test_a_ragged_batch_with_a_bad_point_is_named_stroke_by_stroke():
    strokes = [np.zeros((3, 2)), np.array([[0.0, 0.0], [np.nan, 1.0]])]
    with pytest.raises(InvalidCurveError, match=r"strokes_a\[1\]"):
        match_strokes(Ragged.from_list(strokes, False), [np.eye(2)], [False, False], [False])


def _table(keys):
    (sa, ca), (sb, cb) = keys
    key = [descriptors.KeyDescriptors(st, c, "k", "c", descriptors.MATCH_SAMPLES) for st, c in ((sa, ca), (sb, cb))]
    return costs.CostTable(*key)


@pytest.mark.parametrize("seed", range(8))
def test_costs_and_directions_of_some_pairs_are_those_of_the_whole_table(seed):
    # The whole table's costs are exact below MATCH_MAX_COST and at least that elsewhere (loop
    # pairs it need not fit); once it is made, those of some pairs are its values, bit for bit.
    # Before, a pair's open fit is its own dot product: the same value to round-off.
    keys = _random_keys(seed)
    (sa, _), (sb, _) = keys
    rows, cols = (g.ravel() for g in np.meshgrid(np.arange(len(sa)), np.arange(len(sb)), indexing="ij"))
    pick = np.random.default_rng(seed).permutation(len(rows))[: len(rows) // 2 + 1]
    motion = (0.9 + 0.2j, 0.3 - 0.1j)
    table = _table(keys)
    some = table.costs(*motion, rows[pick], cols[pick])
    alone = table.directions(0.4, rows[pick], cols[pick])
    assert not table.whole
    whole = table.costs(*motion)
    assert table.whole
    low = some < costs.MATCH_MAX_COST
    np.testing.assert_allclose(whole[rows[pick], cols[pick]][low], some[low], rtol=0, atol=1e-7)
    assert np.all(whole[rows[pick], cols[pick]][~low] >= costs.MATCH_MAX_COST - 1e-7)
    every = table.costs(*motion, rows, cols)
    assert np.array_equal(table.costs(*motion, rows[pick], cols[pick]), every[pick])
    assert np.array_equal(np.minimum(whole, 9.0).ravel(), np.minimum(every, 9.0))
    every = table.directions(0.4, rows, cols)
    assert np.array_equal(table.directions(0.4, rows[pick], cols[pick]), every[pick])
    assert np.array_equal(alone, every[pick])


@pytest.mark.parametrize("seed", range(8))
def test_table_costs_and_open_shapes_are_the_plain_formulas_bit_for_bit(seed):
    """The cost table works its (S_a, S_b) terms in place (drawings of thousands of strokes):
    the values are those of the module notes' formula written out, and the open strokes' fits
    those of the complex products read both ways; dots, loops and a turned, scaled motion."""
    keys = _random_keys(seed)
    table = _table(keys)
    table.prior_turn = np.exp(0.3j)
    a, b = 0.8 * np.exp(0.5j), 0.2 - 0.4j
    got = table.costs(a, b)
    scale = max(abs(a), 1e-300)
    ra, rb, za, zb = table.ra[:, None], table.rb[None, :], (a * table.ca + b)[:, None], table.cb[None, :]
    place = np.abs(za - zb) / np.maximum(scale * ra + rb, table.dot_spread)
    ratio = np.maximum(rb, 1e-300) / np.maximum(scale * ra, 1e-300)
    size = np.where((ra > 0) & (rb > 0), np.abs(np.log(ratio)) / np.log(4.0), 0.0)
    want = costs.W_SHAPE * table.shape + costs.W_PLACE * place + costs.W_SCALE * size
    (_, ca), (_, cb) = keys
    valid = np.array([len(p) > 0 for p in keys[0][0]])[:, None] & np.array([len(p) > 0 for p in keys[1][0]])[None, :]
    want = want + costs.MATCH_CYCLIC_PENALTY * (ca[:, None] != cb[None, :])
    want = np.where(valid, want + costs.W_TURN * abs(np.angle(a * np.exp(-0.3j))) / np.pi, np.inf)
    assert np.array_equal(got, want)
    rng = np.random.default_rng(seed)
    oa, ob = (rng.normal(size=(n, 16)) + 1j * rng.normal(size=(n, 16)) for n in (7, 5))
    oa[0] = 0.0  # a dot: no fit
    oa, ob = oa - oa.mean(axis=1)[:, None], ob - ob.mean(axis=1)[:, None]
    norms = np.maximum(np.sum(np.abs(oa) ** 2, axis=1)[:, None] * np.sum(np.abs(ob) ** 2, axis=1)[None, :], 1e-300)
    e_f, e_r, turn_f, turn_r = shape_fits.open_shapes(oa, ob)
    for d, e, turn in zip((np.conj(oa) @ ob.T, np.conj(oa) @ ob[:, ::-1].T), (e_f, e_r), (turn_f, turn_r)):
        assert np.array_equal(e, np.clip(1.0 - np.abs(d) ** 2 / norms, 0.0, 1.0))
        assert np.array_equal(turn, np.angle(d))
    # Pair by pair: each pair's own dot products, the matrix products' values to round-off.
    i, j = (g.ravel() for g in np.meshgrid(np.arange(7), np.arange(5), indexing="ij"))
    pairs = shape_fits.pair_shapes(oa[i], ob[j])
    reads = (np.sum(np.conj(oa[i]) * ob[j], axis=1), np.sum(np.conj(oa[i]) * ob[j][:, ::-1], axis=1))
    for d, e, turn, whole in zip(reads, pairs[:2], pairs[2:], (e_f, e_r)):
        assert np.array_equal(e, np.clip(1.0 - np.abs(d) ** 2 / norms[i, j], 0.0, 1.0))
        assert np.array_equal(turn, np.angle(d))
        np.testing.assert_allclose(e, whole[i, j], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(shape_fits.pair_shapes(oa[i[::3]], ob[j[::3]])[0], pairs[0][::3])


@given(st.integers(0, 2**32 - 1))
def test_loop_fits_of_some_pairs_are_those_of_every_pair(seed):
    rng = np.random.default_rng(seed)
    (la, lb), m = (int(v) for v in rng.integers(1, 9, 2)), 8
    a, b = (rng.normal(size=(n, m)) + 1j * rng.normal(size=(n, m)) for n in (la, lb))
    sign_a, sign_b = rng.integers(-1, 2, la).astype(float), rng.integers(-1, 2, lb).astype(float)
    every = _loop_shapes(a, b, sign_a, sign_b)
    i, j = rng.integers(0, la, 5), rng.integers(0, lb, 5)
    assert np.array_equal(shape_fits.LoopFits(a, b, sign_a, sign_b).residuals(i, j), every[i, j])


@pytest.mark.parametrize("shape", [(150, 150), (90, 200), (200, 90)])
def test_every_row_wanting_one_column_is_solved_by_the_rearrangement_inequality(shape):
    # cost = -a_i b_j with a, b increasing: every row's cheapest column is the last one, so
    # the searches go deeper than their first rows of room (the distances of every row they
    # visit are kept), and the optimum pairs the largest a with the largest b: the last rows
    # with the last columns, in order.
    r, c = shape
    a, b = np.arange(1.0, r + 1), np.arange(1.0, c + 1)
    rows, cols = solve_assignment(-np.outer(a, b))
    k = min(r, c)
    np.testing.assert_array_equal(rows, np.arange(r - k, r))
    np.testing.assert_array_equal(cols, np.arange(c - k, c))


def _turned_arcs(n, degrees, scale=1.0, seed=3):
    """The benchmark's open arcs (key A) and key B turned by ``degrees`` and scaled about the
    drawing's centre, reordered and one stroke short: (a, b, source of each stroke of B)."""
    key_a, key_b = bench_drawings.make_keys("open", n, 40, seed)
    source = np.random.default_rng(seed).permutation(n)[:-1]
    centre = np.mean(np.concatenate(key_a), axis=0)
    turn = scale * np.exp(1j * np.radians(degrees))
    rotate = np.array([[turn.real, -turn.imag], [turn.imag, turn.real]])
    return key_a, [(key_b[i] - centre) @ rotate.T + centre for i in source], source


@pytest.mark.parametrize("degrees", [45, 90, 150, -120])
def test_a_drawing_turned_and_redrawn_in_another_order_pairs_right(degrees):
    # No drawing order to fit (the counts differ), strokes of every orientation: before the turn
    # guess, 2 of 29 pairs were right at 45 degrees, none at 90 or 150.
    a, b, source = _turned_arcs(30, degrees)
    m = match_strokes(a, b, [False] * 30, [False] * 29)
    assert sorted((i, j) for i, j, _ in m.pairs) == sorted((int(s), j) for j, s in enumerate(source))


def test_the_turn_guess_reads_the_turn_and_scale_without_pairing():
    a, b, _ = _turned_arcs(60, 70.0, 1.25)
    keys = [descriptors.KeyDescriptors(k, [False] * len(k), "k", "c", descriptors.MATCH_SAMPLES) for k in (a, b)]
    turn, _ = motion_search._turn_guess(costs.CostTable(*keys), *keys)
    # The arcs of key B are key A's redrawn, each a little turned (up to 8 degrees) and scaled.
    assert abs(np.degrees(np.angle(turn)) - 70.0) < 4.0
    assert abs(abs(turn) / 1.25 - 1.0) < 0.05
