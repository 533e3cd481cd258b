"""The stroke-pair pipeline (drawing/pair_morphs/pipeline.py): the route each pair takes is a
field of its report (``PairReport.used.route``), never parsed from the report's words."""

import numpy as np
import pytest
from shapes import circle

import ballmorph_core as bm
from ballmorph_core.drawing.strokes import Route


def _route(a, b, cyclic, **options):
    key_a = bm.StrokeSet.from_strokes([a], cyclic=[cyclic])
    key_b = bm.StrokeSet.from_strokes([b], cyclic=[cyclic])
    (pair,) = [p for p in bm.inbetween(key_a, key_b, [0.5], **options).pairs if p.stroke_a is not None]
    return pair.used.route, pair


def _wavy(amplitude, n=60):
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x, amplitude * np.sin(3 * np.pi * x)]


def test_a_moved_copy_keeps_its_own_points():
    a = _wavy(0.2)
    route, pair = _route(a, a * 1.5 + [2.0, 1.0], False)
    assert route == Route.OWN_POINTS, pair


def test_crossing_loops_are_cut_into_lenses():
    route, pair = _route(circle(1.0, 64), circle(1.0, 64, centre=(0.8, 0.0)) * [1.0, 1.3], True, carrier="none")
    assert route == Route.LENSES and "split at" in pair.reason, pair


def _arch(height, n=60):
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x, height * np.sin(np.pi * x)]


def test_strokes_sharing_their_ends_are_one_lens():
    route, pair = _route(_arch(0.2), _arch(0.45), False)
    assert route == Route.LENSES and pair.used.morphs == ("circular-ball",) and not pair.reason, pair


def test_nested_loops_are_ball_mapped_whole():
    route, pair = _route(circle(1.0, 64), circle(2.0, 64) * [1.0, 0.8], True, carrier="none")
    assert route == Route.WHOLE and pair.used.morphs == ("circular-ball",), pair


def test_a_dot_moves_point_by_point():
    route, pair = _route(np.array([[0.0, 0.0]]), np.array([[1.0, 0.5]]), False)
    assert route == Route.DOT, pair


@pytest.mark.parametrize("method", ["laplace-blending", "heat-propagation"])
def test_the_papers_comparison_morphs_take_their_own_route(method):
    route, pair = _route(_arch(0.2), _arch(0.45), False, method=method)
    assert route == Route.COMPARISON and method in pair.used.morphs, pair
