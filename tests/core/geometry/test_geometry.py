"""geometry/ and the typed data between the ball-map's steps, tested directly against brute force."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapes import circle, distance_to_polyline

from ballmorph_core.ballmap.onemap import OneWayMap
from ballmorph_core.geometry import intersections, polyline, projection, spatial
from ballmorph_core.geometry.circles import circumcircles
from ballmorph_core.geometry.intersections import (
    batch_crossings,
    crossings,
    is_simple,
    matched_hits,
    segment_hits,
    self_crossings,
    simple_curves,
)
from ballmorph_core.geometry.polyline import (
    COARSEN_RATIO,
    already_clean,
    as_curve,
    coarsen,
    default_spacing,
    default_spacings,
    pair_scales,
    points_in_loop,
    reversal_order,
    reverse,
    reversed_fractions,
    scale_of,
    subcurve,
)
from ballmorph_core.geometry.projection import (
    FollowedQueries,
    NearestEdges,
    PolylineProjector,
    distances_to_polyline,
    nearest_within,
)
from ballmorph_core.geometry.ragged import Ragged, budget_slices, group_argmin, ragged_arange
from ballmorph_core.geometry.spatial import CurveTree, PointTree, _box_reach, box_pair_chunks, box_pairs
from ballmorph_core.geometry.vectors import row_norms, unit_left

POINTS = st.integers(0, 2**32 - 1).map(lambda seed: np.random.default_rng(seed).uniform(-1, 1, (60, 2)))


def _wobbly(n, seed, closed=True):
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * np.pi, n, endpoint=not closed)
    r = 1 + 0.3 * np.sin(3 * t + rng.uniform(0, 6)) + 0.05 * rng.standard_normal(n)
    return np.c_[r * np.cos(t), r * np.sin(t)] + rng.uniform(-0.5, 0.5, 2)


# ------------------------------------------------------------------ ragged arrays


def test_row_norms_are_numpys_norms_bit_for_bit():
    """Lengths column by column (the paths', the splines', unit_left's) against
    np.linalg.norm(axis=-1): rows of every scale, zeros, subnormals, values whose squares
    overflow, a strided view and a batch of batches."""
    rng = np.random.default_rng(3)
    v = rng.standard_normal((4000, 2)) * 10.0 ** rng.integers(-320, 300, (4000, 1))
    v[:5] = [[0.0, 0.0], [-0.0, 5e-324], [1e300, 1e300], [3.0, -4.0], [np.inf, 1.0]]
    with np.errstate(over="ignore"):
        for rows in (v, v[::3], v.reshape(40, 100, 2)):
            np.testing.assert_array_equal(row_norms(rows), np.linalg.norm(rows, axis=-1))


def test_unit_left_is_the_row_wise_normal_bit_for_bit():
    """Column by column, unit_left gives the values of the row-wise form it replaced (a norm
    along the last axis, a division where it is positive, the turn), signs of zeros included."""
    rng = np.random.default_rng(3)
    scaled = rng.normal(size=(2000, 2)) * 10.0 ** rng.uniform(-150, 150, (2000, 1))
    for v in (scaled, rng.normal(size=(4, 3, 2)), np.array([[0.0, -0.0], [-0.0, 0.0], [3.0, 4.0], [5e-324, 0.0]])):
        norm = np.linalg.norm(v, axis=-1, keepdims=True)
        u = np.divide(v, norm, out=np.zeros_like(v), where=norm > 0)
        want = np.stack([-u[..., 1], u[..., 0]], axis=-1)
        got = unit_left(v)
        assert got.shape == want.shape
        np.testing.assert_array_equal(got, want)
        np.testing.assert_array_equal(np.signbit(got), np.signbit(want))


def test_ragged_arange_and_budget_slices():
    owner, local = ragged_arange([3, 0, 2])
    assert owner.tolist() == [0, 0, 0, 2, 2] and local.tolist() == [0, 1, 2, 0, 1]
    slices = list(budget_slices([5, 1, 1, 9, 2], 6))
    assert [(s.start, s.stop) for s in slices] == [(0, 2), (2, 3), (3, 4), (4, 5)]
    assert list(budget_slices([], 6)) == []


def test_group_argmin_finds_the_first_minimum_of_each_group():
    values = np.array([3.0, 1.0, 1.0, 5.0, 0.5, 7.0])
    owner = np.array([0, 0, 0, 2, 2, 3])
    assert group_argmin(values, owner, 4).tolist() == [1, 0, 4, 5]
    # A group whose minimum is NaN gets 0 like an empty one; the others are untouched.
    values[3:5] = np.nan
    assert group_argmin(values, owner, 4).tolist() == [1, 0, 0, 5]


def test_global_arc_lengths_are_made_once_and_shifted_per_curve():
    curves = [np.array([[0.0, 0.0], [3.0, 4.0]]), np.array([[1.0, 1.0], [1.0, 2.0], [2.0, 2.0]])]
    batch = Ragged.from_list(curves, False)
    g, base = batch.global_s()
    assert batch.global_s()[0] is g  # kept for every locate
    # Each curve is followed by a gap of the longest one's length (5), not of 1.0: the same
    # shifts at any scale (issue 41: a gap of 1.0 swamped a tiny drawing's lengths in round-off).
    np.testing.assert_array_equal(base, [0.0, 10.0])
    np.testing.assert_array_equal(g, [0.0, 5.0, 10.0, 11.0, 12.0])
    tiny = Ragged.from_list([c * 2.0**-40 for c in curves], False).global_s()
    np.testing.assert_array_equal(tiny[0], g * 2.0**-40)


def test_ragged_boxes_of_curves_with_and_without_points():
    """Each curve's box from its own points; a curve without any (first, between, last) gets NaN."""
    a, b = np.array([[0.0, 1.0], [2.0, -1.0], [1.0, 3.0]]), np.array([[5.0, 5.0]])
    empty = np.zeros((0, 2))
    boxes = Ragged.from_list([empty, a, empty, empty, b, empty], False).boxes()
    assert np.isnan(boxes[[0, 2, 3, 5]]).all()
    np.testing.assert_array_equal(boxes[[1, 4]], [[0.0, -1.0, 2.0, 3.0], [5.0, 5.0, 5.0, 5.0]])
    assert Ragged.from_list([empty], False).boxes().shape == (1, 4)


def test_ragged_measures_each_curve_as_the_single_curve_functions_do():
    a, b = circle(1.0, 40), _wobbly(30, 1, closed=False)
    rg = Ragged.from_list([a, b], [True, False])
    np.testing.assert_allclose(
        rg.length, [2 * 40 * np.sin(np.pi / 40), np.linalg.norm(np.diff(b, axis=0), axis=1).sum()]
    )
    assert rg.n_edges.tolist() == [40, 29]
    np.testing.assert_allclose(rg.boxes()[1], [*b.min(axis=0), *b.max(axis=0)])
    piece = rg.pieces(np.array([0]), np.array([1.0]), np.array([2.0]))
    np.testing.assert_allclose(piece.curve(0), subcurve(a, True, 1.0, 2.0))


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=40)
def test_pieces_are_the_ends_points_and_the_vertices_strictly_between(seed):
    """Stretches of open curves and loops (some running on past a loop's first vertex, some
    of one curve only, some shorter than an edge): the point at s0, every vertex whose arc
    length lies strictly between (a loop's second lap after its first), the point at s1."""
    rng = np.random.default_rng(seed)
    closed = rng.integers(0, 2, 4).astype(bool)
    curves = [_wobbly(int(rng.integers(3, 30)), int(rng.integers(1, 4)), closed=bool(c)) for c in closed]
    rg = Ragged.from_list(curves, closed)
    curve = rng.integers(0, 4, 12)
    length = rg.length[curve]
    s0 = rng.uniform(0, 1, 12) * length
    s1 = s0 + rng.uniform(0, 1, 12) * np.where(rg.closed[curve], length, length - s0)
    got = rg.pieces(curve, s0, s1)
    for k, c in enumerate(curve):
        s, pts = rg.s[rg.offsets[c] : rg.offsets[c + 1]], rg.curve(c)
        laps = [(s, pts), (s + length[k], pts)] if rg.closed[c] else [(s, pts)]
        between = [p for lap_s, lap_pts in laps for t, p in zip(lap_s, lap_pts) if s0[k] < t < s1[k]]
        end = s1[k] - length[k] if rg.closed[c] and s1[k] > length[k] else s1[k]
        first, last = (rg.point_at(np.array([c]), np.array([at])) for at in (s0[k], end))
        want = np.vstack([first, *between, last])
        np.testing.assert_array_equal(got.curve(k), want)


