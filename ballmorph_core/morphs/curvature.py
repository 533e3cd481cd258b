"""Curvature interpolation (paper section 2; Sederberg, Gao, Wang and Mu 1993, "2-D shape
blending: an intrinsic solution to the vertex path problem").

Edge lengths and turning angles of corresponding polygons are interpolated linearly, and the
polygon is rebuilt edge by edge. A loop rebuilt that way does not close in general; the edge
lengths are corrected by the smallest weighted change that closes it (Sederberg's closed form
with two Lagrange multipliers). A stroke is fitted to its interpolated endpoints by a
similarity, as the paper does ("retrofitting them through a trivial similarity
transformation").
"""

import numpy as np

from .. import tolerances as tol
from ..geometry.polyline import edges, turning_angles
from ..geometry.similarity import as_complex
from ..options import check_option
from .base import KeyedMorph, register
from .linear import sample_count, uniform_correspondence

__all__ = ["CurvatureMorph", "close_polygon", "STROKE_FITS"]

#: Curvature interpolation: an edge's closure weight L_AB is at least this fraction of the mean
#: edge length (Sederberg's L_tol), so edges whose length does not change still take a share.
CURVATURE_LENGTH_FLOOR = 1e-3

#: How a stroke's frames meet its endpoints (see :class:`CurvatureMorph`).
STROKE_FITS = ("similarity", "closure")


def close_polygon(lengths, angles, weights, target):
    """Edge lengths closest to ``lengths`` whose edges add up to ``target``.

    Minimises ``sum S_i^2 / weights_i^2`` subject to
    ``sum (lengths_i + S_i) exp(1j angles_i) = target`` (Sederberg et al. 1993, section 4).

    Parameters
    ----------
    lengths, angles, weights : ndarray, shape (E,)
        Edge lengths, absolute edge directions (radians), and how freely each length may
        change (Sederberg's ``L_AB``; larger changes more).
    target : complex
        Required sum of the edge vectors: 0 for a loop, the chord for a stroke.

    Returns
    -------
    ndarray, shape (E,)
        Corrected lengths ``lengths + S``.

    Notes
    -----
    Setting the gradient of the Lagrangian to zero gives ``S_i = w_i^2 (l1 cos a_i + l2 sin a_i)``;
    the two multipliers solve a 2x2 system. When every edge points the same way the system is
    singular and the least-norm multipliers are used.

    Examples
    --------
    >>> import numpy as np
    >>> out = close_polygon(np.ones(4), np.arange(4) * np.pi / 2, np.ones(4), 0.5)
    >>> out.round(6).tolist()  # only the two horizontal edges change
    [1.25, 1.0, 0.75, 1.0]
    """
    c, s = np.cos(angles), np.sin(angles)
    w2 = np.square(weights)
    err = complex(target) - np.sum(lengths * (c + 1j * s))
    m = np.array([[np.sum(w2 * c * c), np.sum(w2 * c * s)], [np.sum(w2 * c * s), np.sum(w2 * s * s)]])
    lam = np.linalg.lstsq(m, np.array([err.real, err.imag]), rcond=None)[0]
    return lengths + w2 * (lam[0] * c + lam[1] * s)


