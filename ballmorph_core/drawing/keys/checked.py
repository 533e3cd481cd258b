"""The keys, times and options a plan is asked for, checked before any work: a clear error
(:class:`~ballmorph_core.errors.InvalidCurveError` naming the key, the attribute and the strokes,
numbered as the animator counts them) instead of NaN frames or a failure deep in the pipeline."""

import numpy as np

from ...errors import InvalidCurveError
from ...geometry.polyline import MAX_COORDINATE
from ...options import CARRIERS, MATCHINGS, UNMATCHED, check_option, check_positive
from ..strokes import StrokeSet, as_written

__all__ = ["check_inputs", "check_times", "check_key"]


def check_inputs(key_a, key_b, method, carrier, matching, unmatched, spacing):
    """The options in the core's spelling (and the keys checked), or a clear error."""
    from ...morphs import METHODS  # local: the registry is complete once the package is imported

    options = (
        check_option("method", method, METHODS),
        check_option("carrier", carrier, CARRIERS),
        check_option("matching", matching, MATCHINGS),
        check_option("unmatched", unmatched, UNMATCHED),
        None if spacing is None else check_positive("spacing", spacing),
    )
    for name, key in (("key_a", key_a), ("key_b", key_b)):
        check_key(name, key)
    return options


def check_times(times):
    """Times as a float array clamped to [0, 1] (a morph has nothing before or after its keys)."""
    try:
        times = np.asarray(times, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InvalidCurveError(f"times: must be numbers in [0, 1], got {times!r}") from None
    if not np.all(np.isfinite(times)):
        raise InvalidCurveError("times: must be finite numbers in [0, 1]")
    return np.clip(times, 0.0, 1.0)


def check_key(name, key):
    """Reject what cannot be a drawing, naming the key, the attribute and the strokes."""
    if not isinstance(key, StrokeSet):
        raise InvalidCurveError(f"{name}: expected a StrokeSet, got {type(key).__name__}")
    for attr, values in (
        ("positions", key.positions),
        ("radius", key.radius),
        ("opacity", key.opacity),
        ("vertex_color", key.vertex_color),
    ):
        if values.size and not np.all(np.isfinite(values)):
            points = np.flatnonzero(~np.all(np.isfinite(values.reshape(len(values), -1)), axis=1))
            bad = [as_written(k) for k in np.unique(np.searchsorted(key.offsets, points, "right") - 1)[:10]]
            what = "coordinates" if attr == "positions" else attr
            raise InvalidCurveError(f"{name}: stroke(s) {bad} have NaN or infinite {what}: redraw or delete them")
    huge = np.flatnonzero(np.abs(key.positions).max(axis=1, initial=0.0) > MAX_COORDINATE)
    if len(huge):
        bad = [as_written(k) for k in np.unique(np.searchsorted(key.offsets, huge, "right") - 1)[:10]]
        largest = float(np.abs(key.positions).max())
        raise InvalidCurveError(
            f"{name}: stroke(s) {bad} have coordinates up to {largest:.3g}, beyond the {MAX_COORDINATE:g} "
            "the geometry can square and multiply: scale the drawing down"
        )
