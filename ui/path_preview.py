"""The path preview in the 3D viewport: a thin ``gpu`` draw handler.

The sidebar's *Path Preview* toggle (``scene.ballmorph_inbetween.path_preview``) installs it and
removes it (:func:`sync`); disabling the add-on removes it too. What it draws comes ready from
:data:`..operators.preview.PREVIEW` (the trajectories of the keys around the current frame, in
world space), one colour per stroke pair; the handler only turns them into one GPU batch, and
keeps the batch until the trajectories change. In background mode (no GPU) it draws nothing.

Blender 4.5 and 5.0 both have the built-in shader ``'POLYLINE_SMOOTH_COLOR'`` (attributes
``pos``, ``color``; uniforms ``viewportSize``, ``lineWidth``), drawn with
``gpu_extras.batch.batch_for_shader(shader, 'LINES', ..., indices=...)``.
"""

import bpy
import numpy as np

from ..ballmorph_core import pair_colors
from ..operators.preview import PREVIEW
from . import overlay

__all__ = ["draw", "installed", "sync", "toggled", "register", "unregister"]

#: The built-in shader the trajectories are drawn with (the same name in Blender 4.5 and 5.0).
SHADER = "POLYLINE_SMOOTH_COLOR"
#: Trajectory width in pixels at a Resolution Scale of 1 (scaled by the UI scale), and opacity.
LINE_WIDTH = 2.0
ALPHA = 0.9

_handle = None  # the SpaceView3D draw handler, while installed
_batch = (None, None)  # (the PathPreview drawn, its GPU batch)


def _toggle_on(scene):
    settings = getattr(scene, "ballmorph_inbetween", None)
    return settings is not None and settings.path_preview


def draw():
    """The draw handler: the current scene's trajectories, if its toggle is on."""
    if bpy.app.background:
        return
    context = bpy.context
    if not _toggle_on(context.scene) or not overlay.overlays_shown(context):
        return
    preview = PREVIEW.world(context)
    if preview is not None and len(preview):
        _draw_lines(preview)


def _draw_lines(preview):
    """Draw a PathPreview's trajectories as coloured lines (needs a GPU: never in background)."""
    global _batch
    import gpu
    from gpu_extras.batch import batch_for_shader

    shader = gpu.shader.from_builtin(SHADER)
    if _batch[0] is not preview:
        vertices, indices, owner = preview.segments()
        content = {
            "pos": vertices.astype(np.float32),
            "color": pair_colors(preview.pair, ALPHA)[owner].astype(np.float32),
        }
        _batch = (preview, batch_for_shader(shader, "LINES", content, indices=indices.astype(np.int32)))
    gpu.state.blend_set("ALPHA")
    shader.uniform_float("viewportSize", gpu.state.viewport_get()[2:])
    shader.uniform_float("lineWidth", LINE_WIDTH * overlay.ui_scale(bpy.context))
    _batch[1].draw(shader)
    gpu.state.blend_set("NONE")


@bpy.app.handlers.persistent
def _edited(*args):
    PREVIEW.edited()


@bpy.app.handlers.persistent
def _loaded(*args):
    PREVIEW.clear()
    sync()


def installed():
    """Whether the draw handler is installed."""
    return _handle is not None


def _install():
    global _handle
    _handle = overlay.install(_handle, draw, "POST_VIEW", _edited)


def _remove():
    global _handle, _batch
    _handle = overlay.remove(_handle, _edited)
    _batch = (None, None)
    PREVIEW.clear()


def toggled(settings, context):
    """The toggle's update callback."""
    sync()


def sync():
    """Install the handler when any scene's toggle is on, remove it otherwise (when the toggle
    changes, the add-on is enabled or a file is loaded)."""
    scenes = getattr(bpy.data, "scenes", ())  # (bpy.data is restricted while add-ons load)
    if any(_toggle_on(scene) for scene in scenes):
        _install()
    else:
        _remove()
    _redraw()


def _redraw():
    """Redraw every 3D viewport (there are none in background mode)."""
    for window in getattr(getattr(bpy.context, "window_manager", None), "windows", ()):
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()


def register():
    bpy.app.handlers.load_post.append(_loaded)
    sync()


def unregister():
    _remove()
    if _loaded in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.remove(_loaded)
