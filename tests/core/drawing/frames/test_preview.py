"""The path preview (issue 13, deliverable 4): trajectories of a few points of every stroke pair."""

import numpy as np
import pytest
from shapes import circle, distance_to_polyline

import ballmorph_core as bm
from ballmorph_core.drawing.frames.preview import PathPreview


def _xz(points):
    """Blender's front canvas (x, z) of 3D points, shape (..., 2)."""
    return points[..., [0, 2]]


def _drawing():
    """Two keys of three strokes each: a loop that grows and moves, an arch that dips, and a
    stroke the second key draws the other way (so that pair is flipped)."""
    x = np.linspace(0.0, 2.0, 70)
    arch, dip = np.c_[x, 0.6 * np.sin(np.pi * x / 2)], np.c_[x, -0.3 * np.sin(np.pi * x / 2)]
    line = np.c_[np.linspace(0, 1.5, 30), np.full(30, -1.5)]
    key_a = bm.StrokeSet.from_strokes([circle(0.5, 90), arch + [0, 2], line], cyclic=[True, False, False])
    key_b = bm.StrokeSet.from_strokes(
        [circle(0.8, 120, centre=(0.3, 0.2)), dip + [0, 2], (line + [0.2, -0.3])[::-1]],
        cyclic=[True, False, False],
    )
    return key_a, key_b


def _sample_of(trajectory_start, frame):
    """The sample of an in-between each trajectory starts at (its index in the frame), shape (L,)."""
    distance = np.linalg.norm(trajectory_start[:, None] - frame.positions[None], axis=2)
    assert np.all(distance.min(axis=1) == 0.0)  # taken from the frame, not recomputed
    return distance.argmin(axis=1)


def test_trajectories_are_the_plans_own_in_betweens_from_key_a_to_key_b():
    key_a, key_b = _drawing()
    plan = bm.plan_inbetween(key_a, key_b)
    preview = bm.path_preview(plan)
    assert preview.points.shape == (len(preview), bm.PREVIEW_TIMES, 3)
    np.testing.assert_array_equal(preview.times, np.linspace(0, 1, bm.PREVIEW_TIMES))
    # Every point at time t_i is a sample of the plan's in-between at t_i, the same sample all along.
    frames = plan.evaluate(preview.times).frames
    samples = _sample_of(preview.points[:, 0], frames[0])
    for i, frame in enumerate(frames):
        np.testing.assert_array_equal(preview.points[:, i], frame.positions[samples])
    # ... so it starts on the first key's stroke of its pair and ends on the second key's (on the
    # spline through the stroke's points, which leaves the polyline by less than its sagitta).
    for c, (a, b) in enumerate(preview.strokes):
        mine = preview.points[preview.pair == c]
        for key, stroke, end in ((key_a, a, 0), (key_b, b, -1)):
            curve = _xz(key.positions[key.points(stroke)])
            far = distance_to_polyline(_xz(mine[:, end]), curve, bool(key.cyclic[stroke]))
            assert far.max() < 1e-3 * np.ptp(curve, axis=0).max(), (c, end, far.max())
    assert preview.strokes.tolist() == [[0, 0], [1, 1], [2, 2]]


@pytest.mark.parametrize("points", [1, 3, 8, 30])
def test_at_most_the_requested_trajectories_per_pair_all_distinct(points):
    plan = bm.plan_inbetween(*_drawing())
    preview = bm.path_preview(plan, points=points, times=5)
    counts = np.bincount(preview.pair, minlength=3)
    assert counts.tolist() == [points] * 3  # every pair has more samples than that
    assert np.all(np.diff(preview.pair) >= 0)  # a pair's trajectories are consecutive
    starts = preview.points[:, 0]
    assert len(np.unique(starts, axis=0)) == len(starts)
    assert preview.points.shape[1] == 5


def test_a_pair_with_fewer_samples_shows_all_of_them():
    # Strokes of too few distinct points move point by point: one sample per point.
    dot, seed = [[0.0, 0.0]], [[0.0, 0.0]] * 3
    moved, line = [[1.0, 1.0]], [[1.0, 1.0], [2.0, 1.0], [3.0, 1.0]]
    keys = bm.StrokeSet.from_strokes([dot, seed]), bm.StrokeSet.from_strokes([moved, line])
    plan = bm.plan_inbetween(*keys, matching="index")
    preview = bm.path_preview(plan, points=8)
    assert np.bincount(preview.pair).tolist() == [1, 3]
    np.testing.assert_array_equal(_xz(preview.points[preview.pair == 0][:, -1]), moved)


