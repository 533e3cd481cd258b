"""Menu entries: next to Blender's own Interpolate entries in the 3D viewport, and in the Dope
Sheet's Key and context menus (Grease Pencil mode).

In the 3D viewport, Blender's Draw menu (Draw mode) and Grease Pencil menu (Edit mode) both show
the *Animation* submenu (``VIEW3D_MT_edit_greasepencil_animation``, checked on 4.5.15 and 5.0.1)
directly above *Interpolate Sequence*: the add-on's submenu closes that Animation menu, the
nearest an appended entry can sit to Interpolate. Blender has no Interpolate in the Dope Sheet;
there the submenu closes the Key and context menus.

The submenu: "In-between" runs with the scene settings (sidebar panel), "In-between at Current
Frame" writes one in-between on the current frame (``current_frame_only``), then the animator's
morphs, each a run with that morph; the paper's comparison morphs stay in the sidebar's Morph list.
"""

import bpy

from ..operators import options
from ..operators.inbetween import BALLMORPH_OT_inbetween

__all__ = ["BALLMORPH_MT_inbetween", "MENU_ENTRIES", "QUICK_METHODS"]

#: The morphs the submenu offers (the comparison morphs of the paper are left to the sidebar).
QUICK_METHODS = tuple(item for item in options.option("method").items if not item.research)


class BALLMORPH_MT_inbetween(bpy.types.Menu):
    bl_idname = "BALLMORPH_MT_inbetween"
    bl_label = "Ball-morph In-between"

    def draw(self, context):
        layout = self.layout
        layout.operator(BALLMORPH_OT_inbetween.bl_idname, text="In-between", icon="IPO_EASE_IN_OUT")
        at_frame = layout.operator(BALLMORPH_OT_inbetween.bl_idname, text="In-between at Current Frame")
        at_frame.current_frame_only = True
        layout.separator()
        for item in QUICK_METHODS:
            layout.operator(BALLMORPH_OT_inbetween.bl_idname, text=item.label).method = item.id


def _draw_entry(self, context):
    self.layout.separator()
    self.layout.menu(BALLMORPH_MT_inbetween.bl_idname, icon="IPO_EASE_IN_OUT")


def _draw_dopesheet_entry(self, context):
    space = context.space_data
    obj = context.active_object
    if space.mode == "GPENCIL" or (obj is not None and obj.type == "GREASEPENCIL"):
        _draw_entry(self, context)


# (menu class name, draw function): appended on register, removed on unregister.
MENU_ENTRIES = (
    ("DOPESHEET_MT_key", _draw_dopesheet_entry),
    ("DOPESHEET_MT_context_menu", _draw_dopesheet_entry),
    ("VIEW3D_MT_edit_greasepencil_animation", _draw_entry),  # just above Interpolate Sequence
)

classes = (BALLMORPH_MT_inbetween,)


def register():
    for name, draw in MENU_ENTRIES:
        getattr(bpy.types, name).append(draw)


def unregister():
    for name, draw in MENU_ENTRIES:
        getattr(bpy.types, name).remove(draw)
