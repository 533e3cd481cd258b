"""The README's picture of correspondence hints, from a real Grease Pencil scene (``make demo``).

With bpy, headless: a wheel (a rim and three spokes) drawn the same on frames 1 and 9, except
that the animator turned it a quarter turn; its spokes and rim match themselves as they are, so
the automatic in-betweens keep the wheel still. With one hint (``ballmorph.hint_add`` on a rim
point of each key: 0 degrees on frame 1, 90 on frame 9) the operator turns it. The picture shows
both runs, the in-betweens in grey, the keys in black, the hinted point's path, and the numbered
dots the viewport draws (the add-on's own hint marks, ``operators.hints.MARKS``), into
out/hints.png (docs/hints.png is a copy).
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
from demo import MODULE, OUT, add_key, addon_session, material, new_shot, save_figure

PICTURE = os.path.join(OUT, "hints.png")
FIRST, LAST = 1, 9


def _wheel(turn_degrees):
    """A rim of 72 points and three spokes, turned by ``turn_degrees``: (strokes, cyclic)."""
    t = np.radians(np.arange(72) * 5.0 + turn_degrees)
    rim = np.c_[np.cos(t), np.sin(t)]
    spokes = []
    for k in range(3):
        a = np.radians(turn_degrees + 120.0 * k + 30.0)
        r = np.linspace(0.0, 0.95, 12)[:, None]
        spokes.append(r * [np.cos(a), np.sin(a)])
    return [rim, *spokes], [True, False, False, False]


def _select(drawing, point):
    n = len(drawing.attributes["position"].data)
    selection = drawing.attributes.get(".selection") or drawing.attributes.new(".selection", "BOOLEAN", "POINT")
    values = np.zeros(n, dtype=bool)
    values[point] = True
    selection.data.foreach_set("value", values)


def _scene(name, x_offset, hinted):
    ink = material("Ink", (0.05, 0.05, 0.08))
    obj = new_shot(name, x_offset, [ink])
    layer = obj.data.layers["Ink"]
    for number, turn in ((FIRST, 0.0), (LAST, 90.0)):
        strokes, cyclic = _wheel(turn)
        add_key(obj, number, strokes, cyclic, [0] * len(strokes), [0.02] * len(strokes))
        if hinted:  # the rim's first point: at 0 degrees on frame 1, at 90 on frame 9
            bpy.context.view_layer.objects.active = obj
            bpy.context.scene.frame_current = number
            _select(next(f for f in layer.frames if f.frame_number == number).drawing, 0)
            assert bpy.ops.ballmorph.hint_add() == {"FINISHED"}
    return obj


def _run(obj):
    bpy.context.view_layer.objects.active = obj
    bpy.context.scene.frame_current = FIRST
    assert bpy.ops.ballmorph.inbetween(method="CIRCULAR_BALL") == {"FINISHED"}


def _strokes(obj, number):
    io = importlib.import_module(f"{MODULE}.operators.grease_pencil")
    frame = next(f for f in obj.data.layers["Ink"].frames if f.frame_number == number)
    return io.read_strokes(frame.drawing), frame.drawing


def _draw(ax, obj, title, marks):
    hint_path = []
    for number in range(FIRST, LAST + 1):
        strokes, drawing = _strokes(obj, number)
        key = number in (FIRST, LAST)
        for i in range(len(strokes)):
            xz = strokes.positions[strokes.points(i)][:, [0, 2]]  # object space
            if strokes.cyclic[i]:
                xz = np.vstack([xz, xz[:1]])
            ax.plot(xz[:, 0], xz[:, 1], color="0.05" if key else "0.75", lw=1.6 if key else 0.8)
        hints = drawing.attributes.get("ballmorph_hint")
        if hints is not None:
            values = np.empty(len(hints.data), dtype=np.int32)
            hints.data.foreach_get("value", values)
            hint_path += [strokes.positions[at, [0, 2]] for at in np.flatnonzero(values == 1)]
    if hint_path:
        path = np.array(hint_path)
        ax.plot(path[:, 0], path[:, 1], "-", color="tab:orange", lw=1.2)
    if marks is not None:
        points, numbers, side = marks
        for p, k, s in zip(points, numbers, side):
            colour = "tab:orange" if s == 0 else "tab:blue"
            x, z = p[0] - obj.location.x, p[2]
            ax.plot(x, z, "o", color=colour, ms=7)
            ax.annotate(str(k), (x, z), xytext=(6, 6), textcoords="offset points", color=colour, fontsize=9)
    ax.set_title(title, fontsize=9)
    ax.set_aspect("equal")
    ax.axis("off")


def main(path=PICTURE):
    os.makedirs(OUT, exist_ok=True)
    with addon_session():
        plain, hinted = _scene("Wheel", 0.0, False), _scene("Wheel hinted", 3.0, True)
        hint_marks = importlib.import_module(f"{MODULE}.operators.hints").MARKS
        bpy.context.view_layer.objects.active = hinted
        bpy.context.scene.frame_current = FIRST
        hint_marks.edited()
        marks = hint_marks.marks(bpy.context)
        for obj in (plain, hinted):
            _run(obj)
        fig, axes = plt.subplots(1, 2, figsize=(7.5, 3.9))
        _draw(axes[0], plain, "no hint: each spoke takes its nearest,\nthe rim stays still", None)
        _draw(
            axes[1],
            hinted,
            "hint 1 on the rim (0\u00b0 on frame 1, 90\u00b0 on frame 9):\nthe whole wheel turns",
            marks,
        )
        fig.suptitle("Correspondence hints: the point with hint k travels to the point with hint k", fontsize=10)
        save_figure(fig, path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
