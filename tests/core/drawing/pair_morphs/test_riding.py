"""Issue 39 item 2: strokes without an orientation of their own (circles, dots) take the turn of
the drawing they ride on: a tyre valve on a turning wheel stays on its arc."""

import numpy as np
import pytest
import scenes

import ballmorph_core as bm
from ballmorph_core.geometry.orientation import orientation_free
from ballmorph_core.geometry.ragged import Ragged


def _frames(keys):
    a, b, cyclic = keys
    result = bm.inbetween(scenes.key(a, cyclic).stroke_set(), scenes.key(b, cyclic).stroke_set(), scenes.TIMES)
    return [scenes.key(a, cyclic), scenes.key(b, cyclic)], [scenes.as_drawing(f) for f in result.frames], result


@pytest.mark.parametrize("dot", [False, True], ids=["circle", "dot"])
@pytest.mark.parametrize(
    "turn, roll, valve_at, radius",
    [(-30.0, 0.6, 60.0, 1.0), (45.0, 1.0, 200.0, 1.5), (-20.0, 0.3, 120.0, 0.5), (-12.0, 0.9, 300.0, 2.0)],
    ids=["scene", "held-back-45", "held-back-20", "held-back-12"],
)
def test_a_valve_on_a_turning_wheel_stays_on_its_arc(turn, roll, valve_at, radius, dot):
    keys, frames, result = _frames(scenes.wheel(turn, roll, valve_at, radius, dot))
    figure = scenes.figure_riding(tuple(scenes.as_drawing(k) for k in keys), frames, scenes.TIMES)
    assert figure.ok, f"wheel turning {turn}°, valve at {valve_at}° ({'dot' if dot else 'circle'}): {figure}"
    # And on its arc: as far from the hub's centre as on the keys (0.92 of the radius).
    a, _, _ = scenes.wheel(turn, roll, valve_at, radius, dot)
    for t, frame in zip(scenes.TIMES, result.frames):
        hub, valve = (frame.positions[frame.points(i)][:, [0, 2]].mean(axis=0) for i in (1, len(a) - 1))
        off = abs(float(np.linalg.norm(valve - hub)) - 0.92 * radius) / (2 * radius)
        assert off <= 0.005, f"t={t}: valve {off:.2%} of the wheel off its arc about the hub"


def test_orientation_free_loops():
    shapes = {
        "circle": (scenes.circle(1.0, n=96), True, True),
        "16-gon": (scenes.circle(1.0, n=16), True, True),
        "wobbly circle": (scenes.circle(1.0, n=40) * (1 + 0.02 * np.sin(np.arange(40) * 2.3))[:, None], True, True),
        "ellipse 1.1 x 1": (scenes.circle(1.0, n=64, axes=(1.1, 1.0)), True, False),
        "hexagon": (scenes.circle(1.0, n=6), True, False),
        "square": (scenes.polyline([(0, 0), (1, 0), (1, 1), (0, 1)], 5, closed=True), True, False),
        "open arc": (scenes.circle(1.0, n=96)[:80], False, False),
    }
    P = Ragged.from_list([s for s, _, _ in shapes.values()], [c for _, c, _ in shapes.values()])
    got = dict(zip(shapes, orientation_free(P).tolist()))
    assert got == {name: want for name, (_, _, want) in shapes.items()}


def test_a_circle_on_a_drawing_turning_less_than_the_agreement_keeps_its_path():
    """Below TURN_AGREE (10°) the drawing does not count as turning: the valve moves as before
    (its own fit), so drawings that barely turn keep their frames."""
    a, b, cyclic = scenes.wheel(-6.0, 0.6)
    _, _, result = _frames((a, b, cyclic))
    t, frame = scenes.TIMES[3], result.frames[3]
    got = frame.positions[frame.points(len(a) - 1)][:, [0, 2]].mean(axis=0)
    straight = (1 - t) * a[-1].mean(axis=0) + t * b[-1].mean(axis=0)
    assert np.linalg.norm(got - straight) <= 1e-9


def test_dots_alone_show_no_turn_to_ride():
    """Two dots: their centroids fit a similarity exactly (here a
    27-degree turn growing 2.2 times), but nothing in the drawing turns, so the dot moves
    straight (Blender test: test_dots_and_zero_length_strokes_move_point_by_point)."""
    other_a = np.full((5, 2), 0.5)  # a stroke of five points in one place: a dot
    other_b = other_a + 1.0
    key_a = bm.StrokeSet.from_strokes([[[0.0, 0.0]], other_a])
    key_b = bm.StrokeSet.from_strokes([[[1.0, 0.0]], other_b])
    middle = bm.inbetween(key_a, key_b, [0.5], matching="index").frames[0]
    dot = middle.positions[middle.offsets[0] : middle.offsets[1]]
    np.testing.assert_allclose(dot[:, [0, 1]] if dot.shape[1] == 2 else dot[:, [0, 2]], [[0.5, 0.0]], atol=1e-9)


def test_circles_alone_show_no_turn_to_ride():
    """Circles only (no stroke shows a turn): their centroids fit the drawing a 40-degree turn,
    but no circle rides it, nor takes it as the prior of its own symmetric fit: each moves
    straight, its points matched where they lie (the guard sits where the riding happens,
    :meth:`Rides.of_pairs`; the drawing's scale is kept)."""
    a = [scenes.circle(0.2, (0.0, 0.0), 24), scenes.circle(0.2, (1.0, 0.0), 24)]
    b = [scenes.circle(0.2, (0.0, 0.0), 24), scenes.circle(0.2, (np.cos(0.7), np.sin(0.7)), 24)]
    keys = scenes.key(a, [True, True]), scenes.key(b, [True, True])
    middle = bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), [0.5]).frames[0]
    xy = middle.positions[middle.points(1)][:, [0, 2]]
    want = 0.5 * (a[1] + b[1])
    np.testing.assert_allclose(xy, want, atol=1e-9)
    assert all("rode" not in p.reason for p in bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), [0.5]).pairs)