def test_a_stroke_drawn_as_a_dot_is_spread_along_its_partner():
    # The first key's stroke has no length: the trajectories are spaced along the second key's.
    plan = bm.plan_inbetween(
        bm.StrokeSet.from_strokes([[[0.0, 0.0]] * 3]), bm.StrokeSet.from_strokes([[[1.0, 1.0], [2.0, 1.0], [3.0, 1.0]]])
    )
    ends = _xz(bm.path_preview(plan, points=2).points[:, -1])
    assert sorted(ends[:, 0].tolist()) == [1.0, 3.0]


def test_points_are_evenly_spaced_along_a_loop_and_end_to_end_on_an_open_stroke():
    ring = bm.StrokeSet.from_strokes([circle(1.0, 200)], cyclic=[True])
    big = bm.StrokeSet.from_strokes([circle(1.5, 200)], cyclic=[True])
    start = _xz(bm.path_preview(bm.plan_inbetween(ring, big, carrier="none"), points=8).points[:, 0])
    angles = np.sort(np.arctan2(start[:, 1], start[:, 0]) % (2 * np.pi))
    gaps = np.diff(np.r_[angles, angles[0] + 2 * np.pi])
    np.testing.assert_allclose(gaps, np.full(8, np.pi / 4), atol=2 * np.pi / 200)

    x = np.linspace(0.0, 3.0, 301)
    a = bm.StrokeSet.from_strokes([np.c_[x, np.zeros_like(x)]])
    b = bm.StrokeSet.from_strokes([np.c_[x, 0.5 * np.sin(np.pi * x / 3)]])
    start = _xz(bm.path_preview(bm.plan_inbetween(a, b), points=4).points[:, 0])
    np.testing.assert_allclose(start[:, 0], [0.0, 1.0, 2.0, 3.0], atol=3.0 / 100)


def test_concentric_circles_without_carrier_travel_straight_out_at_steady_speed():
    # The circular ball-morph of concentric circles: every contact pair is radial and the
    # circular path degenerates to the radius, traversed at constant speed.
    plan = bm.plan_inbetween(
        bm.StrokeSet.from_strokes([circle(1.0, 120)], cyclic=[True]),
        bm.StrokeSet.from_strokes([circle(2.0, 160)], cyclic=[True]),
        carrier="none",
    )
    preview = bm.path_preview(plan)
    xz = _xz(preview.points)
    radius, angle = np.linalg.norm(xz, axis=2), np.arctan2(xz[..., 1], xz[..., 0])
    np.testing.assert_allclose(radius, np.broadcast_to(1.0 + preview.times, radius.shape), atol=1e-3)
    np.testing.assert_allclose(np.angle(np.exp(1j * (angle - angle[:, :1]))), 0.0, atol=1e-9)
    # ... and the points at an intermediate time are the plan's in-between there.
    middle = plan.evaluate([preview.times[5]]).frames[0]
    _sample_of(preview.points[:, 5], middle)


def _circle_through(points):
    """Least-squares circle through (T, 2) points: centre (2,), radius, worst residual."""
    a = np.c_[2 * points, np.ones(len(points))]
    sol = np.linalg.lstsq(a, (points**2).sum(axis=1), rcond=None)[0]
    centre = sol[:2]
    radius = np.sqrt(sol[2] + centre @ centre)
    return centre, radius, np.abs(np.linalg.norm(points - centre, axis=1) - radius).max()


def test_offset_circles_travel_on_arcs_orthogonal_to_both_keys_or_on_segments():
    small, big = circle(1.0, 120), circle(2.0, 160, centre=(0.5, 0.2))
    keys = (
        bm.StrokeSet.from_strokes([small], cyclic=[True]),
        bm.StrokeSet.from_strokes([big], cyclic=[True]),
    )
    # Circular ball-morph: each path is an arc leaving the first circle and reaching the second
    # at right angles (its centre lies on both circles' tangents there).
    arcs = bm.path_preview(bm.plan_inbetween(*keys, carrier="none"))
    for trajectory in _xz(arcs.points):
        centre, radius, off = _circle_through(trajectory)
        assert off < 1e-9 * radius
        p, q = trajectory[0], trajectory[-1]
        normal_p, normal_q = p / np.linalg.norm(p), (q - (0.5, 0.2)) / np.linalg.norm(q - (0.5, 0.2))
        assert abs((centre - p) @ normal_p) < 1e-2 * radius
        assert abs((centre - q) @ normal_q) < 1e-2 * radius
    # Linear ball-morph: straight segments between the same kind of contacts.
    lines = _xz(bm.path_preview(bm.plan_inbetween(*keys, method="linear-ball", carrier="none")).points)
    direction = lines[:, -1] - lines[:, 0]
    normal = np.c_[-direction[:, 1], direction[:, 0]] / np.linalg.norm(direction, axis=1, keepdims=True)
    assert np.abs(np.einsum("ltk,lk->lt", lines - lines[:, :1], normal)).max() < 1e-12


