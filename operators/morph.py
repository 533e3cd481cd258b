"""Compute the in-betweens of one key interval: read both keys, time them, call the core.

The times: the frames' fractions eased, or the interval's timing chart as it is; then favored.
After the morph, the stroke pairs that stray from their keys are found (:func:`.reports.strays`).

Nothing is written here: the service (:mod:`.service`) computes every interval first and writes
only when all of them are ready (see :mod:`.writer`).
"""

from dataclasses import dataclass, field, replace

import numpy as np

from ..addon_logic import reports
from ..addon_logic.report_data import Report, StrokeRef
from ..ballmorph_core import StrokeSet, apply_favor, ease, length_deviation
from . import grease_pencil
from .plans import PLANS

__all__ = ["IntervalKeys", "Morphed", "morph_interval", "plan_options", "read_keys", "corrected"]

# A layer transform whose 3x3 part has a smaller determinant cannot be inverted to write back.
_SINGULAR_DETERMINANT = 1e-12


@dataclass
class Morphed:
    """The in-betweens of one :class:`.pairing.Interval`, ready to write.

    Attributes
    ----------
    layer : bpy.types.GreasePencilLayer
        The layer to write them on.
    interval : pairing.Interval
    frames : list of StrokeSet
        One per ``interval.targets``, in layer space.
    messages : list of (level, text)
        For the animator (level INFO or WARNING).
    method : str
        The core method that made the frames.
    strays : list of reports.Stray
        The stroke pairs that stray from their keys, worst first.
    plan : ballmorph_core.InbetweenPlan
        The plan the frames were evaluated from, at ``times`` (the morph's fractions).
    keys : IntervalKeys
        The keys as the core received them.
    times : ndarray, shape (T,)
    """

    layer: object
    interval: object
    frames: list
    messages: list = field(default_factory=list)
    method: str = ""
    strays: list = field(default_factory=list)
    plan: object = None
    keys: object = None
    times: object = None


def _frame(layer, number):
    return next(frame for frame in layer.frames if frame.frame_number == number)


def _to_layer_space(strokes, matrix_inverse):
    if matrix_inverse is None:
        return strokes
    return strokes.replace_positions(strokes.positions @ matrix_inverse[:3, :3].T + matrix_inverse[:3, 3])


def _selection(key_a, key_b, messages):
    """Strokes to morph in each key, the first key's strokes to hold, for 'selected only', and the
    drawing's index of each stroke morphed in each key (None: all of them, in order)."""
    if not key_a.selected.any() or not key_b.selected.any():
        which = "first" if not key_a.selected.any() else "second"
        messages.append((reports.INFO, f"no stroke is selected in the {which} key: all strokes were in-betweened"))
        return key_a, key_b, None, (None, None)
    held = key_a.subset(np.flatnonzero(~key_a.selected))
    chosen = (np.flatnonzero(key_a.selected), np.flatnonzero(key_b.selected))
    return key_a.subset(chosen[0]), key_b.subset(chosen[1]), held, chosen


@dataclass
class IntervalKeys:
    """Both keys of an interval as the core receives them.

    Attributes
    ----------
    key_a, key_b : StrokeSet
        In the morph's space (the layer's transform applied); with 'selected only', just the
        selected strokes.
    held : StrokeSet or None
        The first key's strokes held unchanged ('selected only'), in the morph's space.
    to_layer : ndarray, shape (4, 4), or None
        Morph space -> layer space (None: the layer has no transform).
    messages : list of (level, text)
    chosen : (ndarray or None, ndarray or None)
        Per key, the drawing's index of each stroke the core receives ('selected only'); None:
        every stroke, in order.
    """

    key_a: StrokeSet
    key_b: StrokeSet
    held: object = None
    to_layer: object = None
    messages: list = field(default_factory=list)
    chosen: tuple = (None, None)

    def stroke_ref(self, interval, key, index):
        """The StrokeRef (key frame, number from 1 in the drawing) of the core's stroke ``index``
        of key ``key`` (0 the first, 1 the second)."""
        chosen = self.chosen[key]
        frame = (interval.frame_a, interval.frame_b)[key]
        return StrokeRef.of_index(frame, index if chosen is None else int(chosen[index]))


