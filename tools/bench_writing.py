"""How writing in-betweens grows with the number of frames (issue 41: linear), inside bpy.

One layer, keys ``frames`` apart with one small stroke (10 points), and the writer
(``operators.writer.write_all``) asked to write every frame between them: the time of
Blender's own data-block work per frame, apart from the core's morph (the frames are given).
Beside it, in the same process and on the same keys: Blender's ``layer.frames.copy`` alone, as
many times (the part of the writer no add-on can avoid through the Python API), and Blender's
own ``grease_pencil.interpolate_sequence`` writing the same frames.

Usage::

    $(tools/bootstrap.sh 5.0.1) tools/bench_writing.py [--frames 2000,4000,8000,16000,32000] [--profile N] [--markdown]
"""

import argparse
import cProfile
import importlib.util
import os
import pstats
import sys
import time
from types import SimpleNamespace

import bpy
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FRAMES = (2000, 4000, 8000, 16000, 32000)
#: The goal: time(2 F) / time(F) at most this (issue 41).
GROWTH_GOAL = 2.2


def _addon():
    """The add-on package from this checkout (its modules import each other relatively)."""
    spec = importlib.util.spec_from_file_location(
        "ballmorph_bench_addon", os.path.join(ROOT, "__init__.py"), submodule_search_locations=[ROOT]
    )
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return tuple(importlib.import_module(f"{spec.name}.operators.{name}") for name in ("writer", "morph"))


def _scene(frames):
    """A fresh Grease Pencil object whose layer has keys at 1 and ``frames + 1``: ``(object,
    data, layer)``."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    collection = bpy.data.grease_pencils_v3 if hasattr(bpy.data, "grease_pencils_v3") else bpy.data.grease_pencils
    data = collection.new("Bench")
    obj = bpy.data.objects.new("Bench", data)
    bpy.context.scene.collection.objects.link(obj)
    layer = data.layers.new("Ink")
    for number, bend in ((1, 1.0), (frames + 1, 0.5)):
        drawing = layer.frames.new(number).drawing
        drawing.add_strokes([10])
        x = np.linspace(0.0, 1.0, 10)
        points = np.c_[x, np.zeros(10), bend * x * x].astype(np.float32)
        drawing.attributes["position"].data.foreach_set("vector", points.ravel())
    return obj, data, layer


def _stroke(core, t):
    x = np.linspace(0.0, 1.0, 10)
    return core.StrokeSet.from_strokes([np.c_[x, np.zeros(10), (1.0 - t) * x * x]])


def write_time(writer, morph, frames, progress=None):
    """CPU seconds to write ``frames - 1`` in-betweens (float): the process's, not the wall
    clock's, so other work on a shared machine does not count (Blender writes on one thread)."""
    _obj, data, layer = _scene(frames)
    core = sys.modules["ballmorph_bench_addon.ballmorph_core"]
    targets = np.arange(2, frames + 1)
    interval = SimpleNamespace(targets=targets, replace=[])
    frames_made = [_stroke(core, t) for t in (targets - 1) / frames]
    item = morph.Morphed(layer, interval, frames_made)
    start = time.process_time()
    written = writer.write_all(data, [item], **({} if progress is None else {"progress": progress}))
    seconds = time.process_time() - start
    assert written == len(targets), (written, len(targets))
    return seconds


def copy_time(frames):
    """CPU seconds of Blender's ``layer.frames.copy`` alone, ``frames - 1`` times from one
    one-stroke frame, last to first as the writer does (float): the part no add-on can avoid."""
    _obj, _data, layer = _scene(frames)
    start = time.process_time()
    for number in range(frames, 1, -1):
        layer.frames.copy(1, number)
    return time.process_time() - start


def builtin_time(frames):
    """CPU seconds of Blender's own ``grease_pencil.interpolate_sequence`` (every frame between
    the same keys, step 1, linear) on the same drawing (float)."""
    obj, _data, layer = _scene(frames)
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.context.view_layer.objects.active = obj
        obj.select_set(True)
        bpy.ops.object.mode_set(mode="EDIT")
        start = time.process_time()
        bpy.ops.grease_pencil.interpolate_sequence("EXEC_DEFAULT", step=1, layers="ACTIVE", type="LINEAR")
        seconds = time.process_time() - start
        bpy.ops.object.mode_set(mode="OBJECT")
    assert len(layer.frames) == frames + 1, (len(layer.frames), frames + 1)
    return seconds


def _ratios(times):
    """Each time over the one before it (the first blank), as table cells."""
    return [""] + [f"{b / a:.2f}" for a, b in zip(times, times[1:])]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", default=",".join(map(str, FRAMES)))
    parser.add_argument("--profile", type=int, default=0, help="profile one run of this many frames")
    parser.add_argument("--markdown", action="store_true")
    args = parser.parse_args(argv)
    writer, morph = _addon()
    if args.profile:
        profile = cProfile.Profile()
        profile.enable()
        write_time(writer, morph, args.profile)
        profile.disable()
        pstats.Stats(profile).sort_stats("tottime").print_stats(15)
        return 0
    counts = [int(v) for v in args.frames.split(",")]
    times = [write_time(writer, morph, n) for n in counts]
    copies = [copy_time(n) for n in counts]
    builtin = [builtin_time(n) for n in counts]
    rows = [
        "| frames | writer (CPU s) | ratio | of which `frames.copy` alone | ratio "
        "| Blender's Interpolate Sequence | ratio |",
        "|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for n, s, r, c, cr, b, br in zip(
        counts, times, _ratios(times), copies, _ratios(copies), builtin, _ratios(builtin), strict=True
    ):
        rows.append(f"| {n:,} | {s:.2f} | {r} | {c:.2f} | {cr} | {b:.2f} | {br} |")
    print("\n".join(rows) if args.markdown else "\n".join(r.replace("|", " ") for r in rows))
    worst = max((b / a for a, b in zip(times, times[1:])), default=0.0)
    print(f"worst ratio per doubling {worst:.2f} (goal <= {GROWTH_GOAL})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
