"""Issue 39 item 2 in Blender: a tyre valve rides the wheel it lies in, not the whole drawing.

A car body (an outline, a window, a door line) that only translates, and its wheel (rim, hub,
eight curved spokes, one shorter, a valve: a small circle near the rim) rolling with it, keyed on
frames 1 and 9; the real operator fills frames 2..8, read back: the valve stays on its arc about
the hub (within 0.5% of the wheel's size), and the spokes turn with the wheel.
"""

import bpy
import gp_data
import numpy as np
import pytest
import scenes  # tests/fixtures, on the path by tests/conftest.py

#: Strokes of scenes.car_wheel: the body (0-2), the rim, the hub, eight spokes, the valve.
HUB, SPOKES, VALVE = 4, range(5, 13), 13


@pytest.mark.parametrize("turn", [-30.0, -60.0])
def test_a_valve_on_a_rolling_car_wheel_stays_on_its_arc(addon, turn):
    a, b, cyclic = scenes.car_wheel(turn)
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, a, cyclic=cyclic)
    gp_data.add_key(layer, 9, b, cyclic=cyclic)
    bpy.context.scene.frame_current = 5
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert gp_data.frame_numbers(layer) == list(range(1, 10))
    worst, spokes_off = 0.0, 0.0
    for number in range(2, 9):
        frame = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        xy = [frame.positions[frame.points(i)][:, [0, 2]].astype(float) for i in range(len(frame))]
        hub, valve = xy[HUB].mean(axis=0), xy[VALVE].mean(axis=0)
        worst = max(worst, abs(float(np.linalg.norm(valve - hub)) - 0.92) / 2.0)
        # Each spoke at its key-A place turned about the hub as far as the hub has rolled.
        t = float(hub[0]) / np.radians(abs(turn))
        turned = [scenes.turned(a[k], turn * t, (0.0, 0.0)) + hub for k in SPOKES]
        spokes_off = max(spokes_off, max(float(np.abs(xy[k] - s).max()) for k, s in zip(SPOKES, turned)) / 2.0)
    assert worst <= 0.005, f"wheel turning {turn}° on a car: the valve up to {worst:.3%} of the wheel off its arc"
    assert spokes_off <= 0.005, f"wheel turning {turn}° on a car: a spoke up to {spokes_off:.3%} of the wheel off"
