"""Correspondence hints in the 3D viewport: a numbered dot on every hinted point of the two keys
around the current frame (the earlier key's in orange, the later's in blue).

A thin ``POST_PIXEL`` draw handler over :data:`..operators.hints.MARKS` (which reads the hints
only when the frame or the data changed); installed with the add-on, removed with it, and
drawing nothing in background mode (no GPU). Blender 4.5 and 5.0 both have the built-in shader
``'UNIFORM_COLOR'`` and ``blf`` for the numbers.

Like Blender's own overlays, the dots follow the viewport's Overlays switch and have a toggle of
their own (``scene.ballmorph_inbetween.hint_dots``, in the Overlays popover's Grease Pencil
Options and in the sidebar), and their size follows the Resolution Scale preference.
"""

import bpy

from ..operators.hints import MARKS
from . import overlay

__all__ = ["draw", "installed", "shown", "sizes", "register", "unregister"]

#: Dot size, the numbers' size and offset, in pixels at a Resolution Scale of 1; each key's colour.
DOT_SIZE = 8.0
TEXT_SIZE = 14
TEXT_OFFSET = (6.0, 6.0)
COLORS = ((1.0, 0.55, 0.1, 1.0), (0.2, 0.6, 1.0, 1.0))

_handle = None


def sizes(ui_scale):
    """``(dot size, text size, text offset)`` in pixels at this UI scale
    (``preferences.system.ui_scale``: the Resolution Scale times the display's own scale)."""
    return DOT_SIZE * ui_scale, TEXT_SIZE * ui_scale, (TEXT_OFFSET[0] * ui_scale, TEXT_OFFSET[1] * ui_scale)


def shown(context):
    """Whether the dots are wanted: the viewport shows overlays and the hint dots are on."""
    if not overlay.overlays_shown(context):
        return False
    settings = getattr(context.scene, "ballmorph_inbetween", None) if context.scene is not None else None
    return settings is None or settings.hint_dots


def draw():
    """The draw handler: the active layer's hints on the keys around the current frame."""
    if bpy.app.background:
        return
    context = bpy.context
    region, view = context.region, context.region_data
    if region is None or view is None or not shown(context):
        return
    marks = MARKS.marks(context)
    if marks is not None:
        _draw_marks(region, view, *marks, sizes(overlay.ui_scale(context)))


def _draw_marks(region, view, points, numbers, side, scaled):
    import blf
    import gpu
    from bpy_extras.view3d_utils import location_3d_to_region_2d
    from gpu_extras.batch import batch_for_shader

    dot_size, text_size, text_offset = scaled
    shader = gpu.shader.from_builtin("UNIFORM_COLOR")
    gpu.state.point_size_set(dot_size)
    font = 0
    blf.size(font, text_size)
    for which, color in enumerate(COLORS):
        shown = [(location_3d_to_region_2d(region, view, p), n) for p, n, s in zip(points, numbers, side) if s == which]
        shown = [(xy, n) for xy, n in shown if xy is not None]
        if not shown:
            continue
        batch = batch_for_shader(shader, "POINTS", {"pos": [(xy.x, xy.y) for xy, _ in shown]})
        shader.uniform_float("color", color)
        batch.draw(shader)
        blf.color(font, *color)
        for xy, number in shown:
            blf.position(font, xy.x + text_offset[0], xy.y + text_offset[1], 0)
            blf.draw(font, str(int(number)))
    gpu.state.point_size_set(1.0)


@bpy.app.handlers.persistent
def _edited(*args):
    MARKS.edited()


def installed():
    """Whether the draw handler is installed."""
    return _handle is not None


def draw_toggle(self, context):
    """The toggle in the viewport's Overlays popover (Grease Pencil Options)."""
    settings = getattr(context.scene, "ballmorph_inbetween", None)
    if settings is not None:
        self.layout.prop(settings, "hint_dots")


#: Blender's panel the toggle is appended to (the Overlays popover, with a Grease Pencil object).
TOGGLE_PANEL = "VIEW3D_PT_overlay_grease_pencil_options"


def register():
    global _handle
    _handle = overlay.install(_handle, draw, "POST_PIXEL", _edited)
    getattr(bpy.types, TOGGLE_PANEL).append(draw_toggle)


def unregister():
    global _handle
    getattr(bpy.types, TOGGLE_PANEL).remove(draw_toggle)
    _handle = overlay.remove(_handle, _edited)
