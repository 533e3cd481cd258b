"""Circles through three points: the local circle of a polyline at a vertex.

Refining a contact or a closest point on the circle through three consecutive vertices instead
of on their chords makes it exact on circles and second-order accurate on smooth curves (the
paper's exact construction for piecewise-circular curves, section 5.1). The ball-map and the
closest projection both do it.
"""

import numpy as np

__all__ = ["circumcircles"]

#: Three points whose doubled triangle area is below this times the squared distance between
#: the outer two are collinear: they have no useful circle.
STRAIGHT = 1e-9


def circumcircles(a, b, c):
    """Circles through three points, row by row.

    Parameters
    ----------
    a, b, c : ndarray, shape (K, 2)

    Returns
    -------
    centre : ndarray, shape (K, 2)
    radius : ndarray, shape (K,)
    ok : ndarray of bool, shape (K,)
        False where the points are collinear within ``STRAIGHT`` (centre and radius are then
        meaningless but finite).
    """
    ab, ac = b - a, c - a
    det = 2.0 * (ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0])
    ab2, ac2 = np.einsum("ij,ij->i", ab, ab), np.einsum("ij,ij->i", ac, ac)
    ok = np.abs(det) > STRAIGHT * ac2
    det = np.where(ok, det, 1.0)
    offset = np.stack([ac[:, 1] * ab2 - ab[:, 1] * ac2, ab[:, 0] * ac2 - ac[:, 0] * ab2], axis=1) / det[:, None]
    return a + offset, np.hypot(offset[:, 0], offset[:, 1]), ok
