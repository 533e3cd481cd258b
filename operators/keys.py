"""Which keys to in-between, on which layers, and which frames between them may be written.

Read-only: nothing here changes Blender data. The operator turns the :class:`Interval`s found
here into in-betweens.

Keys on a layer are its frames other than the in-betweens this add-on made. The pair is:
two or more selected keys (Dope Sheet selection) -> every consecutive pair of them; otherwise
the last key at or before the current frame and the first key after it (as Blender's own
Interpolate does).
"""

from dataclasses import dataclass, field

import numpy as np

from ..ballmorph_core import frame_times
from . import generated

__all__ = ["Interval", "grease_pencil_object", "target_layers", "layer_blocker", "find_intervals"]


@dataclass
class Interval:
    """Two keys on one layer and the frames between them.

    Attributes
    ----------
    layer : bpy.types.GreasePencilLayer
    frame_a, frame_b : int
        The two keys (``frame_a < frame_b``).
    targets : ndarray of int, shape (T,)
        Frames to write an in-between on.
    fractions : ndarray, shape (T,)
        ``(target - frame_a) / (frame_b - frame_a)``.
    replace : list of int
        Frames between the keys that this add-on made earlier: removed before writing.
    occupied : list of int
        Other frames between the keys (the animator's): never touched.
    skipped : list of int
        Requested in-between frames not written because they are occupied.
    """

    layer: object
    frame_a: int
    frame_b: int
    targets: np.ndarray
    fractions: np.ndarray
    replace: list = field(default_factory=list)
    occupied: list = field(default_factory=list)
    skipped: list = field(default_factory=list)

    @property
    def name(self):
        return f"{self.layer.name} {self.frame_a}\u2192{self.frame_b}"


def grease_pencil_object(context):
    """The active object if it is a Grease Pencil (v3) object, else None."""
    obj = getattr(context, "active_object", None) or getattr(context, "object", None)
    return obj if obj is not None and obj.type == "GREASEPENCIL" else None


def target_layers(grease_pencil_data, mode):
    """Layers named by the 'layers' option: ``'ACTIVE'`` or ``'ALL'`` (in stacking order)."""
    if mode == "ACTIVE":
        active = grease_pencil_data.layers.active
        return [active] if active is not None else []
    return list(grease_pencil_data.layers)


def layer_blocker(layer):
    """Why a layer cannot be written (locked or hidden, itself or through a group), or ''."""
    node, where = layer, ""
    while node is not None:
        if node.lock:
            return f"layer '{layer.name}' is locked{where}: unlock it to in-between it"
        if node.hide:
            return f"layer '{layer.name}' is hidden{where}: show it to in-between it"
        node = node.parent_group
        where = f" (group '{node.name}')" if node is not None else ""
    return ""


def _keys(grease_pencil_data, layer):
    """Key frames of a layer (sorted frame numbers) and the frames this add-on made."""
    keys, made = [], set()
    for frame in layer.frames:
        if generated.is_generated(grease_pencil_data, layer, frame):
            made.add(frame.frame_number)
        else:
            keys.append(frame)
    keys.sort(key=lambda frame: frame.frame_number)
    return keys, made


def find_intervals(grease_pencil_data, layer, current_frame, frame_count):
    """Key pairs on a layer and the frames to write between them.

    Parameters
    ----------
    grease_pencil_data : bpy.types.GreasePencil
    layer : bpy.types.GreasePencilLayer
    current_frame : int
    frame_count : int
        In-betweens per interval (0: every frame between the keys).

    Returns
    -------
    intervals : list of Interval
    problem : str
        Why there is no interval ('' when there is one).
    """
    keys, made = _keys(grease_pencil_data, layer)
    numbers = [frame.frame_number for frame in keys]
    selected = [frame.frame_number for frame in keys if frame.select]
    if len(selected) >= 2:
        pairs = list(zip(selected[:-1], selected[1:]))
    else:
        before = [n for n in numbers if n <= current_frame]
        after = [n for n in numbers if n > current_frame]
        if len(numbers) < 2:
            return [], f"layer '{layer.name}' has {len(numbers)} keyframe(s): draw a second key to in-between"
        if not before or not after:
            side = "before" if not before else "after"
            return [], (
                f"layer '{layer.name}' has no keyframe {side} frame {current_frame}: select two keyframes, "
                "or go to a frame between two keys"
            )
        pairs = [(before[-1], after[0])]
    intervals, problems = [], []
    for a, b in pairs:
        if b - a < 2:
            problems.append(
                f"layer '{layer.name}': keys {a} and {b} have no frame between them: "
                "move them apart, or select two keys with frames between them"
            )
            continue
        frames, fractions = frame_times(a, b, frame_count)
        between = [n for n in numbers if a < n < b]
        keep = ~np.isin(frames, between)
        intervals.append(
            Interval(
                layer=layer,
                frame_a=a,
                frame_b=b,
                targets=frames[keep],
                fractions=fractions[keep],
                replace=sorted(n for n in made if a < n < b),
                occupied=between,
                skipped=[int(n) for n in frames[~keep]],
            )
        )
    return intervals, "; ".join(problems)
