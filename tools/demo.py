"""The main demo: the add-on in-betweens four shot-like Grease Pencil cases inside Blender.

Run by ``make demo`` (tools/demo.sh) with bpy (Blender as a Python module), headless:

1. enables the add-on from this checkout (a development extension repository),
2. builds one Grease Pencil object per shot, with hand-made keys on its layer "Ink":
   - "Apple to pear": an apple outline and stem morphing into a pear (loops, frames 1-13),
   - "Bend": a stroke whose ends stay put while its arch bends down into a dip (strokes sharing
     their endpoints, frames 1-9), with the circular ball-morph. (A second row compared it with
     linear interpolation; on these keys the two look alike, and keys where they differ visibly
     cross each other, where today's ball-morph pins the crossing and kinks the in-betweens:
     the row was dropped, issue 40.)
   - "Squash and stretch": a ball falling (round, stretched, squashed on the floor: three
     selected keys, frames 1, 7, 9; the contact at 7 typed Extreme, so the fall keeps its corner
     there) with a gravity ease-in,
   - "Head turn": keys drawn the way animators draw them (frames 1-11): the head moves and
     turns so its outline crosses its first position, and the second key's outline starts
     elsewhere and runs the other way; the brow is drawn the other way too; no stroke shares an
     endpoint with its partner; and a sweat drop appears in the second key,
3. runs ``bpy.ops.ballmorph.inbetween`` on each (the same call the Dope Sheet menu makes),
4. saves out/demo.blend (open it in Blender 4.5+ and scrub the timeline) and draws
   out/demo.png, a contact sheet of the keys and in-betweens read back from Blender.
"""

import importlib
import os
import sys
import tempfile
from contextlib import contextmanager

import bpy
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The shots' drawings live with the test fixtures: the golden test draws the same keys.
sys.path.insert(0, os.path.join(ROOT, "tests", "fixtures"))
from shots import apple, bend_arch, bend_down, ellipse, floor, head_turn_keys, pear, stem  # noqa: E402

OUT = os.path.join(ROOT, "out")
ADDON_ID = "ballmorph_inbetween"
REPO_MODULE = "ballmorph_demo"
MODULE = f"bl_ext.{REPO_MODULE}.{ADDON_ID}"
addon_utils = importlib.import_module("addon_utils")


# -- Blender data ------------------------------------------------------------------------------


def enable_addon():
    """Enable the add-on from this checkout through a temporary development repository."""
    repo_dir = tempfile.mkdtemp(prefix="ballmorph-demo-repo-")
    os.symlink(ROOT, os.path.join(repo_dir, ADDON_ID))
    bpy.context.preferences.extensions.repos.new(
        name="Ball-morph demo", module=REPO_MODULE, custom_directory=repo_dir, source="USER"
    )
    addon_utils.enable(MODULE, default_set=True, handle_error=_raise)
    return importlib.import_module(MODULE)


def _raise(exc):
    raise exc


@contextmanager
def addon_session():
    """Blender's factory settings and the add-on enabled from this checkout for the block,
    disabled after it (bpy may hang at exit with operators or handlers registered)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    enable_addon()
    try:
        yield
    finally:
        addon_utils.disable(MODULE, default_set=True)


def save_figure(fig, path):
    """A matplotlib figure laid out, written to ``path`` at the pictures' resolution, closed."""
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")


def material(name, rgb):
    mat = bpy.data.materials.get(name)
    if mat is None:
        mat = bpy.data.materials.new(name)
        bpy.data.materials.create_gpencil_data(mat)
        mat.grease_pencil.color = (*rgb, 1.0)
    return mat


def new_shot(name, x_offset, materials):
    io = importlib.import_module(f"{MODULE}.operators.grease_pencil")
    data = io.data_collection().new(name)
    obj = bpy.data.objects.new(name, data)
    obj.location = (x_offset, 0.0, 0.0)
    bpy.context.scene.collection.objects.link(obj)
    for mat in materials:
        data.materials.append(mat)
    # Flat 2D ink: the strokes show their material colours whatever the lights (Workbench has none)
    data.layers.new("Ink").use_lights = False
    return obj


