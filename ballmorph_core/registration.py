"""Registration and carrier motions (paper section 1.4; Rossignac & Vinacua's steady motions).

The paper's ball-morph needs strokes that share both endpoints, or nested loops. An animator's
keys rarely are: an arm turns and bends, a ball moves. We *register* P onto Q with a
similarity ``S`` (z -> a z + b in complex numbers, a = s e^{i theta}), ball-morph between the
registered ``S(P)`` and ``Q``, and move the result along a *carrier* that undoes the
registration progressively:

    in-between(t) = C_t(F(t)),  F = ball-morph from S(P) to Q,  C_0 = S^-1,  C_1 = identity.

* ``'SIMILARITY'``: ``C_t = S^-(1-t)``. A similarity has a fixed point ``c = b / (1 - a)``
  and its steady interpolation ``z -> c + a^s (z - c)`` moves every point on a logarithmic
  spiral about ``c`` (a circular arc when the scale is 1, a straight line when ``a = 1``).
* ``'RIGID'``: ``S`` is split into a uniform scaling about the registered curve's centre and a
  rigid motion ``R``; the carrier moves along ``R^-(1-t)`` (circular arcs) and the scale is
  interpolated geometrically about that centre, so the path of the centre is a circle arc
  rather than a spiral. The result equals 'SIMILARITY' when no scaling is involved.

Strokes are registered by their endpoints (the similarity that maps P's endpoints onto Q's, so
``S(P)`` and ``Q`` share them); loops by the least-squares similarity between uniform
arc-length samples, over the cyclic shift and direction that fit best. Then a stroke turned by
90 degrees keeps its length (linear interpolation shrinks it to 71 % at the middle), and a
circle that moves stays a circle.
"""

from dataclasses import dataclass

import numpy as np

from .curves import curve_length, resample
from .options import check_option

__all__ = ["Similarity", "endpoint_similarity", "fit_similarity", "Carrier", "CARRIERS"]

CARRIERS = ("SIMILARITY", "RIGID", "NONE")


def _z(points):
    points = np.asarray(points, dtype=np.float64)
    return points[..., 0] + 1j * points[..., 1]


def _xy(z):
    return np.stack([z.real, z.imag], axis=-1)


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
        return _xy(self.a * _z(points) + self.b)

    def inverse(self):
        """The inverse similarity."""
        return Similarity(1.0 / self.a, -self.b / self.a)

    @property
    def scale(self):
        return float(abs(self.a))

    @property
    def angle(self):
        return float(np.angle(self.a))

    def power(self, s):
        """``S^s`` along the steady (log-spiral) interpolation; ``S^0`` is the identity.

        The rotation angle is taken in (-pi, pi], so the carrier turns the short way.
        """
        log_a = np.log(abs(self.a)) + 1j * np.angle(self.a)
        a_s = np.exp(s * log_a)
        if abs(self.a - 1) < 1e-12:
            return Similarity(1.0 + 0j, s * self.b)
        c = self.b / (1 - self.a)  # fixed point
        return Similarity(a_s, c - a_s * c)

    def is_identity(self, scale, tol=1e-12):
        """True when it moves no point of a drawing of size ``scale`` by more than tol*scale."""
        return abs(self.a - 1) * scale <= tol * scale and abs(self.b) <= tol * scale


def endpoint_similarity(P, Q):
    """The similarity mapping P's endpoints onto Q's (Similarity).

    Degenerate strokes whose endpoints coincide get the translation of their first points.
    """
    zp, zq = _z(P[[0, -1]]), _z(Q[[0, -1]])
    dp, dq = zp[1] - zp[0], zq[1] - zq[0]
    if abs(dp) <= 1e-12 * (abs(zp[0]) + 1) or abs(dq) <= 1e-12 * (abs(zq[0]) + 1):
        return Similarity(1.0 + 0j, zq[0] - zp[0])
    a = dq / dp
    return Similarity(a, zq[0] - a * zp[0])


