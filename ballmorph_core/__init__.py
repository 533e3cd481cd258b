"""ballmorph_core: ball-map correspondence and ball-morphs of planar curves, in pure numpy.

Whited & Rossignac, "Ball-morph: Definition, Implementation and Comparative Evaluation".
This package never imports bpy: it runs in plain CPython and vendored inside the add-on.
"""

from .ballmap import CompatibilityReport, Correspondence, ball_map, classify
from .drawing.plan import (
    CARRIERS,
    FALLBACK_METHOD,
    MATCHINGS,
    UNMATCHED,
    InbetweenPlan,
    InbetweenResult,
    StrokeSet,
    inbetween,
    plan_inbetween,
)
from .drawing.timing import EASING_MODES, EASING_TYPES, ease, frame_times
from .errors import BallMorphError, IncompatibleCurvesError, InvalidCurveError
from .morphs import METHODS, Morph, make_morph
from .morphs.paths import BallPaths, midpoint_locus
from .study.measures import measure

__all__ = [
    "METHODS",
    "CARRIERS",
    "MATCHINGS",
    "UNMATCHED",
    "FALLBACK_METHOD",
    "EASING_TYPES",
    "EASING_MODES",
    "ease",
    "frame_times",
    "InbetweenPlan",
    "InbetweenResult",
    "StrokeSet",
    "inbetween",
    "plan_inbetween",
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
