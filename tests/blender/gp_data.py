"""Build and inspect Grease Pencil data with Blender's raw API, independently of the add-on.

The tests write keys with these helpers and read results back with them, so the add-on's own
I/O layer is checked against plain ``foreach_get``/``foreach_set`` code rather than itself.
"""

import bpy
import numpy as np

import ballmorph_core as bm

# Every attribute a drawing may carry that the tests compare byte for byte.
POINT_ATTRIBUTES = {"position": ("vector", 3), "radius": ("value", 1), "opacity": ("value", 1)}


def collection():
    return bpy.data.grease_pencils_v3 if hasattr(bpy.data, "grease_pencils_v3") else bpy.data.grease_pencils


def new_object(name="Drawing", layers=("Ink",)):
    """A Grease Pencil object with the given layers, linked to the scene and made active."""
    data = collection().new(name)
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    for material_name in ("Black", "Red"):
        material = bpy.data.materials.new(material_name)
        bpy.data.materials.create_gpencil_data(material)
        data.materials.append(material)
    for layer_name in layers:
        data.layers.new(layer_name)
    data.layers.active = data.layers[layers[0]]
    return obj


def loop(scale=1.0, n=80, centre=(0.0, 0.0), wobble=0.0):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = scale * (1 + wobble * np.cos(3 * t))
    return np.c_[centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)]


def arc(height, n=60):
    x = np.linspace(0, 2, n)
    return np.c_[x, height * np.sin(np.pi * x / 2)]


def add_key(layer, number, strokes, cyclic=None, materials=None, radius=None, opacity=None, colors=None):
    """Write a keyframe from a list of (n, 2) strokes on the front (XZ) canvas.

    Per-point radius/opacity default to ramps so interpolation is visible; vertex colour to
    a per-stroke grey.
    """
    frame = layer.frames.new(number)
    drawing = frame.drawing
    sizes = [len(s) for s in strokes]
    drawing.add_strokes(sizes)
    points = np.concatenate([np.c_[s[:, 0], np.zeros(len(s)), s[:, 1]] for s in strokes])
    n = len(points)
    attributes = drawing.attributes
    for name, data_type, domain in (
        ("radius", "FLOAT", "POINT"),
        ("opacity", "FLOAT", "POINT"),
        ("vertex_color", "FLOAT_COLOR", "POINT"),
        ("cyclic", "BOOLEAN", "CURVE"),
        ("material_index", "INT", "CURVE"),
    ):
        if name not in attributes:
            attributes.new(name, data_type, domain)
    radius = np.linspace(0.02, 0.04, n) if radius is None else np.asarray(radius)
    opacity = np.linspace(0.5, 1.0, n) if opacity is None else np.asarray(opacity)
    if colors is None:
        colors = np.repeat(np.linspace(0.2, 0.8, len(strokes)), sizes)[:, None] * np.array([1, 1, 1, 1.0])
    attributes["position"].data.foreach_set("vector", points.astype(np.float32).ravel())
    attributes["radius"].data.foreach_set("value", radius.astype(np.float32))
    attributes["opacity"].data.foreach_set("value", opacity.astype(np.float32))
    attributes["vertex_color"].data.foreach_set("color", np.asarray(colors, np.float32).ravel())
    cyclic = np.zeros(len(strokes), bool) if cyclic is None else np.asarray(cyclic, bool)
    attributes["cyclic"].data.foreach_set("value", cyclic)
    materials = np.zeros(len(strokes), np.int32) if materials is None else np.asarray(materials, np.int32)
    attributes["material_index"].data.foreach_set("value", materials)
    return frame


def frame_at(layer, number):
    return next((f for f in layer.frames if f.frame_number == number), None)


def frame_numbers(layer):
    return sorted(f.frame_number for f in layer.frames)


def read_raw(drawing):
    """Every attribute of a drawing as {name: (domain, data_type, bytes)} plus the offsets."""
    out = {}
    offsets = np.zeros(len(drawing.curve_offsets), np.int32)  # zeros: an empty drawing ...
    if len(offsets) > 1:  # ... reports one offset but stores none
        drawing.curve_offsets.foreach_get("value", offsets)
    out["curve_offsets"] = ("CURVE", "INT", offsets.tobytes())
    for attribute in drawing.attributes:
        key, dtype, width = {
            "FLOAT": ("value", np.float32, 1),
            "INT": ("value", np.int32, 1),
            "INT8": ("value", np.int32, 1),
            "BOOLEAN": ("value", bool, 1),
            "FLOAT_VECTOR": ("vector", np.float32, 3),
            "FLOAT2": ("vector", np.float32, 2),
            "FLOAT_COLOR": ("color", np.float32, 4),
            "BYTE_COLOR": ("color", np.float32, 4),
            "QUATERNION": ("value", np.float32, 4),
        }[attribute.data_type]
        buffer = np.empty(len(attribute.data) * width, dtype)
        attribute.data.foreach_get(key, buffer)
        out[attribute.name] = (attribute.domain, attribute.data_type, buffer.tobytes())
    return out