def fit_similarity(P, Q, closed, count=128):
    """Least-squares similarity from P to Q (Procrustes in complex form).

    Parameters
    ----------
    P, Q : ndarray, shape (N, 2), (M, 2)
    closed : bool
        For loops, the best cyclic shift and direction of the correspondence are searched too
        (all shifts at once by FFT cross-correlation).
    count : int
        Uniform arc-length samples per curve.

    Returns
    -------
    Similarity
    """
    zp = _z(resample(P, closed, count=count))
    zq = _z(resample(Q, closed, count=count))
    cp, cq = zp.mean(), zq.mean()
    xp, xq = zp - cp, zq - cq
    norm = float(np.vdot(xp, xp).real)
    if norm <= 0:
        return Similarity(1.0 + 0j, cq - cp)
    best = None
    candidates = (xq, np.concatenate([xq[:1], xq[:0:-1]])) if closed else (xq, xq[::-1])
    for k, target in enumerate(candidates):
        if closed:
            # c(s) = sum conj(xp_i) target_(i+s), for every shift s.
            corr = np.fft.ifft(np.conj(np.fft.fft(xp)) * np.fft.fft(target))
            s = int(np.argmax(np.abs(corr)))
            c = corr[s]
        else:
            if k == 1:
                continue  # a stroke's direction is fixed by the caller
            c = np.vdot(xp, target)
        if best is None or abs(c) > abs(best):
            best = c
    a = best / norm
    return Similarity(a, cq - a * cp)


class Carrier:
    """The carrier motion ``C_t`` that takes ``S(P)`` back to ``P`` at t = 0 and is the identity
    at t = 1 (see the module docstring).

    Parameters
    ----------
    similarity : Similarity
        The registration ``S`` (P -> registered P).
    kind : {'SIMILARITY', 'RIGID'}
    centre : ndarray, shape (2,)
        Centre of the registered curve (the scaling centre for 'RIGID').
    """

    def __init__(self, similarity, kind, centre):
        self.kind = check_option("carrier", kind, ("SIMILARITY", "RIGID"))
        self.similarity = similarity
        self.centre = _z(np.asarray(centre, dtype=np.float64))
        if kind == "RIGID":
            s = similarity.scale
            # S = R o Z with Z the scaling by s about S^-1(centre): equivalently S = Zc o R with
            # Zc the scaling by s about the registered centre; R = Zc^-1 o S is rigid.
            zc_inv = Similarity(1.0 / s + 0j, self.centre - self.centre / s)
            rigid = zc_inv.a * similarity.a, zc_inv.a * similarity.b + zc_inv.b
            self._rigid = Similarity(complex(rigid[0]), complex(rigid[1]))
            self._scale = s

    def at(self, t):
        """The similarity ``C_t`` (Similarity)."""
        s = -(1.0 - float(t))
        if self.kind == "SIMILARITY":
            return self.similarity.power(s)
        rigid = self._rigid.power(s)
        zoom = self._scale**s
        # C_t = R^s o Zc^s  (scale about the registered centre first, then move rigidly).
        a = rigid.a * zoom
        b = rigid.a * (self.centre - zoom * self.centre) + rigid.b
        return Similarity(a, b)

    def apply(self, t, points):
        """``C_t`` applied to points, shape (K, 2)."""
        return self.at(t)(points)


def registration(P, Q, closed):
    """The registration similarity for a pair (strokes: endpoints; loops: best fit).

    Returns
    -------
    Similarity
    """
    return fit_similarity(P, Q, True) if closed else endpoint_similarity(P, Q)


def centre_of(curve, closed):
    """Arc-length centroid of a curve, shape (2,)."""
    pts = resample(curve, closed, count=max(16, min(256, len(curve))))
    if curve_length(curve, closed) <= 0:
        return curve.mean(axis=0)
    return pts.mean(axis=0)
