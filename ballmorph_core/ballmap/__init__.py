"""The ball-map correspondence (paper sections 3-5): topology and compatibility reports,
candidate disks, lacing, the disk check, symmetric thinning."""

from .correspondence import Correspondence, DenseMaps, ball_map, ball_maps, dense_maps
from .report import CompatibilityReport, Violation
from .topology import CONFIGURATIONS, PairSetup, classify, orient_pair, shared_endpoints

__all__ = [
    "CONFIGURATIONS",
    "CompatibilityReport",
    "Correspondence",
    "DenseMaps",
    "PairSetup",
    "Violation",
    "ball_map",
    "ball_maps",
    "classify",
    "dense_maps",
    "orient_pair",
    "shared_endpoints",
]
