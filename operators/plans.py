"""Plans kept from the last run, so a redo only re-evaluates them.

F9 (Adjust Last Operation) and the sidebar's re-runs change the frame count or the easing far
more often than the keys. Everything expensive in an in-between (stroke matching, ball-maps,
carriers) depends only on the two keys and the morph options, not on the times
(:func:`ballmorph_core.plan_inbetween`), so the operator keeps each interval's plan with the
keys and options it was computed from, and evaluates it at the new times.

A plan is reused only for keys equal, array by array, to the ones it was made from (every
array the core receives is compared: a memory comparison, ~20 times faster than hashing them)
and the same options; its evaluation is then exactly what a fresh computation gives
(``tests/scenarios/test_real_drawings.py``). Only the plans of the last run are kept, which bounds
the memory to one run's correspondences (the plans hold the keys anyway).
"""

from dataclasses import dataclass, fields

import numpy as np

from ..ballmorph_core import StrokeSet, ink_lengths, plan_inbetween

__all__ = ["PlanCache", "PLANS", "same_key"]


def _same_array(x, y):
    return x.dtype == y.dtype and x.shape == y.shape and np.array_equal(x, y)


def same_key(a, b):
    """Whether two StrokeSets hold equal arrays (dtype, shape and values) in every field, extra
    attributes included."""
    for f in fields(StrokeSet):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, dict):
            if x.keys() != y.keys() or not all(
                x[k] == y[k] if isinstance(x[k], str) else _same_array(x[k], y[k]) for k in x
            ):
                return False
        elif not _same_array(x, y):
            return False
    return True


@dataclass
class _Entry:
    """A kept plan, the keys and options it was made from, and the keys' ink lengths once asked."""

    options: dict
    key_a: StrokeSet
    key_b: StrokeSet
    plan: object
    lengths: tuple = None


class PlanCache:
    """The in-between plans of the last run, with the keys and options they were made from.

    Call :meth:`begin` before a run and :meth:`end` after it: plans the run did not use are
    dropped then.
    """

    def __init__(self):
        self._kept = []  # _Entry
        self._used = []
        self.hits = self.misses = 0

    def begin(self):
        self._used = []

    def end(self):
        self._kept, self._used = self._used, []

    def clear(self):
        self._kept, self._used = [], []

    def _find(self, key_a, key_b, options):
        for entry in self._used + self._kept:
            if entry.options == options and same_key(entry.key_a, key_a) and same_key(entry.key_b, key_b):
                return entry
        return None

    def find(self, key_a, key_b, **options):
        """The plan kept for these keys and options, or None (nothing is recorded: the path
        preview looks here without changing what the next run keeps)."""
        entry = self._find(key_a, key_b, options)
        return None if entry is None else entry.plan

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
        entry = self._find(key_a, key_b, options)
        if entry is None:
            self.misses += 1
            entry = _Entry(dict(options), key_a, key_b, plan_inbetween(key_a, key_b, **options))
        else:
            self.hits += 1
        if not any(used is entry for used in self._used):
            self._used.append(entry)
        return entry.plan

    def key_lengths(self, plan):
        """The ink lengths of the keys ``plan`` (one this run used) was made from, shapes (S_a,)
        and (S_b,) (:func:`ballmorph_core.ink_lengths`): measured once per plan, as every redo
        measures its in-betweens against them.
        """
        entry = next(entry for entry in self._used if entry.plan is plan)
        if entry.lengths is None:
            entry.lengths = ink_lengths(entry.key_a), ink_lengths(entry.key_b)
        return entry.lengths


#: The add-on's one cache (module state: it outlives the undo steps a redo replays).
PLANS = PlanCache()
