"""Render the demo with Blender: every frame of out/demo.blend through Workbench, into a GIF.

Run by ``make demo`` (tools/demo.sh) after tools/demo.py has written out/demo.blend, with bpy
(Blender as a Python module), headless. It opens the file, sets the stage in memory (the file
is not saved again): an orthographic camera framing the four shots side by side, a white
world, the Workbench engine with flat lighting, a frame counter, and under each shot its name
and what the frame is for that shot (key, in-between, or hold after its last key). Then it
renders every frame of the scene to out/demo_frames/frame_NNNN.png and assembles them into
out/demo.gif (Pillow), looping, with the first and last frames held.

Grease Pencil strokes show their material colours in Workbench only on layers that do not use
the scene's lights (``layer.use_lights``, off in tools/demo.py: flat 2D ink); Workbench's
colour type does not change them (it colours the labels).
"""

import math
import os
import sys
import time

import bpy
import numpy as np
from PIL import Image

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "out")
BLEND = os.path.join(OUT, "demo.blend")
FRAMES = os.path.join(OUT, "demo_frames")
GIF = os.path.join(OUT, "demo.gif")

WIDTH = 1280  # pixels; the height follows the shots' extent
MARGIN = 0.3  # Blender units around the shots
LABEL_SIZE = 0.26
# Label colours (Workbench's object colour): names, and what a frame is in a shot.
INK = (0.08, 0.08, 0.1, 1.0)
STATUS_COLOURS = {"key": (0.85, 0.3, 0.0, 1.0), "in-between": (0.3, 0.3, 0.33, 1.0), "hold": (0.62, 0.62, 0.62, 1.0)}
FPS = 12  # animation speed: the shots' drawings as if on twos at 24 fps, 12 a second
HOLD_MS = 700  # on the first and the last frame
#: Colours of the GIF's one palette, shared by every frame: the drawings are flat ink on white,
#: so 32 keep every stroke and label clean, and unchanged pixels stay identical from frame to
#: frame, which the GIF stores once (the 256-colour palettes of each frame made 413 KB).
GIF_COLOURS = 32


def _shots():
    """The Grease Pencil objects (left to right) with each one's frames: {number: keyframe type}."""
    shots = [obj for obj in bpy.data.objects if obj.type == "GREASEPENCIL"]
    shots.sort(key=lambda obj: obj.location.x)
    return [(obj, {f.frame_number: f.keyframe_type for f in obj.data.layers["Ink"].frames}) for obj in shots]


def _bounds(obj):
    """World-space (x, z) bounds of every stroke point on every frame of an object, shape (2, 2)."""
    matrix = np.array(obj.matrix_world)
    points = []
    for layer in obj.data.layers:
        for frame in layer.frames:
            position = frame.drawing.attributes.get("position")
            if position is None or not len(position.data):
                continue
            xyz = np.empty(len(position.data) * 3, np.float32)
            position.data.foreach_get("vector", xyz)
            xyz = xyz.reshape(-1, 3) @ matrix[:3, :3].T + matrix[:3, 3]
            points.append(xyz[:, [0, 2]])
    points = np.concatenate(points)
    return np.array([points.min(axis=0), points.max(axis=0)])


def _label(name, x, z, size, align="CENTER"):
    """A text object facing the camera (it looks along +Y at the XZ canvas)."""
    curve = bpy.data.curves.new(name, "FONT")
    curve.align_x = align
    curve.size = size
    obj = bpy.data.objects.new(name, curve)
    obj.location = (x, 0.0, z)
    obj.rotation_euler = (math.pi / 2, 0.0, 0.0)
    obj.color = INK
    bpy.context.scene.collection.objects.link(obj)
    return obj


def _status(frames, number):
    """What frame ``number`` is in a shot: its key, an in-between the add-on wrote, or a hold."""
    kind = frames.get(number)
    if kind is None:
        return "hold" if number > max(frames) else ""
    return "key" if kind == "KEYFRAME" else "in-between"


