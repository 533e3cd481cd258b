"""What the add-on tells the animator: every report text, built from plain data.

No bpy here (plain CPython imports it: ``tests/addon``). A report is a ``(level, text)`` pair;
the levels are Blender's report types (:data:`INFO`, :data:`WARNING`, :data:`ERROR`), which the
operator passes to ``self.report`` and the command line prints. Texts say what happened and,
when something was not done, what to do about it.

It also decides which stroke pairs deserve a warning after a run (:func:`strays`): those whose
in-betweens stray from what the keys suggest, each with the frame where a breakdown key would
help most.
"""

import re
from dataclasses import dataclass, field

import numpy as np

from ..ballmorph_core import FALLBACK_MORPHS
from .report_data import Report, StrokeRef

__all__ = [
    "INFO",
    "WARNING",
    "ERROR",
    "LEVELS",
    "frames_text",
    "failure",
    "object_kind",
    "no_object",
    "method_unavailable",
    "no_layers",
    "layer_blocked",
    "too_few_keys",
    "no_key_around",
    "no_frame_between",
    "on_a_key",
    "no_room_between_keys",
    "all_drawn",
    "both_keys_empty",
    "flat_transform",
    "invalid_coordinates",
    "fell_back",
    "morph_failed",
    "joined_smoothly",
    "not_joined",
    "interval_reports",
    "no_custom_curve",
    "warned_selected",
    "warned_missing",
    "warned_none_left",
    "nothing_to_do",
    "write_failed",
    "summary",
    "is_warning",
    "bad_chart",
    "labelled",
    "chart_does_not_fit",
    "kept_chart_ignored",
    "Stray",
    "strays",
    "stray_reports",
]

INFO, WARNING, ERROR = "INFO", "WARNING", "ERROR"
LEVELS = (INFO, WARNING, ERROR)

# Messages listed per interval before "and N more" (the Info editor keeps them all).
MESSAGES_PER_REPORT = 6
#: A pair whose in-between's ink length is off the keys' blend of lengths by more than this
#: fraction strays (0.2: 20% longer or shorter).
LENGTH_STRAY = 0.2
#: Straying pairs reported one line each per interval; the others share one line.
STRAYS_LISTED = 3
_NAME = "Ball-morph In-between"


def frames_text(numbers):
    """Frame numbers for a sentence: ``'2–8'`` for a run of three or more, else ``'2, 5'``.

    Examples
    --------
    >>> frames_text([2, 3, 4, 5])
    '2–5'
    >>> frames_text([3, 5, 7])
    '3, 5, 7'
    """
    numbers = [int(n) for n in numbers]
    if len(numbers) > 2 and numbers[-1] - numbers[0] == len(numbers) - 1:
        return f"{numbers[0]}\u2013{numbers[-1]}"
    return ", ".join(str(n) for n in numbers)


def failure(exc):
    """An unexpected exception as a report fragment: ``'ZeroDivisionError: ...'``."""
    return f"{type(exc).__name__}: {exc}"


def object_kind(object_type):
    """Blender's object type id as a word: ``'LIGHT_PROBE'`` -> ``'light probe'``."""
    return object_type.replace("_", " ").lower()


def is_warning(level):
    """Whether a report level asks for attention (a warning or an error)."""
    return level in (WARNING, ERROR)


# -- before anything is read ----------------------------------------------------------------------


def no_object(active_name=None, active_type=None):
    """Why the operator has nothing to work on: no active object, or one of another type.

    ``active_type`` is Blender's object type id (``'MESH'``).
    """
    if active_name is None:
        return f"No Grease Pencil object is active: select one and run {_NAME} again"
    return (
        f"The active object '{active_name}' is a {object_kind(active_type)}, not a Grease Pencil object: "
        f"make a Grease Pencil object active and run {_NAME} again"
    )


def labelled(text, name, label):
    """``text`` with an option's argument name (the core's words: ``'timing_chart: ...'``,
    ``'favor must be ...'``) replaced by the option's label as the UI shows it.

    Examples
    --------
    >>> labelled("Ink 1→4: timing_chart: 3 fractions", "timing_chart", "Timing Chart")
    'Ink 1→4: Timing Chart: 3 fractions'
    >>> labelled("favor must be a number in [-1, 1], got 2", "favor", "Favor")
    'Favor must be a number in [-1, 1], got 2'
    """
    return re.sub(rf"\b{re.escape(name)}\b", label, text)


