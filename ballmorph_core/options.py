"""The core's option vocabularies (lowercase strings) and their one validator (shapely style), and
the one check of positive lengths."""

import numpy as np

from .errors import InvalidCurveError

__all__ = [
    "CARRIERS",
    "MATCHINGS",
    "UNMATCHED",
    "SAMPLINGS",
    "PATH_KINDS",
    "EASING_TYPES",
    "EASING_MODES",
    "KEY_MOTIONS",
    "check_option",
    "check_positive",
]

#: Carrier motion of a stroke pair (see :mod:`~ballmorph_core.drawing.pair_morphs.registration`).
CARRIERS = ("similarity", "rigid", "none")
#: How the strokes of two keys are paired (see :mod:`~ballmorph_core.drawing.pairing.matching`).
MATCHINGS = ("auto", "index")
#: What a stroke without a partner does: switch at the middle, hold on every in-between, fade,
#: shrink along itself, or shrink into its nearest paired stroke (see drawing/unmatched.py).
UNMATCHED = ("middle", "hold", "fade", "shrink", "neighbour")
#: Which curve a correspondence samples uniformly (the paper's approaches 3 and 2).
SAMPLINGS = ("symmetric", "p", "q")
#: The five ball-morph paths (paper section 4.2).
PATH_KINDS = ("hat", "linear", "tangent", "circular", "parabolic")
#: Easing types and modes, as Blender's Grease Pencil interpolation names them ('custom': a
#: curve the caller samples, see drawing/frames/timing.py).
EASING_TYPES = (
    "linear",
    "custom",
    "sine",
    "quad",
    "cubic",
    "quart",
    "quint",
    "expo",
    "circ",
    "back",
    "bounce",
    "elastic",
)
EASING_MODES = ("auto", "ease-in", "ease-out", "ease-in-out")
#: How in-betweens pass through the inner keys of three or more: joined smoothly (C1, arcs
#: through the keys) or each interval on its own, with a corner at every key (see drawing/arcs.py).
KEY_MOTIONS = ("smooth", "per-interval")


def _canonical(value):
    return value.strip().lower().replace("_", "-") if isinstance(value, str) else value


def check_option(name, value, valid):
    """The entry of ``valid`` that ``value`` names, else raise a clear error.

    Matching ignores case and treats ``_`` as ``-``, so Blender's enum ids (``'EASE_IN'``,
    ``'CIRCULAR_BALL'``) name the core's values (``'ease-in'``, ``'circular-ball'``).

    Parameters
    ----------
    name : str
        The argument's name, used in the message.
    value : str
        The value given.
    valid : sequence of str
        The accepted values.

    Returns
    -------
    str
        The entry of ``valid`` (its spelling, not the caller's).

    Raises
    ------
    InvalidCurveError
        (a ``ValueError``) naming the argument and listing the valid values.

    Examples
    --------
    >>> check_option("closed_mode", "loop", ("loop", "stroke"))
    'loop'
    >>> check_option("closed_mode", "LOOP", ("loop", "stroke"))
    'loop'
    >>> check_option("closed_mode", "ring", ("loop", "stroke"))
    Traceback (most recent call last):
    ...
    ballmorph_core.errors.InvalidCurveError: closed_mode='ring' is not valid; expected one of 'loop', 'stroke'
    """
    if value in valid:
        return value
    wanted = _canonical(value)
    for entry in valid:
        if _canonical(entry) == wanted:
            return entry
    listed = ", ".join(repr(v) for v in valid)
    raise InvalidCurveError(f"{name}={value!r} is not valid; expected one of {listed}")


def check_positive(name, value):
    """``value`` as a float if it is a positive finite number, else raise a clear error.

    Parameters
    ----------
    name : str
        The argument's name, used in the message.
    value : object
        The value given (anything ``float()`` accepts).

    Returns
    -------
    float

    Raises
    ------
    InvalidCurveError
        (a ``ValueError``) naming the argument and the value.

    Examples
    --------
    >>> check_positive("spacing", 0.5)
    0.5
    >>> check_positive("spacing", -1)
    Traceback (most recent call last):
    ...
    ballmorph_core.errors.InvalidCurveError: spacing must be a positive finite number, got -1
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidCurveError(f"{name} must be a positive finite number, got {value!r}") from None
    if not (np.isfinite(number) and number > 0):
        raise InvalidCurveError(f"{name} must be a positive finite number, got {value!r}")
    return number
