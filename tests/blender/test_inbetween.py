"""ballmorph.inbetween on real Grease Pencil data: frames, strokes, attributes, options, errors."""

import importlib

import bpy
import gp_data
import numpy as np
import pytest

import ballmorph_core as bm
from ballmorph_core import ease, frame_times


def run(capfd, **options):
    """Run the operator; return its result and everything it reported."""
    capfd.readouterr()
    result = bpy.ops.ballmorph.inbetween(**options)
    out, err = capfd.readouterr()
    return result, out + err


def ink(obj):
    return obj.data.layers["Ink"]


def test_fills_every_frame_between_the_keys_with_breakdowns(shot, capfd):
    result, text = run(capfd)
    assert result == {"FINISHED"}
    layer = ink(shot)
    assert gp_data.frame_numbers(layer) == list(range(1, 10))
    types = {f.frame_number: f.keyframe_type for f in layer.frames}
    assert all(types[n] == "BREAKDOWN" for n in range(2, 9))
    assert types[1] == types[9] == "KEYFRAME"
    assert "7 in-between(s) on frame(s) 2\u20138" in text


@pytest.mark.parametrize(("count", "expected"), [(1, [5]), (3, [3, 5, 7]), (50, list(range(2, 9)))])
def test_frame_count_spreads_in_betweens_evenly(shot, count, expected):
    assert bpy.ops.ballmorph.inbetween(frame_count=count) == {"FINISHED"}
    made = [f.frame_number for f in ink(shot).frames if f.keyframe_type == "BREAKDOWN"]
    assert made == expected


@pytest.mark.parametrize(
    ("method", "easing_type", "easing"),
    [
        ("CIRCULAR_BALL", "LINEAR", "EASE_IN"),
        ("LINEAR_BALL", "QUAD", "EASE_IN_OUT"),
        ("PARABOLIC_BALL", "SINE", "AUTO"),
    ],
)
def test_strokes_equal_the_core_output_for_the_same_keys(shot, method, easing_type, easing):
    layer = ink(shot)
    key_a = gp_data.read_strokes(gp_data.frame_at(layer, 1).drawing)
    key_b = gp_data.read_strokes(gp_data.frame_at(layer, 9).drawing)
    frames, fractions = frame_times(1, 9, 3)
    expected = bm.inbetween(
        key_a, key_b, ease(fractions, easing_type, easing), method=method.lower().replace("_", "-")
    ).frames

    assert bpy.ops.ballmorph.inbetween(method=method, frame_count=3, easing_type=easing_type, easing=easing) == {
        "FINISHED"
    }
    for number, want in zip(frames, expected):
        got = gp_data.read_strokes(gp_data.frame_at(layer, int(number)).drawing)
        np.testing.assert_array_equal(got.offsets, want.offsets)
        np.testing.assert_allclose(got.positions, want.positions, rtol=0, atol=1e-6)
        np.testing.assert_allclose(got.radius, want.radius, rtol=1e-6)
        np.testing.assert_allclose(got.opacity, want.opacity, rtol=1e-6)
        np.testing.assert_allclose(got.vertex_color, want.vertex_color, rtol=1e-6, atol=1e-7)
        np.testing.assert_array_equal(got.cyclic, want.cyclic)
        np.testing.assert_array_equal(got.material_index, want.material_index)


def test_radius_and_opacity_are_interpolated(addon):
    obj = gp_data.new_object()
    layer = ink(obj)
    stroke = gp_data.arc(0.4)
    n = len(stroke)
    gp_data.add_key(layer, 1, [stroke], radius=np.full(n, 0.02), opacity=np.full(n, 0.2))
    gp_data.add_key(layer, 5, [stroke + [0, 0.1]], radius=np.full(n, 0.06), opacity=np.full(n, 1.0))
    bpy.context.scene.frame_current = 1
    assert bpy.ops.ballmorph.inbetween(method="LINEAR_BALL", easing_type="LINEAR") == {"FINISHED"}
    for number, t in ((2, 0.25), (3, 0.5), (4, 0.75)):
        got = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        np.testing.assert_allclose(got.radius, 0.02 + t * 0.04, rtol=1e-5)
        np.testing.assert_allclose(got.opacity, 0.2 + t * 0.8, rtol=1e-5)
        # every written point is a real point: no zero opacity from a missing attribute
        assert got.opacity.min() > 0.2


