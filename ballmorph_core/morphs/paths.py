"""Vertex trajectories: the five ball-morph paths of paper section 4.2, and sampled paths.

For a contact pair ``(p, m, q)`` with ``|m - p| = |m - q| = r``:

* ``'hat'``: p -> m -> q;
* ``'linear'``: the segment pq;
* ``'tangent'``: the shorter arc of the disk's boundary from p to q;
* ``'circular'``: the arc leaving p along pm and reaching q along mq, orthogonal to both curves;
  its centre is where the tangents of P at p and of Q at q meet. It degenerates to the segment
  pq when p, m, q are collinear (parallel tangents): the formula below uses a ratio of sincs,
  so it passes through that case without a branch;
* ``'parabolic'``: the quadratic Bezier curve with control points p, m, q.

Every path is traversed at uniform arc-length speed. :class:`SampledPaths` carries paths given
as polylines (heat-propagation gradients, composite ball-morph arcs) with the same interface.
"""

import functools
import itertools
import math

import numpy as np

from ..geometry.vectors import row_norms
from ..options import check_option

__all__ = ["KINDS", "BallPaths", "SampledPaths", "LevelPaths", "LinearPaths", "midpoint_locus"]

#: Points along each trajectory used to tabulate arc length for uniform-speed traversal.
ARC_TABLE_SAMPLES = 16

KINDS = ("hat", "linear", "tangent", "circular", "parabolic")

#: A tangent path's contacts within this fraction of half a turn of being opposite on their
#: disk have two equal arcs: the side is taken from the samples' order instead.
OPPOSITE = 1e-6

# 3-point Gauss-Legendre nodes and weights on [-1, 1].
_GAUSS3 = ((-np.sqrt(0.6), 5.0 / 9.0), (0.0, 8.0 / 9.0), (np.sqrt(0.6), 5.0 / 9.0))


def _cross(a, b):
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


#: :func:`_sincos` keeps the Taylor terms whose size at its largest angle can reach this (a
#: quarter of an ulp of 1): the first term it leaves out is below it.
SINCOS_TERM = 2.0**-55


@functools.lru_cache(maxsize=64)
def _sincos_terms(bound):
    """How :func:`_sincos` computes angles up to ``bound`` (<= pi): the double-angle steps that
    bring them within pi / 4, and the Taylor coefficients of sin(y) / y and cos(y) in y^2 at the
    angle they leave, highest first."""
    doublings = 0
    while bound / 2.0**doublings > math.pi / 4 and doublings < 2:
        doublings += 1
    y = bound / 2.0**doublings
    # sin's terms y^(2k+1) / (2k+1)! and cos's y^(2k) / (2k)! for k < n, n the first one small enough.
    n_sin = next(n for n in itertools.count(1) if y ** (2 * n + 1) / math.factorial(2 * n + 1) <= SINCOS_TERM)
    n_cos = next(n for n in itertools.count(1) if y ** (2 * n) / math.factorial(2 * n) <= SINCOS_TERM)
    sin = tuple((-1) ** k / math.factorial(2 * k + 1) for k in range(n_sin - 1, -1, -1))
    cos = tuple((-1) ** k / math.factorial(2 * k) for k in range(n_cos - 1, -1, -1))
    return doublings, sin, cos


def _sincos(x, sin, cos, work, bound=math.pi):
    """``sin(x)`` and ``cos(x)`` for ``|x| <= bound <= pi``, to a few units in the last place.

    Taylor polynomials, of the angles halved as many times (at most twice) as brings them within
    pi / 4, then as many double-angle steps: plain arithmetic, which numpy runs 2 to 4 times
    faster than its float64 sin and cos (numpy 1.26, Blender's, has no SIMD loop for those
    without AVX-512), and they are most of a redo's circular paths. Nearly parallel curves turn
    their paths by small angles (a tenth of a radian at most on the benchmark's strokes): those
    need no doubling and half the terms.

    Parameters
    ----------
    x : ndarray, shape (K,)
        Angles, overwritten (with the halved angles and then work values).
    sin, cos, work : ndarray, shape (K,)
        The results, and a work buffer.
    bound : float
        A bound on ``|x|`` (the fewer terms, the smaller).
    """
    doublings, sin_terms, cos_terms = _sincos_terms(float(bound))
    y, z = x, work
    if doublings:
        y *= 0.5**doublings
    np.multiply(y, y, out=z)
    for out, terms in ((sin, sin_terms), (cos, cos_terms)):
        if len(terms) == 1:
            out.fill(terms[0])
            continue
        np.multiply(z, terms[0], out=out)
        out += terms[1]
        for a in terms[2:]:
            out *= z
            out += a
    sin *= y
    for _ in range(doublings):  # sin 2y = 2 sin y cos y, cos 2y = (cos y - sin y)(cos y + sin y)
        np.multiply(sin, cos, out=y)
        np.subtract(cos, sin, out=z)
        cos += sin
        cos *= z
        np.multiply(y, 2.0, out=sin)
    return sin, cos