def bad_chart(problem):
    """A ``timing_chart`` option that is not a chart (``problem``: the core's words for what is wrong)."""
    return (
        f"{problem}: nothing was written; write fractions between 0 and 1 in rising order, such as "
        "'0.1 0.3 0.6 0.9', or leave the chart empty"
    )


def chart_does_not_fit(interval_name, problem):
    """The chart has more fractions than frames between an interval's keys: the run is refused."""
    return f"{interval_name}: {problem}: nothing was written; give fewer fractions, or keys farther apart"


def kept_chart_ignored(interval_name, text, problem):
    """A chart kept with an interval cannot be read (edited by hand): the interval is timed as without."""
    return f"{interval_name}: the timing chart kept here ('{text}') was ignored ({problem}): type the chart again"


def no_custom_curve(scene_name):
    """The Custom type in a scene where Blender has not made its curve yet."""
    return (
        f"scene '{scene_name}' has no Custom curve yet, so the Custom type ran Linear (Blender's new curve): "
        "run Interpolate Sequence once with Type Custom to make the curve, then shape it there or in this "
        "add-on's panel"
    )


def method_unavailable(method_label):
    return f"The {method_label} morph is not available in this version: choose another"


def no_layers(object_name, layers):
    """The object has no layer to in-between (``layers`` is the option's value)."""
    if layers == "active":
        return f"'{object_name}' has no active layer: add or select a layer"
    return f"'{object_name}' has no layers: add a layer and draw keys on it"


def layer_blocked(layer_name, chain):
    """Why a layer cannot be written, or ''.

    Parameters
    ----------
    layer_name : str
    chain : sequence of (group name or None, locked, hidden)
        The layer itself (name None), then each layer group it is in, innermost first.

    Returns
    -------
    str
        The first lock or hide on the way up, with what to do; '' when the layer is writable.
    """
    for group, locked, hidden in chain:
        where = f" (group '{group}')" if group is not None else ""
        if locked:
            return f"layer '{layer_name}' is locked{where}: unlock it to in-between it"
        if hidden:
            return f"layer '{layer_name}' is hidden{where}: show it to in-between it"
    return ""


# -- which keys ------------------------------------------------------------------------------------


def too_few_keys(layer_name, count):
    return f"layer '{layer_name}' has {count} keyframe(s): draw a second key to in-between"


def no_key_around(layer_name, side, current_frame):
    """No key ``side`` (``'before'`` or ``'after'``) the current frame."""
    return (
        f"layer '{layer_name}' has no keyframe {side} frame {current_frame}: select two keyframes, "
        "or go to a frame between two keys"
    )


def on_a_key(layer_name, frame):
    """The current frame holds a key, and the run asked for one in-between on the current frame."""
    return (
        f"layer '{layer_name}': the current frame {frame} is a keyframe: "
        "go to a frame between two keys to in-between it"
    )


def no_frame_between(layer_name, frame_a, frame_b):
    return (
        f"layer '{layer_name}': keys {frame_a} and {frame_b} have no frame between them: "
        "move them apart, or select two keys with frames between them"
    )


def no_room_between_keys(layer_name):
    """Every pair of consecutive keys is on consecutive frames (the command line's rule)."""
    return f"layer '{layer_name}': every key is on the frame after the previous one: no frame to in-between"


def all_drawn(interval_name):
    return (
        f"{interval_name}: every frame between the keys is drawn by hand: nothing was written "
        "(delete drawn frames there to make room for in-betweens)"
    )


def both_keys_empty(interval_name):
    return f"{interval_name}: both keys are empty: draw strokes in them first"


# -- keys the core cannot take -------------------------------------------------------------------


def flat_transform(layer_name):
    return f"layer '{layer_name}' has a flat transform (zero scale): give the layer a non-zero scale to in-between it"


def invalid_coordinates(frame_number, strokes):
    """Points with NaN or infinite coordinates in the key on ``frame_number`` (``strokes``: indices)."""
    listed = ", ".join(str(int(s)) for s in list(strokes)[:6])
    return (
        f"the key on frame {frame_number} has points with invalid (NaN or infinite) coordinates in stroke(s) "
        f"{listed}: redraw or delete those strokes"
    )


# -- morphs that failed ----------------------------------------------------------------------------


def fell_back(method_label, failed, fallback_label):
    """The interval was redone whole with the fallback morph after ``failed`` (see :func:`failure`)."""
    return (
        f"the {method_label} morph failed ({failed}): every in-between here was made with {fallback_label} "
        "instead; please report this drawing"
    )


