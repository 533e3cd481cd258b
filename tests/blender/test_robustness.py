"""The operator on bad or awkward input: a clear report, and no drawing damaged.

Each case checks the report's level (Blender prints ``Error:``, ``Warning:`` or ``Info:`` before
each report; a cancelled run raises ``RuntimeError("Error: ...")``), that the message says what
to do, and that every frame that existed before the run is byte-identical afterwards: frame
numbers, keyframe types, stroke offsets and every attribute of every drawing
(:func:`gp_data.snapshot`).

Undo and redo in background mode: ``ed.undo`` and ``ed.redo`` work under a window override;
``ed.undo_redo`` (F9's "Adjust Last Operation") segfaults bpy 4.5 and 5.0, and so does any
operator called with ``undo=True`` under a window + area override, so those are not driven here
(test_contexts.py replays what F9 does in two steps).
"""

import importlib

import bpy
import gp_data
import numpy as np
import pytest

from ballmorph_core import frame_times

LEVELS = ("Info", "Warning", "Error")


def run(capfd, *args, **options):
    """Run the operator; return its result and its reports as (level, text) pairs."""
    capfd.readouterr()
    result = bpy.ops.ballmorph.inbetween(*args, **options)
    out, err = capfd.readouterr()
    return result, reports(out + err)


def reports(text):
    found = []
    for line in text.splitlines():
        level, sep, message = line.partition(": ")
        if sep and level in LEVELS:
            found.append((level, message))
    return found


def cancelled(**options):
    """Run the operator expecting a cancel; return the error report's text."""
    with pytest.raises(RuntimeError) as info:
        bpy.ops.ballmorph.inbetween(**options)
    text = str(info.value).strip()
    assert text.startswith("Error: "), text  # an ERROR report, not a Python traceback
    assert "Traceback" not in text
    return text[len("Error: ") :]


def unchanged_frames(before, after):
    """Assert every frame of ``before`` is in ``after``, byte for byte."""
    for layer, frames in before.items():
        for number, frame in frames.items():
            assert after[layer].get(number) == frame, f"layer {layer!r} frame {number} changed"


def two_layer_shot(layers=("Ink", "Paint")):
    """Layers each with keys on frames 1 and 5 (an arch into a dip); current frame 2."""
    obj = gp_data.new_object(layers=layers)
    for name in layers:
        gp_data.add_key(obj.data.layers[name], 1, [gp_data.arc(0.3)])
        gp_data.add_key(obj.data.layers[name], 5, [gp_data.arc(-0.3)])
    bpy.context.scene.frame_current = 2
    return obj


# -- no Grease Pencil object, too few keys, empty or broken keys --------------------------------


# (no active Grease Pencil object: the operator's poll fails and says why, test_inbetween.py)


@pytest.mark.parametrize("count", [0, 1])
def test_fewer_than_two_keys(addon, count):
    obj = gp_data.new_object()
    for number in range(1, count + 1):
        gp_data.add_key(obj.data.layers["Ink"], number, [gp_data.arc(0.3)])
    before = gp_data.snapshot(obj)
    text = cancelled()
    assert text == f"Nothing to in-between: layer 'Ink' has {count} keyframe(s): draw a second key to in-between"
    assert gp_data.snapshot(obj) == before


def test_both_keys_empty(addon):
    obj = gp_data.new_object()
    obj.data.layers["Ink"].frames.new(1)
    obj.data.layers["Ink"].frames.new(6)
    bpy.context.scene.frame_current = 2
    before = gp_data.snapshot(obj)
    assert cancelled() == "Nothing to in-between: Ink 1\u21926: both keys are empty: draw strokes in them first"
    assert gp_data.snapshot(obj) == before


