"""Stroke matching from the pairs near each other: the pairs priced, the duals' certificate, the
strokes widened, and the drawing order's guess (issue 14: a drawing of many small strokes)."""

import bench_drawings
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ballmorph_core.drawing.pairing import certified, costs, descriptors, motion_search
from ballmorph_core.drawing.pairing.matching import match_strokes


def _keys(seed, count=None):
    """Two keys of random walks on a grid (some loops, a dot, strokes of every size), key B key
    A moved, turned, redrawn with noise, reordered and one stroke short: (strokes, flags) twice."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 40)) if count is None else count
    side = int(np.ceil(np.sqrt(n)))
    scale = rng.choice([0.02, 0.2, 1.0], size=n)
    walks = [np.cumsum(rng.normal(0.0, s, (int(rng.integers(1, 12)), 2)), axis=0) for s in scale]
    a = [walk + [k % side, k // side] for k, walk in enumerate(walks)]
    closed_a = rng.random(n) < 0.3
    turn = rng.normal(0.0, 0.3)
    rot = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]]) * np.exp(rng.normal(0.0, 0.1))
    perm = rng.permutation(n)[: n - int(rng.integers(0, 2))]
    noise = rng.choice([0.001, 0.02, 0.2])
    b = [a[p] @ rot.T + rng.normal(0.0, noise, a[p].shape) + rng.normal(0.0, 0.3, 2) for p in perm]
    return (a, closed_a), (b, closed_a[perm])


def _many_small_keys(seed):
    """Two keys of many small strokes on a grid (hatching, ticks, small loops, dots), key B
    redrawn a little moved with a little noise, reordered, a few strokes dropped and a few
    added: the drawings the pairs near each other settle. (strokes, flags) twice."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(60, 160))
    side = int(np.ceil(np.sqrt(n)))
    kinds = rng.integers(0, 3, n)  # line, loop, dot
    a, closed = [], []
    for k, kind in enumerate(kinds):
        corner = np.array([k % side, k // side]) * 0.5 + rng.uniform(-0.05, 0.05, 2)
        if kind == 2:
            a.append(corner[None, :])
        elif kind == 1:
            t = np.linspace(0.0, 2 * np.pi, int(rng.integers(5, 12)), endpoint=False)
            a.append(corner + rng.uniform(0.03, 0.1) * np.c_[np.cos(t), np.sin(t)])
        else:
            a.append(corner + np.linspace(0.0, 1.0, int(rng.integers(2, 8)))[:, None] * rng.uniform(-0.2, 0.2, 2))
        closed.append(kind == 1)
    closed = np.array(closed)
    keep = rng.permutation(n)[: n - int(rng.integers(0, 4))]
    move = rng.uniform(-0.03, 0.03, 2)
    b = [a[p] + move + rng.normal(0.0, 0.002, a[p].shape) for p in keep]
    extra = int(rng.integers(0, 3))
    b += [rng.uniform(0.0, side * 0.5, 2) + np.linspace(0.0, 0.1, 4)[:, None] for _ in range(extra)]
    return (a, closed), (b, np.r_[closed[keep], np.zeros(extra, bool)])


def _table(keys, whole=False):
    """The cost table of two keys; with ``whole``, one that may be laid out whole however many
    pairs it has (the whole-table path's tests, on drawings above ``MATCH_WHOLE_MOST``)."""
    (sa, ca), (sb, cb) = keys
    key = [descriptors.KeyDescriptors(st, c, "k", "c", descriptors.MATCH_SAMPLES) for st, c in ((sa, ca), (sb, cb))]
    with pytest.MonkeyPatch.context() as patch:
        if whole:
            patch.setattr(costs, "MATCH_WHOLE_MOST", np.inf)
        return costs.CostTable(*key)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([0.01, 0.1, 0.4, 1.5]))
def test_no_pair_left_out_of_the_near_ones_costs_less_than_the_level(seed, level):
    # The boxes around the centroids hold every pair whose cost may fall below the level (the
    # place term alone reaches it), at any motion: the whole table says which pairs do.
    keys = _keys(seed)
    rng = np.random.default_rng(seed)
    motion = complex(*rng.normal(1.0, 0.3, 2)), complex(*rng.normal(0.0, 0.5, 2))
    table = _table(keys)
    rows, cols = table.near(*motion, level)
    every = table.costs(*motion)
    near = np.zeros(every.shape, bool)
    near[rows, cols] = True
    assert not np.any(~near & (every < level))
    # Sorted by row then column, each pair once.
    code = rows * every.shape[1] + cols
    assert np.all(np.diff(code) > 0)


def _whole_only(monkeypatch):
    monkeypatch.setattr(certified, "_assign_near", lambda *args, **kwargs: certified._UNSETTLED)


@pytest.mark.parametrize("draw", [_keys, _many_small_keys])
def test_the_near_pairs_match_as_the_whole_table(draw, monkeypatch):
    # Where the duals certify the solve on the near pairs, it is the solve on every pair: the
    # same pairs; their costs are the same to the round-off of the open fits' sums. Drawings
    # of many small strokes are mostly settled by the near pairs, the others mostly not.
    settled = []
    real = certified._assign_near

    def spy(*args, **kwargs):
        out = real(*args, **kwargs)
        settled.append(out is not certified._UNSETTLED)
        return out

    for seed in range(12):
        (sa, ca), (sb, cb) = draw(seed)
        with monkeypatch.context() as spied:
            spied.setattr(certified, "_assign_near", spy)
            near = match_strokes(sa, sb, ca, cb)
        with monkeypatch.context() as whole_only:
            _whole_only(whole_only)
            whole = match_strokes(sa, sb, ca, cb)
        assert near.pairs == whole.pairs, seed
        assert (near.unmatched_a, near.unmatched_b, near.method) == (whole.unmatched_a, whole.unmatched_b, whole.method)
        np.testing.assert_allclose(near.costs, whole.costs, rtol=0, atol=1e-6)
    if draw is _many_small_keys:
        assert np.mean(settled) > 0.5


@pytest.mark.parametrize("draw", [_keys, _many_small_keys])
def test_the_bounded_candidate_lists_match_as_the_whole_table(draw, monkeypatch):
    # Every table made bounded (issue 41: what a drawing of thousands of strokes takes): each
    # stroke's candidate lists, widened where the duals do not certify them, pair as the whole
    # table does, and the drawing order is kept or left alike.
    # (Chains far behind kept, as the whole-table path keeps them: see MATCH_BEHIND.)
    monkeypatch.setattr(motion_search, "MATCH_BEHIND", np.inf)
    for seed in range(12):
        (sa, ca), (sb, cb) = draw(seed)
        whole = match_strokes(sa, sb, ca, cb)
        with monkeypatch.context() as bounded_only:
            bounded_only.setattr(costs, "MATCH_WHOLE_MOST", 0)
            bounded = match_strokes(sa, sb, ca, cb)
        assert bounded.pairs == whole.pairs, seed
        assert (bounded.unmatched_a, bounded.unmatched_b, bounded.method) == (
            whole.unmatched_a,
            whole.unmatched_b,
            whole.method,
        )
        np.testing.assert_allclose(bounded.costs, whole.costs, rtol=0, atol=1e-6)


def _hatching_matched_without_the_whole_table(monkeypatch, n, move=(0.0, 0.0)):
    """Whether ``n`` reordered hatch lines, key B also moved by ``move``, pair right with the
    whole table never priced (two bools)."""
    a, b, perm = bench_drawings.reordered_hatching(n, 2)
    b = [s + move for s in b]
    flags = [False] * n
    made = []
    monkeypatch.setattr(costs.CostTable, "_fit_whole", lambda table: made.append(table))
    m = match_strokes(a, b, flags, flags)
    return m.pairs == sorted((int(p), j, False) for j, p in enumerate(perm)), made == []


def test_reordered_hatching_is_settled_by_the_near_pairs(monkeypatch):
    # Look-alike strokes redrawn a little moved: every motion's solve is certified on each
    # stroke's neighbours, and the whole table is never priced.
    assert _hatching_matched_without_the_whole_table(monkeypatch, 300) == (True, True)


def test_a_stroke_whose_partner_is_far_gets_all_its_pairs_priced(monkeypatch):
    # One hatch line of key B is redrawn three lines away: the pairs about it cost more than
    # the near level, so potentials break the first certificate; those strokes' pairs are all
    # priced, and the solve then settles the drawing as the whole table does.
    a, b, perm = bench_drawings.reordered_hatching(120, 3)
    far = int(np.flatnonzero(perm == 0)[0])
    b[far] = b[far] + [0.9, 0.6]
    flags = [False] * 120
    widened = []
    real = costs.CostTable.widened

    def counted(table, priced, *args):
        out = real(table, priced, *args)
        widened.append((int(args[-2].sum()), int(args[-1].sum())))
        return out

    monkeypatch.setattr(costs.CostTable, "widened", counted)
    m = match_strokes(a, b, flags, flags)
    assert widened and all(0 < sa + sb <= 120 * 2 * certified.MATCH_NEAR_SHARE for sa, sb in widened)
    with monkeypatch.context() as whole_only:
        _whole_only(whole_only)
        whole = match_strokes(a, b, flags, flags)
    assert m.pairs == whole.pairs


def test_a_drawing_far_from_its_near_pairs_is_priced_whole(monkeypatch):
    # Every stroke changed shape: no pair costs less than the near level, and the motion is
    # priced whole at once (no solve on the near pairs first).
    (sa, ca), (sb, cb) = _keys(7, count=30)
    sb = [s[::-1] * [1.0, -0.5] for s in sb]
    solves = []
    real = certified.solve_assignment

    def counted(cost, **options):
        solves.append(options.get("duals", False))
        return real(cost, **options)

    monkeypatch.setattr(certified, "solve_assignment", counted)
    match_strokes(sa, sb, ca, cb)
    assert solves and not any(solves)


def _tried_turns(monkeypatch):
    """The turns and scales (complex ``a``) of every motion the matching solves at, as a list
    filled while it runs."""
    tried = []
    real = certified.assign_at

    def counted(table, motion, beat=None):
        tried.append(motion[0])
        return real(table, motion, beat)

    monkeypatch.setattr(motion_search, "assign_at", counted)
    return tried


def test_the_drawing_order_guess_is_tried_where_the_order_accounts_for_the_motion(monkeypatch):
    # A drawing turned by 150 degrees and listed in order: only the order's motion finds the
    # turn. Listed in another order, that guess accounts for nothing and is not tried.
    (sa, ca), _ = _keys(3, count=100)
    sa = [s for s in sa if len(s) > 2]
    ca = np.zeros(len(sa), bool)
    turn = np.deg2rad(150)
    rot = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    sb = [s @ rot.T + [0.4, -0.2] for s in sa]
    tried = _tried_turns(monkeypatch)
    m = match_strokes(sa, sb, ca, ca)
    assert m.pairs == [(i, i, False) for i in range(len(sa))]
    assert m.drawing.turn == pytest.approx(turn, abs=1e-6)
    assert any(abs(np.angle(a) - turn) < 1e-6 for a in tried)
    table = _table(((sa, ca), (sb, ca)))
    index = np.arange(len(sa))
    assert table.explained(index, index, table.fit_motion(index, index)) == pytest.approx(1.0)
    perm = np.random.default_rng(0).permutation(len(sa))
    shuffled = _table(((sa, ca), ([sb[p] for p in perm], ca)))
    order = shuffled.fit_motion(index, index)
    assert shuffled.explained(index, index, order) < motion_search.MATCH_ORDER_EXPLAINS
    tried.clear()
    match_strokes(sa, [sb[p] for p in perm], ca, ca)
    assert tried and all(abs(a - order[0]) > 1e-9 for a in tried)


def test_a_few_strokes_always_try_the_drawing_order_guess(monkeypatch):
    # Below MATCH_ORDER_GATE strokes a reordered drawing's order may account for much by
    # chance, and its chain costs little: its motion is tried whatever it accounts for.
    (sa, ca), (sb, cb) = _keys(5, count=20)
    sb, cb = sb[: len(sa)], cb[: len(sa)]
    sb = sb + [sa[0]] * (len(sa) - len(sb))
    cb = np.r_[cb, ca[:1].repeat(len(sa) - len(cb))]
    table = _table(((sa, ca), (sb, cb)))
    index = np.arange(len(sa))
    order = table.fit_motion(index, index)
    tried = _tried_turns(monkeypatch)
    match_strokes(sa, sb, ca, cb)
    assert any(abs(a - order[0]) < 1e-12 for a in tried)
    monkeypatch.setattr(motion_search, "MATCH_ORDER_GATE", 0)
    tried.clear()
    match_strokes(sa, sb, ca, cb)
    explained = table.explained(index, index, order)
    assert (explained >= motion_search.MATCH_ORDER_EXPLAINS) == any(abs(a - order[0]) < 1e-12 for a in tried)


def _candidates_per_stroke(n):
    """Pairs a stroke of ``n`` reordered hatch lines may form (its place term alone below the
    limit), on average over the strokes."""
    a, b, _ = bench_drawings.reordered_hatching(n, 3)
    table = _table(((a, [False] * n), (b, [False] * n)))
    return len(table.near(1.0 + 0j, 0j)[0]) / n


def test_a_hatch_line_reaches_as_many_candidates_however_many_lines_are_drawn():
    # The floor of the pairs' spread follows the strokes' spacing beyond DOT_SPREAD_STROKES
    # strokes: drawn on the same grid, 1,600 lines give each line about as many candidates as
    # 800 (333 against 293, the grid's edges cut fewer neighbourhoods; relative to the
    # drawing's size only, 957 against 466: quadratic growth).
    small, large = _candidates_per_stroke(800), _candidates_per_stroke(1600)
    assert large <= 1.25 * small
    # ... and up to that count, the floor is the drawing's share, as it always was.
    a, b, _ = bench_drawings.reordered_hatching(100, 3)
    table = _table(((a, [False] * 100), (b, [False] * 100)))
    keys = [descriptors.KeyDescriptors(k, [False] * 100, "a", "c", descriptors.MATCH_SAMPLES) for k in (a, b)]
    assert table.dot_spread == descriptors.DOT_SPREAD * max(k.diagonal for k in keys)


def _moved_hatching(n, seed, far, angle, turn=0.0):
    """Reordered hatch lines (key A) and a motion moving them ``far`` of the drawing's width
    towards ``angle``, turned by ``turn`` (radians): the table and the motion."""
    a, b, _ = bench_drawings.reordered_hatching(n, seed)
    width = 0.3 * np.ceil(np.sqrt(n))
    table = _table(((a, [False] * n), (b, [False] * n)), whole=True)
    return table, (np.exp(1j * turn), far * width * np.exp(1j * angle))


@settings(max_examples=12, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.8, 1.4), st.floats(-np.pi, np.pi), st.floats(-0.3, 0.3))
def test_every_pair_that_may_form_solves_as_the_whole_table(seed, far, angle, turn):
    # Where few pairs may form at a motion (key A moved across key B), the solve on those pairs
    # alone is optimal on the whole table: the same total (between look-alike strokes on a
    # grid, another assignment may tie within the round-off of the pairs' fits).
    n = int(np.random.default_rng(seed).integers(450, 650))
    table, motion = _moved_hatching(n, seed, far, angle, turn)
    solved = certified._assign_every(table, motion)
    if solved is certified._UNSETTLED:
        return
    whole = certified._assign_within(table.costs(*motion))
    totals = [certified.padded_total(table.costs(*motion, *pairs), n, n) for pairs in (solved, whole)]
    assert totals[0] == pytest.approx(totals[1], rel=0, abs=motion_search.MATCH_ROUNDOFF * n)


