"""Arcs through keys: in-betweens of consecutive intervals joined smoothly (C1) at inner keys.

Each interval between two keys is planned on its own (:func:`~.plan.plan_inbetween`), so over
three or more keys every sample travels on one path per interval, with a corner at each inner
key (a ball keyed on an arc runs on its chords). Here each interval's sample paths get a cubic
Hermite term that vanishes at both of its keys (the keys stay exactly the keys) and whose
derivatives there replace the path's own:

    p(s) = path(s) + h10(s) (D_start - path'(0)) + h11(s) (D_end - path'(1)),
    h10(s) = s^3 - 2 s^2 + s,  h11(s) = s^3 - s^2,

with ``s`` the interval's morph time in [0, 1] and ``D`` the wanted derivatives (per unit of
``s``: a velocity per frame times the interval's length in frames). At an inner key the
velocity of a point is that of the parabola through its three positions (previous key, this
key, next key, at their frames: the Bessel tangent, Catmull-Rom's on evenly spaced keys), the
positions taken along the intervals' own correspondences. The velocity is the same on both
sides of the key, so the paths join C1. At an end of a chain (the first or last key, or a key
that keeps its corner) an interval whose other key is smooth takes its parabola's velocity
there (``2 chord - velocity at the smooth key``), so a chain of three keys runs on one parabola
per sample; an interval between two corners is left as it is.

A sample of one interval is matched to the sample of the next nearest to it along the same key
stroke at their shared key (the two plans sample the key differently; a sort, however long the
strokes), offset by their distance: exact for strokes that translate, first order in the
sample spacing otherwise.
The velocities are linear in the key positions, so a stroke that moves, turns and grows as a
whole (a similarity) keeps its shape, and its position, turn and scale join C1 too.

Timing (easing, favor, charts) still applies per interval: the correction is a function of the
morph time, so a velocity per frame is continuous across a key when both intervals are timed
linearly there.
"""

from dataclasses import dataclass

import numpy as np

from ...options import KEY_MOTIONS, check_option, check_positive

__all__ = [
    "DERIVATIVE_STEP",
    "IntervalEnds",
    "PathCorrection",
    "chain_corrections",
    "hermite_bumps",
    "interval_ends",
    "key_places",
    "key_velocities",
    "smooth_chain",
]

#: Morph-time step of the one-sided second-order differences that measure a path's derivative
#: at its keys (paths are smooth within an interval: the truncation error is ~step^2 of the
#: path's curvature).
DERIVATIVE_STEP = 1e-3

#: Query x sample pairs measured at once when matching samples across a key (bounds memory).
NEAREST_BUDGET = 2_000_000

_TIMES = np.array([0.0, DERIVATIVE_STEP, 2 * DERIVATIVE_STEP, 1 - 2 * DERIVATIVE_STEP, 1 - DERIVATIVE_STEP, 1.0])


def hermite_bumps(times):
    """The two cubic Hermite basis functions that vanish at both ends.

    Parameters
    ----------
    times : array_like, shape (T,)
        Morph times in [0, 1].

    Returns
    -------
    ndarray, shape (T, 2)
        ``h10(s) = s^3 - 2 s^2 + s`` (slope 1 at 0, 0 at 1) and ``h11(s) = s^3 - s^2`` (slope 0
        at 0, 1 at 1); both exactly 0 at s = 0 and s = 1.

    Examples
    --------
    >>> hermite_bumps([0.0, 0.5, 1.0]).tolist()
    [[0.0, 0.0], [0.125, -0.125], [0.0, 0.0]]
    """
    s = np.asarray(times, dtype=np.float64).reshape(-1)
    s2 = s * s
    return np.stack([s2 * s - 2.0 * s2 + s, s2 * s - s2], axis=1)


@dataclass
class IntervalEnds:
    """One interval's sample paths at its keys, in 3D.

    Attributes
    ----------
    start, end : ndarray, shape (K, 3)
        Every sample at morph time 0 (on the first key) and 1 (on the second).
    d_start, d_end : ndarray, shape (K, 3)
        The paths' derivatives there, per unit of morph time.
    frames : float
        The interval's length in frames (> 0).
    leaves, reaches : ndarray, shape (K,), optional
        Where each sample leaves the first key and reaches the second (:func:`key_places`):
        samples are matched across a key along their key stroke; None: by their positions.
    """

    start: np.ndarray
    end: np.ndarray
    d_start: np.ndarray
    d_end: np.ndarray
    frames: float
    leaves: np.ndarray = None
    reaches: np.ndarray = None

    @property
    def chord(self):
        """Each sample's mean velocity over the interval, per frame, shape (K, 3)."""
        return (self.end - self.start) / self.frames