def test_one_empty_key_makes_the_strokes_disappear_halfway(addon, capfd):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [gp_data.arc(0.3), gp_data.loop(0.4)], cyclic=[False, True])
    layer.frames.new(5)
    bpy.context.scene.frame_current = 2
    before = gp_data.snapshot(obj)
    result, said = run(capfd)
    assert result == {"FINISHED"}
    warnings = " ".join(text for level, text in said if level == "Warning")
    assert warnings.startswith("Ink 1\u21925: ")
    for stroke in (0, 1):
        assert f"stroke {stroke + 1} of the first key has no partner: disappears at the middle" in warnings
    unchanged_frames(before, gp_data.snapshot(obj))
    key = gp_data.read_strokes(gp_data.frame_at(layer, 1).drawing)
    held = gp_data.read_strokes(gp_data.frame_at(layer, 2).drawing)  # t = 0.25: still shown
    np.testing.assert_array_equal(held.offsets, key.offsets)
    np.testing.assert_allclose(held.positions, key.positions, atol=1e-6)
    for number in (3, 4):  # t >= 0.5: gone
        assert len(gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)) == 0
        assert gp_data.frame_at(layer, number).keyframe_type == "BREAKDOWN"


def test_points_with_nan_coordinates_are_refused(addon):
    obj = gp_data.new_object()
    broken = gp_data.arc(0.3)
    broken[7] = np.nan
    gp_data.add_key(obj.data.layers["Ink"], 1, [gp_data.loop(0.2), broken])
    gp_data.add_key(obj.data.layers["Ink"], 5, [gp_data.loop(0.3), gp_data.arc(-0.3)])
    bpy.context.scene.frame_current = 2
    before = gp_data.snapshot(obj)
    assert cancelled() == (
        "Nothing to in-between: Ink 1\u21925: the key on frame 1 has points with invalid (NaN or infinite) "
        "coordinates in stroke(s) 1: redraw or delete those strokes"
    )
    assert gp_data.snapshot(obj) == before


def test_dots_and_zero_length_strokes_move_point_by_point(addon, capfd):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [np.array([[0.0, 0.0]]), np.full((5, 2), 0.5)])
    gp_data.add_key(layer, 5, [np.array([[1.0, 0.0]]), np.full((4, 2), 1.5)])
    bpy.context.scene.frame_current = 2
    before = gp_data.snapshot(obj)
    result, said = run(capfd, matching="INDEX")
    assert result == {"FINISHED"}
    warnings = " ".join(text for level, text in said if level == "Warning")
    assert "stroke 1 -> 1: too few distinct points" in warnings and "stroke 2 -> 2: too few distinct points" in warnings
    unchanged_frames(before, gp_data.snapshot(obj))
    middle = gp_data.read_strokes(gp_data.frame_at(layer, 3).drawing)
    np.testing.assert_allclose(middle.positions[middle.points(0)][:, [0, 2]], [[0.5, 0.0]], atol=1e-6)
    np.testing.assert_allclose(middle.positions[middle.points(1)][:, [0, 2]], 1.0, atol=1e-6)


def test_layer_scaled_to_zero_is_refused(shot):
    shot.data.layers["Ink"].scale = (1.0, 1.0, 0.0)  # flat along the canvas's Z: cannot be inverted
    before = gp_data.snapshot(shot)
    assert cancelled() == (
        "Nothing to in-between: Ink 1\u21929: layer 'Ink' has a flat transform (zero scale): give the layer a "
        "non-zero scale to in-between it"
    )
    assert gp_data.snapshot(shot) == before


# -- locked, hidden, grouped layers -------------------------------------------------------------