def test_empty_drawings_give_no_trajectories():
    for key_a, key_b in (
        (bm.StrokeSet.empty(), bm.StrokeSet.empty()),
        (bm.StrokeSet.from_strokes([circle(1.0, 40)], cyclic=[True]), bm.StrokeSet.empty()),
    ):
        preview = bm.path_preview(bm.plan_inbetween(key_a, key_b), times=9)
        assert len(preview) == 0
        assert preview.points.shape == (0, 9, 3) and preview.pair.shape == (0,)
        vertices, indices, owner = preview.segments()
        assert vertices.shape == (0, 3) and indices.shape == (0, 2) and owner.shape == (0,)


def test_strokes_without_a_partner_have_no_trajectory():
    lone = circle(0.3, 50, centre=(3.0, 3.0))
    key_a = bm.StrokeSet.from_strokes([circle(1.0, 80), lone], cyclic=[True, True])
    key_b = bm.StrokeSet.from_strokes([circle(1.2, 80)], cyclic=[True])
    plan = bm.plan_inbetween(key_a, key_b)
    assert len(plan.strokes) == 1 and len(plan.held) == 1
    preview = bm.path_preview(plan)
    assert set(preview.pair.tolist()) == {0} and preview.strokes.tolist() == [[0, 0]]
    assert np.linalg.norm(_xz(preview.points) - (3.0, 3.0), axis=2).min() > 1.0  # nothing near it


@pytest.mark.parametrize("points,times", [(0, 17), (2.5, 17), (-1, 17), (8, 1), (8, 0), ("many", 17)])
def test_bad_counts_are_refused_naming_the_argument(points, times):
    plan = bm.plan_inbetween(*_drawing())
    with pytest.raises(ValueError, match="points" if times == 17 else "times"):
        bm.path_preview(plan, points=points, times=times)


def test_transformed_applies_a_homogeneous_matrix():
    preview = bm.path_preview(bm.plan_inbetween(*_drawing()), points=2, times=3)
    matrix = np.array([[0.0, -2.0, 0.0, 1.0], [2.0, 0.0, 0.0, -1.0], [0.0, 0.0, 2.0, 0.5], [0.0, 0.0, 0.0, 1.0]])
    moved = preview.transformed(matrix)
    homogeneous = np.concatenate([preview.points, np.ones((*preview.points.shape[:2], 1))], axis=2)
    np.testing.assert_allclose(moved.points, (homogeneous @ matrix.T)[..., :3], atol=1e-12)
    assert moved.pair is preview.pair and moved.strokes is preview.strokes


def test_segments_join_consecutive_points_of_each_trajectory_only():
    points = np.arange(2 * 4 * 3, dtype=np.float64).reshape(2, 4, 3)
    preview = PathPreview(points, np.array([0, 3]), np.linspace(0, 1, 4), np.zeros((4, 2), dtype=np.int64))
    vertices, indices, owner = preview.segments()
    np.testing.assert_array_equal(vertices, points.reshape(-1, 3))
    assert indices.tolist() == [[0, 1], [1, 2], [2, 3], [4, 5], [5, 6], [6, 7]]
    assert owner.tolist() == [0, 0, 0, 0, 1, 1, 1, 1]


def test_pair_colours_are_stable_distinct_and_valid():
    colours = bm.pair_colors(np.arange(12), alpha=0.5)
    assert colours.shape == (12, 4)
    assert np.all((colours >= 0) & (colours <= 1)) and np.all(colours[:, 3] == 0.5)
    rgb = colours[:, :3]
    closest = np.linalg.norm(rgb[:, None] - rgb[None], axis=2) + 9 * np.eye(12)
    assert closest.min() > 0.05
    np.testing.assert_array_equal(bm.pair_colors([3, 7]), bm.pair_colors(np.arange(8))[[3, 7]])