def _rotate(v, angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]], axis=1)


def _arc_table(points):
    """Normalised cumulative chord length along sampled paths, shape (K, S)."""
    seg = np.linalg.norm(np.diff(points, axis=1), axis=2)
    cum = np.concatenate([np.zeros((len(points), 1)), np.cumsum(seg, axis=1)], axis=1)
    total = cum[:, -1:]
    even = np.tile(np.linspace(0, 1, cum.shape[1]), (len(cum), 1))  # for paths of zero length
    return np.divide(cum, total, out=even, where=total > 0), total[:, 0]


def _invert_rows(table, levels):
    """For each row of a monotone table in [0, 1], the fractional index where it reaches each level.

    Parameters
    ----------
    table : ndarray, shape (K, S)
    levels : ndarray, shape (J,)

    Returns
    -------
    ndarray, shape (K, J)
        Fractional column index in [0, S - 1].
    """
    k, s = table.shape
    # One global searchsorted: shift row i by 2i so the flattened table stays sorted.
    shift = 2.0 * np.arange(k)[:, None]
    flat = table + shift
    want = levels[None, :] + shift
    idx = np.searchsorted(flat.ravel(), want.ravel(), side="right").reshape(k, len(levels))
    del flat, want
    # In place from here (the same values: a parabolic plan's table of 200,000 paths is 27 MB
    # an array, and this made a dozen of them).
    idx -= 1
    idx -= (np.arange(k) * s)[:, None]
    np.clip(idx, 0, s - 2, out=idx)
    lo = np.take_along_axis(table, idx, axis=1)
    idx += 1
    span = np.take_along_axis(table, idx, axis=1)
    idx -= 1
    span -= lo
    frac = np.subtract(levels[None, :], lo, out=lo)
    rising = span > 0
    np.divide(frac, span, out=frac, where=rising)
    np.copyto(frac, 0.0, where=~rising)
    np.clip(frac, 0.0, 1.0, out=frac)
    return idx + frac


class _Polylines:
    """Paths stored as polylines, shape (K, S, 2) (first point = start, last = end)."""

    def __init__(self, points):
        self.points = np.asarray(points, dtype=np.float64)

    def __len__(self):
        return len(self.points)

    @property
    def start(self):
        """Start points, shape (K, 2)."""
        return self.points[:, 0]

    @property
    def end(self):
        """End points, shape (K, 2)."""
        return self.points[:, -1]


class SampledPaths(_Polylines):
    """Paths given as polylines, traversed at uniform arc length.

    Parameters
    ----------
    points : ndarray, shape (K, S, 2)
        Polyline of each of the K paths (S >= 2 points, first = start, last = end).
    """

    def __init__(self, points):
        super().__init__(points)
        self._table, self._lengths = _arc_table(self.points)

    def lengths(self):
        """Arc length of each path, shape (K,)."""
        return self._lengths

    def at(self, t):
        """Positions at time ``t`` in [0, 1], shape (K, 2)."""
        t = float(np.clip(t, 0.0, 1.0))
        f = _invert_rows(self._table, np.array([t]))[:, 0]
        i = np.minimum(np.floor(f).astype(np.int64), self.points.shape[1] - 2)
        u = (f - i)[:, None]
        rows = np.arange(len(i))
        return (1 - u) * self.points[rows, i] + u * self.points[rows, i + 1]


class _Endpoints:
    """Paths from ``p`` to ``q`` (K of them)."""

    def __len__(self):
        return len(self.p)

    @property
    def start(self):
        """Start points, shape (K, 2)."""
        return self.p

    @property
    def end(self):
        """End points, shape (K, 2)."""
        return self.q


