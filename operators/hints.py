"""``ballmorph.hint_add`` and ``ballmorph.hint_clear``: correspondence hints on the active key.

A hint is a number on a point of a key drawing (the INT point attribute ``ballmorph_hint``,
:data:`ballmorph_core.HINT`): the point with hint ``k`` on one key travels to the point with
hint ``k`` on the other (see ``ballmorph_core/drawing/hints.py``). In Edit Mode, select a point
on the first key and add a hint, go to the second key, select its partner and add the same
number. The numbering is :mod:`.hint_numbers`; these operators only read the selection, write
the attribute and report.
"""

from dataclasses import replace

import bpy
import numpy as np

from ..addon_logic import hint_numbers, pairing
from ..ballmorph_core import HINT
from . import grease_pencil, keys

__all__ = ["BALLMORPH_OT_hint_add", "BALLMORPH_OT_hint_clear", "active_key", "HintMarks", "MARKS"]


def active_key(context):
    """The drawing of the active layer's key at the current frame (its frame), or None."""
    obj = context.active_object
    if obj is None or obj.type != "GREASEPENCIL":
        return None
    layer = obj.data.layers.active
    if layer is None or layer.lock:
        return None
    return layer.current_frame()


def _read(drawing):
    n = len(drawing.attributes["position"].data) if "position" in drawing.attributes else 0
    values = np.zeros(n, dtype=np.int32)
    attribute = drawing.attributes.get(HINT)
    if attribute is not None and attribute.domain == "POINT" and attribute.data_type == "INT":
        attribute.data.foreach_get("value", values)
    return values


def _write(drawing, values):
    attribute = drawing.attributes.get(HINT)
    if attribute is None or attribute.domain != "POINT" or attribute.data_type != "INT":
        if attribute is not None:
            drawing.attributes.remove(attribute)
        attribute = drawing.attributes.new(HINT, "INT", "POINT")
    attribute.data.foreach_set("value", np.ascontiguousarray(values, dtype=np.int32))
    drawing.tag_positions_changed()  # redraw the numbered dots


class _OnActiveKey:
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        frame = active_key(context)
        return frame is not None and frame.drawing is not None


class BALLMORPH_OT_hint_add(_OnActiveKey, bpy.types.Operator):
    """Number the selected points of the active key: hint k travels to the point with hint k on the other key"""

    bl_idname = "ballmorph.hint_add"
    bl_label = "Add Correspondence Hint"

    number: bpy.props.IntProperty(
        name="Number",
        description="The hint's number (0: the next free number; several selected points get successive ones)",
        default=0,
        min=0,
    )

    def execute(self, context):
        frame = active_key(context)
        drawing = frame.drawing
        values = _read(drawing)
        selected = grease_pencil.selected_points(drawing)
        try:
            values, given = hint_numbers.add_hints(values, selected, self.number)
        except ValueError as exc:
            self.report({"ERROR"}, f"Ball-morph hint: {exc}")
            return {"CANCELLED"}
        _write(drawing, values)
        numbers = ", ".join(str(k) for _, k in given)
        self.report({"INFO"}, f"Ball-morph hint: {numbers} on frame {frame.frame_number}")
        return {"FINISHED"}


class BALLMORPH_OT_hint_clear(_OnActiveKey, bpy.types.Operator):
    """Remove the hints of the selected points of the active key (or all its hints)"""

    bl_idname = "ballmorph.hint_clear"
    bl_label = "Clear Correspondence Hints"

    all_points: bpy.props.BoolProperty(
        name="All Points", description="Clear every hint of the active key", default=False
    )

    def execute(self, context):
        frame = active_key(context)
        drawing = frame.drawing
        values = _read(drawing)
        selected = None if self.all_points else grease_pencil.selected_points(drawing)
        values, cleared = hint_numbers.clear_hints(values, selected)
        if len(values):
            _write(drawing, values)
        text = ", ".join(map(str, cleared)) if cleared else "none"
        self.report({"INFO"}, f"Ball-morph hints cleared on frame {frame.frame_number}: {text}")
        return {"FINISHED"}


class HintMarks:
    """The hinted points of the keys around the current frame, in world space, for the viewport's
    numbered dots (``ui/hint_dots.py``); kept until the frame, the object or its data change."""

    def __init__(self):
        self._state, self._marks, self._edits = None, None, 0

    def edited(self):
        """Blender's data changed (a depsgraph update): read the hints again at the next redraw."""
        self._edits += 1

    def marks(self, context):
        """``(points (M, 3), numbers (M,), key (M,) 0 for the earlier key, 1 for the later)``, or None."""
        obj = keys.grease_pencil_object(context)
        layer = obj.data.layers.active if obj is not None else None
        if layer is None:
            return None
        frame = context.scene.frame_current
        world = np.array(obj.matrix_world, dtype=np.float64) @ grease_pencil.layer_matrix(layer)
        state = (obj.name, layer.name, frame, tuple(world.ravel()), self._edits)
        if state != self._state:
            self._state, self._marks = state, _read_marks(obj, layer, frame, world)
        return self._marks


def _read_marks(obj, layer, frame, world):
    found = replace(keys.layer_keys(obj.data, layer), selected=())
    pairs, _ = pairing.selected_or_current(found, frame)
    if not pairs:
        return None
    frames = {f.frame_number: f for f in layer.frames}
    points, numbers, side = [], [], []
    for which, number in enumerate(pairs[0]):
        drawing = frames[number].drawing
        values = _read(drawing)
        at = np.flatnonzero(values > 0)
        if not len(at):
            continue
        positions = grease_pencil.read_strokes(drawing).positions[at]
        points.append(positions @ world[:3, :3].T + world[:3, 3])
        numbers.append(values[at])
        side.append(np.full(len(at), which))
    if not points:
        return None
    return np.concatenate(points), np.concatenate(numbers), np.concatenate(side)


#: The add-on's one record of hint marks (module state, like the plans).
MARKS = HintMarks()
