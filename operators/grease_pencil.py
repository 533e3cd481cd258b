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
    "selected_points",
    "select_strokes",
    "write_strokes",
    "fingerprint",
    "Staging",
    "Scratch",
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

# Every other attribute is carried: data type -> (foreach key, shape of one element, numpy dtype).
# Verified on 4.5.15 and 5.0.1 (attributes.new of each type on both domains of a drawing).
_EXTRA_TYPES = {
    "FLOAT": ("value", (), np.float32),
    "FLOAT2": ("vector", (2,), np.float32),
    "FLOAT_VECTOR": ("vector", (3,), np.float32),
    "FLOAT_COLOR": ("color", (4,), np.float32),
    "BYTE_COLOR": ("color", (4,), np.float32),
    "QUATERNION": ("value", (4,), np.float32),
    "FLOAT4X4": ("value", (4, 4), np.float32),
    "INT": ("value", (), np.int32),
    "INT8": ("value", (), np.int32),
    "INT16_2D": ("value", (2,), np.int32),
    "INT32_2D": ("value", (2,), np.int32),
    "BOOLEAN": ("value", (), bool),
}
# Attributes that define a curve's shape from its control points: an in-between's points are
# samples, so these are not carried (and its curve type is POLY or CATMULL_ROM, see below).
_SHAPE_ONLY = {"handle_left", "handle_right", "handle_type_left", "handle_type_right", "nurbs_weight"}


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


def _read_extras(attributes, n_points, n_strokes):
    """Every attribute not read into a StrokeSet field: (point dict, curve dict, types)."""
    points, curves, types = {}, {}, {}
    for attribute in attributes:
        name, kind = attribute.name, attribute.data_type
        if name in _ATTRIBUTES or name.startswith(".") or name in _SHAPE_ONLY or kind not in _EXTRA_TYPES:
            continue  # the fields, Blender's internal ones (selection), shape-only, strings
        if attribute.domain not in ("POINT", "CURVE"):
            continue
        key, shape, dtype = _EXTRA_TYPES[kind]
        size = n_points if attribute.domain == "POINT" else n_strokes
        buffer = np.empty(size * int(np.prod(shape, dtype=np.int64)), dtype=dtype)
        attribute.data.foreach_get(key, buffer)
        values = buffer.reshape(size, *shape)
        if values.ndim > 2:
            values = values.reshape(size, -1)
        if dtype is np.float32:  # floats are interpolated in float64, integers kept as integers
            values = values.astype(np.float64)
        elif dtype is not bool:
            values = values.astype(np.int64)
        (points if attribute.domain == "POINT" else curves)[name] = values
        types[name] = kind
    return points, curves, types


def selected_points(drawing):
    """Per-point edit-mode selection of a drawing, shape (N,) of bool (a selected stroke selects
    its points; without a ``.selection`` attribute everything counts as selected)."""
    offsets = _offsets(drawing)
    n_points = int(offsets[-1])
    attribute = drawing.attributes.get(".selection")
    if attribute is None or attribute.data_type not in _FOREACH_KEY:
        return np.ones(n_points, dtype=bool)
    values = np.empty(len(attribute.data), dtype=_DTYPE[attribute.data_type])
    attribute.data.foreach_get(_FOREACH_KEY[attribute.data_type], values)
    values = values.astype(bool)
    return np.repeat(values, np.diff(offsets)) if attribute.domain == "CURVE" else values


#: Blender's edit-mode selection attributes: the points' (or strokes') and, on Bezier strokes,
#: their handles'.
_SELECTION_NAMES = (".selection", ".selection_handle_left", ".selection_handle_right")


def select_strokes(drawing, selected):
    """Make the edit-mode selection of a drawing exactly the strokes ``selected`` (shape (S,) of
    bool): every point (and handle) of those, nothing else. Only the selection attributes are
    written, in the domain and type Blender keeps them (``.selection`` on points when the
    drawing has none yet: no attribute means everything is selected)."""
    offsets = _offsets(drawing)
    selected = np.asarray(selected, dtype=bool)
    if len(selected) == 0:
        return
    attributes = drawing.attributes
    if attributes.get(".selection") is None:
        attributes.new(".selection", "BOOLEAN", "POINT")
    for name in _SELECTION_NAMES:
        attribute = attributes.get(name)
        if attribute is None or attribute.data_type not in _FOREACH_KEY:
            continue
        values = selected if attribute.domain == "CURVE" else np.repeat(selected, np.diff(offsets))
        attribute.data.foreach_set(_FOREACH_KEY[attribute.data_type], values.astype(_DTYPE[attribute.data_type]))


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
    points, curves, types = _read_extras(attributes, n_points, n_strokes)
    return StrokeSet(
        _transform(positions, matrix),
        offsets,
        _read(attributes, "cyclic", n_strokes),
        _read(attributes, "material_index", n_strokes),
        _read(attributes, "radius", n_points),
        _read(attributes, "opacity", n_points),
        _read(attributes, "vertex_color", n_points),
        _selected_strokes(attributes, offsets),
        point_attributes=points,
        curve_attributes=curves,
        attribute_types=types,
    )


