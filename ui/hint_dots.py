"""Correspondence hints in the 3D viewport: a numbered dot on every hinted point of the two keys
around the current frame (the earlier key's in orange, the later's in blue).

A thin ``POST_PIXEL`` draw handler over :data:`..operators.hints.MARKS` (which reads the hints
only when the frame or the data changed); installed with the add-on, removed with it, and
drawing nothing in background mode (no GPU). Blender 4.5 and 5.0 both have the built-in shader
``'UNIFORM_COLOR'`` and ``blf`` for the numbers.
"""

import bpy

from ..operators.hints import MARKS
from . import overlay

__all__ = ["draw", "installed", "register", "unregister"]

#: Dot size in pixels, the numbers' size and offset, and each key's colour.
DOT_SIZE = 8.0
TEXT_SIZE = 14
TEXT_OFFSET = (6.0, 6.0)
COLORS = ((1.0, 0.55, 0.1, 1.0), (0.2, 0.6, 1.0, 1.0))

_handle = None


def draw():
    """The draw handler: the active layer's hints on the keys around the current frame."""
    if bpy.app.background:
        return
    context = bpy.context
    region, view = context.region, context.region_data
    if region is None or view is None:
        return
    marks = MARKS.marks(context)
    if marks is not None:
        _draw_marks(region, view, *marks)


def _draw_marks(region, view, points, numbers, side):
    import blf
    import gpu
    from bpy_extras.view3d_utils import location_3d_to_region_2d
    from gpu_extras.batch import batch_for_shader

    shader = gpu.shader.from_builtin("UNIFORM_COLOR")
    gpu.state.point_size_set(DOT_SIZE)
    font = 0
    blf.size(font, TEXT_SIZE)
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
            blf.position(font, xy.x + TEXT_OFFSET[0], xy.y + TEXT_OFFSET[1], 0)
            blf.draw(font, str(int(number)))
    gpu.state.point_size_set(1.0)


@bpy.app.handlers.persistent
def _edited(*args):
    MARKS.edited()


def installed():
    """Whether the draw handler is installed."""
    return _handle is not None


def register():
    global _handle
    _handle = overlay.install(_handle, draw, "POST_PIXEL", _edited)


def unregister():
    global _handle
    _handle = overlay.remove(_handle, _edited)