class CurvatureMorph(KeyedMorph):
    """Interpolated edge lengths and turning angles between corresponding polygons.

    Parameters
    ----------
    p, q : ndarray, shape (K, 2)
        Corresponding samples (for loops both turning the same way).
    u_p, u_q : ndarray, shape (K,)
    closed : bool
    stroke_fit : {'similarity', 'closure'}
        Strokes only. ``'similarity'`` (the paper's): the rebuilt stroke is rotated, scaled and
        moved so its ends land on the interpolated endpoints. ``'closure'``: its edge lengths
        are first corrected (as loops are) so its edges add up to the interpolated chord; the
        similarity then only removes round-off.

    Notes
    -----
    * The direction of the first edge is interpolated along the shorter way round, then each
      edge turns by the interpolated turning angle (each in (-pi, pi]); two loops turning the
      same way have the same total turning (+-2 pi), so every interpolated loop does too.
    * Closure weights are ``L_AB,i = max(|L^A_i - L^B_i|, CURVATURE_LENGTH_FLOOR * mean edge)``:
      edges whose length changes most absorb the correction.
    * A loop is placed so the mean of its vertices moves linearly from P's to Q's.
    * If the shapes are similar (one a rotated, scaled, moved copy of the other, with the
      corresponding samples), every frame is similar to both.
    * Nothing prevents a corrected length from going negative (the polygon then folds): the
      method has no such guard in the literature either.
    """

    method = "curvature-interpolation"

    def __init__(self, p, q, u_p, u_q, closed, stroke_fit="similarity"):
        super().__init__(p, q, u_p, u_q, closed)
        self.stroke_fit = check_option("stroke_fit", stroke_fit, STROKE_FITS)
        ea, eb = as_complex(edges(p, closed)), as_complex(edges(q, closed))
        self._len_a, self._len_b = np.abs(ea), np.abs(eb)
        self._turn_a, self._turn_b = turning_angles(p, closed), turning_angles(q, closed)
        self._dir_a = float(np.angle(ea[0]))
        self._dir_b = self._dir_a + float(np.angle(eb[0] / ea[0])) if ea[0] != 0 else float(np.angle(eb[0]))
        floor = CURVATURE_LENGTH_FLOOR * 0.5 * (self._len_a.mean() + self._len_b.mean())
        self._weights = np.maximum(np.abs(self._len_a - self._len_b), floor)

    def _directions(self, t):
        turn = (1 - t) * self._turn_a + t * self._turn_b
        # Loops: turning_angles()[i] is at vertex i, from edge i-1 to edge i; vertex 0's turn
        # closes the loop and is implied. Strokes: it is at vertex i + 1.
        steps = turn[1:] if self.closed else turn
        first = (1 - t) * self._dir_a + t * self._dir_b
        return first + np.concatenate([[0.0], np.cumsum(steps)])

    def _solve(self, t):
        lengths = (1 - t) * self._len_a + t * self._len_b
        angles = self._directions(t)
        p, q = self._p, self._q
        if self.closed:
            lengths = close_polygon(lengths, angles, self._weights, 0.0)
        elif self.stroke_fit == "closure":
            chord = (1 - t) * as_complex(p[-1] - p[0]) + t * as_complex(q[-1] - q[0])
            lengths = close_polygon(lengths, angles, self._weights, chord)
        z = np.concatenate([[0.0], np.cumsum(lengths * np.exp(1j * angles))])
        if self.closed:
            z = z[:-1]
            z += (1 - t) * as_complex(p).mean() + t * as_complex(q).mean() - z.mean()
        else:
            start = (1 - t) * as_complex(p[0]) + t * as_complex(q[0])
            end = (1 - t) * as_complex(p[-1]) + t * as_complex(q[-1])
            span = z[-1] - z[0]
            # A rebuilt stroke whose ends meet cannot be fitted: it is only moved.
            scale = (end - start) / span if abs(span) > tol.COINCIDENT * np.abs(lengths).sum() else 1.0
            z = start + scale * (z - z[0])
        return np.stack([z.real, z.imag], axis=1)


@register("curvature-interpolation")
def build(P, Q, closed, spacing, sampling, stroke_fit="similarity"):
    """Curvature interpolation on the uniform arc-length correspondence (see
    :class:`CurvatureMorph`); the sample count follows ``sampling`` as for linear
    interpolation, and loops are paired so both turn the same way."""
    count = sample_count(P, Q, closed, spacing, sampling)
    p, q, u_p, u_q = uniform_correspondence(P, Q, closed, count, match_orientation=True)
    return CurvatureMorph(p, q, u_p, u_q, closed, stroke_fit)