def test_every_pair_that_may_form_is_often_few_across_a_drawing():
    # (The property above would hold vacuously if the pairs were never few.)
    settled = [
        certified._assign_every(*_moved_hatching(500, seed, 1.0, seed)) is not certified._UNSETTLED for seed in range(6)
    ]
    assert sum(settled) >= 3


def test_hatching_moved_across_itself_is_never_priced_whole(monkeypatch):
    # 1,000 hatch lines moved by most of the drawing: at no motion, not even before the ink's
    # shift is guessed, is the whole table priced; few pairs may form at each.
    assert _hatching_matched_without_the_whole_table(monkeypatch, 1000, np.array([8.0, 5.0])) == (True, True)


def test_where_most_pairs_may_form_they_are_not_listed_before_the_whole_table(monkeypatch):
    # The benchmark's 400 open strokes: the near pairs do not settle the first motion, and they
    # say the pairs that may form are most of the table (96,000 of 160,000): the whole table is
    # priced without listing them first.
    key_a, key_b = bench_drawings.make_keys("open", 400, 50)
    levels = []
    real = costs.CostTable.near

    def spy(table, a, b, level=costs.MATCH_MAX_COST, only_a=None, only_b=None):
        if only_a is None and only_b is None:  # (a widening lists a few strokes' pairs)
            levels.append(level)
        return real(table, a, b, level, only_a, only_b)

    monkeypatch.setattr(costs.CostTable, "near", spy)
    monkeypatch.setattr(costs, "MATCH_WHOLE_MOST", 400 * 400)  # (the whole-table path's own test)
    flags = [False] * 400
    match_strokes(key_a, key_b, flags, flags)
    assert certified.MATCH_NEAR_COST in levels and costs.MATCH_MAX_COST not in levels