@given(POINTS)
@settings(max_examples=20)
def test_containment_matches_brute_force(points):
    loop = _wobbly(50, 3)
    rg = Ragged.from_list([circle(0.2, 10), loop], [True, True])
    got = rg.contains(points, np.ones(len(points), dtype=np.int64))
    np.testing.assert_array_equal(got, points_in_loop(points, loop))
    # brute force: winding number
    d = loop[None] - points[:, None]
    ang = np.arctan2(d[..., 1], d[..., 0])
    turn = np.mod(np.diff(np.concatenate([ang, ang[:, :1]], axis=1), axis=1) + np.pi, 2 * np.pi) - np.pi
    np.testing.assert_array_equal(got, np.abs(turn.sum(axis=1)) > np.pi)


def test_reversal_helpers_agree_with_reverse():
    c = _wobbly(12, 4)
    for closed in (True, False):
        np.testing.assert_array_equal(c[reversal_order(len(c), closed)], reverse(c, closed))
    u = np.array([0.0, 0.25, 0.9])
    np.testing.assert_allclose(reversed_fractions(u, True), [0.0, 0.75, 0.1])
    np.testing.assert_allclose(reversed_fractions(u, False), [1.0, 0.75, 0.1])


def test_batched_spacings_and_scales_are_the_single_ones():
    curves_a = [_wobbly(40, k) for k in range(4)]
    curves_b = [1.5 * _wobbly(25, k + 9) for k in range(4)]
    A, B = Ragged.from_list(curves_a, True), Ragged.from_list(curves_b, True)
    want = [default_spacing(a, b, closed=True) for a, b in zip(curves_a, curves_b)]
    np.testing.assert_allclose(default_spacings(A, B), want, rtol=1e-12)
    np.testing.assert_allclose(pair_scales(A, B), [scale_of(a, b) for a, b in zip(curves_a, curves_b)], rtol=1e-12)


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=30)
def test_default_spacings_take_each_groups_exact_median_edge(seed):
    """Curve c of every batch is one group: its spacing comes from the median of all their edge
    lengths (np.median, exactly), whether the groups are of similar sizes (a padded table) or
    one dwarfs the others (one sort of every edge)."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 6))
    sizes = rng.integers(0, 12, (2, n))
    if rng.random() < 0.5:
        sizes[0, 0] = 600  # one group far larger: the padded table would be mostly padding
    batches = [
        Ragged.from_list([np.cumsum(rng.normal(size=(k, 2)), axis=0) for k in row], rng.random(n) < 0.5)
        for row in sizes
    ]
    got = default_spacings(*batches)
    for c in range(n):
        edges = np.concatenate(
            [
                b.length_of_edge[b.offsets[c] : b.offsets[c + 1]][b.nxt[b.offsets[c] : b.offsets[c + 1]] >= 0]
                for b in batches
            ]
        )
        longest = max(b.length[c] for b in batches)
        want = np.clip(
            np.median(edges) if len(edges) else 0.0,
            longest / polyline.DEFAULT_SAMPLES_MAX,
            longest / polyline.DEFAULT_SAMPLES_MIN,
        )
        assert got[c] == want


# ------------------------------------------------------------------ spatial search


@given(POINTS, POINTS)
@settings(max_examples=20)
def test_box_pairs_finds_exactly_the_overlapping_boxes(a, b):
    boxes_a = np.c_[a, a + 0.2]
    boxes_b = np.c_[b, b + 0.05]
    i, j = box_pairs(boxes_a, boxes_b)
    ba, bb = boxes_a[:, None], boxes_b[None]
    overlap = (
        (ba[..., 0] <= bb[..., 2])
        & (bb[..., 0] <= ba[..., 2])
        & (ba[..., 1] <= bb[..., 3])
        & (bb[..., 1] <= ba[..., 3])
    )
    assert sorted(zip(i.tolist(), j.tolist())) == sorted(zip(*np.nonzero(overlap)))


def _overlapping(ba, bb):
    """Brute force: (i, j) of every pair of overlapping boxes, sorted."""
    ba, bb = ba[:, None], bb[None]
    overlap = (ba[..., 0] <= bb[..., 2]) & (bb[..., 0] <= ba[..., 2]) & (ba[..., 1] <= bb[..., 3])
    return sorted(zip(*np.nonzero(overlap & (bb[..., 1] <= ba[..., 3]))))


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=30)
def test_box_pairs_of_points_tiny_and_long_boxes_are_exact(seed):
    """Points, tiny boxes and boxes spanning the whole set (the grid grows its cells for them),
    far from the origin, between two sets and within one (i < j)."""
    rng = np.random.default_rng(seed)
    sets = []
    for n in rng.integers(1, 60, 2):
        low = rng.uniform(-1, 1, (n, 2)) + 1e3
        size = rng.choice([0.0, 1e-3, 0.05, 3.0], size=(n, 1)) * rng.uniform(0, 1, (n, 2))
        sets.append(np.c_[low, low + size])
    i, j = box_pairs(*sets)
    assert sorted(zip(i.tolist(), j.tolist())) == _overlapping(*sets)
    # The same boxes as four columns each (no rows made).
    runs = list(box_pair_chunks(*(tuple(s.T) for s in sets)))
    np.testing.assert_array_equal(np.concatenate([r[0] for r in runs]) if runs else [], i)
    np.testing.assert_array_equal(np.concatenate([r[1] for r in runs]) if runs else [], j)
    i, j = box_pairs(sets[0])
    assert sorted(zip(i.tolist(), j.tolist())) == [(p, q) for p, q in _overlapping(sets[0], sets[0]) if p < q]


def _grid_only(function, *args, **kwargs):
    """``function`` with the grid for every size of box sets (no direct pairing)."""
    saved, spatial.DIRECT_PAIRS = spatial.DIRECT_PAIRS, 0
    try:
        return function(*args, **kwargs)
    finally:
        spatial.DIRECT_PAIRS = saved


@given(st.integers(0, 2**32 - 1), st.booleans())
@settings(max_examples=40)
def test_small_box_sets_paired_directly_give_the_grids_pairs(seed, within_one):
    """Few boxes are paired by testing every pair: the grid's pairs, in its order (by i then
    j, i < j within one set), inactive boxes of the first set left out."""
    rng = np.random.default_rng(seed)
    sets = []
    for n in rng.integers(1, 64, 2):
        low = rng.uniform(-1, 1, (n, 2)) * rng.choice([1e-3, 1.0, 1e3])
        sets.append(np.c_[low, low + rng.choice([0.0, 0.01, 0.3, 5.0], size=(n, 1)) * rng.uniform(0, 1, (n, 2))])
    sets = sets[:1] if within_one else sets
    active = rng.random(len(sets[0])) < 0.8
    assert len(sets[0]) * len(sets[-1]) <= spatial.DIRECT_PAIRS
    for kwargs in ({}, {"active": active}):
        direct = list(box_pair_chunks(*sets, **kwargs))
        grid = list(_grid_only(lambda kw: list(box_pair_chunks(*sets, **kw)), kwargs))
        for k in range(2):
            np.testing.assert_array_equal(
                np.concatenate([r[k] for r in direct]), np.concatenate([r[k] for r in grid] or [np.zeros(0, int)])
            )


@given(POINTS, st.integers(1, 400))
@settings(max_examples=20)
def test_box_pair_runs_join_into_box_pairs_and_skip_inactive_boxes(a, budget):
    # The grid's runs (small sets like these are otherwise paired directly, in one run).
    _grid_only(_runs_join_and_skip, np.c_[a, a + 0.5], budget)


def _runs_join_and_skip(boxes, budget):
    runs = list(box_pair_chunks(boxes, budget=budget))
    i, j = box_pairs(boxes)
    np.testing.assert_array_equal(np.concatenate([r[0] for r in runs]) if runs else [], i)
    np.testing.assert_array_equal(np.concatenate([r[1] for r in runs]) if runs else [], j)
    # Boxes cleared between runs are not looked up again.
    active = np.ones(len(boxes), dtype=bool)
    seen = []
    for ri, _ in box_pair_chunks(boxes, budget=budget, active=active):
        seen.append(ri)
        active[:] = False
    assert len(np.concatenate(seen)) == len(runs[0][0]) if runs else not seen


@given(POINTS, POINTS)
@settings(max_examples=20)
def test_point_tree_nearest_and_within_match_brute_force(points, queries):
    tree = PointTree(points, leaf_size=4)
    d2 = ((queries[:, None] - points[None]) ** 2).sum(axis=2)
    np.testing.assert_allclose(tree.nearest_d2(queries), d2.min(axis=1))
    radii = np.full(len(queries), 0.3)
    q, p = tree.within(queries, radii)
    assert sorted(zip(q.tolist(), p.tolist())) == sorted(zip(*np.nonzero(d2 < 0.09)))


@pytest.mark.parametrize("seed", range(4))
def test_point_tree_nodes_hold_their_items_split_at_the_median_of_the_wider_side(seed):
    # Boxes on a coarse grid (many equal coordinates) in three groups, rebuilt level by level:
    # every node's box is its items' box, and its children are its items in (stable) order of
    # their centres along its wider side, cut in half.
    rng = np.random.default_rng(seed)
    lows = np.round(rng.random((2000, 2)) * 6) / 6
    highs = lows + np.round(rng.random((2000, 2)) * 3) / 30
    tree = PointTree(lows, 4, highs=highs, groups=np.array([0, 40, 41, 2000]))
    centres = 0.5 * (lows + highs)
    perm = np.arange(2000)
    for depth, (starts, ends, boxes) in enumerate(tree.levels):
        for k in np.flatnonzero(ends > starts):
            mine = perm[starts[k] : ends[k]]
            np.testing.assert_array_equal(boxes[:, k], [*lows[mine].min(axis=0), *highs[mine].max(axis=0)])
            if depth + 1 < len(tree.levels):
                axis = int(boxes[2, k] - boxes[0, k] < boxes[3, k] - boxes[1, k])
                perm[starts[k] : ends[k]] = mine[np.argsort(centres[mine, axis], kind="stable")]
        if depth + 1 < len(tree.levels):
            np.testing.assert_array_equal(tree.levels[depth + 1][0][::2], starts)
    np.testing.assert_array_equal(perm, tree.perm)


def test_curve_tree_searches_only_the_curves_named():
    a, b = _wobbly(80, 5), _wobbly(70, 6) + 0.1
    pts = np.concatenate([a, b])
    tree = CurveTree(pts, [0, 80, 150], leaf_size=4)
    centres = np.array([[0.0, 0.0], [0.5, 0.5]])
    q, p = tree.within(centres, np.array([1.0, 0.8]), np.array([[1], [0]]))
    d2 = ((centres[:, None] - pts[None]) ** 2).sum(axis=2)
    want = [(0, k) for k in range(80, 150) if d2[0, k] < 1.0] + [(1, k) for k in range(80) if d2[1, k] < 0.64]
    assert sorted(zip(q.tolist(), p.tolist())) == sorted(want)


# ------------------------------------------------------------------ closest points, crossings, circles


@given(POINTS)
@settings(max_examples=20)
def test_closest_points_match_brute_force(queries):
    curve = _wobbly(45, 7, closed=False)
    dist, _ = distances_to_polyline(queries, curve, False, np.inf)
    np.testing.assert_allclose(dist, distance_to_polyline(queries, curve, False), atol=1e-12)
    projector = PolylineProjector(curve, False)
    feet = projector.foot(*projector.nearest(queries))
    np.testing.assert_allclose(np.linalg.norm(feet - queries, axis=1), dist, atol=1e-12)
    near, _, _ = nearest_within(queries, np.zeros(len(queries), np.int64), Ragged.from_list([curve], [False]), 0.1)
    np.testing.assert_array_equal(np.isfinite(near), dist <= 0.1)
    np.testing.assert_allclose(near[dist <= 0.1], dist[dist <= 0.1], atol=1e-12)


@given(st.integers(0, 2**32 - 1), st.sampled_from([None, 0.1, 0.5]))
@settings(max_examples=20)
def test_nearest_edge_on_long_edges_matches_brute_force(seed, reach):
    # A scribble: every edge spans the drawing, so the search cuts them into pieces and widens
    # step by step; the answer is still the closest point within the reach.
    rng = np.random.default_rng(seed)
    curve = rng.random((rng.integers(2, 300), 2))
    queries = rng.uniform(-0.2, 1.2, (50, 2))
    limit = np.inf if reach is None else reach
    near, edge, frac = nearest_within(queries, np.zeros(50, np.int64), Ragged.from_list([curve], [False]), limit)
    brute = distance_to_polyline(queries, curve, False)
    np.testing.assert_array_equal(np.isfinite(near), brute <= limit)
    np.testing.assert_allclose(near[np.isfinite(near)], brute[np.isfinite(near)], atol=1e-12)
    feet = curve[edge] + frac[:, None] * (curve[np.minimum(edge + 1, len(curve) - 1)] - curve[edge])
    np.testing.assert_allclose(np.linalg.norm(feet - queries, axis=1)[np.isfinite(near)], near[np.isfinite(near)])


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=30)
def test_box_reach_is_the_nearest_and_farthest_point_of_each_box(seed):
    # Points inside, beside and on the boxes, boxes of zero size, and empty nodes (NaN): the
    # squared distances to the nearest and farthest points, operation for operation.
    rng = np.random.default_rng(seed)
    k = 200
    lo = rng.uniform(-1, 1, (k, 2))
    hi = lo + rng.choice([0.0, 0.3, 1.0], (k, 1)) * rng.random((k, 2))
    boxes = np.concatenate([lo, hi], axis=1).T.copy()
    boxes[:, rng.random(k) < 0.1] = np.nan
    centres = np.where(rng.random((k, 1)) < 0.2, lo, rng.uniform(-1.5, 1.5, (k, 2))).T.copy()
    (x0, y0, x1, y1), (cx, cy) = boxes, centres
    dx, dy = np.maximum(np.maximum(x0 - cx, cx - x1), 0.0), np.maximum(np.maximum(y0 - cy, cy - y1), 0.0)
    fx, fy = np.maximum(np.abs(x0 - cx), np.abs(x1 - cx)), np.maximum(np.abs(y0 - cy), np.abs(y1 - cy))
    near2, far2 = _box_reach(boxes, centres)
    np.testing.assert_array_equal(near2, dx * dx + dy * dy)
    np.testing.assert_array_equal(far2, fx * fx + fy * fy)


@given(st.integers(0, 2**32 - 1), st.integers(1, 9))
@settings(max_examples=30)
def test_leaf_points_are_every_point_of_each_pairs_leaf_in_order(seed, leaf_size):
    # The leaves' expansion (nearest_candidates, within, nearest_d2): pair after pair, the
    # query with each point of its leaf, as one loop over the pairs lists them.
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 300))
    groups = np.unique(np.r_[0, rng.integers(0, n, 3), n])
    tree = PointTree(rng.random((n, 2)), leaf_size, groups=groups)
    leaves = len(tree.levels[-1][0])
    q = np.sort(rng.integers(0, 50, 80))
    node = rng.integers(0, leaves, 80)
    starts, ends, _ = tree.levels[-1]
    want_q = np.concatenate([np.full(ends[v] - starts[v], a) for a, v in zip(q, node)])
    want_p = np.concatenate([tree.perm[starts[v] : ends[v]] for v in node])
    got_q, got_p = tree._leaf_points(q, node)
    np.testing.assert_array_equal(got_q, want_q)
    np.testing.assert_array_equal(got_p, want_p)


def _nearest_edges_brute(points, owner, curves, reach):
    # Every edge of the query's curve, measured as the search measures it; ties to the lower edge.
    e = np.flatnonzero(curves.nxt >= 0)
    dist, edge, frac = np.full(len(points), np.inf), np.zeros(len(points), np.int64), np.zeros(len(points))
    for k, x in enumerate(points):
        j = e[curves.owner[e] == owner[k]]
        a, d = curves.pts[j], curves.edge[j]
        ee = np.einsum("ij,ij->i", d, d)
        f = np.divide(np.einsum("ij,ij->i", x - a, d), ee, out=np.zeros_like(ee), where=ee > 0)
        f = np.clip(f, 0, 1)
        d2 = np.sum(np.square(a + f[:, None] * d - x), axis=1)
        best = np.lexsort((j, d2))[0]
        if len(j) and d2[best] <= reach[k] ** 2:
            dist[k], edge[k], frac[k] = np.sqrt(d2[best]), j[best], f[best]
    return dist, edge, frac


@given(st.integers(0, 2**32 - 1), st.sampled_from(["wobbly", "scribble", "mixed"]))
@settings(max_examples=30, deadline=None)
def test_nearest_edges_match_brute_force_edge_and_fraction(seed, kind):
    # The same edge and fraction as measuring every edge (not just the same distance), for
    # batches of curves, searched twice with one NearestEdges (as the sliding fit does).
    rng = np.random.default_rng(seed)
    curves = []
    for c in range(rng.integers(1, 5)):
        n = int(rng.integers(2, 120))
        if kind == "scribble" or (kind == "mixed" and c % 2):
            pts = rng.random((n, 2)) + c * 0.3
        else:
            pts = np.cumsum(rng.normal(0, 0.05, (n, 2)), axis=0)
        if rng.random() < 0.3:
            pts[rng.integers(n)] = pts[0]  # a repeated vertex: zero-length edges, exact ties
        curves.append(pts)
    batch = Ragged.from_list(curves, [bool(rng.random() < 0.5) for _ in curves])
    search = NearestEdges(batch)
    for _ in range(2):
        owner = rng.integers(0, len(curves), 60)
        on_vertex = batch.pts[batch.offsets[owner] + rng.integers(0, 2, 60)]
        points = np.where(rng.random((60, 1)) < 0.2, on_vertex, rng.uniform(-0.5, 1.5, (60, 2)))
        reach = rng.choice([0.01, 0.1, 0.5, np.inf], 60)
        got = search.within(points, owner, reach)
        want = _nearest_edges_brute(points, owner, batch, reach)
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g, w)
    one = nearest_within(points, owner, batch, reach)
    for g, w in zip(one, want):
        np.testing.assert_array_equal(g, w)


@given(st.integers(0, 2**32 - 1), st.sampled_from([0, 2, 1000]))
@settings(max_examples=30, deadline=None)
def test_nearest_edges_pick_the_least_candidate_stepping_or_sorting(seed, short_runs):
    # Each query's least candidate, found by stepping through the runs (short ones) or by
    # reduceat and a sort of the ties (long ones): the brute force's edge and fraction, with
    # exact ties (feet on shared and repeated vertices) and pieces of one edge.
    rng = np.random.default_rng(seed)
    curves = []
    for c in range(int(rng.integers(1, 4))):
        n = int(rng.integers(2, 40))
        pts = rng.random((n, 2)) + c * 0.3 if rng.random() < 0.5 else np.cumsum(rng.normal(0, 0.05, (n, 2)), axis=0)
        pts[rng.integers(n)] = pts[0]
        curves.append(pts)
    batch = Ragged.from_list(curves, [bool(rng.random() < 0.5) for _ in curves])
    # Three queries on every curve at least: more than every edge twice, so the tree searches.
    owner = np.r_[rng.integers(0, len(curves), 80), np.repeat(np.arange(len(curves)), 3)]
    k = len(owner)
    on_vertex = batch.pts[batch.offsets[owner] + rng.integers(0, 3, k) % batch.n[owner]]
    points = np.where(rng.random((k, 1)) < 0.4, on_vertex, rng.uniform(-0.5, 1.5, (k, 2)))
    reach = rng.choice([0.01, 0.2, np.inf], k)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(projection, "_SHORT_RUNS", short_runs)
        got = NearestEdges(batch).within(points, owner, reach)
    for g, w in zip(got, _nearest_edges_brute(points, owner, batch, reach)):
        np.testing.assert_array_equal(g, w)


@given(st.integers(0, 2**32 - 1), st.floats(1e-6, 1e6))
@settings(max_examples=40, deadline=None)
def test_nearest_edges_cut_only_reaches_their_far_corner_would(seed, scale):
    # Reaches around the uncut share of the diagonal, from the boxes' centres (whose far corner
    # is half the diagonal away), corners and afar: the very reaches of cutting every one.
    rng = np.random.default_rng(seed)
    curves = [scale * (rng.random((int(rng.integers(1, 8)), 2)) + c) for c in range(3)]
    search = NearestEdges(Ragged.from_list(curves, [False, True, False]))
    box, k = search._curve_boxes, 90
    owner = rng.integers(0, 3, k)
    diagonal = np.hypot(box[owner, 2] - box[owner, 0], box[owner, 3] - box[owner, 1])
    centre, corner = 0.5 * (box[owner, :2] + box[owner, 2:]), box[owner, :2]
    afar = rng.uniform(-2 * scale, 5 * scale, (k, 2))
    points = np.select([rng.random((k, 1)) < 0.4, rng.random((k, 1)) < 0.5], [centre, corner], afar)
    share = rng.choice([0.0, 0.3, projection._UNCUT_DIAGONAL, 0.4901, 0.5, 0.5001, 2.0], k)
    reach = np.where(rng.random(k) < 0.1, np.inf, share * diagonal)
    _, _, got = search._bounded(points, owner, reach)
    np.testing.assert_array_equal(got, search._far_corner_cut(points, owner, reach))
    assert (got < reach).any() and (got == reach).any()


@pytest.mark.parametrize("seed", range(6))
def test_few_queries_per_curve_measure_every_edge_as_the_tree_would(seed):
    # One query per curve (the ends of strokes): every edge of its curve is measured and no
    # tree is built; the very answers of the tree's search (which three queries per curve
    # take: more than every edge twice) and of the brute force.
    rng = np.random.default_rng(seed)
    curves = [np.cumsum(rng.normal(0, 0.05, (int(rng.integers(2, 120)), 2)), axis=0) for _ in range(7)]
    curves[0][3 % len(curves[0])] = curves[0][0]  # a zero-length edge or an exact tie
    batch = Ragged.from_list(curves, [bool(rng.random() < 0.5) for _ in curves])
    owner = rng.permutation(len(curves))
    on_vertex = batch.pts[batch.offsets[owner] + rng.integers(0, 2, len(owner))]
    points = np.where(rng.random((len(owner), 1)) < 0.3, on_vertex, rng.uniform(-0.5, 1.5, (len(owner), 2)))
    reach = rng.choice([0.01, 0.1, 0.5, np.inf], len(owner))
    want = _nearest_edges_brute(points, owner, batch, reach)
    direct = NearestEdges(batch)
    got = direct.within(points, owner, reach)
    assert "_index" not in vars(direct)
    searched = NearestEdges(batch)
    thrice = [np.repeat(a, 3, axis=0) for a in (points, owner, reach)]
    for g, t, w in zip(got, searched.within(*thrice), want):
        np.testing.assert_array_equal(g, w)
        np.testing.assert_array_equal(t, np.repeat(w, 3))
    assert "_index" in vars(searched)


def _drifting(rng, batch, owner, points, rows):
    """Queries of an iterative fit: small steps, a few jumps, a few onto vertices (exact ties)."""
    k = len(points)
    step = rng.normal(0, 0.003, (k, 2)) * np.where(rng.random((k, 1)) < 0.1, 100.0, 1.0)
    on_vertex = batch.pts[batch.offsets[owner] + rng.integers(0, 2, k)]
    return np.where(rng.random((k, 1)) < 0.05, on_vertex, points + step)


@given(st.integers(0, 2**32 - 1), st.sampled_from(["wobbly", "scribble"]), st.sampled_from([0.0, 0.02, 0.2]))
@settings(max_examples=30, deadline=None)
def test_followed_queries_answer_as_the_tree_does(seed, kind, margin):
    # Drifting queries asked in changing subsets: the very edges, fractions and distances.
    rng = np.random.default_rng(seed)
    n_curves = int(rng.integers(1, 4))
    curves = []
    for c in range(n_curves):
        n = int(rng.integers(2, 150))
        walk = np.cumsum(rng.normal(0, 0.05, (n, 2)), axis=0)
        curves.append(rng.random((n, 2)) + c if kind == "scribble" else walk)
    batch = Ragged.from_list(curves, [bool(rng.random() < 0.5) for _ in curves])
    search, k = NearestEdges(batch), 80
    owner = rng.integers(0, n_curves, k)
    followed = FollowedQueries(search, owner, margin)
    _answer_as_the_tree(rng, batch, followed, rng.uniform(-0.5, 1.5, (k, 2)), [0.01, 0.1, np.inf], 8)


def _answer_as_the_tree(rng, batch, followed, points, reaches, steps):
    """Queries drifting ``steps`` times (most of them each time), asked within reaches drawn
    from ``reaches``: every answer of ``followed`` is the tree's."""
    search, owner, k = followed.search, followed.owner, len(points)
    for _ in range(steps):
        rows = np.flatnonzero(rng.random(k) < 0.8)
        points = _drifting(rng, batch, owner, points, rows)
        reach = rng.choice(reaches, len(rows))
        got = followed.within(rows, points[rows], reach)
        want = search.within(points[rows], owner[rows], reach)
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g, w)