class LinearPaths(_Endpoints):
    """Straight paths from ``p`` to ``q`` at constant speed.

    Parameters
    ----------
    p, q : ndarray, shape (K, 2)
    """

    def __init__(self, p, q):
        self.p = np.asarray(p, dtype=np.float64)
        self.q = np.asarray(q, dtype=np.float64)
        self._columns = None  # p and q - p as (2, K), made at the first at() into a buffer

    @classmethod
    def join(cls, parts):
        """Many of them (``(paths, kept samples)`` each) as one: one evaluation for them all."""
        return cls(*(np.concatenate([getattr(paths, end)[keep] for paths, keep in parts]) for end in "pq"))

    def lengths(self):
        """Shape (K,)."""
        return row_norms(self.q - self.p)

    def at(self, t, out=None):
        """Shape (K, 2); written into ``out`` (any (K, 2) array) when given."""
        if out is None:
            return self.p + float(t) * (self.q - self.p)
        # Column by column from columns kept contiguous (the same values: p + t (q - p)).
        if self._columns is None:
            self._columns = np.ascontiguousarray(self.p.T), np.ascontiguousarray((self.q - self.p).T)
        for p, d, column in zip(*self._columns, out.T):
            np.multiply(d, float(t), out=column)
            column += p
        return out

    def at_times(self, ts):
        """Positions at every time of ``ts`` (shape (T,), each already in [0, 1]), shape
        (T, K, 2): the values :meth:`at` gives time by time, in one pass."""
        return self.p + np.asarray(ts, dtype=np.float64)[:, None, None] * (self.q - self.p)


