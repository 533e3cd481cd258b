"""What the plan says of each stroke pair and of each stroke without a partner: the pair's
:class:`~..strokes.PairReport` (its fields: what made it) and the messages for the animator."""

from ..pair_morphs.fallbacks import ALIGNED_METHOD, FALLBACK_METHOD, STRAIGHT_POINT_MOTION
from ..strokes import Message, PairOutcome, PairReport, as_written

__all__ = ["pair_report", "unmatched_report", "piece_report"]

#: How the report says what a stroke without a partner does: (going, coming) per option.
UNMATCHED_WORDS = {
    "middle": ("disappears at the middle", "appears at the middle"),
    "hold": ("held", "held"),
    "fade": ("fades out", "fades in"),
    "shrink": ("shrinks into its middle", "grows out of its middle"),
    "neighbour": ("shrinks into its nearest stroke", "grows out of its nearest stroke"),
}


def pair_report(a, b, flipped, used, notes, travelled=False):
    """The report of a morphed pair and its messages.

    Parameters
    ----------
    a, b : KeyStroke
    flipped : bool
        Whether B's stroke runs the other way (it was reversed).
    used : PairMorphs
    notes : list of str
        What the pipeline said of the pair (fallbacks, splits); the last is a warning when the
        pair fell back.
    travelled : bool
        Paired by the drawing's motion (:mod:`..pairing.travelling`).

    Returns
    -------
    PairReport, list of Message
    """
    report = PairReport(a.index, b.index, str(used), "; ".join(notes), used=used, travelled=travelled)
    if flipped:
        notes = ["the second key's stroke runs the other way: flipped", *notes]
    first = used.morphs[0] if used.morphs else ""
    fell_back = first in (FALLBACK_METHOD, ALIGNED_METHOD) or first == STRAIGHT_POINT_MOTION
    strokes = ((0, a.index), (1, b.index))
    messages = [
        Message(
            "WARNING" if fell_back and note is notes[-1] else "INFO",
            f"stroke {as_written(a.index)} -> {as_written(b.index)}: {note}",
            strokes,
        )
        for note in notes
    ]
    return report, messages


def piece_report(piece, side, whole):
    """The report of stroke ``piece`` of key ``side`` ('a' or 'b'), a piece of the line of
    stroke ``whole`` of the other key (morphed with it)."""
    stroke_a, stroke_b = (piece, None) if side == "a" else (None, piece)
    return PairReport(stroke_a, stroke_b, f"piece of the line of stroke {as_written(whole)}", outcome=PairOutcome.PIECE)


def unmatched_report(index, from_a, unmatched):
    """The report of stroke ``index`` of the first key (``from_a``) or the second, without a
    partner, doing what option ``unmatched`` says: PairReport, Message."""
    key = "first" if from_a else "second"
    what = UNMATCHED_WORDS[unmatched][0 if from_a else 1]
    outcome = PairOutcome.HOLD if unmatched == "hold" else (PairOutcome.DISAPPEAR if from_a else PairOutcome.APPEAR)
    report = PairReport(index if from_a else None, None if from_a else index, outcome.value, outcome=outcome)
    text = f"stroke {as_written(index)} of the {key} key has no partner: {what}"
    return report, Message("WARNING", text, ((0 if from_a else 1, index),))
