"""A line redrawn in pieces (drawing/splits.py): the gaps open or close without a pop."""

import numpy as np
import pytest

import ballmorph_core as bm

TIMES = np.linspace(0.0, 1.0, 9)


def arc(x0, x1, n):
    """Part of a gentle arch from x0 to x1 (the same curve whatever the part)."""
    x = np.linspace(x0, x1, n)
    return np.c_[x, 0.3 * np.sin(np.pi * x / 4.0)]


def ink(frame):
    return sum(
        np.linalg.norm(np.diff(frame.positions[frame.points(i)], axis=0), axis=1).sum() for i in range(len(frame))
    )


def key(strokes, radius=None):
    return bm.StrokeSet.from_strokes(strokes, radius=radius)


@pytest.mark.parametrize(
    ("whole", "pieces"),
    [
        ([arc(0, 4, 60)], [arc(0, 1.9, 30), arc(2.1, 4, 30)]),
        ([arc(0, 4, 60)], [arc(0, 1.2, 20), arc(1.4, 2.6, 20), arc(2.8, 4, 20)]),
        ([arc(0, 4, 60)], [arc(4, 2.1, 30), arc(0, 1.9, 30)]),  # pieces listed backwards, one reversed
    ],
    ids=["two", "three", "backwards"],
)
@pytest.mark.parametrize("direction", ["split", "merge"])
def test_the_gaps_open_or_close_and_the_ink_follows_the_keys(whole, pieces, direction):
    a, b = (key(whole), key(pieces)) if direction == "split" else (key(pieces), key(whole))
    result = bm.inbetween(a, b, TIMES)
    assert not any("no partner" in m.text for m in result.messages)
    assert any("drawn in pieces" in m.text for m in result.messages)
    ink_a, ink_b = ink(a), ink(b)
    inks = [ink(f) for f in result.frames]
    for t, value in zip(TIMES, inks):
        assert abs(value / ((1 - t) * ink_a + t * ink_b) - 1) < 0.1
    assert np.abs(np.diff(inks)).max() <= abs(ink_b - ink_a) / (len(TIMES) - 1) * 1.5  # no pop
    counts = [len(f) for f in result.frames]
    assert counts[0] == len(a) and counts[-1] == len(b)
    np.testing.assert_allclose(np.sort(result.frames[-1].positions[:, 0]).take([0, -1]), [0.0, 4.0], atol=1e-6)


def test_each_piece_keeps_its_own_attributes():
    pieces = [arc(0, 1.9, 30), arc(2.1, 4, 30)]
    b = key(pieces, radius=[np.full(30, 0.02), np.full(30, 0.05)])
    result = bm.inbetween(key([arc(0, 4, 60)], radius=[np.full(60, 0.02)]), b, [1.0])
    frame = result.frames[0]
    assert len(frame) == 2
    np.testing.assert_allclose(frame.radius[frame.points(0)], 0.02, atol=1e-9)
    np.testing.assert_allclose(frame.radius[frame.points(1)], 0.05, atol=1e-9)


def test_strokes_that_are_not_pieces_of_the_line_stay_without_a_partner():
    far = arc(0, 1.9, 30) + [0.0, 3.0]  # a stroke elsewhere
    result = bm.inbetween(key([arc(0, 4, 60)]), key([arc(0, 4, 60), far]), [0.5])
    assert any("no partner" in m.text for m in result.messages)
    assert not any("drawn in pieces" in m.text for m in result.messages)


@pytest.mark.parametrize("direction", ["split", "merge"])
def test_evaluating_leaves_the_plans_samples_as_they_were(direction):
    """The first evaluation reads the pieces' fractions back onto their strokes, on copies: the
    layout's own fractions stay, and a plan evaluated again gives the same in-betweens."""
    whole, pieces = [arc(0, 4, 60)], [arc(0, 1.9, 30), arc(2.1, 4, 30)]
    a, b = (key(whole), key(pieces)) if direction == "split" else (key(pieces), key(whole))
    plan = bm.plan_inbetween(a, b)
    layout = plan.pairs.layout
    u_a, u_b = layout.u_a.copy(), layout.u_b.copy()
    first = plan.evaluate(TIMES)
    np.testing.assert_array_equal(layout.u_a, u_a)
    np.testing.assert_array_equal(layout.u_b, u_b)
    again = plan.evaluate(TIMES)
    for f, g in zip(first.frames, again.frames):
        np.testing.assert_array_equal(f.positions, g.positions)
        np.testing.assert_array_equal(f.offsets, g.offsets)
