"""Issue 39 item 3: a symmetric loop takes the smallest turn the keys allow (a figure eight
turning 10 degrees turns 10, not 190); ties go the drawn way, never by round-off."""

import numpy as np
import pytest
import scenes

import ballmorph_core as bm
from ballmorph_core.drawing.pairing import descriptors
from ballmorph_core.drawing.pairing.matching import match_strokes
from ballmorph_core.drawing.pairing.symmetry import unoriented


def _turns(a, b):
    """Best-fit rotation (degrees) of every in-between's loop against key A's."""
    result = bm.inbetween(scenes.key([a], True).stroke_set(), scenes.key([b], True).stroke_set(), scenes.TIMES)
    return [scenes.best_rotation(a, f.positions[:, [0, 2]], True) for f in result.frames]


@pytest.mark.parametrize(
    "turn, width, start, shift, backwards",
    [
        (10.0, 1.2, 180.0, (0.3, 0.1), False),  # the scene
        (10.0, 1.2, 0.0, (0.3, 0.1), False),
        (-25.0, 1.3, 90.0, (1.0, 0.0), False),  # held back: other turn, width, start
        (35.0, 0.8, 180.0, (-0.5, 0.4), True),  # held back: key B drawn the other way round
        (-6.0, 1.0, 270.0, (0.0, 0.0), True),
    ],
)
def test_a_figure_eight_turns_the_keys_turn_at_every_inbetween(turn, width, start, shift, backwards):
    a = scenes.figure_eight()
    b = scenes.turned(scenes.figure_eight(width, start), turn, (0.0, 0.0)) + shift
    b = b[::-1] if backwards else b
    turns = _turns(a, b)
    want = [t * turn for t in scenes.TIMES]
    worst = max(abs(scenes.wrap_degrees(g - w)) for g, w in zip(turns, want))
    assert worst <= 2.0, f"eight turning {turn}°: in-betweens turn {np.round(turns, 2)} (want {np.round(want, 2)})"


def test_a_tie_goes_the_drawn_way_whatever_the_round_off():
    """Turned exactly 90 degrees, the eight read forward turns +90 and read backwards -90: a tie,
    so key B runs as drawn; a nudge of 1e-12 (round-off) does not change that."""
    a = scenes.figure_eight()
    b = scenes.turned(scenes.figure_eight(), 90.0, (0.0, 0.0))
    rng = np.random.default_rng(3)
    for nudge in (0.0, 1e-12, -1e-12):
        m = match_strokes([a], [b + nudge * rng.standard_normal(b.shape)], [True], [True])
        assert m.pairs == [(0, 0, False)], f"nudge {nudge}: {m.pairs}"


def test_an_oriented_loop_still_runs_by_its_area():
    circle = scenes.circle(1.0, n=40)
    m = match_strokes([circle], [circle[::-1] + (0.2, 0.0)], [True], [True])
    assert m.pairs == [(0, 0, True)]


def test_which_loops_their_area_cannot_orient():
    shapes = [scenes.circle(1.0, n=64), scenes.circle(1.0, n=64, axes=(30.0, 1.0)), scenes.figure_eight()]
    key = descriptors.KeyDescriptors(shapes, [True] * 3, "strokes", "closed", descriptors.MATCH_SAMPLES)
    assert unoriented(key.areas(), key.sizes()).tolist() == [False, False, True]
