"""Closest-projection morph (paper sections 2 and 3.5): every sample moves straight to its closest
point on the other curve.

The morph needs the pair to be *c-compatible* (paper section 3.5): every point of P or Q has a
single closest projection on the other curve, so that projecting is a homeomorphism. Both
projections (P onto Q and Q onto P) are checked, whichever one the morph uses, because the
paper's definition is symmetric; where it fails the error says where.

:class:`Projector` (closest points on a polyline for many query points at once) is also used by
the heat-propagation morph.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..ballmap.topology import orient_pair
from ..errors import IncompatibleCurvesError
from ..geometry.circles import circumcircles
from ..geometry.polyline import as_curve, curve_length, resample, resolve_spacing, reverse
from ..geometry.projection import PolylineProjector
from ..geometry.ragged import ragged_arange
from ..geometry.spline import densify
from .base import PathMorph, register
from .paths import LinearPaths

__all__ = ["Projector", "Projection", "ProjectionDefect", "c_compatibility"]

#: Comparison morphs (ballmorph_core.morphs.closest, curvature, laplace, heat).
#: Closest projection: consecutive samples whose closest points step backwards along the other
#: curve by more than this many sample spacings make the projection non-monotone.
PROJECTION_REVERSAL = 0.01
#: Closest projection: a vertex of the other curve passed over between two consecutive samples'
#: closest points lying farther than both samples' distances by this many sample spacings means
#: the closest point jumped (a point in between has two closest projections). A continuous
#: projection passes over vertices only O(h^2 curvature) farther.
PROJECTION_BULGE = 0.25
#: At most this many places are listed in an incompatibility message.
DEFECTS_LISTED = 3


@dataclass
class Projection:
    """Closest points of query points on a curve.

    Attributes
    ----------
    foot : ndarray, shape (K, 2)
        The closest points.
    pos : ndarray, shape (K,)
        Their positions on the projector's dense polyline, in edge units: ``edge + fraction``.
    dist : ndarray, shape (K,)
        Distance from each query point to its closest point.
    """

    foot: np.ndarray
    pos: np.ndarray
    dist: np.ndarray


class Projector:
    """Closest points on one curve, for many query points at once.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
        The target curve (validated).
    closed : bool
    spacing : float
        The morph's sample spacing; the curve is densified and resampled (on its centripetal
        Catmull-Rom spline, like every sampling of the core) at half of it.

    Attributes
    ----------
    dense : ndarray, shape (M, 2)
        The resampled polyline the projections land on.
    """

    def __init__(self, curve, closed, spacing):
        step = 0.5 * float(spacing)
        self.closed = bool(closed)
        self.dense = resample(densify(curve, closed, step), closed, step)
        self._polyline = PolylineProjector(self.dense, closed)
        self.n_edges = self._polyline.n_edges
        self.mean_edge = float(self._polyline.curves.length_of_edge[: self.n_edges].mean())

    def project(self, points):
        """Closest points on the dense polyline.

        Parameters
        ----------
        points : ndarray, shape (K, 2)

        Returns
        -------
        Projection
        """
        x = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        edge, frac = self._polyline.nearest(x)
        foot = self._polyline.foot(edge, frac)
        return self._refine(x, Projection(foot, edge + frac, np.linalg.norm(foot - x, axis=1)))

    def _refine(self, x, proj):
        """Move each foot onto the circle through the three dense vertices nearest to it.

        On a polyline the foot is off by up to a quarter edge along the curve (it is the foot
        on a chord); the closest point on the local osculating circle is second-order accurate
        (the same local-circle idea as the ball-map's refinement). Kept only where it stays
        within that arc and near the polyline foot.
        """
        n_v = len(self.dense)
        j = np.floor(proj.pos + 0.5).astype(np.int64)
        if self.closed:
            j = np.mod(j, n_v)
            jm, jp = np.mod(j - 1, n_v), np.mod(j + 1, n_v)
        else:
            j = np.clip(j, 1, n_v - 2)
            jm, jp = j - 1, j + 1
        a, b, c = self.dense[jm], self.dense[j], self.dense[jp]
        centre, radius, ok = circumcircles(a, b, c)
        ac = c - a
        ac2 = np.einsum("ij,ij->i", ac, ac)
        w = x - centre
        wn = np.linalg.norm(w, axis=1)
        ok &= wn > 0
        foot = centre + radius[:, None] * np.divide(w, wn[:, None], out=np.zeros_like(w), where=ok[:, None])
        t = np.einsum("ij,ij->i", foot - b, ac) / np.maximum(ac2, tol.TINY)
        ok &= (np.abs(t) <= 0.5) & (np.linalg.norm(foot - proj.foot, axis=1) <= np.sqrt(ac2))
        if not self.closed:
            ok &= (proj.pos > 0) & (proj.pos < self.n_edges)  # a stroke's ends stay exact
        proj.foot = np.where(ok[:, None], foot, proj.foot)
        proj.pos = np.where(ok, j + 2.0 * t, proj.pos)
        if self.closed:
            proj.pos = np.mod(proj.pos, self.n_edges)
        proj.dist = np.linalg.norm(x - proj.foot, axis=1)
        return proj

    def fraction(self, pos):
        """Arc-length fractions along the curve as given of dense positions, shape (K,).

        The dense polyline is resampled at uniform arc length of the given polyline, so vertex
        ``j`` sits at fraction ``j / n_edges`` (exactly, unless coarse input was subdivided).
        """
        return np.clip(np.asarray(pos, dtype=np.float64) / self.n_edges, 0.0, 1.0)


@dataclass
class ProjectionDefect:
    """One place where a closest projection is not a homeomorphism.

    Attributes
    ----------
    curve : str
        ``'P'`` or ``'Q'``: the curve whose points are projected onto the other.
    kind : str
        ``'jump'`` (a point between two samples is equidistant to two separate parts of the
        other curve), ``'reversal'`` (the projections run backwards) or ``'winding'`` (the
        projections of a loop do not go once around the other loop).
    point : ndarray, shape (2,)
        Where on ``curve`` (between the two samples).
    s : float
        Its arc length along ``curve`` as given.
    feet : ndarray, shape (2, 2)
        The closest points of the two samples on the other curve.
    s_feet : ndarray, shape (2,)
        Their arc lengths along the other curve as given.
    """

    curve: str
    kind: str
    point: np.ndarray
    s: float
    feet: np.ndarray
    s_feet: np.ndarray

    def describe(self):
        """A sentence saying where (str)."""
        other = "Q" if self.curve == "P" else "P"
        (ax, ay), (bx, by) = self.feet
        where = (
            f"{self.curve} near ({self.point[0]:.4g}, {self.point[1]:.4g}) (s={self.s:.4g}): its closest "
            f"points on {other} go from ({ax:.4g}, {ay:.4g}) (s={self.s_feet[0]:.4g}) to "
            f"({bx:.4g}, {by:.4g}) (s={self.s_feet[1]:.4g})"
        )
        if self.kind == "jump":
            return where + f", jumping over a part of {other}: a point there has two closest projections"
        if self.kind == "reversal":
            return where + f", running backwards along {other}"
        return f"the closest points of {self.curve} do not go once around {other}"


def _defects(name, samples, feet, closed, spacing):
    """Where the projection of consecutive samples onto a curve is not a homeomorphism.

    Parameters
    ----------
    name : str
        The projected curve, ``'P'`` or ``'Q'``.
    samples : tuple
        ``(src, s_src, length_src)``: its uniform samples in order, shape (K, 2), their arc
        lengths along it as given, shape (K,), and its length.
    feet : tuple
        ``(proj, projector, s_feet)``: their closest points on the target (Projection), the
        Projector (running the same way as ``src``), and the arc lengths of the closest points
        along the target as given, shape (K,).
    closed : bool
    spacing : float

    Returns
    -------
    list of ProjectionDefect

    Notes
    -----
    Between consecutive samples the projection must move forward along the target (within
    ``PROJECTION_REVERSAL`` sample spacings), and no target vertex passed over may lie farther
    than both samples' distances from the segment joining them by ``PROJECTION_BULGE`` spacings
    (else the closest point jumped over a bulge of the target: a point in between has two
    closest projections). A loop's projections must go around the target exactly once.
    """
    (src, s_src, length_src), (proj, projector, s_feet) = samples, feet
    k = len(src)
    n = projector.n_edges
    nxt = np.r_[np.arange(1, k), 0] if closed else np.arange(1, k)
    cur = np.arange(len(nxt))
    step = proj.pos[nxt] - proj.pos[cur]
    if closed:
        step = np.mod(step + 0.5 * n, n) - 0.5 * n
    found = []

    def add(kind, i):
        j = nxt[i]
        mid = 0.5 * (src[i] + src[j])
        s_mid = s_src[i] + 0.5 * np.mod(s_src[j] - s_src[i], length_src) if closed else 0.5 * (s_src[i] + s_src[j])
        feet = np.stack([proj.foot[i], proj.foot[j]])
        found.append(ProjectionDefect(name, kind, mid, float(s_mid), feet, s_feet[[i, j]]))

    for i in np.flatnonzero(step * projector.mean_edge < -PROJECTION_REVERSAL * spacing):
        add("reversal", i)
    forward = np.flatnonzero(step > 0)
    start = np.floor(proj.pos[cur[forward]]).astype(np.int64)
    stop = np.ceil(proj.pos[cur[forward]] + step[forward]).astype(np.int64)
    owner, local = ragged_arange(np.maximum(stop - start - 1, 0))
    v = start[owner] + 1 + local
    v = np.mod(v, n) if closed else np.clip(v, 0, len(projector.dense) - 1)
    which = forward[owner]
    a, ab = src[cur[which]], src[nxt[which]] - src[cur[which]]
    ab2 = np.einsum("ij,ij->i", ab, ab)
    w = np.divide(np.einsum("ij,ij->i", projector.dense[v] - a, ab), ab2, out=np.zeros_like(ab2), where=ab2 > 0)
    dist = np.linalg.norm(projector.dense[v] - (a + np.clip(w, 0.0, 1.0)[:, None] * ab), axis=1)
    excess = dist - np.maximum(proj.dist[cur[which]], proj.dist[nxt[which]])
    for i in np.unique(which[excess > PROJECTION_BULGE * spacing]):
        add("jump", i)
    if closed and abs(step.sum() - n) > 0.5 * n:
        add("winding", 0)
    return found


def c_compatibility(P, Q, closed, spacing=None):
    """Where a pair is not c-compatible (paper section 3.5).

    Parameters
    ----------
    P, Q : array_like, shape (N, 2) and (M, 2)
        Disjoint nested loops or strokes sharing both endpoints (paper configurations 1, 2).
    closed : bool
    spacing : float, optional
        Sample spacing of the check (default from the curves).

    Returns
    -------
    list of ProjectionDefect
        Empty when both closest projections (P onto Q, Q onto P) are homeomorphisms at this
        sampling.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    >>> c = np.c_[np.cos(t), np.sin(t)]
    >>> c_compatibility(c, 2 * c, closed=True)
    []
    """
    P, Q = as_curve(P, "P", closed), as_curve(Q, "Q", closed)
    return _ClosestPair(P, Q, closed, resolve_spacing(P, Q, closed, spacing)).defects


class _ClosestPair:
    """Both closest projections of a pair, sampled uniformly, and their defects."""

    def __init__(self, P, Q, closed, spacing):
        setup = orient_pair(P, Q, closed)
        # Whether Q as given runs against P (a stroke starting at P's end, a loop turning the
        # other way): each target is then reversed so both curves run the same way.
        self.flip = setup.reversed_p != setup.reversed_q
        self.closed = closed
        self.spacing = spacing
        self.lengths = {"P": curve_length(P, closed), "Q": curve_length(Q, closed)}
        self.samples = {"P": resample(P, closed, spacing), "Q": resample(Q, closed, spacing)}
        curves = {"P": P, "Q": Q}
        self.maps = {}
        self.defects = []
        for src, dst in (("P", "Q"), ("Q", "P")):
            target = reverse(curves[dst], closed) if self.flip else curves[dst]
            projector = Projector(target, closed, spacing)
            x = self.samples[src]
            proj = projector.project(x)
            if not closed:
                # The shared endpoints map to each other exactly.
                last = projector.n_edges
                proj.foot[0], proj.foot[-1] = projector.dense[0], projector.dense[-1]
                proj.pos[0], proj.pos[-1] = 0.0, float(last)
                proj.dist[0] = proj.dist[-1] = 0.0
            u_src = self._uniform(len(x))
            u_dst = projector.fraction(proj.pos)
            if self.flip:
                u_dst = np.mod(1.0 - u_dst, 1.0) if closed else 1.0 - u_dst
            self.maps[src] = (x, proj.foot, u_src, u_dst)
            length = self.lengths[src]
            s_feet = u_dst * self.lengths[dst]
            self.defects += _defects(src, (x, u_src * length, length), (proj, projector, s_feet), closed, spacing)

    def _uniform(self, k):
        return np.arange(k) / (k if self.closed else k - 1)


@register("closest-projection")
def build(P, Q, closed, spacing, sampling):
    """Closest-projection morph: straight trajectories to the closest points.

    ``sampling='p'`` (and ``'symmetric'``, the same: this morph is not symmetric) samples P
    uniformly at ``spacing`` and moves each sample to its closest point on Q; ``'q'`` samples
    Q uniformly, pairs each sample with its closest point on P and moves from there. Samples
    are ordered along P as given.

    Raises
    ------
    IncompatibleCurvesError
        If the pair is not in configuration 1 or 2, or not c-compatible (either projection is
        not a homeomorphism at this sampling); the message says where and ``error.report``
        lists the :class:`ProjectionDefect` found.
    """
    pair = _ClosestPair(P, Q, closed, resolve_spacing(P, Q, closed, spacing))
    if pair.defects:
        listed = "; ".join(d.describe() for d in pair.defects[:DEFECTS_LISTED])
        more = len(pair.defects) - DEFECTS_LISTED
        tail = f"; and {more} more places" if more > 0 else ""
        raise IncompatibleCurvesError(
            "not c-compatible: a closest projection is not a homeomorphism (paper section 3.5): "
            + listed
            + tail
            + "; use a ball-morph or the heat-propagation morph instead",
            pair.defects,
        )
    if sampling == "q":
        q, p, u_q, u_p = pair.maps["Q"]
        if pair.flip:  # keep the samples in P's direction
            order = np.r_[0, np.arange(len(q) - 1, 0, -1)] if closed else np.arange(len(q))[::-1]
            p, q, u_p, u_q = p[order], q[order], u_p[order], u_q[order]
    else:
        p, q, u_p, u_q = pair.maps["P"]
    return PathMorph("closest-projection", closed, LinearPaths(p, q), u_p, u_q)
