"""Timing: which frames get in-betweens, and where in the morph each one sits (t in [0, 1]).

Three ways to time an interval, applied in this order:

- easing (:func:`ease`) maps each frame's fraction of the interval to a morph time. The types
  and modes match Blender's Grease Pencil interpolation (types 'linear', 'custom', 'sine',
  'quad', 'cubic', 'quart', 'quint', 'expo', 'circ', 'back', 'bounce', 'elastic'; modes
  'ease-in', 'ease-out', 'ease-in-out', 'auto'; Blender's ids such as 'EASE_IN' are accepted
  too), using Robert Penner's equations as Blender does (``BLI_easing``), with Interpolate
  Sequence's Back, Amplitude and Period settings; 'custom' reads a curve the caller samples
  (the add-on: Blender's own Custom curve, so the core never sees Blender);
- or a timing chart (:func:`parse_timing_chart`) gives the morph times outright, one in-between
  per fraction, on frames spread evenly between the keys (:func:`frame_times`), not eased;
- then favoring (:func:`apply_favor`) pulls every time toward one key.
"""

import re

import numpy as np

from ...errors import InvalidCurveError
from ...options import EASING_MODES, EASING_TYPES, check_option

__all__ = ["ease", "frame_times", "apply_favor", "parse_timing_chart", "FAVOR_ODDS", "BACK", "AMPLITUDE", "PERIOD"]

#: Favor 1 multiplies the odds t / (1 - t) of every morph time by this (favor -1 divides them):
#: the middle in-between moves to 3/4 (or 1/4) of the way, the animator's "favor" mark.
FAVOR_ODDS = 3.0
# Spaces, commas, or both, between a timing chart's fractions.
_CHART_SEPARATORS = re.compile(r"[\s,]+")

# 'auto' follows Blender: ease in for the "dynamic" types, ease out for back/bounce/elastic.
_AUTO_OUT = ("back", "bounce", "elastic")

#: Blender's Interpolate Sequence defaults for its Back, Amplitude and Period settings
#: (``bpy.ops.grease_pencil.interpolate_sequence``: back 1.702, amplitude 0.15, period 0.15, on
#: Blender 4.5 and 5.0). Robert Penner's fixed constants are back 1.70158 and, for elastic,
#: amplitude 1 and period 0.3.
BACK = 1.702
AMPLITUDE = 0.15
PERIOD = 0.15


def _bounce_out(x):
    n1, d1 = 7.5625, 2.75
    return np.select(
        [x < 1 / d1, x < 2 / d1, x < 2.5 / d1],
        [n1 * x * x, n1 * (x - 1.5 / d1) ** 2 + 0.75, n1 * (x - 2.25 / d1) ** 2 + 0.9375],
        n1 * (x - 2.625 / d1) ** 2 + 0.984375,
    )


def _elastic_in(x, amplitude, period):
    """Blender's ``BLI_easing_elastic_ease_in`` (begin 0, change 1, duration 1), vectorised.

    An amplitude below 1 (the change) keeps the curve's phase and scales its swings by the
    amplitude, blended back to full size in the last quarter period before the key (Blender's
    ``elastic_blend``); an amplitude above 1 shifts the phase so the swing starts at that size.
    """
    t = x - 1.0
    if amplitude > 1.0:
        s, f = period / (2 * np.pi) * np.arcsin(1.0 / amplitude), amplitude
    else:
        s, f = period / 4, 1.0
        if amplitude < 1.0:  # elastic_blend: the swings scaled, back to 1 near the key
            reach = np.abs(s)
            near = np.minimum(np.abs(t) / reach, 1.0) if reach > 0 else np.ones_like(t)
            f = amplitude * near + (1.0 - near)
    # Written so that amplitude 1, period 0.3 give Penner's 2^(10x - 10) sin((10x - 10.75) 2 pi / 3)
    # bit for bit.
    wave = -f * 2.0 ** (10 * x - 10) * np.sin((x * 10 - (10 + 10 * s)) * (2 * np.pi / (10 * period)))
    return np.where((x <= 0) | (x >= 1), x, wave)


