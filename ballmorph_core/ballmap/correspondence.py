"""The ball-map correspondence between two polylines (paper sections 4.1 and 5.2).

For a sample ``p`` of P with unit normal ``n`` pointing into the gap, the ball-map finds the
smallest ``r >= 0`` such that the disk of centre ``m = p + r n`` and radius ``r`` touches Q
(:mod:`.candidates`). Every dense sample of each curve is mapped by lacing by bisection
(:mod:`.lacing`), the disks are checked for emptiness (:mod:`.check`), and the two one-way maps
are joined and thinned into symmetric samples (:mod:`.thinning`, the paper's approach 3).
``sampling='p'`` is the paper's approach 2 (uniform samples on P mapped to Q), used for its fair
comparison; ``'q'`` the mirror.
"""

from dataclasses import dataclass, replace

import numpy as np

from .. import tolerances as tol
from ..errors import IncompatibleCurvesError
from ..geometry.polyline import as_curve, resolve_spacing, scale_of
from ..options import SAMPLINGS, check_option
from .check import check_maps
from .lacing import one_way
from .onemap import OneWayMap
from .report import CompatibilityReport
from .sides import Sides
from .thinning import symmetric_samples
from .topology import PairSetup, orient_pair

__all__ = [
    "Correspondence",
    "MapBatch",
    "map_batch",
    "ball_map",
    "ball_maps",
    "DenseMaps",
    "dense_maps",
    "dense_map_batch",
]


#: Fields of a Correspondence that trade places when it is read from Q to P.
_MIRROR = (("p", "q"), ("normal_p", "normal_q"), ("s_p", "s_q"), ("dense_p", "dense_q"))


@dataclass
class Correspondence:
    """A sampled ball-map correspondence.

    Attributes
    ----------
    p : ndarray, shape (K, 2)
        Samples on P (in order along the oriented P).
    q : ndarray, shape (K, 2)
        Their images on Q.
    centers : ndarray, shape (K, 2)
        Centres of the maximal disks.
    radii : ndarray, shape (K,)
        Their radii: ``|centers - p| = |centers - q| = radii``.
    normal_p, normal_q : ndarray, shape (K, 2)
        Unit normals of P at p and of Q at q, pointing into the gap.
    s_p, s_q : ndarray, shape (K,)
        Arc-length positions of p on the oriented P and of q on the oriented Q (for loops,
        unwrapped so they increase; take them modulo the length for a position).
    closed : bool
    setup : PairSetup
        The oriented curves and the side of the gap.
    dense_p, dense_q : ndarray, shape (Np, 2), (Nq, 2)
        The resampled polylines the map was computed on.
    spacing : float
        The geodesic sample spacing.
    report : CompatibilityReport
    """

    p: np.ndarray
    q: np.ndarray
    centers: np.ndarray
    radii: np.ndarray
    normal_p: np.ndarray
    normal_q: np.ndarray
    s_p: np.ndarray
    s_q: np.ndarray
    closed: bool
    setup: PairSetup
    dense_p: np.ndarray
    dense_q: np.ndarray
    spacing: float
    report: CompatibilityReport

    def __len__(self):
        return len(self.p)

    def inverse(self):
        """The same correspondence read from Q to P (Correspondence)."""
        mirrored = {a: getattr(self, b) for pair in _MIRROR for a, b in (pair, pair[::-1])}
        return replace(self, setup=self.setup.swapped(), **mirrored)

    @classmethod
    def from_map(cls, one_way, setup, dense_p, dense_q, spacing, report):
        """The correspondence held by a one-way map's rows (all of one chain)."""
        return cls(
            p=one_way.src,
            q=one_way.dst,
            centers=one_way.m,
            radii=one_way.r,
            normal_p=one_way.n_src,
            normal_q=one_way.n_dst,
            s_p=one_way.s_src,
            s_q=one_way.s_dst,
            closed=bool(setup.closed),
            setup=setup,
            dense_p=dense_p,
            dense_q=dense_q,
            spacing=spacing,
            report=report,
        )


def _both_sides(setups, spacing):
    closed = np.array([s.closed for s in setups], dtype=bool)
    sp = Sides([s.P for s in setups], closed, [s.side_p for s in setups], spacing)
    sq = Sides([s.Q for s in setups], closed, [s.side_q for s in setups], spacing)
    reports = [CompatibilityReport("disjoint-loops" if c else "quasi-disjoint-strokes") for c in closed]
    return closed, sp, sq, reports


def _count_samples(maps, reports):
    for one_way_map, _, _, _ in maps:
        counts = np.bincount(one_way_map.chain, minlength=len(reports))
        for c, report in enumerate(reports):
            report.samples += int(counts[c])


