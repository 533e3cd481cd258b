"""What the add-on tells the animator: every report text, built from plain data.

No bpy here (plain CPython imports it: ``tests/addon``). A report is a ``(level, text)`` pair;
the levels are Blender's report types (:data:`INFO`, :data:`WARNING`, :data:`ERROR`), which the
operator passes to ``self.report`` and the command line prints. Texts say what happened and,
when something was not done, what to do about it.
"""

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
    "no_room_between_keys",
    "all_drawn",
    "both_keys_empty",
    "flat_transform",
    "invalid_coordinates",
    "fell_back",
    "morph_failed",
    "interval_reports",
    "nothing_to_do",
    "write_failed",
    "summary",
    "is_warning",
]

INFO, WARNING, ERROR = "INFO", "WARNING", "ERROR"
LEVELS = (INFO, WARNING, ERROR)

# Messages listed per interval before "and N more" (the Info editor keeps them all).
MESSAGES_PER_REPORT = 6
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


# -- after the run ---------------------------------------------------------------------------------


def interval_reports(interval, method_label, messages):
    """Reports for one written interval: what was written, what was left alone, what the morph said.

    Parameters
    ----------
    interval : pairing.Interval
    method_label : str
        The morph that made the frames, as the animator reads it.
    messages : sequence of (level, text)
        The morph's own messages (the core's ERROR ones concern single strokes: the run went on,
        so they become warnings).

    Returns
    -------
    list of (level, text)
    """
    name = interval.name
    replaced = f", replacing {len(interval.replace)} earlier" if interval.replace else ""
    reports = [
        (
            INFO,
            f"{name}: {len(interval.targets)} in-between(s) on frame(s) {frames_text(interval.targets)} "
            f"({method_label}{replaced})",
        )
    ]
    if interval.skipped:
        reports.append((WARNING, f"{name}: frame(s) {frames_text(interval.skipped)} already drawn: left untouched"))
    elif interval.occupied:
        reports.append((INFO, f"{name}: frame(s) {frames_text(interval.occupied)} between the keys left untouched"))
    for level in (WARNING, INFO):
        texts = [text for lvl, text in messages if (lvl == INFO) == (level == INFO)]
        if texts:
            more = len(texts) - MESSAGES_PER_REPORT
            shown = "; ".join(texts[:MESSAGES_PER_REPORT]) + (f"; and {more} more" if more > 0 else "")
            reports.append((level, f"{name}: {shown}"))
    return reports


def nothing_to_do(problems):
    """The cancel text when no interval could be in-betweened (``problems``: report texts)."""
    return "Nothing to in-between: " + "; ".join(problems)


def write_failed(exc):
    return f"Writing the in-betweens failed, nothing was changed: {exc}"


def summary(frames, layers, warnings):
    """The run's last report (the one the status bar shows): a warning when anything warned."""
    text = f"{_NAME}: {frames} frame(s) on {layers} layer(s)"
    if warnings:
        return WARNING, f"{text}, {warnings} warning(s): see the Info editor"
    return INFO, text
