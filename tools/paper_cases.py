"""The three test cases of the paper's comparative study (Whited & Rossignac, section 8).

Made here, shaped like the paper's figures so that the ball-morphs apply (every pair is
b-compatible, checked by ``bm.ball_map``):

* ``circle-ellipse`` (Fig. 24): a unit circle inside an ellipse that comes close to it at the
  top and bottom (the paper notes the heat-propagation-morph suffers where the curves are close
  relative to its grid) and leaves a wide gap at the sides. Nested disjoint loops.
* ``s-strokes`` (Fig. 25): two S-shaped strokes sharing both endpoints, each the other turned
  half a turn about the midpoint of the common chord. Their arc length is distributed
  oppositely along the chord, so a uniform arc-length correspondence slides points along the
  curves (the paper's "extreme distortion and travel lengths") while the ball-map does not.
* ``apple-pear`` (Figs. 1 and 26): a pear nested inside an apple. The paper's Fig. 1 may show
  crossing outlines; we keep them disjoint and b-compatible so every ball-morph runs without
  crossing support, and so the heat-propagation-morph has a clean gap.

Every curve is a densely sampled analytic curve (loops counter-clockwise, not repeating their
first point); ``height`` is the z extent used to stack the frames of every morph of a case into
a surface for the mean-curvature measures (the same for all methods of the case).
"""

from dataclasses import dataclass

import numpy as np

__all__ = ["Case", "circle_ellipse", "s_strokes", "apple_pear", "paper_cases"]


@dataclass
class Case:
    """A curve pair to compare morphs on.

    Attributes
    ----------
    name : str
        Short identifier (file names).
    title : str
        Human-readable title (the paper's figure).
    P, Q : ndarray, shape (N, 2), (M, 2)
    closed : bool
    height : float
        z extent of the stacked-frames surface (mean-curvature measures).
    spacing : float or None
        Geodesic sample spacing of the measures (None: ``bm.measure``'s default).
    """

    name: str
    title: str
    P: np.ndarray
    Q: np.ndarray
    closed: bool
    height: float
    spacing: float


def _angles(n):
    return np.linspace(0.0, 2 * np.pi, n, endpoint=False)


def circle_ellipse(n=400):
    """Unit circle inside the ellipse with semi-axes 1.8 and 1.15 (Fig. 24)."""
    t = _angles(n)
    P = np.c_[np.cos(t), np.sin(t)]
    Q = np.c_[1.8 * np.cos(t), 1.15 * np.sin(t)]
    return Case("circle-ellipse", "Circle and ellipse (paper Fig. 24)", P, Q, True, height=2.0, spacing=0.03)


def s_strokes(n=400, height=0.14, wiggle=0.17):
    """Two S-shaped strokes from (0, 0) to (1, 0), each the other turned half a turn (Fig. 25).

    ``P: y = height sin(pi x) + wiggle sin(2 pi x)`` and ``Q: y = -height sin(pi x) + wiggle
    sin(2 pi x)``, so ``P - Q = 2 height sin(pi x) > 0`` between the shared endpoints;
    ``wiggle > height / 8`` gives each an inflection (the S). The product ``height * wiggle``
    is kept small so the gap stays narrower than the curves' bends are tight (b-compatible).
    """
    x = np.linspace(0.0, 1.0, n)
    s = wiggle * np.sin(2 * np.pi * x)
    P = np.c_[x, height * np.sin(np.pi * x) + s]
    Q = np.c_[x, -height * np.sin(np.pi * x) + s]
    return Case("s-strokes", "Symmetric S-shaped strokes (paper Fig. 25)", P, Q, False, height=1.0, spacing=0.008)


def _bump(t, centre, width):
    """Smooth periodic bump of height 1 at angle ``centre``."""
    return np.exp((np.cos(t - centre) - 1.0) / width**2)


def apple_pear(n=480):
    """A pear nested inside an apple (Figs. 1 and 26).

    Both are star-shaped polar curves ``r(theta)``. Apple: a slightly flattened round loop with a
    dimple at the stem and a shallow one at the base. Pear: a round body plus a narrow bump
    upwards, which makes the head and, on each side of it, a gently concave waist (gentle
    enough for the maximal disks in the gap to stay tangent to it at one point).
    """
    t = _angles(n)
    r = 1.3 + 0.06 * np.cos(2 * t) - 0.22 * _bump(t, np.pi / 2, 0.32) - 0.06 * _bump(t, -np.pi / 2, 0.3)
    apple = np.c_[1.08 * r * np.cos(t), r * np.sin(t)]
    r = 0.65 + 0.5 * _bump(t, np.pi / 2, 0.4)
    pear = np.c_[0.95 * r * np.cos(t), r * np.sin(t) - 0.3]
    return Case("apple-pear", "Apple and pear (paper Figs. 1 and 26)", pear, apple, True, height=2.5, spacing=0.03)


def paper_cases():
    """The three test cases, in the paper's order (list of :class:`Case`)."""
    return [circle_ellipse(), s_strokes(), apple_pear()]
