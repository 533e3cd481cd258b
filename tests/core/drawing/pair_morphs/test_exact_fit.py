"""Pairs the keys' own points carry (drawing/exact.py): unchanged strokes come back bit for bit,
similar copies move rigidly with their own points."""

import importlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapes import circle

import ballmorph_core as bm
from ballmorph_core.drawing.pair_morphs.exact_fit import exact_fit, may_be_exact

HOUSE = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.5, 1.5), (0.0, 1.0)])


def similar(xy, a, b):
    z = a * (xy @ [1, 1j]) + b
    return np.c_[z.real, z.imag]


def test_an_unchanged_drawing_comes_back_bit_for_bit():
    key = bm.StrokeSet.from_strokes([HOUSE, circle(0.3, 40, centre=(2.0, 0.5))], cyclic=[True, True])
    key.positions[:] = key.positions.astype(np.float32)  # as Blender stores them
    result = bm.inbetween(key, key, np.linspace(0, 1, 7))
    for frame in result.frames:
        np.testing.assert_array_equal(frame.positions, key.positions)
        np.testing.assert_array_equal(frame.offsets, key.offsets)
    assert {p.method for p in result.pairs} == {"own points"}


@pytest.mark.parametrize("a", [1.0, np.exp(0.7j), 1.6 * np.exp(-0.3j)])
def test_a_similar_copy_moves_with_its_own_points(a):
    b = 0.4 - 0.2j
    key_a = bm.StrokeSet.from_strokes([HOUSE], cyclic=[True])
    key_b = bm.StrokeSet.from_strokes([similar(HOUSE, a, b)], cyclic=[True])
    result = bm.inbetween(key_a, key_b, np.linspace(0, 1, 5))
    assert result.pairs[0].method.startswith("own points")
    for frame in result.frames:
        xy = frame.positions[:, [0, 2]]
        assert len(xy) == len(HOUSE)
        # Every in-between is the house under some similarity: corners sharp, edges straight.
        fit = exact_fit(HOUSE, xy, True)
        assert fit is not None and fit.shift == 0
    np.testing.assert_allclose(result.frames[-1].positions[:, [0, 2]], similar(HOUSE, a, b), atol=1e-12)


def test_a_regular_polygon_takes_the_start_that_turns_least():
    square = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
    moved = np.roll(square, 1, axis=0) + [3.0, 0.0]  # the same square, listed from another corner
    fit = exact_fit(square, moved, True)
    assert fit.shift == 1 and abs(fit.a - 1.0) < 1e-12  # a translation, not a quarter turn
    turned = exact_fit(square, moved, True, turn=np.pi / 2)
    assert abs(turned.a - 1j) < 1e-12  # the drawing turns a quarter: so does the square


def test_what_is_not_a_similar_copy_is_not_exact():
    assert exact_fit(HOUSE, HOUSE[:-1], True) is None  # other point count
    bent = HOUSE.copy()
    bent[3, 1] += 1e-3
    assert exact_fit(HOUSE, bent, True) is None
    assert exact_fit(HOUSE, HOUSE * 1.2, True, similarity=False) is None  # no carrier: only itself
    assert exact_fit(HOUSE, HOUSE.astype(np.float32).astype(np.float64) + 1e-8, True, similarity=False) is not None


def test_a_copy_far_from_the_origin_is_exact_to_float32_rounding():
    far = HOUSE * 0.01 + [1000.0, -500.0]
    rounded = (far + [0.25, 0.0]).astype(np.float32).astype(np.float64)
    assert exact_fit(far, rounded, True) is not None


def test_a_bug_in_the_own_points_route_sends_its_pairs_down_the_ball_route(monkeypatch):
    routes = importlib.import_module("ballmorph_core.drawing.pair_morphs.point_routes")

    def broken(*args, **kwargs):
        raise ZeroDivisionError("simulated core bug")

    monkeypatch.setattr(routes, "exact_fit", broken)
    key = bm.StrokeSet.from_strokes([HOUSE], cyclic=[True])
    result = bm.inbetween(key, key, [0.5])
    assert result.pairs[0].method == "polyline"  # the next route took it
    np.testing.assert_allclose(result.frames[0].positions, key.positions, atol=1e-12)


@settings(max_examples=150, deadline=None)
@given(
    n=st.integers(2, 40),
    closed=st.booleans(),
    turn=st.floats(-3.1, 3.1),
    scale=st.floats(0.05, 20.0),
    shift=st.integers(0, 39),
    noise=st.sampled_from([0.0, 1e-9, 1e-7, 1e-3]),
    far=st.sampled_from([0.0, 1e3]),
    seed=st.integers(0, 2**31 - 1),
)
def test_the_batched_prefilter_keeps_every_pair_exact_fit_fits(n, closed, turn, scale, shift, noise, far, seed):
    rng = np.random.default_rng(seed)
    xy = rng.normal(size=(n, 2)) + far
    b = similar(xy, scale * np.exp(1j * turn), 0.3 - 0.1j) + noise * rng.normal(size=(n, 2))
    b = np.roll(b, -shift % n if closed else 0, axis=0).astype(np.float32).astype(np.float64)
    pairs = [(xy, b), (xy, xy), (xy, rng.normal(size=(n, 2)))]
    maybe = may_be_exact([p for p, _ in pairs], [q for _, q in pairs], [closed] * 3)
    for (p, q), kept in zip(pairs, maybe):
        for similarity in (True, False):
            if exact_fit(p, q, closed, similarity=similarity) is not None:
                assert kept
