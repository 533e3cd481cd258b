"""ballmorph_core: ball-map correspondence and ball-morphs of planar curves, in pure numpy.

Whited & Rossignac, "Ball-morph: Definition, Implementation and Comparative Evaluation".
This package never imports bpy: it runs in plain CPython and vendored inside the add-on.

The subpackages go from the bottom up: ``geometry`` (polylines, nothing from the paper),
``ballmap`` (the correspondence), ``morphs`` (every morph behind one interface), ``drawing``
(what the Blender operator calls: whole drawings through the one stroke-pair pipeline) and
``study`` (the paper's quality measures). See docs/architecture.md.
"""

from .ballmap import CompatibilityReport, Correspondence, ball_map, classify
from .drawing import (
    FALLBACK_METHOD,
    FALLBACK_MORPHS,
    FAVOR_ODDS,
    HINT,
    PREVIEW_POINTS,
    PREVIEW_TIMES,
    InbetweenPlan,
    InbetweenResult,
    Message,
    PairMorphs,
    PairOutcome,
    PairReport,
    PathCorrection,
    PathPreview,
    StrokeSet,
    apply_favor,
    chain_corrections,
    ease,
    frame_times,
    inbetween,
    ink_lengths,
    length_deviation,
    pair_colors,
    parse_timing_chart,
    path_preview,
    plan_inbetween,
)
from .errors import BallMorphError, IncompatibleCurvesError, InvalidCurveError
from .morphs import METHODS, Morph, make_morph
from .morphs.paths import BallPaths, midpoint_locus
from .options import CARRIERS, EASING_MODES, EASING_TYPES, KEY_MOTIONS, MATCHINGS, UNMATCHED

__all__ = [
    "METHODS",
    "CARRIERS",
    "MATCHINGS",
    "UNMATCHED",
    "KEY_MOTIONS",
    "FALLBACK_METHOD",
    "FALLBACK_MORPHS",
    "EASING_TYPES",
    "EASING_MODES",
    "FAVOR_ODDS",
    "ease",
    "apply_favor",
    "chain_corrections",
    "PathCorrection",
    "frame_times",
    "parse_timing_chart",
    "InbetweenPlan",
    "InbetweenResult",
    "Message",
    "PairMorphs",
    "PairOutcome",
    "PairReport",
    "HINT",
    "StrokeSet",
    "inbetween",
    "ink_lengths",
    "length_deviation",
    "plan_inbetween",
    "PathPreview",
    "PREVIEW_POINTS",
    "PREVIEW_TIMES",
    "path_preview",
    "pair_colors",
    "BallPaths",
    "Morph",
    "make_morph",
    "measure",
    "midpoint_locus",
    "BallMorphError",
    "CompatibilityReport",
    "Correspondence",
    "IncompatibleCurvesError",
    "InvalidCurveError",
    "ball_map",
    "classify",
]


def __getattr__(name):
    """``measure`` on first use: the paper's measures (``study``) are not imported with the core,
    so the add-on, which never measures, does not load them (and its zip leaves them out)."""
    if name == "measure":
        try:
            from .study import measure
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.study":
                raise
            # the add-on's zip: study is not shipped
            raise ImportError("ballmorph_core.measure needs the study package, which the add-on does not ship") from exc
        return measure
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
