"""The README's picture of the path preview, from the demo's own scene (run by ``make demo``).

With bpy (Blender as a Python module), headless: builds the demo's shots (tools/demo.py, keys
only: nothing is in-betweened), turns the sidebar's *Path Preview* toggle on, and for each shot
asks the add-on for what its 3D-viewport draw handler draws (``operators.preview.PREVIEW``: the
trajectories between the keys around the current frame, in world space). Background mode has
no GPU, so matplotlib draws that same geometry, seen from the front (x, z), over both keys, one
colour per stroke pair as in the viewport, into out/path_preview.png (docs/path_preview.png is a
copy).
"""

import importlib
import os
import sys

import bpy
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from demo import MODULE, OUT, addon_session, build_scene, save_figure

PICTURE = os.path.join(OUT, "path_preview.png")


def _world_strokes(obj, number):
    """The strokes of an object's key ``number`` in world space: list of ((n, 3) points, cyclic)."""
    io = importlib.import_module(f"{MODULE}.operators.grease_pencil")
    layer = obj.data.layers["Ink"]
    frame = next(f for f in layer.frames if f.frame_number == number)
    strokes = io.read_strokes(frame.drawing, io.layer_matrix(layer))
    world = np.array(obj.matrix_world)
    points = strokes.positions @ world[:3, :3].T + world[:3, 3]
    return [(points[strokes.points(i)], bool(strokes.cyclic[i])) for i in range(len(strokes))]


def _keys_around(obj, frame):
    """The two keys the preview spans at ``frame``."""
    numbers = sorted(f.frame_number for f in obj.data.layers["Ink"].frames)
    return max(n for n in numbers if n <= frame), min(n for n in numbers if n > frame)


def _plot_key(ax, strokes, colour, style):
    for points, cyclic in strokes:
        xz = points[:, [0, 2]]
        if cyclic:
            xz = np.vstack([xz, xz[:1]])
        ax.plot(xz[:, 0], xz[:, 1], style, color=colour, lw=1.6, solid_capstyle="round")


def draw_shot(ax, obj, frame, options, core):
    """One shot's keys and trajectories at ``frame``, with the demo's options for it in the sidebar."""
    settings = bpy.context.scene.ballmorph_inbetween
    for name, value in options.items():
        setattr(settings, name, value)
    bpy.context.view_layer.objects.active = obj
    bpy.context.scene.frame_current = frame
    preview = importlib.import_module(f"{MODULE}.operators.preview").PREVIEW.world(bpy.context)
    first, second = _keys_around(obj, frame)
    _plot_key(ax, _world_strokes(obj, first), "0.6", "-")
    _plot_key(ax, _world_strokes(obj, second), "0.1", "-")
    colours = core.pair_colors(preview.pair)
    for trajectory, colour in zip(preview.points, colours):
        ax.plot(trajectory[:, 0], trajectory[:, 2], color=colour, lw=1.4)
        ax.plot(*trajectory[0, [0, 2]], "o", color=colour, ms=2.5)
    method = options["method"].replace("_", " ").lower()
    ax.set_title(f"{obj.name}\n{method}, keys {first} (grey) \u2192 {second} (black)", fontsize=8)
    ax.set_aspect("equal")
    ax.axis("off")


def main(path=PICTURE):
    os.makedirs(OUT, exist_ok=True)
    with addon_session():
        shots = build_scene()  # keys only: the shots are not in-betweened
        bpy.context.scene.ballmorph_inbetween.path_preview = True  # installs the draw handler
        core = importlib.import_module(f"{MODULE}.ballmorph_core")
        fig, axes = plt.subplots(1, len(shots), figsize=(2.9 * len(shots), 3.4))
        for ax, (obj, frame, options) in zip(axes, shots):
            draw_shot(ax, obj, frame, options, core)
        fig.suptitle(
            "Path preview: where points of every stroke pair travel between the keys around the current frame "
            "(one colour per pair; dots on the first key)",
            fontsize=10,
        )
        save_figure(fig, path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