def test_followed_queries_that_barely_move_do_not_search_the_tree_again():
    # Asked within their last foot's distance, queries drifting 0.002 find their closest
    # edges among the candidates kept 0.05 wider.
    rng = np.random.default_rng(3)
    t = np.linspace(0, 3, 200)
    batch = Ragged.from_list([np.c_[t, np.sin(t)]], [False])
    search = NearestEdges(batch)
    asked = []
    tree_candidates = search.tree.nearest_candidates
    search.tree.nearest_candidates = lambda x, *args: asked.append(len(x)) or tree_candidates(x, *args)
    points = np.c_[t[::2], np.sin(t[::2]) + 0.05]
    followed = FollowedQueries(search, np.zeros(len(points), np.int64), 0.05)
    reach = np.inf
    for _ in range(3):
        _, edge, frac = followed.within(np.arange(len(points)), points, reach)
        foot = batch.pts[edge] + frac[:, None] * batch.edge[edge]
        points = points + rng.normal(0, 0.002, points.shape)
        reach = np.linalg.norm(points - foot, axis=1) * (1 + 1e-9)  # as the sliding fit bounds them
    assert asked == [len(points)]


@given(st.integers(0, 2**32 - 1), st.sampled_from([1, 3, 8]))
@settings(max_examples=20, deadline=None)
def test_followed_queries_with_more_candidates_than_kept_answer_as_the_tree_does(seed, kept):
    # A query whose search finds more than _KEPT candidates keeps its nearest _KEPT and holds
    # only as far as the first one dropped: still the very answers of the tree.
    rng = np.random.default_rng(seed)
    curves = [np.cumsum(rng.normal(0, 0.05, (int(rng.integers(2, 150)), 2)), axis=0) for _ in range(2)]
    batch = Ragged.from_list(curves, [False, True])
    search, k = NearestEdges(batch), 60
    owner = rng.integers(0, 2, k)
    points = rng.uniform(-0.5, 1.0, (k, 2))
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(projection, "_KEPT", kept)
        _answer_as_the_tree(rng, batch, FollowedQueries(search, owner, 0.1), points, [0.05, 0.3, np.inf], 6)


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=20, deadline=None)
def test_followed_queries_on_short_curves_keep_every_piece_in_narrow_tables(seed):
    # Short scribbles (long edges cut into pieces): the kept tables are as wide as the most
    # pieces a curve has, fewer than _KEPT, and a query taking every piece of its curve (an
    # unbounded margin) keeps them all; its answers stay the tree's as it drifts.
    rng = np.random.default_rng(seed)
    curves = [rng.random((int(rng.integers(2, 6)), 2)) + c for c in range(3)]
    batch = Ragged.from_list(curves, [bool(rng.random() < 0.5) for _ in curves])
    search, k = NearestEdges(batch), 40
    pieces = np.bincount(batch.owner[search.e[search.piece_edge]], minlength=3)
    owner = rng.integers(0, 3, k)
    followed = FollowedQueries(search, owner, np.inf)
    assert followed.width == pieces.max() < projection._KEPT
    points = rng.uniform(-0.5, 3.5, (k, 2))
    followed.within(np.arange(k), points, np.full(k, np.inf))
    np.testing.assert_array_equal(followed.count, pieces[owner])
    _answer_as_the_tree(rng, batch, followed, points, [0.01, 0.3, np.inf], 6)


