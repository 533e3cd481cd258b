"""The keys, times and options checked before any work (drawing/keys/checked.py); the whole
catalogue of bad input, through the public calls, is tests/scenarios/test_bad_input.py."""

import numpy as np
import pytest

import ballmorph_core as bm
from ballmorph_core.drawing.keys.checked import check_inputs, check_key, check_times
from ballmorph_core.errors import InvalidCurveError


def _key(*strokes):
    return bm.StrokeSet.from_strokes([np.asarray(s, dtype=float) for s in strokes])


def test_times_are_clamped_to_the_keys_and_must_be_finite():
    np.testing.assert_array_equal(check_times([-0.5, 0.25, 2.0]), [0.0, 0.25, 1.0])
    for bad in ([np.nan], "soon", [0.5, np.inf]):
        with pytest.raises(InvalidCurveError, match="times"):
            check_times(bad)


def test_a_bad_stroke_is_named_as_the_animator_counts_it():
    good, bad = [(0, 0), (1, 0)], [(0, 0), (np.nan, 1)]
    with pytest.raises(InvalidCurveError, match=r"key_b: stroke\(s\) \[2\] have NaN or infinite coordinates"):
        check_key("key_b", _key(good, bad))
    with pytest.raises(InvalidCurveError, match=r"key_a: stroke\(s\) \[1\] have coordinates up to 1e\+70"):
        check_key("key_a", _key([(0, 0), (1e70, 0)]))
    with pytest.raises(InvalidCurveError, match="expected a StrokeSet, got list"):
        check_key("key_a", [good])


def test_options_come_back_in_the_core_spelling():
    key = _key([(0, 0), (1, 0)])
    method, carrier, matching, unmatched, spacing = check_inputs(
        key, key, "Circular_Ball", "NONE", "auto", "hold", None
    )
    assert (method, carrier, spacing) == ("circular-ball", "none", None)
    with pytest.raises(InvalidCurveError, match="carrier=.wobbly. is not valid"):
        check_inputs(key, key, "circular-ball", "wobbly", "auto", "hold", None)
