"""The one morph interface every method implements, and the method registry."""

import numpy as np

from ..geometry.polyline import as_curve
from ..options import SAMPLINGS, check_option

__all__ = ["Morph", "PathMorph", "KeyedMorph", "register", "registered", "build", "morph_time"]

_REGISTRY = {}


def morph_time(t):
    """A morph's time as every morph takes it: a finite number, clamped to [0, 1] (float).

    Raises
    ------
    ValueError
        For NaN or an infinite ``t``.
    """
    t = float(t)
    if not np.isfinite(t):
        raise ValueError(f"t must be a finite number, got {t!r}")
    return min(max(t, 0.0), 1.0)


def register(name):
    """Class or function decorator: ``name`` builds a morph with ``builder(P, Q, closed, spacing,
    sampling, **options)``."""

    def deco(builder):
        _REGISTRY[name] = builder
        return builder

    return deco


def registered():
    """Names of the registered methods, in registration order (tuple of str)."""
    return tuple(_REGISTRY)


def build(P, Q, method, closed, spacing, sampling, **options):
    """Validate the inputs and call the method's builder (see :func:`make_morph`)."""
    method = check_option("method", method, registered())
    sampling = check_option("sampling", sampling, SAMPLINGS)
    P = as_curve(P, "P", closed)
    Q = as_curve(Q, "Q", closed)
    return _REGISTRY[method](P, Q, closed=closed, spacing=spacing, sampling=sampling, **options)


class Morph:
    """A morph from P to Q.

    Calling it at ``t`` in [0, 1] gives the in-between curve as ``(K, 2)`` samples, in the same
    order for every ``t`` (sample ``i`` of every frame is the same material point), so frames can
    be compared, stacked into a surface, or written as strokes with interpolated attributes.

    Attributes
    ----------
    method : str
    closed : bool
        Whether every frame is a loop.
    u_p, u_q : ndarray, shape (K,)
        Where each sample comes from on P and goes to on Q, as arc-length fractions in [0, 1]
        along the curves *as given* (from their first point, in their own direction). Used to
        carry per-point attributes (radius, opacity, colour) along the correspondence.
    """

    method = "?"
    u_p = None
    u_q = None

    def __init__(self, closed):
        self.closed = bool(closed)

    def __call__(self, t):
        """In-between curve at ``t``, shape (K, 2)."""
        return self._frame(morph_time(t))

    def _frame(self, t):
        raise NotImplementedError

    def frames(self, ts):
        """In-between curves at several times, shape (T, K, 2)."""
        return np.stack([self(t) for t in np.atleast_1d(ts)])

    @property
    def p(self):
        """Samples on P (the frame at t=0), shape (K, 2)."""
        return self(0.0)

    @property
    def q(self):
        """Their images on Q (the frame at t=1), shape (K, 2)."""
        return self(1.0)

    def __len__(self):
        return len(self.p)


class PathMorph(Morph):
    """A morph whose samples each travel along their own path at constant speed.

    Parameters
    ----------
    method : str
    closed : bool
    paths : BallPaths, LinearPaths or SampledPaths
        Anything with ``at(t) -> (K, 2)``, ``start``, ``end`` and ``lengths()``.
    u_p, u_q : array_like, shape (K,)
        See :class:`Morph`.
    correspondence : object, optional
        What the paths were built from (for example a ball-map Correspondence).
    """

    def __init__(self, method, closed, paths, u_p, u_q, correspondence=None):
        super().__init__(closed)
        self.method = method
        self.paths = paths
        self.u_p = np.asarray(u_p, dtype=np.float64)
        self.u_q = np.asarray(u_q, dtype=np.float64)
        self.correspondence = correspondence

    def _frame(self, t):
        return self.paths.at(t)

    def frames(self, ts):
        """In-between curves at several times, shape (T, K, 2): in one pass where the paths
        can (``at_times``: the same values as time by time)."""
        at_times = getattr(self.paths, "at_times", None)
        if at_times is None:
            return super().frames(ts)
        return at_times(np.array([morph_time(t) for t in np.atleast_1d(ts)], dtype=np.float64))

    @property
    def p(self):
        return self.paths.start

    @property
    def q(self):
        return self.paths.end

    def __len__(self):
        return len(self.paths)


class KeyedMorph(Morph):
    """A morph that solves every in-between from the two key polygons.

    Sample ``i`` of ``p`` corresponds to sample ``i`` of ``q``; the frames at t = 0 and 1 are
    the keys exactly, and subclasses implement ``_solve(t)`` for the times between.

    Parameters
    ----------
    p, q : ndarray, shape (K, 2)
    u_p, u_q : array_like, shape (K,)
        See :class:`Morph`.
    closed : bool
    """

    def __init__(self, p, q, u_p, u_q, closed):
        super().__init__(closed)
        self._p, self._q = p, q
        self.u_p, self.u_q = np.asarray(u_p, dtype=np.float64), np.asarray(u_q, dtype=np.float64)

    def __len__(self):
        return len(self._p)

    def _frame(self, t):
        if t == 0.0:
            return self._p.copy()
        if t == 1.0:
            return self._q.copy()
        return self._solve(t)

    def _solve(self, t):
        raise NotImplementedError
