"""Which frames this add-on made, so a re-run replaces them and nothing else.

Grease Pencil layers and frames cannot hold custom properties, so the record lives on the
Grease Pencil data-block (saved with the .blend, restored by undo)::

    grease_pencil["ballmorph_inbetween"] = {layer key: {"<frame number>": "<fingerprint>"}}

A frame counts as ours only while all of these hold: it is recorded for its layer and frame
number, it is still a 'BREAKDOWN' keyframe, and its strokes still have the fingerprint we
recorded (see :func:`.grease_pencil.fingerprint`). So a breakdown the animator redrew, moved,
retyped or copied elsewhere becomes theirs and is never touched again; renaming a layer also
makes its in-betweens the animator's (the safe direction).
"""

import zlib

from . import grease_pencil

__all__ = ["is_generated", "mark", "unmark", "prune"]

PROPERTY = "ballmorph_inbetween"
_MAX_KEY = 63  # Blender's ID property names hold at most 63 bytes


def _layer_key(layer):
    name = layer.name
    if len(name.encode()) <= _MAX_KEY:
        return name
    return f"~{zlib.crc32(name.encode()):08x}"


def _records(grease_pencil_data, layer, create=False):
    """The {frame number: fingerprint} group of a layer (None if absent and not created)."""
    root = grease_pencil_data.get(PROPERTY)
    if root is None:
        if not create:
            return None
        grease_pencil_data[PROPERTY] = {}
        root = grease_pencil_data[PROPERTY]
    key = _layer_key(layer)
    if key not in root:
        if not create:
            return None
        root[key] = {}
    return root[key]


def is_generated(grease_pencil_data, layer, frame):
    """Whether ``frame`` (a frame of ``layer``) is an unchanged in-between this add-on wrote."""
    records = _records(grease_pencil_data, layer)
    if records is None or frame.keyframe_type != "BREAKDOWN":
        return False
    recorded = records.get(str(frame.frame_number))
    return recorded is not None and recorded == grease_pencil.fingerprint(frame.drawing)


def mark(grease_pencil_data, layer, frame):
    """Record ``frame`` as written by this add-on (call after its strokes are written)."""
    _records(grease_pencil_data, layer, create=True)[str(frame.frame_number)] = grease_pencil.fingerprint(frame.drawing)


def unmark(grease_pencil_data, layer, frame_number):
    """Forget the record of a frame number (when that frame is removed)."""
    records = _records(grease_pencil_data, layer)
    if records is not None and str(frame_number) in records:
        del records[str(frame_number)]


def prune(grease_pencil_data, layer):
    """Drop records of frames that no longer exist or are no longer ours."""
    records = _records(grease_pencil_data, layer)
    if records is None:
        return
    frames = {frame.frame_number: frame for frame in layer.frames}
    for number in list(records.keys()):
        frame = frames.get(int(number)) if number.lstrip("-").isdigit() else None
        if frame is None or not is_generated(grease_pencil_data, layer, frame):
            del records[number]
