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


def _attributed(strokes, cyclic, seed=3):
    key = _key(strokes, cyclic)
    rng = np.random.default_rng(seed)
    n = len(key.positions)
    key.radius, key.opacity, key.vertex_color = rng.uniform(size=n), rng.uniform(size=n), rng.uniform(size=(n, 4))
    return key


@pytest.mark.parametrize("loop", [False, True])
def test_values_are_read_at_any_fraction_whether_or_not_a_table_is_made(loop):
    """Open strokes read their values from the key's own arrays (nothing copied), a key with
    a loop from a table with the loop's closing point: both interpolate each stroke's values
    along its fractions, give each point's own values and its nearest point."""
    rng = np.random.default_rng(4)
    strokes = [np.cumsum(rng.normal(size=(n, 2)), axis=0) for n in (5, 9, 4)]
    key = _attributed(strokes, [False, loop, False])
    projected = ProjectedKey(key, fit_plane(key.positions))
    own = np.c_[np.zeros(len(key.radius)), key.radius, key.opacity, key.vertex_color]
    assert np.shares_memory(projected.values(slice(0, 3)), key.radius) is False  # values are copies
    held = [np.shares_memory(column, key.radius) for column in projected._columns]
    assert any(held) is not loop  # open: the key's own radius is read, not copied
    np.testing.assert_array_equal(projected.values(np.arange(len(own))), own)
    np.testing.assert_array_equal(projected.values(slice(5, 14)), own[5:14])
    stroke, u = np.repeat([0, 1, 2], 7), np.tile(np.linspace(0.0, 1.0, 7), 3)
    got = projected.sample(stroke, u)
    for c, sl in enumerate(key.points(i) for i in range(3)):
        fractions, values = projected.u[sl], own[sl]
        if loop and c == 1:
            fractions, values = np.r_[fractions, 1.0], np.r_[values, values[:1]]
        want = np.column_stack([np.interp(u[stroke == c], fractions, column) for column in values.T])
        np.testing.assert_allclose(got[stroke == c], want, rtol=0.0, atol=1e-12)  # (read at u + 2 c)
        nearest = projected.nearest(stroke[stroke == c], u[stroke == c])
        offset = key.offsets[c]
        expected = offset + np.abs(u[stroke == c][:, None] - projected.u[sl][None, :]).argmin(axis=1)
        if loop and c == 1:  # the loop's end is its first point again
            expected[u[stroke == c] == 1.0] = offset
        np.testing.assert_array_equal(nearest, expected)
