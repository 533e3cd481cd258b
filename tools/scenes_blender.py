"""The scenes of tests/fixtures/scenes/ through Blender's own Interpolate, next to the core and the baseline.

    $(tools/bootstrap.sh 5.0.1) tools/scenes_blender.py [NAME_PART ...]

Runs inside ``bpy`` (Blender as a module; no add-on needed): writes each scene's keys on frames
1 and 9 with the Blender tests' raw helpers (tests/blender/gp_data.py), runs
``grease_pencil.interpolate_sequence`` (linear, every frame between), reads frames 2..8 back and
prints ``scene | figure | ours | Blender | baseline | goal``: the core, Blender's real Interpolate,
and the numpy imitation of it (:func:`scenes.baseline_inbetween`). Exits 0.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TESTS = os.path.join(os.path.dirname(HERE), "tests")
sys.path[:0] = [HERE, os.path.dirname(HERE), os.path.join(TESTS, "fixtures"), os.path.join(TESTS, "blender")]

import bpy  # noqa: E402
import gp_data  # noqa: E402
import scenes  # noqa: E402
from scenes_report import print_table  # noqa: E402


def blender_interpolate(scene):
    """Frames 2..8 of Blender's own Interpolate on the scene's keys (drawings)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    for number, k in zip((1, 9), scene.keys):
        gp_data.add_key(layer, number, list(k.strokes), cyclic=list(k.cyclic))
    bpy.context.scene.frame_current = 1
    with gp_data.view3d_override():
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.grease_pencil.interpolate_sequence()
        bpy.ops.object.mode_set(mode="OBJECT")
    frames = []
    for number in range(2, 9):
        frame = gp_data.frame_at(layer, number)
        frames.append(scenes.as_drawing(gp_data.read_strokes(frame.drawing)) if frame else ())
    keys = tuple(scenes.as_drawing(gp_data.read_strokes(gp_data.frame_at(layer, n).drawing)) for n in (1, 9))
    return keys, frames


def _cell(figure):
    return figure.shown + ("" if figure.ok else " ✗")


def main(argv):
    chosen = [s for n, s in scenes.SCENES.items() if not argv or any(a in n for a in argv)]
    lines = [("scene", "figure", "ours", "Blender", "baseline", "goal")]
    beats = loses = 0
    for scene in chosen:
        keys, blender_frames = blender_interpolate(scene)
        ours = scene.figures(scene.key_drawings(), scene.run_core()[0])
        theirs = scene.figures(keys, blender_frames)
        base = scene.figures(scene.key_drawings(), scene.run_baseline())
        for n, (o, b, m) in enumerate(zip(ours, theirs, base)):
            beats += o.ok and not b.ok and not o.informative
            loses += b.ok and not o.ok and not o.informative
            lines.append((scene.name if n == 0 else "", o.name, _cell(o), _cell(b), _cell(m), o.goal))
    print_table(lines)
    print(f"\nfigures the core meets and Blender's Interpolate misses: {beats}; the reverse: {loses}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