@pytest.mark.parametrize(("flag", "fix"), [("lock", "unlock it"), ("hide", "show it")], ids=["locked", "hidden"])
def test_locked_or_hidden_layer_is_not_written(addon, capfd, flag, fix):
    obj = two_layer_shot()
    paint = obj.data.layers["Paint"]
    setattr(paint, flag, True)
    state = "locked" if flag == "lock" else "hidden"
    before = gp_data.snapshot(obj)

    result, said = run(capfd, layers="ALL")
    assert result == {"FINISHED"}
    assert ("Warning", f"layer 'Paint' is {state}: {fix} to in-between it") in said
    after = gp_data.snapshot(obj)
    assert after["Paint"] == before["Paint"]
    assert sorted(after["Ink"]) == [1, 2, 3, 4, 5]
    unchanged_frames(before, after)

    obj.data.layers.active = paint
    assert cancelled(layers="ACTIVE") == f"Nothing to in-between: layer 'Paint' is {state}: {fix} to in-between it"
    assert gp_data.snapshot(obj) == after


@pytest.mark.parametrize(
    ("lock", "hide", "nested", "blocker"),
    [
        (False, False, False, None),
        (True, False, False, "is locked (group 'Outer'): unlock it"),
        (False, True, False, "is hidden (group 'Outer'): show it"),
        (True, False, True, "is locked (group 'Outer'): unlock it"),  # the outer group of two
        (False, True, True, "is hidden (group 'Outer'): show it"),
    ],
    ids=["plain-group", "locked-group", "hidden-group", "locked-outer-group", "hidden-outer-group"],
)
def test_layers_in_groups(addon, capfd, lock, hide, nested, blocker):
    obj = two_layer_shot()
    data = obj.data
    outer = data.layer_groups.new("Outer")
    group = data.layer_groups.new("Inner", parent_group=outer) if nested else outer
    data.layers.move_to_layer_group(data.layers["Paint"], group)
    outer.lock, outer.hide = lock, hide
    before = gp_data.snapshot(obj)

    result, said = run(capfd, layers="ALL")
    assert result == {"FINISHED"}
    after = gp_data.snapshot(obj)
    unchanged_frames(before, after)
    assert sorted(after["Ink"]) == [1, 2, 3, 4, 5]
    if blocker is None:
        assert sorted(after["Paint"]) == [1, 2, 3, 4, 5]
        assert not [text for level, text in said if level != "Info"]
        return
    assert after["Paint"] == before["Paint"]
    assert ("Warning", f"layer 'Paint' {blocker} to in-between it") in said
    data.layers.active = data.layers["Paint"]
    assert cancelled(layers="ACTIVE") == f"Nothing to in-between: layer 'Paint' {blocker} to in-between it"
    assert gp_data.snapshot(obj) == after


# -- keys far from flat, frames already drawn --------------------------------------------------


def test_keys_far_from_flat_are_reported_and_still_morphed(shot, capfd):
    layer = shot.data.layers["Ink"]
    drawing = gp_data.frame_at(layer, 9).drawing
    positions = np.empty(len(drawing.attributes["position"].data) * 3, np.float32)
    drawing.attributes["position"].data.foreach_get("vector", positions)
    positions = positions.reshape(-1, 3)
    positions[:, 1] = 0.6 * np.sin(3 * positions[:, 0])  # bumps off the XZ canvas
    drawing.attributes["position"].data.foreach_set("vector", positions.ravel())
    before = gp_data.snapshot(shot)

    result, said = run(capfd, frame_count=3)
    assert result == {"FINISHED"}
    assert any(level == "Warning" and text.startswith("Ink 1\u21929: ") and "not flat" in text for level, text in said)
    assert any(
        "strokes were morphed in the best-fit plane, keeping each point's offset from it" in text for _, text in said
    )
    unchanged_frames(before, gp_data.snapshot(shot))
    key_a = gp_data.read_strokes(gp_data.frame_at(layer, 1).drawing)
    key_b = gp_data.read_strokes(gp_data.frame_at(layer, 9).drawing)
    low = np.minimum(key_a.positions.min(axis=0), key_b.positions.min(axis=0))
    high = np.maximum(key_a.positions.max(axis=0), key_b.positions.max(axis=0))
    for number in (3, 5, 7):
        got = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        assert len(got) == 2 and np.isfinite(got.positions).all()
        span = high - low
        assert np.all(got.positions >= low - 0.2 * span) and np.all(got.positions <= high + 0.2 * span)
        assert not np.allclose(got.positions[:, 1], 0.0)  # the depth is carried, not flattened
        assert np.ptp(got.positions[:, 1]) < np.ptp(key_b.positions[:, 1])


