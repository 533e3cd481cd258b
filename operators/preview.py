"""The path preview's geometry: trajectories between the keys around the current frame.

Read-only, no drawing here (``ui/path_preview.py`` draws): the active Grease Pencil object's
active layer, its keys around the current frame (the operator's rule, :func:`.pairing.
selected_or_current`, without the Dope Sheet selection: the preview follows the playhead), read
as the operator reads them (:func:`.morph.read_keys`), their plan (the operator's kept plan when
it matches, :data:`.plans.PLANS`), and the core's :func:`ballmorph_core.path_preview` of it,
moved to world space.

:data:`PREVIEW` keeps the result. The viewport redraws far more often than anything changes, so
a redraw only compares a few values (object, layer, frame, options, matrices, an edit counter
that a depsgraph handler bumps); when one changed, the keys are read again, and only keys or
options that differ from the kept ones are planned again.
"""

from dataclasses import replace

import numpy as np

from ..addon_logic import pairing
from ..ballmorph_core import BallMorphError, path_preview, plan_inbetween
from . import keys, morph, options
from .plans import PLANS, same_key

__all__ = ["PreviewCache", "PREVIEW"]


def _matrix(matrix):
    """A Blender matrix as a (4, 4) float64 array."""
    return np.array(matrix, dtype=np.float64)


class PreviewCache:
    """The last path preview, with what it was made from.

    Attributes
    ----------
    computed : int
        Previews computed (a morph's trajectories evaluated) since the cache was made.
    planned : int
        Plans this cache made itself (the others were the operator's, reused).
    """

    def __init__(self):
        self.computed = self.planned = 0
        self.clear()

    def clear(self):
        """Forget everything (the keys, the plan's trajectories, the edit counter)."""
        self._state, self._world = None, None
        self._source = None  # (plan options, key_a, key_b, PathPreview in morph space)
        self._edits = 0

    def edited(self):
        """Something in Blender's data changed (a depsgraph update): check the keys again."""
        self._edits += 1

    def world(self, context):
        """The trajectories to draw in world space (PathPreview), or None when there is none.

        Parameters
        ----------
        context : bpy.types.Context
            Its scene's settings, active object and current frame.
        """
        obj = keys.grease_pencil_object(context)
        layer = obj.data.layers.active if obj is not None else None
        if layer is None:
            return None
        values = options.values_of(context.scene.ballmorph_inbetween)
        state = (
            obj.name,
            layer.name,
            context.scene.frame_current,
            tuple(sorted(values.items())),
            tuple(_matrix(obj.matrix_world).ravel()),
            tuple(_matrix(layer.matrix_local).ravel()),
            self._edits,
        )
        if state != self._state:
            # Stored first: should the morph fail, the next redraws do not try again.
            self._state, self._world = state, None
            local = self._local(obj, layer, context.scene.frame_current, values)
            self._world = None if local is None else local.transformed(_matrix(obj.matrix_world))
        return self._world

    def _local(self, obj, layer, frame, values):
        """The preview in the object's space (where the morph runs), or None."""
        found = replace(keys.layer_keys(obj.data, layer), selected=())
        pairs, _ = pairing.selected_or_current(found, frame)
        if not pairs:
            return None
        try:
            read = morph.read_keys(layer, pairing.intervals(found, pairs, 0)[0], values)
        except ValueError:  # the keys cannot be in-betweened: the operator says why
            return None
        if read is None:
            return None
        wanted = morph.plan_options(values, values["method"])
        kept = self._source
        if kept is not None and kept[0] == wanted and same_key(kept[1], read.key_a) and same_key(kept[2], read.key_b):
            return kept[3]
        plan = PLANS.find(read.key_a, read.key_b, **wanted)
        try:
            if plan is None:
                self.planned += 1
                plan = plan_inbetween(read.key_a, read.key_b, **wanted)
            local = path_preview(plan)
        except BallMorphError:
            return None
        self.computed += 1
        self._source = (wanted, read.key_a, read.key_b, local)
        return local


#: The add-on's one preview (module state, like the plans).
PREVIEW = PreviewCache()
