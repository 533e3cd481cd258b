"""Candidate maximal disks on a polyline (paper section 5.2, equations 3-5).

For a sample ``x`` of one curve with unit normal ``n`` into the gap, the disk of centre
``x + r n`` and radius ``r`` grows until it touches the other curve. On a polyline the candidates
are its vertices and edges:

* a vertex ``v``: ``r = |v - x|^2 / (2 (v - x) . n)``, valid when the denominator is positive;
* an edge ``c -> d`` with unit normal ``N`` into the gap: ``r = ((x - c) . N) / (1 - n . N)``,
  contact ``x + r n - r N``, discarded when the contact is off the edge or ``1 - n . N`` is below
  ``PARALLEL`` (an edge facing the same way as ``n``: no finite disk touches it).
"""

import numpy as np

from ..geometry.ragged import group_argmin, ragged_arange

__all__ = ["tangent_disks", "disk_between"]

#: ``1 - n_P . N_Q`` below this means the edge faces the same way as the normal at p: the
#: tangent disk would be infinite (the paper's parallel singular case).
PARALLEL = 1e-12

#: Slack, as a fraction of the edge length, when deciding that a contact lies on an edge.
ON_EDGE = 1e-9

#: Levels of :func:`disk_between`'s bisection decided per evaluation of the disks (every
#: midpoint they may visit, 2**levels - 1 per row, evaluated at once: a bridge is one row, and
#: evaluating it alone level after level is all call overhead).
BISECTION_LEVELS = 5


def tangent_disks(x, n, a, b, N, eps):
    """Smallest disk tangent at ``x`` (normal ``n``) touching edge ``a -> b`` (normal ``N``) or its ends.

    Parameters
    ----------
    x, n : ndarray, shape (2, K)
        Samples and their unit gap normals, coordinate by coordinate (rows ``x`` and ``y``:
        contiguous rows make every step one pass over plain arrays).
    a, b, N : ndarray, shape (2, K)
        One edge per sample and its unit gap normal, likewise.
    eps : float or ndarray, shape (K,)
        Length tolerance (a vertex this close to ``x`` is touched by a zero disk).

    Returns
    -------
    r : ndarray, shape (K,)
        Radius (inf where no disk touches the edge).
    u : ndarray, shape (K,)
        The contact's position along the edge in [0, 1].
    """
    # One errstate for the whole computation (entering one costs as much as a few passes over
    # a level's candidates): the divisions by zero and NaN are all masked afterwards.
    with np.errstate(divide="ignore", invalid="ignore"):
        return _tangent_disks(x, n, a, b, N, eps)


def _tangent_disks(x, n, a, b, N, eps):
    """:func:`tangent_disks`, the floating-point errors it masks ignored by the caller."""
    # In place where it can be (every full-size temporary is a fresh allocation), each value
    # by the same operations in the same order as the plain expressions: bitwise the same.
    # Masked values are set by np.putmask (a third of the work of a boolean-mask assignment).
    (xx, xy), (nx, ny), (ax, ay), (Nx, Ny) = x, n, a, N
    dx, dy = b[0] - ax, b[1] - ay
    len2 = dx * dx
    len2 += dy * dy
    wx, wy = xx - ax, xy - ay  # x - a
    # Edge (eq. 4, 5).
    r_e = wx * Nx
    r_e += wy * Ny
    den = nx * Nx
    den += ny * Ny
    np.subtract(1.0, den, out=den)
    r_e /= den
    # Not ~(den > PARALLEL): where den is NaN, so is r_e, which the next test sets to inf too.
    np.putmask(r_e, den <= PARALLEL, np.inf)
    unreached = r_e >= -eps
    np.logical_not(unreached, out=unreached)
    np.maximum(r_e, 0.0, out=r_e)
    np.putmask(r_e, unreached, np.inf)
    step = np.where(np.isfinite(r_e), r_e, 0.0)
    u = nx - Nx
    u *= step
    u += xx
    u -= ax
    u *= dx
    uy = ny - Ny
    uy *= step
    uy += xy
    uy -= ay
    uy *= dy
    u += uy
    u /= len2
    off_edge = u >= -ON_EDGE
    off_edge &= u <= 1 + ON_EDGE
    np.logical_not(off_edge, out=off_edge)
    np.putmask(r_e, off_edge, np.inf)
    np.clip(u, 0.0, 1.0, out=u)
    np.putmask(u, np.isnan(u), 0.0)
    # Vertices (eq. 3): r = |v - x|^2 / (2 (v - x) . n); for a, v - x is -(x - a), exactly.
    best_r, best_u = r_e, u
    for (ex, ey), twice, uu in (((wx, wy), -2.0, 0.0), ((b[0] - xx, b[1] - xy), 2.0, 1.0)):
        dist2 = ex * ex
        dist2 += ey * ey
        den_v = ex * nx
        den_v += ey * ny
        den_v *= twice
        r_v = dist2 / den_v
        # Not ~(den_v > 0): where den_v is NaN, so is r_v, never less than best_r (as inf).
        np.putmask(r_v, den_v <= 0, np.inf)
        np.putmask(r_v, dist2 <= eps * eps, 0.0)
        better = r_v < best_r
        np.putmask(best_r, better, r_v)
        np.putmask(best_u, better, uu)
    return best_r, best_u


