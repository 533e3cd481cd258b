"""Where the operator runs from (Dope Sheet, 3D viewport), and what F9 does (undo, redo: test_robustness)."""

import importlib

import bpy
import gp_data
import numpy as np


def ink(obj):
    return obj.data.layers["Ink"]


def test_runs_from_the_dope_sheet_on_selected_keys(shot):
    layer = ink(shot)
    gp_data.add_key(layer, 13, [gp_data.loop(0.8), gp_data.arc(0.1)], cyclic=[True, False])
    for frame in layer.frames:
        frame.select = True  # three selected keys: two intervals
    bpy.context.scene.frame_current = 30  # far from the keys: the selection decides
    with gp_data.dopesheet_override():
        assert bpy.context.space_data.mode == "GPENCIL"
        assert bpy.ops.ballmorph.inbetween.poll()
        assert bpy.ops.ballmorph.inbetween(frame_count=1) == {"FINISHED"}
    made = {f.frame_number: f.keyframe_type for f in layer.frames}
    assert made == {1: "KEYFRAME", 5: "BREAKDOWN", 9: "KEYFRAME", 11: "BREAKDOWN", 13: "KEYFRAME"}


def test_runs_from_the_3d_viewport_around_the_current_frame(shot):
    with gp_data.view3d_override():
        assert bpy.context.area.type == "VIEW_3D"
        assert bpy.ops.ballmorph.inbetween(frame_count=3) == {"FINISHED"}
    assert gp_data.frame_numbers(ink(shot)) == [1, 3, 5, 7, 9]


def test_runs_in_edit_mode(shot):
    with gp_data.view3d_override():
        bpy.ops.object.mode_set(mode="EDIT")
        assert bpy.ops.ballmorph.inbetween(frame_count=1) == {"FINISHED"}
        bpy.ops.object.mode_set(mode="OBJECT")
    assert gp_data.frame_numbers(ink(shot)) == [1, 5, 9]


def _window():
    return bpy.context.temp_override(window=bpy.context.window_manager.windows[0])


def test_redo_reruns_with_the_changed_options(shot):
    """What F9 does: undo the run, then repeat it with the options edited in the redo panel.

    ``ed.undo_redo`` itself crashes bpy in background mode, so the test performs its two steps:
    it takes the properties the run registered (every option is set on the operator, so the
    redo does not depend on the panel settings any more) and repeats with one of them changed.
    """
    bpy.ops.ed.undo_push(message="before")
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, method="LINEAR_BALL") == {"FINISHED"}
    last = bpy.context.window_manager.operators[-1]
    assert last.bl_idname == "BALLMORPH_OT_inbetween"
    options = {name: getattr(last.properties, name) for name in last.properties.bl_rna.properties.keys()}
    options.pop("rna_type")
    assert options["method"] == "LINEAR_BALL" and options["frame_count"] == 0
    bpy.context.scene.ballmorph_inbetween.method = "PARABOLIC_BALL"  # the panel changes meanwhile
    with _window():
        assert bpy.ops.ed.undo() == {"FINISHED"}
    assert gp_data.frame_numbers(ink(bpy.data.objects["Drawing"])) == [1, 9]
    options["frame_count"] = 1
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, **options) == {"FINISHED"}
    assert gp_data.frame_numbers(ink(bpy.data.objects["Drawing"])) == [1, 5, 9]
    assert bpy.context.scene.ballmorph_inbetween.method == "LINEAR_BALL"


def test_redo_reuses_the_plan_of_unchanged_keys_and_writes_the_same_frames(shot, addon):
    """F9 with another frame count or easing reuses the last run's plan (matching, ball-maps,
    carriers: the expensive part), and what it writes is exactly what a fresh run writes. Keys
    edited since, or another morph, are planned again."""
    plans = importlib.import_module(f"{addon.__name__}.operators.plans").PLANS

    def drawing():  # undo replaces the scene's data: look the object up again each time
        return bpy.data.objects["Drawing"]

    bpy.ops.ed.undo_push(message="before")
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, frame_count=3) == {"FINISHED"}
    assert (plans.misses, plans.hits) == (1, 0)
    redo = {"frame_count": 5, "easing_type": "SINE", "easing": "EASE_IN_OUT"}
    with _window():
        assert bpy.ops.ed.undo() == {"FINISHED"}
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, **redo) == {"FINISHED"}
    assert (plans.misses, plans.hits) == (1, 1)
    reused = gp_data.snapshot(drawing())
    assert gp_data.frame_numbers(ink(drawing())) == [1, 2, 4, 5, 6, 8, 9]

    plans.clear()  # the same redo from scratch
    with _window():
        assert bpy.ops.ed.undo() == {"FINISHED"}
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, **redo) == {"FINISHED"}
    assert (plans.misses, plans.hits) == (2, 1)
    assert gp_data.snapshot(drawing()) == reused

    # Another morph, then an edited key: planned again.
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, method="LINEAR_BALL", **redo) == {"FINISHED"}
    assert (plans.misses, plans.hits) == (3, 1)
    key = gp_data.frame_at(ink(drawing()), 9).drawing
    position = key.attributes["position"]
    points = np.empty(len(position.data) * 3, np.float32)
    position.data.foreach_get("vector", points)
    points[0] += 0.05
    position.data.foreach_set("vector", points)
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, method="LINEAR_BALL", **redo) == {"FINISHED"}
    assert (plans.misses, plans.hits) == (4, 1)