@pytest.mark.parametrize("kind", ["KEYFRAME", "BREAKDOWN"])
def test_every_frame_between_the_keys_drawn_by_hand(addon, kind):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    for number in range(1, 6):
        frame = gp_data.add_key(layer, number, [gp_data.arc(0.1 * number)])
        frame.keyframe_type = "KEYFRAME" if number in (1, 5) else kind
        frame.select = number in (1, 5)
    bpy.context.scene.frame_current = 3
    before = gp_data.snapshot(obj)
    assert cancelled() == (
        "Nothing to in-between: Ink 1\u21925: every frame between the keys is drawn by hand: nothing was written "
        "(delete drawn frames there to make room for in-betweens)"
    )
    assert gp_data.snapshot(obj) == before
    for frame in layer.frames:
        frame.select = False  # now the keys around the current frame are 3 and 4
    assert cancelled() == (
        "Nothing to in-between: layer 'Ink': keys 3 and 4 have no frame between them: move them apart, "
        "or select two keys with frames between them"
    )
    assert gp_data.snapshot(obj) == before


# -- repeated runs, undo and redo ---------------------------------------------------------------


def _blend_size(path):
    bpy.ops.wm.save_as_mainfile(filepath=str(path), copy=True, compress=False)
    return path.stat().st_size


def test_the_same_run_ten_times_changes_nothing_more(shot, capfd, tmp_path):
    layer = shot.data.layers["Ink"]
    gp_data.add_key(layer, 4, [gp_data.loop(0.6)], cyclic=[True])  # a hand-drawn frame in between
    for number in (1, 9):
        gp_data.frame_at(layer, number).select = True
    bpy.context.preferences.filepaths.save_version = 0
    before = gp_data.snapshot(shot)
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    first, first_marks = gp_data.snapshot(shot), gp_data.marks(shot)
    first_size = _blend_size(tmp_path / "first.blend")
    assert sorted(first["Ink"]) == list(range(1, 10))
    assert sorted(first_marks["Ink"]) == sorted(str(n) for n in (2, 3, 5, 6, 7, 8))
    for _ in range(9):
        result, said = run(capfd)
        assert result == {"FINISHED"}
        made = "6 in-between(s) on frame(s) 2, 3, 5, 6, 7, 8 (Circular Ball-morph, replacing 6 earlier)"
        assert ("Info", f"Ink 1\u21929: {made}") in said
        assert ("Warning", "Ink 1\u21929: frame(s) 4 already drawn: left untouched") in said
    unchanged_frames(before, gp_data.snapshot(shot))
    assert gp_data.snapshot(shot) == first
    assert gp_data.marks(shot) == first_marks
    assert len(layer.frames) == len({f.frame_number for f in layer.frames}) == 9
    assert _blend_size(tmp_path / "tenth.blend") == first_size  # no drawing left behind


def _window():
    return bpy.context.temp_override(window=bpy.context.window_manager.windows[0])


