"""Arcs through keys (issue 39): a ball keyed on an arc at frames 1, 7, 13, all selected."""

import bpy
import gp_data
import numpy as np
import pytest
from conftest import MODULE

KEYS = (1, 7, 13)
RADIUS = 5.0  # the arc's: keys 20 degrees apart, so a frame turns 3.33 degrees along it
DEGREES = (110.0, 90.0, 70.0)
#: Every in-between's centre within this fraction of the path's size from the arc.
ON_ARC = 0.01
#: The steps into and out of the middle key: lengths within 10%, directions within 5 degrees.
STEP_RATIO, STEP_TURN = 0.10, 5.0


def ball_on_an_arc(selected=KEYS, extreme=(), degrees=DEGREES, radius=RADIUS):
    """A ball (a loop of radius 0.2) keyed on a circular arc at frames 1, 7, 13 of layer 'Ink'."""
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    for number, angle in zip(KEYS, np.radians(degrees)):
        centre = (radius * np.cos(angle), radius * np.sin(angle))
        frame = gp_data.add_key(layer, number, [gp_data.loop(0.2, n=40, centre=centre)], cyclic=[True])
        frame.select = number in selected
        if number in extreme:
            frame.keyframe_type = "EXTREME"
    bpy.context.scene.frame_current = 1
    return obj


def centres(obj):
    """The ball's centre (x, z) on frames 1 to 13, shape (13, 2)."""
    layer = obj.data.layers["Ink"]
    out = []
    for number in range(KEYS[0], KEYS[-1] + 1):
        positions = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing).positions
        out.append(positions.mean(axis=0)[[0, 2]])
    return np.array(out)


def figures(c):
    """(largest distance off the arc / path size, step ratio at frame 7, turn there in degrees)."""
    size = float(np.ptp(c[[0, 6, 12]], axis=0).max())
    off = float(np.abs(np.hypot(c[:, 0], c[:, 1]) - RADIUS).max()) / size
    before, after = c[6] - c[5], c[7] - c[6]
    ratio = float(np.linalg.norm(after) / np.linalg.norm(before))
    turn = float(np.degrees(np.arccos(np.clip(before @ after / np.linalg.norm(before) / np.linalg.norm(after), -1, 1))))
    return off, ratio, turn


def frames_bytes(obj):
    """Every frame's raw attributes (bytes), by frame number."""
    layer = obj.data.layers["Ink"]
    return {f.frame_number: gp_data.read_raw(f.drawing) for f in layer.frames}


def run(capfd, **options):
    capfd.readouterr()
    result = bpy.ops.ballmorph.inbetween(**options)
    out, err = capfd.readouterr()
    return result, out + err


def test_smooth_runs_the_ball_on_the_arc_with_no_corner_at_the_middle_key(addon, capfd):
    obj = ball_on_an_arc()
    result, said = run(capfd)  # Smooth is the default
    assert result == {"FINISHED"}, said
    off, ratio, turn = figures(centres(obj))
    message = f"off the arc {off:.3%} of the path, step ratio {ratio:.3f}, turn {turn:.2f} degrees at frame 7"
    assert off < ON_ARC and abs(ratio - 1) < STEP_RATIO and turn < STEP_TURN, message
    assert "joined smoothly at frame 7" in said, said


def _one_sided_velocities(c, k):
    """Second-order one-sided velocity estimates at frame index ``k`` from before and after."""
    return 1.5 * c[k] - 2.0 * c[k - 1] + 0.5 * c[k - 2], -1.5 * c[k] + 2.0 * c[k + 1] - 0.5 * c[k + 2]


