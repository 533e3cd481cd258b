"""Issue 5 in Blender: keys drawn like real drawings, not like test curves.

A face: key 1 has four strokes (head outline, brow, mouth, hair curl), key 2 five: the head has
moved and turned so its outline crosses its first position, and was started elsewhere and drawn
the other way round; the brow is drawn the other way, the mouth turned from a smile into a
frown, the curl turns the other way, and a new stroke appears. No stroke shares an endpoint with
its partner. The operator must finish, say what it did with the new stroke and the reversed
ones, and write only strokes that do not cross themselves (Blender's own Interpolate, on the
same keys, writes outlines that do: the check has teeth).
"""

import bpy
import gp_data
import numpy as np
import pytest

from ballmorph_core.geometry.intersections import crossings, is_simple
from ballmorph_core.geometry.polyline import curve_length

HEAD, BROW, MOUTH, CURL, NEW = range(5)


def _ellipse(rx, rz, centre, turn=0.0, wobble=0.0, n=120):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + np.pi / 2
    r = 1 + wobble * np.cos(3 * t)
    c, s = np.cos(turn), np.sin(turn)
    return np.c_[rx * r * np.cos(t), rz * r * np.sin(t)] @ np.array([[c, s], [-s, c]]) + centre


def _bent(start, end, sag, n=40):
    """A stroke from ``start`` to ``end`` bowed sideways by ``sag``."""
    u = np.linspace(0, 1, n)[:, None]
    start, end = np.asarray(start, float), np.asarray(end, float)
    d = end - start
    return start + u * d + sag * np.sin(np.pi * u) * np.array([-d[1], d[0]]) / np.linalg.norm(d)


def _arc(centre, radius, start, sweep, n=50, grow=0.0):
    """A circular arc (a curl when ``grow`` widens it), counter-clockwise for sweep > 0."""
    a = start + np.linspace(0, sweep, n)
    r = radius * (1 + grow * np.linspace(0, 1, n))
    return np.c_[centre[0] + r * np.cos(a), centre[1] + r * np.sin(a)]


def face_keys():
    """(key 1 strokes, key 2 strokes) as (n, 2) arrays on the XZ canvas."""
    key_1 = [
        _ellipse(1.0, 1.2, (0.0, 0.0), wobble=0.25),  # a lumpy outline
        _bent((-0.6, 0.5), (-0.1, 0.6), 0.08),
        _arc((0.0, -0.45), 0.35, 1.15 * np.pi, 0.7 * np.pi),  # smile
        _arc((0.4, 1.5), 0.25, -np.pi / 2, 1.6 * np.pi, 60, grow=0.6),
    ]
    key_2 = [
        # crosses the first outline; started elsewhere and drawn clockwise
        np.roll(_ellipse(1.1, 1.1, (0.5, 0.2), turn=0.5, wobble=0.25)[::-1], 60, axis=0),
        _bent((0.1, 0.9), (-0.5, 0.65), -0.15),  # drawn right to left
        _arc((0.3, -0.75), 0.35, 0.15 * np.pi, 0.7 * np.pi),  # frown, drawn right to left
        _arc((0.9, 1.6), 0.28, -np.pi / 2, -1.6 * np.pi, 60, grow=0.6),  # the curl turns the other way
        _bent((1.9, 0.2), (2.1, 0.9), 0.12, 30),  # new: a hand coming in
    ]
    return key_1, key_2


@pytest.fixture
def face(addon):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    key_1, key_2 = face_keys()
    # the brow wears material 1 so the test can find it in the in-betweens
    gp_data.add_key(layer, 1, key_1, cyclic=[True, False, False, False], materials=[0, 1, 0, 0])
    gp_data.add_key(layer, 9, key_2, cyclic=[True, False, False, False, False], materials=[0, 1, 0, 0, 0])
    bpy.context.scene.frame_current = 3
    return obj


def test_the_face_keys_are_what_the_test_claims():
    key_1, key_2 = face_keys()
    assert (len(key_1), len(key_2)) == (4, 5)
    assert len(crossings(key_1[HEAD], True, key_2[HEAD], True)) >= 2  # the outline crosses itself in time
    for i in (BROW, MOUTH, CURL):
        ends_1, ends_2 = key_1[i][[0, -1]], key_2[i][[0, -1]]
        assert np.min(np.linalg.norm(ends_1[:, None] - ends_2[None], axis=2)) > 0.1  # no shared endpoint
    # the brow runs the other way: its start is nearer the partner's end than the partner's start
    assert np.linalg.norm(key_1[BROW][0] - key_2[BROW][-1]) < np.linalg.norm(key_1[BROW][0] - key_2[BROW][0])


