"""Issues 11 and 12: the scenes of tests/fixtures/scenes/ through the core, every figure asserted.

A scene today's core misses is ``xfail(strict=True)`` with the figures it misses today
(``scenes.XFAIL_TODAY``): main stays green, and the marker must go once the core meets them.
The second half tests the figures themselves on frames whose answer is known, so a figure that
cannot fail (or measures the wrong thing) is caught.
"""

import numpy as np
import pytest
import scenes
from scenes import Stroke


def _params():
    for name, scene in scenes.SCENES.items():
        reason = scenes.XFAIL_TODAY.get(name)
        marks = [pytest.mark.xfail(strict=True, raises=AssertionError, reason=reason)] if reason else []
        yield pytest.param(scene, id=name, marks=marks)


@pytest.mark.parametrize("scene", list(_params()))
def test_scene_meets_every_figure(scene):
    frames, result = scene.run_core()
    assert len(frames) == len(scene.times)
    figures = scene.figures(scene.key_drawings(), frames)
    missed = [str(f) for f in figures if not (f.ok or f.informative)]
    assert not missed, f"{scene.name} ({scene.about}): " + "; ".join(missed)


def test_every_xfail_names_a_scene():
    assert set(scenes.XFAIL_TODAY) <= set(scenes.SCENES)


@pytest.mark.parametrize("name", [n for n, s in scenes.SCENES.items() if scenes.figure_unpaired in s.measures])
def test_the_pairing_figure_sees_what_the_core_reports(name):
    """The geometric pairing figure counts exactly the strokes the core reports without a partner."""
    scene = scenes.SCENES[name]
    frames, result = scene.run_core()
    reported = sum(p.method in ("appear", "disappear", "hold") for p in result.pairs)
    assert scenes.figure_unpaired(scene.key_drawings(), frames, scene.times).value == reported


def test_scene_names_and_keys_are_sound():
    for scene in scenes.SCENES.values():
        assert scene.issue in (11, 12, 39) and scene.about
        for k in scene.keys:
            assert len(k.strokes) == len(k.cyclic)
            assert all(np.asarray(s).ndim == 2 and np.asarray(s).shape[1] == 2 for s in k.strokes)
        a, b = scene.key_drawings()
        if scenes.figure_new_crossings in scene.measures:  # "no new crossings" assumes simple keys
            for s in (*a, *b):
                assert scenes.segment_crossings(s.xy, s.cyclic) == 0, scene.name


def test_head_has_35_strokes_shuffled_and_some_drawn_the_other_way():
    a, b = scenes.SCENES["head-35-shuffled"].keys
    ordered = scenes.SCENES["head-35-ordered"].keys[1]
    assert len(a.strokes) == len(b.strokes) == 35
    lengths = [round(scenes.polyline_length(s, c), 9) for s, c in zip(ordered.strokes, ordered.cyclic)]
    shuffled = [round(scenes.polyline_length(s, c), 9) for s, c in zip(b.strokes, b.cyclic)]
    assert sorted(lengths) == sorted(shuffled) and lengths != shuffled
    starts = {tuple(np.round(s[0], 9)) for s in ordered.strokes}
    assert sum(tuple(np.round(s[0], 9)) not in starts for s in b.strokes) >= 10


def test_float32_twins_differ_only_by_rounding():
    f64, f32 = scenes.SCENES["turn+90-centre-f64"].keys[1], scenes.SCENES["turn+90-centre-f32"].keys[1]
    d = np.abs(f64.strokes[0] - f32.strokes[0]).max()
    assert 0 < d < 1e-6
    np.testing.assert_array_equal(f32.strokes[0], f32.strokes[0].astype(np.float32))


# ------------------------------------------------------------------ the figures on known frames


def _frames(drawing, n=7):
    return [drawing] * n


def _moved(drawing, f):
    return tuple(Stroke(f(s.xy), s.cyclic) for s in drawing)