@pytest.mark.parametrize("key_motion", ["SMOOTH", "PER_INTERVAL"])
def test_a_wide_arc_runs_on_the_smooth_curve_through_the_keys(addon, capfd, key_motion):
    # The geometry: 120 degrees of arc over 12 frames (10 degrees a frame, so single
    # frame steps turn as much on any smooth curve): chords 7.7% of the path off the arc. The
    # smooth curve through the keys' centres is the one Smooth builds for three keys: each
    # centre's parabola in time through them; velocities from both sides to second order.
    obj = ball_on_an_arc(degrees=(150.0, 90.0, 30.0), radius=2.0)
    assert run(capfd, key_motion=key_motion)[0] == {"FINISHED"}
    c = centres(obj)
    frames = np.arange(13.0)
    keyed = c[[0, 6, 12]]
    weights = np.stack([np.prod([(frames - b) / (a - b) for b in (0, 6, 12) if b != a], axis=0) for a in (0, 6, 12)])
    curve = weights.T @ keyed  # the parabola through the keyed centres, frame by frame
    size = float(np.ptp(keyed, axis=0).max())
    off_curve = float(np.linalg.norm(c - curve, axis=1).max()) / size
    off_circle = float(np.abs(np.hypot(c[:, 0], c[:, 1]) - 2.0).max()) / size
    before, after = _one_sided_velocities(c, 6)
    ratio = float(np.linalg.norm(after) / np.linalg.norm(before))
    turn = float(np.degrees(np.arccos(before @ after / np.linalg.norm(before) / np.linalg.norm(after))))
    message = (
        f"{key_motion}: {off_curve:.3%} of the path off the smooth curve ({off_circle:.2%} off the circle); "
        f"velocity at frame 7 from both sides: ratio {ratio:.3f}, {turn:.2f} degrees apart"
    )
    if key_motion == "SMOOTH":
        assert off_curve < ON_ARC and abs(ratio - 1) < STEP_RATIO and turn < STEP_TURN, message
    else:
        assert off_curve > 0.05 and turn > 50.0, message


def test_timing_still_applies_per_interval_on_the_smooth_path(addon, capfd):
    obj = ball_on_an_arc()
    options = {"easing_type": "QUAD", "easing": "EASE_IN_OUT", "favor": 0.3, "key_motion": "SMOOTH"}
    assert run(capfd, **options)[0] == {"FINISHED"}
    c = centres(obj)
    off = figures(c)[0]
    steps = np.linalg.norm(np.diff(c, axis=0), axis=1)
    # Eased in and out of every key: the first and last steps of each interval are the shortest.
    message = f"off the arc {off:.3%} of the path; steps {np.round(steps, 4).tolist()}"
    assert off < ON_ARC and steps[0] < steps[2] and steps[5] < steps[3] and steps[6] < steps[8], message


def test_per_interval_is_each_interval_alone_bit_for_bit_with_its_corner(addon, capfd):
    alone = {}
    for pair in ((1, 7), (7, 13)):
        obj = ball_on_an_arc(selected=pair)
        assert run(capfd)[0] == {"FINISHED"}
        alone.update({n: raw for n, raw in frames_bytes(obj).items() if pair[0] < n < pair[1]})
        bpy.data.objects.remove(obj)
    obj = ball_on_an_arc()
    assert run(capfd, key_motion="PER_INTERVAL")[0] == {"FINISHED"}
    together = frames_bytes(obj)
    assert sorted(alone) == [n for n in together if n not in KEYS]
    different = [n for n in alone if together[n] != alone[n]]
    assert not different, f"frames {different} differ from each interval run alone"
    off, ratio, turn = figures(centres(obj))
    assert off > 0.02 and turn > 19.0, f"chords: off the arc {off:.3%}, turn {turn:.2f} degrees at frame 7"


def test_a_key_typed_extreme_keeps_its_corner(addon, capfd):
    per_interval = ball_on_an_arc()
    assert run(capfd, key_motion="PER_INTERVAL")[0] == {"FINISHED"}
    expected = frames_bytes(per_interval)
    bpy.data.objects.remove(per_interval)
    obj = ball_on_an_arc(extreme=(7,))
    result, said = run(capfd, key_motion="SMOOTH")  # (the scene keeps the last run's options)
    assert result == {"FINISHED"}
    got = frames_bytes(obj)
    different = [n for n in expected if n != 7 and got[n] != expected[n]]
    assert not different, f"frames {different} differ from Per Interval"
    turn = figures(centres(obj))[2]
    assert turn > 19.0 and "the Extreme key at frame 7 keeps its corner" in said, f"turn {turn:.2f}: {said}"


def test_an_interval_that_cannot_be_made_leaves_the_other_as_it_is(addon, capfd):
    alone = ball_on_an_arc(selected=(1, 7))
    assert run(capfd)[0] == {"FINISHED"}
    expected = {n: raw for n, raw in frames_bytes(alone).items() if n < 7}
    bpy.data.objects.remove(alone)
    obj = ball_on_an_arc()
    drawing = gp_data.frame_at(obj.data.layers["Ink"], 13).drawing
    positions = drawing.attributes["position"].data
    broken = np.zeros(3 * len(positions), np.float32)
    positions.foreach_get("vector", broken)
    broken[5] = np.nan
    positions.foreach_set("vector", broken)
    result, said = run(capfd)
    got = frames_bytes(obj)
    assert result == {"FINISHED"} and "key on frame 13 has points with invalid" in said, said
    assert sorted(got) == [1, 2, 3, 4, 5, 6, 7, 13], sorted(got)  # nothing between 7 and 13
    assert all(got[n] == expected[n] for n in expected), "the interval 1-7 is not what it is alone"