class Staging:
    """Buffers the arrays handed to ``foreach_set`` are converted in, one per dtype, kept from
    drawing to drawing (Blender copies what it is given): a fresh converted copy of every
    attribute of every frame is page-faulted anew in Blender's process."""

    def __init__(self):
        self._buffers = {}

    def flat(self, values, dtype):
        """``values`` as a flat contiguous array of ``dtype``: itself when it is one, else
        converted (as ``astype`` does) into this dtype's buffer, valid until the next call."""
        values = np.asarray(values)
        if values.dtype == dtype and values.flags.c_contiguous:
            return values.reshape(-1)
        dtype = np.dtype(dtype)
        buffer = self._buffers.get(dtype)
        if buffer is None or len(buffer) < values.size:
            buffer = self._buffers[dtype] = np.empty(values.size, dtype)
        out = buffer[: values.size]
        np.copyto(out.reshape(values.shape), values, casting="unsafe")
        return out


def _write(attributes, name, values, staging):
    domain, data_type, key, _, dtype, _ = _ATTRIBUTES[name]
    attribute = attributes.get(name)
    if attribute is None:
        attribute = attributes.new(name, data_type, domain)
    attribute.data.foreach_set(key, staging.flat(values, dtype))


def write_strokes(drawing, strokes, matrix=None, staging=None):
    """Fill an empty drawing with strokes.

    Parameters
    ----------
    drawing : bpy.types.GreasePencilDrawing
        A drawing with no strokes (a new frame's).
    strokes : StrokeSet
    matrix : ndarray, shape (4, 4), optional
        Applied to the positions (morph space -> layer space); None writes them as given.
    staging : Staging, optional
        Conversion buffers to reuse (a writer of many drawings passes one for them all).

    Returns
    -------
    str
        The drawing's :func:`fingerprint` as written (made from the arrays handed to Blender,
        not read back from it).

    Raises
    ------
    ValueError
        If the drawing already has strokes, or a stroke has no points.
    """
    if len(drawing.curve_offsets) > 1:
        raise ValueError("write_strokes: the drawing already has strokes")
    if len(strokes) == 0:
        # An empty drawing (add_strokes([]) would crash Blender 5.0.1).
        return _fingerprint(np.zeros(1, dtype=np.int32), np.zeros((0, 3), dtype=np.float32))
    sizes = strokes.sizes
    if np.any(sizes < 1):
        raise ValueError(f"write_strokes: stroke {int(np.argmin(sizes))} has no points")
    staging = Staging() if staging is None else staging
    drawing.add_strokes(sizes.tolist())
    attributes = drawing.attributes
    positions = staging.flat(_transform(strokes.positions, matrix), np.float32)
    _write(attributes, "position", positions, staging)
    # Now: the staging buffer is reused for the next attributes.
    written = _fingerprint(strokes.offsets, positions)
    _write(attributes, "radius", strokes.radius, staging)
    # Always written: a new drawing has no opacity attribute, which Python reads as 0.
    _write(attributes, "opacity", strokes.opacity, staging)
    if _any_nonzero(strokes.vertex_color):
        _write(attributes, "vertex_color", strokes.vertex_color, staging)
    _write(attributes, "cyclic", strokes.cyclic, staging)
    _write(attributes, "material_index", strokes.material_index, staging)
    for domain, extras in (("POINT", strokes.point_attributes), ("CURVE", strokes.curve_attributes)):
        for name, values in extras.items():
            _write_extra(attributes, name, domain, strokes.attribute_types.get(name), values, staging)
    drawing.tag_positions_changed()
    return written


