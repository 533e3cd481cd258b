"""Favor, timing charts (kept with their keys) and the warnings about pairs that stray (issue 13)."""

import bpy
import gp_data
import numpy as np
import pytest

import ballmorph_core as bm


def run(capfd, **options):
    """Run the operator; return its result and everything it reported."""
    capfd.readouterr()
    result = bpy.ops.ballmorph.inbetween(**options)
    out, err = capfd.readouterr()
    return result, out + err


def circles(last_key):
    """Concentric circles of radius 1 (frame 1) and 2 (frame ``last_key``) on layer 'Ink'."""
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [gp_data.loop(1.0)], cyclic=[True])
    gp_data.add_key(layer, last_key, [gp_data.loop(2.0)], cyclic=[True])
    bpy.context.scene.frame_current = 1
    return obj


def radius(obj, number):
    """Mean distance of the points of frame ``number`` from the circles' centre (x, z)."""
    strokes = gp_data.read_strokes(gp_data.frame_at(obj.data.layers["Ink"], number).drawing)
    return float(np.mean(np.hypot(strokes.positions[:, 0], strokes.positions[:, 2])))


def breakdowns(obj):
    return [f.frame_number for f in obj.data.layers["Ink"].frames if f.keyframe_type == "BREAKDOWN"]


CIRCLES = {"method": "CIRCULAR_BALL", "carrier": "NONE"}


# -- favor ----------------------------------------------------------------------------------------


@pytest.mark.parametrize(("favor", "toward"), [(0.0, 0), (0.5, 1), (-0.5, -1)])
def test_favor_moves_a_single_in_between_toward_the_key_it_names(addon, favor, toward):
    obj = circles(3)
    assert bpy.ops.ballmorph.inbetween(favor=favor, **CIRCLES) == {"FINISHED"}
    assert breakdowns(obj) == [2]
    middle = radius(obj, 2)
    if toward:
        assert (middle - 1.5) * toward > 0.1, middle
    # the odds warp: t' = k t / (k t + 1 - t), k = 3 ** favor, at t = 0.5
    assert middle == pytest.approx(1 + 3**favor / (3**favor + 1), abs=1e-3)


def test_favor_is_applied_after_easing(addon):
    obj = circles(3)
    options = {"easing_type": "QUAD", "easing": "EASE_IN", **CIRCLES}
    assert bpy.ops.ballmorph.inbetween(favor=1.0, **options) == {"FINISHED"}
    # quad ease-in: 0.5 -> 0.25; then favor 1 (odds x 3): 0.25 -> 0.5
    assert radius(obj, 2) == pytest.approx(1.5, abs=1e-3)


# -- timing charts --------------------------------------------------------------------------------


def test_a_timing_chart_puts_one_in_between_per_fraction_at_that_fraction(addon, capfd):
    obj = circles(9)
    result, text = run(capfd, timing_chart="0.1 0.5 0.9", frame_count=1, easing_type="QUAD", **CIRCLES)
    assert result == {"FINISHED"}
    assert breakdowns(obj) == [3, 5, 7]  # the chart's count, not frame_count, and no easing
    assert [radius(obj, n) for n in (3, 5, 7)] == pytest.approx([1.1, 1.5, 1.9], abs=1e-3)
    assert "3 in-between(s) on frame(s) 3, 5, 7 (Circular Ball-morph, timing chart 0.1 0.5 0.9)" in text
    assert obj.data["ballmorph_timing_charts"].to_dict() == {"Ink:1-9": "0.1 0.5 0.9"}


def test_favor_applies_to_chart_fractions_too(addon):
    obj = circles(9)
    assert bpy.ops.ballmorph.inbetween(timing_chart="0.25, 0.5", favor=1.0, **CIRCLES) == {"FINISHED"}
    assert breakdowns(obj) == [4, 6]
    assert [radius(obj, 4), radius(obj, 6)] == pytest.approx([1.5, 1.75], abs=1e-3)


@pytest.mark.parametrize(
    ("chart", "said"),
    [
        ("0.1 half", "Timing Chart: 'half' is not a number"),
        ("0.2 1.5", "Timing Chart: 1.5 is not between 0 and 1"),
        ("0.6 0.3", "Timing Chart: 0.3 comes after 0.6 (the fractions must rise)"),
        ("0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8", "Ink 1\u21929: Timing Chart: 8 fractions but only 7 frame(s) between"),
    ],
    ids=["word", "out-of-range", "descending", "too-many"],
)
def test_a_malformed_chart_is_refused_saying_what_is_wrong_and_writes_nothing(addon, chart, said):
    obj = circles(9)
    before = gp_data.snapshot(obj)
    with pytest.raises(RuntimeError) as refused:
        bpy.ops.ballmorph.inbetween(timing_chart=chart, **CIRCLES)
    assert said in str(refused.value) and "nothing was written" in str(refused.value)
    assert "timing_chart" not in str(refused.value), "the option is named as the UI shows it"
    assert gp_data.snapshot(obj) == before
    assert "ballmorph_timing_charts" not in obj.data and "ballmorph_inbetween" not in obj.data


