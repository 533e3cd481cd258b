"""Reliability at the edges (issue 41): degenerate keys, guarded divisions, any scale."""

import warnings

import numpy as np
import pytest

import ballmorph_core as bm
from ballmorph_core.drawing.matching import match_strokes
from ballmorph_core.drawing.plan import StrokeSet
from ballmorph_core.geometry.guards import least, ratio


def _key(strokes, cyclic=None):
    """A StrokeSet of 2D strokes (shapes (n_i, 2)) drawn in the XZ plane."""
    sizes = [len(p) for p in strokes]
    n = int(sum(sizes))
    return StrokeSet(
        np.concatenate([np.c_[p[:, 0], np.zeros(len(p)), p[:, 1]] for p in strokes]),
        np.r_[0, np.cumsum(sizes)].astype(np.int64),
        [False] * len(strokes) if cyclic is None else cyclic,
        np.zeros(len(strokes), np.int64),
        np.full(n, 0.01),
        np.ones(n),
        np.zeros((n, 4)),
    )


def _twice_in_place(dtype):
    """Issue 41's overflow: key A a 10-point stroke drawn twice in place, key B that stroke
    moved and an 11-point stroke at (3.9e5, 4.3e5); coordinates rounded to ``dtype``."""
    t = np.linspace(0.0, 1.0, 10)
    s = np.c_[t, 0.3 * np.sin(3 * t)]
    u = np.linspace(0.0, 1.0, 11)
    far = np.c_[3.9e5 + u, 4.3e5 + u**2]
    rounded = [p.astype(dtype).astype(np.float64) for p in (s, 1.1 * s + [0.2, 0.1], far)]
    return [rounded[0], rounded[0]], [rounded[1], rounded[2]]


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_a_stroke_drawn_twice_in_place_against_a_far_stroke_neither_overflows_nor_warns(dtype):
    strokes_a, strokes_b = _twice_in_place(dtype)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m = match_strokes(strokes_a, strokes_b, [False, False], [False, False])
        result = bm.inbetween(_key(strokes_a), _key(strokes_b), [0.0, 0.5, 1.0])
    # Key A's centroids do not spread: the turn guess scales by the keys' sizes, and no motion
    # is a ratio of round-off (it was 1e305 before: OverflowError).
    assert abs(m.rotation) < 1e6, f"the matching's motion scales by {abs(m.rotation):.3g}"
    assert [(p.stroke_a, p.stroke_b) for p in result.pairs if None not in (p.stroke_a, p.stroke_b)] == [(0, 0)]
    assert all(np.all(np.isfinite(f.positions)) for f in result.frames)


def test_ratio_takes_its_default_below_the_floor_without_a_warning():
    floor = least(2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert ratio(3.0, 1e-12, floor) == 1.0
        assert ratio(3.0, 1e-12, floor, default=0.0) == 0.0
        assert ratio(3.0, 2.0, floor) == 1.5
        assert ratio(1j, 2.0, floor) == 0.5j
        np.testing.assert_array_equal(ratio(np.array([1.0, 2.0]), np.array([0.0, 4.0]), floor, 7.0), [7.0, 0.5])
    assert least(2.0, 2) == pytest.approx((2e-9) ** 2)
    assert least(0.0) > 0.0, "a drawing of size 0 must still divide by nothing"