def test_middle_chord_reports_the_turn_it_is_fed():
    scene = scenes.SCENES["turn+120-centre-f64"]
    keys = scene.key_drawings()
    pivot = keys[0][0].xy.mean(axis=0)
    for turn in (30.0, -30.0, 60.0):
        frames = _frames(_moved(keys[0], lambda xy, turn=turn: scenes.turned(xy, turn, pivot)))
        figure = scenes.figure_middle_chord(keys, frames, scene.times, angle=120.0)
        assert figure.value == pytest.approx(turn, abs=1e-9)
        assert figure.ok == (turn == 60.0)
        assert str(figure) == f"middle chord turned {turn:+.1f}° (goal +60.0 ± 5°)"


def test_length_reversal_and_the_ideal_turn():
    scene = scenes.SCENES["turn+170-centre-f64"]
    keys = scene.key_drawings()
    pivot = keys[0][0].xy.mean(axis=0)
    ideal = [_moved(keys[0], lambda xy, t=t: scenes.turned(xy, 170 * t, pivot)) for t in scene.times]
    assert all(f.ok for f in scene.figures(keys, ideal))
    reversed_ = [tuple(Stroke(s.xy[::-1], s.cyclic) for s in f) for f in ideal]
    assert scenes.figure_not_reversed(keys, reversed_, scene.times, pivot, 170.0).value == 7
    stretched = [_moved(f, lambda xy: (xy - pivot) * 1.1 + pivot) for f in ideal]
    assert scenes.figure_length_kept(keys, stretched, scene.times).value == pytest.approx(0.1)


def test_arm_figures_see_a_drifting_shoulder_and_a_hand_left_behind():
    scene = scenes.SCENES["arm-swing"]
    keys = scene.key_drawings()
    ideal = [_moved(keys[0], lambda xy, t=t: scenes.turned(xy, 120 * t, (0, 0))) for t in scene.times]
    assert all(f.ok for f in scene.figures(keys, ideal))
    length = keys[0][0].length
    drifted = [(Stroke(f[0].xy + (0.05 * length, 0), False), *f[1:]) for f in ideal]
    assert scenes.figure_fixed_end(keys, drifted, scene.times, np.zeros(2)).value == pytest.approx(0.05)
    left_behind = [(f[0], keys[0][1]) for f in ideal]  # the hand held on key A while the arm swings
    figure = scenes.figure_attached(keys, left_behind, scene.times, np.zeros(2))
    assert not figure.ok and figure.value > 0.5


def test_best_rotation_whatever_the_sampling_and_start():
    leaf = scenes.leaf()
    for turn in (30.0, -100.0, 170.0):
        other = np.roll(scenes.resample(scenes.turned(leaf, turn, (0.3, 0.2)) * 1.2, True, 57), 20, axis=0)
        assert scenes.best_rotation(leaf, other, True) == pytest.approx(turn, abs=1.0)
    scene = scenes.SCENES["leaf-turn"]
    keys = scene.key_drawings()
    frames = _frames(_moved(keys[0], lambda xy: scenes.turned(xy, 30.0, (0, 0))))
    assert scenes.figure_middle_rotation(keys, frames, scene.times, 120.0).value == pytest.approx(30.0, abs=1.0)
    bigger = _frames(_moved(keys[0], lambda xy: xy * 1.05))
    assert scenes.figure_area_kept(keys, bigger, scene.times).value == pytest.approx(0.1025)


def test_unpaired_counts_held_and_missing_strokes():
    scene = scenes.SCENES["ball-2.7x-in-drawing"]
    keys = scene.key_drawings()
    moving = [_moved(keys[0], lambda xy, t=t: xy + (t, 0)) for t in scene.times]
    assert scenes.figure_unpaired(keys, moving, scene.times).value == 0
    popping = [f[:1] + (keys[0][1] if t < 0.5 else keys[1][1],) + f[2:] for f, t in zip(moving, scene.times)]
    assert scenes.figure_unpaired(keys, popping, scene.times).value == 2
    dropped = [f[:-1] for f in moving]
    assert scenes.figure_unpaired(keys, dropped, scene.times).value == 1


