"""Select Warned Strokes (``ballmorph.select_warned``): the strokes the last run's warnings name,
selected in their keys, and nothing else changed (issue 40: strokes an animator can find)."""

import bpy
import gp_data
import numpy as np
from conftest import MODULE


def selection(drawing):
    """Per-point edit-mode selection of a drawing, read with plain foreach_get (no attribute:
    everything counts as selected)."""
    n = len(drawing.attributes["position"].data)
    attribute = drawing.attributes.get(".selection")
    if attribute is None:
        return np.ones(n, dtype=bool)
    values = np.zeros(len(attribute.data), dtype=bool)
    attribute.data.foreach_get("value", values)
    if attribute.domain == "CURVE":
        offsets = np.zeros(len(drawing.curve_offsets), np.int32)
        drawing.curve_offsets.foreach_get("value", offsets)
        values = np.repeat(values, np.diff(offsets))
    return values


def positions(drawing):
    return gp_data.read_raw(drawing)["position"]


def key_without_partner():
    """Key 1: a loop and an arc; key 5: the loop only (the arc, stroke 2 of the first key, has
    no partner). Everything starts selected, as after drawing."""
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [gp_data.loop(1.0), gp_data.arc(0.3)], cyclic=[True, False])
    gp_data.add_key(layer, 5, [gp_data.loop(1.2)], cyclic=[True])
    bpy.context.scene.frame_current = 2
    return obj, layer


def test_it_selects_exactly_the_stroke_without_a_partner_and_changes_nothing_else(addon, capfd):
    obj, layer = key_without_partner()
    assert not bpy.ops.ballmorph.select_warned.poll()  # no run yet
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    first, second = gp_data.frame_at(layer, 1).drawing, gp_data.frame_at(layer, 5).drawing
    before = {n: positions(gp_data.frame_at(layer, n).drawing) for n in (1, 2, 3, 4, 5)}
    frames = gp_data.frame_numbers(layer)
    assert bpy.ops.ballmorph.select_warned.poll()
    capfd.readouterr()
    assert bpy.ops.ballmorph.select_warned() == {"FINISHED"}
    out, err = capfd.readouterr()
    assert "Selected 1 warned stroke(s) in their keys (layer 'Ink': key 1 stroke 2)" in out + err
    loop_points = len(gp_data.loop(1.0))
    assert not selection(first)[:loop_points].any() and selection(first)[loop_points:].all()
    assert not selection(second).any()
    for n in (2, 3, 4):  # the in-betweens: deselected too
        assert not selection(gp_data.frame_at(layer, n).drawing).any()
    # only the selection changed: every position, every frame the same
    assert {n: positions(gp_data.frame_at(layer, n).drawing) for n in (1, 2, 3, 4, 5)} == before
    assert gp_data.frame_numbers(layer) == frames
    assert bpy.context.scene.frame_current == 2


def test_the_record_is_kept_with_the_data_and_replaced_by_the_next_run(addon):
    obj, layer = key_without_partner()
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert obj.data["ballmorph_warned_strokes"].to_dict() == {"Ink": [1, 2]}  # key 1, stroke 2
    gp_data.frame_at(layer, 1).drawing.remove_strokes(indices=[1])  # every stroke has a partner now
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert "ballmorph_warned_strokes" not in obj.data
    assert not bpy.ops.ballmorph.select_warned.poll()


def test_a_stroke_removed_since_the_run_is_reported_not_guessed(addon, capfd):
    obj, layer = key_without_partner()
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    gp_data.frame_at(layer, 1).drawing.remove_strokes(indices=[1])  # the warned arc is gone
    capfd.readouterr()
    assert bpy.ops.ballmorph.select_warned() == {"FINISHED"}
    out, err = capfd.readouterr()
    assert "Not found (the keys changed since the run): layer 'Ink': key 1 stroke 2" in out + err
    assert not selection(gp_data.frame_at(layer, 1).drawing).any()


def test_the_operator_is_registered_and_unregistered_with_the_add_on(addon):
    assert bpy.ops.ballmorph.select_warned.idname() == "BALLMORPH_OT_select_warned"
    assert hasattr(bpy.types, "BALLMORPH_OT_select_warned")
    assert MODULE


def _select(drawing, selected):
    """A stroke selection, as edit mode keeps it."""
    if ".selection" in drawing.attributes:
        drawing.attributes.remove(drawing.attributes[".selection"])
    drawing.attributes.new(".selection", "BOOLEAN", "CURVE")
    drawing.attributes[".selection"].data.foreach_set("value", np.asarray(selected, bool))


def test_with_selected_strokes_only_the_warned_stroke_is_found_by_its_place_in_the_key(addon):
    """The core sees only the selected strokes (here strokes 2 and 3 of key 1): its stroke 2 is
    the drawing's stroke 3, and that is the one selected."""
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    strokes = [gp_data.loop(0.3, centre=(-2, 0)), gp_data.loop(1.0), gp_data.arc(0.3)]
    gp_data.add_key(layer, 1, strokes, cyclic=[True, True, False])
    gp_data.add_key(layer, 5, [gp_data.loop(0.3, centre=(-2, 0)), gp_data.loop(1.2)], cyclic=[True, True])
    _select(gp_data.frame_at(layer, 1).drawing, [False, True, True])
    _select(gp_data.frame_at(layer, 5).drawing, [False, True])
    bpy.context.scene.frame_current = 2
    assert bpy.ops.ballmorph.inbetween(selected_only=True) == {"FINISHED"}
    assert obj.data["ballmorph_warned_strokes"].to_dict() == {"Ink": [1, 3]}  # key 1, stroke 3
    assert bpy.ops.ballmorph.select_warned() == {"FINISHED"}
    first = selection(gp_data.frame_at(layer, 1).drawing)
    sizes = np.cumsum([0] + [len(s) for s in strokes])
    assert [bool(first[sizes[k] : sizes[k + 1]].all()) for k in range(3)] == [False, False, True]
    assert not first[: sizes[2]].any()
