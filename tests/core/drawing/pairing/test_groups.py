"""Issue 39 item 2: a stroke without an orientation of its own (a circle, a dot) rides the group
it lies in (the strokes inside the smallest loop around it), not the whole drawing: a tyre valve
on the wheel of a car that only translates stays on its arc while the wheel rolls."""

import numpy as np
import pytest
import scenes

import ballmorph_core as bm
from ballmorph_core.drawing.pairing.groups import ride_groups
from ballmorph_core.drawing.pairing.matching import match_strokes
from ballmorph_core.geometry.ragged import Ragged

#: Strokes of scenes.car_wheel: the body (0-2), the rim, the hub, eight spokes, the valve.
RIM, HUB, SPOKES, VALVE = 3, 4, range(5, 13), 13
#: The valve sits 0.92 of the wheel's radius (1) from the hub: the wheel's size is 2.
REACH, SIZE = 0.92, 2.0


def _matched(a, b, cyclic):
    A, B = Ragged.from_list(a, cyclic), Ragged.from_list(b, cyclic)
    m = match_strokes(A, B, A.closed, B.closed)
    return A, B, [(i, j, f) for i, j, f in m.pairs], m.drawing


@pytest.mark.parametrize("turn", [-30.0, -60.0, -90.0])
def test_the_wheel_is_a_group_turning_as_drawn_about_its_hub(turn):
    A, B, matched, drawing = _matched(*scenes.car_wheel(turn))
    groups = ride_groups(A, B, matched, drawing)
    assert abs(np.degrees(drawing.turn)) < 10  # the car does not turn: the drawing barely does
    assert sorted(groups.members) == [RIM, HUB, *SPOKES, VALVE]
    group = groups.members[VALVE]
    assert abs(np.degrees(group.motion.turn) - turn) <= 0.05, np.degrees(group.motion.turn)
    assert abs(group.motion.scale - 1.0) <= 1e-9 and group.loop == RIM
    np.testing.assert_allclose(group.pivot, [0.0, 0.0], atol=1e-9)
    # Every spoke paired with itself: the spokes turn with the wheel (at -60 the matching paired
    # seven of them a symmetry step off, each with its nearest neighbour; at -90 all eight).
    assert [groups.matched[k][:2] for k in SPOKES] == [(k, k) for k in SPOKES]
    assert groups.repaired == {-30.0: [], -60.0: [(RIM, 7)], -90.0: [(RIM, 8)]}[turn]


def test_a_symmetric_wheel_turns_as_its_valve_shows():
    """Eight equal spokes fit a turn every 45°: the valve says which (its turn about the hub)."""
    a, b, cyclic = scenes.car_wheel(-60.0)
    long = scenes.turned(a[5], 135.0, (0.0, 0.0))  # spoke 3 drawn as long as the others
    a[8], b[8] = long, scenes.turned(long, -60.0, (0.0, 0.0)) + (np.radians(60.0), 0.0)
    A, B, matched, drawing = _matched(a, b, cyclic)
    group = ride_groups(A, B, matched, drawing).members[VALVE]
    assert abs(np.degrees(group.motion.turn) + 60.0) <= 0.05


def test_a_group_turning_with_the_drawing_is_the_drawings():
    """The wheel alone: its motion is the drawing's, which riders ride already (no group: the
    frames of such drawings are unchanged)."""
    A, B, matched, drawing = _matched(*scenes.wheel(-30.0, 0.6))
    assert ride_groups(A, B, matched, drawing).members == {}


def test_no_group_where_no_loop_holds_a_rider():
    a, b, cyclic = scenes.car_wheel(-60.0)
    keep = [k for k in range(len(a)) if k not in (RIM, VALVE)]
    A, B, matched, drawing = _matched([a[k] for k in keep], [b[k] for k in keep], [cyclic[k] for k in keep])
    groups = ride_groups(A, B, matched, drawing)
    assert groups.members == {} and groups.matched == matched


@pytest.mark.parametrize("dot", [False, True], ids=["circle", "dot"])
@pytest.mark.parametrize("turn", [-30.0, -60.0, -90.0])
def test_a_valve_on_a_rolling_car_wheel_stays_on_its_arc(turn, dot):
    a, b, cyclic = scenes.car_wheel(turn, dot=dot)
    keys = scenes.key(a, cyclic), scenes.key(b, cyclic)
    result = bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), scenes.TIMES)
    worst = 0.0
    for frame in result.frames:
        hub, valve = (frame.positions[frame.points(i)][:, [0, 2]].mean(axis=0) for i in (HUB, VALVE))
        worst = max(worst, abs(float(np.linalg.norm(valve - hub)) - REACH) / SIZE)
    assert worst <= 0.005, f"wheel turning {turn}° on a car: the valve up to {worst:.3%} of the wheel off its arc"
    report = result.pairs[VALVE]
    assert "rode its group's motion (stroke 4 and the strokes inside it" in report.reason, report.reason
    assert not any("rode" in p.reason for p in result.pairs[:RIM])  # the body: its own motion


def test_a_pupil_glancing_across_a_round_eye_moves_straight():
    """Nothing in a round eye but its pupil shows a turn (the pupil's own move would fit a half
    turn about the eye's centre): no group, the pupil moves straight."""
    brow = scenes.bowed((-1.0, 1.3), (1.0, 1.3), 0.2, 20)
    a = [scenes.circle(1.0, (0.0, 0.0), 64), scenes.circle(0.2, (-0.6, 0.0), 24), brow]
    b = [scenes.circle(1.0, (0.0, 0.0), 64), scenes.circle(0.2, (0.6, 0.0), 24), brow]
    A, B, matched, drawing = _matched(a, b, [True, True, False])
    assert ride_groups(A, B, matched, drawing).members == {}
    keys = scenes.key(a, [True, True, False]), scenes.key(b, [True, True, False])
    middle = bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), [0.5]).frames[0]
    np.testing.assert_allclose(middle.positions[middle.points(1)][:, [0, 2]].mean(axis=0), [0.0, 0.0], atol=1e-6)


@pytest.mark.parametrize("turn", [-30.0, -60.0, -90.0])
def test_a_valve_drawn_a_little_further_round_stays_on_its_arc(turn):
    """The second key's valve drawn 6 degrees further round than the wheel turned: it turns by its
    own angle about the hub (within TURN_AGREE of the wheel's), not the wheel's (1.3% off at -60)."""
    a, b, cyclic = scenes.car_wheel(turn)
    b[VALVE] = scenes.turned(b[VALVE], -6.0, b[HUB].mean(axis=0))
    keys = scenes.key(a, cyclic), scenes.key(b, cyclic)
    result = bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), scenes.TIMES)
    worst = 0.0
    for frame in result.frames:
        hub, valve = (frame.positions[frame.points(i)][:, [0, 2]].mean(axis=0) for i in (HUB, VALVE))
        worst = max(worst, abs(float(np.linalg.norm(valve - hub)) - REACH) / SIZE)
    assert worst <= 1e-9, f"wheel turning {turn}°, valve 6° further: up to {worst:.3%} of the wheel off its arc"