def test_a_failure_to_join_keeps_every_interval(addon, capfd, monkeypatch):
    import importlib

    service = importlib.import_module(f"{MODULE}.operators.service")

    def broken(*args, **kwargs):
        raise RuntimeError("no arcs today")

    monkeypatch.setattr(service, "chain_corrections", broken)
    obj = ball_on_an_arc()
    result, said = run(capfd)
    assert result == {"FINISHED"} and "no arcs today" in said, said
    turn = figures(centres(obj))[2]
    assert turn > 19.0, f"every interval on its own: turn {turn:.2f} at frame 7"


@pytest.mark.parametrize("key_motion", ["SMOOTH", "PER_INTERVAL"])
def test_two_keys_are_the_same_either_way(addon, capfd, key_motion):
    obj = ball_on_an_arc(selected=(1, 7))
    assert run(capfd, key_motion=key_motion)[0] == {"FINISHED"}
    raw = frames_bytes(obj)
    bpy.data.objects.remove(obj)
    other = ball_on_an_arc(selected=(1, 7))
    assert run(capfd, key_motion="PER_INTERVAL")[0] == {"FINISHED"}
    assert frames_bytes(other) == raw


@pytest.mark.parametrize(("key_motion", "corner"), [("smooth", False), ("per-interval", True)])
def test_the_command_line_takes_the_same_option(addon, tmp_path, key_motion, corner):
    import importlib

    ball_on_an_arc(selected=())  # the command line in-betweens every key pair
    source, output = tmp_path / "arc.blend", tmp_path / "out.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(source))
    cli = importlib.import_module(f"{MODULE}.cli")
    assert cli.main([str(source), "--output", str(output), "--key-motion", key_motion]) == 0
    bpy.ops.wm.open_mainfile(filepath=str(output))
    off, ratio, turn = figures(centres(bpy.data.objects["Drawing"]))
    message = f"{key_motion}: off the arc {off:.3%}, step ratio {ratio:.3f}, turn {turn:.2f} degrees at frame 7"
    assert (turn > 19.0) if corner else (off < ON_ARC and turn < STEP_TURN), message


@pytest.mark.parametrize(
    ("key_motion", "extreme"),
    [("SMOOTH", ()), ("PER_INTERVAL", ()), ("SMOOTH", (7,))],
    ids=["smooth", "per-interval", "extreme"],
)
def test_the_path_preview_shows_the_paths_the_frames_follow(addon, key_motion, extreme):
    import importlib

    cache = importlib.import_module(f"{MODULE}.operators.preview").PREVIEW
    cache.clear()
    obj = ball_on_an_arc(selected=(), extreme=extreme)
    bpy.context.scene.ballmorph_inbetween.key_motion = key_motion
    tracks = []
    for frame in (3, 9):  # the playhead in each interval
        bpy.context.scene.frame_current = frame
        tracks.append(cache.world(bpy.context).points.mean(axis=0)[:, [0, 2]])  # the ball's centre
    preview = np.concatenate(tracks)
    size = float(np.ptp(preview, axis=0).max())
    off = float(np.abs(np.hypot(preview[:, 0], preview[:, 1]) - RADIUS).max()) / size
    # The frames the operator writes with the same option lie on the previewed paths.
    for number in KEYS:
        gp_data.frame_at(obj.data.layers["Ink"], number).select = True
    assert bpy.ops.ballmorph.inbetween(key_motion=key_motion) == {"FINISHED"}
    # Preview times k / 16, frames k / 6 of each interval: they meet at the keys and halfway.
    written = centres(obj)[[0, 3, 6, 9, 12]]
    gap = float(np.abs(written - preview[[0, 8, 16, 25, 33]]).max()) / size
    message = f"{key_motion}: preview {off:.3%} of the path off the arc; written frames {gap:.2e} from the preview"
    arc = key_motion == "SMOOTH" and not extreme
    assert ((off < ON_ARC) if arc else (off > 0.02)) and gap < 1e-6, f"{message} (Extreme: {extreme})"
