"""Whole drawings, what the Blender operator calls: strokes, matching, registration, splitting,
the one stroke-pair pipeline, fallbacks, attributes, the plan, timing, the path preview."""

from .fallbacks import FALLBACK_METHOD
from .plan import InbetweenPlan, inbetween, plan_inbetween
from .preview import PREVIEW_POINTS, PREVIEW_TIMES, PathPreview, pair_colors, path_preview
from .strokes import InbetweenResult, Message, PairReport, StrokeSet
from .timing import ease, frame_times

__all__ = [
    "FALLBACK_METHOD",
    "InbetweenPlan",
    "InbetweenResult",
    "Message",
    "PREVIEW_POINTS",
    "PREVIEW_TIMES",
    "PairReport",
    "PathPreview",
    "StrokeSet",
    "ease",
    "frame_times",
    "inbetween",
    "pair_colors",
    "path_preview",
    "plan_inbetween",
]
