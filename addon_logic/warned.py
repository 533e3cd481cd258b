"""The strokes the last run's warnings name, kept with the Grease Pencil data for
``ballmorph.select_warned`` (Select Warned Strokes).

No bpy here (plain CPython imports it: ``tests/addon``). A run's warnings carry the strokes they
are about (:class:`.report_data.Report` ``strokes``: key frame and stroke number from 1). The
service keeps them, after a run that wrote frames, as one ID property of the Grease Pencil data:
``ballmorph_warned_strokes = {layer key: [key frame, stroke number, key frame, stroke number,
...]}`` (the layer key is :func:`.id_keys.id_key` of the layer name). Why there, and not in a
window-manager property or in module state:

- undo keeps it true: undoing a run takes its record away with its frames, redo brings both
  back, and the keys it points into are never changed by a run;
- it survives saving, reopening and reloading the add-on, so the strokes the command line warned
  about in a batch can be selected when the file is opened;
- it belongs to the drawing it names (several objects each keep their own last run).

Each run that writes replaces the record of its Grease Pencil data (a run with no warned stroke
removes it). A record can go stale when the animator edits the keys after the run: strokes
that no longer exist are then reported, never guessed.
"""

from . import reports
from .id_keys import id_key
from .report_data import StrokeRef

__all__ = ["PROPERTY", "warned_strokes", "record", "keep", "strokes_of"]

#: The ID property of the Grease Pencil data that keeps the record.
PROPERTY = "ballmorph_warned_strokes"


def warned_strokes(found_reports):
    """The strokes named by the warnings (and errors) among ``found_reports``, per layer.

    Parameters
    ----------
    found_reports : iterable of report_data.Report
        A run's reports (plain ``(level, text)`` pairs name no stroke and are skipped).

    Returns
    -------
    dict
        ``{layer name: tuple of StrokeRef}``, each layer's strokes in order (key, number), once.

    Examples
    --------
    >>> from .report_data import Report
    >>> found = [
    ...     Report("WARNING", "...", layer="Ink", strokes=(StrokeRef(9, 2), StrokeRef(1, 1))),
    ...     Report("INFO", "...", layer="Ink", strokes=(StrokeRef(1, 3),)),
    ...     Report("WARNING", "...", layer="Ink", strokes=(StrokeRef(1, 1),)),
    ... ]
    >>> warned_strokes(found)
    {'Ink': ((1, 1), (9, 2))}
    """
    found = {}
    for report in found_reports:
        strokes = getattr(report, "strokes", ())
        if strokes and report.layer is not None and reports.is_warning(report[0]):
            found.setdefault(report.layer, set()).update(strokes)
    return {layer: tuple(sorted(strokes)) for layer, strokes in found.items()}


def record(found):
    """The ID property value for :func:`warned_strokes`' result (None when it names no stroke).

    >>> record({"Ink": (StrokeRef(1, 1), StrokeRef(9, 2))})
    {'Ink': [1, 1, 9, 2]}
    """
    kept = {id_key(layer): [n for ref in strokes for n in ref] for layer, strokes in found.items() if strokes}
    return kept or None


def keep(grease_pencil_data, found_reports):
    """Replace the record on ``grease_pencil_data`` (any mapping: an ID, or a dict in tests) with
    the strokes ``found_reports`` warn about (remove it when they name none)."""
    value = record(warned_strokes(found_reports))
    if value is None:
        if PROPERTY in grease_pencil_data:
            del grease_pencil_data[PROPERTY]
        return
    grease_pencil_data[PROPERTY] = value


def strokes_of(grease_pencil_data, layer_name):
    """The strokes kept for layer ``layer_name``: a tuple of StrokeRef (empty when none).

    >>> data = {PROPERTY: {"Ink": [1, 1, 9, 2]}}
    >>> strokes_of(data, "Ink"), strokes_of(data, "Paint"), strokes_of({}, "Ink")
    (((1, 1), (9, 2)), (), ())
    """
    kept = grease_pencil_data.get(PROPERTY)
    if kept is None:
        return ()
    numbers = [int(n) for n in kept.get(id_key(layer_name), ())]
    return tuple(StrokeRef(key, number) for key, number in zip(numbers[::2], numbers[1::2]))