def test_radial_figure_passes_a_sliding_outline_and_fails_a_rotating_one():
    scene = scenes.SCENES["outline-start-moved"]
    keys = scene.key_drawings()
    profiles = (
        lambda th: scenes.outline_profile(0.08, 0.0, th),
        lambda th: scenes.outline_profile(0.1, 0.02, th),
    )

    def at(t):
        return lambda th: (1 - t) * profiles[0](th) + t * profiles[1](th)

    sliding = [(Stroke(scenes.polar(at(t), 100 * t, 330, 110), False),) for t in scene.times]
    assert scenes.figure_radial(keys, sliding, scene.times, profiles, 0.02).value < 1e-12
    rotating = [_moved(keys[0], lambda xy, t=t: scenes.turned(xy, 100 * t, (0, 0))) for t in scene.times]
    assert not scenes.figure_radial(keys, rotating, scene.times, profiles, 0.02).ok


def test_circle_figures():
    scene = scenes.SCENES["ball-grow-2x"]
    keys = scene.key_drawings()
    ts = scene.times
    even = [(Stroke(scenes.circle(0.5 + 0.5 * t, (3 * t, 0)), True),) for t in ts]
    assert scenes.figure_even_steps(keys, even, ts).value == pytest.approx(1.0)
    assert scenes.figure_middle_radius(keys, even, ts).value == pytest.approx(0.75)
    spiral = [(Stroke(scenes.circle(0.5 * 2**t, (3 * (2**t - 1), 0)), True),) for t in ts]
    assert scenes.figure_even_steps(keys, spiral, ts).value == pytest.approx(2 ** (7 / 8))
    assert scenes.figure_middle_radius(keys, spiral, ts).value == pytest.approx(np.sqrt(0.5))
    gap = scenes.SCENES["open-circle-gap"]
    bulged = [(Stroke(scenes.polar(lambda th: 1.02 + 0 * th, 10, 330, 90), False),)] * 7
    assert scenes.figure_on_circle(gap.key_drawings(), bulged, ts).value == pytest.approx(0.02)


def test_ellipse_fit_and_distance():
    rng = np.random.default_rng(3)
    t = np.sort(rng.uniform(0, 2 * np.pi, 70))  # uneven sampling
    xy = scenes.turned(np.c_[1.4 * np.cos(t), 0.6 * np.sin(t)], 25.0, (0, 0)) + (2.0, -1.0)
    conic = scenes.fit_ellipse(xy)
    assert scenes.ellipse_distance(xy, conic).max() < 1e-9
    off = np.array([2.0, -1.0]) + 1.41 * np.array([np.cos(np.radians(25)), np.sin(np.radians(25))])
    assert scenes.ellipse_distance([off], conic)[0] == pytest.approx(0.01, rel=1e-2)  # first order in the distance
    scene = scenes.SCENES["circle-to-ellipse"]
    keys = scene.key_drawings()
    exact = [(Stroke(scenes.circle(1.0, n=50, axes=(1 + 0.3 * t, 1 - 0.25 * t)), True),) for t in scene.times]
    assert scenes.figure_ellipse(keys, exact, scene.times).value < 1e-9
    square = scenes.polar(lambda th: 1 / np.maximum(abs(np.cos(th)), abs(np.sin(th))) ** 0.3, 0, 360, 80, False)
    assert not scenes.figure_ellipse(keys, [(Stroke(square, True),)] * 7, scene.times).ok


def test_crossing_counts():
    t = np.linspace(0, 2 * np.pi, 80, endpoint=False) + 0.01  # the crossing falls inside segments
    eight = np.c_[np.sin(t), np.sin(t) * np.cos(t)]
    assert scenes.segment_crossings(eight, True) == 1
    assert scenes.segment_crossings(np.roll(eight, 10, axis=0)[:60], False) == 1  # both passes through 0
    assert scenes.segment_crossings(np.roll(eight, 10, axis=0)[:40], False) == 0  # one pass only
    assert scenes.segment_crossings(scenes.circle(1.0), True) == 0
    assert scenes.segment_crossings(scenes.polyline(scenes.HOUSE, 3, closed=True), True) == 0
    keys = (scenes.key([scenes.circle(1.0)], True),) * 2
    keys = tuple(scenes.as_drawing(k) for k in keys)
    frames = [(Stroke(eight, True), Stroke(scenes.circle(1.0), True))] * 3 + [keys[0]] * 4
    figure = scenes.figure_new_crossings(keys, frames, scenes.TIMES)
    assert (figure.value, figure.ok) == (3, False)
    assert scenes.figure_crossings_at(keys, frames, scenes.TIMES, t=0.375).value == 1


