"""Polylines morph corner to corner with straight edges (drawing/polylines.py)."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from shapes import circle

import ballmorph_core as bm
from ballmorph_core.drawing.pair_morphs.polylines import FEW, RUN_OFF, STRAIGHT, corners, corners_of

HOUSE = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.5, 1.5), (0.0, 1.0)])
HOUSE_B = np.array([(0.0, 0.0), (1.0, 0.0), (1.05, 1.0), (0.6, 1.65), (0.0, 1.0)])


def edge_points(corner_points, per_edge, closed):
    """A polyline through corners with ``per_edge - 1`` points inside each edge."""
    ends = np.roll(corner_points, -1, axis=0) if closed else corner_points[1:]
    f = np.arange(per_edge)[:, None] / per_edge
    pts = [a + f * (b - a) for a, b in zip(corner_points[: len(ends)], ends)]
    return np.concatenate(pts + ([] if closed else [corner_points[-1:]]))


def off_straight(xy, closed, corner_index):
    """Largest distance of a vertex from the segment between the corners around it."""
    n, worst = len(xy), 0.0
    ring = list(corner_index) + ([corner_index[0] + n] if closed else [])
    for a, b in zip(ring[:-1], ring[1:]):
        p, q = xy[a % n], xy[b % n]
        d = (q - p) / np.linalg.norm(q - p)
        for i in range(a + 1, b):
            r = xy[i % n] - p
            worst = max(worst, abs(r[0] * d[1] - r[1] * d[0]))
    return worst


def test_polylines_and_curves_are_told_apart():
    assert corners(HOUSE, True).index.tolist() == [0, 1, 2, 3, 4]
    assert corners(np.r_[HOUSE, HOUSE[:1]], True) is None  # a loop's closing point repeated (as_curve drops it)
    zigzag = edge_points(np.array([(0, 0), (1, 1), (2, 0), (3, 1)], float), 5, False)
    assert corners(zigzag, False).index.tolist() == [0, 5, 10, 15]
    octagon = circle(1.0, 8)
    assert corners(octagon, True) is not None  # few vertices: drawn as an octagon
    assert corners(circle(1.0, 30), True) is None  # every vertex turns a little: a curve
    t = np.linspace(0, 1, 50)
    assert corners(np.c_[t, 0.2 * np.sin(3 * t)], False) is None  # a hand-drawn curve
    # A stroke without points in a batch is no polyline, and leaves the others as they are.
    first, house, last = corners_of([np.zeros((0, 2)), HOUSE, np.zeros((0, 2))], [False, True, False])
    assert first is None and last is None and house.index.tolist() == [0, 1, 2, 3, 4]


def test_a_polyline_morph_keeps_edges_straight_and_corners_sharp():
    a = edge_points(HOUSE, 4, True)
    b = edge_points(HOUSE_B, 4, True)
    result = bm.inbetween(
        bm.StrokeSet.from_strokes([a], [True]), bm.StrokeSet.from_strokes([b], [True]), np.linspace(0, 1, 9)
    )
    assert result.pairs[0].method.startswith("polyline")
    for frame in result.frames:
        xy = frame.positions[:, [0, 2]]
        assert len(xy) == len(a)
        assert off_straight(xy, True, np.arange(0, len(a), 4)) < 1e-12
    np.testing.assert_allclose(result.frames[0].positions[:, [0, 2]], a, atol=1e-12)
    np.testing.assert_allclose(result.frames[-1].positions[:, [0, 2]], b, atol=1e-12)


def test_polyline_loops_pair_corners_whatever_corner_they_start_at():
    a, b = HOUSE, np.roll(HOUSE_B, 2, axis=0)
    result = bm.inbetween(
        bm.StrokeSet.from_strokes([a], [True]), bm.StrokeSet.from_strokes([b], [True]), [0.0, 0.5, 1.0]
    )
    mid = result.frames[1].positions[:, [0, 2]]
    np.testing.assert_allclose(mid, 0.5 * (HOUSE + HOUSE_B), atol=0.05)  # each corner halfway to its own
    end = result.frames[2].positions[:, [0, 2]]
    np.testing.assert_allclose(np.sort(end, axis=0), np.sort(HOUSE_B, axis=0), atol=1e-12)


def test_polylines_with_other_corner_counts_take_the_ball_route():
    square = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
    result = bm.inbetween(
        bm.StrokeSet.from_strokes([HOUSE], [True]), bm.StrokeSet.from_strokes([square], [True]), [0.5]
    )
    assert not result.pairs[0].method.startswith("polyline")


def _one_by_one(xy, closed):
    """The module docstring's rule, vertex by vertex: the corner indices of a polyline, or None."""
    n = len(xy)
    if n < 2 or any(np.array_equal(xy[i], xy[i + 1]) for i in range(n - 1)):
        return None
    found = []
    for i in range(n):
        if not closed and i in (0, n - 1):
            found.append(i)
            continue
        d0, d1 = xy[i] - xy[i - 1], xy[(i + 1) % n] - xy[i]
        if abs(math.atan2(d0[0] * d1[1] - d0[1] * d1[0], d0 @ d1)) > STRAIGHT:
            found.append(i)
    if len(found) < (3 if closed else 2) or not (len(found) <= FEW or len(found) <= n // 3):
        return None
    if off_straight(xy, closed, found) > RUN_OFF * np.ptp(xy, axis=0).max():
        return None
    return found


@settings(max_examples=100, deadline=None)
@given(seed=st.integers(0, 2**31 - 1))
def test_corners_of_a_batch_are_each_strokes_own(seed):
    """Polylines, bare corner points, coarse and dense curves, a repeated point, one point,
    open and closed, in one batch: each stroke gets what the rule gives it alone (as
    :func:`corners`), vertex by vertex."""
    rng = np.random.default_rng(seed)
    curves, closed = [], rng.random(12) < 0.5
    for ring in closed:
        k = int(rng.integers(3 if ring else 2, 16))
        corner_pts = rng.normal(size=(k, 2)) * 10.0 ** rng.uniform(-3, 3)
        kind = rng.integers(5)
        if kind == 0:  # a polyline: straight runs between the corners
            steps = rng.integers(1, 5, k)
            ends = np.roll(corner_pts, -1, axis=0) if ring else np.r_[corner_pts[1:], corner_pts[-1:]]
            parts = [
                a + np.linspace(0, 1, m, endpoint=False)[:, None] * (b - a) for a, b, m in zip(corner_pts, ends, steps)
            ]
            xy = np.concatenate(parts if ring else parts[:-1] + [corner_pts[-1:]])
        elif kind == 1:
            xy = corner_pts
        elif kind == 2:  # a curve, coarse or dense
            t = np.linspace(0, rng.uniform(1, 6), int(rng.integers(3, 80)))
            xy = np.c_[np.cos(t), rng.uniform(0.3, 1) * np.sin(t)]
        elif kind == 3:
            xy = np.r_[corner_pts[:1], corner_pts]  # a repeated point
        else:
            xy = corner_pts[:1]
        curves.append(xy)
    batch = corners_of(curves, closed)
    for xy, ring, got in zip(curves, closed, batch):
        alone = corners(xy, ring)
        want = _one_by_one(xy, ring)
        assert (got is None) == (alone is None) == (want is None)
        if got is not None:
            assert got.index.tolist() == alone.index.tolist() == want
            np.testing.assert_array_equal(got.u, alone.u)