def read_strokes(drawing):
    """A drawing as a core StrokeSet (positions in layer space), with plain foreach_get."""
    if len(drawing.curve_offsets) < 2:
        return bm.StrokeSet.empty()
    offsets = np.empty(len(drawing.curve_offsets), np.int32)
    drawing.curve_offsets.foreach_get("value", offsets)
    n, s = int(offsets[-1]), len(offsets) - 1
    a = drawing.attributes

    def get(name, key, width, dtype, size, missing):
        if name not in a:
            return np.full(size * width, missing, dtype)
        buffer = np.empty(size * width, dtype)
        a[name].data.foreach_get(key, buffer)
        return buffer

    return bm.StrokeSet(
        get("position", "vector", 3, np.float32, n, 0).reshape(-1, 3),
        offsets,
        get("cyclic", "value", 1, bool, s, False),
        get("material_index", "value", 1, np.int32, s, 0),
        get("radius", "value", 1, np.float32, n, 0.01),
        get("opacity", "value", 1, np.float32, n, 1.0),
        get("vertex_color", "color", 4, np.float32, n, 0).reshape(-1, 4),
    )


def dopesheet_override(gpencil_mode=True):
    """Context override for the factory screen's Dope Sheet area (switched to Grease Pencil mode)."""
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "DOPESHEET_EDITOR")
    area.ui_type = "DOPESHEET"
    if gpencil_mode:
        area.spaces.active.ui_mode = "GPENCIL"
    region = next(r for r in area.regions if r.type == "WINDOW")
    return bpy.context.temp_override(window=window, area=area, region=region)


def view3d_override():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return bpy.context.temp_override(window=window, area=area, region=region)


def snapshot(obj):
    """Every frame of every layer of a Grease Pencil object, to compare byte for byte.

    Returns ``{layer name: {frame number: (keyframe_type, read_raw(drawing))}}``: frame numbers,
    keyframe types, stroke offsets and every attribute of every drawing.
    """
    return {
        layer.name: {
            frame.frame_number: (frame.keyframe_type, read_raw(frame.drawing))
            for frame in sorted(layer.frames, key=lambda f: f.frame_number)
        }
        for layer in obj.data.layers
    }


def marks(obj):
    """The add-on's record of the frames it wrote (a plain dict; {} when there is none)."""
    record = obj.data.get("ballmorph_inbetween")
    return record.to_dict() if record is not None else {}


def ensure_interpolate_curve(points=None):
    """The scene's Interpolate curve (tool settings), made as Blender makes it: by running
    Interpolate Sequence once (on a throwaway object, removed after); with ``points``
    (``[(x, y), ...]``) it is set to that polyline (vector handles)."""
    settings = bpy.context.scene.tool_settings.gpencil_interpolate
    if settings.interpolation_curve is None:
        active = bpy.context.view_layer.objects.active
        frame = bpy.context.scene.frame_current
        scratch = new_object("Scratch")
        layer = scratch.data.layers["Ink"]
        add_key(layer, 1, [loop(1.0)], cyclic=[True])
        add_key(layer, 3, [loop(2.0)], cyclic=[True])
        bpy.context.scene.frame_current = 2
        assert bpy.ops.grease_pencil.interpolate_sequence() == {"FINISHED"}
        data = scratch.data
        bpy.data.objects.remove(scratch)
        collection().remove(data)
        bpy.context.view_layer.objects.active = active
        bpy.context.scene.frame_current = frame
    mapping = settings.interpolation_curve
    if points is not None:
        curve = mapping.curves[0]
        while len(curve.points) > 2:
            curve.points.remove(curve.points[1])
        curve.points[0].location, curve.points[-1].location = points[0], points[-1]
        for x, y in points[1:-1]:
            curve.points.new(x, y)
        for point in curve.points:
            point.handle_type = "VECTOR"
        mapping.update()
    return mapping
