"""Divisions by a spread, a norm or an area that may vanish, guarded relative to a size.

A spread, a norm or a distance is zero when it is at most ``tolerances.DEGENERATE`` times the
size of the drawing it comes from (the round-off of coordinates of that size), an area or a
squared length when at most the square of that. Dividing by such a value gives a ratio made of
round-off, as large as ``1e300`` or infinite: the callers take a named default instead (no
OverflowError, no RuntimeWarning, the same answer at any scale).

Examples
--------
>>> ratio(3.0, 1e-20, least(1.0))
1.0
>>> ratio(3.0, 2.0, least(1.0))
1.5
"""

import numpy as np

from .. import tolerances as tol

__all__ = ["least", "ratio"]


def least(size, power=1):
    """The least value that is not zero for a length (``power`` 1) or an area (2) of a drawing of
    ``size`` (its bounding-box diagonal; float): ``(DEGENERATE * size) ** power``, at least the
    smallest normal float (a drawing of size 0 divides by nothing)."""
    return max((tol.DEGENERATE * float(size)) ** power, np.finfo(np.float64).tiny)


def ratio(numerator, denominator, floor, default=1.0):
    """``numerator / denominator`` where ``|denominator| > floor`` (see :func:`least`), else
    ``default``: a Python float (or complex) for scalars, else an array of the broadcast shape,
    with no warning."""
    num, den = np.asarray(numerator), np.asarray(denominator, dtype=np.float64)
    ok = np.abs(den) > floor
    kind = np.result_type(num, den, np.asarray(default))
    out = np.full(np.broadcast(num, den).shape, default, dtype=kind)
    np.divide(num, np.where(ok, den, 1.0), out=out, where=ok)
    return out.item() if out.ndim == 0 else out