class BallPaths(_Endpoints):
    """One of the five ball-morph paths for every contact pair.

    Parameters
    ----------
    p, m, q : ndarray, shape (K, 2)
        Contacts on P, disk centres, contacts on Q.
    kind : {'hat', 'linear', 'tangent', 'circular', 'parabolic'}

    Examples
    --------
    >>> import numpy as np
    >>> paths = BallPaths(np.array([[0.0, 0.0]]), np.array([[0.0, 1.0]]), np.array([[1.0, 1.0]]), "circular")
    >>> paths.at(1.0).round(12).tolist()
    [[1.0, 1.0]]
    >>> float(paths.lengths()[0].round(6))  # a quarter circle of radius 1
    1.570796
    """

    def __init__(self, p, m, q, kind="circular"):
        self.kind = check_option("kind", kind, KINDS)
        self.p = np.asarray(p, dtype=np.float64)
        self.m = np.asarray(m, dtype=np.float64)
        self.q = np.asarray(q, dtype=np.float64)
        d = self.q - self.p
        self._chord = row_norms(d)
        self._work = None  # the circular paths' work buffers (at the first at())
        if kind == "circular":
            # Angle phi between the start direction (p -> m) and the chord; the arc turns 2 phi.
            u = self.m - self.p
            size = row_norms(u)[:, None]
            self._u = np.divide(u, size, out=np.zeros_like(u), where=size > 0)
            self._phi = np.arctan2(_cross(self._u, d), np.einsum("ij,ij->i", self._u, d))
            self._phi = np.where(self._chord > 0, self._phi, 0.0)
            chord_per_sinc = self._chord / np.sinc(self._phi / np.pi)
            # The chord reached at time t is |d| sin(phi t) / sin(phi) long (|d| t on a straight
            # path): at() needs its two coefficients every frame, and the sine it computes anyway.
            turning = self._phi != 0
            self._per_sin = np.divide(chord_per_sinc, self._phi, out=np.zeros_like(self._phi), where=turning)
            self._straight = np.where(turning, 0.0, self._chord)
        elif kind == "tangent":
            self._beta = self._tangent_turns()
        elif kind == "parabolic":
            self._init_parabola()

    def _tangent_turns(self):
        """Signed angle of each tangent path around its disk: the shorter arc, and where p and q
        are opposite (both arcs equal: concentric circles) the one leaving p forward along the
        samples' order, so round-off never picks the side."""
        a, b = self.p - self.m, self.q - self.m
        beta = np.arctan2(_cross(a, b), np.einsum("ij,ij->i", a, b))
        forward = np.gradient(self.p, axis=0) if len(self.p) > 1 else np.zeros_like(self.p)
        # Turning a (from m to p) by +90 degrees gives the direction of a counter-clockwise start.
        ccw_forward = _cross(a, forward) >= 0
        opposite = np.abs(np.abs(beta) - np.pi) <= OPPOSITE * np.pi
        return np.where(opposite, np.where(ccw_forward, np.pi, -np.pi), beta)

    def _speed(self, s):
        """|B'(s)| = 2 |a + s b| of the Bezier curves (a = m - p, b = q - 2 m + p), for ``s`` of
        shape (K,) or (K, n) (row k: path k), the same shape.

        Coordinate by coordinate from columns made once: the values of
        ``2 * np.linalg.norm(a + s b, axis=-1)`` bit for bit (s b + a, then x x + y y and the
        root), without its (K, n, 2) temporaries and its reduction along rows two long (a
        frame evaluates 16 of these: most of a parabolic redo).
        """
        ax, ay, bx, by = (c if s.ndim == 1 else c[:, None] for c in self._ab)
        x = s * bx
        x += ax
        y = s * by
        y += ay
        x *= x
        y *= y
        x += y
        np.sqrt(x, out=x)
        x *= 2.0
        return x

    def _init_parabola(self):
        # Arc length L(s): a table at ARC_TABLE_SAMPLES nodes, each interval integrated by
        # 3-point Gauss-Legendre, and between nodes the same rule from the node below (so the
        # table and the evaluation agree exactly); inverted by Newton steps from a linear guess.
        n = ARC_TABLE_SAMPLES
        k = len(self.p)
        a, b = self.m - self.p, self.q - 2 * self.m + self.p
        self._ab = tuple(np.ascontiguousarray(c) for c in (a[:, 0], a[:, 1], b[:, 0], b[:, 1]))
        s = np.linspace(0.0, 1.0, n + 1)
        pieces = np.zeros((k, n))
        for x, w in _GAUSS3:
            speed = self._speed(np.broadcast_to(s[:-1] + (1 + x) / (2 * n), (k, n)))
            speed *= w
            pieces += speed
        pieces /= 2 * n
        self._L = np.concatenate([np.zeros((k, 1)), np.cumsum(pieces, axis=1)], axis=1)
        del pieces
        self._par_len = self._L[:, -1].copy()
        table = np.divide(self._L, self._par_len[:, None], out=np.tile(s, (k, 1)), where=self._par_len[:, None] > 0)
        # The Bezier parameter at each node of arc-length fraction, node by node (a frame reads
        # two nodes of every path: rows, not strided columns), shape (n + 1, K).
        self._tau_nodes = np.ascontiguousarray((_invert_rows(table, s) / n).T)
        # Where each path's row of L starts in the flat table.
        self._row_start = np.arange(k) * (n + 1)

    def _arc_length(self, s):
        """L(s) per path for s of shape (K,): the tabulated length at the node below s plus the
        same Gauss-Legendre rule from there."""
        n = ARC_TABLE_SAMPLES
        j = np.clip(np.floor(s * n).astype(np.int64), 0, n - 1)
        node = j / n
        half = s - node
        half *= 0.5
        mid = node + half
        total = None
        for x, w in _GAUSS3:
            term = self._speed(mid + half * x)
            term *= w
            # The first term as it is: 0 + term is term (speeds are not negative).
            total = term if total is None else np.add(total, term, out=total)
        total *= half
        # L[k, j[k]] (row k of the table, flat): j is within 0..n - 1, so 'wrap' skips the bounds check.
        total += np.take(self._L, self._row_start + j, mode="wrap")
        return total

    def _parabola_parameter(self, t):
        f = t * ARC_TABLE_SAMPLES
        j = min(int(f), ARC_TABLE_SAMPLES - 1)
        u = f - j
        s = (1 - u) * self._tau_nodes[j] + u * self._tau_nodes[j + 1]
        target = t * self._par_len
        for _ in range(4):  # Newton on L(s) = target, from the table's guess
            speed = self._speed(s)
            step = self._arc_length(s)
            step -= target
            moving = speed > 0
            np.divide(step, speed, out=step, where=moving)
            np.copyto(step, 0.0, where=~moving)
            s -= step
            np.clip(s, 0.0, 1.0, out=s)
        return s

    def lengths(self):
        """Arc length of each path, shape (K,)."""
        r = row_norms(self.m - self.p)
        if self.kind == "linear":
            return self._chord
        if self.kind == "hat":
            return 2 * r
        if self.kind == "tangent":
            return r * np.abs(self._beta)
        if self.kind == "circular":
            return self._chord / np.sinc(self._phi / np.pi)
        return self._par_len

    def _circular_work(self):
        """The circular paths' kept work buffers (5, K), their ``u`` and ``p`` as contiguous
        columns, and the bound of every angle phi t (made at the first evaluation)."""
        if self._work is None:
            self._work = np.empty((5, len(self.p)))
            self._columns = tuple(np.ascontiguousarray(a.T) for a in (self._u, self.p))
            # Held once: u only as these columns, p as a view of its own (the same values).
            self._u, self.p = None, self._columns[1].T
            # Every angle phi t lies within the largest |phi| (at most pi: phi is an arctan2).
            largest = float(np.max(np.abs(self._phi), initial=0.0))
            self._bound = largest if largest <= np.pi else np.pi
        return self._work

    def _circular_at(self, t, out):
        """The circular paths at time ``t`` into ``out`` (K, 2): the chord from p to the point
        reached after turning 2 phi t, of length |d| sin(phi t) / sin(phi), along u turned by
        phi t.

        Column by column, into work buffers kept from call to call (the values of
        ``p + length * rotate(u, phi t)``): each full-size temporary costs a redo its page
        faults, frame after frame.
        """
        return self._circular(t, self._circular_work(), out)

    def _circular(self, t, work, out):
        """:meth:`_circular_at` at ``t`` (a float, or times of shape (T, 1)) with work buffers
        ``work`` (5 arrays of the result's shape without its last axis) into ``out`` (that shape
        and 2): elementwise, so each value is the same whatever the shape."""
        turn, cos, sin, length, term = work
        (u0, u1), p = self._columns
        np.multiply(self._phi, t, out=turn)
        _sincos(turn, sin, cos, length, self._bound)
        np.multiply(self._per_sin, sin, out=length)
        length += np.multiply(self._straight, t, out=term)
        x, y = np.multiply(cos, u0, out=turn), sin  # u turned by phi t
        x -= np.multiply(sin, u1, out=term)
        np.multiply(sin, u0, out=y)
        y += np.multiply(cos, u1, out=term)
        for axis, column in enumerate((x, y)):
            column *= length
            np.add(column, p[axis], out=out[..., axis])
        return out

    def at_times(self, ts):
        """Positions at every time of ``ts`` (shape (T,), each already in [0, 1]), shape
        (T, K, 2): the values :meth:`at` gives time by time (a morph's sampled frames, a
        composite's stages). The circular paths in one pass (:meth:`_circular` on (T, K)
        buffers); the others time by time."""
        ts = np.asarray(ts, dtype=np.float64)
        if not len(ts):
            return np.zeros((0, *self.p.shape))
        if self.kind != "circular":
            return np.stack([self.at(t) for t in ts])
        self._circular_work()
        shape = (len(ts), len(self.p))
        return self._circular(ts[:, None], np.empty((5, *shape)), np.empty((*shape, 2)))

    def at(self, t, out=None):
        """Positions at time ``t`` in [0, 1] (uniform arc-length speed), shape (K, 2); the
        circular paths write them into ``out`` (any (K, 2) array) when given."""
        t = float(np.clip(t, 0.0, 1.0))
        if self.kind == "circular":
            return self._circular_at(t, np.empty(self.p.shape) if out is None else out)
        p, m, q = self.p, self.m, self.q
        if out is not None:
            out[:] = self.at(t)
            return out
        if self.kind == "linear":
            return p + t * (q - p)
        if self.kind == "hat":
            return p + 2 * t * (m - p) if t <= 0.5 else m + (2 * t - 1) * (q - m)
        if self.kind == "tangent":
            return m + _rotate(p - m, self._beta * t)
        # Parabolic: Bezier parameter reached at arc-length fraction t.
        s = self._parabola_parameter(t)[:, None]
        return (1 - s) ** 2 * p + 2 * s * (1 - s) * m + s**2 * q