def test_followed_queries_settle_on_a_kept_edge_and_measure_only_those_within_reach():
    # Asked with no reach (the far corner of the curve, far beyond what they hold), queries
    # drifting 0.002 still settle: their closest kept edge lies within what they hold, so no
    # other edge can be closer. Of the edges kept 0.3 wider, only those within their last
    # foot's distance plus their move are measured.
    rng = np.random.default_rng(5)
    t = np.linspace(0, 3, 300)
    batch = Ragged.from_list([np.c_[t, np.sin(t)]], [False])
    search = NearestEdges(batch)
    asked, measured = [], []
    tree_candidates, closest = search.tree.nearest_candidates, search._closest
    search.tree.nearest_candidates = lambda x, *args: asked.append(len(x)) or tree_candidates(x, *args)
    search._closest = lambda out, rows, x, i, *args: measured.append(len(i)) or closest(out, rows, x, i, *args)
    points = np.c_[t[::3], np.sin(t[::3]) + 0.05]
    followed = FollowedQueries(search, np.zeros(len(points), np.int64), 0.3)
    for _ in range(3):
        followed.within(np.arange(len(points)), points, np.full(len(points), np.inf))
        points = points + rng.normal(0, 0.002, points.shape)
    assert asked == [len(points)]
    foot = NearestEdges(batch).within(points, np.zeros(len(points), np.int64), np.inf)
    reach = foot[0] * (1 + 1e-9)
    measured.clear()
    got = followed.within(np.arange(len(points)), points, reach)
    for g, w in zip(got, foot):
        np.testing.assert_array_equal(g, w)
    assert asked == [len(points)]
    assert measured[0] < 0.25 * followed.count.sum()


