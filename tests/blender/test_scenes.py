"""Issues 11 and 12 in Blender: the scenes of tests/fixtures/scenes/ as real Grease Pencil keys.

Each scene's keys are written on frames 1 and 9 with plain ``foreach_set`` (gp_data), the real
operator fills frames 2..8 (7 in-betweens, linear timing, the scene's options), the frames are
read back with plain ``foreach_get`` and judged by the same figure functions as the core's
output (tests/scenarios/test_scenes.py), with the same ``xfail(strict=True)`` markers.

Blender stores float32, so the float64 twins of the turn scenes are left out (their float32
twins run), and so are the tangent-ball scenes: the operator does not offer that morph.
"""

import bpy
import gp_data
import numpy as np
import pytest
import scenes  # tests/fixtures, on the path by tests/conftest.py

FIRST, LAST = 1, 9


def _params():
    for name, scene in scenes.SCENES.items():
        if scene.blender:
            reason = None if name in scenes.BLENDER_PASSES else scenes.XFAIL_TODAY.get(name)
            marks = [pytest.mark.xfail(strict=True, raises=AssertionError, reason=reason)] if reason else []
            yield pytest.param(scene, id=name, marks=marks)


def _write_keys(scene):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    for number, k in zip((FIRST, LAST), scene.keys):
        radius = None if k.radius is None else np.concatenate(k.radius)
        opacity = None if k.opacity is None else np.concatenate(k.opacity)
        gp_data.add_key(layer, number, list(k.strokes), cyclic=list(k.cyclic), radius=radius, opacity=opacity)
    bpy.context.scene.frame_current = (FIRST + LAST) // 2
    return layer


def _drawing(layer, number):
    return scenes.as_drawing(gp_data.read_strokes(gp_data.frame_at(layer, number).drawing))


@pytest.mark.parametrize("scene", list(_params()))
def test_operator_meets_every_figure(addon, scene):
    layer = _write_keys(scene)
    assert bpy.ops.ballmorph.inbetween(method="CIRCULAR_BALL", **scene.blender_options()) == {"FINISHED"}
    assert gp_data.frame_numbers(layer) == list(range(FIRST, LAST + 1))
    keys = (_drawing(layer, FIRST), _drawing(layer, LAST))  # as Blender stores them: float32
    frames = [_drawing(layer, n) for n in range(FIRST + 1, LAST)]
    figures = scene.figures(keys, frames)
    missed = [str(f) for f in figures if not (f.ok or f.informative)]
    assert not missed, f"{scene.name} ({scene.about}): " + "; ".join(missed)
    if scene.name.startswith("identical-"):  # the bytes Blender stores, not only the figure
        key_bytes = gp_data.read_raw(gp_data.frame_at(layer, FIRST).drawing)["position"]
        for number in range(FIRST + 1, LAST):
            assert gp_data.read_raw(gp_data.frame_at(layer, number).drawing)["position"] == key_bytes


def test_the_keys_read_back_are_the_scene_keys_in_float32(addon):
    scene = scenes.SCENES["turn-90-centre-f32"]
    layer = _write_keys(scene)
    for number, k in zip((FIRST, LAST), scene.keys):
        (stroke,) = _drawing(layer, number)
        np.testing.assert_array_equal(stroke.xy, k.strokes[0])  # the f32 twin is exactly what Blender holds
