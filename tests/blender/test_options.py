"""One option vocabulary: every enum item carries its lowercase value, and only values reach the core."""

import importlib

import bpy
import gp_data
import pytest


def addon_module(addon, name):
    return importlib.import_module(f"{addon.__name__}.{name}")


def test_every_item_has_a_lowercase_value_and_a_blender_id(addon):
    options = addon_module(addon, "operators.options")
    properties = bpy.ops.ballmorph.inbetween.get_rna_type().properties
    for option in options.OPTIONS:
        if option.kind != "ENUM":
            continue
        assert [item.id for item in option.items] == [i.identifier for i in properties[option.name].enum_items]
        for item in option.items:
            assert item.value == item.value.lower() and "_" not in item.value and " " not in item.value, item
            assert option.value(item.id) == item.value and option.blender(item.value) == item.id
        assert option.default in option.values
        assert properties[option.name].default == option.blender(option.default)


def test_the_core_takes_every_value_of_the_table(addon):
    options = addon_module(addon, "operators.options")
    core = addon_module(addon, "ballmorph_core")
    assert set(options.option("method").values) <= set(core.METHODS)
    assert core.FALLBACK_METHOD in options.option("method").values
    for kind in options.option("easing_type").values:
        for mode in options.option("easing").values:
            eased = core.ease([0.0, 0.5, 1.0], kind, mode, curve=[0.0, 1.0])
            assert eased[[0, -1]].tolist() == pytest.approx([0.0, 1.0])
    key_a = core.StrokeSet.from_strokes([gp_data.arc(0.3)])
    key_b = core.StrokeSet.from_strokes([gp_data.arc(-0.3), gp_data.loop(0.2)], cyclic=[False, True])
    for name in ("carrier", "matching", "unmatched"):
        for value in options.option(name).values:
            assert core.plan_inbetween(key_a, key_b, **{name: value}).evaluate([0.5]).frames


def test_values_of_reads_any_holder_of_the_options(addon):
    options = addon_module(addon, "operators.options")
    settings = bpy.context.scene.ballmorph_inbetween
    settings.method, settings.easing, settings.layers = "PARABOLIC_BALL", "EASE_IN_OUT", "ALL"
    values = options.values_of(settings)
    assert values == {
        "method": "parabolic-ball",
        "frame_count": 0,
        "timing_chart": "",
        "easing_type": "linear",
        "easing": "ease-in-out",
        "back": pytest.approx(1.702),
        "amplitude": pytest.approx(0.15),
        "period": pytest.approx(0.15),
        "favor": 0.0,
        "layers": "all",
        "selected_only": False,
        "carrier": "similarity",
        "matching": "auto",
        "unmatched": "middle",
        "key_motion": "smooth",
    }
    assert options.label("method", "parabolic-ball") == "Parabolic Ball-morph"


@pytest.mark.parametrize(
    ("given", "core"),
    [
        ({}, ("circular-ball", "linear", "ease-in", "similarity", "auto", "middle")),
        (
            {"method": "LINEAR_BALL", "easing_type": "QUAD", "easing": "EASE_IN_OUT", "carrier": "RIGID"},
            ("linear-ball", "quad", "ease-in-out", "rigid", "auto", "middle"),
        ),
        (
            {"easing_type": "BACK", "easing": "AUTO", "matching": "INDEX", "unmatched": "HOLD", "carrier": "NONE"},
            ("circular-ball", "back", "auto", "none", "index", "hold"),
        ),
    ],
)
def test_the_operator_passes_the_core_values_from_the_table(shot, addon, monkeypatch, given, core):
    morph = addon_module(addon, "operators.morph")
    plans = addon_module(addon, "operators.plans")
    eased, planned = [], []
    real_ease, real_plan = morph.ease, plans.plan_inbetween

    def spy_ease(x, kind, mode, **settings):
        eased.append((kind, mode))
        return real_ease(x, kind, mode, **settings)

    def spy_plan(key_a, key_b, **kwargs):
        planned.append(kwargs)
        return real_plan(key_a, key_b, **kwargs)

    monkeypatch.setattr(morph, "ease", spy_ease)
    monkeypatch.setattr(plans, "plan_inbetween", spy_plan)
    assert bpy.ops.ballmorph.inbetween(frame_count=1, **given) == {"FINISHED"}
    method, kind, mode, carrier, matching, unmatched = core
    assert eased == [(kind, mode)]
    assert planned == [{"method": method, "carrier": carrier, "matching": matching, "unmatched": unmatched}]


@pytest.mark.parametrize(
    ("given", "settings"),
    [
        ({"easing_type": "BACK", "back": 2.5}, {"back": 2.5}),
        ({"easing_type": "ELASTIC", "amplitude": 1.5, "period": 0.4}, {"amplitude": 1.5, "period": 0.4}),
        ({"easing_type": "ELASTIC"}, {"amplitude": 0.15, "period": 0.15}),  # Interpolate Sequence's defaults
    ],
)
def test_the_types_settings_reach_the_easing(shot, addon, monkeypatch, given, settings):
    morph = addon_module(addon, "operators.morph")
    seen, real_ease = [], morph.ease

    def spy_ease(x, kind, mode, **kwargs):
        seen.append(kwargs)
        return real_ease(x, kind, mode, **kwargs)

    monkeypatch.setattr(morph, "ease", spy_ease)
    assert bpy.ops.ballmorph.inbetween(frame_count=1, **given) == {"FINISHED"}
    assert {name: seen[0][name] for name in settings} == pytest.approx(settings)
    assert seen[0]["curve"] is None  # only the Custom type samples the scene's curve


def test_saved_type_numbers_keep_their_meaning(addon):
    """Custom came second in the Type list, as in Interpolate Sequence, but scenes and preferences
    store the item's number: the types before it keep theirs."""
    options = addon_module(addon, "operators.options")
    numbers = {
        item.identifier: item.value
        for item in bpy.ops.ballmorph.inbetween.get_rna_type().properties["easing_type"].enum_items
    }
    assert (numbers["LINEAR"], numbers["SINE"], numbers["QUAD"], numbers["ELASTIC"], numbers["CUSTOM"]) == (
        0,
        1,
        2,
        10,
        11,
    )
    settings = bpy.context.scene.ballmorph_inbetween
    settings.easing_type = "QUAD"
    assert settings["easing_type"] == 2 == options.option("easing_type").raw("quad")
    settings.easing_type = "CUSTOM"
    assert settings["easing_type"] == 11 == options.option("easing_type").raw("custom")
