"""Issue 38 in Blender: shapes that change where they lie, through the operator.

Each case puts one stroke on frame 1 and its partner on frame 9, runs the operator and reads the
seven in-betweens back: a ball stretching into a smear (in place and moving 1.5) stays an
ellipse, a dot changing its proportions squashes in place (no turn), an L-shaped outline growing
bolder in place follows the vertex-wise blend, and dissimilar open strokes stay in the keys' box
without crossing themselves.
"""

import bpy
import gp_data
import numpy as np
import pytest

from ballmorph_core.geometry.intersections import simple_curves
from tests.core.drawing.pair_morphs.test_deforming import (
    BOLDER_TOLERANCE,
    BOX_TOLERANCE,
    DISSIMILAR_STROKES,
    DOT_TOLERANCE,
    DOT_TURN,
    ELLIPSE_TOLERANCE,
    best_turn,
    ellipse_gap,
    hausdorff,
    rounded_l,
    rounded_rectangle,
)
from tests.fixtures.shapes import circle


def _inbetweens(a, b, closed):
    """The operator's seven in-betweens of stroke ``a`` (frame 1) into ``b`` (frame 9), (n, 2) each."""
    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [a], cyclic=[closed])
    gp_data.add_key(layer, 9, [b], cyclic=[closed])
    bpy.context.scene.frame_current = 4
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    out = []
    for number in range(2, 9):
        frame = gp_data.read_strokes(gp_data.frame_at(layer, number).drawing)
        assert len(frame) == 1 and np.isfinite(frame.positions).all()
        out.append(frame.positions[frame.points(0)][:, [0, 2]].astype(float))
    return out


@pytest.mark.parametrize("move", [0.0, 1.5])
def test_a_ball_stretching_into_a_smear_stays_an_ellipse(addon, move):
    ball = circle(0.25, 200)
    smear = np.c_[3.0 * ball[:, 0], ball[:, 1]] + (move, 0.0)
    gaps = [ellipse_gap(f) for f in _inbetweens(ball, smear, True)]
    assert max(gaps) <= ELLIPSE_TOLERANCE, f"move {move}: up to {max(gaps):.4%} off an ellipse"


def _closest_t(frame, truth_at):
    """The time whose truth (``truth_at(t)``) lies closest to ``frame``, and its Hausdorff."""
    ts = np.linspace(0.0, 1.0, 101)
    gaps = [hausdorff(frame, truth_at(t)) for t in ts]
    return ts[int(np.argmin(gaps))], min(gaps)


def test_a_dot_changing_proportions_squashes_in_place(addon):
    tall = rounded_rectangle(0.10, 0.30, 0.03, 20)
    wide = rounded_rectangle(0.32, 0.11, 0.03, 27, centre=(0.01, 0.0))

    def truth_at(t):
        return rounded_rectangle(0.10 + 0.22 * t, 0.30 - 0.19 * t, 0.03, 200, centre=(0.01 * t, 0.0))

    for number, frame in enumerate(_inbetweens(tall, wide, True), 2):
        t, gap = _closest_t(frame, truth_at)
        turn = best_turn(frame, truth_at(t))
        assert turn < DOT_TURN and gap / 0.32 < DOT_TOLERANCE, (
            f"frame {number}: turned {turn:.2f} deg, {gap / 0.32:.2%} off the proportional dot"
        )


def test_an_l_growing_bolder_in_place_follows_the_vertex_wise_blend(addon):
    for number, frame in enumerate(_inbetweens(rounded_l(0.08, 400), rounded_l(0.30, 333), True), 2):
        _, gap = _closest_t(frame, lambda t: rounded_l(0.08 + 0.22 * t, 1500))
        assert gap <= BOLDER_TOLERANCE, f"frame {number}: {gap:.4f} from the vertex-wise blend"


@pytest.mark.parametrize("name", sorted(DISSIMILAR_STROKES))
def test_dissimilar_open_strokes_stay_in_the_keys_box_and_simple(addon, name):
    a, b = DISSIMILAR_STROKES[name]
    frames = _inbetweens(a, b, False)
    lo, hi = np.minimum(a.min(axis=0), b.min(axis=0)), np.maximum(a.max(axis=0), b.max(axis=0))
    excess = max(
        float(np.hypot(*(np.maximum(lo - f, 0) + np.maximum(f - hi, 0)).T).max()) / float(np.hypot(*(hi - lo)))
        for f in frames
    )
    simple = simple_curves(frames, np.zeros(len(frames), dtype=bool))
    assert excess < BOX_TOLERANCE and simple.all(), (
        f"{name}: leaves the keys' box by {excess:.2%}; frames crossing themselves: {np.flatnonzero(~simple) + 2}"
    )