def add_key(obj, number, strokes, cyclic, materials, radius):
    """Draw a keyframe: (n, 2) strokes on the XZ canvas, written through the add-on's own I/O."""
    io = importlib.import_module(f"{MODULE}.operators.grease_pencil")
    core = importlib.import_module(f"{MODULE}.ballmorph_core")
    n = [len(s) for s in strokes]
    # Pressure-like radius: thin ends, full in the middle of each stroke.
    taper = [r * (0.35 + 0.65 * np.sin(np.linspace(0, np.pi, k)) ** 0.5) for r, k in zip(radius, n)]
    keys = core.StrokeSet.from_strokes(
        strokes,
        cyclic=cyclic,
        material_index=materials,
        radius=[np.full(k, r) if c else t for r, c, k, t in zip(radius, cyclic, n, taper)],
        opacity=[np.full(k, 1.0) for k in n],
    )
    frame = obj.data.layers["Ink"].frames.new(number)
    io.write_strokes(frame.drawing, keys)
    return frame


def build_scene():
    """The four shots' keys (inside :func:`addon_session`): list of (object, frame, options)."""
    ink = material("Ink", (0.05, 0.05, 0.08))
    red = material("Apple red", (0.75, 0.1, 0.1))
    brown = material("Stem", (0.35, 0.2, 0.05))
    blue = material("Ball", (0.1, 0.3, 0.8))
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, 13

    shots = []
    obj = new_shot("Apple to pear", 0.0, [red, brown])
    add_key(obj, 1, [apple(), stem((0.0, 0.84), (0.12, 1.3))], [True, False], [0, 1], [0.035, 0.03])
    add_key(obj, 13, [pear(), stem((0.0, 1.65), (0.16, 2.05))], [True, False], [0, 1], [0.035, 0.03])
    shots.append((obj, 2, {"method": "CIRCULAR_BALL", "easing_type": "SINE", "easing": "EASE_IN_OUT"}))

    obj = new_shot("Bend", 3.2, [ink])
    add_key(obj, 1, [bend_arch()], [False], [0], [0.04])
    add_key(obj, 9, [bend_down()], [False], [0], [0.04])
    shots.append((obj, 2, {"method": "CIRCULAR_BALL"}))

    obj = new_shot("Squash and stretch", 7.2, [blue, ink])
    ball_keys = (
        (1, ellipse(0.5, 0.5, (0.0, 2.6))),
        (7, ellipse(0.36, 0.66, (0.0, 0.9))),
        (9, ellipse(0.72, 0.3, (0.0, 0.3))),
    )
    for number, ball in ball_keys:
        frame = add_key(obj, number, [ball, floor()], [True, False], [0, 1], [0.03, 0.02])
        frame.select = True  # the animator selected the three keys in the Dope Sheet
        if number == 7:
            # The contact, typed Extreme as animators mark one: the fall keeps its corner there
            # (passed through smoothly, the squash's spread would swing the fall sideways).
            frame.keyframe_type = "EXTREME"
    # Paired by drawing order: the ball travels too far for the automatic matching to pair it.
    options = {"method": "CIRCULAR_BALL", "easing_type": "QUAD", "easing": "EASE_IN", "matching": "INDEX"}
    shots.append((obj, 2, options))

    obj = new_shot("Head turn", 10.4, [ink, blue])
    for number, (strokes, cyclic, materials) in zip((1, 11), head_turn_keys()):
        add_key(obj, number, strokes, cyclic, materials, [0.03 if c else 0.025 for c in cyclic])
    # Every option given: the scene remembers the previous shot's (By Index matching).
    options = {"method": "CIRCULAR_BALL", "easing_type": "SINE", "easing": "EASE_IN_OUT", "matching": "AUTO"}
    shots.append((obj, 2, options))
    return shots


