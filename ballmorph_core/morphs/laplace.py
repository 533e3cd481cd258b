"""Laplace blending (paper section 2; Alexa 2003, Sorkine et al. 2004): blend the differential
coordinates of corresponding polygons and rebuild the polygon by least squares.

The differential coordinate of vertex ``i`` is ``delta_i = v_i - (v_(i-1) + v_(i+1)) / 2``.
Blending the deltas of P and Q linearly is not rotation invariant (a shape rotated by a half
turn would shrink to nothing on the way), so by default each delta is expressed in its
vertex's *local frame*, the chord ``tau_i = v_(i+1) - v_(i-1)`` to its neighbours, as the
paper describes ("the local coordinates of each vertex in the coordinate system defined by its
neighbors"): ``c_i = delta_i / tau_i`` in complex numbers, invariant to rotation and scale.
Frame ``t`` prescribes ``delta_i(t) = c_i(t) tau_i(t)`` with ``c_i(t)`` interpolated linearly
and ``tau_i(t)`` interpolated in polar form (length linearly, direction along the shorter way
round, the same branch for every vertex), so the rebuilt curve only has to solve one linear
system, and the result of two similar shapes is similar to both at every ``t``.
``deltas='plain'`` blends the deltas themselves (the textbook version) for comparison.

The rebuild: strokes keep their interpolated endpoints exactly and solve the square tridiagonal
system for the interior vertices; loops solve ``L v = delta(t)`` in the least-squares sense
(the circulant ``L`` has the constants as its null space, so the part of ``delta(t)`` that no
loop has, its mean, is dropped) with the vertex mean anchored at the interpolated centroid.
Hard anchors are the limit of the weighted soft anchors ``w^2 |anchor - target|^2`` as ``w``
grows; for a loop the centroid anchor is orthogonal to the range of ``L`` and every weight gives
this result. The system matrix does not depend on ``t``: it is diagonalised once in the
constructor (discrete Fourier modes for a loop, sine modes for a stroke's interior), and each
frame costs two FFTs.
"""

import numpy as np

from .. import tolerances as tol
from ..geometry.polyline import scale_of
from ..geometry.similarity import as_complex
from ..options import check_option
from .base import KeyedMorph, register
from .linear import sample_count, uniform_correspondence

__all__ = ["LaplaceMorph", "DELTAS"]

#: How the differential coordinates are blended (see the module docstring).
DELTAS = ("local", "plain")


def _dst1(f):
    """Type-I discrete sine transform along the first axis (complex allowed), via the FFT.

    ``F_k = sum_j f_j sin(pi j k / (n + 1))`` for ``j, k = 1..n``; applying it twice multiplies
    by ``(n + 1) / 2``.
    """
    n = len(f)
    g = np.zeros(2 * (n + 1), dtype=np.complex128)
    g[1 : n + 1] = f
    g[n + 2 :] = -f[::-1]
    return 0.5j * np.fft.fft(g)[1 : n + 1]


class LaplaceMorph(KeyedMorph):
    """Blended differential coordinates, rebuilt by least squares (see the module docstring).

    Parameters
    ----------
    p, q : ndarray, shape (K, 2)
        Corresponding samples (loops turning the same way).
    u_p, u_q : ndarray, shape (K,)
    closed : bool
    deltas : {'local', 'plain'}
    """

    method = "laplace-blending"

    def __init__(self, p, q, u_p, u_q, closed, deltas="local"):
        super().__init__(p, q, u_p, u_q, closed)
        self.deltas = check_option("deltas", deltas, DELTAS)
        za, zb = as_complex(p), as_complex(q)
        if closed:
            prev_a, next_a, prev_b, next_b = np.roll(za, 1), np.roll(za, -1), np.roll(zb, 1), np.roll(zb, -1)
            mid_a, mid_b = za, zb
            # Eigenvalues of L = I - (shift + shift^-1) / 2 on the Fourier modes.
            self._eig = 1.0 - np.cos(2.0 * np.pi * np.arange(len(za)) / len(za))
        else:
            prev_a, next_a, prev_b, next_b = za[:-2], za[2:], zb[:-2], zb[2:]
            mid_a, mid_b = za[1:-1], zb[1:-1]
            n = len(za) - 2
            # Eigenvalues of tridiag(-1, 2, -1) on the sine modes.
            self._eig = 2.0 - 2.0 * np.cos(np.pi * np.arange(1, n + 1) / (n + 1))
        self._delta_a = mid_a - 0.5 * (prev_a + next_a)
        self._delta_b = mid_b - 0.5 * (prev_b + next_b)
        tau_a, tau_b = next_a - prev_a, next_b - prev_b
        tiny = tol.COINCIDENT * scale_of(p, q)
        # A vertex whose neighbours coincide (a hairpin thinner than the sampling) has no frame:
        # its delta is blended plainly.
        self._framed = (np.abs(tau_a) > tiny) & (np.abs(tau_b) > tiny)
        safe_a = np.where(self._framed, tau_a, 1.0)
        safe_b = np.where(self._framed, tau_b, 1.0)
        self._coord_a, self._coord_b = self._delta_a / safe_a, self._delta_b / safe_b
        self._mag_a, self._mag_b = np.abs(safe_a), np.abs(safe_b)
        ang_a, ang_b = np.unwrap(np.angle(safe_a)), np.unwrap(np.angle(safe_b))
        # One branch for all vertices: the mean local rotation lies in (-pi, pi].
        turn = np.mean(ang_b[self._framed] - ang_a[self._framed]) if self._framed.any() else 0.0
        ang_b = ang_b - 2.0 * np.pi * np.round(turn / (2.0 * np.pi))
        self._ang_a, self._ang_b = ang_a, ang_b

    def differential(self, t):
        """The differential coordinates prescribed at ``t``, complex, shape (K,) for a loop and
        (K - 2,) for a stroke (interior vertices)."""
        plain = (1 - t) * self._delta_a + t * self._delta_b
        if self.deltas == "plain":
            return plain
        coord = (1 - t) * self._coord_a + t * self._coord_b
        tau = ((1 - t) * self._mag_a + t * self._mag_b) * np.exp(1j * ((1 - t) * self._ang_a + t * self._ang_b))
        return np.where(self._framed, coord * tau, plain)

    def _solve(self, t):
        za, zb = as_complex(self._p), as_complex(self._q)
        delta = self.differential(t)
        if self.closed:
            spec = np.fft.fft(delta)
            spec[1:] /= self._eig[1:]
            spec[0] = len(za) * ((1 - t) * za.mean() + t * zb.mean())
            z = np.fft.ifft(spec)
        else:
            start = (1 - t) * za[0] + t * zb[0]
            end = (1 - t) * za[-1] + t * zb[-1]
            rhs = 2.0 * delta
            rhs[0] += start
            rhs[-1] += end
            n = len(rhs)
            inner = _dst1(_dst1(rhs) / self._eig) * (2.0 / (n + 1))
            z = np.concatenate([[start], inner, [end]])
        return np.stack([z.real, z.imag], axis=1)


@register("laplace-blending")
def build(P, Q, closed, spacing, sampling, deltas="local"):
    """Laplace blending on the uniform arc-length correspondence (see :class:`LaplaceMorph`);
    the sample count follows ``sampling`` as for linear interpolation, and loops are paired so
    both turn the same way."""
    count = sample_count(P, Q, closed, spacing, sampling)
    p, q, u_p, u_q = uniform_correspondence(P, Q, closed, count, match_orientation=True)
    return LaplaceMorph(p, q, u_p, u_q, closed, deltas)