def morph_failed(interval_name, failed):
    """Every morph failed for an interval: nothing written there."""
    return (
        f"{interval_name}: the morph failed ({failed}): nothing was written between these keys; "
        "try another morph, or simplify the strokes, and please report this drawing"
    )


def joined_smoothly(smooth, corners):
    """An interval's in-betweens were joined smoothly to its neighbours' at the keys ``smooth``
    (frame numbers); ``corners`` are its inner keys typed Extreme, which kept their corner."""
    text = f"arcs through the keys: joined smoothly at frame {frames_text(smooth)}" if smooth else ""
    if corners:
        kept = f"the Extreme key at frame {frames_text(corners)} keeps its corner"
        text = f"{text}; {kept}" if text else f"arcs through the keys: {kept}"
    return text


def not_joined(failed):
    """Joining intervals smoothly failed (see :func:`failure`): each kept its own in-betweens."""
    return (
        f"could not join the intervals smoothly ({failed}): each keeps its own in-betweens, with a corner at the keys"
    )


# -- after the run ---------------------------------------------------------------------------------


def interval_reports(interval, method_label, messages, found_strays=()):
    """Reports for one written interval: what was written, what was left alone, what the morph said.

    Parameters
    ----------
    interval : pairing.Interval
    method_label : str
        The morph that made the frames, as the animator reads it.
    messages : sequence of (level, text)
        The morph's own messages (the core's ERROR ones concern single strokes: the run went on,
        so they become warnings); a :class:`.report_data.Report` among them lends its strokes to
        the report that says it.
    found_strays : sequence of Stray
        The pairs that stray (:func:`strays`), worst first: reported last (:func:`stray_reports`).

    Returns
    -------
    list of report_data.Report
        Each with its kind (``'written'``, ``'timing-chart'``, ``'drawn-frames'``, ``'morph'``,
        ``'stray'``), the interval's layer and keys.
    """
    name = interval.name
    about = {"layer": interval.layer, "frames": (interval.frame_a, interval.frame_b)}
    replaced = f", replacing {len(interval.replace)} earlier" if interval.replace else ""
    chart = interval.chart
    charted = f", timing chart {chart.text}" if chart is not None and not chart.kept else ""
    written = (
        f"{name}: {len(interval.targets)} in-between(s) on frame(s) {frames_text(interval.targets)} "
        f"({method_label}{charted}{replaced})"
    )
    reports = [Report(INFO, written, kind="written", **about)]
    if chart is not None and chart.kept:
        kept = f"timed by the chart {chart.text} kept from an earlier run on these keys (type a chart to change it)"
        reports.append(Report(INFO, f"{name}: {kept}", kind="timing-chart", **about))
    if interval.skipped:
        drawn = f"{name}: frame(s) {frames_text(interval.skipped)} already drawn: left untouched"
        reports.append(Report(WARNING, drawn, kind="drawn-frames", **about))
    elif interval.occupied:
        drawn = f"{name}: frame(s) {frames_text(interval.occupied)} between the keys left untouched"
        reports.append(Report(INFO, drawn, kind="drawn-frames", **about))
    for level in (WARNING, INFO):
        chosen = [message for message in messages if (message[0] == INFO) == (level == INFO)]
        if chosen:
            texts = [text for _, text in chosen]
            more = len(texts) - MESSAGES_PER_REPORT
            shown = "; ".join(texts[:MESSAGES_PER_REPORT]) + (f"; and {more} more" if more > 0 else "")
            # the strokes of every message it stands for (a plain (level, text) pair names none)
            strokes = tuple(dict.fromkeys(ref for message in chosen for ref in getattr(message, "strokes", ())))
            reports.append(Report(level, f"{name}: {shown}", kind="morph", strokes=strokes, **about))
    keys = (interval.frame_a, interval.frame_b)
    return reports + [report.about(**about) for report in stray_reports(name, found_strays, keys)]


def _strokes_text(found):
    """``{layer: StrokeRefs}`` as the animator reads them: ``"layer 'Ink': key 1 stroke 2, key 9 stroke 1"``."""
    return "; ".join(
        f"layer '{layer}': " + ", ".join(f"key {key} stroke {number}" for key, number in refs)
        for layer, refs in found.items()
    )


