"""Lengths and normals of many plane vectors at once, coordinate by coordinate.

numpy 1.26 runs ``np.linalg.norm(v, axis=-1)`` over rows two elements long and broadcasts
(..., 1) columns a row at a time, several times slower than the same arithmetic on the x and
y columns. These give its values bit for bit (x x + y y, then the root).
"""

import numpy as np

__all__ = ["norms", "row_norms", "unit_left"]


def norms(x, y):
    """Lengths of the vectors ``(x, y)`` (ndarrays of one shape), a new array of that shape."""
    out = x * x
    out += y * y
    return np.sqrt(out, out=out)


def row_norms(v):
    """Lengths of the vectors ``v``, shape (..., 2) -> (...,): ``np.linalg.norm(v, axis=-1)``."""
    return norms(v[..., 0], v[..., 1])


def unit_left(v):
    """Unit vectors turned +90 degrees (zero for zero vectors), shape (..., 2).

    The ball-map turns every dense vertex and edge of both sides: the values of
    ``v / np.linalg.norm(v, axis=-1)[..., None]`` turned, bit for bit."""
    v = np.asarray(v, dtype=np.float64)
    x, y = v[..., 0], v[..., 1]
    norm = norms(x, y)
    some = norm > 0
    out = np.zeros_like(v)
    np.divide(y, norm, out=out[..., 0], where=some)
    np.negative(out[..., 0], out=out[..., 0])
    np.divide(x, norm, out=out[..., 1], where=some)
    return out
