"""Grease Pencil I/O: drawings to and from :class:`ballmorph_core.StrokeSet`.

This is the only code that reads or writes stroke data. Bulk data moves through
``attributes[...].data.foreach_get`` / ``foreach_set`` on numpy buffers (never a Python loop
over points). Positions are converted between the layer's space (where Blender stores them)
and the space the morph runs in with the layer's own transform (``matrix_local``), so a
layer moved, turned or scaled non-uniformly morphs the way it looks.
"""

import zlib

import bpy
import numpy as np

from ..ballmorph_core import StrokeSet

__all__ = [
    "data_collection",
    "layer_matrix",
    "read_strokes",
    "write_strokes",
    "fingerprint",
]

# Attribute name -> (domain, data type, foreach key, width, numpy dtype, value Blender assumes
# when the attribute does not exist).
_ATTRIBUTES = {
    "position": ("POINT", "FLOAT_VECTOR", "vector", 3, np.float32, 0.0),
    "radius": ("POINT", "FLOAT", "value", 1, np.float32, 0.01),
    "opacity": ("POINT", "FLOAT", "value", 1, np.float32, 1.0),
    "vertex_color": ("POINT", "FLOAT_COLOR", "color", 4, np.float32, 0.0),
    "cyclic": ("CURVE", "BOOLEAN", "value", 1, bool, False),
    "material_index": ("CURVE", "INT", "value", 1, np.int32, 0),
}
_FOREACH_KEY = {"FLOAT": "value", "BOOLEAN": "value", "INT": "value", "INT8": "value"}
_DTYPE = {"FLOAT": np.float32, "BOOLEAN": bool, "INT": np.int32, "INT8": np.int32}


def data_collection():
    """``bpy.data``'s Grease Pencil (v3) collection: renamed between Blender 4.5 and 5.0."""
    return bpy.data.grease_pencils_v3 if hasattr(bpy.data, "grease_pencils_v3") else bpy.data.grease_pencils


def layer_matrix(layer):
    """The layer's own transform (layer space -> object space), shape (4, 4)."""
    return np.array(layer.matrix_local, dtype=np.float64)


def _transform(points, matrix):
    if matrix is None:
        return points
    return points @ matrix[:3, :3].T + matrix[:3, 3]


def _offsets(drawing):
    """Stroke offsets, shape (S + 1,) (``[0]`` for a drawing without strokes)."""
    size = len(drawing.curve_offsets)
    if size < 2:  # an empty drawing reports one offset but stores none
        return np.zeros(1, dtype=np.int32)
    offsets = np.empty(size, dtype=np.int32)
    drawing.curve_offsets.foreach_get("value", offsets)
    return offsets


def _read(attributes, name, size):
    domain, _, key, width, dtype, missing = _ATTRIBUTES[name]
    attribute = attributes.get(name)
    shape = (size, width) if width > 1 else (size,)
    if attribute is None or attribute.domain != domain:
        return np.full(shape, missing, dtype=dtype)
    buffer = np.empty(size * width, dtype=dtype)
    attribute.data.foreach_get(key, buffer)
    return buffer.reshape(shape)


def _selected_strokes(attributes, offsets):
    """Per-stroke selection, shape (S,): a stroke is selected if any of its points is.

    Blender stores edit-mode selection in the ``.selection`` attribute (on points or strokes,
    bool or float); when it is absent everything counts as selected.
    """
    n_strokes = len(offsets) - 1
    attribute = attributes.get(".selection")
    if attribute is None or attribute.data_type not in _FOREACH_KEY:
        return np.ones(n_strokes, dtype=bool)
    values = np.empty(len(attribute.data), dtype=_DTYPE[attribute.data_type])
    attribute.data.foreach_get(_FOREACH_KEY[attribute.data_type], values)
    values = values.astype(bool)
    if attribute.domain == "CURVE":
        return values
    selected_before = np.concatenate([[0], np.cumsum(values, dtype=np.int64)])
    return selected_before[offsets[1:]] > selected_before[offsets[:-1]]


def read_strokes(drawing, matrix=None):
    """The strokes of a drawing.

    Parameters
    ----------
    drawing : bpy.types.GreasePencilDrawing
    matrix : ndarray, shape (4, 4), optional
        Applied to the positions (layer space -> morph space); None keeps layer space.

    Returns
    -------
    StrokeSet
        Positions (N, 3) in float64, per-point radius, opacity and vertex colour, per-stroke
        cyclic flag, material index and selection. Missing attributes get the values Blender
        itself assumes (radius 0.01, opacity 1, no vertex colour, open, material 0).
    """
    offsets = _offsets(drawing)
    if len(offsets) < 2:
        return StrokeSet.empty()
    attributes = drawing.attributes
    n_points, n_strokes = int(offsets[-1]), len(offsets) - 1
    positions = _read(attributes, "position", n_points).astype(np.float64)
    return StrokeSet(
        _transform(positions, matrix),
        offsets,
        _read(attributes, "cyclic", n_strokes),
        _read(attributes, "material_index", n_strokes),
        _read(attributes, "radius", n_points),
        _read(attributes, "opacity", n_points),
        _read(attributes, "vertex_color", n_points),
        _selected_strokes(attributes, offsets),
    )


def _write(attributes, name, values):
    domain, data_type, key, _, dtype, _ = _ATTRIBUTES[name]
    attribute = attributes.get(name)
    if attribute is None:
        attribute = attributes.new(name, data_type, domain)
    attribute.data.foreach_set(key, np.ascontiguousarray(values, dtype=dtype).reshape(-1))


def write_strokes(drawing, strokes, matrix=None):
    """Fill an empty drawing with strokes.

    Parameters
    ----------
    drawing : bpy.types.GreasePencilDrawing
        A drawing with no strokes (a new frame's).
    strokes : StrokeSet
    matrix : ndarray, shape (4, 4), optional
        Applied to the positions (morph space -> layer space); None writes them as given.

    Raises
    ------
    ValueError
        If the drawing already has strokes, or a stroke has no points.
    """
    if len(drawing.curve_offsets) > 1:
        raise ValueError("write_strokes: the drawing already has strokes")
    if len(strokes) == 0:
        return  # an empty drawing; add_strokes([]) would crash Blender 5.0.1
    sizes = strokes.sizes
    if np.any(sizes < 1):
        raise ValueError(f"write_strokes: stroke {int(np.argmin(sizes))} has no points")
    drawing.add_strokes(sizes.tolist())
    attributes = drawing.attributes
    _write(attributes, "position", _transform(strokes.positions, matrix))
    _write(attributes, "radius", strokes.radius)
    # Always written: a new drawing has no opacity attribute, which Python reads as 0.
    _write(attributes, "opacity", strokes.opacity)
    if np.any(strokes.vertex_color):
        _write(attributes, "vertex_color", strokes.vertex_color)
    _write(attributes, "cyclic", strokes.cyclic)
    _write(attributes, "material_index", strokes.material_index)
    drawing.tag_positions_changed()


def fingerprint(drawing):
    """A short hash of a drawing's stroke sizes and point positions, as Blender stores them.

    Used to recognise frames this add-on wrote and nobody changed since.
    """
    offsets = _offsets(drawing)
    positions = _read(drawing.attributes, "position", int(offsets[-1]))
    crc = zlib.crc32(offsets.astype("<i4").tobytes())
    crc = zlib.crc32(positions.astype("<f4").tobytes(), crc)
    return f"{crc:08x}"
