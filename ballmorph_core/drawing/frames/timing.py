"""Timing: which frames get in-betweens, and where in the morph each one sits (t in [0, 1]).

Three ways to time an interval, applied in this order:

- easing (:func:`ease`) maps each frame's fraction of the interval to a morph time. The types
  and modes match Blender's Grease Pencil interpolation (types 'linear', 'sine', 'quad',
  'cubic', 'quart', 'quint', 'expo', 'circ', 'back', 'bounce', 'elastic'; modes 'ease-in',
  'ease-out', 'ease-in-out', 'auto'; Blender's ids such as 'EASE_IN' are accepted too), using
  Robert Penner's equations as Blender does;
- or a timing chart (:func:`parse_timing_chart`) gives the morph times outright, one in-between
  per fraction, on frames spread evenly between the keys (:func:`frame_times`), not eased;
- then favoring (:func:`apply_favor`) pulls every time toward one key.
"""

import re

import numpy as np

from ...errors import InvalidCurveError
from ...options import EASING_MODES, EASING_TYPES, check_option

__all__ = ["ease", "frame_times", "apply_favor", "parse_timing_chart", "FAVOR_ODDS"]

#: Favor 1 multiplies the odds t / (1 - t) of every morph time by this (favor -1 divides them):
#: the middle in-between moves to 3/4 (or 1/4) of the way, the animator's "favor" mark.
FAVOR_ODDS = 3.0
# Spaces, commas, or both, between a timing chart's fractions.
_CHART_SEPARATORS = re.compile(r"[\s,]+")

# 'auto' follows Blender: ease in for the "dynamic" types, ease out for back/bounce/elastic.
_AUTO_OUT = ("back", "bounce", "elastic")


def _bounce_out(x):
    n1, d1 = 7.5625, 2.75
    return np.select(
        [x < 1 / d1, x < 2 / d1, x < 2.5 / d1],
        [n1 * x * x, n1 * (x - 1.5 / d1) ** 2 + 0.75, n1 * (x - 2.25 / d1) ** 2 + 0.9375],
        n1 * (x - 2.625 / d1) ** 2 + 0.984375,
    )


def _ease_in(kind, x):
    if kind == "sine":
        return 1 - np.cos(x * np.pi / 2)
    if kind in ("quad", "cubic", "quart", "quint"):
        return x ** (2 + ("quad", "cubic", "quart", "quint").index(kind))
    if kind == "expo":
        return np.where(x <= 0, 0.0, 2.0 ** (10 * x - 10))
    if kind == "circ":
        return 1 - np.sqrt(np.clip(1 - x * x, 0, 1))
    if kind == "back":
        c1 = 1.70158
        return (c1 + 1) * x**3 - c1 * x**2
    if kind == "bounce":
        return 1 - _bounce_out(1 - x)
    if kind == "elastic":
        c4 = 2 * np.pi / 3
        return np.where((x <= 0) | (x >= 1), x, -(2.0 ** (10 * x - 10)) * np.sin((x * 10 - 10.75) * c4))
    return x


def ease(x, kind="linear", mode="auto"):
    """Map frame fractions to morph times.

    Parameters
    ----------
    x : array_like
        Fractions of the key interval, in [0, 1].
    kind : str
        One of :data:`EASING_TYPES`.
    mode : str
        One of :data:`EASING_MODES`.

    Returns
    -------
    ndarray
        Same shape as ``x``; 0 maps to 0 and 1 to 1 (BACK and ELASTIC may overshoot between).

    Examples
    --------
    >>> ease([0.0, 0.5, 1.0], "quad", "ease-in").tolist()
    [0.0, 0.25, 1.0]
    >>> ease([0.25], "quad", "ease-in-out").tolist()
    [0.125]
    """
    kind = check_option("kind", kind, EASING_TYPES)
    mode = check_option("mode", mode, EASING_MODES)
    x = np.clip(np.asarray(x, dtype=np.float64), 0.0, 1.0)
    if kind == "linear":
        return x
    if mode == "auto":
        mode = "ease-out" if kind in _AUTO_OUT else "ease-in"
    if mode == "ease-in":
        return _ease_in(kind, x)
    if mode == "ease-out":
        return 1 - _ease_in(kind, 1 - x)
    return np.where(x < 0.5, _ease_in(kind, 2 * x) / 2, 1 - _ease_in(kind, 2 - 2 * x) / 2)


def frame_times(frame_a, frame_b, count=None):
    """In-between frame numbers strictly between two keys, and their fractions.

    Parameters
    ----------
    frame_a, frame_b : int
        The two keyframes, ``frame_a < frame_b``.
    count : int, optional
        Number of in-betweens; default every frame between the keys. Fewer are spread evenly
        (rounded to whole frames, never on a key, no duplicates).

    Returns
    -------
    frames : ndarray of int, shape (T,)
    fractions : ndarray of float, shape (T,)
        ``(frame - frame_a) / (frame_b - frame_a)``.

    Examples
    --------
    >>> frame_times(1, 5)[0].tolist()
    [2, 3, 4]
    >>> frame_times(1, 13, count=3)[0].tolist()
    [4, 7, 10]
    """
    gap = int(frame_b) - int(frame_a)
    if gap < 2:
        return np.zeros(0, dtype=np.int64), np.zeros(0)
    available = gap - 1
    count = available if count is None or count <= 0 else min(int(count), available)
    frames = np.unique(np.round(frame_a + gap * np.arange(1, count + 1) / (count + 1)).astype(np.int64))
    frames = frames[(frames > frame_a) & (frames < frame_b)]
    return frames, (frames - frame_a) / gap


