"""Which hint numbers the hint operators give and take (no bpy: plain CPython tests it).

Hints live in a key drawing's INT point attribute ``ballmorph_hint``
(:data:`ballmorph_core.HINT`): 0 for none, ``k >= 1`` for hint ``k``, one point per number.
"""

import numpy as np

__all__ = ["free_numbers", "add_hints", "clear_hints"]


def free_numbers(values, count, start=1):
    """The ``count`` smallest hint numbers ``>= start`` no point uses yet (list of int).

    >>> free_numbers([0, 1, 3, 0], 3)
    [2, 4, 5]
    """
    used = set(np.asarray(values, dtype=np.int64).tolist())
    out, k = [], max(int(start), 1)
    while len(out) < count:
        if k not in used:
            out.append(k)
        k += 1
    return out


def add_hints(values, selected, chosen=0):
    """Hint numbers for the selected points.

    Parameters
    ----------
    values : ndarray of int, shape (N,)
        The drawing's hint attribute (zeros if it had none).
    selected : ndarray of bool, shape (N,)
    chosen : int
        0: each selected point (in drawing order) gets the next free number; ``k >= 1``: a single
        selected point gets ``k`` (any other point holding ``k`` loses it: one point per number).

    Returns
    -------
    values : ndarray of int, shape (N,)
        The new attribute.
    given : list of (int, int)
        ``(point, number)`` for every point that got a number.

    Raises
    ------
    ValueError
        Nothing selected, or a chosen number for several points, with what to do.
    """
    values = np.asarray(values, dtype=np.int64).copy()
    points = np.flatnonzero(selected)
    if not len(points):
        raise ValueError("select the point(s) to hint first (Edit Mode, point selection)")
    if chosen:
        if len(points) > 1:
            raise ValueError(f"hint {chosen} goes on one point: {len(points)} are selected")
        values[values == chosen] = 0
        numbers = [int(chosen)]
    else:
        values[points] = 0  # re-hinting a point gives it a new number
        numbers = free_numbers(values, len(points))
    values[points] = numbers
    return values, list(zip(points.tolist(), numbers))


def clear_hints(values, selected=None):
    """The attribute without the hints of the selected points (all points if ``selected`` is
    None): ``(values, cleared numbers)``."""
    values = np.asarray(values, dtype=np.int64).copy()
    where = np.ones(len(values), bool) if selected is None else np.asarray(selected, bool)
    cleared = sorted(set(values[where & (values > 0)].tolist()))
    values[where] = 0
    return values, cleared
