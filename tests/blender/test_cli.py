"""``blender -c ballmorph`` (cli.main) on saved files: what it writes, saves, prints and returns.

The pip bpy has no Blender binary to run ``blender -c`` with, so the tests call the command's
handler, ``cli.main(argv)``, as Blender does (with the arguments after the command's name), in
this process and in a fresh one; and they check that enabling the add-on registers the command
with Blender and disabling it removes it.
"""

import hashlib
import importlib
import json
import os
import subprocess
import sys

import bpy
import gp_data
import numpy as np
import pytest
from conftest import MODULE, ROOT, disable_addon, enable_addon


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def cli():
    return importlib.import_module(f"{MODULE}.cli")


def run(capfd, *argv):
    """``blender -c ballmorph ARGV...``: exit status, stdout, stderr."""
    capfd.readouterr()
    code = cli().main([str(a) for a in argv])
    out, err = capfd.readouterr()
    return code, out, err


def run_json(capfd, *argv):
    code, out, err = run(capfd, *argv, "--json")
    return code, json.loads(out), err


def build_file(path, locked=False):
    """A saved file: 'Drawing' (layer Ink: keys 1, 5, 9) and 'Other' (Ink: keys 1, 4; Paint: keys
    2, 6, or locked; Notes: one key)."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)  # keeps the preferences: the add-on
    drawing = gp_data.new_object("Drawing")
    ink = drawing.data.layers["Ink"]
    gp_data.add_key(ink, 1, [gp_data.loop(1.0), gp_data.arc(0.5)], cyclic=[True, False])
    gp_data.add_key(ink, 5, [gp_data.loop(1.2, centre=(0.1, 0)), gp_data.arc(0.1)], cyclic=[True, False])
    gp_data.add_key(ink, 9, [gp_data.loop(1.3, wobble=0.08), gp_data.arc(-0.3)], cyclic=[True, False])
    other = gp_data.new_object("Other", layers=("Ink", "Paint", "Notes"))
    gp_data.add_key(other.data.layers["Ink"], 1, [gp_data.arc(0.3)])
    gp_data.add_key(other.data.layers["Ink"], 4, [gp_data.arc(-0.3)])
    gp_data.add_key(other.data.layers["Paint"], 2, [gp_data.loop(0.5)], cyclic=[True])
    gp_data.add_key(other.data.layers["Paint"], 6, [gp_data.loop(0.7)], cyclic=[True])
    gp_data.add_key(other.data.layers["Notes"], 1, [gp_data.arc(0.2)])
    other.data.layers["Paint"].lock = locked
    cube = bpy.data.objects.new("Cube", bpy.data.meshes.new("Cube"))
    bpy.context.scene.collection.objects.link(cube)
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    return path


@pytest.fixture
def saved(addon, tmp_path):
    return build_file(tmp_path / "shot.blend")


def frames_of(path):
    """Every frame of every Grease Pencil object in a saved file (gp_data.snapshot)."""
    bpy.ops.wm.open_mainfile(filepath=str(path))
    return {obj.name: gp_data.snapshot(obj) for obj in bpy.data.objects if obj.type == "GREASEPENCIL"}


# -- registration ---------------------------------------------------------------------------------


def _duplicate_warning(capfd):
    """Register 'ballmorph' once more: Blender warns if the id is taken. Whether it did."""
    capfd.readouterr()
    handle = bpy.utils.register_cli_command("ballmorph", lambda argv: 0)
    bpy.utils.unregister_cli_command(handle)
    out, err = capfd.readouterr()
    return 'registered duplicate command "ballmorph"' in out + err


def test_the_command_is_registered_on_register_and_removed_on_unregister(addon, capfd, monkeypatch):
    assert _duplicate_warning(capfd)  # taken: the add-on registered it
    handle = cli()._handle
    disable_addon()
    assert not _duplicate_warning(capfd)  # free again
    with pytest.raises(ValueError, match="already been removed"):
        bpy.utils.unregister_cli_command(handle)

    calls = []
    real = bpy.utils.register_cli_command

    def spy(command, execute):
        calls.append((command, execute))
        return real(command, execute)

    monkeypatch.setattr(bpy.utils, "register_cli_command", spy)
    enable_addon()
    assert calls == [("ballmorph", cli().main)]
    assert _duplicate_warning(capfd)


# -- what it writes and saves ------------------------------------------------------------------------


def test_output_writes_what_the_operator_writes_and_leaves_the_input_untouched(saved, tmp_path, capfd):
    before = sha(saved)
    out_path = tmp_path / "out.blend"
    code, summary, err = run_json(capfd, saved, "--output", out_path, "--object", "Drawing", "--frame-count", "1")
    assert code == 0, err
    assert sha(saved) == before
    assert not os.path.exists(f"{saved}1")
    assert summary["saved"] and summary["output"] == str(out_path) and summary["backup"] is None
    assert summary["frames_written"] == 2
    (drawing,) = summary["objects"]
    assert drawing["layers"][0]["intervals"] == [
        {"keys": [1, 5], "frames": [3], "method": "circular-ball", "replaced": [], "left_untouched": []},
        {"keys": [5, 9], "frames": [7], "method": "circular-ball", "replaced": [], "left_untouched": []},
    ]
    written = frames_of(out_path)

    # The operator in the input file, with every key selected, writes the same frames.
    original = frames_of(saved)
    obj = bpy.data.objects["Drawing"]
    bpy.context.view_layer.objects.active = obj
    for frame in obj.data.layers["Ink"].frames:
        frame.select = True
    assert bpy.ops.ballmorph.inbetween(frame_count=1) == {"FINISHED"}
    assert written["Drawing"] == gp_data.snapshot(obj)
    assert written["Other"] == original["Other"]  # not chosen: not touched
    assert sorted(written["Drawing"]["Ink"]) == [1, 3, 5, 7, 9]
    assert all(written["Drawing"]["Ink"][n] == original["Drawing"]["Ink"][n] for n in (1, 5, 9))


def test_in_place_keeps_the_previous_file_as_blend1_whatever_the_preferences_say(saved, capfd):
    before = sha(saved)
    bpy.context.preferences.filepaths.save_version = 0  # no backups, says the animator
    code, summary, err = run_json(capfd, saved, "--object", "Drawing")
    assert code == 0, err
    assert sha(f"{saved}1") == before  # IN.blend1 is the file as it was
    assert summary["backup"] == f"{saved}1" and summary["output"] == str(saved)
    assert bpy.context.preferences.filepaths.save_version == 0  # put back
    assert sorted(frames_of(saved)["Drawing"]["Ink"]) == list(range(1, 10))


def test_every_key_interval_of_every_object_and_what_is_skipped_is_said_per_object_and_layer(addon, tmp_path, capfd):
    path = build_file(tmp_path / "shot.blend", locked=True)
    code, summary, err = run_json(capfd, path, "--output", tmp_path / "out.blend")
    assert code == 3  # saved, with a warning: the locked layer was skipped
    objects = {entry["name"]: entry for entry in summary["objects"]}
    assert list(objects) == ["Drawing", "Other"]  # every Grease Pencil object, not the cube
    layers = {name: {layer["name"]: layer for layer in entry["layers"]} for name, entry in objects.items()}
    assert [i["keys"] for i in layers["Drawing"]["Ink"]["intervals"]] == [[1, 5], [5, 9]]
    assert layers["Drawing"]["Ink"]["frames_written"] == 6
    assert [i["frames"] for i in layers["Other"]["Ink"]["intervals"]] == [[2, 3]]
    paint = layers["Other"]["Paint"]
    assert paint["frames_written"] == 0 and paint["intervals"] == []
    assert paint["reports"] == [
        {
            "level": "warning",
            "text": "layer 'Paint' is locked: unlock it to in-between it",
            "kind": "layer-skipped",
            "layer": "Paint",
            "frames": [],
            "strokes": [],
        }
    ]
    notes = layers["Other"]["Notes"]  # one key: nothing to do there, and every layer was asked for
    assert [(r["level"], r["text"], r["kind"], r["layer"]) for r in notes["reports"]] == [
        ("info", "layer 'Notes' has 1 keyframe(s): draw a second key to in-between", "keys", "Notes")
    ]
    assert summary["frames_written"] == 8 and summary["saved"]
    written = frames_of(tmp_path / "out.blend")
    assert sorted(written["Other"]["Paint"]) == [2, 6]
    assert sorted(written["Other"]["Ink"]) == [1, 2, 3, 4]
    assert "ballmorph: Drawing: Ink 5\u21929 (2/2)" in err  # progress on stderr

    # unlocked, the same file in-betweens completely
    path = build_file(tmp_path / "unlocked.blend")
    code, summary, err = run_json(capfd, path, "--output", tmp_path / "out2.blend", "--layers", "all")
    assert code == 0, err
    assert summary["frames_written"] == 11


def test_active_layer_only_warns_about_a_layer_with_nothing_to_do(saved, tmp_path, capfd):
    code, summary, _ = run_json(capfd, saved, "--output", tmp_path / "out.blend", "--layers", "active")
    # Other's active layer is Ink (its first): in-betweened; Drawing's too
    assert code == 0
    assert [[layer["name"] for layer in entry["layers"]] for entry in summary["objects"]] == [["Ink"], ["Ink"]]
    bpy.ops.wm.open_mainfile(filepath=str(saved))
    obj = bpy.data.objects["Other"]
    obj.data.layers.active = obj.data.layers["Notes"]
    bpy.ops.wm.save_mainfile()
    code, summary, _ = run_json(capfd, saved, "--output", tmp_path / "out.blend", "--layers", "active")
    assert code == 3
    assert summary["objects"][1]["layers"][0]["reports"][0]["level"] == "warning"


def test_a_frame_the_animator_drew_is_a_key_in_betweened_around_and_never_modified(saved, capfd):
    bpy.ops.wm.open_mainfile(filepath=str(saved))
    layer = bpy.data.objects["Drawing"].data.layers["Ink"]
    frame = gp_data.add_key(layer, 7, [gp_data.loop(1.25), gp_data.arc(-0.1)], cyclic=[True, False])
    frame.keyframe_type = "BREAKDOWN"  # drawn by hand, typed as a breakdown: still the animator's
    bpy.ops.wm.save_mainfile()
    drawn = gp_data.read_raw(gp_data.frame_at(layer, 7).drawing)
    code, summary, _ = run_json(capfd, saved, "--object", "Drawing", "--frame-count", "3")
    # keys 1, 5, 7, 9: three intervals, and nothing between them to skip
    assert code == 0
    intervals = summary["objects"][0]["layers"][0]["intervals"]
    assert [(i["keys"], i["frames"]) for i in intervals] == [([1, 5], [2, 3, 4]), ([5, 7], [6]), ([7, 9], [8])]
    layer = bpy.data.objects["Drawing"].data.layers["Ink"]
    assert gp_data.read_raw(gp_data.frame_at(layer, 7).drawing) == drawn


def test_running_again_replaces_only_its_own_in_betweens(saved, capfd):
    code, first, _ = run_json(capfd, saved, "--frame-count", "1")
    assert code == 0
    after_first = frames_of(saved)
    code, second, _ = run_json(capfd, saved, "--frame-count", "1")
    assert code == 0
    assert frames_of(saved) == after_first
    intervals = second["objects"][0]["layers"][0]["intervals"]
    assert [i["replaced"] for i in intervals] == [[3], [7]]
    assert first["frames_written"] == second["frames_written"]


def test_the_text_summary_on_stdout_and_blenders_own_messages_on_stderr(saved, tmp_path, capfd):
    code, out, err = run(capfd, saved, "--output", tmp_path / "out.blend", "--method", "linear-ball")
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0] == f"{saved}: 11 frame(s) written, 0 warning(s); saved {tmp_path / 'out.blend'}"
    assert "Drawing: 6 frame(s) on 1 layer(s)" in lines
    assert "  Info: Ink 1\u21925: 3 in-between(s) on frame(s) 2\u20134 (Linear Ball-morph)" in lines
    assert "  Info: layer 'Notes' has 1 keyframe(s): draw a second key to in-between" in lines
    assert "Read blend" not in out and "Saved" not in out
    assert "Read blend" in err and "ballmorph: saving" in err


def test_options_from_the_operators_table(saved, tmp_path, capfd):
    argv = ["--easing-type", "quad", "--easing", "ease-in-out", "--carrier", "rigid", "--matching", "index"]
    code, summary, _ = run_json(capfd, saved, "--output", tmp_path / "o.blend", *argv, "--unmatched", "hold")
    assert code == 0
    assert summary["options"] == {
        "method": "circular-ball",
        "frame_count": 0,
        "timing_chart": "",
        "easing_type": "quad",
        "easing": "ease-in-out",
        "back": 1.702,
        "amplitude": 0.15,
        "period": 0.15,
        "favor": 0.0,
        "layers": "all",
        "selected_only": False,
        "carrier": "rigid",
        "matching": "index",
        "unmatched": "hold",
        "key_motion": "smooth",
    }
    help_text = run(capfd, "--help")
    assert help_text[0] == 0
    for flag in ("--method", "--frame-count", "--layers", "--selected-only", "--carrier", "--easing-type"):
        assert flag in help_text[1]
    assert "--favor X" in help_text[1] and "--timing-chart TEXT" in help_text[1]


def test_the_custom_type_reads_the_curve_of_the_files_scene(addon, tmp_path, capfd):
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    gp_data.ensure_interpolate_curve([(0.0, 0.0), (0.5, 0.8), (1.0, 1.0)])
    obj = gp_data.new_object()
    gp_data.add_key(obj.data.layers["Ink"], 1, [gp_data.loop(1.0)], cyclic=[True])
    gp_data.add_key(obj.data.layers["Ink"], 3, [gp_data.loop(2.0)], cyclic=[True])
    path = tmp_path / "custom.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    out = tmp_path / "o.blend"
    code, summary, _ = run_json(capfd, path, "--output", out, "--easing-type", "custom", "--carrier", "none")
    assert code == 0 and summary["options"]["easing_type"] == "custom"
    bpy.ops.wm.open_mainfile(filepath=str(out))
    layer = bpy.data.objects["Drawing"].data.layers["Ink"]
    positions = gp_data.read_strokes(gp_data.frame_at(layer, 2).drawing).positions
    assert np.mean(np.hypot(positions[:, 0], positions[:, 2])) == pytest.approx(1.8, abs=1e-3)  # the curve's 0.8


@pytest.mark.parametrize(
    ("argv", "said"),
    [(["--back", "-1"], "expected a number of at least 0"), (["--period", "nan"], "expected a number, got 'nan'")],
)
def test_the_types_settings_are_checked_on_the_command_line(saved, capfd, argv, said):
    code, _, err = run(capfd, saved, *argv)
    assert code == 2 and said in err


def test_favor_and_a_timing_chart_and_the_chart_kept_for_the_next_run(saved, tmp_path, capfd):
    out = tmp_path / "o.blend"
    code, summary, _ = run_json(capfd, saved, "--output", out, "--object", "Drawing", "--timing-chart", "0.2,0.8")
    assert code == 0 and summary["options"]["timing_chart"] == "0.2,0.8"
    assert [i["frames"] for i in summary["objects"][0]["layers"][0]["intervals"]] == [[2, 4], [6, 8]]
    code, summary, _ = run_json(capfd, out, "--object", "Drawing", "--favor", "-0.5")
    assert code == 0 and summary["options"]["favor"] == -0.5
    assert [i["frames"] for i in summary["objects"][0]["layers"][0]["intervals"]] == [[2, 4], [6, 8]]
    said = [r["text"] for r in summary["objects"][0]["layers"][0]["reports"]]
    assert "Ink 1\u21925: timed by the chart 0.2 0.8 kept from an earlier run on these keys" in " ".join(said)
    bpy.ops.wm.open_mainfile(filepath=str(out))
    assert bpy.data.objects["Drawing"].data["ballmorph_timing_charts"].to_dict() == {
        "Ink:1-5": "0.2 0.8",
        "Ink:5-9": "0.2 0.8",
    }


def test_a_timing_chart_too_long_for_an_interval_writes_nothing_for_that_object(saved, tmp_path, capfd):
    # Other's Ink keys are on frames 1 and 4: two frames between them, for three fractions.
    out = tmp_path / "o.blend"
    code, summary, _ = run_json(capfd, saved, "--output", out, "--timing-chart", "0.25 0.5 0.75")
    assert code == 3
    other = next(o for o in summary["objects"] if o["name"] == "Other")
    assert other["frames_written"] == 0
    assert "Ink 1\u21924: Timing Chart: 3 fractions but only 2 frame(s) between the keys" in other["error"]
    assert next(o for o in summary["objects"] if o["name"] == "Drawing")["frames_written"] == 6


# -- bad arguments, unreadable files, nothing to do ------------------------------------------------


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        ([], "the following arguments are required: IN.blend"),
        (["{in}", "--bogus"], "unrecognized arguments: --bogus"),
        (["{in}", "--method", "bogus"], "argument --method: invalid choice: 'bogus'"),
        (["{in}", "--method", "CIRCULAR_BALL"], "invalid choice: 'CIRCULAR_BALL' (choose from 'circular-ball'"),
        (["{in}", "--method", "composite-ball"], "invalid choice: 'composite-ball'"),  # not an operator morph
        (["{in}", "--frame-count", "-1"], "expected a whole number of at least 0, got '-1'"),
        (["{in}", "--frame-count", "two"], "expected a whole number of at least 0, got 'two'"),
        (["{in}", "--layers", "some"], "argument --layers: invalid choice: 'some'"),
        (["{in}", "--favor", "2"], "argument --favor: expected a number from -1 to 1, got '2'"),
        (["{in}", "--favor", "nan"], "argument --favor: expected a number from -1 to 1, got 'nan'"),
        (["{in}", "--timing-chart", "0.5 0.2"], "Timing Chart: 0.2 comes after 0.5 (the fractions must rise)"),
        (["{in}", "--timing-chart", "soon"], "Timing Chart: 'soon' is not a number"),
        (["{dir}/missing.blend"], "cannot read {dir}/missing.blend: no such file"),
        (["{dir}/notes.blend"], 'cannot read {dir}/notes.blend: File format is not supported in file "'),
        (["{in}", "--object", "Nobody"], "has no object of that name (its Grease Pencil objects: 'Drawing', 'Other')"),
        (["{in}", "--object", "Drawing", "--object", "Cube"], "--object 'Cube' is a mesh, not a Grease Pencil object"),
        (["{in}", "--output", "{in}"], "--output names the input file: leave --output out to save in place"),
        (["{in}", "--output", "{dir}/nowhere/out.blend"], "cannot write {dir}/nowhere/out.blend: no directory"),
        (["{in}", "--output", ""], "--output is empty: give a file name, or leave --output out to save IN.blend in"),
        (["{in}", "--output", "{dir}"], "cannot write {dir}: it is a directory; give a file name"),
        (["{in}", "--json-file", "{dir}"], "cannot write {dir}: it is a directory; give a file name"),
    ],
    ids=[
        "no-file",
        "unknown-option",
        "bad-method",
        "blender-id",
        "core-only-method",
        "negative-count",
        "not-a-number",
        "bad-layers",
        "favor-out-of-range",
        "favor-nan",
        "chart-descending",
        "chart-not-a-number",
        "missing-file",
        "not-a-blend",
        "no-such-object",
        "not-grease-pencil",
        "output-is-input",
        "no-output-directory",
        "empty-output",
        "output-is-a-directory",
        "json-file-is-a-directory",
    ],
)
def test_bad_arguments_exit_2_with_a_clear_message_and_save_nothing(saved, tmp_path, capfd, argv, said):
    (tmp_path / "notes.blend").write_text("not a blend file\n")
    before = sha(saved)
    argv = [a.format(**{"in": saved, "dir": tmp_path}) for a in argv]
    code, out, err = run(capfd, *argv)
    assert code == 2
    assert said.format(**{"in": saved, "dir": tmp_path}) in err, err
    assert "Traceback" not in err + out
    assert out == ""
    assert sha(saved) == before and not os.path.exists(f"{saved}1")
    assert sorted(os.listdir(tmp_path)) == ["notes.blend", "shot.blend"]


@pytest.mark.parametrize("output", ["", "{dir}"], ids=["empty", "directory"])
def test_an_output_that_cannot_be_a_file_is_refused_before_anything_is_read(saved, tmp_path, capfd, output):
    before = sha(saved)
    code, out, err = run(capfd, saved, "--output", output.format(dir=tmp_path), "--json")
    assert code == 2
    assert json.loads(out)["error"]["kind"] == "bad-arguments"
    assert "ballmorph: reading" not in err, "the input was opened before the output was checked"
    assert sha(saved) == before and sorted(os.listdir(tmp_path)) == ["shot.blend"]


def test_a_file_without_grease_pencil_exits_3_and_is_not_saved(addon, tmp_path, capfd):
    path = tmp_path / "empty.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    before = sha(path)
    code, summary, _ = run_json(capfd, path)
    assert code == 3
    assert [(note["level"], note["text"]) for note in summary["notes"]] == [
        ("warning", f"{path} has no Grease Pencil object: nothing to do"),
        ("info", f"nothing was written: {path} was not saved"),
    ]
    assert not summary["saved"] and sha(path) == before and not os.path.exists(f"{path}1")


def test_linked_duplicates_are_in_betweened_once(saved, tmp_path, capfd):
    bpy.ops.wm.open_mainfile(filepath=str(saved))
    twin = bpy.data.objects.new("Twin", bpy.data.objects["Drawing"].data)
    bpy.context.scene.collection.objects.link(twin)
    bpy.ops.wm.save_mainfile()
    code, summary, _ = run_json(capfd, saved, "--object", "Twin", "--object", "Drawing", "--frame-count", "1")
    assert code == 0
    assert [(o["name"], o["frames_written"], o["same_data_as"]) for o in summary["objects"]] == [
        ("Twin", 2, None),
        ("Drawing", 0, "Twin"),
    ]


# -- exit codes, --json on every exit, --version, the Windows C library --------------------------------


def test_the_exit_codes_are_the_documented_ones(addon, capfd):
    module = cli()
    assert (module.OK, module.FAILED, module.BAD_ARGUMENTS, module.WARNINGS) == (0, 1, 2, 3)
    code, out, _ = run(capfd, "--help")
    assert code == 0
    flat = " ".join(out.split())
    for status, meaning in module.EXIT_CODES.items():
        assert f"{status} {meaning}" in flat, f"the help does not document exit status {status}"
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    for status in module.EXIT_CODES:
        assert f"| {status} |" in readme, f"the README's exit status table lacks {status}"


def test_help_texts_are_sentences_alike(addon):
    helps = [action.help for action in cli().parser()._actions if action.help]
    assert helps and all(text[0].isupper() and not text.endswith(".") for text in helps), helps


def test_version_prints_the_manifests_version(addon, capfd):
    import tomllib

    with open(os.path.join(ROOT, "blender_manifest.toml"), "rb") as f:
        version = tomllib.load(f)["version"]
    code, out, err = run(capfd, "--version")
    assert (code, out) == (0, f"blender -c ballmorph {version}\n"), err


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        (["{dir}/missing.blend"], "no such file"),
        (["--output", "{dir}/out.blend", "{dir}/missing.blend", "--bogus"], "unrecognized arguments"),
    ],
    ids=["missing-file", "bad-argument"],
)
def test_json_says_an_error_as_a_json_object_with_exit_2(addon, tmp_path, capfd, argv, said):
    code, out, err = run(capfd, *[a.format(dir=tmp_path) for a in argv], "--json")
    assert code == 2
    summary = json.loads(out)
    assert summary["exit_code"] == 2 and summary["saved"] is False
    assert summary["input"] == str(tmp_path / "missing.blend")
    assert summary["error"]["kind"] == "bad-arguments" and said in summary["error"]["message"]
    assert said in err


def test_json_file_holds_the_summary_and_stdout_the_text(saved, tmp_path, capfd):
    report = tmp_path / "report.json"
    code, out, _ = run(capfd, saved, "--output", tmp_path / "out.blend", "--json-file", report)
    assert code == 0
    assert out.startswith(f"{saved}: 11 frame(s) written")
    with open(report, encoding="utf-8") as f:
        summary = json.load(f)
    assert summary["exit_code"] == 0 and summary["frames_written"] == 11 and summary["error"] is None
    code, _, _ = run(capfd, tmp_path / "missing.blend", "--json-file", report)
    with open(report, encoding="utf-8") as f:
        assert code == 2 and json.load(f)["error"]["kind"] == "bad-arguments"


def test_json_reports_say_their_kind_layer_frames_and_strokes(addon, tmp_path, capfd):
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    obj = gp_data.new_object("Drawing")
    ink = obj.data.layers["Ink"]
    gp_data.add_key(ink, 1, [gp_data.arc(0.3)])
    gp_data.add_key(ink, 9, [gp_data.arc(-0.3), gp_data.loop(0.3, centre=(2, 0))], cyclic=[False, True])
    path = tmp_path / "extra.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    code, summary, _ = run_json(capfd, path, "--output", tmp_path / "out.blend")
    assert code == 3  # saved, with the warning about the stroke without a partner
    said = summary["objects"][0]["layers"][0]["reports"]
    kinds = {report["kind"] for report in said}
    assert {"written", "morph"} <= kinds, said
    for report in said:
        assert report["layer"] == "Ink" and report["frames"] == [1, 9], report
    warnings = [r for r in said if r["level"] == "warning"]
    assert len(warnings) == 1, f"one stroke without a partner, {len(warnings)} warnings: {warnings}"


def test_windows_c_library_lookup_failing_still_saves_summarises_and_exits_0(saved, tmp_path, capfd, monkeypatch):
    import ctypes

    def windows_cdll(name, *args, **kwargs):
        raise TypeError("expected str, bytes or os.PathLike object, not NoneType")  # CDLL(None) on Windows

    monkeypatch.setattr(ctypes, "CDLL", windows_cdll)
    code, out, err = run(capfd, saved, "--output", tmp_path / "out.blend", "--frame-count", "1")
    assert code == 0, err
    assert out.startswith(f"{saved}: 4 frame(s) written, 0 warning(s); saved {tmp_path / 'out.blend'}"), out
    assert "internal error" not in err
    assert os.path.exists(tmp_path / "out.blend")
    print("stdout is stdout again")
    assert capfd.readouterr().out == "stdout is stdout again\n"


def test_an_internal_error_exits_1_says_so_in_json_and_saves_nothing(saved, tmp_path, capfd, monkeypatch):
    service = importlib.import_module(f"{MODULE}.operators.service")

    def broken(*args, **kwargs):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(service, "inbetween_object", broken)
    before = sha(saved)
    code, out, err = run(capfd, saved, "--json")
    assert code == 1
    summary = json.loads(out)
    assert summary["error"]["kind"] == "internal" and "nothing was saved" in summary["error"]["message"]
    assert "ZeroDivisionError: a bug" in err
    assert sha(saved) == before and not os.path.exists(f"{saved}1")


# -- a fresh process, as Blender runs the command ---------------------------------------------------

SCRIPT = """
import importlib, os, sys, tempfile
import bpy
import addon_utils
bpy.ops.wm.read_factory_settings(use_empty=True)
repo = tempfile.mkdtemp()
os.symlink({root!r}, os.path.join(repo, "ballmorph_inbetween"))
bpy.context.preferences.extensions.repos.new(name="dev", module="cli_dev", custom_directory=repo, source="USER")
addon_utils.enable("bl_ext.cli_dev.ballmorph_inbetween", default_set=True)
code = importlib.import_module("bl_ext.cli_dev.ballmorph_inbetween.cli").main(sys.argv[1:])
# Blender prints after the command, on stdout ("Not freed memory blocks" and the like)
print("Not freed memory blocks: 1, total unfreed memory 0.000000 MB")
os.write(1, b"Error: Not freed memory blocks: 1\\n")
addon_utils.disable("bl_ext.cli_dev.ballmorph_inbetween", default_set=True)  # bpy 4.5 hangs at exit otherwise
sys.exit(code)
"""


def test_in_a_fresh_process_stdout_holds_only_the_summary_and_the_status_is_the_exit_code(saved, tmp_path):
    def command(*argv):
        script = SCRIPT.format(root=ROOT)
        return subprocess.run(
            [sys.executable, "-c", script, *map(str, argv)], capture_output=True, text=True, timeout=300
        )

    done = command(saved, "--output", tmp_path / "out.blend", "--json", "--frame-count", "1")
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)  # nothing else on stdout: Blender's messages went to stderr
    assert "Not freed memory blocks" in done.stderr  # what Blender printed after the JSON
    assert summary["frames_written"] == 4 and summary["exit_code"] == 0
    assert "Read blend" in done.stderr
    assert command(saved, "--frame-count", "-2").returncode == 2
    bad = command(tmp_path / "missing.blend")
    assert bad.returncode == 2 and "no such file" in bad.stderr and "Traceback" not in bad.stderr
