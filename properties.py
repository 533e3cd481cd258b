"""Scene settings: the options the sidebar panel shows and the menus run with.

Stored per scene (``scene.ballmorph_inbetween``). Until the animator changes an option in a
scene, it reads the add-on preferences, so the preferences are the defaults for every scene.
"""

import bpy

from .operators.options import property_annotations
from .ui import path_preview

__all__ = ["BALLMORPH_PG_settings"]


def addon_preferences(context=None):
    """The add-on preferences, or None when the add-on is not enabled through Blender's add-ons."""
    addon = (context or bpy.context).preferences.addons.get(__package__)
    return addon.preferences if addon is not None else None


def _getter(option):
    def get(self):
        if option.name in self:
            return self[option.name]
        preferences = addon_preferences()
        return option.raw(getattr(preferences, option.name) if preferences is not None else option.default)

    return get


def _setter(option):
    def set_value(self, value):
        self[option.name] = value

    return set_value


class BALLMORPH_PG_settings(bpy.types.PropertyGroup):
    """Ball-morph In-between options of a scene (defaults: the add-on preferences)."""

    __annotations__ = {
        **property_annotations(getter=_getter, setter=_setter),
        # A view setting, not an option: the operator never reads it.
        "path_preview": bpy.props.BoolProperty(
            name="Path Preview",
            description="Show in the 3D viewport where points of every stroke pair travel between the keys "
            "around the current frame (active layer)",
            update=path_preview.toggled,
        ),
        "hint_dots": bpy.props.BoolProperty(
            name="Hint Dots",
            description="Show the hints' numbered dots on the keys around the current frame (3D viewport)",
            default=True,
        ),
    }


classes = (BALLMORPH_PG_settings,)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.ballmorph_inbetween = bpy.props.PointerProperty(type=BALLMORPH_PG_settings)


def unregister():
    del bpy.types.Scene.ballmorph_inbetween
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
