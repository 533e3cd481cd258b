"""Which frames this add-on made, so a re-run replaces them and nothing else.

Grease Pencil layers and frames cannot hold custom properties, so the record lives on the
Grease Pencil data-block (saved with the .blend)::

    grease_pencil["ballmorph_inbetween"] = {layer key: {"<frame number>": "<fingerprint> ..."}}

A frame counts as ours only while all of these hold: it is still a 'BREAKDOWN' keyframe, and
its strokes have a fingerprint (see :func:`.grease_pencil.fingerprint`) that we recorded for
its layer and frame number. So a breakdown the animator redrew, moved, retyped or copied
elsewhere becomes theirs and is never touched again; renaming a layer also makes its
in-betweens the animator's (the safe direction).

Each frame number keeps the last few fingerprints written there, not only the latest: undo in
Edit Mode restores the frames but not this record (Blender's edit-mode undo step stores the
drawings and layers, not the data-block's custom properties), so after undoing a re-run the
frames it replaced must still be recognised. Undo in Object or Draw Mode restores both.
"""

from ..addon_logic.id_keys import id_key
from . import grease_pencil

__all__ = ["is_generated", "mark", "mark_many", "save", "restore"]

PROPERTY = "ballmorph_inbetween"
# Fingerprints kept per frame number: how many re-runs an edit-mode undo can go back through.
_HISTORY = 8


def _records(grease_pencil_data, layer, create=False):
    """The {frame number: fingerprints} group of a layer (None if absent and not created)."""
    root = grease_pencil_data.get(PROPERTY)
    if root is None:
        if not create:
            return None
        grease_pencil_data[PROPERTY] = {}
        root = grease_pencil_data[PROPERTY]
    key = id_key(layer.name)
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
    return recorded is not None and grease_pencil.fingerprint(frame.drawing) in recorded.split()


def mark(grease_pencil_data, layer, frame, new):
    """Record ``frame`` as written by this add-on, its strokes' fingerprint ``new`` (what
    :func:`.grease_pencil.write_strokes` returns)."""
    mark_many(grease_pencil_data, layer, {frame.frame_number: new})


def mark_many(grease_pencil_data, layer, written):
    """:func:`mark` for many frames of ``layer`` at once: ``written`` maps frame numbers to
    their fingerprints. The record is read and put back once (each lookup in an ID property
    group scans it: marking frame by frame is quadratic in the frames)."""
    if not written:
        return
    _records(grease_pencil_data, layer, create=True)
    root = grease_pencil_data[PROPERTY]
    key = id_key(layer.name)
    records = root[key].to_dict()
    for number, new in written.items():
        number = str(number)
        kept = [fingerprint for fingerprint in records.get(number, "").split() if fingerprint != new]
        records[number] = " ".join([*kept[max(0, len(kept) + 1 - _HISTORY) :], new])
    root[key] = records


def save(grease_pencil_data):
    """A copy of the whole record (plain dicts), for :func:`restore`."""
    root = grease_pencil_data.get(PROPERTY)
    return root.to_dict() if root is not None else None


def restore(grease_pencil_data, saved):
    """Put back a record taken by :func:`save` (when a write is rolled back)."""
    if saved is None:
        grease_pencil_data.pop(PROPERTY, None)
    else:
        grease_pencil_data[PROPERTY] = saved