@pytest.mark.parametrize("method", ["CIRCULAR_BALL", "LINEAR_BALL", "PARABOLIC_BALL"])
def test_real_drawing_in_betweens_are_simple_and_reported(face, capfd, method):
    layer = face.data.layers["Ink"]
    keys = {n: gp_data.read_raw(gp_data.frame_at(layer, n).drawing) for n in (1, 9)}
    capfd.readouterr()
    assert bpy.ops.ballmorph.inbetween(method=method) == {"FINISHED"}
    text = "".join(capfd.readouterr())

    assert "Warning: Ink 1\u21929: " in text
    assert "stroke 5 of the second key has no partner: appears at the middle" in text
    for stroke in (HEAD, BROW):
        assert f"stroke {stroke + 1} -> {stroke + 1}: the second key's stroke runs the other way: flipped" in text
    assert "7 in-between(s) on frame(s) 2\u20138" in text
    assert {n: gp_data.read_raw(gp_data.frame_at(layer, n).drawing) for n in (1, 9)} == keys

    key_1 = gp_data.read_strokes(gp_data.frame_at(layer, 1).drawing)
    key_2 = gp_data.read_strokes(gp_data.frame_at(layer, 9).drawing)
    brow_length = min(curve_length(k.positions[k.points(BROW)][:, [0, 2]], False) for k in (key_1, key_2))
    head_start = key_1.positions[key_1.points(HEAD)].mean(axis=0)
    head_travel = key_2.positions[key_2.points(HEAD)].mean(axis=0) - head_start
    progress = []
    for number in range(2, 9):
        frame = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        t = (number - 1) / 8
        assert len(frame) == (4 if t < 0.5 else 5)
        assert np.isfinite(frame.positions).all()
        # the reversed brow was flipped, not folded through itself: it keeps its length
        brow = frame.positions[frame.points(int(np.flatnonzero(frame.material_index == 1)[0]))][:, [0, 2]]
        assert curve_length(brow, False) > 0.8 * brow_length
        head = frame.positions[frame.points(int(np.flatnonzero(frame.cyclic)[0]))]
        progress.append(float((head.mean(axis=0) - head_start) @ head_travel / (head_travel @ head_travel)))
        if t >= 0.5:  # the new stroke appears as drawn
            new = key_2.positions[key_2.points(NEW)]
            shown = [frame.positions[frame.points(i)] for i in range(len(frame)) if frame.sizes[i] == len(new)]
            assert any(np.allclose(points, new, atol=1e-5) for points in shown)
    assert np.all(np.diff(progress) > 0) and 0 < progress[0] and progress[-1] < 1  # the head travels steadily
    assert _self_crossing_strokes(layer, range(2, 9)) == []


def _self_crossing_strokes(layer, numbers):
    found = []
    for number in numbers:
        frame = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        found += [
            (number, i)
            for i in range(len(frame))
            if not is_simple(frame.positions[frame.points(i)][:, [0, 2]], bool(frame.cyclic[i]))
        ]
    return found


def test_blenders_own_interpolate_tangles_the_same_keys(face):
    """The contrast: index pairing, no loop alignment, surplus strokes dropped (design.md 7)."""
    layer = face.data.layers["Ink"]
    bpy.context.scene.frame_current = 1
    with gp_data.view3d_override():
        bpy.ops.object.mode_set(mode="EDIT")
        assert bpy.ops.grease_pencil.interpolate_sequence() == {"FINISHED"}
        bpy.ops.object.mode_set(mode="OBJECT")
    assert gp_data.frame_numbers(layer) == list(range(1, 10))
    assert {len(gp_data.read_strokes(gp_data.frame_at(layer, n).drawing)) for n in range(2, 9)} == {4}
    tangled = _self_crossing_strokes(layer, range(2, 9))
    assert tangled and {stroke for _, stroke in tangled} == {HEAD}  # the outline folds through itself
