"""The plans kept from the last run (operators/plans.py), in plain CPython."""

import numpy as np
from addon_package import load

plans = load("operators.plans")
core = load("ballmorph_core")


def _key(shift):
    arc = np.c_[np.linspace(0.0, 1.0, 20), np.zeros(20), np.sin(np.linspace(0.0, 3.0, 20))]
    return core.StrokeSet.from_strokes([arc, 0.5 * arc + shift], cyclic=[False, False])


def test_a_redo_of_equal_keys_gets_the_keys_ink_lengths_measured_for_its_plan():
    """The keys' ink lengths are measured once per kept plan: a redo reading the keys afresh
    (equal arrays, other objects) gets the same plan and those same lengths."""
    cache = plans.PlanCache()
    cache.begin()
    plan = cache.plan(_key(0.0), _key(0.1), method="linear-interpolation")
    lengths = cache.key_lengths(plan)
    for got, key in zip(lengths, (_key(0.0), _key(0.1))):
        np.testing.assert_array_equal(got, core.ink_lengths(key))
    cache.end()
    cache.begin()
    again = cache.plan(_key(0.0), _key(0.1), method="linear-interpolation")
    assert again is plan and cache.key_lengths(again) is lengths