def test_undo_restores_and_redo_repeats_a_run(shot, capfd):
    assert bpy.ops.ballmorph.inbetween(frame_count=2) == {"FINISHED"}  # earlier in-betweens to replace
    before, before_marks = gp_data.snapshot(shot), gp_data.marks(shot)
    bpy.ops.ed.undo_push(message="before")
    # undo=True: pushed as one undo step named after the operator, as in the UI
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, frame_count=0) == {"FINISHED"}
    obj = bpy.data.objects["Drawing"]
    after, after_marks = gp_data.snapshot(obj), gp_data.marks(obj)
    assert sorted(after["Ink"]) == list(range(1, 10)) and after != before

    with _window():
        assert bpy.ops.ed.undo() == {"FINISHED"}
    obj = bpy.data.objects["Drawing"]  # undo reloads data-blocks: look them up again
    assert gp_data.snapshot(obj) == before
    assert gp_data.marks(obj) == before_marks

    with _window():
        assert bpy.ops.ed.redo() == {"FINISHED"}
    obj = bpy.data.objects["Drawing"]
    assert gp_data.snapshot(obj) == after
    assert gp_data.marks(obj) == after_marks
    # the redone in-betweens are still the tool's: a re-run replaces them and nothing else
    bpy.context.view_layer.objects.active = obj
    result, said = run(capfd, frame_count=0)
    assert result == {"FINISHED"}
    assert any("replacing 7 earlier" in text for _, text in said)
    assert gp_data.snapshot(obj) == after


def test_undo_in_edit_mode_leaves_the_earlier_in_betweens_the_tools(shot, capfd):
    """Edit-mode undo restores the frames but not the data-block's record of them."""
    with gp_data.view3d_override():
        bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.ed.undo_push(message="before")
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, frame_count=2) == {"FINISHED"}
    before = gp_data.snapshot(bpy.data.objects["Drawing"])
    assert sorted(before["Ink"]) == [1, 4, 6, 9]
    assert bpy.ops.ballmorph.inbetween("EXEC_DEFAULT", True, frame_count=3) == {"FINISHED"}
    with _window():
        assert bpy.ops.ed.undo() == {"FINISHED"}
    obj = bpy.data.objects["Drawing"]
    assert obj.mode == "EDIT"
    assert gp_data.snapshot(obj) == before
    # frames 4 and 6 are still the tool's: replaced, not taken for the animator's keys
    result, said = run(capfd, frame_count=3)
    assert result == {"FINISHED"}
    assert (
        "Info",
        "Ink 1\u21929: 3 in-between(s) on frame(s) 3, 5, 7 (Circular Ball-morph, replacing 2 earlier)",
    ) in said
    after = gp_data.snapshot(obj)
    assert sorted(after["Ink"]) == [1, 3, 5, 7, 9]
    assert {n: after["Ink"][n] for n in (1, 9)} == {n: before["Ink"][n] for n in (1, 9)}
    with gp_data.view3d_override():
        bpy.ops.object.mode_set(mode="OBJECT")


# -- failures in the middle of a run ------------------------------------------------------------


def _core_inbetween(addon):
    """The add-on's own copy of the core's drawing pipeline (the module the operator calls)."""
    return importlib.import_module(f"{addon.__name__}.ballmorph_core.drawing.plan")


def _core_fallbacks(addon):
    """The add-on's own copy of the pipeline's fallback step (which builds the comparison morphs)."""
    return importlib.import_module(f"{addon.__name__}.ballmorph_core.drawing.pair_morphs.fallbacks")


def _keys_as_the_addon_reads_them(addon, layer, first=1, last=9):
    """The two keys read by the add-on's own reader: the core checks keys are its own
    StrokeSet class, and the add-on's vendored core is a different module from the tests'."""
    reader = importlib.import_module(f"{addon.__name__}.operators.grease_pencil")
    return tuple(reader.read_strokes(gp_data.frame_at(layer, n).drawing) for n in (first, last))