def _smallest_in_windows(x, n, edges, windows, eps):
    """Smallest tangent disk at each sample over its own window of ``edges`` (a, b, N): radii
    and contacts (``eps`` a float, or one per sample)."""
    a, b, N = edges
    counts = np.array([len(w) for w in windows])
    owner, _ = ragged_arange(counts)
    e = np.concatenate(windows)
    eps = eps if np.ndim(eps) == 0 else eps[owner]
    rr, uu = tangent_disks(x[owner].T, n[owner].T, a[e].T, b[e].T, N[e].T, eps)
    best = group_argmin(rr, owner, len(x))
    return rr[best], a[e[best]] + uu[best][:, None] * (b[e[best]] - a[e[best]])


def disk_between(ends, edges, windows, eps, iterations=40):
    """Disks tangent to a curve between two samples that touch two other edge windows equally.

    For each row, the tangent point moves along the segment from ``x0`` to ``x1`` (normal
    interpolated) until the smallest disk touching edges ``window_a`` equals the smallest one
    touching ``window_b`` (bisection): the maximal disk that touches the other curve twice,
    used to bridge an incompatible stretch (paper section 7, relative blending).

    Parameters
    ----------
    ends : tuple of ndarray, each shape (J, 2)
        ``(x0, n0, x1, n1)``: the two samples and their unit gap normals.
    edges : tuple of ndarray, each shape (E, 2)
        ``(a, b, N)``: edges ``a -> b`` of the other curve with their gap normals.
    windows : tuple of list of ndarray of int
        ``(window_a, window_b)``: edge indices per row.
    eps : float or ndarray, shape (J,)
        Length tolerance (per row: rows of several pairs, each with its own, are each
        bisected as alone).
    iterations : int

    Returns
    -------
    x, n, r : ndarray, shapes (J, 2), (J, 2), (J,)
        Tangent point, normal and radius of each disk.
    qa, qb : ndarray, shape (J, 2)
        Its contacts in the two windows.
    """
    x0, n0, x1, n1 = ends
    lo = np.zeros(len(x0))
    hi = np.ones(len(x0))
    step_x, step_n = x1 - x0, n1 - n0

    def evaluate(lam, rows):
        x = x0[rows] + lam[:, None] * step_x[rows]
        n = n0[rows] + lam[:, None] * step_n[rows]
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        row_eps = eps if np.ndim(eps) == 0 else eps[rows]
        return x, n, [_smallest_in_windows(x, n, edges, [w[i] for i in rows], row_eps) for w in windows]

    every = np.arange(len(x0))
    done = 0
    while done < iterations:
        # Every midpoint the next levels may visit, at once (level by level: 1, 2, 4, ... per
        # row); dyadic, so lo + (2k + 1) (hi - lo) / 2^(level + 1) is exactly the midpoint the
        # bisection reaches there, and each row's disks are its own: the same decisions.
        depth = min(BISECTION_LEVELS, iterations - done)
        level = np.repeat(np.arange(depth), 2 ** np.arange(depth))
        k = np.arange(len(level)) - (2**level - 1)
        lam = lo[:, None] + (2 * k + 1) * (hi - lo)[:, None] / 2.0 ** (level + 1)
        _, _, ((ra, _), (rb, _)) = evaluate(lam.ravel(), np.repeat(every, len(level)))
        first_a = (ra < rb).reshape(lam.shape)
        at = np.zeros(len(x0), dtype=np.int64)
        for d in range(depth):
            node = 2**d - 1 + at
            mid, here = lam[every, node], first_a[every, node]
            # Window a is touched first at lo (ra < rb), window b first at hi.
            lo = np.where(here, mid, lo)
            hi = np.where(here, hi, mid)
            at = 2 * at + here
        done += depth
    x, n, ((ra, qa), (rb, qb)) = evaluate((lo + hi) / 2, every)
    return x, n, np.minimum(ra, rb), qa, qb
