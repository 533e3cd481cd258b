"""All morphs behind one interface: ``make_morph(P, Q, method) -> Morph``.

Each module registers its methods; importing them here fixes the order of ``METHODS``.
"""

from . import ball, linear, closest, curvature, laplace, heat  # noqa: F401  # isort: skip  (import order = METHODS order)
from . import composite  # noqa: F401  (after the morphs its extensions fall back to)
from .base import Morph, PathMorph, build, registered

__all__ = ["METHODS", "Morph", "PathMorph", "make_morph"]

METHODS = registered()


def make_morph(P, Q, method="circular-ball", closed=False, spacing=None, sampling="symmetric", **options):
    """Build a morph from P to Q.

    Parameters
    ----------
    P, Q : array_like, shape (N, 2) and (M, 2)
        The key curves (not modified).
    method : str
        One of :data:`METHODS`.
    closed : bool
        Loops (True) or strokes (False).
    spacing : float, optional
        Geodesic sample spacing (default from the curves' size and edge lengths).
    sampling : {'symmetric', 'p', 'q'}
        Which curve is sampled uniformly (see :func:`~ballmorph_core.ballmap.ball_map`); the
        measures use ``'P'`` and ``'Q'``. Methods that need no correspondence of their own
        accept and ignore it where it has no meaning.
    **options
        Method-specific options.

    Returns
    -------
    Morph
        ``morph(t)`` is the in-between curve at ``t`` in [0, 1], shape (K, 2).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, np.pi, 50)
    >>> P = np.c_[np.cos(t), np.sin(t)]
    >>> Q = np.c_[np.cos(t), 0.5 * np.sin(t)]
    >>> morph = make_morph(P, Q, "circular-ball")
    >>> morph(0.5).shape[1]
    2
    """
    return build(P, Q, method, closed, spacing, sampling, **options)
