"""Menu entries: Dope Sheet Key and context menus (Grease Pencil mode), 3D viewport Draw/Edit menus.

Every entry opens one submenu: "In-between" runs with the scene settings (sidebar panel); the
morph list runs with one morph chosen there.
"""

import bpy

from ..operators.inbetween import BALLMORPH_OT_inbetween

__all__ = ["BALLMORPH_MT_inbetween", "MENU_ENTRIES"]


class BALLMORPH_MT_inbetween(bpy.types.Menu):
    bl_idname = "BALLMORPH_MT_inbetween"
    bl_label = "Ball-morph In-between"

    def draw(self, context):
        layout = self.layout
        layout.operator(BALLMORPH_OT_inbetween.bl_idname, text="In-between", icon="IPO_EASE_IN_OUT")
        at_frame = layout.operator(BALLMORPH_OT_inbetween.bl_idname, text="In-between at Current Frame")
        at_frame.current_frame_only = True
        layout.separator()
        layout.operator_enum(BALLMORPH_OT_inbetween.bl_idname, "method")


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
    ("VIEW3D_MT_paint_grease_pencil", _draw_entry),  # Draw mode: next to Interpolate Sequence
    ("VIEW3D_MT_edit_greasepencil", _draw_entry),
)

classes = (BALLMORPH_MT_inbetween,)


def register():
    for name, draw in MENU_ENTRIES:
        getattr(bpy.types, name).append(draw)


def unregister():
    for name, draw in MENU_ENTRIES:
        getattr(bpy.types, name).remove(draw)
