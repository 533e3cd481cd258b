"""Issue 39 item 1: strokes that travel far past strokes that stay are paired by their shapes."""

import numpy as np
import pytest
import scenes

import ballmorph_core as bm
from ballmorph_core.drawing.pairing.matching import match_strokes
from ballmorph_core.drawing.pairing.travelling import pair_leftovers


def _inbetween(a, b, cyclic_a, cyclic_b=None):
    keys = scenes.key(a, cyclic_a), scenes.key(b, cyclic_a if cyclic_b is None else cyclic_b)
    return bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), scenes.TIMES)


def _off_translation(result, a, b, index):
    """Worst distance of stroke ``index``'s in-betweens from its key moved along the straight
    line, over the drawing's size (the keys' strokes ``a``, ``b`` have the same points)."""
    size = scenes.drawing_size(*(scenes.as_drawing(scenes.key(k, False)) for k in (a, b)))
    shift = b[index].mean(axis=0) - a[index].mean(axis=0)
    worst = 0.0
    for t, frame in zip(scenes.TIMES, result.frames):
        xy = frame.positions[frame.points(index)][:, [0, 2]]
        worst = max(worst, float(np.abs(xy - (a[index] + t * shift)).max()) / size)
    return worst


@pytest.mark.parametrize(
    "keys, times, travel",
    [
        (scenes.thrown_ball(), 20, "ball r 0.09 thrown 4.2"),
        (scenes.thrown_ball(0.05, 3.1), 20, "held back: ball r 0.05 thrown 3.1"),
        (scenes.flying_bird(), 7, "bird 0.3 wide flying 2.2"),
        (scenes.flying_bird(3.7, 0.18), 20, "held back: bird 0.18 wide flying 3.7"),
    ],
)
def test_a_small_stroke_travelling_far_is_paired_and_moves_exactly(keys, times, travel):
    a, b, cyclic = keys
    sizes = [np.ptp(s, axis=0).max() for s in (a[3], b[3])]
    distance = float(np.linalg.norm(b[3].mean(axis=0) - a[3].mean(axis=0)))
    assert distance >= times * max(sizes), f"{travel}: travels {distance / max(sizes):.1f}x its size"
    result = _inbetween(a, b, cyclic)
    pairs = {(p.stroke_a, p.stroke_b): p for p in result.pairs}
    assert set(pairs) == {(i, i) for i in range(4)}, f"{travel}: pairs {sorted(pairs)}"
    assert pairs[(3, 3)].travelled and not any(pairs[(i, i)].travelled for i in range(3))
    assert any("paired by the drawing's motion" in m.text for m in result.messages)
    off = _off_translation(result, a, b, 3)
    assert off <= 1e-6, f"{travel} ({distance / max(sizes):.0f}x its size): {off:.2g} of the drawing off its path"
    for i in range(3):  # the strokes that stay, stay
        assert _off_translation(result, a, b, i) <= 1e-12


def test_leftovers_pair_by_shape_when_several_are_left():
    """Counts differ: a ball and a bird both travel far, a new hill appears in key B. The ball
    pairs with the ball and the bird with the bird (by shape, not by order or distance), the hill
    stays new; swapped in key B's order, the same pairs."""
    a, b, cyclic = scenes.flying_bird()
    ball = scenes.circle(0.08, (-1.5, 0.6), 24), scenes.circle(0.1, (2.5, 0.8), 24)
    hill = scenes.bowed((0.5, -0.5), (1.5, -0.6), 0.05, 20)
    keys_a, flags_a = [*a, ball[0]], [*cyclic, True]
    for keys_b, flags_b, want in (
        ([*b, ball[1], hill], [*cyclic, True, False], [(3, 3), (4, 4)]),
        ([*b[:3], hill, ball[1], b[3]], [*cyclic[:3], False, True, False], [(3, 5), (4, 4)]),
    ):
        m = match_strokes(keys_a, keys_b, flags_a, flags_b)
        assert m.travelled == want, (m.pairs, m.reason)
        assert m.unmatched_a == [] and len(m.unmatched_b) == 1 and keys_b[m.unmatched_b[0]] is hill


def test_a_far_stroke_of_another_shape_is_left_unpaired():
    """Where several are left, shapes must agree: a square far off in key A, a hook and a hill new
    in key B: nothing pairs across."""
    a, b, cyclic = scenes.flying_bird()
    square = scenes.polyline([(0.0, 2.0), (0.2, 2.0), (0.2, 2.2), (0.0, 2.2)], 3, closed=True)
    hook = scenes.bowed((2.0, 2.0), (2.5, 2.2), 0.2, 10)
    hill = scenes.bowed((0.5, -0.5), (1.5, -0.6), 0.05, 20)
    m = match_strokes([*a[:3], square], [*b[:3], hook, hill], [*cyclic[:3], True], [False] * 5)
    assert m.travelled == [] and m.unmatched_a == [3] and m.unmatched_b == [3, 4], m.pairs


def test_a_stroke_much_bigger_than_the_drawing_grew_is_not_a_traveller():
    a, b, cyclic = scenes.flying_bird()
    big = (b[3] - b[3].mean(axis=0)) * 5 + (6.0, 5.0)  # the V five times wider, far off
    extra = scenes.bowed((0.5, -0.5), (1.5, -0.6), 0.05, 20)
    m = match_strokes(a, [*b[:3], big, extra], cyclic, [*cyclic, False])
    assert m.travelled == [] and m.unmatched_a == [3], m.pairs


def test_nothing_left_or_one_side_left_pairs_nothing():
    rows, cols = pair_leftovers(None, (1.0 + 0j, 0j), [], [2], True)
    assert len(rows) == len(cols) == 0
