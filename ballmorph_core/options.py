"""One helper validates every option string of the core (shapely style), one every positive length."""

import numpy as np

from .errors import InvalidCurveError

__all__ = ["check_option", "check_positive"]


def check_option(name, value, valid):
    """Return ``value`` if it is one of ``valid``, else raise a clear error.

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
        ``value`` unchanged.

    Raises
    ------
    InvalidCurveError
        (a ``ValueError``) naming the argument and listing the valid values.

    Examples
    --------
    >>> check_option("closed_mode", "loop", ("loop", "stroke"))
    'loop'
    >>> check_option("closed_mode", "ring", ("loop", "stroke"))
    Traceback (most recent call last):
    ...
    ballmorph_core.errors.InvalidCurveError: closed_mode='ring' is not valid; expected one of 'loop', 'stroke'
    """
    if value not in valid:
        listed = ", ".join(repr(v) for v in valid)
        raise InvalidCurveError(f"{name}={value!r} is not valid; expected one of {listed}")
    return value


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