def run_shots(shots):
    for obj, frame, options in shots:
        bpy.context.view_layer.objects.active = obj
        bpy.context.scene.frame_current = frame
        print(f"== {obj.name}: bpy.ops.ballmorph.inbetween({', '.join(f'{k}={v!r}' for k, v in options.items())})")
        result = bpy.ops.ballmorph.inbetween(**options)
        layer = obj.data.layers["Ink"]
        kinds = " ".join(f"{f.frame_number}{'k' if f.keyframe_type == 'KEYFRAME' else 'b'}" for f in layer.frames)
        print(f"   {result} frames (k = key, b = breakdown): {kinds}")


# -- contact sheet -----------------------------------------------------------------------------


def _frames(obj):
    io = importlib.import_module(f"{MODULE}.operators.grease_pencil")
    layer = obj.data.layers["Ink"]
    frames = sorted(layer.frames, key=lambda f: f.frame_number)
    return [(f.frame_number, f.keyframe_type, io.read_strokes(f.drawing)) for f in frames]


def _draw(ax, obj, strokes, colour=None, alpha=1.0, width_scale=1.0):
    colours = [tuple(slot.material.grease_pencil.color[:3]) for slot in obj.material_slots]
    for i in range(len(strokes)):
        sl = strokes.points(i)
        xz = strokes.positions[sl][:, [0, 2]]
        if strokes.cyclic[i]:
            xz = np.vstack([xz, xz[:1]])
        lw = width_scale * 70 * float(np.mean(strokes.radius[sl]))
        c = colour or colours[int(strokes.material_index[i])]
        ax.plot(xz[:, 0], xz[:, 1], color=c, lw=lw, alpha=alpha, solid_capstyle="round")


def contact_sheet(shots, path, columns=6):
    rows = len(shots)
    fig, axes = plt.subplots(rows, columns + 1, figsize=(2.0 * (columns + 1), 2.2 * rows))
    for row, (obj, _, options) in enumerate(shots):
        frames = _frames(obj)
        onion = axes[row, 0]
        cmap = plt.get_cmap("viridis")
        for k, (_, kind, strokes) in enumerate(frames):
            if kind == "KEYFRAME":
                _draw(onion, obj, strokes, colour="black", width_scale=0.8)
            else:
                _draw(onion, obj, strokes, colour=cmap(k / max(len(frames) - 1, 1)), alpha=0.8, width_scale=0.4)
        onion.set_title(f"{obj.name}\n{options['method'].replace('_', ' ').lower()}", fontsize=8)
        picks = np.unique(np.round(np.linspace(0, len(frames) - 1, columns)).astype(int))
        limits = np.concatenate([s.positions[:, [0, 2]] for _, _, s in frames if len(s)])
        lo, hi = limits.min(axis=0) - 0.15, limits.max(axis=0) + 0.15
        for col in range(columns):
            ax = axes[row, col + 1]
            if col < len(picks):
                number, kind, strokes = frames[picks[col]]
                _draw(ax, obj, strokes)
                ax.set_title(f"frame {number} ({'key' if kind == 'KEYFRAME' else 'in-between'})", fontsize=8)
        for ax in axes[row]:
            ax.set_xlim(lo[0], hi[0])
            ax.set_ylim(lo[1], hi[1])
            ax.set_aspect("equal")
            ax.axis("off")
    fig.suptitle("Ball-morph In-between: keys (black in the onion skin) and the in-betweens the add-on wrote")
    save_figure(fig, path)


def main():
    os.makedirs(OUT, exist_ok=True)
    with addon_session():
        shots = build_scene()
        run_shots(shots)
        blend = os.path.join(OUT, "demo.blend")
        bpy.context.preferences.filepaths.save_version = 0  # no demo.blend1 backups
        bpy.ops.wm.save_as_mainfile(filepath=blend)
        print(f"wrote {blend}")
        contact_sheet(shots, os.path.join(OUT, "demo.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
