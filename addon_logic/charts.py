"""Timing charts kept with their intervals, so that a re-run uses them.

No bpy here (plain CPython imports it: ``tests/addon``; a dict stands in for the data-block).
Grease Pencil layers and frames cannot hold custom properties, so, like the record of generated
frames (:mod:`.generated`), the charts live on the Grease Pencil data-block (saved with the
.blend)::

    grease_pencil["ballmorph_timing_charts"] = {"<layer name>:<first key>-<last key>": "0.1 0.5 0.9"}

A run with a timing chart keeps it for every interval it wrote. A later run on the same keys of
the same layer with an empty ``timing_chart`` uses the kept chart again (and says so); a run with
another chart replaces it. Renaming the layer or moving a key forgets it (the safe direction: the
frame count and easing apply again). Deleting the custom property forgets every chart of the
object.
"""

from ..ballmorph_core import parse_timing_chart
from . import reports
from .id_keys import id_key
from .pairing import Chart, interval_name

__all__ = ["PROPERTY", "interval_key", "kept", "keep", "charts_for"]

PROPERTY = "ballmorph_timing_charts"


def interval_key(layer_name, frame_a, frame_b):
    """The chart's name in the record: ``'<layer name>:<first key>-<last key>'``.

    Examples
    --------
    >>> interval_key("Ink", 1, 9)
    'Ink:1-9'
    """
    return id_key(f"{layer_name}:{frame_a}-{frame_b}")


def kept(grease_pencil_data, layer_name, frame_a, frame_b):
    """The chart text kept for an interval ('' when none).

    Examples
    --------
    >>> data = {PROPERTY: {"Ink:1-9": "0.1 0.5 0.9"}}
    >>> kept(data, "Ink", 1, 9), kept(data, "Ink", 1, 5), kept({}, "Ink", 1, 9)
    ('0.1 0.5 0.9', '', '')
    """
    root = grease_pencil_data.get(PROPERTY)
    if root is None:
        return ""
    text = root.get(interval_key(layer_name, frame_a, frame_b), "")
    return text if isinstance(text, str) else ""


def keep(grease_pencil_data, interval):
    """Keep the chart of a written :class:`.pairing.Interval` with it (nothing without a chart).

    Examples
    --------
    >>> import numpy as np
    >>> from .pairing import Interval
    >>> data = {}
    >>> keep(data, Interval("Ink", 1, 9, np.array([3, 5, 7]), np.array([0.25, 0.5, 0.75]), chart=Chart((0.1, 0.5))))
    >>> data
    {'ballmorph_timing_charts': {'Ink:1-9': '0.1 0.5'}}
    """
    if interval.chart is None:
        return
    if grease_pencil_data.get(PROPERTY) is None:
        grease_pencil_data[PROPERTY] = {}
    # (read back after assigning: Blender copies a dict into an ID property group of its own)
    grease_pencil_data[PROPERTY][interval_key(interval.layer, interval.frame_a, interval.frame_b)] = interval.chart.text


def charts_for(grease_pencil_data, layer_name, pairs, given):
    """The chart of each key pair of a layer: the option's, else the one kept for the pair.

    Parameters
    ----------
    grease_pencil_data : bpy.types.GreasePencil or dict
    layer_name : str
    pairs : sequence of (int, int)
        The key pairs of the layer (``frame_a < frame_b``).
    given : str
        The ``timing_chart`` option (checked already: :func:`ballmorph_core.parse_timing_chart`).

    Returns
    -------
    charts : dict
        ``{(frame_a, frame_b): pairing.Chart}`` for the pairs a chart times.
    notes : list of (level, text)
        Kept charts that no longer fit their keys (ignored).

    Raises
    ------
    ValueError
        When the option's chart has more fractions than frames between a pair's keys: the
        operator refuses the run (nothing is written), saying which interval and why.

    Examples
    --------
    >>> charts, notes = charts_for({}, "Ink", [(1, 9)], "0.1 0.5")
    >>> charts[(1, 9)].text, charts[(1, 9)].kept
    ('0.1 0.5', False)
    >>> charts, _ = charts_for({PROPERTY: {"Ink:1-9": "0.1 0.5 0.9"}}, "Ink", [(1, 9), (9, 13)], "")
    >>> charts[(1, 9)].text, charts[(1, 9)].kept, (9, 13) in charts
    ('0.1 0.5 0.9', True, False)
    """
    charts, notes = {}, []
    for a, b in pairs:
        name = interval_name(layer_name, a, b)
        if given.strip():
            try:
                charts[a, b] = Chart(parse_timing_chart(given, room=b - a - 1))
            except ValueError as exc:
                raise ValueError(reports.chart_does_not_fit(name, str(exc))) from None
            continue
        text = kept(grease_pencil_data, layer_name, a, b)
        if not text:
            continue
        try:
            fractions = parse_timing_chart(text, room=b - a - 1)
        except ValueError as exc:
            notes.append((reports.WARNING, reports.kept_chart_ignored(name, text, str(exc))))
            continue
        if fractions:
            charts[a, b] = Chart(fractions, kept=True)
    return charts, notes
