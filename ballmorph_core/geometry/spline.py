"""Smooth curves through polyline vertices: the centripetal Catmull-Rom spline and the
interpolating four-point subdivision.

Both pass through every drawn vertex, so resampling or refining a stroke keeps its points where
they were drawn while new points land on the smooth curve the polyline approximates.
"""

import numpy as np

from .. import tolerances as tol
from .vectors import norms

__all__ = ["catmull_rom", "subdivide", "densify", "needs_subdivision"]

#: Interpolating subdivision steps are applied until no edge is longer than this many sample
#: spacings (so coarse, hand-placed polylines become smooth before the PLC ball-map), at most
#: SUBDIVIDE_MAX_STEPS steps (each doubles the vertex count).
SUBDIVIDE_EDGE_RATIO = 4.0
SUBDIVIDE_MAX_STEPS = 4


def catmull_rom(p0, p1, p2, p3, frac):
    """Centripetal Catmull-Rom spline between p1 and p2 at fractions ``frac``.

    Parameters
    ----------
    p0, p1, p2, p3 : ndarray, shape (K, 2)
        Control points (the segment runs from p1 to p2).
    frac : ndarray, shape (K,)

    Returns
    -------
    ndarray, shape (K, 2)
        Passes through p1 at 0 and p2 at 1; the centripetal knots (alpha = 1/2) avoid cusps
        and overshoot on unevenly spaced points.
    """
    floor = tol.ROUNDOFF  # repeated control points: keep the knots distinct
    # Coordinate by coordinate on contiguous (K,) arrays: broadcasting (K, 1) knots against
    # (K, 2) points runs numpy's inner loops two elements long. The same operations in the same
    # order: the same bits.
    (x0, y0), (x1, y1), (x2, y2), (x3, y3) = (
        (np.ascontiguousarray(p[:, 0]), np.ascontiguousarray(p[:, 1])) for p in (p0, p1, p2, p3)
    )
    t1 = np.maximum(norms(x1 - x0, y1 - y0) ** 0.5, floor)
    d12 = np.maximum(norms(x2 - x1, y2 - y1) ** 0.5, floor)
    t2 = t1 + d12
    t3 = t2 + np.maximum(norms(x3 - x2, y3 - y2) ** 0.5, floor)
    t = t1 + frac * d12
    # Barry-Goldman pyramid (t0 = 0).
    out = np.empty((len(t), 2))
    for k, (c0, c1, c2, c3) in enumerate(((x0, x1, x2, x3), (y0, y1, y2, y3))):
        a1 = ((t1 - t) * c0 + t * c1) / t1
        a2 = ((t2 - t) * c1 + (t - t1) * c2) / (t2 - t1)
        a3 = ((t3 - t) * c2 + (t - t2) * c3) / (t3 - t2)
        b1 = ((t2 - t) * a1 + t * a2) / t2
        b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1)
        out[:, k] = ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1)
    return out


def subdivide(curve, closed, steps=1):
    """Interpolating four-point subdivision (Dyn, Levin and Gregory, weight 1/16).

    Every step keeps the existing vertices and inserts one new vertex per edge, so the drawn
    points stay on the curve while the polyline becomes smoother. At a stroke's ends the
    missing neighbour is extrapolated linearly.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool
    steps : int

    Returns
    -------
    ndarray, shape (M, 2)
        ``M = 2^steps N`` for a loop, ``2^steps (N - 1) + 1`` for a stroke.
    """
    out = np.asarray(curve, dtype=np.float64)
    for _ in range(int(steps)):
        if closed:
            a, b, c, d = (np.roll(out, k, axis=0) for k in (1, 0, -1, -2))
        else:
            ext = np.concatenate([[2 * out[0] - out[1]], out, [2 * out[-1] - out[-2]]])
            a, b, c, d = ext[:-3], ext[1:-2], ext[2:-1], ext[3:]
        mid = (9.0 * (b + c) - (a + d)) / 16.0
        n_new = len(out) if closed else len(out) - 1
        res = np.empty((len(out) + n_new, 2))
        res[0::2] = out
        res[1::2] = mid
        out = res
    return out


def needs_subdivision(longest, spacing):
    """Whether curves whose longest edge is ``longest`` are subdivided by :func:`densify` at
    ``spacing`` (scalars or arrays of one shape; NaN counts as needing it), bool."""
    return ~(np.asarray(longest) / (SUBDIVIDE_EDGE_RATIO * np.asarray(spacing)) <= 1)


def densify(curve, closed, spacing):
    """Subdivide a coarse polyline until no edge is much longer than ``spacing``.

    At most ``SUBDIVIDE_MAX_STEPS`` steps; a dense curve is returned unchanged.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool
    spacing : float

    Returns
    -------
    ndarray, shape (M, 2)
    """
    nxt = np.roll(curve, -1, axis=0) if closed else curve[1:]
    longest = float(np.linalg.norm(nxt - curve[: len(nxt)], axis=1).max())
    ratio = longest / (SUBDIVIDE_EDGE_RATIO * spacing)
    steps = min(int(np.ceil(np.log2(ratio))), SUBDIVIDE_MAX_STEPS) if needs_subdivision(longest, spacing) else 0
    return subdivide(curve, closed, steps) if steps else curve