@dataclass
class MapBatch:
    """The ball-maps of a batch of pairs as arrays, chain after chain.

    Attributes
    ----------
    samples : OneWayMap
        Every pair's samples, sorted by pair (its ``chain``) and along P; a coincident pair's are
        its dense points with zero disks.
    offsets : ndarray of int, shape (C + 1,)
        Pair ``c`` owns samples ``offsets[c]:offsets[c + 1]``.
    sides_p, sides_q : Sides
        The dense curves (their ``rg.length`` are the lengths the samples' arc lengths run along).
    reports : list of CompatibilityReport
    spacing : ndarray, shape (C,)
    """

    samples: OneWayMap
    offsets: np.ndarray
    sides_p: Sides
    sides_q: Sides
    reports: list
    spacing: np.ndarray


def _static_rows(setups, sp):
    """Coincident pairs: every dense point maps to itself with a zero disk (OneWayMap)."""
    coincident = np.array([s.coincident for s in setups], dtype=bool)
    rows = coincident[sp.rg.owner]
    pts, normals = sp.rg.pts[rows], sp.vnormals[rows]
    zeros = np.zeros(len(pts))
    return OneWayMap(
        pts, pts, pts, zeros, np.ones(len(pts), bool), sp.rg.s[rows], sp.rg.s[rows], normals, normals, sp.rg.owner[rows]
    )


def map_batch(setups, spacing, sampling="symmetric", eps=None):
    """Ball-maps of many oriented pairs at once, as arrays (MapBatch; see :func:`ball_maps`)."""
    n = len(setups)
    spacing = np.broadcast_to(np.asarray(spacing, dtype=np.float64), (n,)).copy()
    if eps is None:
        eps = np.array([tol.COINCIDENT * scale_of(s.P, s.Q) for s in setups])
    eps = float(np.min(eps))
    # Both one-way maps sample their source at the output spacing; the symmetric thinning then
    # keeps about one of their union's pairs per spacing (half the spacing would double the work
    # for no visible gain: every kept pair is an exact contact either way).
    _, sp, sq, reports = _both_sides(setups, spacing)
    fwd = one_way(sp, sq, eps) if sampling in ("p", "symmetric") else None
    bwd = one_way(sq, sp, eps) if sampling in ("q", "symmetric") else None
    maps = [(m, a, b, d) for m, a, b, d in ((fwd, sp, sq, "P"), (bwd, sq, sp, "Q")) if m is not None]
    _count_samples(maps, reports)
    check_maps(maps, spacing, eps, reports)
    if sampling == "p":
        out = fwd
    elif sampling == "q":
        out = bwd.flipped()
    else:
        out = symmetric_samples(fwd, bwd, sp, sq, spacing, spacing, reports)
    coincident = np.array([s.coincident for s in setups], dtype=bool)
    if coincident.any():
        out = OneWayMap.concatenate([out.take(~coincident[out.chain]), _static_rows(setups, sp)])
        out = out.take(np.argsort(out.chain, kind="stable"))
    for c in np.flatnonzero(coincident):
        reports[c] = CompatibilityReport("coincident", samples=int(np.sum(out.chain == c)))
    return MapBatch(out, np.searchsorted(out.chain, np.arange(n + 1)), sp, sq, reports, spacing)


def ball_maps(setups, spacing, sampling="symmetric", check=True, eps=None):
    """Ball-maps of many oriented pairs at once (the batched engine behind :func:`ball_map`).

    Parameters
    ----------
    setups : list of PairSetup
        Pairs already checked and oriented by :func:`~ballmorph_core.ballmap.topology.orient_pair`
        (or an equivalent batched check).
    spacing : array_like, shape (C,)
        Output sample spacing of each pair.
    sampling : {'symmetric', 'p', 'q'}
        Already validated (see :func:`ball_map`).
    check : bool
        Raise for the first pair that is not b-compatible; with False every pair's
        ``report`` says where it fails.
    eps : array_like, shape (C,), optional
        Absolute length tolerance per pair (default from each pair's size).

    Returns
    -------
    list of Correspondence
    """
    if not setups:
        return []
    batch = map_batch(setups, spacing, sampling, eps)
    result = []
    for c, setup in enumerate(setups):
        if check and batch.reports[c].violations:
            raise IncompatibleCurvesError(batch.reports[c].describe(), batch.reports[c])
        rows = batch.samples.take(slice(batch.offsets[c], batch.offsets[c + 1]))
        dense_p, dense_q = batch.sides_p.rg.curve(c), batch.sides_q.rg.curve(c)
        if setup.coincident:
            dense_q = dense_p.copy()
        result.append(Correspondence.from_map(rows, setup, dense_p, dense_q, float(batch.spacing[c]), batch.reports[c]))
    return result