def warned_selected(found):
    """Select Warned Strokes selected ``found`` (``{layer: StrokeRefs}``).

    >>> from .report_data import StrokeRef
    >>> print(warned_selected({"Ink": (StrokeRef(1, 2), StrokeRef(9, 1))}))  # doctest: +NORMALIZE_WHITESPACE
    Selected 2 warned stroke(s) in their keys (layer 'Ink': key 1 stroke 2, key 9 stroke 1):
    go to a key's frame in Edit Mode to see them
    """
    count = sum(len(refs) for refs in found.values())
    return (
        f"Selected {count} warned stroke(s) in their keys ({_strokes_text(found)}): "
        "go to a key's frame in Edit Mode to see them"
    )


def warned_missing(missing):
    """Strokes the last run warned about that are gone (keys edited since)."""
    return f"Not found (the keys changed since the run): {_strokes_text(missing)}; run Ball-morph In-between again"


def warned_none_left():
    return "None of the strokes the last run warned about is left (the keys changed since): nothing selected"


def nothing_to_do(problems):
    """The cancel text when no interval could be in-betweened (``problems``: report texts)."""
    return "Nothing to in-between: " + "; ".join(problems)


def write_failed(exc):
    return f"Writing the in-betweens failed, nothing was changed: {exc}"


def summary(frames, layers, warnings, strokes_warned=False):
    """The run's last report (the one the status bar shows): a warning when anything warned;
    ``strokes_warned``: some warnings name strokes (Select Warned Strokes selects them)."""
    text = f"{_NAME}: {frames} frame(s) on {layers} layer(s)"
    if warnings:
        select = "; Select Warned Strokes (sidebar) selects their strokes" if strokes_warned else ""
        return WARNING, f"{text}, {warnings} warning(s): see the Info editor{select}"
    return INFO, text


# -- pairs that stray from their keys --------------------------------------------------------------


@dataclass(frozen=True)
class Stray:
    """A stroke pair whose in-betweens stray from what its keys suggest.

    Attributes
    ----------
    what : str
        The pair as the animator reads it, strokes numbered from 1: ``'stroke 1 -> 2'``.
    why : str
        ``'ink 34% longer than the keys' blend'``, ``'made with linear-interpolation (a fallback)'``, ...
    frame : int
        The in-between where it strays most: where a breakdown key would help.
    indices : tuple of (int or None)
        ``(stroke_a, stroke_b)``: the pair's stroke indices in the two keys (from 0; None: no
        stroke there), for :class:`.report_data.StrokeRef`.
    """

    what: str
    why: str
    frame: int
    indices: tuple = field(default=(None, None), compare=False)  # the text names the pair already


def _fallbacks_used(used, method):
    """The fallback morphs among a pair's morphs (``PairReport.used``), a tuple."""
    return tuple(m for m in used.morphs if m in FALLBACK_MORPHS and m != method)


def _middle(times):
    """Index of the in-between nearest the middle of the morph (the later one of a tie: where
    strokes without a partner switch)."""
    return int(np.lexsort((-times, np.abs(times - 0.5)))[0])


def _length_why(deviation):
    way = "longer" if deviation > 0 else "shorter"
    amount = "far" if not np.isfinite(deviation) else f"{abs(deviation):.0%}"
    return f"ink {amount} {way} than the keys' blend of lengths"


def _stray(pair, method, off, size, worst, middle):
    """``(Stray fields without the frame number, frame index, rank)`` for one pair, or None;
    ``off`` and ``size`` are its deviation and its size at its worst frame ``worst``."""
    if pair.stroke_a is None or pair.stroke_b is None:
        return None  # the morph's own warning says it already: one warning per stroke
    whys = []
    fallbacks = _fallbacks_used(pair.used, method)
    if fallbacks:
        whys.append(f"made with {' and '.join(fallbacks)} (a fallback)")
    if size > LENGTH_STRAY:
        whys.append(_length_why(off))
    if not whys:
        return None
    # numbered from 1, as the animator counts the strokes of a key
    what = f"stroke {pair.stroke_a + 1} -> {pair.stroke_b + 1}"
    return what, "; ".join(whys), worst, (0 if fallbacks else 1, -size)


