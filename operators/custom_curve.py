"""The Custom type's curve: Blender's own, sampled into a table the core reads.

Interpolate Sequence's Custom type reads one curve per scene, in its tool settings
(``scene.tool_settings.gpencil_interpolate.interpolation_curve``, a CurveMapping; verified on
Blender 4.5 and 5.0): ``BKE_curvemapping_evaluateF(curve, 0, fraction)`` for each in-between.
The add-on's Custom type evaluates that same curve, so one curve times both tools. Blender makes
the curve the first time Interpolate Sequence runs in a scene (until then the pointer is None
and Python cannot make it); Blender's new curve is the straight line, so a scene without one
runs Linear, and says so.

The core never sees Blender: the curve is sampled here (``CurveMapping.evaluate``, after
``initialize()``, which builds its table when a loaded file has none, as Interpolate Sequence
does) at :data:`SAMPLES` evenly spaced fractions, and the core interpolates that table linearly.
Blender evaluates its own 257-entry table (``CM_TABLE`` + 1) linearly too, and the samples
include those entries (1024 = 4 x 256), so the table reproduces Blender's values up to its
float32 rounding.
"""

import numpy as np

from ..addon_logic import reports

__all__ = ["SAMPLES", "table", "with_custom_curve"]

#: Samples of the curve from fraction 0 to 1 (see the module's docstring).
SAMPLES = 1025


def table(scene):
    """The scene's Custom curve at :data:`SAMPLES` evenly spaced fractions, or None when the
    scene has none yet."""
    mapping = scene.tool_settings.gpencil_interpolate.interpolation_curve
    if mapping is None:
        return None
    mapping.initialize()
    curve = mapping.curves[0]
    return np.array([mapping.evaluate(curve, x) for x in np.linspace(0.0, 1.0, SAMPLES)])


def with_custom_curve(values, scene):
    """``values`` (:func:`.options.values_of`) with the table the 'custom' type reads.

    Returns
    -------
    values : dict
        A copy with ``'custom_curve'`` (the scene's curve, or the straight line when it has
        none) when the type is 'custom'; else ``values`` itself.
    note : str
        Why a Custom run is linear ('' when it is not).
    """
    if values["easing_type"] != "custom":
        return values, ""
    sampled = table(scene)
    if sampled is not None:
        return {**values, "custom_curve": sampled}, ""
    return {**values, "custom_curve": np.array([0.0, 1.0])}, reports.no_custom_curve(scene.name)