def key_places(strokes, fractions):
    """One number per sample that orders samples along the key strokes: ``4 stroke + fraction``.

    Parameters
    ----------
    strokes : ndarray of int, shape (K,)
        Each sample's key stroke.
    fractions : ndarray, shape (K,)
        Its arc-length fraction along the stroke, in [0, 1].

    Returns
    -------
    ndarray, shape (K,)
        Strokes lie 4 apart, so a place's nearest is on its own stroke whenever that stroke has
        one (within 1), and never nearer than 3 on another.

    Examples
    --------
    >>> key_places(np.array([0, 2]), np.array([0.25, 1.0])).tolist()
    [0.25, 9.0]
    """
    return 4.0 * np.asarray(strokes, dtype=np.float64) + np.asarray(fractions, dtype=np.float64)


def interval_ends(samples, frames, sources=None):
    """The :class:`IntervalEnds` of an interval, from its sample paths.

    Parameters
    ----------
    samples : callable
        ``samples(times) -> ndarray, shape (T, K, 3)``: every sample of the interval's plan at
        morph times ``times`` (the same samples at every time), e.g.
        :meth:`InbetweenPlan.samples <.plan.InbetweenPlan.samples>`.
    frames : float
        The interval's length in frames.
    sources : (stroke_a, u_a, stroke_b, u_b), optional
        Where the samples leave and reach the keys, each shape (K,) (e.g.
        :meth:`InbetweenPlan.sample_sources <.plan.InbetweenPlan.sample_sources>`).

    Returns
    -------
    IntervalEnds or None
        None when a path is not finite near a key (the interval then keeps its corners).
    """
    f = np.asarray(samples(_TIMES), dtype=np.float64)
    if not np.isfinite(f.sum()):
        return None
    h = DERIVATIVE_STEP
    d_start = (-3.0 * f[0] + 4.0 * f[1] - f[2]) / (2.0 * h)
    d_end = (3.0 * f[5] - 4.0 * f[4] + f[3]) / (2.0 * h)
    places = (None, None) if sources is None else (key_places(*sources[:2]), key_places(*sources[2:]))
    return IntervalEnds(f[0], f[5], d_start, d_end, float(frames), *places)


@dataclass
class PathCorrection:
    """The Hermite terms added to one interval's sample paths (zero at both keys).

    Attributes
    ----------
    start, end : ndarray, shape (K, 3)
        Wanted minus own derivative of every sample's path at morph time 0 and 1.
    """

    start: np.ndarray
    end: np.ndarray

    def offsets(self, times):
        """What each sample moves by at ``times`` (T,): shape (T, K, 3), exactly 0 at 0 and 1.

        Examples
        --------
        >>> c = PathCorrection(np.ones((1, 3)), np.zeros((1, 3)))
        >>> c.offsets([0.0, 0.5, 1.0])[:, 0, 0].tolist()
        [0.0, 0.125, 0.0]
        """
        h = hermite_bumps(times)
        return h[:, 0, None, None] * self.start + h[:, 1, None, None] * self.end


