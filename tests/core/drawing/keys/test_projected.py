"""A key projected into the drawing plane (drawing/keys.py): its points' fractions along their strokes."""

import numpy as np
import pytest

from ballmorph_core import StrokeSet
from ballmorph_core.drawing.keys.projected import ProjectedKey
from ballmorph_core.geometry.plane import fit_plane


def _key(strokes, cyclic):
    sets = [np.c_[s[:, 0], np.zeros(len(s)), s[:, 1]] for s in strokes]
    return StrokeSet.from_strokes(sets, cyclic=np.array(cyclic))


@pytest.mark.parametrize("degenerate", [False, True])
def test_fractions_run_along_each_stroke_and_evenly_along_one_of_no_length(degenerate):
    rng = np.random.default_rng(2)
    strokes = [np.cumsum(rng.normal(size=(n, 2)), axis=0) for n in (5, 9, 4)]
    if degenerate:
        strokes += [np.ones((4, 2)), np.ones((1, 2))]  # no length: evenly spaced, a dot at 0
    key = _key(strokes, [False, True, False] + [False, True][: len(strokes) - 3])
    projected = ProjectedKey(key, fit_plane(key.positions))
    rg = projected.rg
    length = rg.length[rg.owner]
    local = np.arange(len(rg.pts)) - key.offsets[:-1][rg.owner]
    even = local / np.maximum(rg.n[rg.owner] - 1, 1)
    expected = np.where(length > 0, rg.s / np.where(length > 0, length, 1.0), even)
    assert np.array_equal(projected.u, expected)
    if degenerate:
        np.testing.assert_array_equal(projected.u[-5:], [0.0, 1 / 3, 2 / 3, 1.0, 0.0])