@given(st.integers(0, 2**32 - 1), st.booleans())
@settings(max_examples=40)
def test_is_simple_stops_early_but_agrees_with_every_self_crossing(seed, closed):
    # Random walks: short ones are often simple, long ones cross themselves.
    rng = np.random.default_rng(seed)
    curve = np.cumsum(rng.standard_normal((rng.integers(3, 200), 2)), axis=0)
    assert is_simple(curve, closed) == (len(self_crossings(curve, closed)) == 0)


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=30)
def test_simple_curves_answers_each_curve_as_is_simple_does(seed):
    """Random walks (often crossing themselves), a loop with a repeated point, a fold-back
    spike and single points, open and closed, lying over each other: each curve's answer is
    its own (its self-crossings or spikes; another curve's segments never count), and equals
    what its self-crossings and spikes say."""
    rng = np.random.default_rng(seed)
    curves = [np.cumsum(rng.standard_normal((int(rng.integers(3, 60)), 2)), axis=0) for _ in range(6)]
    ring = circle(1.0, 30)
    curves += [np.insert(ring, 7, ring[7], axis=0), np.c_[[0.0, 1.0, 0.4, 2.0], [0.0, 0.0, 0.0, 0.0]], np.zeros((1, 2))]
    closed = rng.random(len(curves)) < 0.5
    closed[6] = True
    got = simple_curves(curves, closed)
    for curve, loop, answer in zip(curves, closed, got):
        crossing = len(self_crossings(curve, loop)) > 0 if len(curve) > 1 else False
        assert answer == is_simple(curve, loop)
        assert not answer or not crossing
    assert got[6] and not got[7]  # the repeated point is no crossing; the spike folds back
    assert simple_curves([], []).shape == (0,)


