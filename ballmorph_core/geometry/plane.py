"""The drawing plane: strokes live in 3D, morphs happen in the plane that fits both keys.

Grease Pencil strokes are usually drawn on a canvas plane (Blender's front view: XZ). We fit
the plane through all points of both keys, morph the projected 2D curves, and lift the result
back. Each point's small offset from the plane is kept and interpolated like any attribute, so
slightly non-planar strokes lose nothing; strokes far from planar are reported by the caller.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol

__all__ = ["Plane", "fit_plane"]

#: A fitted drawing plane within this (1 - |cos|) of a world axis plane is taken as that plane,
#: so a drawing on Blender's front canvas maps to plain (x, z) coordinates.
PLANE_AXIS = 1e-6


@dataclass
class Plane:
    """An orthonormal frame ``(origin, u, v, normal)``.

    Attributes
    ----------
    origin, u, v, normal : ndarray, shape (3,)
    """

    origin: np.ndarray
    u: np.ndarray
    v: np.ndarray
    normal: np.ndarray

    def to_2d(self, points):
        """Project points, shape (N, 3) -> coordinates (N, 2) and offsets along the normal (N,)."""
        rel = np.asarray(points, dtype=np.float64).reshape(-1, 3) - self.origin
        return np.stack([rel @ self.u, rel @ self.v], axis=1), rel @ self.normal

    def farthest(self, points):
        """The largest distance of points (N, 3), N > 0, from the plane (float).

        On a world axis plane (the normal a unit axis) it is the largest ``|coordinate -
        origin|`` along the axis: the distances ``|rel @ normal|`` are exactly those (products
        by 0 and 1, sums with zeros), without the projection."""
        points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        axis = np.flatnonzero(self.normal)
        if len(axis) == 1 and abs(self.normal[axis[0]]) == 1.0:
            return float(np.abs(points[:, axis[0]] - self.origin[axis[0]]).max())
        return float(np.abs(self.to_2d(points)[1]).max())

    def to_3d(self, coords, offsets=None, out=None):
        """Lift coordinates (N, 2) (and optional normal offsets (N,)) back to 3D, shape (N, 3)
        (into ``out`` when given)."""
        coords = np.asarray(coords, dtype=np.float64).reshape(-1, 2)
        if offsets is not None:
            offsets = np.asarray(offsets, dtype=np.float64).reshape(-1)
        # Column by column, skipping zero terms: a canvas plane (XZ) is two sums and a fill,
        # several times faster than a (N, 2) @ (2, 3) product on every in-between. Each column
        # is origin + u x + v y + n offset, summed in that order; its first term is written
        # with the origin (one pass less over a column of a fresh array).
        out = np.empty((len(coords), 3)) if out is None else out
        terms = [(coords[:, 0], self.u), (coords[:, 1], self.v)]
        if offsets is not None:
            terms.append((offsets, self.normal))
        for axis in range(3):
            column, first = out[:, axis], True
            for values, direction in terms:
                weight = direction[axis]
                if weight == 0.0:
                    continue
                term = values if weight == 1.0 else weight * values
                if first:
                    np.add(term, self.origin[axis], out=column)
                else:
                    column += term
                first = False
            if first:
                column.fill(self.origin[axis])
        return out


# World-axis frames, preferred when the fitted plane is (nearly) one of them, so a drawing on
# Blender's front canvas (XZ) maps to plain (x, z) coordinates.
_AXIS_FRAMES = (
    (np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), np.array([0, -1.0, 0])),  # front XZ
    (np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), np.array([0, 0, 1.0])),  # top XY
    (np.array([0, 1.0, 0]), np.array([0, 0, 1.0]), np.array([1.0, 0, 0])),  # side YZ
)


#: The SVD's normal of points lying exactly on an axis plane (see :func:`_on_axis_plane`) is
#: far less than this (1 - |cos|) off the axis.
_AXIS_ROUNDOFF = 1e-12
#: Two coordinates' spread whose Gram determinant is at least this fraction of its largest
#: possible value (their singular values' ratio at least its square root) is far from collinear.
_SPREAD = 1e-6


def _on_axis_plane(pts, origin):
    """The world axis (0, 1 or 2) along which every point lies exactly at ``origin``, when the
    other two coordinates spread far from collinear (see ``_SPREAD``); else None.

    Then the fit needs no SVD: the points lie exactly in that axis plane, and the SVD's normal
    (that of the points less round-off, its singular value apart from the others by
    ``sqrt(_SPREAD)`` of the largest) is within round-off over that gap of the axis, so its
    frame is the one :func:`fit_plane` returns (for ``axis_tolerance`` from ``_AXIS_ROUNDOFF``).

    Parameters
    ----------
    pts : ndarray, shape (N, 3)
    origin : ndarray, shape (3,)
    """
    for axis in range(3):
        if np.all(pts[:, axis] == origin[axis]):
            a, b = (pts[:, k] - origin[k] for k in range(3) if k != axis)
            aa, bb, ab = a @ a, b @ b, a @ b
            return axis if aa * bb - ab * ab > _SPREAD * (aa + bb) ** 2 else None
    return None


def fit_plane(points, axis_tolerance=PLANE_AXIS):
    """Least-squares plane through points.

    Parameters
    ----------
    points : array_like, shape (N, 3)
    axis_tolerance : float
        If the fitted normal is within this (1 - |cos|) of a world axis, that axis' frame is
        used exactly.

    Returns
    -------
    Plane
        For fewer than three non-collinear points the front (XZ) frame through their centroid.
    """
    pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    origin = pts.mean(axis=0) if len(pts) else np.zeros(3)
    shortcut = len(pts) >= 3 and _AXIS_ROUNDOFF <= axis_tolerance <= 0.5  # (one frame fits)
    axis = _on_axis_plane(pts, origin) if shortcut else None
    if axis is not None:
        u, v, n = next(frame for frame in _AXIS_FRAMES if frame[2][axis] != 0.0)
        return Plane(origin, u, v, n)
    if len(pts) >= 3:
        _, sing, vt = np.linalg.svd(pts - origin, full_matrices=False)
        planar_enough = sing[1] > 1e-12 * max(sing[0], tol.TINY)
    else:
        planar_enough = False
    if not planar_enough:
        u, v, n = _AXIS_FRAMES[0]
        return Plane(origin, u, v, n)
    normal = vt[2]
    for u, v, n in _AXIS_FRAMES:
        if 1.0 - abs(float(normal @ n)) <= axis_tolerance:
            return Plane(origin, u, v, n)
    u = vt[0]
    v = np.cross(normal, u)
    return Plane(origin, u, v, normal)
