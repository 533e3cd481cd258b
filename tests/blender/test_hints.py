"""Issue 13: correspondence hints on real Grease Pencil keys (the ``ballmorph_hint`` point
attribute, a contract), the ``ballmorph.hint_add`` / ``ballmorph.hint_clear`` operators, and the
in-betweens' hints."""

import importlib

import bpy
import gp_data
import numpy as np
import pytest
from conftest import MODULE, disable_addon, enable_addon

HINT = "ballmorph_hint"


def _hints(drawing):
    attribute = drawing.attributes.get(HINT)
    if attribute is None:
        return None
    values = np.empty(len(attribute.data), dtype=np.int32)
    attribute.data.foreach_get("value", values)
    return values


def _set_hints(drawing, points):
    n = len(drawing.attributes["position"].data)
    values = np.zeros(n, dtype=np.int32)
    for point, number in points.items():
        values[point] = number
    attribute = drawing.attributes.get(HINT) or drawing.attributes.new(HINT, "INT", "POINT")
    attribute.data.foreach_set("value", values)


def _select(drawing, points):
    n = len(drawing.attributes["position"].data)
    selection = drawing.attributes.get(".selection") or drawing.attributes.new(".selection", "BOOLEAN", "POINT")
    values = np.zeros(n, dtype=bool)
    values[list(points)] = True
    selection.data.foreach_set("value", values)


def _circle_keys():
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    circle = gp_data.loop(1.0, n=80)
    gp_data.add_key(layer, 1, [circle], cyclic=[True])
    gp_data.add_key(layer, 9, [circle], cyclic=[True])
    return obj, layer, circle


def test_a_hint_turns_a_circle_that_would_otherwise_stay_put(addon):
    obj, layer, circle = _circle_keys()
    start = int(np.argmin(np.abs(np.arctan2(circle[:, 1], circle[:, 0]))))  # the point at 0 degrees
    quarter = int(np.argmin(np.abs(np.arctan2(circle[:, 1], circle[:, 0]) - np.pi / 2)))
    _set_hints(gp_data.frame_at(layer, 1).drawing, {start: 1})
    _set_hints(gp_data.frame_at(layer, 9).drawing, {quarter: 1})
    bpy.context.scene.frame_current = 5
    assert bpy.ops.ballmorph.inbetween(method="CIRCULAR_BALL") == {"FINISHED"}
    angles = []
    for number in range(2, 9):
        drawing = gp_data.frame_at(layer, number).drawing
        hints = _hints(drawing)
        (at,) = np.flatnonzero(hints == 1)  # exactly one point carries hint 1
        assert np.count_nonzero(hints) == 1
        position = gp_data.read_strokes(drawing).positions[at]
        angles.append(np.degrees(np.arctan2(position[2], position[0])))
    assert np.all(np.diff(angles) > 0), angles
    assert abs(angles[3] - 45.0) < 2.0, angles  # frame 5: the middle


def test_hints_override_the_automatic_pairing(addon):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    x = np.linspace(0.0, 1.0, 30)
    low, high = np.c_[x, 0 * x], np.c_[x, 0 * x + 1.0]
    gp_data.add_key(layer, 1, [low, high])
    gp_data.add_key(layer, 9, [low, high])
    _set_hints(gp_data.frame_at(layer, 1).drawing, {15: 1})  # the low line's middle ...
    _set_hints(gp_data.frame_at(layer, 9).drawing, {45: 1})  # ... is the high line's middle
    bpy.context.scene.frame_current = 5
    assert bpy.ops.ballmorph.inbetween(method="CIRCULAR_BALL") == {"FINISHED"}
    middle = gp_data.frame_at(layer, 5).drawing
    (at,) = np.flatnonzero(_hints(middle) == 1)
    np.testing.assert_allclose(gp_data.read_strokes(middle).positions[at][[0, 2]], [0.5, 0.5], atol=0.05)


def test_bad_hints_are_reported_and_the_run_finishes(addon, capfd):
    obj, layer, circle = _circle_keys()
    _set_hints(gp_data.frame_at(layer, 1).drawing, {0: 1, 10: 2})
    _set_hints(gp_data.frame_at(layer, 9).drawing, {0: 1, 5: 1})  # 1 twice, 2 missing
    bpy.context.scene.frame_current = 5
    assert bpy.ops.ballmorph.inbetween(method="CIRCULAR_BALL") == {"FINISHED"}
    text = capfd.readouterr().out
    assert "hint 1 is on 2 points of the second key" in text
    assert "hint 2 is on the first key only" in text
    assert gp_data.frame_numbers(layer) == list(range(1, 10))


def test_hint_add_numbers_the_selected_points_and_hint_clear_removes_them(addon):
    obj, layer, circle = _circle_keys()
    bpy.context.view_layer.objects.active = obj
    bpy.context.scene.frame_current = 1
    drawing = gp_data.frame_at(layer, 1).drawing
    _select(drawing, [3])
    assert bpy.ops.ballmorph.hint_add() == {"FINISHED"}
    _select(drawing, [7, 12])
    assert bpy.ops.ballmorph.hint_add() == {"FINISHED"}
    hints = _hints(drawing)
    assert hints[[3, 7, 12]].tolist() == [1, 2, 3] and np.count_nonzero(hints) == 3
    _select(drawing, [20])
    assert bpy.ops.ballmorph.hint_add(number=2) == {"FINISHED"}  # 2 moves to point 20
    assert _hints(drawing)[[7, 20]].tolist() == [0, 2]
    _select(drawing, [3])
    assert bpy.ops.ballmorph.hint_clear() == {"FINISHED"}
    assert _hints(drawing)[3] == 0 and np.count_nonzero(_hints(drawing)) == 2
    assert bpy.ops.ballmorph.hint_clear(all_points=True) == {"FINISHED"}
    assert not _hints(drawing).any()
    _select(drawing, [])
    with pytest.raises(RuntimeError, match="select the point"):  # nothing selected: says so
        bpy.ops.ballmorph.hint_add()


def test_the_hints_show_as_numbered_dots_on_both_keys(addon):
    module = importlib.import_module(f"{MODULE}.ui.hint_dots")
    marks = importlib.import_module(f"{MODULE}.operators.hints").MARKS
    assert module.installed()  # with the add-on
    obj, layer, circle = _circle_keys()
    bpy.context.view_layer.objects.active = obj
    _set_hints(gp_data.frame_at(layer, 1).drawing, {0: 1, 20: 2})
    _set_hints(gp_data.frame_at(layer, 9).drawing, {10: 1})
    bpy.context.scene.frame_current = 4
    marks.edited()
    points, numbers, key = marks.marks(bpy.context)
    assert numbers.tolist() == [1, 2, 1] and key.tolist() == [0, 0, 1]
    np.testing.assert_allclose(points[0], [circle[0, 0], 0.0, circle[0, 1]], atol=1e-6)
    module.draw()  # background: draws nothing, raises nothing
    disable_addon()
    assert not module.installed()
    enable_addon()
