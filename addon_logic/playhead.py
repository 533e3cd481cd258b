"""One in-between on the current frame (the ``current_frame_only`` option), as Blender's Interpolate.

No bpy here (plain CPython imports it: ``tests/addon``). Interpolate (Ctrl+E) puts one in-between
on the current frame, at the fraction that frame sits between the keys around it. Here the same:
:func:`around` is the pairing rule (the keys around the current frame, whatever is selected),
and :func:`at_frame` narrows each interval to that one frame, its fraction
``(frame - frame_a) / (frame_b - frame_a)`` eased as the options ask. The add-on's other
in-betweens between the keys stay; a timing chart does not apply (it spreads its own frames).
"""

from dataclasses import replace

from . import pairing, reports

__all__ = ["around", "at_frame"]


def around(current_frame):
    """The pairing rule of ``current_frame_only``: the keys around ``current_frame``.

    Examples
    --------
    >>> rule = around(3)
    >>> rule(pairing.LayerKeys("Ink", keys=(1, 9, 17), selected=(9, 17)))
    ([(1, 9)], [])
    >>> rule(pairing.LayerKeys("Ink", keys=(1, 9)))[0]
    [(1, 9)]
    >>> around(9)(pairing.LayerKeys("Ink", keys=(1, 9, 17)))
    ([], ["layer 'Ink': the current frame 9 is a keyframe: go to a frame between two keys to in-between it"])
    """

    def rule(layer):
        if current_frame in layer.keys:
            return [], [reports.on_a_key(layer.name, current_frame)]
        return pairing.selected_or_current(replace(layer, selected=()), current_frame)

    return rule


def at_frame(interval, frame):
    """``interval`` (written on every frame between its keys) narrowed to ``frame`` alone.

    Parameters
    ----------
    interval : pairing.Interval
        From :func:`.pairing.intervals` with a frame count of 0 (every frame) and no chart.
    frame : int
        The current frame, between the interval's keys.

    Returns
    -------
    pairing.Interval
        Targets ``[frame]`` at fraction ``(frame - frame_a) / (frame_b - frame_a)``; it replaces
        only the add-on's own in-between on that frame, if any.

    Examples
    --------
    >>> [whole] = pairing.intervals(pairing.LayerKeys("Ink", keys=(1, 9), made=(3, 5)), [(1, 9)], 0)
    >>> one = at_frame(whole, 3)
    >>> one.targets.tolist(), one.fractions.tolist(), one.replace
    ([3], [0.25], [3])
    """
    keep = interval.targets == frame
    return replace(
        interval,
        targets=interval.targets[keep],
        fractions=interval.fractions[keep],
        replace=[n for n in interval.replace if n == frame],
        skipped=[],
        chart=None,
        chart_times=None,
    )
