"""The path preview's geometry: trajectories between the keys around the current frame.

Read-only, no drawing here (``ui/path_preview.py`` draws): the active Grease Pencil object's
active layer, its keys around the current frame (the operator's rule, :func:`.pairing.
selected_or_current`, without the Dope Sheet selection: the preview follows the playhead), read
as the operator reads them (:func:`.morph.read_keys`), their plan (the operator's kept plan when
it matches, :data:`.plans.PLANS`), and the core's :func:`ballmorph_core.path_preview` of it,
moved to world space. With Smooth key motion the keys before and after them are read and
planned too, so the preview shows the paths joined smoothly to the neighbouring intervals', as
the operator writes them over three or more keys (:func:`ballmorph_core.chain_corrections`).

:data:`PREVIEW` keeps the result. The viewport redraws far more often than anything changes, so
a redraw only compares a few values (object, layer, frame, options, matrices, an edit counter
that a depsgraph handler bumps); when one changed, the keys are read again, and only keys or
options that differ from the kept ones are planned again.
"""

from dataclasses import replace

import numpy as np

from ..addon_logic import pairing
from ..ballmorph_core import BallMorphError, chain_corrections, path_preview, plan_inbetween
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
        # (plan options, which interval, [(key_a, key_b) per interval], PathPreview in morph space)
        self._source = None
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
        chain, middle = _chain(found, pairs[0], values["key_motion"])
        read = []
        for k, interval in enumerate(pairing.intervals(found, chain, 0)):
            try:
                read.append(morph.read_keys(layer, interval, values))
            except ValueError:  # the keys cannot be in-betweened: the operator says why
                if k == middle:
                    return None
                read.append(None)
        if read[middle] is None:
            return None
        # A neighbour that cannot be read (or has no strokes) is left out: no arc through it.
        kept_ones = [k for k, r in enumerate(read) if r is not None]
        middle = kept_ones.index(middle)
        chain, read = [chain[k] for k in kept_ones], [read[k] for k in kept_ones]
        smooth = [True] * (len(chain) - 1)
        wanted = morph.plan_options(values, values["method"])
        kept = self._source
        if kept is not None and kept[:2] == (wanted, middle) and _same_keys(kept[2], read):
            return kept[3]
        try:
            plans = [self._plan(r, wanted) for r in read]
            corrections = chain_corrections(plans, [b - a for a, b in chain], smooth, values["key_motion"])
            local = path_preview(plans[middle], correction=corrections[middle])
        except BallMorphError:
            return None
        self.computed += 1
        self._source = (wanted, middle, [(r.key_a, r.key_b) for r in read], local)
        return local

    def _plan(self, read, wanted):
        """The plan of keys read (IntervalKeys): the operator's when it kept one, else a new one."""
        plan = PLANS.find(read.key_a, read.key_b, **wanted)
        if plan is None:
            self.planned += 1
            plan = plan_inbetween(read.key_a, read.key_b, **wanted)
        return plan


def _chain(found, pair, key_motion):
    """The intervals whose plans the preview of ``pair`` needs: the pair, and with Smooth key
    motion the intervals with a frame between their keys on each side of it whose shared key
    is passed smoothly (not typed Extreme). Returns ``(pairs, index of pair)``."""
    a, b = pair
    chain, middle = [pair], 0
    if key_motion == "per-interval":
        return chain, middle
    earlier = [n for n in found.keys if n < a]
    later = [n for n in found.keys if n > b]
    if earlier and a - earlier[-1] >= 2 and a not in found.corners:
        chain, middle = [(earlier[-1], a), *chain], 1
    if later and later[0] - b >= 2 and b not in found.corners:
        chain = [*chain, (b, later[0])]
    return chain, middle


def _same_keys(kept, read):
    """Whether the kept intervals' keys are the ones read now, interval by interval."""
    return len(kept) == len(read) and all(
        same_key(ka, r.key_a) and same_key(kb, r.key_b) for (ka, kb), r in zip(kept, read)
    )


#: The add-on's one preview (module state, like the plans).
PREVIEW = PreviewCache()
