"""Sidebar panels (Dope Sheet and 3D viewport, tab "Ball-morph"): morph type, frame count, run."""

import bpy

from ..addon_logic import warned
from ..operators.inbetween import BALLMORPH_OT_inbetween
from ..operators.options import draw_options
from ..operators.select_warned import BALLMORPH_OT_select_warned

__all__ = ["BALLMORPH_PT_dopesheet", "BALLMORPH_PT_view3d"]


class _InbetweenPanel:
    bl_region_type = "UI"
    bl_category = "Ball-morph"
    bl_label = "Ball-morph In-between"

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "GREASEPENCIL"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.ballmorph_inbetween
        draw_options(layout.column(), settings, compact=True, scene=context.scene)
        row = layout.row(align=True)
        row.prop(settings, "path_preview", icon="CURVE_PATH")
        row.prop(settings, "hint_dots", icon="PINNED")
        row = layout.row(align=True)
        row.operator("ballmorph.hint_add", text="Add Hint", icon="PINNED")
        row.operator("ballmorph.hint_clear", text="Clear Hints", icon="UNPINNED")
        layout.operator(BALLMORPH_OT_inbetween.bl_idname, text="In-between", icon="IPO_EASE_IN_OUT")
        if warned.PROPERTY in context.active_object.data:  # the last run warned about strokes
            layout.operator(BALLMORPH_OT_select_warned.bl_idname, icon="RESTRICT_SELECT_OFF")


class _MoreOptionsPanel:
    bl_region_type = "UI"
    bl_category = "Ball-morph"
    bl_label = "Stroke Pairing"
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        settings = context.scene.ballmorph_inbetween
        layout.prop(settings, "carrier")
        layout.prop(settings, "matching")
        layout.prop(settings, "unmatched")


class BALLMORPH_PT_dopesheet(_InbetweenPanel, bpy.types.Panel):
    bl_space_type = "DOPESHEET_EDITOR"


class BALLMORPH_PT_dopesheet_pairing(_MoreOptionsPanel, bpy.types.Panel):
    bl_space_type = "DOPESHEET_EDITOR"
    bl_parent_id = "BALLMORPH_PT_dopesheet"


class BALLMORPH_PT_view3d(_InbetweenPanel, bpy.types.Panel):
    bl_space_type = "VIEW_3D"


class BALLMORPH_PT_view3d_pairing(_MoreOptionsPanel, bpy.types.Panel):
    bl_space_type = "VIEW_3D"
    bl_parent_id = "BALLMORPH_PT_view3d"


classes = (BALLMORPH_PT_dopesheet, BALLMORPH_PT_dopesheet_pairing, BALLMORPH_PT_view3d, BALLMORPH_PT_view3d_pairing)