def test_keys_are_byte_identical_after_the_run(shot):
    layer = ink(shot)
    before = {n: gp_data.read_raw(gp_data.frame_at(layer, n).drawing) for n in (1, 9)}
    meta = {n: (f.keyframe_type, f.select) for n in (1, 9) for f in [gp_data.frame_at(layer, n)]}
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert bpy.ops.ballmorph.inbetween(method="LINEAR_BALL", frame_count=2) == {"FINISHED"}
    for n in (1, 9):
        frame = gp_data.frame_at(layer, n)
        assert gp_data.read_raw(frame.drawing) == before[n]
        assert (frame.keyframe_type, frame.select) == meta[n]


def test_hand_drawn_frame_between_the_keys_is_untouched_and_reported(shot, capfd):
    layer = ink(shot)
    for frame in layer.frames:
        frame.select = True  # the animator selected keys 1 and 9 ...
    gp_data.add_key(layer, 5, [gp_data.loop(0.5)], cyclic=[True])  # ... and had drawn frame 5
    drawn = gp_data.read_raw(gp_data.frame_at(layer, 5).drawing)
    result, text = run(capfd)
    assert result == {"FINISHED"}
    assert gp_data.read_raw(gp_data.frame_at(layer, 5).drawing) == drawn
    assert gp_data.frame_at(layer, 5).keyframe_type == "KEYFRAME"
    assert gp_data.frame_numbers(layer) == list(range(1, 10))
    assert "frame(s) 5 already drawn: left untouched" in text
    # the status bar shows the last report: it says there are warnings
    assert (
        text.strip().splitlines()[-1].startswith("Warning: Ball-morph In-between: 6 frame(s) on 1 layer(s), 1 warning")
    )


def test_rerun_replaces_only_its_own_frames(shot, capfd):
    layer = ink(shot)
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    first = {n: gp_data.read_raw(gp_data.frame_at(layer, n).drawing) for n in range(2, 9)}
    for _ in range(2):
        result, text = run(capfd)
        assert result == {"FINISHED"}
        assert "replacing 7 earlier" in text
        assert "untouched" not in text
    assert gp_data.frame_numbers(layer) == list(range(1, 10))
    assert {n: gp_data.read_raw(gp_data.frame_at(layer, n).drawing) for n in range(2, 9)} == first
    # fewer in-betweens: the earlier ones between the keys go, nothing else does
    assert bpy.ops.ballmorph.inbetween(frame_count=1) == {"FINISHED"}
    assert gp_data.frame_numbers(layer) == [1, 5, 9]
    result, text = run(capfd, frame_count=1)
    assert result == {"FINISHED"} and "replacing 1 earlier" in text
    assert gp_data.frame_numbers(layer) == [1, 5, 9]


def test_the_recorded_fingerprints_are_the_ones_blender_reads_back(shot, addon):
    """The writer records each in-between's fingerprint from the arrays it hands to Blender, not
    read back: it must be what reading it back gives, or re-runs would not know their frames."""
    io = importlib.import_module(f"{addon.__name__}.operators.grease_pencil")
    layer = ink(shot)
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    (record,) = gp_data.marks(shot).values()
    for n in range(2, 9):
        assert record[str(n)].split()[-1] == io.fingerprint(gp_data.frame_at(layer, n).drawing)
    strokes = io.read_strokes(gp_data.frame_at(layer, 5).drawing)
    turned = np.array([[0.0, -2.0, 0.0, 0.3], [1.0, 0.0, 0.0, 0.1], [0.0, 0.0, 0.7, 0.0], [0.0, 0.0, 0.0, 1.0]])
    for number, written, matrix in ((20, strokes, turned), (21, bm.StrokeSet.empty(), None)):
        drawing = layer.frames.new(number).drawing
        assert io.write_strokes(drawing, written, matrix) == io.fingerprint(drawing)


def test_drawings_written_through_one_staging_are_the_drawings_written_alone(shot, addon):
    """The writer converts every frame's arrays in one set of kept buffers (Staging): a drawing
    written after a bigger or a smaller one is what writing it on its own gives, fingerprint
    included (the fingerprint is taken before the buffer is reused)."""
    io = importlib.import_module(f"{addon.__name__}.operators.grease_pencil")
    layer = ink(shot)
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    big = io.read_strokes(gp_data.frame_at(layer, 5).drawing)
    small = big.subset([0])
    staging, number = io.Staging(), 30
    for strokes in (big, small, big, small):
        alone, shared = layer.frames.new(number).drawing, layer.frames.new(number + 1).drawing
        assert io.write_strokes(shared, strokes, staging=staging) == io.write_strokes(alone, strokes)
        assert gp_data.read_raw(shared) == gp_data.read_raw(alone)
        assert io.fingerprint(shared) == io.fingerprint(alone)
        number += 2


