"""Timing (ballmorph_core/drawing/timing.py): favoring and timing charts."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import ballmorph_core as bm

favors = st.floats(-1.0, 1.0, allow_nan=False)
T = np.linspace(0.0, 1.0, 201)


# -- favor ----------------------------------------------------------------------------------------


@given(favors)
def test_favor_keeps_both_keys_fixed_and_is_strictly_increasing(favor):
    warped = bm.apply_favor(T, favor)
    assert warped[0] == 0.0 and warped[-1] == 1.0
    assert np.all(np.diff(warped) > 0)
    assert np.all((warped >= 0) & (warped <= 1))


def test_favor_zero_is_the_identity():
    assert np.array_equal(bm.apply_favor(T, 0.0), T)
    assert np.array_equal(bm.apply_favor(T, -0.0), T)


@given(st.floats(0.01, 1.0))
def test_positive_favor_pulls_toward_the_second_key_and_negative_toward_the_first(amount):
    inner = T[1:-1]
    assert np.all(bm.apply_favor(inner, amount) > inner)
    assert np.all(bm.apply_favor(inner, -amount) < inner)


@given(favors, favors)
def test_more_favor_pulls_further(a, b):
    low, high = sorted((a, b))
    assert np.all(bm.apply_favor(T, low) <= bm.apply_favor(T, high) + 1e-15)


@given(favors)
def test_opposite_favors_mirror_each_other(favor):
    assert bm.apply_favor(1 - T, -favor) == pytest.approx(1 - bm.apply_favor(T, favor), abs=1e-12)


def test_full_favor_moves_the_middle_to_a_quarter_of_the_way_from_the_key():
    assert bm.apply_favor([0.5], 1.0)[0] == pytest.approx(0.75)
    assert bm.apply_favor([0.5], -1.0)[0] == pytest.approx(0.25)
    assert bm.FAVOR_ODDS == 3.0


def test_favor_clamps_the_overshoot_of_easing_instead_of_making_nan():
    eased = bm.ease(np.linspace(0, 1, 9), "back", "ease-in")
    assert eased.min() < 0  # back overshoots before the first key
    warped = bm.apply_favor(eased, 0.5)
    assert np.all(np.isfinite(warped)) and warped.min() == 0.0


@pytest.mark.parametrize("favor", [1.5, -1.01, float("nan"), "much", None])
def test_a_favor_outside_its_range_is_refused(favor):
    with pytest.raises(ValueError, match="favor must be a number in \\[-1, 1\\]"):
        bm.apply_favor([0.5], favor)


# -- timing charts --------------------------------------------------------------------------------


charts = st.lists(st.floats(0.0, 1.0, exclude_min=True, exclude_max=True), min_size=1, max_size=12, unique=True).map(
    sorted
)


@given(charts, st.lists(st.sampled_from([" ", ",", ", ", "  ,\t", "\n"]), min_size=12, max_size=12))
def test_a_chart_parses_back_to_its_fractions_whatever_the_separators(fractions, separators):
    text = repr(fractions[0]) + "".join(sep + repr(x) for sep, x in zip(separators, fractions[1:]))
    assert bm.parse_timing_chart(f" {text} ") == tuple(fractions)
    assert bm.parse_timing_chart(text, room=len(fractions)) == tuple(fractions)


@pytest.mark.parametrize("text", ["", "   ", " , ,"])
def test_an_empty_chart_is_no_chart(text):
    assert bm.parse_timing_chart(text) == ()
    assert bm.parse_timing_chart(text, room=0) == ()


@pytest.mark.parametrize(
    ("text", "room", "said"),
    [
        ("0.1 half 0.9", None, "timing_chart: 'half' is not a number"),
        ("0.1 0.5;0.9", None, "timing_chart: '0.5;0.9' is not a number"),
        ("0 0.5", None, "timing_chart: 0 is not between 0 and 1 (both keys excluded)"),
        ("0.5 1", None, "timing_chart: 1 is not between 0 and 1 (both keys excluded)"),
        ("-0.2 0.5", None, "timing_chart: -0.2 is not between 0 and 1"),
        ("0.2 nan", None, "timing_chart: nan is not between 0 and 1"),
        ("0.2 inf", None, "timing_chart: inf is not between 0 and 1"),
        ("0.2 0.6 0.4", None, "timing_chart: 0.4 comes after 0.6 (the fractions must rise)"),
        ("0.2 0.2", None, "timing_chart: 0.2 comes after 0.2 (the fractions must rise)"),
        ("0.1 0.3 0.6 0.9", 3, "timing_chart: 4 fractions but only 3 frame(s) between the keys"),
        ("0.5", 0, "timing_chart: 1 fractions but only 0 frame(s) between the keys"),
    ],
    ids=["word", "semicolon", "zero", "one", "negative", "nan", "inf", "descending", "repeated", "no-room", "no-frame"],
)
def test_a_malformed_chart_is_refused_saying_what_is_wrong(text, room, said):
    with pytest.raises(ValueError) as raised:
        bm.parse_timing_chart(text, room=room)
    assert said in str(raised.value)


def test_a_chart_that_is_not_a_string_is_refused():
    with pytest.raises(ValueError, match="expected a string of fractions, got list"):
        bm.parse_timing_chart([0.1, 0.5])


@given(st.integers(1, 40), st.integers(2, 60))
def test_a_chart_that_fits_gets_one_frame_per_fraction_spread_evenly(n, gap):
    if n > gap - 1:
        with pytest.raises(ValueError, match="between the keys"):
            bm.parse_timing_chart(" ".join(str((i + 1) / (n + 1)) for i in range(n)), room=gap - 1)
        return
    frames, _ = bm.frame_times(10, 10 + gap, count=n)
    assert frames.tolist() == [round(10 + (i + 1) * gap / (n + 1)) for i in range(n)]
