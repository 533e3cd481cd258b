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


# -- easing: Interpolate's Back, Amplitude and Period, and its Custom curve ----------------------

X = np.linspace(0.0, 1.0, 257)
MODES = ("ease-in", "ease-out", "ease-in-out", "auto")


def _penner_in(kind, x):
    """Penner's fixed-constant ease-in (back 1.70158; elastic amplitude 1, period 0.3) as the
    core wrote it before the settings existed: the reference the settings reproduce."""
    if kind == "back":
        c1 = 1.70158
        return (c1 + 1) * x**3 - c1 * x**2
    c4 = 2 * np.pi / 3
    return np.where((x <= 0) | (x >= 1), x, -(2.0 ** (10 * x - 10)) * np.sin((x * 10 - 10.75) * c4))


def _penner(kind, mode, x):
    if mode == "auto":
        mode = "ease-out"
    if mode == "ease-in":
        return _penner_in(kind, x)
    if mode == "ease-out":
        return 1 - _penner_in(kind, 1 - x)
    return np.where(x < 0.5, _penner_in(kind, 2 * x) / 2, 1 - _penner_in(kind, 2 - 2 * x) / 2)


@pytest.mark.parametrize("mode", ("ease-in", "ease-out", "auto"))
def test_back_at_penners_overshoot_is_the_fixed_back_bit_for_bit(mode):
    assert np.array_equal(bm.ease(X, "back", mode, back=1.70158), _penner("back", mode, X))


@pytest.mark.parametrize("mode", MODES)
def test_elastic_at_amplitude_1_and_period_0_3_is_penners_elastic_bit_for_bit(mode):
    assert np.array_equal(bm.ease(X, "elastic", mode, amplitude=1.0, period=0.3), _penner("elastic", mode, X))


# Blender's easing.cc (BLI_easing_*), transcribed scalar by scalar with begin 0, change 1,
# duration 1, as grease_pencil_interpolate_sequence_easing_calc calls them.


def _blender_back(mode, t, s):
    if mode == "ease-in":
        return t * t * ((s + 1) * t - s)
    if mode in ("ease-out", "auto"):
        t -= 1
        return t * t * ((s + 1) * t + s) + 1
    s *= 1.525
    t *= 2
    if t < 1:
        return 0.5 * (t * t * ((s + 1) * t - s))
    t -= 2
    return 0.5 * (t * t * ((s + 1) * t + s) + 2)


def _blend(time, amplitude, s):
    f = amplitude if amplitude else 0.0
    if abs(time) < abs(s):
        ratio = abs(time) / abs(s)
        f = f * ratio + (1 - ratio)
    return f


def _blender_elastic(mode, time, amplitude, period):
    if time == 0:
        return 0.0
    in_out = mode == "ease-in-out"
    if time == 1:
        return 1.0
    if mode == "ease-in":
        time -= 1
    elif in_out:
        time = 2 * time - 1
    else:
        time = -time
    period = period or (0.45 if in_out else 0.3)
    f = 1.0
    if not amplitude or amplitude < 1:
        s = period / 4
        f = _blend(time, amplitude, s)
        amplitude = 1.0
    else:
        s = period / (2 * np.pi) * np.arcsin(1 / amplitude)
    wave = amplitude * 2 ** (10 * time) * np.sin((time - s) * 2 * np.pi / period)
    if mode == "ease-in":
        return -f * wave
    if in_out:
        if time < 0:
            return -0.5 * f * wave
        time = -time
        wave = amplitude * 2 ** (10 * time) * np.sin((time - s) * 2 * np.pi / period)
        return 0.5 * f * wave + 1
    return f * wave + 1


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("back", (0.0, 0.5, 1.702, 3.0))
def test_back_follows_blenders_formula(mode, back):
    expected = [_blender_back(mode, t, back) for t in X]
    assert bm.ease(X, "back", mode, back=back) == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize("mode", ("ease-in", "ease-out", "ease-in-out"))
def test_back_without_overshoot_is_the_cubic(mode):
    assert bm.ease(X, "back", mode, back=0.0) == pytest.approx(bm.ease(X, "cubic", mode), abs=1e-15)
    assert bm.ease(X, "back", mode).min() < 0 or bm.ease(X, "back", mode).max() > 1  # the default overshoots


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize(
    ("amplitude", "period"), [(0.15, 0.15), (0.0, 0.3), (0.5, 0.2), (1.0, 0.3), (2.5, 0.4), (1.0, 0.0)]
)
def test_elastic_follows_blenders_formula(mode, amplitude, period):
    expected = [_blender_elastic(mode, t, amplitude, period) for t in X]
    assert bm.ease(X, "elastic", mode, amplitude=amplitude, period=period) == pytest.approx(expected, abs=1e-12)


def test_elastic_swings_grow_with_the_amplitude_and_come_faster_with_a_shorter_period():
    def overshoot(**settings):
        return bm.ease(X, "elastic", "ease-out", **settings).max() - 1

    assert 0 < overshoot(amplitude=0.15) < overshoot(amplitude=1.0)
    crossings = [
        np.count_nonzero(np.diff(np.sign(bm.ease(X, "elastic", "ease-out", period=p) - 1))) for p in (0.1, 0.4)
    ]
    assert crossings[0] > crossings[1]


def test_the_defaults_are_interpolate_sequences():
    assert (bm.drawing.frames.timing.BACK, bm.drawing.frames.timing.AMPLITUDE) == (1.702, 0.15)
    assert bm.drawing.frames.timing.PERIOD == 0.15
    assert np.array_equal(bm.ease(X, "back", "ease-in"), bm.ease(X, "back", "ease-in", back=1.702))


def test_the_custom_type_reads_its_curve_and_ignores_the_easing():
    identity = np.linspace(0, 1, 5)
    assert np.array_equal(bm.ease(X, "custom", curve=identity), X)
    table = [0.0, 0.8, 1.0]  # up to 0.8 at the middle, then slowly to 1
    for mode in MODES:
        assert bm.ease([0.25, 0.5, 0.75], "custom", mode, curve=table) == pytest.approx([0.4, 0.8, 0.9])


@pytest.mark.parametrize(
    ("settings", "said"),
    [
        ({"back": -0.1}, "back must be a finite number of at least 0"),
        ({"amplitude": float("nan")}, "amplitude must be"),
        ({"period": "soon"}, "period must be a finite number"),
    ],
)
def test_bad_settings_are_refused_by_name(settings, said):
    with pytest.raises(ValueError, match=said):
        bm.ease(X, "elastic", **settings)


@pytest.mark.parametrize("curve", (None, [0.5], [[0, 1]], [0.0, float("inf")]))
def test_the_custom_type_without_a_usable_curve_is_refused(curve):
    with pytest.raises(ValueError, match="'custom' type needs"):
        bm.ease(X, "custom", curve=curve)
