"""Whole drawings, what the Blender operator calls: strokes, matching, registration, splitting,
the one stroke-pair pipeline, fallbacks, attributes, the plan, timing, and how far in-betweens
stray from their keys."""

from .fallbacks import FALLBACK_METHOD
from .plan import InbetweenPlan, inbetween, plan_inbetween
from .straying import FALLBACK_MORPHS, ink_lengths, length_deviation
from .strokes import InbetweenResult, Message, PairReport, StrokeSet
from .timing import FAVOR_ODDS, apply_favor, ease, frame_times, parse_timing_chart

__all__ = [
    "FALLBACK_METHOD",
    "FALLBACK_MORPHS",
    "FAVOR_ODDS",
    "InbetweenPlan",
    "InbetweenResult",
    "Message",
    "PairReport",
    "StrokeSet",
    "apply_favor",
    "ease",
    "frame_times",
    "parse_timing_chart",
    "inbetween",
    "ink_lengths",
    "length_deviation",
    "plan_inbetween",
]
