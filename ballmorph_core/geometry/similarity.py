"""Similarities of the plane in complex coordinates: ``z -> a z + b`` and their steady powers.

A point ``(x, y)`` is the complex number ``x + iy``; a similarity is ``z -> a z + b`` with
``a = s e^{i theta}`` (scale ``s``, rotation ``theta``). Its steady interpolation
``S^s(z) = c + a^s (z - c)`` about the fixed point ``c = b / (1 - a)`` moves every point on a
logarithmic spiral (Rossignac & Vinacua's steady affine motions).
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol

__all__ = ["as_complex", "from_complex", "power", "Similarity"]


def as_complex(points):
    """Points as complex numbers ``x + iy``, shape (...,) from (..., 2)."""
    points = np.asarray(points, dtype=np.float64)
    return points[..., 0] + 1j * points[..., 1]


def from_complex(z):
    """Complex numbers back to points, shape (..., 2)."""
    z = np.asarray(z)
    return np.stack([z.real, z.imag], axis=-1)


def power(a, b, s):
    """``S^s`` for similarities ``z -> a z + b`` (arrays), along the steady interpolation.

    ``S^s(z) = c + a^s (z - c)`` with ``c = b / (1 - a)`` the fixed point (a logarithmic spiral;
    a translation ``z + s b`` when ``a = 1``). The angle of ``a`` is taken in (-pi, pi], so the
    motion turns the short way.

    Returns
    -------
    a_s, b_s : ndarray of complex
    """
    a = np.asarray(a, dtype=complex)
    b = np.asarray(b, dtype=complex)
    a_s = np.exp(s * (np.log(np.abs(a)) + 1j * np.angle(a)))
    near_one = np.abs(a - 1) < tol.ROUNDOFF
    c = np.where(near_one, 0, b / np.where(near_one, 1, 1 - a))
    return a_s, np.where(near_one, s * b, c - a_s * c)


@dataclass
class Similarity:
    """The map ``z -> a z + b`` on complex coordinates.

    Attributes
    ----------
    a, b : complex
        ``|a|`` is the scale, ``arg a`` the rotation.
    """

    a: complex = 1.0 + 0j
    b: complex = 0j

    def __call__(self, points):
        """Apply to points, shape (..., 2) -> (..., 2)."""
        return from_complex(self.a * as_complex(points) + self.b)

    def inverse(self):
        """The inverse similarity."""
        return Similarity(1.0 / self.a, -self.b / self.a)

    @property
    def scale(self):
        """``|a|``."""
        return float(abs(self.a))

    @property
    def turn(self):
        """``arg a``, radians."""
        return float(np.angle(self.a))

    def power(self, s):
        """``S^s`` along the steady (log-spiral) interpolation; ``S^0`` is the identity."""
        a_s, b_s = power(self.a, self.b, s)
        return Similarity(complex(a_s), complex(b_s))