def _nearest_any(points, among):
    """Index of the nearest point of ``among`` (M, 3), M > 0, to each of ``points`` (K, 3): (K,).

    By ``|b|^2 - 2 a.b`` (one matrix product per chunk), about the points' mean so that the
    squares stay small next to the distances."""
    centre = among.mean(axis=0)
    among = among - centre
    square = np.einsum("ij,ij->i", among, among)
    out = np.empty(len(points), dtype=np.int64)
    step = max(1, NEAREST_BUDGET // len(among))
    for lo in range(0, len(points), step):
        chunk = points[lo : lo + step] - centre
        out[lo : lo + step] = np.argmin(square - 2.0 * (chunk @ among.T), axis=1)
    return out


def _nearest(points, among, places=None, among_places=None):
    """Index of the sample of ``among`` (M, 3), M > 0, matching each of ``points`` (K, 3): shape (K,).

    With places (:func:`key_places`, shapes (K,) and (M,)) the nearest place along the same key
    stroke (one sort), -1 for a point whose stroke has no sample in ``among``; without places,
    the nearest by position. (A loop's seam is not wrapped: a sample beside it may take one a
    sample spacing further, which the offset by their distance makes up for.)"""
    if places is None or among_places is None:
        return _nearest_any(points, among)
    order = np.argsort(among_places, kind="stable")
    ranked = among_places[order]
    right = np.clip(np.searchsorted(ranked, places), 0, len(ranked) - 1)
    left = np.maximum(right - 1, 0)
    pick = np.where(np.abs(places - ranked[left]) <= np.abs(ranked[right] - places), left, right)
    out = order[pick]
    out[np.abs(ranked[pick] - places) > 1.0] = -1  # the nearest place is on another stroke
    return out


def _key_velocity(before, here, after, frames_before, frames_after):
    """The parabola's velocity at ``here`` through ``before``, ``here``, ``after`` (each (K, 3))
    placed ``frames_before`` before and ``frames_after`` after it: per frame, shape (K, 3)."""
    chord_before = (here - before) / frames_before
    chord_after = (after - here) / frames_after
    return (frames_after * chord_before + frames_before * chord_after) / (frames_before + frames_after)


def key_velocities(arriving, leaving):
    """Every sample's velocity at the key two intervals share, on both sides.

    Parameters
    ----------
    arriving, leaving : IntervalEnds
        The interval that ends at the key (its ``end``) and the one that starts there.

    Returns
    -------
    at_end : ndarray, shape (K_arriving, 3)
        Velocities per frame of the arriving interval's samples at its end.
    at_start : ndarray, shape (K_leaving, 3)
        Those of the leaving interval's samples at its start.

    A sample whose key stroke has no sample on the other side (its stroke has no partner
    there) keeps its own path's velocity.
    """
    x, y = arriving.end, leaving.start
    k = _nearest(x, y, arriving.reaches, leaving.leaves)
    after = leaving.end[k] + (x - y[k])
    at_end = _key_velocity(arriving.start, x, after, arriving.frames, leaving.frames)
    at_end[k < 0] = arriving.d_end[k < 0] / arriving.frames
    n = _nearest(y, x, leaving.leaves, arriving.reaches)
    before = arriving.start[n] + (y - x[n])
    at_start = _key_velocity(before, y, leaving.end, arriving.frames, leaving.frames)
    at_start[n < 0] = leaving.d_start[n < 0] / leaving.frames
    return at_end, at_start


def smooth_chain(ends, smooth):
    """The corrections that join a chain of consecutive intervals smoothly at its inner keys.

    Parameters
    ----------
    ends : list of IntervalEnds or None
        The intervals in order, interval ``i`` ending on the key interval ``i + 1`` starts
        from; None for an interval that cannot be corrected (it keeps its corners).
    smooth : sequence of bool, length ``len(ends) - 1``
        Whether each inner key is passed through smoothly (False: it keeps its corner).

    Returns
    -------
    list of PathCorrection or None
        One per interval; None for an interval left as it is (both its keys corners).

    Examples
    --------
    Three points on a parabola, keyed 6 frames apart, one sample each: the chain runs on it.

    >>> p = lambda x: np.array([[x, 0.0, x * x]])
    >>> step = lambda a, b: IntervalEnds(p(a), p(b), p(b) - p(a), p(b) - p(a), 6.0)
    >>> first, second = smooth_chain([step(-1, 0), step(0, 1)], [True])
    >>> first.start[0].tolist(), first.end[0].tolist()  # slopes -2 and 0 instead of -1 and -1
    ([0.0, 0.0, -1.0], [0.0, 0.0, 1.0])
    """
    n = len(ends)
    if len(smooth) != n - 1:
        raise ValueError(f"smooth: expected {n - 1} inner keys, got {len(smooth)}")
    # Wanted velocity per frame at each interval's start and end (None: its own path's).
    wanted = [[None, None] for _ in range(n)]
    for j, passes in enumerate(smooth):
        left, right = ends[j], ends[j + 1]
        # (A key with no paired sample on one side has nothing to pass through.)
        if passes and left is not None and right is not None and len(left.end) and len(right.start):
            wanted[j][1], wanted[j + 1][0] = key_velocities(left, right)
    out = []
    for e, (v_start, v_end) in zip(ends, wanted):
        if e is None or (v_start is None and v_end is None):
            out.append(None)
            continue
        # A corner beside a smooth key: the parabola's velocity there (2 chord - the other).
        if v_start is None:
            v_start = 2.0 * e.chord - v_end
        elif v_end is None:
            v_end = 2.0 * e.chord - v_start
        out.append(PathCorrection(e.frames * v_start - e.d_start, e.frames * v_end - e.d_end))
    return out


def chain_corrections(plans, lengths, smooth, key_motion="smooth"):
    """The corrections of a chain of consecutive intervals' plans (what the operator calls).

    Parameters
    ----------
    plans : list of InbetweenPlan or None
        The intervals in order, each ending on the key the next starts from (None: an interval
        not computed; its neighbours keep their corners there).
    lengths : sequence of float, length ``len(plans)``
        Each interval's length in frames (> 0).
    smooth : sequence of bool, length ``len(plans) - 1``
        Whether each inner key is passed through smoothly (False: it keeps its corner, e.g. a
        key the animator typed Extreme).
    key_motion : {'smooth', 'per-interval'}
        'per-interval' corrects nothing (each interval as if alone).

    Returns
    -------
    list of PathCorrection or None
        One per plan, for its :meth:`~.plan.InbetweenPlan.evaluate`; None leaves it as it is.

    Raises
    ------
    InvalidCurveError
        (a ``ValueError``) for an unknown ``key_motion``, or lengths that are not positive.
    """
    key_motion = check_option("key_motion", key_motion, KEY_MOTIONS)
    if len(lengths) != len(plans):
        raise ValueError(f"lengths: expected {len(plans)}, got {len(lengths)}")
    for length in lengths:
        check_positive("lengths", length)
    if key_motion == "per-interval" or len(plans) < 2:
        return [None] * len(plans)
    ends = [
        None if plan is None else interval_ends(plan.samples, length, plan.sample_sources())
        for plan, length in zip(plans, lengths)
    ]
    return smooth_chain(ends, smooth)