def test_stray_ink_sees_a_stroke_that_crosses_the_drawing():
    scene = scenes.SCENES["head-35-ordered"]
    keys = scene.key_drawings()
    ideal = [_moved(keys[0], scenes.rigid_at(*scenes.HEAD_MOTION, t)) for t in scene.times]
    assert scenes.figure_head_stray(keys, ideal, scene.times).value < 0.03
    wrong = [f[:1] + (Stroke(f[1].xy + (0.0, -0.5), f[1].cyclic),) + f[2:] for f in ideal]
    assert scenes.figure_head_stray(keys, wrong, scene.times).value > 0.1


def test_star_measures():
    outer, inner, sharpness = scenes.star_measures(scenes.star(1.0, 0.45))
    assert (outer, inner) == (pytest.approx(1.0, abs=1e-3), pytest.approx(0.45, abs=1e-3))
    assert scenes.star_measures(scenes.circle(1.0, n=720))[2] == pytest.approx(7.2, abs=0.5)  # 2% of 360°
    assert sharpness > 60
    scene = scenes.SCENES["star-pinch"]
    keys = scene.key_drawings()
    pinched = [_moved(keys[0], lambda xy: xy * 1.2)] * 7
    assert not scenes.figure_star(keys, pinched, scene.times, 0, 0.05).ok


def test_identity_is_bit_for_bit_in_float32():
    scene = scenes.SCENES["identical-house"]
    keys = scene.key_drawings()
    assert scenes.figure_identical(keys, _frames(keys[0]), scene.times).value == 0
    nudged = _frames((Stroke(np.nextafter(keys[0][0].xy.astype(np.float32), np.float32(9)).astype(float), True),))
    assert scenes.figure_identical(keys, nudged, scene.times).value == 7
    resampled = _frames((Stroke(scenes.resample(keys[0][0].xy, True, 20), True),))
    figure = scenes.figure_identical(keys, resampled, scene.times)
    assert figure.value == 7 and "point counts [20] (key [5])" in figure.shown


@pytest.mark.parametrize("kind", ["translate", "rotate", "scale"])
def test_similarity_figures(kind):
    scene = scenes.SCENES[f"similarity-{kind}"]
    keys = scene.key_drawings()
    ideal = [_moved(keys[0], scenes.similarity_at(keys, t)) for t in scene.times]
    assert [f.value < 1e-12 for f in scene.figures(keys, ideal)] == [True, True]
    shuffled = [f[::-1] for f in ideal]  # stroke order is not part of the figure
    assert all(f.ok for f in scene.figures(keys, shuffled))
    bent = [f[:2] + (Stroke(f[2].xy + (0, 1e-3), False),) + f[3:] for f in ideal]
    assert not any(f.ok for f in scene.figures(keys, bent))


def test_similarity_figure_tells_timing_from_shape():
    scene = scenes.SCENES["similarity-scale"]
    keys = scene.key_drawings()
    geometric = [_moved(keys[0], lambda xy, t=t: (xy - (0.5, 0.2)) * 1.6**t + (0.5, 0.2)) for t in scene.times]
    timing, shape = scene.figures(keys, geometric)
    assert not timing.ok and shape.ok


