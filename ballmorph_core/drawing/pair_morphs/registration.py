"""Registration and carrier motions (paper section 1.4).

The paper's ball-morph needs strokes that share both endpoints, or nested loops. An animator's
keys rarely are: an arm turns and bends, a ball moves and grows. We *register* P onto Q with a
map ``S`` (``z -> A z + b``), ball-morph between the registered ``S(P)`` and ``Q``, and move the
result along a *carrier* that undoes the registration progressively::

    in-between(t) = S_t(S^-1(F(t))),  F = ball-morph from S(P) to Q,  S_0 = identity,  S_1 = S.

**The fit.** ``A`` is a similarity (rotation and uniform scale) fitted by least squares between
uniform arc-length samples of both curves (complex Procrustes): for loops over every cyclic
shift at once (FFT cross-correlation), for strokes from end to end, and for a stroke that is
nearly closed (an outline drawn open) also as a loop, so that a start moved along the outline is
a shift, not a turn. A stroke's endpoint the two keys share (a shoulder) is a pivot the fit turns
about. Among fits that are equally good, a smaller turn wins; a worse fit never does. A loop
whose shape is squashed or stretched (a ball landing) gets an affine ``A`` from the second
moments of its area, when that explains the shape far better than a similarity.

**The carrier** (``S_t``). ``A = R U`` (a rotation by ``theta`` times a symmetric stretch ``U``)
is interpolated as ``M_t = R(t theta) ((1 - t) I + t U)``: uniform turning, linear scale (a
circle of radius 1 shrinking to 0.5 has radius 0.75 halfway), no easing of its own. It turns and
stretches about a *pivot* ``p`` that moves straight to its image: ``S_t(z) = p_t + M_t (z - p)``.
The pivot is the fixed point of ``S`` (the shoulder of a swinging arm, the hand at its end
follows on an arc) when that point lies near the stroke, else the stroke's centroid (a ball
moving while it grows advances evenly). ``'rigid'`` carries only the turn and the move: the
scale is left to the ball-morph.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ... import tolerances as tol
from ...geometry.polyline import signed_area
from ...geometry.procrustes import cyclic_correlation, similarity_fits, uniform_samples
from ...geometry.ragged import Ragged
from ...geometry.similarity import Similarity, as_complex, from_complex
from .riding import Rides
from .sliding import slide

__all__ = [
    "Fits",
    "similarity_matrices",
    "fit_pairs",
    "stretch_fits",
    "identity_residual",
    "moved_curves",
    "Motions",
    "motions",
    "riding_fits",
    "endpoint_similarity",
    "fit_similarity",
]

#: Uniform samples per curve for the least-squares fits.
FIT_SAMPLES = 128

#: Distinct fits (local minima over the loop's start) whose normalised residuals are within
#: this of the best are equally good: a circle, an ellipse turned by half a turn. The one
#: closest to the drawing's turn wins (a hand at the end of a swinging arm turns with it).
EQUAL_TURNS = 1e-3

#: A stroke whose endpoints are closer than this fraction of its length is also fitted as a
#: loop (a head outline drawn open).
NEARLY_CLOSED = 0.25

#: The affine fit of a loop replaces the similarity when its residual is below this fraction of
#: the similarity's, and its stretch ratio within ``1 / tol.MAX_STRETCH .. tol.MAX_STRETCH``.
AFFINE_GAIN = 0.5

#: Pairs of strokes fitted sliding along each other at a time (:func:`.sliding.slide`).
SLIDE_BATCH = 256

#: The fixed point of a registration is the carrier's pivot when it lies within this many sizes
#: (bounding-box diagonal of the pair) of the stroke's centroid; beyond twice that, the
#: centroid is; in between, a blend.
PIVOT_REACH = 1.5


@dataclass
class Fits:
    """Registrations of a batch of pairs: ``z -> A z + b`` takes each P onto its Q.

    Attributes
    ----------
    A : ndarray, shape (C, 2, 2)
    b : ndarray, shape (C, 2)
    residual : ndarray, shape (C,)
        RMS distance left between the fitted samples (0 when registration makes them coincide).
    """

    A: np.ndarray
    b: np.ndarray
    residual: np.ndarray


def similarity_matrices(a):
    """2x2 matrices of complex multiplications ``z -> a z``, shape (C, 2, 2)."""
    a = np.asarray(a, dtype=complex)
    # Filled entry by entry: four nested np.stack calls were a sixth of a carrier's frame.
    out = np.empty(a.shape + (2, 2))
    out[..., 0, 0], out[..., 1, 1] = a.real, a.real
    out[..., 1, 0] = a.imag
    np.negative(a.imag, out=out[..., 0, 1])
    return out


def _loop_fits(xp, xq, turn=0.0):
    """Best similarity over every cyclic shift of Q's samples: ``(a, b, residual)`` per row.

    Complex Procrustes: with centred samples, ``a = <p, q_s> / <p, p>`` and the residual is
    ``|q|^2 - |<p, q_s>|^2 / |p|^2``; ``<p, q_s>`` for every shift ``s`` is one circular
    cross-correlation. Among fits equally good (a symmetric shape: its residual's local minima
    within ``EQUAL_TURNS`` of the best; any shift within ``tol.EQUAL_FIT``), the one turning closest
    to ``turn`` wins (radians, scalar or shape (L,): the drawing's own turn, else 0).
    """
    cp, cq = xp.mean(axis=1), xq.mean(axis=1)
    p, q = xp - cp[:, None], xq - cq[:, None]
    norm_p = np.maximum(np.sum(np.abs(p) ** 2, axis=1), tol.TINY)
    norm_q = np.maximum(np.sum(np.abs(q) ** 2, axis=1), tol.TINY)
    corr = cyclic_correlation(p, q)
    fit = 1.0 - np.abs(corr) ** 2 / (norm_p * norm_q)[:, None]
    best = fit.min(axis=1, keepdims=True)
    minimum = (fit <= np.roll(fit, 1, axis=1)) & (fit <= np.roll(fit, -1, axis=1))
    equal = (fit <= best + tol.EQUAL_FIT) | (minimum & (fit <= best + EQUAL_TURNS))
    off = np.where(equal, np.abs(np.angle(corr * np.exp(-1j * np.reshape(turn, (-1, 1))))), np.inf)
    # Turns equal but for round-off (a symmetric loop turned a quarter either way): the first
    # shift, whatever the drawing's scale does to the last digits.
    s = np.argmax(off <= off.min(axis=1, keepdims=True) + tol.ROUNDOFF, axis=1)
    rows = np.arange(len(xp))
    a = corr[rows, s] / norm_p
    k = xp.shape[1]
    residual = np.sqrt(np.maximum(norm_q - np.abs(corr[rows, s]) ** 2 / norm_p, 0.0) / k)
    return a, cq - a * cp, residual


def _stroke_fits(xp, xq, pin_start, pin_end):
    """Best similarity of strokes sample to sample (end to end): ``(a, b, residual)`` per row.

    A pinned endpoint (shared by both keys) is the centre the fit turns and scales about.
    """
    cp, cq = xp.mean(axis=1), xq.mean(axis=1)
    cp = np.where(pin_start, xp[:, 0], np.where(pin_end, xp[:, -1], cp))
    cq = np.where(pin_start, xq[:, 0], np.where(pin_end, xq[:, -1], cq))
    p, q = xp - cp[:, None], xq - cq[:, None]
    a, _ = similarity_fits(p, q)
    residual = np.sqrt(np.mean(np.abs(a[:, None] * p - q) ** 2, axis=1))
    return a, cq - a * cp, residual


def shifted_distance(xp, xq):
    """RMS distance between loop samples, at the cyclic shift of Q's that brings them closest, shape (L,)."""
    dot = cyclic_correlation(xp, xq).real
    sq = (np.sum(np.abs(xp) ** 2, axis=1) + np.sum(np.abs(xq) ** 2, axis=1))[:, None] - 2.0 * dot
    return np.sqrt(np.maximum(sq.min(axis=1), 0.0) / xp.shape[1])


def identity_residual(P, Q):
    """RMS distance between P's and Q's uniform samples as they lie (loops: the best shift), shape (C,)."""
    k, out = FIT_SAMPLES, np.zeros(len(P))
    for loop, index in ((True, np.flatnonzero(P.closed)), (False, np.flatnonzero(~P.closed))):
        if len(index):
            xp, xq = uniform_samples(P, index, k), uniform_samples(Q, index, k)
            out[index] = shifted_distance(xp, xq) if loop else np.sqrt(np.mean(np.abs(xp - xq) ** 2, axis=1))
    return out


def _area_moments(rg, index):
    """Area centroid and second moments of loops ``index``: ``(centre (L, 2), cov (L, 2, 2))``."""
    sub = rg.take(index)
    if not len(index):
        return np.zeros((0, 2)), np.zeros((0, 2, 2))
    # Every loop's vertices with their successors (the last one's is its first), summed per loop.
    x, y = sub.pts[:, 0], sub.pts[:, 1]
    after = np.maximum(sub.nxt, 0)
    xn, yn = x[after], y[after]
    cross = x * yn - xn * y

    def total(v):
        return np.bincount(sub.owner, v, minlength=len(index))

    area = 0.5 * total(cross)
    starts = np.minimum(sub.offsets[:-1], max(len(x) - 1, 0))
    ptp = [np.maximum.reduceat(v, starts) - np.minimum.reduceat(v, starts) for v in (x, y)]
    flat = ~(np.abs(area) > tol.ROUNDOFF * (ptp[0] * ptp[1] + tol.TINY)) | (sub.n < 3)
    area = np.where(flat, 1.0, area)
    cx, cy = total((x + xn) * cross) / (6 * area), total((y + yn) * cross) / (6 * area)
    sxx = total((x * x + x * xn + xn * xn) * cross) / (12 * area) - cx * cx
    syy = total((y * y + y * yn + yn * yn) * cross) / (12 * area) - cy * cy
    sxy = total((x * yn + 2 * x * y + 2 * xn * yn + xn * y) * cross) / (24 * area) - cx * cy
    out_c = np.where(flat[:, None], 0.0, np.c_[cx, cy])
    out_m = np.stack([np.c_[sxx, sxy], np.c_[sxy, syy]], axis=1)
    out_m[flat] = np.nan
    return out_c, out_m


def _sqrtm(m):
    """Symmetric square roots and inverse square roots of 2x2 covariances, shape (L, 2, 2) each."""
    w, v = np.linalg.eigh(m)
    w = np.maximum(w, tol.TINY)
    root = np.einsum("lij,lj,lkj->lik", v, np.sqrt(w), v)
    inv = np.einsum("lij,lj,lkj->lik", v, 1 / np.sqrt(w), v)
    return root, inv


def _affine_loops(P, Q, index, res_sim, xp, xq):
    """Affine registrations of loops ``index`` whose area moments say they are squashed or
    stretched (``xp``, ``xq``: their uniform samples, complex, shape (L, k); ``res_sim``: their
    similarities' residuals, shape (L,)).

    ``A = C_Q^(1/2) R C_P^(-1/2)``: whiten both loops by their second moments of area, fit the
    turn ``R`` between the whitened loops (over every cyclic shift), colour back. Kept where the
    residual drops below ``AFFINE_GAIN`` of the similarity's and the stretch is moderate.

    Returns
    -------
    use : ndarray of bool, shape (L,)
    A : ndarray, shape (L, 2, 2)
    b : ndarray, shape (L, 2)
    residual : ndarray, shape (L,)
    """
    (cp, mp), (cq, mq), ok = _loop_moments(P, Q, index)
    root_q, inv_q = _sqrtm(mq)
    _, inv_p = _sqrtm(mp)
    wp = as_complex(np.einsum("lij,lkj->lki", inv_p, from_complex(xp) - cp[:, None]))
    wq = as_complex(np.einsum("lij,lkj->lki", inv_q, from_complex(xq) - cq[:, None]))
    a, _, _ = _loop_fits(wp, wq)
    rot = similarity_matrices(a / np.maximum(np.abs(a), tol.TINY))
    A = root_q @ rot @ inv_p
    b = cq - np.einsum("lij,lj->li", A, cp)
    fitted = as_complex(np.einsum("lij,lkj->lki", A, from_complex(xp)) + b[:, None])
    residual = shifted_distance(fitted, xq)
    sv = np.linalg.svd(A, compute_uv=False)
    moderate = (sv[:, 0] <= tol.MAX_STRETCH * np.maximum(sv[:, 1], tol.TINY)) & (np.linalg.det(A) > 0)
    return ok & moderate & (residual < AFFINE_GAIN * res_sim), A, b, residual


def stretch_fits(P, Q):
    """The squash or stretch without turn that takes each loop P onto its Q (the issue-38
    alternative to a large turn): the symmetric positive ``A`` with ``A C_P A = C_Q`` from the
    loops' second moments of area, about their area centroids (the least-travel map between
    their moment ellipses; exact for any loop stretched along any axis). Its residual is the
    stretched loop's own uniform samples' against Q's.

    Parameters
    ----------
    P, Q : Ragged
        Loops, same number.

    Returns
    -------
    Fits
        Residual inf where a loop has no area to fit (a sliver).
    """
    (cp, mp), (cq, mq), ok = _loop_moments(P, Q, np.arange(len(P)))
    A = _stretch_maps(mp, mq)
    b = cq - np.einsum("lij,lj->li", A, cp)
    return Fits(A, b, np.where(ok, _registered_residual(P, Q, A, b), np.inf))


def _loop_moments(P, Q, index):
    """Both loops' area centroids and second moments (:func:`_area_moments`) of pairs ``index``,
    and which pairs have an area to fit: ``(cp, mp), (cq, mq), ok``; the moments of the others
    (slivers: second moments of rank one) are the identity."""
    (cp, mp), (cq, mq) = _area_moments(P, index), _area_moments(Q, index)
    ok = np.all(np.isfinite(mp), axis=(1, 2)) & np.all(np.isfinite(mq), axis=(1, 2))
    for m in (mp, mq):
        m[~ok] = np.eye(2)
        w = np.linalg.eigvalsh(m)
        ok &= w[:, 0] > tol.ROUNDOFF * np.maximum(np.abs(w[:, 1]), tol.TINY)
    eye = np.eye(2)
    return (cp, np.where(ok[:, None, None], mp, eye)), (cq, np.where(ok[:, None, None], mq, eye)), ok


def _stretch_maps(mp, mq):
    """The one symmetric positive ``A`` with ``A C_P A = C_Q`` for each pair of second moments
    (L, 2, 2): the least-travel map between the moment ellipses (Gaussian optimal transport),
    shape (L, 2, 2). ``C_Q^(1/2) C_P^(-1/2)`` also takes one ellipse onto the other, but turns
    it unless both share their axes."""
    root_p, inv_p = _sqrtm(mp)
    root_mid, _ = _sqrtm(root_p @ mq @ root_p)
    return inv_p @ root_mid @ inv_p


def moved_curves(P, A, b):
    """The curves P, each under its own map ``z -> A z + b`` (A (C, 2, 2), b (C, 2)), a Ragged."""
    moved = np.einsum("kij,kj->ki", np.take(A, P.owner, axis=0), P.pts) + np.take(b, P.owner, axis=0)
    return Ragged(moved, P.offsets, P.closed)


def _registered_residual(P, Q, A, b):
    """The residual of affine fits ``z -> A z + b`` (A (C, 2, 2), b (C, 2)) of curves P onto Q:
    the registered curves' own uniform samples against Q's (:func:`identity_residual`), shape (C,)."""
    return identity_residual(moved_curves(P, A, b), Q)


def fit_pairs(P, Q, affine=True, turn=0.0, scale=1.0):
    """Registrations of every P of a batch onto its Q (see the module docstring).

    Parameters
    ----------
    P, Q : Ragged
        Same number of curves and closed flags; each Q runs the same way as its P.
    affine : bool
        Allow affine fits of squashed or stretched loops.
    turn : float
        The drawing's own turn (radians): symmetric loops turn closest to it.
    scale : float
        The drawing's own scale: strokes sliding along each other start at it (see
        :mod:`.sliding`).

    Returns
    -------
    Fits
    """
    n, k = len(P), FIT_SAMPLES
    a, b = np.ones(n, dtype=complex), np.zeros(n, dtype=complex)
    residual = np.zeros(n)
    loops, opened = np.flatnonzero(P.closed), np.flatnonzero(~P.closed)
    if len(loops):
        loop_samples = uniform_samples(P, loops, k), uniform_samples(Q, loops, k)
        a[loops], b[loops], residual[loops] = _loop_fits(*loop_samples, turn)
    if len(opened):
        a[opened], b[opened], residual[opened] = _open_fits(P, Q, opened, k, turn, scale)
    A, bb = similarity_matrices(a), from_complex(b)
    if affine and len(loops):
        use, A_aff, b_aff, res_aff = _affine_loops(P, Q, loops, residual[loops], *loop_samples)
        A[loops[use]], bb[loops[use]], residual[loops[use]] = A_aff[use], b_aff[use], res_aff[use]
    return Fits(A, bb, residual)


def _open_fits(P, Q, index, k, turn, scale):
    """Strokes: end to end (about a shared endpoint when there is one), as loops when nearly
    closed, or sliding along each other, whichever fits clearly better."""
    xp, xq = uniform_samples(P, index, k), uniform_samples(Q, index, k)
    size = np.maximum(np.abs(xp - xp.mean(axis=1, keepdims=True)).max(axis=1), tol.TINY)
    pin_start = np.abs(xp[:, 0] - xq[:, 0]) <= tol.SHARED_ENDPOINT * size
    pin_end = ~pin_start & (np.abs(xp[:, -1] - xq[:, -1]) <= tol.SHARED_ENDPOINT * size)
    a, b, residual = _stroke_fits(xp, xq, pin_start, pin_end)
    gap_p = np.abs(xp[:, -1] - xp[:, 0]) / np.maximum(P.length[index], tol.TINY)
    gap_q = np.abs(xq[:, -1] - xq[:, 0]) / np.maximum(Q.length[index], tol.TINY)
    round_ = (gap_p < NEARLY_CLOSED) & (gap_q < NEARLY_CLOSED) & ~pin_start & ~pin_end
    if round_.any():
        la, lb, lr = _loop_fits(xp[round_], xq[round_], turn)
        better = lr < residual[round_] - tol.EQUAL_FIT * size[round_]
        rows = np.flatnonzero(round_)[better]
        a[rows], b[rows], residual[rows] = la[better], lb[better], lr[better]
    # A few hundred pairs at a time: the sliding fit's projection tables grow with the pairs it
    # holds (5,000 strokes at once peaked at 390 MiB); each pair's fit is its own.
    for start in range(0, len(index), SLIDE_BATCH):
        rows = slice(start, start + SLIDE_BATCH)  # views: slide updates a, b, residual in place
        slide(xp[rows], Q, index[rows], size[rows], a[rows], b[rows], residual[rows], scale)
    return a, b, residual


# ------------------------------------------------------------------ carrier motions


def _polar(A):
    """``A = R(theta) U``: turn angles (C,) and symmetric stretches (C, 2, 2)."""
    u, s, vt = np.linalg.svd(A)
    rot = u @ vt
    theta = np.arctan2(rot[:, 1, 0], rot[:, 0, 0])
    stretch = np.einsum("lji,lj,ljk->lik", vt, s, vt)
    return theta, stretch


@dataclass
class Motions:
    """The carrier motions of a batch of pairs (see the module docstring).

    Attributes
    ----------
    A, b : ndarray, shapes (C, 2, 2), (C, 2)
        Each pair's registration of P onto Q.
    theta : ndarray, shape (C,)
        The turn of ``A`` (in (-pi, pi]).
    stretch : ndarray, shape (C, 2, 2)
        Its symmetric stretch (``A = R(theta) stretch``).
    pivot : ndarray, shape (C, 2)
        The point of P the carrier turns and stretches about (it moves straight to its image).
    moving : ndarray of bool, shape (C,)
        Pairs whose carrier is not the identity.
    kind : {'similarity', 'rigid'}
    """

    A: np.ndarray
    b: np.ndarray
    theta: np.ndarray
    stretch: np.ndarray
    pivot: np.ndarray
    moving: np.ndarray
    kind: str = "similarity"

    @cached_property
    def _steady(self):
        """The parts of :meth:`at` that do not depend on ``t``: ``A^-1`` (C, 2, 2) and the
        pivot's image ``A p + b`` (C, 2); made at the first evaluation (not a field: :meth:`put`
        drops it)."""
        return _inverses(self.A), np.einsum("lij,lj->li", self.A, self.pivot) + self.b

    def partial(self, t):
        """``S_t(z) = M z + c`` of every pair: ``(M (C, 2, 2), c (C, 2))``."""
        t = float(t)
        rot = similarity_matrices(np.exp(1j * t * self.theta))
        M = rot @ ((1.0 - t) * np.eye(2) + t * self.stretch)
        pivot_t = (1.0 - t) * self.pivot + t * self._steady[1]
        return M, pivot_t - np.einsum("lij,lj->li", M, self.pivot)

    def at(self, t):
        """The carrier ``C_t = S_t o S^-1`` of every pair: ``(M (C, 2, 2), c (C, 2))``."""
        M, c = self.partial(t)
        Mi = M @ self._steady[0]
        return Mi, c - np.einsum("lij,lj->li", Mi, self.b)

    def take(self, rows):
        """The motions of some pairs (Motions)."""
        return Motions(
            self.A[rows],
            self.b[rows],
            self.theta[rows],
            self.stretch[rows],
            self.pivot[rows],
            self.moving[rows],
            self.kind,
        )

    def put(self, rows, motions):
        """Another batch's motions (Motions) written in at pairs ``rows``, its kind taken too."""
        for name in ("A", "b", "theta", "stretch", "pivot", "moving"):
            getattr(self, name)[rows] = getattr(motions, name)
        self.kind = motions.kind
        self.__dict__.pop("_steady", None)  # of the rows before: made again when asked

    @classmethod
    def identity(cls, n, kind="similarity"):
        eye = np.tile(np.eye(2), (n, 1, 1))
        return cls(eye, np.zeros((n, 2)), np.zeros(n), eye.copy(), np.zeros((n, 2)), np.zeros(n, bool), kind)


def _reach_scales(P, fits, scale, drawing):
    """The size each pair's pivot reach is measured in, shape (C,): the pair's own, or the
    drawing's for pairs turning with a drawing that turns."""
    if drawing is None or abs(drawing.turn) <= tol.TURN_AGREE or not len(P):
        return scale
    theta, _ = _polar(fits.A)
    agree = np.abs(np.angle(np.exp(1j * (theta - drawing.turn)))) <= tol.TURN_AGREE
    size = float(np.linalg.norm(P.pts.max(axis=0) - P.pts.min(axis=0)))
    return np.where(agree, np.maximum(scale, size), scale)


def _inverses(A):
    """Inverses of invertible 2 x 2 matrices, shape (L, 2, 2), in closed form: np.linalg.inv of
    100 of them took 100-190 ms on a busy machine with OpenBLAS's default threads (0.05 ms with one)."""
    det = A[:, 0, 0] * A[:, 1, 1] - A[:, 0, 1] * A[:, 1, 0]
    adj = np.stack([np.stack([A[:, 1, 1], -A[:, 0, 1]], axis=-1), np.stack([-A[:, 1, 0], A[:, 0, 0]], axis=-1)], axis=1)
    return adj / det[:, None, None]


def _pivots(P, fits, scale):
    """The fixed point of each registration where it lies near its stroke, else the centroid."""
    centre = P.centroids()
    IA = np.eye(2) - fits.A
    det = IA[:, 0, 0] * IA[:, 1, 1] - IA[:, 0, 1] * IA[:, 1, 0]
    safe = np.abs(det) > tol.ROUNDOFF
    fixed = np.einsum("lij,lj->li", _inverses(np.where(safe[:, None, None], IA, np.eye(2))), fits.b)
    far = np.linalg.norm(fixed - centre, axis=1) / np.maximum(scale, tol.TINY)
    w = np.where(safe, np.clip(2.0 - far / PIVOT_REACH, 0.0, 1.0), 0.0)
    return centre + w[:, None] * (fixed - centre)


def _drawing_turns(P, fits, moving, rides):
    """``fits`` (Fits) where the moving loops with no orientation of their own take the turn
    they ride (``rides``, Rides: their group's or the drawing's; their own scale, their
    centroid's image kept): a valve on a turning wheel rides on its arc instead of crossing the
    wheel straight. The same ``fits`` when none rides."""
    if not len(P):
        return fits
    A = fits.A
    # Similarities only: an affine fit's stretch (a ball squashing) is the loop's own.
    conformal = np.isclose(A[:, 0, 0], A[:, 1, 1]) & np.isclose(A[:, 0, 1], -A[:, 1, 0])
    free = moving & conformal & P.closed & ~np.isnan(rides.a)
    if not free.any():
        return fits
    A, b = fits.A.copy(), fits.b.copy()
    rows = np.flatnonzero(free)
    centre = P.centroids()[rows]
    image = np.einsum("lij,lj->li", A[rows], centre) + b[rows]
    scale = np.sqrt(np.abs(np.linalg.det(A[rows])))
    A[rows] = similarity_matrices(scale * np.exp(1j * np.angle(rides.a[rows])))
    b[rows] = image - np.einsum("lij,lj->li", A[rows], centre)
    return Fits(A, b, fits.residual)


def riding_fits(P, Q, a):
    """Registrations of pairs with no shape to fit (a dot and a dot: strokes of fewer than two
    distinct points): each the motion it rides (``a``, :attr:`Rides.a`: its group's or the
    drawing's turn and scale), each P's centroid onto its Q's (Fits); and which pairs they move
    (those that ride: a straight move says as much for the others), shape (C,).

    Parameters
    ----------
    P, Q : Ragged
        The pairs' points (one location each, perhaps repeated).
    a : ndarray of complex, shape (C,)
    """
    moving = ~np.isnan(a)
    A = similarity_matrices(np.where(moving, a, 1.0))
    b = Q.centroids() - np.einsum("lij,lj->li", A, P.centroids())
    return Fits(A, b, np.zeros(len(P))), moving


def motions(P, fits, kind, scale, moving, drawing=None, turned=None, rides=None):
    """The carrier motions of registered pairs (Motions).

    Parameters
    ----------
    P : Ragged
        The first curves (before registration).
    fits : Fits
    kind : {'similarity', 'rigid'}
        'rigid' carries the turn and the move only (the registration is made rigid about the
        pivot: the ball-morph does the scaling).
    scale : ndarray, shape (C,)
        Size of each pair.
    moving : ndarray of bool, shape (C,)
        Pairs that get a carrier (the others: the identity).
    drawing : Similarity, optional
        The keys' overall motion: a pair turning with it may turn about a farther pivot, and a
        loop with no orientation of its own turns as it does (:mod:`.riding`).
    turned : ndarray of bool, shape (C,), optional
        Pairs whose turn is given (hinted: the animator said where a point goes): they keep
        it, oriented or not.
    rides : Rides, optional
        What each pair rides (default: :meth:`Rides.of_drawing`). Pairs turning with their
        group (within ``tol.TURN_AGREE``) turn about its pivot.
    """
    rides = Rides.of_drawing(P, drawing) if rides is None else rides
    fits = _drawing_turns(P, fits, moving if turned is None else moving & ~turned, rides)
    theta, stretch = _polar(fits.A)
    pivot = _pivots(P, fits, _reach_scales(P, fits, scale, drawing))
    grouped = ~np.isnan(rides.group)
    grouped &= np.abs(np.angle(np.exp(1j * theta) * np.conj(np.where(grouped, rides.group, 1.0)))) <= tol.TURN_AGREE
    pivot[grouped] = rides.pivot[grouped]
    A, b = fits.A.copy(), fits.b.copy()
    if kind == "rigid":
        target = np.einsum("lij,lj->li", fits.A, pivot) + fits.b
        A = similarity_matrices(np.exp(1j * theta))
        b = target - np.einsum("lij,lj->li", A, pivot)
        stretch = np.tile(np.eye(2), (len(theta), 1, 1))
    eye = np.eye(2)
    A = np.where(moving[:, None, None], A, eye)
    b = np.where(moving[:, None], b, 0.0)
    theta = np.where(moving, theta, 0.0)
    stretch = np.where(moving[:, None, None], stretch, eye)
    return Motions(A, b, theta, stretch, pivot, moving.copy(), kind)


def endpoint_similarity(P, Q):
    """The similarity mapping P's endpoints onto Q's (Similarity).

    Degenerate strokes whose endpoints coincide get the translation of their first points.
    """
    zp, zq = as_complex(np.asarray(P, dtype=np.float64)), as_complex(np.asarray(Q, dtype=np.float64))
    dp, dq = zp[-1] - zp[0], zq[-1] - zq[0]
    a = dq / dp if abs(dp) > tol.ROUNDOFF * (abs(zp[0]) + 1) and abs(dq) > tol.ROUNDOFF * (abs(zq[0]) + 1) else 1.0
    return Similarity(complex(a), complex(zq[0] - a * zp[0]))


def fit_similarity(P, Q, closed=True):
    """The least-squares registration of one curve onto another, as a Similarity (a batch of one
    of :func:`fit_pairs`, without the affine fit). Loops drawn opposite ways (the signs of
    their areas) are fitted with Q read backwards, as the stroke matching pairs them."""
    if closed and signed_area(np.asarray(P, float)) * signed_area(np.asarray(Q, float)) < 0:
        Q = np.asarray(Q)[::-1]
    fits = fit_pairs(Ragged.from_list([P], [closed]), Ragged.from_list([Q], [closed]), affine=False)
    return Similarity(complex(fits.A[0, 0, 0] + 1j * fits.A[0, 1, 0]), complex(fits.b[0, 0] + 1j * fits.b[0, 1]))