def test_simple_curves_searches_a_curve_that_meets_itself_no_further(monkeypatch):
    """A scribble that crosses itself thousands of times is not searched past its first run
    of candidates; a simple curve beside it still is, to the end."""
    rng = np.random.default_rng(4)
    scribble = rng.random((400, 2))
    runs = []
    real = intersections.box_pair_chunks

    def spy(boxes, *args, active=None, **kwargs):
        for i, j in real(boxes, *args, active=active, budget=2000, **kwargs):
            runs.append(int(active.sum()))
            yield i, j

    monkeypatch.setattr(intersections, "box_pair_chunks", spy)
    line = np.c_[np.linspace(5.0, 9.0, 400), np.zeros(400)]
    assert simple_curves([scribble, line], [False, False]).tolist() == [False, True]
    assert runs[0] == 399 + 399 and runs[-1] == 399  # the scribble's edges cleared after its first run


def test_crossing_budget_stops_a_crowded_pair_only():
    # Two combs whose teeth all cross (about 1,700 crossings for 60 + 60 points), and a pair
    # of circles crossing twice: only the combs are cut short, the circles' crossings are whole.
    x, y = np.linspace(0, 1, 60), np.tile([0.0, 1.0], 30)
    p, q = np.c_[x, y], np.c_[y, x]
    c0, c1 = circle(1.0, 40), circle(1.0, 40, centre=(0.5, 0.0))
    A, B = Ragged.from_list([p, c0], [False, True]), Ragged.from_list([q, c1], [False, True])
    scale = pair_scales(A, B)
    everything = batch_crossings(A, B, scale)
    assert np.sum(everything.pair == 0) > 1000 and not everything.crowded.any()
    budget = batch_crossings(A, B, scale, max_hits=np.array([500, 500]))
    assert budget.crowded.tolist() == [True, False]
    assert np.sum(budget.pair == 0) == 0
    np.testing.assert_array_equal(budget.s_a, everything.s_a[everything.pair == 1])