def test_a_pair_failing_mid_run_falls_back_for_that_pair_only(shot, addon, capfd, monkeypatch):
    """One stroke pair raises (a simulated core bug): that pair is made with the fallback morph
    and reported; the other pairs keep the requested morph; keys untouched."""
    core, fallbacks = _core_inbetween(addon), _core_fallbacks(addon)
    real, calls = fallbacks.make_morph, []

    def flaky(P, Q, method, *args, **kwargs):
        if method == "laplace-blending":
            calls.append(len(P))
            if len(calls) == 2:
                raise ZeroDivisionError("simulated core bug")
        return real(P, Q, method, *args, **kwargs)

    monkeypatch.setattr(fallbacks, "make_morph", flaky)
    layer = shot.data.layers["Ink"]
    before = gp_data.snapshot(shot)
    result, said = run(capfd, method="LAPLACE_BLENDING", frame_count=3)
    assert result == {"FINISHED"}
    assert len(calls) >= 2
    assert any(
        level == "Warning" and "laplace-blending failed (ZeroDivisionError: simulated core bug)" in text
        for level, text in said
    ), said
    after = gp_data.snapshot(shot)
    unchanged_frames(before, after)
    assert sorted(after["Ink"]) == [1, 3, 5, 7, 9]
    # What was written is what the core gives with the same failure: the first pair morphed by
    # laplace-blending, the failing pair by linear interpolation.
    key_a, key_b = _keys_as_the_addon_reads_them(addon, layer)
    numbers, fractions = frame_times(1, 9, 3)
    calls.clear()
    want = core.inbetween(key_a, key_b, fractions, method="laplace-blending")
    used = [p.method for p in want.pairs]
    assert used[0] == "laplace-blending" and used[1] == "linear-interpolation"
    for number, expected in zip(numbers.tolist(), want.frames):
        got = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        np.testing.assert_array_equal(got.offsets, expected.offsets)
        np.testing.assert_allclose(got.positions, expected.positions, atol=1e-6)


def test_an_interval_whose_morph_fails_is_redone_whole_with_the_fallback(shot, addon, capfd, monkeypatch):
    """The pipeline raises for the requested morph (outside the per-pair guard): the interval is
    redone whole with the fallback morph, so its frames come from one morph, and it says so."""
    plans = importlib.import_module(f"{addon.__name__}.operators.plans")
    real = plans.plan_inbetween

    def broken(key_a, key_b, method, **kwargs):
        if method == "laplace-blending":
            raise FloatingPointError("simulated core bug")
        return real(key_a, key_b, method=method, **kwargs)

    monkeypatch.setattr(plans, "plan_inbetween", broken)
    layer = shot.data.layers["Ink"]
    before = gp_data.snapshot(shot)
    result, said = run(capfd, method="LAPLACE_BLENDING", frame_count=3)
    assert result == {"FINISHED"}
    assert (
        "Warning",
        "Ink 1\u21929: the Laplace Blending morph failed (FloatingPointError: simulated core bug): every "
        "in-between here was made with Linear Interpolation instead; please report this drawing",
    ) in said
    after = gp_data.snapshot(shot)
    unchanged_frames(before, after)
    key_a, key_b = _keys_as_the_addon_reads_them(addon, layer)
    numbers, fractions = frame_times(1, 9, 3)
    want = _core_inbetween(addon).inbetween(key_a, key_b, fractions, method="linear-interpolation")
    for number, expected in zip(numbers.tolist(), want.frames):
        got = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        np.testing.assert_allclose(got.positions, expected.positions, atol=1e-6)


