"""The demo's drawings (tests/fixtures/shots.py) make the case they are there for."""

import numpy as np
import shots

import ballmorph_core as bm


def _middle(method, arch, dip):
    keys = [bm.StrokeSet.from_strokes([stroke]) for stroke in (arch, dip)]
    frame = bm.plan_inbetween(*keys, method=method).evaluate([0.5]).frames[0]
    return frame.positions[:, [0, 2]] if np.ptp(frame.positions[:, 1]) == 0 else frame.positions[:, :2]


def _apart(a, b):
    """The Hausdorff distance of two polylines' points."""
    gaps = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    return max(gaps.min(axis=0).max(), gaps.min(axis=1).max())


def _turn(curve):
    """The largest turn between consecutive edges of a polyline, in degrees."""
    edges = np.diff(curve, axis=0)
    return np.degrees(np.abs(np.diff(np.unwrap(np.arctan2(edges[:, 1], edges[:, 0]))))).max()


def test_the_bend_rows_differ_visibly_and_smoothly():
    """Issue 40: the demo's two Bend rows (circular ball-morph, linear interpolation) looked alike
    (their middle in-betweens 0.7% of the stroke's width apart). A hump leaning over from left to
    right: the ball-morph holds its top flat at the keys' crossing, linear interpolation rounds it
    into a dome above; no in-between kinks."""
    left, right = shots.lean_left(), shots.lean_right()
    width = np.ptp(np.r_[left, right][:, 0])
    circular, linear = _middle("circular-ball", left, right), _middle("linear-interpolation", left, right)
    assert _apart(circular, linear) > 0.05 * width
    crossing = np.interp(1.2, left[:, 0], left[:, 1] - right[:, 1])  # the keys cross near the middle
    assert abs(crossing) < 0.1
    top = np.interp(1.2, left[:, 0], left[:, 1])
    assert circular[:, 1].max() < top + 0.05 < top + 0.1 < linear[:, 1].max()
    keys = [bm.StrokeSet.from_strokes([stroke]) for stroke in (left, right)]
    frames = bm.plan_inbetween(*keys, method="circular-ball").evaluate(np.arange(1, 8) / 8).frames
    assert max(_turn(frame.positions[:, [0, 2]]) for frame in frames) < 2 * max(_turn(left), _turn(right))