def test_corners_figure():
    scene = scenes.SCENES["corners-zigzag"]
    keys = scene.key_drawings()
    dense = [(Stroke(scenes.polyline(scenes.ZIGZAG, 8), False),)] * 7  # the key's corners, more points
    assert scenes.figure_corners(keys, dense, scene.times).ok
    assert scenes.off_straight(scenes.polyline(scenes.HOUSE, 4, closed=True), True) == (5, pytest.approx(0, abs=1e-15))
    chaikin = np.asarray(scenes.ZIGZAG, float)
    chaikin = np.vstack([chaikin[:1], (0.75 * chaikin[:-1] + 0.25 * chaikin[1:]), chaikin[-1:]])
    rounded = scenes.resample(chaikin, False, 60)
    assert not scenes.figure_corners(keys, [(Stroke(rounded, False),)] * 7, scene.times).ok
    assert scenes.figure_point_counts(keys, dense, scene.times).value == pytest.approx(65 / 41)


def test_ink_figures():
    scene = scenes.SCENES["split-1-to-2"]
    keys = scene.key_drawings()
    blended = [(Stroke(np.array([[0.0, 0.0], [4 - 0.2 * t, 0.0]]), False),) for t in scene.times]
    assert [f.ok for f in scene.figures(keys, blended)] == [True, True]
    popping = [keys[0] if t < 0.5 else keys[1][:1] for t in scene.times]
    blend, jump = scene.figures(keys, popping)
    assert not blend.ok and jump.value == pytest.approx(2.1)


def test_baseline_pairs_by_index_and_lerps_arc_length_samples():
    a = (Stroke(np.array([[0.0, 0], [1, 0], [3, 0]]), False), Stroke(scenes.circle(1.0, n=4), True))
    b = (Stroke(np.array([[0.0, 2], [3, 2]]), False),)
    frames = scenes.baseline_inbetween(a, b, [0.0, 0.5, 1.0])
    assert [len(f) for f in frames] == [1, 1, 1]  # the surplus stroke is dropped
    np.testing.assert_allclose(frames[0][0].xy, [[0, 0], [1.5, 0], [3, 0]])
    np.testing.assert_allclose(frames[1][0].xy, [[0, 1], [1.5, 1], [3, 1]])
    loop = scenes.baseline_inbetween(a[1:], a[1:], [0.5])[0][0]
    np.testing.assert_allclose(loop.xy, scenes.circle(1.0, n=4), atol=1e-12)


def test_the_shapes_are_what_they_say():
    hook = scenes.arch_with_hook()
    assert scenes.polyline_length(hook) == pytest.approx(2.8, rel=1e-3)
    assert not np.allclose(hook, scenes.turned(hook[::-1], 180, hook.mean(axis=0)), atol=0.05)  # not symmetric
    assert scenes.chord_angle([[0, 0], [0, 1]]) == 90.0
    assert scenes.wrap_degrees(270.0) == -90.0 and scenes.wrap_degrees(-180.0) == 180.0
    assert scenes.signed_area(scenes.circle(1.0, n=400)) == pytest.approx(np.pi, rel=1e-3)
    centre, radius = scenes.fit_circle(scenes.circle(0.7, (1, 2), 9))
    np.testing.assert_allclose([*centre, radius], [1, 2, 0.7])
    a, b = scenes.fit_similarity(hook, scenes.turned(hook, 30, (0, 0)) * 2)
    assert (abs(a), np.degrees(np.angle(a))) == (pytest.approx(2), pytest.approx(30))
    assert scenes.distance_to_polyline([[0.5, 1.0], [3.0, 0.0]], [[0, 0], [1, 0]], False) == pytest.approx([1.0, 2.0])


def test_travel_figure_sees_a_stroke_held_then_popping():
    scene = scenes.SCENES["thrown-ball"]
    keys = scene.key_drawings()
    blend = [tuple(Stroke((1 - t) * a.xy + t * b.xy, a.cyclic) for a, b in zip(*keys)) for t in scene.times]
    assert scenes.figure_travel(keys, blend, scene.times, 3).ok
    popping = [keys[0] if t < 0.5 else keys[1] for t in scene.times]
    figure = scenes.figure_travel(keys, popping, scene.times, 3)
    assert not figure.ok and figure.value > 0.1, figure
