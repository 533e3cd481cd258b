"""Registration and carrier motions (paper section 1.4; Rossignac & Vinacua's steady motions).

The paper's ball-morph needs strokes that share both endpoints, or nested loops. An animator's
keys rarely are: an arm turns and bends, a ball moves. We *register* P onto Q with a
similarity ``S`` (z -> a z + b in complex numbers, a = s e^{i theta}), ball-morph between the
registered ``S(P)`` and ``Q``, and move the result along a *carrier* that undoes the
registration progressively:

    in-between(t) = C_t(F(t)),  F = ball-morph from S(P) to Q,  C_0 = S^-1,  C_1 = identity.

* ``'similarity'``: ``C_t = S^-(1-t)``. A similarity has a fixed point ``c = b / (1 - a)``
  and its steady interpolation ``z -> c + a^s (z - c)`` moves every point on a logarithmic
  spiral about ``c`` (a circular arc when the scale is 1, a straight line when ``a = 1``).
* ``'rigid'``: ``S`` is split into a uniform scaling about the registered curve's centre and a
  rigid motion ``R``; the carrier moves along ``R^-(1-t)`` (circular arcs) and the scale is
  interpolated geometrically about that centre, so the path of the centre is a circle arc
  rather than a spiral. The result equals 'similarity' when no scaling is involved.

Strokes are registered by their endpoints (the similarity that maps P's endpoints onto Q's, so
``S(P)`` and ``Q`` share them); loops by the least-squares similarity between uniform
arc-length samples, over the cyclic shift and direction that fit best. Then a stroke turned by
90 degrees keeps its length (linear interpolation shrinks it to 71 % at the middle), and a
circle that moves stays a circle.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..geometry.ragged import Ragged
from ..geometry.similarity import Similarity, as_complex, from_complex, power
from ..options import check_option

__all__ = [
    "endpoint_similarity",
    "fit_similarity",
    "similarities",
    "carrier_at",
    "Carrier",
    "Motions",
    "register",
]

#: Loop registration: a fitted rotation costs this times (angle / pi)^2 of the normalised
#: residual, so shapes that merely change proportions (squash and stretch, apple to pear) are
#: not turned to fit better; a shape that really turned still is (its unrotated residual is
#: larger than the penalty).
ROTATION_PENALTY = 1.0

#: Uniform samples per curve for the least-squares fit of loops.
FIT_SAMPLES = 128


# ------------------------------------------------------------------ vectorised core


def carrier_at(a, b, kind, centre, t):
    """The carrier ``C_t`` of registrations ``S`` (arrays; see the module docstring).

    Parameters
    ----------
    a, b : ndarray of complex
        The registrations.
    kind : {'similarity', 'rigid'}
    centre : ndarray of complex
        Centre of each registered curve (the scaling centre of 'rigid').
    t : float

    Returns
    -------
    ca, cb : ndarray of complex
        ``C_t(z) = ca z + cb``.
    """
    s = -(1.0 - float(t))
    if kind == "similarity":
        return power(a, b, s)
    # S = Zc o R: Zc the scaling by |a| about the registered centre, R = Zc^-1 o S rigid;
    # C_t = R^s o Zc^s (scale about the centre, then move rigidly on circular arcs).
    scale = np.abs(a)
    ra = a / scale
    rb = b / scale + centre - centre / scale
    ra_s, rb_s = power(ra, rb, s)
    zoom = scale**s
    return ra_s * zoom, ra_s * (centre - zoom * centre) + rb_s


def similarities(P, Q):
    """Registrations of every curve of a batch onto its partner.

    Strokes map their endpoints onto their partner's endpoints. Loops get the least-squares
    similarity between ``FIT_SAMPLES`` uniform samples over every cyclic shift and both
    directions (FFT cross-correlation). Among the distinct fits (local minima of the residual
    over the shifts) a rotation costs ``ROTATION_PENALTY`` times (angle / pi)^2 of
    the normalised residual, and the best unrotated fit (scale and translation only) competes at
    no cost: a squashed ball or a pear that is merely taller than the apple is not turned by 90
    degrees to fit better, while a shape that really turned keeps its exact fit.

    Parameters
    ----------
    P, Q : Ragged
        Same number of curves, same closed flags.

    Returns
    -------
    a, b : ndarray of complex, shape (C,)
    residual : ndarray, shape (C,)
        RMS distance left between ``FIT_SAMPLES`` uniform samples of the registered curve and
        of its partner (0 when registration makes them coincide).
    """
    n = len(P)
    a = np.ones(n, dtype=complex)
    b = np.zeros(n, dtype=complex)
    residual = np.full(n, np.inf)
    zp, zq = as_complex(P.pts), as_complex(Q.pts)
    opened = np.flatnonzero(~P.closed)
    if len(opened):
        fp, lp = P.offsets[:-1][opened], P.offsets[1:][opened] - 1
        fq, lq = Q.offsets[:-1][opened], Q.offsets[1:][opened] - 1
        dp, dq = zp[lp] - zp[fp], zq[lq] - zq[fq]
        ok = (np.abs(dp) > tol.ROUNDOFF * (np.abs(zp[fp]) + 1)) & (np.abs(dq) > tol.ROUNDOFF * (np.abs(zq[fq]) + 1))
        a[opened] = np.where(ok, dq / np.where(ok, dp, 1), 1.0)
        b[opened] = zq[fq] - a[opened] * zp[fp]
        k = FIT_SAMPLES
        sp = as_complex(P.resample(np.full(n, k)).pts).reshape(n, k)[opened]
        sq = as_complex(Q.resample(np.full(n, k)).pts).reshape(n, k)[opened]
        fitted = a[opened][:, None] * sp + b[opened][:, None]
        residual[opened] = np.sqrt(np.mean(np.abs(fitted - sq) ** 2, axis=1))
    loops = np.flatnonzero(P.closed)
    if len(loops):
        k = FIT_SAMPLES
        xp = as_complex(P.resample(np.full(n, k)).pts).reshape(n, k)[loops]
        xq = as_complex(Q.resample(np.full(n, k)).pts).reshape(n, k)[loops]
        cp, cq = xp.mean(axis=1), xq.mean(axis=1)
        xp, xq = xp - cp[:, None], xq - cq[:, None]
        norm_p = np.sum(np.abs(xp) ** 2, axis=1)
        norm_q = np.sum(np.abs(xq) ** 2, axis=1)
        safe = norm_p > 0
        fp = np.conj(np.fft.fft(xp, axis=1))
        best_cost = np.full(len(loops), np.inf)
        best_c = np.zeros(len(loops), dtype=complex)
        rows = np.arange(len(loops))[:, None]
        for target in (xq, np.concatenate([xq[:, :1], xq[:, :0:-1]], axis=1)):
            corr = np.fft.ifft(fp * np.fft.fft(target, axis=1), axis=1)  # c(s) for every shift
            left = norm_q[:, None] - np.abs(corr) ** 2 / np.where(safe, norm_p, 1.0)[:, None]
            fit = left / np.maximum(norm_q, 1e-300)[:, None]
            # Rotation is penalised only between distinct fits (local minima over the shifts),
            # never within one, so a fit that is right is not biased towards less rotation.
            minimum = (fit <= np.roll(fit, 1, axis=1)) & (fit <= np.roll(fit, -1, axis=1))
            cost = np.where(minimum, fit + ROTATION_PENALTY * (np.angle(corr) / np.pi) ** 2, np.inf)
            # The unrotated fit (a real scale) is always a candidate, at no penalty.
            real = np.maximum(corr.real, 0.0)
            fit0 = (norm_q[:, None] - real**2 / np.where(safe, norm_p, 1.0)[:, None]) / np.maximum(norm_q, 1e-300)[
                :, None
            ]
            cost = np.concatenate([cost, fit0], axis=1)
            s = np.argmin(cost, axis=1)
            chosen = np.where(s < k, corr[rows[:, 0], s % k], real[rows[:, 0], s % k] + 0j)
            better = cost[rows[:, 0], s] < best_cost
            best_cost = np.where(better, cost[rows[:, 0], s], best_cost)
            best_c = np.where(better, chosen, best_c)
        a[loops] = np.where(safe, best_c / np.where(safe, norm_p, 1.0), 1.0)
        b[loops] = cq - a[loops] * cp
        # Least-squares residual of the chosen shift (what is left for the morph to do).
        residual[loops] = np.sqrt(np.maximum(norm_q - np.abs(best_c) ** 2 / np.where(safe, norm_p, 1.0), 0) / k)
    return a, b, residual


# ------------------------------------------------------------------ one pair


def _one(P, Q, closed):
    a, b, _ = similarities(Ragged.from_list([P], [closed]), Ragged.from_list([Q], [closed]))
    return Similarity(complex(a[0]), complex(b[0]))


def endpoint_similarity(P, Q):
    """The similarity mapping P's endpoints onto Q's (Similarity).

    Degenerate strokes whose endpoints coincide get the translation of their first points.
    """
    return _one(P, Q, False)


def fit_similarity(P, Q, closed=True):
    """Registration of a loop onto another (see :func:`similarities`), as a Similarity."""
    return _one(P, Q, closed)


class Carrier:
    """The carrier motion ``C_t`` that takes ``S(P)`` back to ``P`` at t = 0 and is the identity
    at t = 1 (see the module docstring).

    Parameters
    ----------
    similarity : Similarity
        The registration ``S`` (P -> registered P).
    kind : {'similarity', 'rigid'}
    centre : ndarray, shape (2,)
        Centre of the registered curve (the scaling centre for 'rigid').
    """

    def __init__(self, similarity, kind, centre):
        self.kind = check_option("carrier", kind, ("similarity", "rigid"))
        self.similarity = similarity
        self.centre = complex(as_complex(np.asarray(centre, dtype=np.float64)))

    def at(self, t):
        """The similarity ``C_t`` (Similarity)."""
        ca, cb = carrier_at(self.similarity.a, self.similarity.b, self.kind, self.centre, t)
        return Similarity(complex(ca), complex(cb))

    def apply(self, t, points):
        """``C_t`` applied to points, shape (K, 2)."""
        return self.at(t)(points)


@dataclass
class Motions:
    """The carrier motions of a batch of pairs: ``C_t`` per pair, identity where not moving.

    Attributes
    ----------
    a, b : ndarray of complex, shape (C,)
        Each pair's registration ``z -> a z + b`` of P onto Q.
    moving : ndarray of bool, shape (C,)
        Pairs whose carrier is not the identity.
    centre : ndarray of complex, shape (C,)
        Centre of each Q (the scaling centre of a 'rigid' carrier).
    kind : {'similarity', 'rigid'}
    """

    a: np.ndarray
    b: np.ndarray
    moving: np.ndarray
    centre: np.ndarray
    kind: str

    def apply(self, t, points, pair_of):
        """``C_t`` of each point's pair applied to it, shape (K, 2) (points unchanged if no pair moves)."""
        if not self.moving.any():
            return points
        ca, cb = carrier_at(self.a, self.b, self.kind, self.centre, t)
        ca, cb = np.where(self.moving, ca, 1.0), np.where(self.moving, cb, 0.0)
        return from_complex(ca[pair_of] * as_complex(points) + cb[pair_of])


def register(P, Q, carrier, scale):
    """Register every P of a batch onto its Q (see the module docstring).

    Parameters
    ----------
    P, Q : Ragged
    carrier : {'similarity', 'rigid', 'none'}
        'none' registers nothing (the identity, with an infinite residual).
    scale : ndarray, shape (C,)
        Size of each pair (a registration moving nothing by more than ``IDENTITY`` of it is none).

    Returns
    -------
    motions : Motions
    R : Ragged
        The registered P.
    residual : ndarray, shape (C,)
        See :func:`similarities`.
    """
    n = len(P)
    if carrier == "none":
        a, b, residual = np.ones(n, dtype=complex), np.zeros(n, dtype=complex), np.full(n, np.inf)
    else:
        a, b, residual = similarities(P, Q)
    R = Ragged(from_complex(a[P.owner] * as_complex(P.pts) + b[P.owner]), P.offsets, P.closed)
    moving = (carrier != "none") & ~((np.abs(a - 1) <= tol.IDENTITY) & (np.abs(b) <= tol.IDENTITY * scale))
    kind = carrier if carrier != "none" else "similarity"
    return Motions(a, b, moving, as_complex(Q.centroids()), kind), R, residual
