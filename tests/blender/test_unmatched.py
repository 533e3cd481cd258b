"""Issue 12: what a stroke without a partner does, chosen on the operator: fade, shrink into a
point, shrink into the nearest paired stroke (besides switching halfway and holding)."""

import bpy
import gp_data
import numpy as np
import pytest


def _keys():
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    face, drop = gp_data.loop(1.0, n=60), gp_data.loop(0.1, n=20, centre=(1.3, 0.0))
    gp_data.add_key(layer, 1, [face, drop], cyclic=[True, True], opacity=np.ones(80))
    gp_data.add_key(layer, 9, [face + [1.0, 0.0]], cyclic=[True], opacity=np.ones(60))
    bpy.context.scene.frame_current = 5
    return layer


def _drop(layer, number):
    strokes = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
    return strokes if len(strokes) > 1 else None


@pytest.mark.parametrize("unmatched", ["FADE", "SHRINK", "NEIGHBOUR"])
def test_a_stroke_without_a_partner_goes_gradually(addon, unmatched):
    layer = _keys()
    assert bpy.ops.ballmorph.inbetween(method="CIRCULAR_BALL", unmatched=unmatched) == {"FINISHED"}
    sizes, opacities = [], []
    for number in range(2, 9):
        strokes = _drop(layer, number)
        assert strokes is not None, f"the drop is gone on frame {number}"
        xy = strokes.positions[strokes.points(1)][:, [0, 2]]
        ink = np.linalg.norm(np.diff(xy, axis=0), axis=1).sum()  # a shrinking loop is open meanwhile
        sizes.append(ink if unmatched == "SHRINK" else np.ptp(xy, axis=0).max())
        opacities.append(strokes.opacity[strokes.points(1)].mean())
    t = (np.arange(2, 9) - 1) / 8
    if unmatched == "FADE":
        np.testing.assert_allclose(opacities, 1 - t, atol=1e-6)
        np.testing.assert_allclose(sizes, sizes[0], atol=1e-6)
    else:
        assert np.all(np.diff(sizes) < 0), sizes  # it shrinks frame by frame, never pops