def _ease_in(kind, x, back, amplitude, period):
    if kind == "sine":
        return 1 - np.cos(x * np.pi / 2)
    if kind in ("quad", "cubic", "quart", "quint"):
        return x ** (2 + ("quad", "cubic", "quart", "quint").index(kind))
    if kind == "expo":
        return np.where(x <= 0, 0.0, 2.0 ** (10 * x - 10))
    if kind == "circ":
        return 1 - np.sqrt(np.clip(1 - x * x, 0, 1))
    if kind == "back":
        return (back + 1) * x**3 - back * x**2
    if kind == "bounce":
        return 1 - _bounce_out(1 - x)
    if kind == "elastic":
        return _elastic_in(x, amplitude, period)
    return x


def _checked_curve(curve):
    table = np.asarray(curve, dtype=np.float64) if curve is not None else None
    if table is None or table.ndim != 1 or len(table) < 2 or not np.all(np.isfinite(table)):
        raise InvalidCurveError(
            "curve: the 'custom' type needs the curve's values at evenly spaced fractions from 0 to 1 "
            f"(at least two finite numbers), got {curve!r}"
        )
    return table


def _number(name, value, low=-np.inf):
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = np.nan
    if not (np.isfinite(number) and number >= low):
        bound = "" if low == -np.inf else f" of at least {low:g}"
        raise InvalidCurveError(f"{name} must be a finite number{bound}, got {value!r}")
    return number


def ease(x, kind="linear", mode="auto", *, back=BACK, amplitude=AMPLITUDE, period=PERIOD, curve=None):
    """Map frame fractions to morph times, as Blender's Interpolate Sequence does.

    Parameters
    ----------
    x : array_like
        Fractions of the key interval, in [0, 1].
    kind : str
        One of :data:`EASING_TYPES`.
    mode : str
        One of :data:`EASING_MODES` (not used by 'linear' and 'custom').
    back : float, optional
        The overshoot of 'back' (Blender's Back, at least 0; 0 makes 'back' a cubic). Ease in
        and out uses 1.525 times it, as Blender does.
    amplitude, period : float, optional
        The 'elastic' settings (Blender's Amplitude, at least 0, and Period). Below 1 the
        amplitude scales the swings; a period of 0 means Blender's own (0.3, 0.45 in and out).
    curve : array_like, optional
        For 'custom': the curve's values at ``T`` evenly spaced fractions from 0 to 1 (Blender's
        Custom curve sampled by the caller), read by linear interpolation.

    Returns
    -------
    ndarray
        Same shape as ``x``; 0 maps to 0 and 1 to 1 (BACK and ELASTIC may overshoot between;
        'custom' maps them where its curve does).

    Examples
    --------
    >>> ease([0.0, 0.5, 1.0], "quad", "ease-in").tolist()
    [0.0, 0.25, 1.0]
    >>> ease([0.25], "quad", "ease-in-out").tolist()
    [0.125]
    >>> ease([0.5], "back", "ease-in", back=0.0).tolist()  # no overshoot: a cubic
    [0.125]
    >>> ease([0.25, 0.5], "custom", curve=[0.0, 0.8, 1.0]).tolist()
    [0.4, 0.8]
    """
    kind = check_option("kind", kind, EASING_TYPES)
    mode = check_option("mode", mode, EASING_MODES)
    back = _number("back", back, low=0.0)
    amplitude = _number("amplitude", amplitude, low=0.0)
    period = _number("period", period)
    x = np.clip(np.asarray(x, dtype=np.float64), 0.0, 1.0)
    if kind == "linear":
        return x
    if kind == "custom":
        table = _checked_curve(curve)
        return np.interp(x, np.linspace(0.0, 1.0, len(table)), table)
    if mode == "auto":
        mode = "ease-out" if kind in _AUTO_OUT else "ease-in"
    if mode == "ease-in-out":
        back *= 1.525  # Blender's BLI_easing_back_ease_in_out (Penner's)
        period = period or 0.45
    else:
        period = period or 0.3
    settings = (back, amplitude, period)
    if mode == "ease-in":
        return _ease_in(kind, x, *settings)
    if mode == "ease-out":
        return 1 - _ease_in(kind, 1 - x, *settings)
    return np.where(x < 0.5, _ease_in(kind, 2 * x, *settings) / 2, 1 - _ease_in(kind, 2 - 2 * x, *settings) / 2)


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