def test_a_rerun_with_an_empty_chart_uses_the_chart_kept_with_the_keys(addon, capfd):
    obj = circles(9)
    assert bpy.ops.ballmorph.inbetween(timing_chart="0.1 0.5 0.9", **CIRCLES) == {"FINISHED"}
    bpy.context.scene.frame_current = 4
    result, text = run(capfd, timing_chart="", frame_count=0, **CIRCLES)
    assert result == {"FINISHED"}
    assert breakdowns(obj) == [3, 5, 7]
    assert [radius(obj, n) for n in (3, 5, 7)] == pytest.approx([1.1, 1.5, 1.9], abs=1e-3)
    assert "Ink 1\u21929: timed by the chart 0.1 0.5 0.9 kept from an earlier run on these keys" in text
    # another chart replaces the kept one
    assert bpy.ops.ballmorph.inbetween(timing_chart="0.5", **CIRCLES) == {"FINISHED"}
    assert breakdowns(obj) == [5]
    assert obj.data["ballmorph_timing_charts"].to_dict() == {"Ink:1-9": "0.5"}


def test_a_kept_chart_belongs_to_its_keys_only(addon):
    obj = circles(9)
    assert bpy.ops.ballmorph.inbetween(timing_chart="0.1 0.5 0.9", **CIRCLES) == {"FINISHED"}
    gp_data.add_key(obj.data.layers["Ink"], 13, [gp_data.loop(2.5)], cyclic=[True])
    bpy.context.scene.frame_current = 10
    assert bpy.ops.ballmorph.inbetween(**CIRCLES) == {"FINISHED"}
    assert breakdowns(obj) == [3, 5, 7, 10, 11, 12]  # 9 -> 13 has no chart: every frame


def test_a_kept_chart_that_cannot_be_read_is_reported_and_ignored(addon, capfd):
    obj = circles(9)
    obj.data["ballmorph_timing_charts"] = {"Ink:1-9": "0.1 0.9 0.5"}
    result, text = run(capfd, **CIRCLES)
    assert result == {"FINISHED"}
    assert breakdowns(obj) == list(range(2, 9))
    assert "Ink 1\u21929: the timing chart kept here ('0.1 0.9 0.5') was ignored" in text


def test_the_sidebar_settings_hold_favor_and_the_chart(addon):
    obj = circles(9)
    settings = bpy.context.scene.ballmorph_inbetween
    settings.timing_chart, settings.favor, settings.carrier = "0.5", 0.5, "NONE"
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert breakdowns(obj) == [5]
    assert radius(obj, 5) == pytest.approx(1 + 3**0.5 / (3**0.5 + 1), abs=1e-3)
    assert bpy.ops.ballmorph.inbetween(timing_chart="0.25 0.75", favor=0.0) == {"FINISHED"}
    assert (settings.timing_chart, settings.favor) == ("0.25 0.75", 0.0)  # a run is remembered


# -- warnings: pairs that stray from their keys ------------------------------------------------------


def test_a_stroke_without_a_partner_gets_one_warning(addon, capfd):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [gp_data.arc(0.3), gp_data.loop(0.2, centre=(1, 0))], cyclic=[False, True])
    gp_data.add_key(layer, 9, [gp_data.arc(-0.3)])
    bpy.context.scene.frame_current = 2
    result, text = run(capfd)
    assert result == {"FINISHED"}
    warnings = [line for line in text.splitlines() if line.startswith("Warning: Ink")]
    assert len(warnings) == 1 and "has no partner: disappears at the middle" in warnings[0], warnings
    assert "1 warning(s)" in text.strip().splitlines()[-1]


