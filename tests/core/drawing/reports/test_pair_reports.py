"""What the plan says of each pair (drawing/reports/pair_reports.py)."""

import numpy as np
import pytest

from ballmorph_core.drawing.keys.projected import KeyStroke
from ballmorph_core.drawing.reports.pair_reports import pair_report, piece_report, unmatched_report
from ballmorph_core.drawing.strokes import PairMorphs, PairOutcome


def _stroke(index):
    return KeyStroke(index, np.zeros((2, 2)), np.array([0.0, 1.0]), False, 0)


def test_a_pair_that_fell_back_warns_once_on_its_last_note():
    used = PairMorphs(("linear-interpolation",), "similarity")
    report, messages = pair_report(_stroke(2), _stroke(5), True, used, ["split at 2 pieces", "why it fell back"])
    assert (report.stroke_a, report.stroke_b, report.used, report.outcome) == (2, 5, used, PairOutcome.MORPHED)
    assert report.method == "linear-interpolation on a similarity carrier"
    assert [m.level for m in messages] == ["INFO", "INFO", "WARNING"]
    assert messages[0].text == "stroke 3 -> 6: the second key's stroke runs the other way: flipped"
    assert all(m.strokes == ((0, 2), (1, 5)) for m in messages)  # the pair, in both keys (indices from 0)


def test_a_ball_morphed_pair_only_informs():
    _, messages = pair_report(_stroke(0), _stroke(0), False, PairMorphs(("circular-ball",)), ["a note"])
    assert [m.level for m in messages] == ["INFO"]


@pytest.mark.parametrize(
    ("from_a", "unmatched", "outcome", "words"),
    [
        (True, "middle", PairOutcome.DISAPPEAR, "stroke 4 of the first key has no partner: disappears at the middle"),
        (False, "fade", PairOutcome.APPEAR, "stroke 4 of the second key has no partner: fades in"),
        (True, "hold", PairOutcome.HOLD, "stroke 4 of the first key has no partner: held"),
    ],
)
def test_a_stroke_without_a_partner_says_what_it_does(from_a, unmatched, outcome, words):
    report, message = unmatched_report(3, from_a, unmatched)
    assert report.outcome == outcome and (report.stroke_a is None) != from_a
    assert (message.level, message.text) == ("WARNING", words)
    assert message.strokes == ((0 if from_a else 1, 3),)  # the stroke it is about, for the add-on to select


def test_a_piece_of_a_line_names_its_line():
    report = piece_report(4, "b", 1)
    assert (report.stroke_a, report.stroke_b, report.outcome) == (None, 4, PairOutcome.PIECE)
    assert report.method == "piece of the line of stroke 2"
