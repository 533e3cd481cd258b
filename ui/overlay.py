"""A viewport overlay's two Blender hooks: its ``SpaceView3D`` draw handler and the depsgraph
callback that tells its source the data changed (the hint dots and the path preview share them),
and the viewport's Overlays switch that both obey.

The callbacks stay functions of their own modules: ``bpy.app.handlers.persistent`` marks a
function, and the tests find each overlay's callback by its module.
"""

import bpy

__all__ = ["install", "remove", "overlays_shown", "ui_scale"]


def install(handle, draw, kind, edited):
    """The draw handler ``draw`` (``kind``: 'POST_VIEW', 'POST_PIXEL') and the depsgraph
    callback ``edited``, each added unless already there; returns the draw handler's handle."""
    if handle is None:
        handle = bpy.types.SpaceView3D.draw_handler_add(draw, (), "WINDOW", kind)
    if edited not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(edited)
    return handle


def remove(handle, edited):
    """Both hooks removed (those that are there); returns None, the handle to keep."""
    if handle is not None:
        bpy.types.SpaceView3D.draw_handler_remove(handle, "WINDOW")
    if edited in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(edited)
    return None


def overlays_shown(context):
    """Whether the viewport being drawn shows overlays (its Overlays switch; True outside a viewport)."""
    overlay = getattr(getattr(context, "space_data", None), "overlay", None)
    return overlay is None or overlay.show_overlays


def ui_scale(context):
    """The interface scale overlays size their pixels by (the Resolution Scale preference times
    the display's own scale); 1 where Blender has none (background mode reads 0)."""
    return context.preferences.system.ui_scale or 1.0
