"""The path preview: where a few points of every stroke pair travel between two keys.

Like the paper's figures, a preview shows the trajectories of some samples of each stroke pair
of an :class:`~.plan.InbetweenPlan`, taken from the plan's own in-betweens (so they are the
paths the written frames follow), in the same 3D space as the in-betweens. The Blender add-on
draws them in the 3D viewport (one colour per pair, :func:`pair_colors`); tools draw them with
matplotlib. Strokes without a partner travel nowhere and have no trajectory.
"""

from dataclasses import dataclass

import numpy as np

from ...errors import InvalidCurveError
from ...options import check_positive

__all__ = ["PREVIEW_POINTS", "PREVIEW_TIMES", "PathPreview", "path_preview", "pair_colors"]

#: Trajectories shown per stroke pair, at most (evenly spaced along the stroke).
PREVIEW_POINTS = 8

#: Times each trajectory is sampled at, evenly over [0, 1]: enough for arcs to look smooth.
PREVIEW_TIMES = 17

# Hue step between consecutive pairs' colours: the golden ratio's fraction, so neighbouring
# pairs differ a lot and no two of the first dozens look alike.
_HUE_STEP = 0.6180339887498949


@dataclass
class PathPreview:
    """Trajectories of some samples of every stroke pair between two keys.

    Attributes
    ----------
    points : ndarray, shape (L, T, 3)
        Trajectory ``l`` is the polyline ``points[l]``: from the first key (``points[l, 0]``) to
        the second (``points[l, -1]``).
    pair : ndarray of int, shape (L,)
        The stroke pair each trajectory belongs to: an index into the plan's pairs
        (``plan.strokes``), for colouring. Trajectories of a pair are consecutive.
    times : ndarray, shape (T,)
        The morph time of each trajectory point.
    strokes : ndarray of int, shape (C, 2)
        The strokes of the first and second key of each pair (as numbered in the keys).
    """

    points: np.ndarray
    pair: np.ndarray
    times: np.ndarray
    strokes: np.ndarray

    def __len__(self):
        return len(self.points)

    def transformed(self, matrix):
        """The preview with every point moved by an affine transform.

        Parameters
        ----------
        matrix : array_like, shape (4, 4)
            A homogeneous transform (for example Blender's object-to-world matrix).

        Returns
        -------
        PathPreview
        """
        matrix = np.asarray(matrix, dtype=np.float64)
        points = self.points @ matrix[:3, :3].T + matrix[:3, 3]
        return PathPreview(points, self.pair, self.times, self.strokes)

    def segments(self):
        """The trajectories as one list of line segments (what a GPU 'LINES' batch draws).

        Returns
        -------
        vertices : ndarray, shape (L * T, 3)
            Every trajectory's points, trajectory after trajectory.
        indices : ndarray of int, shape (L * (T - 1), 2)
            The two vertices of each segment.
        owner : ndarray of int, shape (L * T,)
            The trajectory of each vertex.

        Examples
        --------
        >>> preview = PathPreview(np.zeros((2, 3, 3)), np.array([0, 1]), np.linspace(0, 1, 3), np.zeros((2, 2)))
        >>> preview.segments()[1].tolist()
        [[0, 1], [1, 2], [3, 4], [4, 5]]
        """
        count, steps = self.points.shape[:2]
        first = (np.arange(count)[:, None] * steps + np.arange(max(steps - 1, 0))).reshape(-1)
        owner = np.repeat(np.arange(count), steps)
        return self.points.reshape(-1, 3), np.c_[first, first + 1].astype(np.int64), owner


def path_preview(plan, points=PREVIEW_POINTS, times=PREVIEW_TIMES, correction=None):
    """The trajectories of a few samples of every stroke pair of a plan.

    Parameters
    ----------
    plan : InbetweenPlan
        From :func:`~ballmorph_core.plan_inbetween`.
    points : int
        Trajectories per pair, at most: samples evenly spaced along the stroke (by arc length on
        the first key, or on the second where the first has none; a loop's around the loop, an
        open stroke's from end to end). A pair with fewer samples shows all of them.
    times : int
        Points per trajectory (at least 2), at evenly spaced morph times from 0 to 1.
    correction : arcs.PathCorrection, optional
        The plan's paths joined smoothly to its neighbours' (as ``plan.evaluate`` takes it).

    Returns
    -------
    PathPreview
        Its points are the plan's own in-betweens: ``points[:, i]`` are samples of
        ``plan.evaluate([t_i])``, in the same space.

    Raises
    ------
    InvalidCurveError
        (a ``ValueError``) when ``points`` is not a positive whole number or ``times`` is below 2.

    Examples
    --------
    >>> import ballmorph_core as bm
    >>> t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    >>> ring = np.c_[np.cos(t), np.sin(t)]
    >>> a, b = (bm.StrokeSet.from_strokes([r * ring], cyclic=[True]) for r in (1.0, 2.0))
    >>> preview = path_preview(bm.plan_inbetween(a, b, carrier="none"), points=4, times=5)
    >>> preview.points.shape, preview.pair.tolist()
    ((4, 5, 3), [0, 0, 0, 0])
    >>> np.round(np.linalg.norm(preview.points[0], axis=1), 6).tolist()  # straight out, radially
    [1.0, 1.25, 1.5, 1.75, 2.0]
    """
    points = _count("points", points, 1)
    times = np.linspace(0.0, 1.0, _count("times", times, 2))
    pairs = len(plan.strokes)
    strokes = np.array([(a.index, b.index) for a, b, _ in plan.strokes], dtype=np.int64).reshape(-1, 2)
    if pairs == 0:
        return PathPreview(np.zeros((0, len(times), 3)), np.zeros(0, dtype=np.int64), times, strokes)
    frames = plan.evaluate(times, correction).frames
    # The pairs come first in every in-between, with the same samples at every time; the strokes
    # without a partner follow them.
    offsets = frames[0].offsets[: pairs + 1]
    cyclic = frames[0].cyclic[:pairs]
    track = np.stack([f.positions[: offsets[-1]] for f in frames])  # (T, K, 3)
    picked = _spread(track[0], track[-1], offsets, cyclic, points)
    pair = np.searchsorted(offsets, picked, side="right") - 1
    return PathPreview(np.ascontiguousarray(track[:, picked].transpose(1, 0, 2)), pair, times, strokes)


