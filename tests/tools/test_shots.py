"""The demo's drawings (tests/fixtures/shots.py) make the case they are there for."""

import numpy as np
import shots

import ballmorph_core as bm


def _turn(curve):
    """The largest turn between consecutive edges of a polyline, in degrees."""
    edges = np.diff(curve, axis=0)
    return np.degrees(np.abs(np.diff(np.unwrap(np.arctan2(edges[:, 1], edges[:, 0]))))).max()


def test_the_demo_bend_stays_smooth():
    """Issue 40: the demo's Bend (an arch bending into a dip, ends shared) shows in-betweens as
    smooth as its keys. Keys that cross each other (a hump leaning over, tried for a comparison
    row) gave elbows at the crossing, visible in Blender's render: that row was dropped."""
    arch, dip = shots.bend_arch(), shots.bend_down()
    keys = [bm.StrokeSet.from_strokes([stroke]) for stroke in (arch, dip)]
    frames = bm.plan_inbetween(*keys, method="circular-ball").evaluate(np.arange(1, 8) / 8).frames
    worst = max(_turn(frame.positions[:, [0, 2]]) for frame in frames)
    assert worst <= 1.5 * max(_turn(arch), _turn(dip)), f"an in-between turns {worst:.2f} degrees at one point"
