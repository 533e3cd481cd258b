"""Add-on preferences: the default options of every scene (Edit > Preferences > Add-ons)."""

import bpy

from ..operators.options import draw_options, property_annotations

__all__ = ["BALLMORPH_AddonPreferences"]


class BALLMORPH_AddonPreferences(bpy.types.AddonPreferences):
    """Defaults for Ball-morph In-between (each scene can override them in the sidebar panel)."""

    bl_idname = __package__.rpartition(".")[0]  # the add-on's own module name

    __annotations__ = property_annotations()

    def draw(self, context):
        layout = self.layout
        layout.label(text="Defaults for scenes where these options were not changed yet:")
        draw_options(layout, self)


classes = (BALLMORPH_AddonPreferences,)
