"""Plans kept from the last run, so a redo only re-evaluates them.

F9 (Adjust Last Operation) and the sidebar's re-runs change the frame count or the easing far
more often than the keys. Everything expensive in an in-between (stroke matching, ball-maps,
carriers) depends only on the two keys and the morph options, not on the times
(:func:`ballmorph_core.plan_inbetween`), so the operator keeps each interval's plan, keyed by a
digest of exactly what it was computed from, and evaluates it at the new times.

A plan is reused only for keys that are byte-identical to the ones it was made from (every
array the core receives is hashed) and the same options; its evaluation is then exactly what
a fresh computation gives (``tests/core/test_real_drawings.py``). Only the plans of the last
run are kept, which bounds the memory to one run's correspondences.
"""

import hashlib
from dataclasses import fields

import numpy as np

from ..ballmorph_core import StrokeSet, plan_inbetween

__all__ = ["PlanCache", "PLANS"]


def _digest(key_a, key_b, options):
    """A digest of the two keys' arrays (dtype, shape and bytes) and the morph options."""
    h = hashlib.blake2b(digest_size=20)
    h.update(repr(sorted(options.items())).encode())
    for key in (key_a, key_b):
        for f in fields(StrokeSet):
            array = np.ascontiguousarray(getattr(key, f.name))
            h.update(f"{f.name}:{array.dtype.str}:{array.shape}".encode())
            h.update(array.data)
    return h.digest()


class PlanCache:
    """The in-between plans of the last run, by digest of their keys and options.

    Call :meth:`begin` before a run and :meth:`end` after it: plans the run did not use are
    dropped then.
    """

    def __init__(self):
        self._kept = {}
        self._used = {}
        self.hits = self.misses = 0

    def begin(self):
        self._used = {}

    def end(self):
        self._kept, self._used = self._used, {}

    def clear(self):
        self._kept, self._used = {}, {}

    def plan(self, key_a, key_b, **options):
        """The plan of ``plan_inbetween(key_a, key_b, **options)``, reused when already made.

        Parameters
        ----------
        key_a, key_b : StrokeSet
            Not modified; the plan keeps them, so the caller must not modify them either.
        **options
            Keyword arguments of :func:`ballmorph_core.plan_inbetween`.

        Returns
        -------
        ballmorph_core.InbetweenPlan
        """
        digest = _digest(key_a, key_b, options)
        plan = self._used.get(digest) or self._kept.get(digest)
        if plan is None:
            self.misses += 1
            plan = plan_inbetween(key_a, key_b, **options)
        else:
            self.hits += 1
        self._used[digest] = plan
        return plan


#: The add-on's one cache (module state: it outlives the undo steps a redo replays).
PLANS = PlanCache()