def _count(name, value, least):
    """A whole number >= ``least``, or an InvalidCurveError (a ValueError) naming the argument."""
    number = check_positive(name, value)
    if number != int(number) or number < least:
        raise InvalidCurveError(f"{name}: must be a whole number of at least {least}, got {value!r}")
    return int(number)


def _along(positions, offsets, cyclic):
    """Arc-length fraction of every sample along its stroke, and each stroke's length.

    Parameters
    ----------
    positions : ndarray, shape (K, 3)
    offsets : ndarray of int, shape (C + 1,)
    cyclic : ndarray of bool, shape (C,)

    Returns
    -------
    fraction : ndarray, shape (K,)
        In [0, 1] (an open stroke's last sample is at 1; a loop's closing edge counts);
        NaN on strokes without length.
    length : ndarray, shape (C,)
    """
    sizes = np.diff(offsets)
    owner = np.repeat(np.arange(len(sizes)), sizes)
    step = np.zeros(len(positions))
    step[1:] = np.linalg.norm(np.diff(positions, axis=0), axis=1)
    step[offsets[:-1][sizes > 0]] = 0.0  # no edge between two strokes
    s = np.cumsum(step)
    start = s[offsets[:-1][sizes > 0]]
    s -= np.repeat(start, sizes[sizes > 0])
    last = np.zeros(len(sizes))
    last[sizes > 0] = s[offsets[1:][sizes > 0] - 1]
    closing = np.zeros(len(sizes))
    loops = cyclic & (sizes > 1)
    closing[loops] = np.linalg.norm(positions[offsets[1:][loops] - 1] - positions[offsets[:-1][loops]], axis=1)
    length = last + closing
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = s / length[owner]
    return np.where(length[owner] > 0, fraction, np.nan), length


def _spread(first, last, offsets, cyclic, points):
    """Up to ``points`` samples per stroke, evenly spaced along it (sorted global indices).

    Spaced by arc length on ``first`` (K, 3), else on ``last``, else by sample index.
    """
    sizes = np.diff(offsets)
    owner = np.repeat(np.arange(len(sizes)), sizes)
    fraction, length = _along(first, offsets, cyclic)
    fraction_last, length_last = _along(last, offsets, cyclic)
    local = np.arange(len(owner)) - offsets[owner]
    by_index = local / np.maximum(sizes - np.where(cyclic, 0, 1), 1)[owner]
    fraction = np.where((length > 0)[owner], fraction, np.where((length_last > 0)[owner], fraction_last, by_index))
    # Targets: m evenly spaced fractions per stroke (a loop's last one short of closing it).
    m = np.minimum(sizes, points)
    target_owner = np.repeat(np.arange(len(sizes)), m)
    j = np.arange(int(m.sum())) - np.repeat(np.cumsum(m) - m, m)
    span = np.where(cyclic, m, m - 1)[target_owner]
    target = np.divide(j, span, out=np.zeros(len(j)), where=span > 0)
    # Stroke c's fractions lie in [2c, 2c + 1]: one search for the nearest sample of every target.
    key, wanted = 2.0 * owner + fraction, 2.0 * target_owner + target
    above = np.clip(np.searchsorted(key, wanted), offsets[target_owner], offsets[target_owner + 1] - 1)
    below = np.maximum(above - 1, offsets[target_owner])
    nearer = np.where(np.abs(key[below] - wanted) <= np.abs(key[above] - wanted), below, above)
    return np.unique(nearer)


def pair_colors(pair, alpha=1.0):
    """A distinct, bright colour per stroke pair (the same pair always gets the same colour).

    Parameters
    ----------
    pair : array_like of int, shape (L,)
        Pair indices (:attr:`PathPreview.pair`).
    alpha : float
        Opacity of every colour.

    Returns
    -------
    ndarray, shape (L, 4)
        RGBA in [0, 1].

    Examples
    --------
    >>> pair_colors([0, 1, 0]).round(2).tolist()
    [[0.95, 0.33, 0.33, 1.0], [0.33, 0.51, 0.95, 1.0], [0.95, 0.33, 0.33, 1.0]]
    """
    hue = (np.asarray(pair, dtype=np.float64).reshape(-1) * _HUE_STEP) % 1.0
    # HSV -> RGB with saturation 0.65 and value 0.95, vectorised over the hues.
    value, saturation = 0.95, 0.65
    k = (np.array([5.0, 3.0, 1.0]) + hue[:, None] * 6.0) % 6.0
    rgb = value - value * saturation * np.clip(np.minimum(k, 4.0 - k), 0.0, 1.0)
    return np.c_[rgb, np.full(len(hue), float(alpha))]
