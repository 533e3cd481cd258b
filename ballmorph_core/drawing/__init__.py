"""Whole drawings, what the Blender operator calls: strokes, matching, registration, splitting,
the one stroke-pair pipeline, fallbacks, attributes, the plan, timing."""

from .fallbacks import FALLBACK_METHOD
from .plan import InbetweenPlan, inbetween, plan_inbetween
from .strokes import InbetweenResult, Message, PairReport, StrokeSet
from .timing import FAVOR_ODDS, apply_favor, ease, frame_times, parse_timing_chart

__all__ = [
    "FALLBACK_METHOD",
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
    "plan_inbetween",
]
