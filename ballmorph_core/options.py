"""One helper validates every option string of the core (shapely style)."""

from .errors import InvalidCurveError

__all__ = ["check_option"]


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
