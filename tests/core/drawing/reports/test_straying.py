"""How far in-betweens stray from their keys (ballmorph_core/drawing/straying.py)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from shapes import circle

import ballmorph_core as bm

strokes = st.lists(
    st.tuples(st.integers(0, 6), st.booleans()),  # points, cyclic
    min_size=0,
    max_size=6,
)


def brute_lengths(drawing):
    out = []
    for i in range(len(drawing)):
        pts = drawing.positions[drawing.points(i)]
        length = sum(np.linalg.norm(pts[k + 1] - pts[k]) for k in range(len(pts) - 1))
        if drawing.cyclic[i] and len(pts) > 2:
            length += np.linalg.norm(pts[0] - pts[-1])
        out.append(length)
    return np.array(out)


@given(strokes, st.integers(0, 2**32 - 1))
def test_ink_lengths_match_a_stroke_by_stroke_sum(shape, seed):
    rng = np.random.default_rng(seed)
    drawing = bm.StrokeSet.from_strokes(
        [rng.normal(size=(n, 3)) for n, _ in shape], cyclic=np.array([c for _, c in shape], dtype=bool)
    )
    assert bm.ink_lengths(drawing) == pytest.approx(brute_lengths(drawing), abs=1e-12)


def key(*curves, cyclic=None):
    return bm.StrokeSet.from_strokes(list(curves), cyclic=cyclic)


def test_concentric_circles_grow_on_the_blend_of_their_lengths():
    a, b = key(circle(1.0, 80), cyclic=[True]), key(circle(2.0, 80), cyclic=[True])
    times = np.linspace(0.1, 0.9, 5)
    result = bm.inbetween(a, b, times, carrier="none")
    assert np.abs(bm.length_deviation(a, b, result, times)).max() < 1e-3


def test_straight_paths_shrink_a_stroke_turned_a_quarter_turn_most_midway():
    s = np.linspace(-1, 1, 30)
    a, b = key(np.c_[s, 0 * s]), key(np.c_[0 * s, s])
    times = np.array([0.25, 0.5, 0.75])
    result = bm.inbetween(a, b, times, method="linear-interpolation")
    deviation = bm.length_deviation(a, b, result, times)
    # |(1 - t, t)| against 1: -0.209 at a quarter, 1 - 1/sqrt(2) midway
    assert deviation[0] == pytest.approx([np.hypot(0.75, 0.25) - 1, np.sqrt(0.5) - 1, np.hypot(0.75, 0.25) - 1])


def test_strokes_without_a_partner_have_no_deviation_and_times_are_clamped():
    a = key(circle(1.0, 60), circle(0.2, 30) + 3, cyclic=[True, True])
    b = key(circle(1.5, 60), cyclic=[True])
    times = np.array([-0.5, 0.5, 1.5])  # an overshooting easing: the morph clamps them
    result = bm.inbetween(a, b, times, carrier="none")
    deviation = bm.length_deviation(a, b, result, times)
    matched = [k for k, p in enumerate(result.pairs) if p.stroke_a is not None and p.stroke_b is not None]
    assert deviation.shape == (len(result.pairs), 3) and len(matched) == 1
    assert np.isnan(np.delete(deviation, matched, axis=0)).all()
    assert np.abs(deviation[matched[0]]).max() < 1e-3


def test_a_stroke_grown_from_nothing_is_infinitely_off_its_blend():
    point = key(np.zeros((3, 2)))
    line = key(np.c_[np.linspace(0, 1, 3), np.zeros(3)])
    empty = bm.InbetweenResult(frames=[line], pairs=[bm.PairReport(0, 0, "linear-interpolation")])
    empty.frames[0].origin[:] = [0, 0]
    assert bm.length_deviation(point, point, empty, [0.5]).tolist() == [[np.inf]]
    still = bm.InbetweenResult(frames=[point], pairs=[bm.PairReport(0, 0, "linear-interpolation")])
    still.frames[0].origin[:] = [0, 0]
    assert bm.length_deviation(point, point, still, [0.5]).tolist() == [[0.0]]


def test_the_fallback_morphs_are_the_cores_own():
    assert bm.FALLBACK_METHOD in bm.FALLBACK_MORPHS and "composite-ball" in bm.METHODS


def test_each_pair_is_measured_on_its_own_stroke_whatever_the_drawing_order():
    a = key(circle(1.0, 80), circle(0.3, 40, centre=(5, 0)), cyclic=[True, True])
    b = key(circle(0.4, 40, centre=(5, 0)), circle(1.2, 80), cyclic=[True, True])
    times = np.array([0.3, 0.6])
    result = bm.inbetween(a, b, times, carrier="none")
    assert sorted((p.stroke_a, p.stroke_b) for p in result.pairs) == [(0, 1), (1, 0)]
    assert np.abs(bm.length_deviation(a, b, result, times)).max() < 1e-2


def test_work_buffers_shared_by_drawings_of_any_size_give_each_its_own_lengths():
    """length_deviation measures every frame with one set of work buffers: a drawing measured
    after a bigger or a smaller one gets exactly the lengths it gets alone."""
    from ballmorph_core.drawing.reports.straying import _ink_lengths, _Work

    rng = np.random.default_rng(6)
    drawings = [
        bm.StrokeSet.from_strokes([rng.normal(size=(n, 3)) for n in sizes], cyclic=[True, False, True][: len(sizes)])
        for sizes in ((40, 3, 17), (5,), (90, 1, 60), (2, 2))
    ]
    work = _Work()
    for drawing in drawings + drawings[::-1]:
        np.testing.assert_array_equal(_ink_lengths(drawing, work), bm.ink_lengths(drawing))


def test_edge_lengths_are_the_steps_norms_over_any_magnitudes():
    """_edge_lengths is each step's Euclidean length to round-off, over 60 orders of magnitude
    (its order of summation is not pinned: no numpy internals are)."""
    from ballmorph_core.drawing.reports.straying import _edge_lengths

    rng = np.random.default_rng(8)
    points = rng.normal(size=(20_001, 3)) * np.exp(rng.uniform(-30, 30, size=(20_001, 3)))
    got = _edge_lengths(points, np.empty(20_000), np.empty(20_000))
    np.testing.assert_allclose(got, np.linalg.norm(np.diff(points, axis=0), axis=1), rtol=4e-16)
