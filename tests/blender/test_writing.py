"""Writing many in-betweens (issue 41): linear in the frames, with progress, stoppable.

The writer (``operators.writer.write_all``) is given computed frames directly, as the
benchmark (tools/bench_writing.py) gives them: what is tested is Blender's side.
"""

import importlib
from types import SimpleNamespace

import bpy
import gp_data
import numpy as np
import pytest

import ballmorph_core as bm


def _modules(addon):
    return (importlib.import_module(f"{addon.__name__}.operators.{name}") for name in ("writer", "morph"))


def _frames(count, colored=()):
    """``count`` one-stroke in-betweens, each its own shape; those in ``colored`` with a vertex colour."""
    x = np.linspace(0.0, 1.0, 7)
    out = []
    for k in range(count):
        colors = np.zeros((7, 4)) + ([0.2, 0.4, 0.6, 1.0] if k in colored else 0.0)
        out.append(bm.StrokeSet.from_strokes([np.c_[x, np.zeros(7), k * x * x]], vertex_color=[colors]))
    return out


def _item(addon, obj, targets, colored=()):
    _, morph = _modules(addon)
    interval = SimpleNamespace(targets=np.asarray(targets), replace=[])
    return morph.Morphed(obj.data.layers["Ink"], interval, _frames(len(targets), colored))


def test_every_frame_gets_its_own_strokes_and_attributes_and_no_scratch_frame_stays(shot, addon):
    """Each frame is filled in one scratch drawing and copied: every copy is its own drawing,
    holds exactly its strokes, and carries a vertex colour only where its strokes have one."""
    writer, _ = _modules(addon)
    io = importlib.import_module(f"{addon.__name__}.operators.grease_pencil")
    item = _item(addon, shot, [2, 3, 4, 5], colored={1})
    expected = list(item.frames)
    filled, real = [], io.write_strokes

    def spy(drawing, strokes, **options):
        filled.append(drawing.as_pointer())
        return real(drawing, strokes, **options)

    io.write_strokes = spy
    try:
        assert writer.write_all(shot.data, [item]) == 4
    finally:
        io.write_strokes = real
    # One drawing filled for all (foreach_set costs as many drawings as precede the one written:
    # each new frame's own, the last, made writing quadratic in the frames).
    assert len(filled) == 4 and len(set(filled)) == 1, f"{len(set(filled))} drawings filled for 4 frames"
    layer = shot.data.layers["Ink"]
    assert gp_data.frame_numbers(layer) == [1, 2, 3, 4, 5, 9], "the scratch frame was left behind"
    other = shot.data.layers.new("Fresh")
    for number, strokes in zip([2, 3, 4, 5], expected):
        frame = gp_data.frame_at(layer, number)
        assert frame.keyframe_type == "BREAKDOWN" and not frame.select
        assert frame.drawing.user_count == 1, f"frame {number} shares its drawing"
        np.testing.assert_allclose(gp_data.read_strokes(frame.drawing).positions, strokes.positions, atol=1e-6)
        # Byte for byte what writing into a new frame's own drawing gives.
        fresh = other.frames.new(number).drawing
        io.write_strokes(fresh, strokes)
        assert gp_data.read_raw(frame.drawing) == gp_data.read_raw(fresh), f"frame {number} differs"
        has_color = frame.drawing.attributes.get("vertex_color") is not None
        assert has_color == (number == 3), f"frame {number}: vertex_color {'kept' if has_color else 'lost'}"
    assert sorted(gp_data.marks(shot)["Ink"]) == ["2", "3", "4", "5"]


def test_progress_is_reported_and_ends_at_the_total(shot, addon):
    writer, _ = _modules(addon)
    calls = []
    item = _item(addon, shot, list(range(10, 260)))
    assert writer.write_all(shot.data, [item], progress=lambda done, total: calls.append((done, total))) == 250
    assert calls[-1] == (250, 250)
    assert all(total == 250 for _, total in calls) and [d for d, _ in calls] == sorted(d for d, _ in calls)
    assert 50 <= len(calls) <= writer.PROGRESS_STEPS + 1, f"{len(calls)} progress calls for 250 frames"


@pytest.mark.parametrize("stop", [KeyboardInterrupt, MemoryError])
def test_a_stop_in_the_middle_leaves_nothing_half_written(shot, addon, stop):
    """Ctrl+C (or the progress callback stopping the run) rolls back as a failure does: the
    layers, their frames and the record of generated frames are as they were."""
    writer, _ = _modules(addon)
    assert bpy.ops.ballmorph.inbetween(frame_count=3) == {"FINISHED"}
    before, before_marks = gp_data.snapshot(shot), gp_data.marks(shot)
    item = _item(addon, shot, list(range(20, 520)))

    def progress(done, total):
        if done >= 200:
            raise stop()

    with pytest.raises(stop):
        writer.write_all(shot.data, [item], progress=progress)
    assert gp_data.snapshot(shot) == before
    assert gp_data.marks(shot) == before_marks


class _Recorder:
    """A window manager that records its progress calls."""

    def __init__(self):
        self.calls = []

    def __getattr__(self, name):
        return lambda *args: self.calls.append((name, *args))


def test_the_operator_shows_the_writing_on_the_progress_indicator(addon):
    inbetween = importlib.import_module(f"{addon.__name__}.operators.inbetween")
    window = _Recorder()
    progress = inbetween._WindowProgress(window)
    for done in (0, 150, 300):
        progress.writing(done, 300)
    assert window.calls == [
        ("progress_begin", 0, 300),
        ("progress_update", 0),
        ("progress_update", 150),
        ("progress_update", 300),
        ("progress_end",),
    ]


def test_the_command_line_says_how_far_a_long_write_is(addon, capfd):
    cli = importlib.import_module(f"{addon.__name__}.cli")
    progress = cli._StderrProgress("Shot")
    for done in range(0, 5001, 50):
        progress.writing(done, 5000)
    lines = [line for line in capfd.readouterr().err.splitlines() if "writing frames" in line]
    assert 10 <= len(lines) <= 12 and lines[-1].endswith("Shot: writing frames 5000/5000"), lines
    progress.writing(10, 20)  # a short write says nothing
    assert "writing frames" not in capfd.readouterr().err