def read_keys(layer, interval, values):
    """Both keys of an interval, read and checked (the in-betweens and the path preview).

    Parameters
    ----------
    layer : bpy.types.GreasePencilLayer
    interval : pairing.Interval
        An interval of ``layer`` (only its two keys are read).
    values : dict
        The options' values (:func:`.options.values_of`).

    Returns
    -------
    IntervalKeys or None
        None when both keys have no strokes.

    Raises
    ------
    ValueError
        When the layer's transform is flat or a key has non-finite coordinates.
    """
    matrix = grease_pencil.layer_matrix(layer)
    identity = np.array_equal(matrix, np.eye(4))
    if not identity and abs(np.linalg.det(matrix[:3, :3])) < _SINGULAR_DETERMINANT:
        raise ValueError(reports.flat_transform(layer.name))
    to_morph, to_layer = (None, None) if identity else (matrix, np.linalg.inv(matrix))
    key_a = grease_pencil.read_strokes(_frame(layer, interval.frame_a).drawing, to_morph)
    key_b = grease_pencil.read_strokes(_frame(layer, interval.frame_b).drawing, to_morph)
    if len(key_a) == 0 and len(key_b) == 0:
        return None
    for number, key in ((interval.frame_a, key_a), (interval.frame_b, key_b)):
        if np.isfinite(key.positions.sum()):  # a finite sum: every coordinate is (one fast pass)
            continue
        bad = ~np.isfinite(key.positions).all(axis=1)
        if bad.any():
            strokes = np.unique(np.searchsorted(key.offsets, np.flatnonzero(bad), side="right") - 1)
            raise ValueError(reports.invalid_coordinates(number, strokes.tolist()))
    messages, held, chosen = [], None, (None, None)
    if values["selected_only"]:
        key_a, key_b, held, chosen = _selection(key_a, key_b, messages)
    return IntervalKeys(key_a, key_b, held, to_layer, messages, chosen)


def plan_options(values, method):
    """The keyword arguments of :func:`ballmorph_core.plan_inbetween` for these option values.

    This is the one place where the options reach the core's plan: an option added to
    :data:`.options.OPTIONS` for the morph is passed on here.
    """
    return {
        "method": method,
        "carrier": values["carrier"],
        "matching": values["matching"],
        "unmatched": values["unmatched"],
    }


def morph_interval(layer, interval, values, method):
    """In-betweens of one interval.

    Parameters
    ----------
    layer : bpy.types.GreasePencilLayer
    interval : pairing.Interval
        An interval of ``layer``.
    values : dict
        The options' values (:func:`.options.values_of`: the core's lowercase names).
    method : str
        The core method to use (``values['method']``, or the fallback morph).

    Returns
    -------
    Morphed or None
        None when both keys have no strokes.

    Raises
    ------
    ballmorph_core.BallMorphError, ValueError
        When the core cannot in-between these keys at all.
    """
    keys = read_keys(layer, interval, values)
    if keys is None:
        return None
    if interval.chart is None:
        times = ease(
            interval.fractions,
            values["easing_type"],
            values["easing"],
            back=values["back"],
            amplitude=values["amplitude"],
            period=values["period"],
            curve=values.get("custom_curve"),  # the scene's Custom curve, sampled (custom_curve.py)
        )
    else:  # a chart gives the morph's own fractions: not eased
        times = interval.chart_times
    times = apply_favor(times, values["favor"])
    # The times only enter at the evaluation: a redo with another frame count or easing reuses
    # the plan (matching, ball-maps, carriers) of the same keys and options.
    plan = PLANS.plan(keys.key_a, keys.key_b, **plan_options(values, method))
    item = Morphed(layer, interval, [], list(keys.messages), method, plan=plan, keys=keys, times=times)
    result = _evaluate(item)
    # Each message with the strokes it is about, in the drawing (for select_warned and the JSON).
    item.messages.extend(
        Report(m.level, m.text, strokes=tuple(keys.stroke_ref(interval, key, index) for key, index in m.strokes))
        for m in result.messages
    )
    return item


def _evaluate(item, correction=None):
    """Fill ``item``'s frames and strays from its plan (moved by ``correction``, see
    :func:`corrected`); the core's InbetweenResult."""
    keys, times = item.keys, item.times
    result = item.plan.evaluate(times, correction)
    deviation = length_deviation(keys.key_a, keys.key_b, result, times, PLANS.key_lengths(item.plan))
    found = reports.strays(result.pairs, item.method, deviation, times, item.interval.targets)
    item.strays = [_in_drawing(stray, keys) for stray in found]
    held = keys.held
    frames = [StrokeSet.concatenate([held, frame]) if held is not None else frame for frame in result.frames]
    item.frames = [_to_layer_space(frame, keys.to_layer) for frame in frames]
    return result


def _in_drawing(stray, keys):
    """``stray`` with the drawing's stroke indices ('selected only' morphs a subset)."""
    indices = tuple(
        index if index is None or chosen is None else int(chosen[index])
        for index, chosen in zip(stray.indices, keys.chosen)
    )
    return replace(stray, indices=indices)


def corrected(item, correction):
    """``item`` (a Morphed) evaluated again with its paths moved by ``correction`` (a
    :class:`ballmorph_core.PathCorrection`: the interval joined smoothly to its neighbours);
    its messages are kept. Nothing is changed if the evaluation fails."""
    again = Morphed(
        item.layer,
        item.interval,
        [],
        list(item.messages),
        item.method,
        plan=item.plan,
        keys=item.keys,
        times=item.times,
    )
    _evaluate(again, correction)
    return again