class LevelPaths(_Polylines):
    """Paths sampled at uniform *times*: ``points[:, j]`` is reached at ``t = j / (S - 1)``.

    The heat-propagation morph stores its gradient paths by level of the field this way, so that
    frame t is that level's iso-contour (not a uniform arc-length traversal).

    Parameters
    ----------
    points : ndarray, shape (K, S, 2)
    """

    def lengths(self):
        """Polyline length of each path, shape (K,)."""
        return np.linalg.norm(np.diff(self.points, axis=1), axis=2).sum(axis=1)

    def at(self, t):
        """Positions at time (level) ``t``, linear between stored levels, shape (K, 2)."""
        f = float(np.clip(t, 0.0, 1.0)) * (self.points.shape[1] - 1)
        j = min(int(np.floor(f)), self.points.shape[1] - 2)
        w = f - j
        return (1 - w) * self.points[:, j] + w * self.points[:, j + 1]


def midpoint_locus(p, m, q, kind):
    """Midpoints of the paths (paper section 4.2), shape (K, 2).

    ``'hat'`` gives the medial axis M (the centres themselves), ``'linear'`` the midpoint
    locus L of Asada and Brady, ``'tangent'`` Leyton's PISA T, ``'circular'`` N and
    ``'parabolic'`` B.
    """
    return BallPaths(p, m, q, kind).at(0.5)