class Scratch:
    """A frame of one layer whose drawing is filled and copied into every new frame.

    ``foreach_set`` finds the drawing an attribute belongs to by scanning the data-block's
    drawings from the first: a call costs as many drawings as come before it, and a new frame's
    drawing is the last one (1.4 ms a call for the 8,000th drawing, against 6 us for the
    first), so filling each new frame in turn is quadratic in the frames. The scratch drawing is
    made once, before the new frames, and ``frames.copy`` duplicates it without that scan.

    Parameters
    ----------
    layer : bpy.types.GreasePencilLayer
    number : int
        A frame number free on the layer (the scratch frame is removed by :meth:`remove`).
    """

    def __init__(self, layer, number):
        self.layer, self.number = layer, number
        frame = layer.frames.new(number)
        frame.keyframe_type = "BREAKDOWN"  # what every copy is
        frame.select = False
        self._drawing = frame.drawing

    def write(self, number, strokes, staging):
        """A new frame ``number`` holding ``strokes`` (StrokeSet, layer space): ``(frame,
        fingerprint)``, as :func:`write_strokes` gives it."""
        drawing = self._drawing
        if len(drawing.curve_offsets) > 1:
            drawing.remove_strokes()
        # The attributes an earlier frame wrote and this one does not: gone, as from a new drawing.
        wanted = _written_names(strokes)
        for name in [a.name for a in drawing.attributes if a.name not in wanted and not a.name.startswith(".")]:
            drawing.attributes.remove(drawing.attributes[name])
        written = write_strokes(drawing, strokes, staging=staging)
        return self.layer.frames.copy(self.number, number), written

    def remove(self):
        """Remove the scratch frame (if it is still there)."""
        if any(frame.frame_number == self.number for frame in self.layer.frames):
            self.layer.frames.remove(self.number)


def _written_names(strokes):
    """The attributes :func:`write_strokes` writes for ``strokes`` (and ``position``), a set."""
    names = {"position", "radius", "opacity", "cyclic", "material_index"}
    if len(strokes) and _any_nonzero(strokes.vertex_color):
        names.add("vertex_color")
    return names | set(strokes.point_attributes) | set(strokes.curve_attributes)


def _any_nonzero(values):
    """``np.any(values)`` of a float array, from its extremes (a NaN is nonzero, as in np.any):
    numpy 1.26's any makes every value a bool first, 5 times slower over a frame's colours."""
    return values.size > 0 and not (values.max() == 0 and values.min() == 0)


def _write_extra(attributes, name, domain, kind, values, staging):
    """Write one carried attribute with its own data type (guessed from the values if unknown)."""
    values = np.asarray(values)
    if name == "curve_type":
        # Resampled points are no Bezier or NURBS control points: those strokes become POLY
        # (two comparisons, not np.isin: its set machinery was 0.8 ms of a 100x200x9 redo).
        values = np.where((values == 2) | (values == 3), 0, values)
    if kind not in _EXTRA_TYPES:
        kind = _guess_type(values)
    key, shape, dtype = _EXTRA_TYPES[kind]
    attribute = attributes.get(name)
    if attribute is None or attribute.domain != domain or attribute.data_type != kind:
        if attribute is not None:
            attributes.remove(attribute)
        attribute = attributes.new(name, kind, domain)
    attribute.data.foreach_set(key, staging.flat(values, dtype))


def _guess_type(values):
    """Blender's data type for an attribute array the core made up (no type recorded)."""
    width = values.shape[1] if values.ndim > 1 else 1
    if values.dtype == bool:
        return "BOOLEAN"
    if np.issubdtype(values.dtype, np.integer):
        return {1: "INT", 2: "INT32_2D"}.get(width, "INT")
    return {1: "FLOAT", 2: "FLOAT2", 3: "FLOAT_VECTOR", 4: "FLOAT_COLOR", 16: "FLOAT4X4"}.get(width, "FLOAT")


def fingerprint(drawing):
    """A short hash of a drawing's stroke sizes and point positions, as Blender stores them.

    Used to recognise frames this add-on wrote and nobody changed since.
    """
    offsets = _offsets(drawing)
    return _fingerprint(offsets, _read(drawing.attributes, "position", int(offsets[-1])))


def _fingerprint(offsets, positions):
    """The hash of stroke offsets (S + 1,) and positions (N, 3) as Blender stores them (int32,
    float32)."""
    crc = zlib.crc32(np.ascontiguousarray(offsets, dtype="<i4"))
    crc = zlib.crc32(np.ascontiguousarray(positions, dtype="<f4"), crc)  # its buffer: no copy
    return f"{crc:08x}"
