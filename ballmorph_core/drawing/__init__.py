"""Whole drawings, what the Blender operator calls: strokes, matching, registration, splitting,
the one stroke-pair pipeline, fallbacks, attributes, the plan, timing."""

from .fallbacks import FALLBACK_METHOD
from .plan import InbetweenPlan, inbetween, plan_inbetween
from .strokes import InbetweenResult, Message, PairReport, StrokeSet
from .timing import ease, frame_times

__all__ = [
    "FALLBACK_METHOD",
    "InbetweenPlan",
    "InbetweenResult",
    "Message",
    "PairReport",
    "StrokeSet",
    "ease",
    "frame_times",
    "inbetween",
    "plan_inbetween",
]