def strays(pairs, method, deviation, times, frames):
    """The stroke pairs whose in-betweens stray from what their keys suggest, worst first.

    A pair strays when its in-betweens' ink length is off the keys' linear blend of lengths by
    more than :data:`LENGTH_STRAY`, or when it was made with a fallback morph
    (:data:`ballmorph_core.FALLBACK_MORPHS`, other than the one asked for). A stroke without a
    partner is not a stray: the morph's own warning says it, once. Its worst frame is the
    in-between whose length is farthest from the blend; for a pair whose length stays on the
    blend, the in-between nearest the middle of the morph.

    Parameters
    ----------
    pairs : sequence of ballmorph_core.PairReport
        What happened to each pair (the core's ``result.pairs``): P of them.
    method : str
        The morph asked for (a core value: ``'circular-ball'``).
    deviation : array_like, shape (P, T)
        Each pair's ink length off the blend at each in-between
        (:func:`ballmorph_core.length_deviation`; NaN where there is none).
    times : array_like, shape (T,)
        The morph time of each in-between.
    frames : array_like of int, shape (T,)
        The frame number of each in-between.

    Returns
    -------
    list of Stray
        Pairs that fell back first, then the others by how far they stray.

    Examples
    --------
    >>> from ballmorph_core import PairMorphs, PairReport
    >>> ball, fell_back = PairMorphs(("circular-ball",)), PairMorphs(("circular-ball", "linear-interpolation"))
    >>> pairs = [PairReport(0, 0, str(ball), used=ball), PairReport(1, 1, str(fell_back), used=fell_back)]
    >>> deviation = [[0.05, -0.3, 0.1], [0.0, 0.02, 0.0]]
    >>> for s in strays(pairs, "circular-ball", deviation, [0.25, 0.5, 0.75], [3, 5, 7]):
    ...     print(s.what, "|", s.why, "|", s.frame)
    stroke 2 -> 2 | made with linear-interpolation (a fallback) | 5
    stroke 1 -> 1 | ink 30% shorter than the keys' blend of lengths | 5
    """
    times = np.clip(np.asarray(times, dtype=np.float64).reshape(-1), 0.0, 1.0)
    frames = np.asarray(frames).reshape(-1)
    deviation = np.asarray(deviation, dtype=np.float64).reshape(len(pairs), len(times))
    if not len(times):
        return []
    # Every pair's worst frame at once (one pass over the (P, T) table, not one per pair).
    size = np.abs(np.nan_to_num(deviation, nan=0.0, posinf=np.inf))
    middle = _middle(times)
    worst = np.where(size.max(axis=1, initial=0.0) > 0, np.argmax(size, axis=1), middle)
    rows = np.arange(len(pairs))
    found = []
    for pair, off, at, index in zip(pairs, deviation[rows, worst].tolist(), size[rows, worst].tolist(), worst.tolist()):
        stray = _stray(pair, method, off, at, index, middle)
        if stray is not None:
            what, why, frame, rank = stray
            found.append((rank, Stray(what, why, int(frames[frame]), (pair.stroke_a, pair.stroke_b))))
    return [stray for _, stray in sorted(found, key=lambda item: item[0])]


def stray_reports(interval_name, found_strays, keys=None):
    """The warnings for the pairs that stray in an interval: a few one by one, the rest in one line.

    Parameters
    ----------
    interval_name : str
    found_strays : sequence of Stray
        Worst first (:func:`strays`).
    keys : (int, int), optional
        The interval's key frames: each report then names its strokes (``strokes``).

    Returns
    -------
    list of report_data.Report
        At most :data:`STRAYS_LISTED` + 1 reports, of kind ``'stray'``.

    Examples
    --------
    >>> stray_reports("Ink 1→9", [Stray("stroke 1 -> 1", "ink 30% shorter than the keys' blend of lengths", 5)])
    [('WARNING', "Ink 1→9: stroke 1 -> 1 strays from its keys (ink 30% shorter than the keys' blend of lengths), \
most on frame 5: draw a breakdown key on frame 5")]
    """
    listed, rest = list(found_strays[:STRAYS_LISTED]), list(found_strays[STRAYS_LISTED:])
    reports = [
        Report(
            WARNING,
            f"{interval_name}: {s.what} strays from its keys ({s.why}), most on frame {s.frame}: "
            f"draw a breakdown key on frame {s.frame}",
            kind="stray",
            strokes=_stroke_refs([s], keys),
        )
        for s in listed
    ]
    if rest:
        where = frames_text(sorted({s.frame for s in rest}))
        reports.append(
            Report(
                WARNING,
                f"{interval_name}: {len(rest)} more stroke pair(s) stray from their keys, most on frame(s) {where}: "
                "breakdown keys there would help",
                kind="stray",
                strokes=_stroke_refs(rest, keys),
            )
        )
    return reports


def _stroke_refs(found_strays, keys):
    """The strokes of some strays, in their keys (none without ``keys``)."""
    if keys is None:
        return ()
    return tuple(
        StrokeRef.of_index(key, index)
        for stray in found_strays
        for key, index in zip(keys, stray.indices)
        if index is not None
    )