def test_colours_are_written_when_np_any_would_have_them(addon):
    """The writer asks whether a frame has colours from their extremes: what np.any says, for
    -0.0, NaN, infinities and nothing at all."""
    io = importlib.import_module(f"{addon.__name__}.operators.grease_pencil")
    cases = [np.zeros((5, 4)), np.full((5, 4), -0.0), np.zeros((0, 4)), np.eye(5, 4), -np.eye(5, 4)]
    cases += [np.where(np.eye(5, 4) > 0, value, 0.0) for value in (np.nan, np.inf, -np.inf, 1e-300)]
    for colours in cases:
        assert io._any_nonzero(colours) == np.any(colours)


def test_an_in_between_the_animator_edited_becomes_theirs(shot, capfd):
    layer = ink(shot)
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    drawing = gp_data.frame_at(layer, 5).drawing
    positions = np.empty(len(drawing.attributes["position"].data) * 3, np.float32)
    drawing.attributes["position"].data.foreach_get("vector", positions)
    drawing.attributes["position"].data.foreach_set("vector", positions + np.float32(0.05))
    edited = gp_data.read_raw(drawing)
    # standing on frame 4, the edited frame 5 is now the next key ...
    result, text = run(capfd)
    assert result == {"FINISHED"}
    assert "Ink 1\u21925: 3 in-between(s) on frame(s) 2\u20134" in text
    assert gp_data.read_raw(gp_data.frame_at(layer, 5).drawing) == edited
    # ... and with keys 1 and 9 selected it is a drawn frame between them
    for number in (1, 9):
        gp_data.frame_at(layer, number).select = True
    result, text = run(capfd)
    assert result == {"FINISHED"}
    assert gp_data.read_raw(gp_data.frame_at(layer, 5).drawing) == edited
    assert gp_data.frame_at(layer, 5).keyframe_type == "BREAKDOWN"
    assert "frame(s) 5 already drawn: left untouched" in text