def set_stage(shots):
    """Camera, world, Workbench and labels; returns the frame counter and {shot object: its
    status label} (text objects)."""
    scene = bpy.context.scene
    bounds = {obj: _bounds(obj) for obj, _ in shots}
    low = np.min([b[0] for b in bounds.values()], axis=0)
    high = np.max([b[1] for b in bounds.values()], axis=0)
    label_z = low[1] - 0.45  # the status row; names below it, on up to two lines
    low = np.array([low[0], label_z - 3.2 * LABEL_SIZE]) - MARGIN
    high = high + MARGIN
    width, height = high - low

    camera = bpy.data.objects.new("Demo camera", bpy.data.cameras.new("Demo camera"))
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = width
    camera.location = ((low[0] + high[0]) / 2, -10.0, (low[1] + high[1]) / 2)
    camera.rotation_euler = (math.pi / 2, 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera

    world = bpy.data.worlds.new("Paper")
    world.color = (1.0, 1.0, 1.0)
    scene.world = world
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.shading.light = "FLAT"
    scene.display.shading.color_type = "OBJECT"  # the labels' colours; strokes keep their materials
    scene.view_settings.view_transform = "Standard"  # colours as the materials give them
    scene.render.resolution_x = WIDTH
    scene.render.resolution_y = 2 * round(WIDTH * height / width / 2)
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"

    counter = _label("Frame counter", low[0] + MARGIN, high[1] - MARGIN - LABEL_SIZE, LABEL_SIZE, "LEFT")
    status = {}
    for obj, _ in shots:
        x = float(bounds[obj][:, 0].mean())
        status[obj] = _label(f"{obj.name} status", x, label_z, 0.85 * LABEL_SIZE)
        name = _label(f"{obj.name} label", x, label_z - 1.15 * LABEL_SIZE, LABEL_SIZE)
        name.data.body = obj.name.replace(" (", "\n(")
    return counter, status


def render_frames(shots, counter, status):
    """Render every frame of the scene; returns the PNG paths and the seconds each render took."""
    scene = bpy.context.scene
    os.makedirs(FRAMES, exist_ok=True)
    for old in os.listdir(FRAMES):
        os.remove(os.path.join(FRAMES, old))
    paths, seconds = [], []
    for number in range(scene.frame_start, scene.frame_end + 1):
        counter.data.body = f"frame {number} of {scene.frame_end}"
        for obj, frames in shots:
            kind = _status(frames, number)
            status[obj].data.body = kind
            status[obj].color = STATUS_COLOURS.get(kind, INK)
        scene.frame_set(number)
        scene.render.filepath = os.path.join(FRAMES, f"frame_{number:04d}.png")
        start = time.perf_counter()
        bpy.ops.render.render(write_still=True)
        seconds.append(time.perf_counter() - start)
        paths.append(scene.render.filepath)
    return paths, seconds


def assemble_gif(paths, path):
    """An endlessly looping GIF of the frames at :data:`FPS`, the first and last held a little,
    all in one palette of :data:`GIF_COLOURS` colours (no dithering)."""
    frames = [Image.open(p).convert("RGB") for p in paths]
    width, height = frames[0].size
    sheet = Image.new("RGB", (width, height * len(frames)))
    for i, frame in enumerate(frames):
        sheet.paste(frame, (0, i * height))
    palette = sheet.quantize(colors=GIF_COLOURS, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
    frames = [frame.quantize(palette=palette, dither=Image.Dither.NONE) for frame in frames]
    durations = [round(1000 / FPS)] * len(frames)
    durations[0] = durations[-1] = HOLD_MS
    frames[0].save(path, save_all=True, append_images=frames[1:], duration=durations, loop=0, optimize=True)


def main():
    start = time.perf_counter()
    bpy.ops.wm.open_mainfile(filepath=BLEND)
    shots = _shots()
    counter, status = set_stage(shots)
    paths, seconds = render_frames(shots, counter, status)
    assemble_gif(paths, GIF)
    scene = bpy.context.scene
    print(
        f"rendered {len(paths)} frames of {scene.render.resolution_x}x{scene.render.resolution_y} with Workbench: "
        f"first {seconds[0]:.1f} s (engine start), then {np.median(seconds[1:]):.2f} s per frame (median); "
        f"{time.perf_counter() - start:.1f} s in all"
    )
    print(f"wrote {FRAMES}/frame_*.png\nwrote {GIF}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
