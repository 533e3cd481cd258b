"""Whole drawings, what the Blender operator calls: strokes, matching, registration, splitting,
the one stroke-pair pipeline, fallbacks, attributes, the plan, timing, how far in-betweens
stray from their keys, and the path preview."""

from .frames.arcs import PathCorrection, chain_corrections
from .frames.preview import PREVIEW_POINTS, PREVIEW_TIMES, PathPreview, pair_colors, path_preview
from .frames.timing import FAVOR_ODDS, apply_favor, ease, frame_times, parse_timing_chart
from .keys.hints import HINT
from .pair_morphs.fallbacks import FALLBACK_METHOD
from .plan import InbetweenPlan, inbetween, plan_inbetween
from .reports.straying import FALLBACK_MORPHS, ink_lengths, length_deviation
from .strokes import InbetweenResult, Message, PairMorphs, PairOutcome, PairReport, StrokeSet

__all__ = [
    "FALLBACK_METHOD",
    "FALLBACK_MORPHS",
    "FAVOR_ODDS",
    "HINT",
    "InbetweenPlan",
    "InbetweenResult",
    "Message",
    "PREVIEW_POINTS",
    "PREVIEW_TIMES",
    "PairMorphs",
    "PairOutcome",
    "PairReport",
    "PathCorrection",
    "PathPreview",
    "StrokeSet",
    "apply_favor",
    "chain_corrections",
    "ease",
    "frame_times",
    "parse_timing_chart",
    "inbetween",
    "ink_lengths",
    "length_deviation",
    "pair_colors",
    "path_preview",
    "plan_inbetween",
]