@pytest.mark.parametrize(
    ("options", "bend", "why"),
    [
        ({"method": "LINEAR_INTERPOLATION"}, 0.0, "ink 29% shorter than the keys' blend of lengths"),
        # Bent a little, the stroke is no polyline: without a carrier the ball route falls back.
        (CIRCLES, 0.05, "made with linear-interpolation (a fallback); ink 29% shorter than the keys' blend of lengths"),
    ],
    ids=["too-short", "fallback"],
)
def test_a_pair_that_strays_is_reported_with_the_frame_where_it_is_worst(addon, capfd, options, bend, why):
    # A stroke turned a quarter turn: straight point paths shrink it by 29% midway.
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    s = np.linspace(-1, 1, 30)
    gp_data.add_key(layer, 1, [np.c_[s, bend * (1 - s**2)]])
    gp_data.add_key(layer, 9, [np.c_[-bend * (1 - s**2), s]])
    bpy.context.scene.frame_current = 2
    result, text = run(capfd, **options)
    assert result == {"FINISHED"}
    assert (
        f"Ink 1\u21929: stroke 1 -> 1 strays from its keys ({why}), most on frame 5: draw a breakdown key on frame 5"
    ) in text


def test_in_betweens_that_follow_their_keys_give_no_stray_warning(addon, capfd):
    circles(9)
    result, text = run(capfd, **CIRCLES)
    assert result == {"FINISHED"}
    assert "strays" not in text and "Warning" not in text


def test_favor_and_the_chart_are_properties_of_the_operator_scene_and_preferences(addon):
    operator = bpy.ops.ballmorph.inbetween.get_rna_type().properties
    assert (operator["favor"].hard_min, operator["favor"].hard_max, operator["favor"].default) == (-1.0, 1.0, 0.0)
    assert operator["timing_chart"].type == "STRING" and operator["timing_chart"].default == ""
    preferences = bpy.context.preferences.addons[addon.__name__].preferences
    preferences.favor, preferences.timing_chart = -0.25, "0.5"
    settings = bpy.context.scene.ballmorph_inbetween
    assert (settings.favor, settings.timing_chart) == (-0.25, "0.5")  # the scene reads the defaults
    settings.timing_chart = "0.2 0.4"
    assert (settings.timing_chart, preferences.timing_chart) == ("0.2 0.4", "0.5")


# -- Interpolate's Custom curve and Back / Elastic settings ------------------------------------------


def test_the_custom_type_writes_each_in_between_at_the_scenes_interpolate_curve(addon, capfd):
    # The curve Interpolate Sequence's Custom type reads: up to 0.8 at the middle, then slowly to 1.
    gp_data.ensure_interpolate_curve([(0.0, 0.0), (0.5, 0.8), (1.0, 1.0)])
    obj = circles(5)
    result, text = run(capfd, easing_type="CUSTOM", easing="EASE_IN_OUT", **CIRCLES)  # Easing: not used
    assert result == {"FINISHED"}
    assert breakdowns(obj) == [2, 3, 4]
    # fractions 1/4, 1/2, 3/4 -> the curve's 0.4, 0.8, 0.9 (radius 1 + t)
    assert [radius(obj, n) for n in (2, 3, 4)] == pytest.approx([1.4, 1.8, 1.9], abs=1e-3)
    assert "no Custom curve" not in text


def test_the_custom_type_in_a_scene_without_a_curve_runs_linear_and_says_so(addon, capfd):
    assert bpy.context.scene.tool_settings.gpencil_interpolate.interpolation_curve is None
    obj = circles(5)
    result, text = run(capfd, easing_type="CUSTOM", **CIRCLES)
    assert result == {"FINISHED"}
    assert [radius(obj, n) for n in (2, 3, 4)] == pytest.approx([1.25, 1.5, 1.75], abs=1e-3)
    assert "has no Custom curve yet, so the Custom type ran Linear" in text


@pytest.mark.parametrize(
    ("options", "settings"),
    [
        ({"easing_type": "BACK", "easing": "EASE_IN_OUT", "back": 0.0}, {"back": 0.0}),
        ({"easing_type": "BACK", "easing": "AUTO", "back": 2.5}, {"back": 2.5}),
        (
            {"easing_type": "ELASTIC", "easing": "EASE_OUT", "amplitude": 1.2, "period": 0.5},
            {"amplitude": 1.2, "period": 0.5},
        ),
    ],
)
def test_back_and_elastic_settings_time_the_in_betweens(addon, options, settings):
    obj = circles(5)
    assert bpy.ops.ballmorph.inbetween(**options, **CIRCLES) == {"FINISHED"}
    times = bm.ease([0.25, 0.5, 0.75], options["easing_type"], options["easing"], **settings)
    assert [radius(obj, n) for n in (2, 3, 4)] == pytest.approx(1 + np.clip(times, 0, 1), abs=1e-3)
