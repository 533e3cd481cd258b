"""``ballmorph.select_warned``: select, in their keys, the strokes the last run's warnings name.

After a run, the warnings say "stroke 2 of the first key has no partner" or "stroke 1 -> 3
strays"; this operator (Select Warned Strokes, in the sidebar panel and the Ball-morph submenu)
makes exactly those strokes the edit-mode selection of their key drawings, and deselects every
other stroke of the object, so the animator finds them in Edit Mode on the key's frame (the
report names it). The strokes come from the record the last run kept on the Grease Pencil data
(:mod:`..addon_logic.warned`: why it is kept there). Only the selection changes: no point moves,
no key or frame is added or removed, the current frame stays.
"""

import bpy
from bpy.app.translations import pgettext_rpt as rpt_

from ..addon_logic import reports, warned
from . import grease_pencil, keys

__all__ = ["BALLMORPH_OT_select_warned"]


class BALLMORPH_OT_select_warned(bpy.types.Operator):
    """Select, in their keys, the strokes the last Ball-morph In-between run warned about (only selection changes)"""

    bl_idname = "ballmorph.select_warned"
    bl_label = "Select Warned Strokes"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = keys.grease_pencil_object(context)
        if obj is None:
            cls.poll_message_set(rpt_("Select a Grease Pencil object"))
            return False
        if warned.PROPERTY not in obj.data:
            cls.poll_message_set(rpt_("The last Ball-morph In-between run on this object warned about no stroke"))
            return False
        return True

    def execute(self, context):
        obj = keys.grease_pencil_object(context)
        if obj is None or warned.PROPERTY not in obj.data:
            self.report({"ERROR"}, rpt_("The last Ball-morph In-between run on this object warned about no stroke"))
            return {"CANCELLED"}
        found, missing = select_warned(obj.data)
        if missing:
            self.report({"WARNING"}, rpt_(reports.warned_missing(missing)))
        if not found:
            self.report({"WARNING"}, rpt_(reports.warned_none_left()))
            return {"FINISHED"}
        self.report({"INFO"}, rpt_(reports.warned_selected(found)))
        obj.data.update_tag()  # redraw the selection
        return {"FINISHED"}


def select_warned(data):
    """Select the warned strokes of ``data`` (Grease Pencil data) and deselect every other stroke.

    Returns
    -------
    found : dict
        ``{layer name: tuple of StrokeRef}``: the strokes selected.
    missing : dict
        ``{layer name: tuple of StrokeRef}``: strokes the record names that are gone (the key
        or the stroke was removed since the run).
    """
    found, missing = {}, {}
    masks = {}  # drawing pointer -> (drawing, selection); a drawing shared by frames gets one
    for layer in data.layers:
        wanted = set(warned.strokes_of(data, layer.name))
        for frame in layer.frames:
            drawing = frame.drawing
            if drawing is None:
                continue
            count = max(len(drawing.curve_offsets) - 1, 0)  # an empty drawing reports one offset
            _, mask = masks.setdefault(drawing.as_pointer(), (drawing, [False] * count))
            for ref in sorted(r for r in wanted if r[0] == frame.frame_number):
                if 1 <= ref[1] <= count:
                    mask[ref[1] - 1] = True
                    found.setdefault(layer.name, []).append(ref)
                    wanted.discard(ref)
        if wanted:
            missing[layer.name] = tuple(sorted(wanted))
    for drawing, mask in masks.values():
        grease_pencil.select_strokes(drawing, mask)
    return {layer: tuple(refs) for layer, refs in found.items()}, missing
