"""ballmorph_core: ball-map correspondence and ball-morphs of planar curves, in pure numpy.

Whited & Rossignac, "Ball-morph: Definition, Implementation and Comparative Evaluation".
This package never imports bpy: it runs in plain CPython and vendored inside the add-on.
"""

from .ballmap import Correspondence, ball_map
from .compat import CompatibilityReport, classify
from .errors import BallMorphError, IncompatibleCurvesError, InvalidCurveError
from .inbetween import (
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
from .measures import measure
from .morphs import METHODS, Morph, make_morph
from .timing import EASING_MODES, EASING_TYPES, ease, frame_times
from .trajectories import BallPaths, midpoint_locus

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
