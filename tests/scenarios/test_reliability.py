"""Reliability at the edges (issue 41): degenerate keys, guarded divisions, any scale."""

import copy
import warnings

import numpy as np
import pytest
from golden_cases import FIELDS, TIMES, cases, path

import ballmorph_core as bm
from ballmorph_core.drawing.pairing.matching import match_strokes
from ballmorph_core.drawing.strokes import StrokeSet
from ballmorph_core.geometry.guards import least, ratio
from ballmorph_core.geometry.polyline import MAX_COORDINATE

#: The same keys scaled by any of these give the same in-betweens (issue 41 promises 1e-6 to 1e9).
SCALES = (1e-6, 1e-3, 1e9)
#: ... up to this difference relative to the drawing's size (the round-off measured: 1e-14).
SCALE_ROUNDOFF = 1e-9
#: The heat-propagation morph (a comparison morph of the paper, never the add-on's default)
#: traces a grid field: the sample on the symmetry axis of the golden bump drifts off it by
#: round-off, 7.2e-5 of the drawing at 1e-6 and 1e-4 (3e-10 at 1e-3, 2.5e-13 at 1e9).
HEAT_SCALE_DRIFT = 1e-3

_CASES = cases()


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
    assert abs(m.drawing.a) < 1e6, f"the matching's motion scales by {abs(m.drawing.a):.3g}"
    paired = {(p.stroke_a, p.stroke_b): p.travelled for p in result.pairs if None not in (p.stroke_a, p.stroke_b)}
    # The copy pairs the stroke moved; the duplicate, left over in a key of equal counts, pairs
    # the far stroke by the drawing's motion (issue 39: one left in each key always pairs).
    assert paired == {(0, 0): False, (1, 1): True}, paired
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


def _scaled(key, factor):
    out = copy.deepcopy(key)
    out.positions = key.positions * factor
    return out


@pytest.mark.parametrize("factor", SCALES)
@pytest.mark.parametrize("case", _CASES, ids=[c[0] for c in _CASES])
def test_the_golden_drawings_scaled_give_the_same_inbetweens(case, factor):
    """Every tolerance is relative: at 1e-6 the in-betweens had other point counts (absolute
    gaps of 1.0 between the curves of a batch), and a symmetric loop's turn was chosen by the
    last bits of its fit."""
    name, key_a, key_b, options = case
    stored = np.load(path(name))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        result = bm.inbetween(_scaled(key_a, factor), _scaled(key_b, factor), TIMES, **options)
    size = float(np.ptp(np.concatenate([key_a.positions, key_b.positions]), axis=0).max())
    limit = HEAT_SCALE_DRIFT if "heat" in name else SCALE_ROUNDOFF
    for k, frame in enumerate(result.frames):
        for field in FIELDS:
            want, got = stored[f"{k}/{field}"], getattr(frame, field)
            at = f"{name} x{factor:g} t={TIMES[k]} {field}"
            assert got.shape == want.shape, f"{at}: shape {got.shape} != {want.shape}"
            if field == "positions":
                worst = float(np.abs(got / factor - want).max(initial=0.0)) / size
                assert worst <= limit, f"{at}: off by {worst:.3g} of the drawing"
            elif np.issubdtype(want.dtype, np.floating):
                np.testing.assert_allclose(got, want, rtol=0, atol=limit, err_msg=at)
            else:
                np.testing.assert_array_equal(got, want, err_msg=at)


@pytest.mark.parametrize("factor", [1e-10, 1e55])
def test_scales_beyond_the_promise_still_give_the_same_inbetweens(factor):
    """At 1e-10 every frame used to be the flat chord; up to MAX_COORDINATE nothing overflows."""
    name, key_a, key_b, options = next(c for c in _CASES if c[0] == "apple-pear")
    base = bm.inbetween(key_a, key_b, TIMES, **options)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        got = bm.inbetween(_scaled(key_a, factor), _scaled(key_b, factor), TIMES, **options)
    size = float(np.ptp(key_a.positions, axis=0).max())
    for want, frame in zip(base.frames, got.frames):
        assert np.array_equal(frame.offsets, want.offsets), f"x{factor:g}: {frame.sizes} != {want.sizes}"
        worst = float(np.abs(frame.positions / factor - want.positions).max()) / size
        assert worst <= SCALE_ROUNDOFF, f"x{factor:g}: off by {worst:.3g} of the drawing"


@pytest.mark.parametrize("where", ["key_a", "key_b"])
def test_coordinates_beyond_what_the_geometry_can_multiply_are_refused_naming_the_stroke(where):
    """1e140 gave "SVD did not converge", 1e160 NaN frames: now a clear error before any work."""
    x = np.linspace(0.0, 1.0, 20)
    sane = bm.StrokeSet.from_strokes([np.c_[x, x * x], np.c_[x, 1 - x]])
    huge = bm.StrokeSet.from_strokes([np.c_[x, x * x], np.c_[x, 1 - x] * 1e140])
    keys = (huge, sane) if where == "key_a" else (sane, huge)
    before = huge.positions.copy()
    with pytest.raises(bm.InvalidCurveError, match=rf"^{where}: stroke\(s\) \[2\] have coordinates up to 1e\+140"):
        bm.inbetween(*keys, [0.0, 0.5, 1.0])
    assert np.array_equal(huge.positions, before), "the refused key was modified"
    assert MAX_COORDINATE < 1e140