def test_marks_survive_save_and_reload(shot, tmp_path, capfd):
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    path = str(tmp_path / "shot.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    obj = bpy.data.objects["Drawing"]
    bpy.context.view_layer.objects.active = obj
    result, text = run(capfd)
    assert result == {"FINISHED"}
    assert "replacing 7 earlier" in text
    assert gp_data.frame_numbers(ink(obj)) == list(range(1, 10))


def test_current_frame_after_the_last_key_is_a_clear_cancel(shot):
    bpy.context.scene.frame_current = 20
    with pytest.raises(RuntimeError, match="no keyframe after frame 20"):
        bpy.ops.ballmorph.inbetween()


def test_all_layers_each_use_their_own_keys(addon):
    obj = gp_data.new_object(layers=("Ink", "Paint"))
    gp_data.add_key(obj.data.layers["Ink"], 1, [gp_data.arc(0.3)])
    gp_data.add_key(obj.data.layers["Ink"], 5, [gp_data.arc(-0.3)])
    gp_data.add_key(obj.data.layers["Paint"], 3, [gp_data.loop(0.5)], cyclic=[True])
    gp_data.add_key(obj.data.layers["Paint"], 8, [gp_data.loop(0.7)], cyclic=[True])
    bpy.context.scene.frame_current = 4
    assert bpy.ops.ballmorph.inbetween(layers="ALL") == {"FINISHED"}
    assert gp_data.frame_numbers(obj.data.layers["Ink"]) == [1, 2, 3, 4, 5]
    assert gp_data.frame_numbers(obj.data.layers["Paint"]) == [3, 4, 5, 6, 7, 8]
    assert bpy.ops.ballmorph.inbetween(layers="ACTIVE", frame_count=1) == {"FINISHED"}
    assert gp_data.frame_numbers(obj.data.layers["Ink"]) == [1, 3, 5]
    assert gp_data.frame_numbers(obj.data.layers["Paint"]) == [3, 4, 5, 6, 7, 8]


def test_layer_transform_is_applied_consistently(shot):
    layer = ink(shot)
    layer.translation = (0.5, 0.0, -0.2)
    layer.rotation = (0.0, 0.4, 0.0)
    layer.scale = (2.0, 1.0, 0.5)  # non-uniform: morphing in layer space would differ
    matrix = np.array(layer.matrix_local)

    def to_object(strokes):
        strokes.positions = strokes.positions @ matrix[:3, :3].T + matrix[:3, 3]
        return strokes

    key_a = to_object(gp_data.read_strokes(gp_data.frame_at(layer, 1).drawing))
    key_b = to_object(gp_data.read_strokes(gp_data.frame_at(layer, 9).drawing))
    want = bm.inbetween(key_a, key_b, [0.5]).frames[0]
    assert bpy.ops.ballmorph.inbetween(frame_count=1) == {"FINISHED"}
    got = to_object(gp_data.read_strokes(gp_data.frame_at(layer, 5).drawing))
    np.testing.assert_allclose(got.positions, want.positions, rtol=0, atol=1e-5)


def _select_strokes(drawing, selected):
    """Write a stroke selection (the attribute Blender's edit mode uses)."""
    if ".selection" not in drawing.attributes:
        drawing.attributes.new(".selection", "BOOLEAN", "CURVE")
    drawing.attributes[".selection"].data.foreach_set("value", np.asarray(selected, bool))


def test_selected_strokes_only_morphs_selected_and_holds_the_rest(shot):
    layer = ink(shot)
    _select_strokes(gp_data.frame_at(layer, 1).drawing, [False, True])
    _select_strokes(gp_data.frame_at(layer, 9).drawing, [False, True])
    key_a = gp_data.read_strokes(gp_data.frame_at(layer, 1).drawing)
    key_b = gp_data.read_strokes(gp_data.frame_at(layer, 9).drawing)
    want = bm.inbetween(key_a.subset([1]), key_b.subset([1]), [0.5]).frames[0]
    assert bpy.ops.ballmorph.inbetween(frame_count=1, selected_only=True) == {"FINISHED"}
    got = gp_data.read_strokes(gp_data.frame_at(layer, 5).drawing)
    assert len(got) == 2
    held = got.subset([0])
    np.testing.assert_array_equal(held.positions, key_a.subset([0]).positions)  # the loop stays put
    np.testing.assert_allclose(got.subset([1]).positions, want.positions, atol=1e-6)


@pytest.mark.parametrize(
    "method",
    [
        "CIRCULAR_BALL",
        "LINEAR_BALL",
        "PARABOLIC_BALL",
        "LINEAR_INTERPOLATION",
        "CLOSEST_PROJECTION",
        "CURVATURE_INTERPOLATION",
        "LAPLACE_BLENDING",
        "HEAT_PROPAGATION",
    ],
)
def test_every_method_runs(shot, method):
    assert method.lower().replace("_", "-") in bm.METHODS
    assert bpy.ops.ballmorph.inbetween(method=method, frame_count=1) == {"FINISHED"}
    assert gp_data.frame_at(ink(shot), 5).keyframe_type == "BREAKDOWN"
    assert len(gp_data.read_strokes(gp_data.frame_at(ink(shot), 5).drawing)) == 2


def test_a_method_missing_from_the_core_is_a_clear_cancel(shot, addon, monkeypatch):
    options = __import__(f"{addon.__name__}.operators.options", fromlist=["CORE_METHODS"])
    monkeypatch.setattr(options, "CORE_METHODS", ("circular-ball",))
    with pytest.raises(RuntimeError, match="Heat Propagation morph is not available in this version"):
        bpy.ops.ballmorph.inbetween(method="HEAT_PROPAGATION")
    assert gp_data.frame_numbers(ink(shot)) == [1, 9]


def test_core_warnings_reach_the_report(addon, capfd):
    obj = gp_data.new_object()
    layer = ink(obj)
    gp_data.add_key(layer, 1, [gp_data.arc(0.3), gp_data.loop(0.2, centre=(1, 0))], cyclic=[False, True])
    gp_data.add_key(layer, 5, [gp_data.arc(-0.3)])
    bpy.context.scene.frame_current = 2
    result, text = run(capfd)
    assert result == {"FINISHED"}
    assert "Ink 1\u21925: " in text and "no partner" in text


def test_preferences_are_the_defaults_and_runs_are_remembered(shot, addon):
    preferences = bpy.context.preferences.addons[addon.__name__].preferences
    settings = bpy.context.scene.ballmorph_inbetween
    preferences.method = "LINEAR_BALL"
    preferences.frame_count = 3
    assert (settings.method, settings.frame_count) == ("LINEAR_BALL", 3)
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert [f.frame_number for f in ink(shot).frames if f.keyframe_type == "BREAKDOWN"] == [3, 5, 7]
    assert bpy.ops.ballmorph.inbetween(frame_count=1, method="PARABOLIC_BALL") == {"FINISHED"}
    assert (settings.method, settings.frame_count) == ("PARABOLIC_BALL", 1)
    preferences.method = "CIRCULAR_BALL"
    assert settings.method == "PARABOLIC_BALL"  # the scene now has its own choice


# -- one in-between on the current frame (current_frame_only), as Blender's Interpolate -----------


@pytest.mark.parametrize(("easing_type", "easing"), [("LINEAR", "EASE_IN"), ("QUAD", "EASE_IN_OUT")])
def test_current_frame_only_writes_the_current_frame_at_its_fraction(shot, capfd, easing_type, easing):
    layer = ink(shot)
    key_a = gp_data.read_strokes(gp_data.frame_at(layer, 1).drawing)
    key_b = gp_data.read_strokes(gp_data.frame_at(layer, 9).drawing)
    bpy.context.scene.frame_current = 3  # a quarter of the way from key 1 to key 9
    t = ease(np.array([0.25]), easing_type, easing)
    [want] = bm.inbetween(key_a, key_b, t).frames

    result, text = run(capfd, current_frame_only=True, easing_type=easing_type, easing=easing, frame_count=5)
    assert result == {"FINISHED"}, text
    assert gp_data.frame_numbers(layer) == [1, 3, 9], "one in-between, on the current frame only"
    assert gp_data.frame_at(layer, 3).keyframe_type == "BREAKDOWN"
    got = gp_data.read_strokes(gp_data.frame_at(layer, 3).drawing)
    np.testing.assert_array_equal(got.offsets, want.offsets)
    error = np.abs(got.positions - want.positions).max()
    assert error < 1e-6, f"frame 3 is not the morph at t = {t[0]:.4f} (max distance {error:.2e})"
    assert "1 in-between(s) on frame(s) 3" in text


def test_current_frame_only_keeps_the_other_inbetweens(shot):
    layer = ink(shot)
    assert bpy.ops.ballmorph.inbetween(frame_count=3) == {"FINISHED"}  # frames 3, 5, 7
    before = {n: gp_data.read_raw(gp_data.frame_at(layer, n).drawing) for n in (5, 7)}
    bpy.context.scene.frame_current = 3
    assert bpy.ops.ballmorph.inbetween(current_frame_only=True, method="LINEAR_BALL") == {"FINISHED"}
    assert gp_data.frame_numbers(layer) == [1, 3, 5, 7, 9]
    assert {n: gp_data.read_raw(gp_data.frame_at(layer, n).drawing) for n in (5, 7)} == before


def test_current_frame_only_on_a_key_says_where_to_go(shot):
    before = gp_data.snapshot(shot)
    bpy.context.scene.frame_current = 9
    with pytest.raises(RuntimeError) as info:
        bpy.ops.ballmorph.inbetween(current_frame_only=True)
    assert "the current frame 9 is a keyframe: go to a frame between two keys" in str(info.value)
    assert gp_data.snapshot(shot) == before


# -- poll: an active Grease Pencil object ---------------------------------------------------------


@pytest.mark.parametrize(
    ("active", "expected"),
    [
        (None, "No Grease Pencil object is active: select one and run Ball-morph In-between again"),
        (
            "MESH",
            "The active object 'Cube' is a mesh, not a Grease Pencil object: make a Grease Pencil object "
            "active and run Ball-morph In-between again",
        ),
    ],
    ids=["nothing", "mesh"],
)
def test_poll_fails_without_an_active_grease_pencil_object_and_says_why(shot, active, expected):
    before = gp_data.snapshot(shot)
    assert bpy.ops.ballmorph.inbetween.poll()
    if active is None:
        bpy.context.view_layer.objects.active = None
    else:
        cube = bpy.data.objects.new("Cube", bpy.data.meshes.new("Cube"))
        bpy.context.scene.collection.objects.link(cube)
        bpy.context.view_layer.objects.active = cube
    assert shot.select_get()  # the drawing is still selected: only the active object counts
    assert not bpy.ops.ballmorph.inbetween.poll()
    with pytest.raises(RuntimeError) as info:
        bpy.ops.ballmorph.inbetween()
    assert expected in str(info.value), "poll_message_set did not say why"
    assert gp_data.snapshot(shot) == before
