"""Easing: where in the morph each in-between frame sits (t in [0, 1]).

The types and modes match Blender's Grease Pencil interpolation (types 'linear', 'sine', 'quad',
'cubic', 'quart', 'quint', 'expo', 'circ', 'back', 'bounce', 'elastic'; modes 'ease-in',
'ease-out', 'ease-in-out', 'auto'; Blender's ids such as 'EASE_IN' are accepted too), using
Robert Penner's equations as Blender does.
"""

import numpy as np

from ..options import EASING_MODES, EASING_TYPES, check_option

__all__ = ["ease", "frame_times"]

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
