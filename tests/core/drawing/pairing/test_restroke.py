"""Issue 39 item 4: a line re-stroked as two or three overlapping strokes (and back) morphs
without a pop, its ink within 5% of the keys' blend, as abutting pieces do."""

import numpy as np
import pytest
import scenes

import ballmorph_core as bm
from ballmorph_core.drawing.pairing.redrawn import _joined, cut_frame


def _figures(a, b):
    keys = scenes.key(a, False), scenes.key(b, False)
    result = bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), scenes.TIMES)
    drawings = tuple(scenes.as_drawing(k) for k in keys)
    frames = [scenes.as_drawing(f) for f in result.frames]
    return (
        scenes.figure_ink_blend(drawings, frames, scenes.TIMES, 0.05),
        scenes.figure_steps(drawings, frames, scenes.TIMES),
        result,
    )


@pytest.mark.parametrize("count", [2, 3])
@pytest.mark.parametrize("back", [False, True], ids=["whole-to-pieces", "pieces-to-whole"])
@pytest.mark.parametrize(
    "overlap, bend, shift, length",
    [(0.06, 0.6, (0.4, 0.2), 4.0), (0.04, 0.45, (-0.6, 0.5), 3.0), (0.09, 0.8, (1.0, -0.3), 5.0)],
    ids=["scene", "held-back-4%", "held-back-9%"],
)
def test_overlapping_pieces_join_without_a_pop(count, back, overlap, bend, shift, length):
    whole = scenes.restroked(1, bend=bend / 2, shift=(0.0, 0.0), length=length)
    parts = scenes.restroked(count, overlap, bend, shift, length)
    a, b = (parts, whole) if back else (whole, parts)
    ink, steps, result = _figures(a, b)
    what = f"{count} pieces overlapping {overlap:.0%}, {'to' if back else 'from'} one stroke"
    assert ink.ok and steps.ok, f"{what}: {ink}; {steps}"
    assert not any(p.method in ("appear", "disappear") for p in result.pairs), [p.method for p in result.pairs]


def test_an_overlap_is_joined_without_going_back_and_the_pieces_spans_overlap():
    x = np.linspace(0.0, 1.0, 11)
    first, second = np.c_[x[:7], 0 * x[:7]], np.c_[x[5:], 0 * x[5:]]  # overlap 0.5 .. 0.6
    xy, spans = _joined([(first, False), (second, False)])
    assert np.all(np.diff(xy[:, 0]) >= 0), xy[:, 0]
    np.testing.assert_allclose(xy[[0, -1], 0], [0.0, 1.0])
    np.testing.assert_allclose(spans, [(0.0, 0.6), (0.5, 1.0)], atol=1e-12)
    # A gap stays a gap (bridged).
    _, spans = _joined([(np.c_[x[:6], 0 * x[:6]], False), (np.c_[x[7:], 0 * x[7:]], False)])
    np.testing.assert_allclose(spans, [(0.0, 0.5), (0.7, 1.0)], atol=1e-12)


def test_a_reversed_window_cuts_a_stroke_into_overlapping_pieces():
    line = bm.StrokeSet.from_strokes([np.c_[np.linspace(0, 1, 11), np.zeros(11)]])
    cut = cut_frame(line, {0: [(6.0, 5.0)]})
    assert len(cut) == 2
    xs = [cut.positions[cut.points(i)][:, 0] for i in range(2)]
    np.testing.assert_allclose([xs[0][-1], xs[1][0]], [0.6, 0.5])
    assert len(cut_frame(line, {0: [(5.0, 5.0)]})) == 1  # an empty window cuts nothing


@pytest.mark.parametrize("count, flipped, order", [(2, [1], [1, 0]), (3, [1], [2, 0, 1]), (3, [0, 2], [1, 2, 0])])
def test_pieces_drawn_in_any_order_and_direction_join_the_same(count, flipped, order):
    whole = scenes.restroked(1, bend=0.3, shift=(0.0, 0.0))
    parts = [p[::-1] if i in flipped else p for i, p in enumerate(scenes.restroked(count))]
    parts = [parts[i] for i in order]
    for a, b in ((whole, parts), (parts, whole)):
        ink, steps, _ = _figures(a, b)
        assert ink.ok and steps.ok, f"{count} pieces, {flipped} reversed, in order {order}: {ink}; {steps}"