@given(st.integers(0, 2**32 - 1), st.sampled_from([16, 1 << 18]))
@settings(max_examples=30)
def test_candidates_are_the_edge_pairs_of_each_pair_whose_boxes_overlap(seed, budget):
    # Curves of 1 to 30 points (shorter and longer than a run of boxed edges), open and closed;
    # a small budget makes many runs of the grid.
    rng = np.random.default_rng(seed)
    sizes = rng.integers(1, 30, (2, 4))
    closed = rng.random(4) < 0.5
    A, B = (Ragged.from_list([np.cumsum(rng.normal(0, 0.3, (n, 2)), axis=0) for n in row], closed) for row in sizes)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(intersections, "PAIR_BUDGET", budget)
        ga, gb, crowded, hits = intersections._candidates(A, B, None, np.ones(4), None)
    ea, eb = np.flatnonzero(A.nxt >= 0), np.flatnonzero(B.nxt >= 0)
    box = [
        np.c_[np.minimum(r.pts[e], r.pts[e] + r.edge[e]), np.maximum(r.pts[e], r.pts[e] + r.edge[e])]
        for r, e in ((A, ea), (B, eb))
    ]
    want = [(ea[i], eb[j]) for i, j in _overlapping(*box) if A.owner[ea[i]] == B.owner[eb[j]]]
    assert list(zip(ga.tolist(), gb.tolist())) == want and not crowded.any()
    for got, alone in zip(hits, segment_hits(A.pts[ga], A.edge[ga], B.pts[gb], B.edge[gb], 1.0)):
        np.testing.assert_array_equal(got, alone)


def test_batched_crossings_are_the_crossings_of_each_pair():
    pairs = [
        (circle(1.0, 60), circle(1.0, 50, centre=(0.7, 0.2))),
        (_wobbly(70, 8), _wobbly(80, 9)),
        (circle(1.0, 30), circle(0.3, 30)),
    ]
    A = Ragged.from_list([p for p, _ in pairs], True)
    B = Ragged.from_list([q for _, q in pairs], True)
    found = batch_crossings(A, B, pair_scales(A, B))
    for c, (p, q) in enumerate(pairs):
        alone = crossings(p, True, q, True)
        np.testing.assert_allclose(found.s_a[found.pair == c], alone.s_a, atol=1e-12)
        np.testing.assert_allclose(found.points[found.pair == c], alone.points, atol=1e-12)
    assert np.sum(found.pair == 2) == 0  # nested circles never meet
    assert np.sum(found.pair == 0) == 2


