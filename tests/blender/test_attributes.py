"""Issue 12: every POINT and CURVE attribute of the keys is carried to the in-betweens, on both
Blender versions: floats, vectors and colours interpolated, integers and booleans from the key
nearer in time, an attribute only one key has mixed with Blender's 0."""

import bpy
import gp_data
import numpy as np
import pytest


def _set(drawing, name, data_type, domain, values):
    attributes = drawing.attributes
    attribute = attributes.get(name) or attributes.new(name, data_type, domain)
    key = {"FLOAT_VECTOR": "vector", "FLOAT2": "vector", "FLOAT_COLOR": "color"}.get(data_type, "value")
    attribute.data.foreach_set(key, np.asarray(values).ravel())


def _get(drawing, name):
    attribute = drawing.attributes[name]
    key = {"FLOAT_VECTOR": "vector", "FLOAT2": "vector", "FLOAT_COLOR": "color"}.get(attribute.data_type, "value")
    width = {"FLOAT_VECTOR": 3, "FLOAT2": 2, "FLOAT_COLOR": 4}.get(attribute.data_type, 1)
    dtype = {"INT": np.int32, "INT8": np.int32, "BOOLEAN": bool}.get(attribute.data_type, np.float32)
    out = np.empty(len(attribute.data) * width, dtype=dtype)
    attribute.data.foreach_get(key, out)
    return (
        attribute.domain,
        attribute.data_type,
        out.reshape(len(attribute.data), -1).squeeze(1) if width == 1 else out.reshape(-1, width),
    )


@pytest.fixture
def keys(addon):
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    strokes = [gp_data.arc(0.3), gp_data.loop(0.3, centre=(2.0, 0.0))]
    for number, value in ((1, 0.0), (9, 1.0)):
        gp_data.add_key(layer, number, strokes, cyclic=[False, True])
        drawing = gp_data.frame_at(layer, number).drawing
        n = len(drawing.attributes["position"].data)
        _set(drawing, "softness", "FLOAT", "POINT", np.full(n, value, np.float32))  # a built-in
        _set(
            drawing,
            "fill_color",
            "FLOAT_COLOR",
            "CURVE",
            np.tile([value, 0.5, 1 - value, 1.0], (2, 1)).astype(np.float32),
        )
        _set(drawing, "uv_shift", "FLOAT2", "POINT", np.full((n, 2), value, np.float32))  # a user vector
        _set(drawing, "my_id", "INT", "POINT", np.full(n, 7 if number == 1 else 9, np.int32))  # a user integer
        _set(drawing, "inked", "BOOLEAN", "CURVE", np.array([number == 1, True]))
        if number == 1:
            _set(drawing, "only_first", "FLOAT", "POINT", np.full(n, 2.0, np.float32))
    bpy.context.scene.frame_current = 5
    return layer


def test_every_attribute_reaches_every_in_between(keys):
    assert bpy.ops.ballmorph.inbetween(method="CIRCULAR_BALL") == {"FINISHED"}
    for number in range(2, 9):
        t = (number - 1) / 8
        drawing = gp_data.frame_at(keys, number).drawing
        domain, kind, softness = _get(drawing, "softness")
        assert (domain, kind) == ("POINT", "FLOAT")
        np.testing.assert_allclose(softness, t, atol=1e-6)
        domain, kind, fill = _get(drawing, "fill_color")
        assert (domain, kind) == ("CURVE", "FLOAT_COLOR")
        np.testing.assert_allclose(fill, np.tile([t, 0.5, 1 - t, 1.0], (2, 1)), atol=1e-6)
        assert _get(drawing, "uv_shift")[:2] == ("POINT", "FLOAT2")
        np.testing.assert_allclose(_get(drawing, "uv_shift")[2], t, atol=1e-6)
        domain, kind, ids = _get(drawing, "my_id")
        assert (domain, kind) == ("POINT", "INT")
        assert set(ids.tolist()) == {7 if t < 0.5 else 9}  # from the nearer key, never mixed
        assert _get(drawing, "inked")[2].tolist() == [t < 0.5, True]
        # Only the first key has it: the second's is Blender's 0.
        np.testing.assert_allclose(_get(drawing, "only_first")[2], 2.0 * (1 - t), atol=1e-6)
