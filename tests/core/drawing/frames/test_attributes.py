"""The per-sample attributes of in-betweens (``drawing/attributes.py``): what the keys agree on
is shared by every frame, what differs is mixed as ``(1 - t) a + t b``."""

import numpy as np

from ballmorph_core.drawing.frames.attributes import _Mix


def test_mixed_blocks_are_the_blend_bit_for_bit_into_a_buffer_or_not():
    rng = np.random.default_rng(7)
    va = rng.normal(size=(30, 7))
    vb = va.copy()
    vb[:, 1] += rng.normal(size=30)  # radius differs
    vb[:, 4] += rng.normal(size=30)  # one colour channel differs
    mix = _Mix(iter(va.T.copy()), iter(vb.T.copy()), ((0, 1), (1, 2), (2, 3), (3, 7), (7, 7)), 30)
    out = np.empty(30)
    for t in (0.3, 0.0, 1.0, 0.3):
        blend = (1 - t) * va + t * vb
        assert mix.block(0, t) is mix.block(0, 1 - t)  # shared: the same array every frame
        np.testing.assert_array_equal(mix.block(1, t)[:, 0], blend[:, 1])
        assert np.shares_memory(mix.block(1, t, out=out), out)
        np.testing.assert_array_equal(out, blend[:, 1])
        np.testing.assert_array_equal(mix.block(3, t), np.c_[va[:, 3], blend[:, 4], va[:, 5:7]])
        assert mix.block(7, t).shape == (30, 0)
    assert mix.differ.tolist() == [False, True, False, False, True, False, False]


def test_the_mix_takes_one_pair_of_columns_at_a_time():
    """The samples' values are read column by column as the blocks are made, never all of
    them at once: at any time at most the current block's columns are held beside the kept
    blocks."""
    rng = np.random.default_rng(8)
    va, vb = rng.normal(size=(20, 7)), rng.normal(size=(20, 7))
    read = []

    def columns(values, name):
        for j, column in enumerate(values.T):
            read.append((name, j))
            yield column.copy()

    _Mix(columns(va, "a"), columns(vb, "b"), ((0, 1), (1, 2), (2, 3), (3, 7), (7, 7)), 20)
    assert read == [(name, j) for j in range(7) for name in "ab"]


def test_recycled_arrays_are_given_again_only_when_nothing_refers_to_them():
    from ballmorph_core.drawing.frames.attributes import Recycled

    recycled = Recycled()
    recycled.begin()
    kept, dropped = recycled.empty((4, 3)), recycled.empty((4, 3))
    view = kept.reshape(-1, 3)  # a StrokeSet's positions are such a view
    first = {id(kept), id(dropped)}
    del kept, dropped
    recycled.end()
    recycled.begin()
    again = [recycled.empty((4, 3)), recycled.empty((4, 3)), recycled.empty((4,))]
    recycled.end()
    assert id(again[0]) in first  # the dropped one
    assert not np.shares_memory(again[1], view) and not np.shares_memory(again[0], view)
    assert again[2].shape == (4,)
    ids = {id(a) for a in again}
    del view, again
    recycled.begin()  # only the last evaluation's arrays are candidates: all three free now
    given = [recycled.empty((4, 3)), recycled.empty((4, 3)), recycled.empty((4,))]
    assert {id(a) for a in given} == ids


def test_recycled_memory_is_bounded(monkeypatch):
    """Only the first RECYCLED_BYTES of an evaluation's arrays are kept for the next: the rest
    are let go with their frames (a big run's peak memory)."""
    from ballmorph_core.drawing.frames import attributes
    from ballmorph_core.drawing.frames.attributes import Recycled

    monkeypatch.setattr(attributes, "RECYCLED_BYTES", 2 * 4 * 3 * 8)  # two arrays of (4, 3)
    recycled = Recycled()
    recycled.begin()
    ids = [id(recycled.empty((4, 3))) for _ in range(3)]  # none kept alive by the caller
    recycled.end()
    recycled.begin()
    again = [recycled.empty((4, 3)) for _ in range(3)]
    assert [id(a) for a in again[:2]] == ids[:2]
    assert len(recycled._free) == 0  # the third was not kept: made anew