def _near_pairs(seed):
    """Loops (one started half a turn on, one with one point) and open arcs, each with a
    wobbled copy crossing it, and a wobbled loop against its reversed copy."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    loop = circle(1.0, 90)
    wobbled = loop * (1 + 0.05 * np.sin(3 * t + rng.uniform(0, 6)))[:, None]
    x = np.linspace(0, 1, 70)
    arc = np.c_[x, 0.2 * np.sin(np.pi * x)]
    wavy = arc + np.c_[np.zeros(70), 0.02 * np.sin(4 * np.pi * x + rng.uniform(0, 6))]
    ps = [loop, loop, arc, wobbled, loop[:1]]
    qs = [wobbled, np.roll(wobbled, 45, axis=0), wavy, wobbled[::-1], wobbled]
    return ps, qs, [True, True, False, True, True]


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=20)
def test_matched_hits_are_hits_the_grid_search_finds(seed):
    ps, qs, closed = _near_pairs(seed)
    A, B = Ragged.from_list(ps, closed), Ragged.from_list(qs, closed)
    scale = pair_scales(A, B)
    wanted = np.array([True, True, True, True, True])
    pair, s_a = matched_hits(A, B, scale, wanted)
    found = batch_crossings(A, B, scale)
    for c, x in zip(pair, A.point_at(pair, s_a)):
        assert np.min(np.linalg.norm(found.points[found.pair == c] - x, axis=1)) <= 1e-12
    # Lying along each other: the loops (whatever their starts) and the arcs cross where they
    # match; the loop against its reversed copy may be missed (it is then searched on the
    # grid), a single point never crosses.
    assert set(pair.tolist()) >= {0, 1, 2} and 4 not in pair
    assert not len(matched_hits(A, B, scale, np.zeros(5, bool))[0])


def test_circumcircles_of_points_on_a_circle_and_a_line():
    t = np.array([[0.1, 0.9, 2.0], [3.0, 3.5, 5.0]])
    pts = 2.0 * np.stack([np.cos(t), np.sin(t)], axis=-1) + [1.0, -1.0]
    centre, radius, ok = circumcircles(pts[:, 0], pts[:, 1], pts[:, 2])
    np.testing.assert_allclose(centre, [[1.0, -1.0]] * 2, atol=1e-12)
    np.testing.assert_allclose(radius, 2.0)
    assert ok.all()
    line = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    assert not circumcircles(line[:1], line[1:2], line[2:])[2][0]


# ------------------------------------------------------------------ one-way maps


def _map(n, chain):
    rng = np.random.default_rng(n)
    v = lambda *shape: rng.standard_normal(shape)  # noqa: E731
    return OneWayMap(v(n, 2), v(n, 2), v(n, 2), v(n), np.ones(n, bool), v(n), v(n), v(n, 2), v(n, 2), np.full(n, chain))


def test_one_way_maps_take_flip_and_join():
    a, b = _map(5, 0), _map(3, 1)
    both = OneWayMap.concatenate([a, b])
    assert len(both) == 8 and both.chain.tolist() == [0] * 5 + [1] * 3
    back = a.flipped()
    np.testing.assert_array_equal(back.src, a.dst)
    np.testing.assert_array_equal(back.s_dst, a.s_src)
    np.testing.assert_array_equal(back.n_src, a.n_dst)
    np.testing.assert_array_equal(back.flipped().src, a.src)
    some = both.take(np.array([1, 6]))
    np.testing.assert_array_equal(some.r, both.r[[1, 6]])
    a.put(np.array([0]), b.take(np.array([2])))
    np.testing.assert_array_equal(a.dst[0], b.dst[2])
    np.testing.assert_array_equal(a.src[0], _map(5, 0).src[0])  # sources are not overwritten


@pytest.mark.parametrize("closed", [True, False])
def test_subcurve_keeps_the_stretch(closed):
    c = _wobbly(40, 10, closed=not closed) if not closed else _wobbly(40, 10)
    piece = subcurve(c, closed, 0.5, 1.7)
    assert np.linalg.norm(np.diff(piece, axis=0), axis=1).sum() == pytest.approx(1.2, rel=1e-9)


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), closed=st.booleans())
def test_curves_already_clean_are_what_as_curve_returns(seed, closed):
    rng = np.random.default_rng(seed)
    curves = []
    for _ in range(12):
        xy = rng.normal(size=(int(rng.integers(0, 9)), 2)) * 10 ** rng.uniform(-3, 3)
        kind = rng.integers(0, 6)
        if kind == 1 and len(xy) > 2:
            xy[2] = xy[1]  # a duplicate
        elif kind == 2 and len(xy) > 2:
            xy[-1] = xy[0] * (1 + 1e-12)  # a loop's closing duplicate
        elif kind == 3 and len(xy):
            xy[0, 1] = np.nan
        elif kind == 4 and len(xy) > 2:
            xy[2] = xy[1] + 1e-9 * np.ptp(xy, axis=0).max()  # at the tolerance
        curves.append(xy)
    for xy, clean in zip(curves, already_clean(curves, [closed] * len(curves))):
        if clean:
            np.testing.assert_array_equal(as_curve(xy, "P", closed), xy)


@pytest.mark.parametrize("seed", range(4))
def test_coarsen_skips_only_curves_no_default_spacing_finds_dense(seed):
    rng = np.random.default_rng(seed)
    curves = []
    for n in (2, 3, 50, 400, 3000, 15999, 16000):
        # Edge lengths far from even: a few long edges, many tiny ones (the median is tiny).
        steps = np.where(rng.random(n) < 0.3, 1.0, 1e-6) * rng.random(n)
        curves.append(np.cumsum(np.c_[steps, rng.normal(scale=1e-9, size=n)], axis=0))
    batch = Ragged.from_list(curves, rng.random(len(curves)) < 0.5)
    wanted = np.ceil(COARSEN_RATIO * batch.length / default_spacings(batch)).astype(np.int64) + 1
    assert not np.any(batch.n > 2 * wanted)
    assert coarsen(batch) is batch
    dense = Ragged.from_list([circle(1.0, 40_000)], [True])
    assert len(coarsen(dense).pts) < 40_000


def test_simple_curves_in_batches_answer_as_all_at_once(monkeypatch):
    # Many curves are searched a batch at a time (memory): each curve's answer is its own.
    rng = np.random.default_rng(3)
    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    curves = [np.c_[np.sin(t), np.sin(k % 3 * t)] + rng.normal(0, 0.01, (40, 2)) for k in range(30)]
    closed = np.arange(30) % 2 == 0
    whole = intersections.simple_curves(curves, closed)
    assert 0 < whole.sum() < 30  # both answers occur
    monkeypatch.setattr(intersections, "SIMPLE_BATCH_POINTS", 90)
    np.testing.assert_array_equal(intersections.simple_curves(curves, closed), whole)
