"""Which Grease Pencil object and layers to in-between, and their frames as plain data.

Read-only: nothing here changes Blender data. The decisions (which keys pair up, which frames
to write, what to say) are bpy-free, in :mod:`.pairing` and :mod:`.reports`; this module only
reads what they need from Blender.
"""

from ..addon_logic import pairing, reports
from . import generated

__all__ = ["grease_pencil_object", "target_layers", "layer_blocker", "layer_keys"]


def grease_pencil_object(context):
    """The active object if it is a Grease Pencil (v3) object, else None."""
    obj = getattr(context, "active_object", None) or getattr(context, "object", None)
    return obj if obj is not None and obj.type == "GREASEPENCIL" else None


def target_layers(grease_pencil_data, mode):
    """Layers named by the ``layers`` option's value: ``'active'`` or ``'all'`` (in stacking order)."""
    if mode == "active":
        active = grease_pencil_data.layers.active
        return [active] if active is not None else []
    return list(grease_pencil_data.layers)


def layer_blocker(layer):
    """Why a layer cannot be written (locked or hidden, itself or through a group), or ''."""
    chain, node = [(None, layer.lock, layer.hide)], layer.parent_group
    while node is not None:
        chain.append((node.name, node.lock, node.hide))
        node = node.parent_group
    return reports.layer_blocked(layer.name, chain)


def layer_keys(grease_pencil_data, layer):
    """A layer's keys, selected keys, the frames this add-on made and the keys typed Extreme (they
    keep their corner), for :mod:`.pairing`."""
    keys, selected, made, corners = [], [], [], []
    for frame in layer.frames:
        number = frame.frame_number
        if generated.is_generated(grease_pencil_data, layer, frame):
            made.append(number)
        else:
            keys.append(number)
            if frame.select:
                selected.append(number)
            if frame.keyframe_type == "EXTREME":
                corners.append(number)
    return pairing.LayerKeys(
        layer.name, tuple(sorted(keys)), tuple(sorted(selected)), tuple(sorted(made)), tuple(sorted(corners))
    )