@dataclass
class DenseMaps:
    """Both one-way ball-maps of a pair at the dense spacing (for the composite ball-morph).

    Attributes
    ----------
    setup : PairSetup
    side_p, side_q : Side
        Dense samples of the oriented P and Q (``pts``, ``cum``, ``length``, normals).
    fwd, bwd : OneWayMap
        P -> Q and Q -> P maps; ``bad`` marks samples whose disk is entered or missing.
    spacing : float
        The dense spacing.
    eps : float
    report : CompatibilityReport
    """

    setup: PairSetup
    side_p: object
    side_q: object
    fwd: object
    bwd: object
    spacing: float
    eps: float
    report: CompatibilityReport


def dense_maps(P, Q, closed, spacing, setup=None):
    """Compute both one-way maps of validated curves at ``spacing`` and check them (DenseMaps).

    Unlike :func:`ball_map` this never raises for incompatibility: ``report`` and the ``bad``
    masks say where the disks fail.
    """
    return dense_map_batch([orient_pair(P, Q, closed) if setup is None else setup], [spacing])[0]


def dense_map_batch(setups, spacing):
    """:func:`dense_maps` of many oriented pairs at once (list of DenseMaps), at ``spacing``
    (array_like, shape (C,)); each pair's maps are the rows of its own chain. The batch's
    length tolerance is its smallest pair's (as :func:`map_batch`'s); each DenseMaps keeps its
    own pair's for what is done with it afterwards."""
    if not setups:
        return []
    h = np.asarray(spacing, dtype=np.float64)
    own = np.array([tol.COINCIDENT * scale_of(s.P, s.Q) for s in setups])
    eps = float(own.min())
    _, sp, sq, reports = _both_sides(setups, h)
    fwd, bwd = one_way(sp, sq, eps), one_way(sq, sp, eps)
    maps = ((fwd, sp, sq, "P"), (bwd, sq, sp, "Q"))
    _count_samples(maps, reports)
    check_maps(maps, h, eps, reports)
    # Each map's rows come chain after chain (one_way keeps its sources' order); each pair's
    # own maps are chain 0, as when mapped alone.
    bounds = [np.searchsorted(m.chain, np.arange(len(setups) + 1)) for m in (fwd, bwd)]

    def alone(m, lo, hi):
        return replace(m.take(slice(lo, hi)), chain=np.zeros(hi - lo, m.chain.dtype))

    return [
        DenseMaps(
            setup,
            sp.view(c),
            sq.view(c),
            *(alone(m, b[c], b[c + 1]) for m, b in zip((fwd, bwd), bounds)),
            float(h[c]),
            float(own[c]),
            reports[c],
        )
        for c, setup in enumerate(setups)
    ]


def ball_map(P, Q, closed=False, spacing=None, sampling="symmetric", check=True):
    """Ball-map correspondence between two curves (paper sections 4.1, 5.2).

    Parameters
    ----------
    P, Q : array_like, shape (N, 2) and (M, 2)
        Strokes sharing both endpoints (``closed=False``, configuration 2) or disjoint nested
        loops (``closed=True``, configuration 1). Not modified.
    closed : bool
    spacing : float, optional
        Geodesic sample spacing; default :func:`~ballmorph_core.geometry.polyline.default_spacing`.
    sampling : {'symmetric', 'p', 'q'}
        ``'symmetric'``: the paper's approach 3 (default; does not depend on which curve is
        P). ``'p'``: approach 2, uniform samples on P mapped to Q (the paper's choice for its
        fair comparison). ``'q'``: uniform samples on Q mapped back. Upper case is accepted.
    check : bool
        Raise :class:`IncompatibleCurvesError` if a maximal disk is entered by a curve.

    Returns
    -------
    Correspondence
        Samples in order along the oriented P (loops clockwise; a stroke Q is reversed if it
        started at P's end).

    Raises
    ------
    InvalidCurveError
        Malformed input (shape, NaN, too few points, bad option).
    IncompatibleCurvesError
        The pair is not in configuration 1 or 2, or (with ``check``) not b-compatible; the
        message and ``error.report`` say where.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    >>> c = np.c_[np.cos(t), np.sin(t)]
    >>> corr = ball_map(c, 3 * c, closed=True)
    >>> bool(np.allclose(corr.radii, 1.0, atol=1e-3))
    True
    """
    sampling = check_option("sampling", sampling, SAMPLINGS)
    P = as_curve(P, "P", closed)
    Q = as_curve(Q, "Q", closed)
    spacing = resolve_spacing(P, Q, closed, spacing)
    setup = orient_pair(P, Q, closed)
    return ball_maps([setup], [spacing], sampling, check)[0]