def apply_favor(times, favor):
    """Pull morph times toward the first key (``favor < 0``) or the second (``favor > 0``).

    The warp multiplies the odds of each time by ``k = FAVOR_ODDS ** favor``::

        t' = k t / (k t + 1 - t)

    It is smooth and strictly increasing on [0, 1], keeps 0 and 1 fixed, is the identity at
    ``favor = 0``, and ``favor`` and ``-favor`` mirror each other (``t'(1 - t, -f) = 1 - t'(t, f)``).
    At ``favor = 1`` the middle (t = 0.5) moves to 0.75, at ``favor = -1`` to 0.25.

    Parameters
    ----------
    times : array_like, shape (T,)
        Morph times, after easing. Times outside [0, 1] (the overshoot of 'back' and 'elastic'
        easing) are clamped first, as the morph clamps them.
    favor : float
        In [-1, 1].

    Returns
    -------
    ndarray, shape (T,)

    Raises
    ------
    InvalidCurveError
        (a ``ValueError``) when ``favor`` is not a number in [-1, 1].

    Examples
    --------
    >>> apply_favor([0.0, 0.5, 1.0], 1.0).tolist()
    [0.0, 0.75, 1.0]
    >>> apply_favor([0.5], -1.0).tolist()
    [0.25]
    >>> apply_favor([0.2, 0.7], 0.0).tolist()
    [0.2, 0.7]
    """
    try:
        favor = float(favor)
    except (TypeError, ValueError):
        raise InvalidCurveError(f"favor must be a number in [-1, 1], got {favor!r}") from None
    if not -1.0 <= favor <= 1.0:
        raise InvalidCurveError(f"favor must be a number in [-1, 1], got {favor!r}")
    t = np.clip(np.asarray(times, dtype=np.float64), 0.0, 1.0)
    if favor == 0.0:
        return t
    k = FAVOR_ODDS**favor
    return k * t / (k * t + (1.0 - t))  # the denominator is at least min(k, 1) > 0 on [0, 1]


def parse_timing_chart(text, room=None):
    """The fractions of a timing chart, checked: the one reader of the ``timing_chart`` option.

    Parameters
    ----------
    text : str
        Fractions of the morph in (0, 1), strictly ascending, separated by spaces and/or commas,
        e.g. ``"0.1 0.3 0.6 0.9"``. Empty (or blank): no chart.
    room : int, optional
        Frames between the two keys of the interval the chart is for: a chart with more
        fractions than that does not fit (each fraction gets a frame of its own).

    Returns
    -------
    tuple of float
        The fractions, in order (empty for an empty chart). In-between ``i`` of ``n`` goes on
        frame ``round(first + (i + 1) (last - first) / (n + 1))`` (:func:`frame_times` with
        ``count = n``) at morph time ``fractions[i]``.

    Raises
    ------
    InvalidCurveError
        (a ``ValueError``) saying what is wrong: an entry that is not a number, a fraction not
        strictly between 0 and 1, fractions that do not rise, or more fractions than ``room``.

    Examples
    --------
    >>> parse_timing_chart("0.1 0.3, 0.6,0.9")
    (0.1, 0.3, 0.6, 0.9)
    >>> parse_timing_chart("  ")
    ()
    >>> parse_timing_chart("0.5 0.4")
    Traceback (most recent call last):
    ...
    ballmorph_core.errors.InvalidCurveError: timing_chart: 0.4 comes after 0.5 (the fractions must rise)
    """
    if not isinstance(text, str):
        raise InvalidCurveError(f"timing_chart: expected a string of fractions, got {type(text).__name__}")
    words = [word for word in _CHART_SEPARATORS.split(text.strip()) if word]
    fractions = []
    for word in words:
        try:
            value = float(word)
        except ValueError:
            raise InvalidCurveError(f"timing_chart: {word!r} is not a number") from None
        if not 0.0 < value < 1.0:  # also refuses nan and inf
            raise InvalidCurveError(f"timing_chart: {word} is not between 0 and 1 (both keys excluded)")
        if fractions and value <= fractions[-1]:
            raise InvalidCurveError(f"timing_chart: {word} comes after {fractions[-1]!r} (the fractions must rise)")
        fractions.append(value)
    if room is not None and len(fractions) > room:
        raise InvalidCurveError(
            f"timing_chart: {len(fractions)} fractions but only {max(int(room), 0)} frame(s) between the keys "
            "(one in-between per fraction)"
        )
    return tuple(fractions)