def test_an_interval_failing_for_every_morph_leaves_its_layer_untouched(addon, capfd, monkeypatch):
    """The whole pipeline raises for one layer's keys, and again with the fallback: nothing is
    written on that layer, the other layers still are, and the report says why."""
    obj = gp_data.new_object(layers=("Ink", "Paint"))
    ink, paint = obj.data.layers["Ink"], obj.data.layers["Paint"]
    gp_data.add_key(ink, 1, [gp_data.loop(1.0), gp_data.arc(0.5)], cyclic=[True, False])
    gp_data.add_key(ink, 9, [gp_data.loop(1.2), gp_data.arc(-0.3)], cyclic=[True, False])
    gp_data.add_key(paint, 1, [gp_data.arc(0.3)])
    gp_data.add_key(paint, 9, [gp_data.arc(-0.3)])
    bpy.context.scene.frame_current = 4
    assert bpy.ops.ballmorph.inbetween(layers="ALL", frame_count=1) == {"FINISHED"}  # earlier in-betweens
    before = gp_data.snapshot(obj)
    assert sorted(before["Ink"]) == sorted(before["Paint"]) == [1, 5, 9]

    plans = importlib.import_module(f"{addon.__name__}.operators.plans")
    real, calls = plans.plan_inbetween, []

    def broken(key_a, key_b, method, **kwargs):
        calls.append((len(key_a), method))
        if len(key_a) == 2:  # the Ink keys
            raise FloatingPointError("simulated core bug")
        return real(key_a, key_b, method=method, **kwargs)

    monkeypatch.setattr(plans, "plan_inbetween", broken)
    result, said = run(capfd, layers="ALL", method="CURVATURE_INTERPOLATION", frame_count=0)
    assert result == {"FINISHED"}
    assert (2, "curvature-interpolation") in calls and (2, "linear-interpolation") in calls
    assert (
        "Warning",
        "Ink 1\u21929: the morph failed (FloatingPointError: simulated core bug; then Linear Interpolation: "
        "FloatingPointError: simulated core bug): nothing was written between these keys; try another morph, "
        "or simplify the strokes, and please report this drawing",
    ) in said
    after = gp_data.snapshot(obj)
    assert after["Ink"] == before["Ink"]  # not one frame added, removed or changed
    assert sorted(after["Paint"]) == list(range(1, 10))  # its earlier in-between 5 was replaced
    assert {n: after["Paint"][n] for n in (1, 9)} == {n: before["Paint"][n] for n in (1, 9)}
    made = "7 in-between(s) on frame(s) 2\u20138 (Curvature Interpolation, replacing 1 earlier)"
    assert ("Info", f"Paint 1\u21929: {made}") in said

    # on the failing layer alone the run is cancelled, still with the reason
    text = cancelled(layers="ACTIVE", method="CURVATURE_INTERPOLATION")
    assert text.startswith("Nothing to in-between: Ink 1\u21929: the morph failed (FloatingPointError")
    assert gp_data.snapshot(obj) == after


def test_the_writer_lets_each_in_between_go_once_written(shot, addon, monkeypatch):
    """A big run must not hold its frames twice (ours and Blender's) at the end: the writer lets
    each computed frame go as soon as it is written."""
    writer = importlib.import_module(f"{addon.__name__}.operators.writer")
    real, held = writer.write_all, []

    def spy(data, morphed_list, **options):
        written = real(data, morphed_list, **options)
        held.extend(frame for morphed in morphed_list for frame in morphed.frames if frame is not None)
        return written

    monkeypatch.setattr(writer, "write_all", spy)
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert gp_data.frame_numbers(shot.data.layers["Ink"]) == list(range(1, 10))
    assert not held


def test_a_failed_write_leaves_the_layer_as_it_was(shot, addon, monkeypatch):
    layer = shot.data.layers["Ink"]
    assert bpy.ops.ballmorph.inbetween(frame_count=3) == {"FINISHED"}
    before, before_marks = gp_data.snapshot(shot), gp_data.marks(shot)
    io = importlib.import_module(f"{addon.__name__}.operators.grease_pencil")
    real, calls = io.write_strokes, []

    def failing(drawing, strokes, matrix=None, staging=None):
        calls.append(1)
        if len(calls) == 4:
            raise MemoryError("simulated failure")
        return real(drawing, strokes, matrix, staging)

    monkeypatch.setattr(io, "write_strokes", failing)
    assert cancelled(frame_count=0) == "Writing the in-betweens failed, nothing was changed: simulated failure"
    assert len(calls) >= 4
    assert gp_data.snapshot(shot) == before
    assert gp_data.marks(shot) == before_marks
    monkeypatch.undo()
    # the restored in-betweens are still recognised as the tool's
    assert bpy.ops.ballmorph.inbetween(frame_count=0) == {"FINISHED"}
    assert gp_data.frame_numbers(layer) == list(range(1, 10))
