"""The ball-map correspondence between two polylines (paper sections 4.1 and 5.2).

For a sample ``p`` of P with unit normal ``n`` pointing into the gap, the ball-map finds the
smallest ``r >= 0`` such that the disk of centre ``m = p + r n`` and radius ``r`` touches Q. On a
polyline Q the candidates are (paper equations 3-5):

* a vertex ``v``: ``r = |v - p|^2 / (2 (v - p) . n)``, valid when the denominator is positive;
* an edge ``c -> d`` with unit normal ``N`` into the gap: ``r = ((p - c) . N) / (1 - n . N)``,
  contact ``q = p + r n - r N``, discarded when ``q`` is off the edge or ``1 - n . N`` is below
  ``tolerances.PARALLEL`` (an edge facing the same way as ``n``: no finite disk touches it).

**Lacing by bisection.** For b-compatible curves the images advance monotonically along Q as
the samples advance along P: the invariant the paper's lacing walk (section 5.2, step dStep)
relies on. We use the same invariant but fill it in by bisection, so numpy handles a whole
level at once: the ends of a stroke pair map to the shared endpoints (for a loop, one sample is
mapped by a full search); then the middle sample of every bracket is searched only over the
edges of Q between the images of the bracket's ends. Each level costs about ``N + M``
candidate tests, and there are ``log2 N`` levels: ``O((N + M) log N)`` with no Python loop
over samples or edges. Non-monotone true images (incompatible input) show up in the
emptiness check below instead of corrupting the order.

**Symmetric sampling (default).** The paper's approach 3: both curves are sampled densely, each
sample is mapped to the other curve, the union of the pairs is ordered along the (monotone)
correspondence graph and thinned so that between consecutive kept pairs one of the two contacts
has moved by the spacing and the other by at most the spacing. Every kept pair is an exact
ball-map contact; swapping P and Q gives the same pairs. ``sampling='P'`` is the paper's
approach 2 (uniform samples on P mapped to Q), used for its fair comparison; ``'Q'`` the mirror.

**Check.** Every maximal disk must be empty: the vertices near its contacts may enter it by at
most ``tolerances.DISK_PENETRATION`` sample spacings, and a k-d tree over both curves'
vertices (:class:`~ballmorph_core.spatial.CurveTree`) finds any other part of the curves
deeper inside than ``tolerances.NONLOCAL_*``. Such a disk
touches a curve twice, i.e. the medial axis of the gap bifurcates there (paper section 3.3), and
the pair is not b-compatible at that place.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..errors import IncompatibleCurvesError
from ..geometry.polyline import as_curve, densify, resolve_spacing, scale_of
from ..geometry.ragged import Ragged
from ..geometry.spatial import CurveTree, ragged_arange
from ..options import check_option
from .topology import CompatibilityReport, PairSetup, Violation, orient_pair

__all__ = ["Correspondence", "ball_map", "ball_maps", "SAMPLINGS", "DenseMaps", "dense_maps", "disk_between"]

SAMPLINGS = ("symmetric", "P", "Q")


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
        s = self.setup
        setup = PairSetup(s.Q, s.P, s.closed, s.side_q, s.side_p, s.reversed_q, s.reversed_p, s.coincident)
        return Correspondence(
            self.q,
            self.p,
            self.centers,
            self.radii,
            self.normal_q,
            self.normal_p,
            self.s_q,
            self.s_p,
            self.closed,
            setup,
            self.dense_q,
            self.dense_p,
            self.spacing,
            self.report,
        )


# --------------------------------------------------------------------------------------------
# Candidate disks (paper equations 3-5), for flat arrays of (sample, edge) pairs.


def _candidates(x, n, a, b, N, eps):
    """Smallest tangent disk at x (normal n) touching edge a->b (normal N) or its ends.

    Returns r (inf where none) and the contact's position along the edge in [0, 1].
    """
    d = b - a
    len2 = np.einsum("ij,ij->i", d, d)
    # Edge (eq. 4, 5).
    num = np.einsum("ij,ij->i", x - a, N)
    den = 1.0 - np.einsum("ij,ij->i", n, N)
    with np.errstate(divide="ignore", invalid="ignore"):
        r_e = np.where(den > tol.PARALLEL, num / den, np.inf)
    r_e = np.where(r_e >= -eps, np.maximum(r_e, 0.0), np.inf)
    q = x + np.where(np.isfinite(r_e), r_e, 0.0)[:, None] * (n - N)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.einsum("ij,ij->i", q - a, d) / len2
    r_e = np.where((u >= -tol.ON_EDGE) & (u <= 1 + tol.ON_EDGE), r_e, np.inf)
    u = np.clip(np.nan_to_num(u), 0.0, 1.0)
    # Vertices (eq. 3): r = |v - x|^2 / (2 (v - x) . n).
    best_r, best_u = r_e, u
    for vert, uu in ((a, 0.0), (b, 1.0)):
        dv = vert - x
        dist2 = np.einsum("ij,ij->i", dv, dv)
        den_v = 2.0 * np.einsum("ij,ij->i", dv, n)
        with np.errstate(divide="ignore", invalid="ignore"):
            r_v = np.where(den_v > 0, dist2 / den_v, np.inf)
        r_v = np.where(dist2 <= eps * eps, 0.0, r_v)
        better = r_v < best_r
        best_r = np.where(better, r_v, best_r)
        best_u = np.where(better, uu, best_u)
    return best_r, best_u


def _segment_argmin(values, owner, n_groups):
    """Index of the first minimum of ``values`` within each group (groups contiguous)."""
    starts = np.flatnonzero(np.r_[True, owner[1:] != owner[:-1]])
    mins = np.minimum.reduceat(values, starts)
    counts = np.diff(np.r_[starts, len(values)])
    hit = np.flatnonzero(values == np.repeat(mins, counts))
    groups, first = np.unique(owner[hit], return_index=True)
    out = np.zeros(n_groups, dtype=np.int64)
    out[groups] = hit[first]
    return out


# --------------------------------------------------------------------------------------------
# One side of a batch of pairs: every chain's curve, densely resampled, with gap normals.


class _Sides:
    """Dense samples of one curve per chain, with normals pointing into each chain's gap.

    Attributes
    ----------
    rg : Ragged
    vnormals, enormals : ndarray, shape (N, 2)
        Vertex normals and edge normals (by first vertex).
    """

    def __init__(self, curves, closed, sides, spacing):
        spacing = np.asarray(spacing, dtype=np.float64)
        # Coarse, hand-placed polylines get a few interpolating subdivision steps first.
        curves = [densify(c, cl, h) for c, cl, h in zip(curves, closed, spacing)]
        raw = Ragged.from_list(curves, closed)
        counts = np.round(raw.length / spacing).astype(np.int64) + np.where(raw.closed, 0, 1)
        self.rg = raw.resample(counts)
        side = np.asarray(sides, dtype=np.float64)[self.rg.owner][:, None]
        self.vnormals = side * self.rg.vertex_normals()
        self.enormals = side * self.rg.edge_normals()

    def view(self, c):
        """Curve ``c`` as a single-curve view (for the composite ball-morph)."""
        rg = self.rg
        sl = slice(rg.offsets[c], rg.offsets[c + 1])
        n_e = rg.n_edges[c]
        return _Side(
            rg.pts[sl],
            self.vnormals[sl],
            self.enormals[sl][:n_e],
            np.concatenate([rg.s[sl], [rg.length[c]]]) if rg.closed[c] else rg.s[sl],
            float(rg.length[c]),
        )


@dataclass
class _Side:
    """One dense curve: points, normals, arc length (``cum`` as curves.cumulative_length)."""

    pts: np.ndarray
    vnormals: np.ndarray
    enormals: np.ndarray
    cum: np.ndarray
    length: float


# --------------------------------------------------------------------------------------------
# Lacing by bisection, batched over chains.


def _lace(src, dst, eps):
    """Map every sample of chain ``c``'s source curve onto its target curve.

    Returns
    -------
    r : ndarray, shape (N,)
        Radii (inf where no disk was found in the window).
    pos : ndarray, shape (N,)
        Contact positions in units of target edges (``e + u``), unwrapped for loops.
    """
    s_rg, d_rg = src.rg, dst.rg
    n_chains = len(s_rg)
    xo, do = s_rg.offsets, d_rg.offsets
    n_e = d_rg.n_edges
    closed = d_rg.closed
    X, NX = s_rg.pts, src.vnormals
    A = d_rg.pts
    B = A + d_rg.edge
    NE = dst.enormals
    r = np.full(len(X), np.inf)
    pos = np.zeros(len(X))

    def solve(samples, chain, e_lo, e_hi):
        # In chunks of at most CANDIDATE_BUDGET (sample, edge) pairs, to bound memory.
        counts = e_hi - e_lo + 1
        ends = np.cumsum(counts)
        r_out, pos_out = np.empty(len(samples)), np.empty(len(samples))
        start = 0
        while start < len(samples):
            base = ends[start - 1] if start else 0
            stop = max(start + 1, int(np.searchsorted(ends, base + tol.CANDIDATE_BUDGET, side="right")))
            sl = slice(start, stop)
            owner, local = ragged_arange(counts[sl])
            c = chain[sl][owner]
            e_local = e_lo[sl][owner] + local
            g = do[c] + np.where(closed[c], e_local % np.maximum(n_e[c], 1), e_local)
            s = samples[sl][owner]
            rr, uu = _candidates(X[s], NX[s], A[g], B[g], NE[g], eps)
            best = _segment_argmin(rr, owner, stop - start)
            r_out[sl], pos_out[sl] = rr[best], e_local[best] + uu[best]
            start = stop
        return r_out, pos_out

    chains = np.arange(n_chains)
    lo_idx, hi_idx = xo[:-1].copy(), xo[1:] - 1
    lo_pos, hi_pos = np.zeros(n_chains), n_e.astype(np.float64)
    opened = ~closed
    r[lo_idx[opened]] = 0.0
    r[hi_idx[opened]] = 0.0
    pos[hi_idx[opened]] = n_e[opened]
    loops = chains[closed]
    if len(loops):
        rr, pp = solve(lo_idx[loops], loops, np.zeros(len(loops), np.int64), n_e[loops] - 1)
        r[lo_idx[loops]], pos[lo_idx[loops]] = rr, pp
        lo_pos[loops] = pp
        # A loop's chain closes on its first sample, one lap later.
        hi_idx[loops] = xo[1:][loops]
        hi_pos[loops] = pp + n_e[loops]
    chain, lo, hi, plo, phi = chains, lo_idx, hi_idx, lo_pos, hi_pos
    while True:
        keep = hi - lo > 1
        chain, lo, hi, plo, phi = chain[keep], lo[keep], hi[keep], plo[keep], phi[keep]
        if len(chain) == 0:
            break
        mid = (lo + hi) // 2
        laps = np.where(closed[chain], 2 * n_e[chain], n_e[chain])
        e_lo = np.clip(np.floor(plo).astype(np.int64), 0, laps - 1)
        e_hi = np.clip(np.ceil(phi).astype(np.int64) - 1, e_lo, laps - 1)
        rr, pp = solve(mid, chain, e_lo, e_hi)
        # The window is whole edges, so the best contact may lie just outside the bracket: then
        # the true image does not advance monotonically (or sits on the bracket's end). Clipping
        # it would move the contact off its disk, so beyond round-off it counts as no disk found
        # here; the check reports the sample and the repair searches it without a window.
        outside = (pp < plo - tol.ROUNDOFF * laps) | (pp > phi + tol.ROUNDOFF * laps)
        rr = np.where(outside, np.inf, rr)
        pp = np.where(np.isfinite(rr), np.clip(pp, plo, phi), plo)
        r[mid], pos[mid] = rr, pp
        chain, lo, hi, plo, phi = (
            np.concatenate([chain, chain]),
            np.concatenate([lo, mid]),
            np.concatenate([mid, hi]),
            np.concatenate([plo, pp]),
            np.concatenate([pp, phi]),
        )
    return r, pos


def _contacts(dst, chain, pos):
    """Contact points, unwrapped arc lengths and edge normals at positions on target edges."""
    rg = dst.rg
    n_e = np.maximum(rg.n_edges[chain], 1)
    closed = rg.closed[chain]
    e = np.clip(np.floor(pos).astype(np.int64), 0, np.where(closed, 2 * n_e, n_e) - 1)
    u = np.clip(pos - e, 0.0, 1.0)
    lap = np.where(closed, e // n_e, 0)
    g = rg.offsets[chain] + np.where(closed, e % n_e, e)
    q = rg.pts[g] + u[:, None] * rg.edge[g]
    s = rg.s[g] + u * rg.length_of_edge[g] + lap * rg.length[chain]
    return q, s, dst.enormals[g]


def _refine(x, n, dst, chain, pos, r, eps):
    """Refine polyline contacts on the circle through the three nearest target vertices.

    On a polygon the ball-map is a staircase (every disk touches a flat edge at the foot of its
    centre). Treating the target locally as the circular arc through three consecutive
    vertices (the paper's exact construction for piecewise-circular curves, section 5.1,
    equations 1-2) makes the map exact on circles and second-order accurate on smooth curves.
    A refined contact is kept only if it stays within the arc's span and near the polyline one.

    Returns ok, r_new, q_new and s_new (arc length on the target, within one lap).
    """
    rg = dst.rg
    n_v = rg.n[chain]
    closed = rg.closed[chain]
    j = np.floor(pos + 0.5).astype(np.int64)
    jl = np.where(closed, j % np.maximum(n_v, 1), np.minimum(np.maximum(j, 1), np.maximum(n_v - 2, 1)))
    ok = np.isfinite(r) & (r > eps) & (closed | ((j >= 1) & (j <= n_v - 2)))
    g0 = rg.offsets[chain] + jl
    gm, gp = rg.prv[g0], rg.nxt[g0]
    ok &= (gm >= 0) & (gp >= 0)
    gm, gp = np.maximum(gm, 0), np.maximum(gp, 0)
    a, b, c = rg.pts[gm], rg.pts[g0], rg.pts[gp]
    # Circumcentre of (a, b, c).
    ab, ac = b - a, c - a
    det = 2.0 * (ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0])
    ab2, ac2 = np.einsum("ij,ij->i", ab, ab), np.einsum("ij,ij->i", ac, ac)
    with np.errstate(divide="ignore", invalid="ignore"):
        cx = (ac[:, 1] * ab2 - ab[:, 1] * ac2) / det
        cy = (ab[:, 0] * ac2 - ac[:, 0] * ab2) / det
    centre = a + np.stack([cx, cy], axis=1)
    rad = np.hypot(cx, cy)
    # Nearly straight: the polyline contact is already right, and the circle would cancel badly.
    ok &= (np.abs(det) > 1e-9 * ab2 + 1e-300) & (rad < 1e4 * np.sqrt(ac2))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        w = x - centre
        wn = np.einsum("ij,ij->i", w, n)
        inside = np.einsum("ij,ij->i", dst.vnormals[g0], centre - b) > 0
        den = 2.0 * wn + np.where(inside, 2.0, -2.0) * rad
        r_new = (rad * rad - np.einsum("ij,ij->i", w, w)) / den
        m = x + r_new[:, None] * n
        dm = m - centre
        q_new = centre + rad[:, None] * dm / np.linalg.norm(dm, axis=1, keepdims=True)
        chord = c - a
        t = np.einsum("ij,ij->i", q_new - b, chord) / np.einsum("ij,ij->i", chord, chord)
        r_safe = np.where(np.isfinite(r), r, 0.0)
        ok &= np.isfinite(r_new) & (r_new >= 0) & (np.abs(t) <= 0.5)
        ok &= np.abs(r_new - r_safe) <= 0.25 * r_safe + np.linalg.norm(chord, axis=1)
    s_new = rg.s[g0] + t * (rg.length_of_edge[gm] + rg.length_of_edge[g0])
    return ok, r_new, q_new, s_new


def _same_lap(s_new, s_ref, length, closed):
    """Put loop positions on the lap of reference (unwrapped) positions."""
    return np.where(closed, s_new + length * np.round((s_ref - s_new) / np.maximum(length, 1e-300)), s_new)


def _one_way(src, dst, eps):
    """Map every dense sample of each chain's source onto its target: dict of arrays."""
    r, pos = _lace(src, dst, eps)
    chain = src.rg.owner
    q, s_dst, n_edge = _contacts(dst, chain, pos)
    better, r_new, q_new, s_new = _refine(src.rg.pts, src.vnormals, dst, chain, pos, r, eps)
    closed = dst.rg.closed[chain]
    length = dst.rg.length[chain]
    s_new = _same_lap(s_new, s_dst, length, closed)
    # Refining must not break the monotone order lacing produced: where refined neighbours
    # would step back, both fall back to their polyline contacts (which are in order).
    nxt = src.rg.nxt
    has_next = nxt >= 0
    nxt_safe = np.maximum(nxt, 0)
    wraps = has_next & (nxt_safe == src.rg.offsets[:-1][chain])
    for _ in range(8):
        s_try = np.where(better, s_new, s_dst)
        step = s_try[nxt_safe] + np.where(wraps, length, 0.0) - s_try
        back = np.flatnonzero(has_next & (step < 0))
        if len(back) == 0:
            break
        better[back] = False
        better[nxt_safe[back]] = False
    r = np.where(better, r_new, r)
    q = np.where(better[:, None], q_new, q)
    s_dst = np.where(better, s_new, s_dst)
    return _assemble(src, chain, src.rg.pts, src.vnormals, src.rg.s, r, q, s_dst, n_edge, eps)


def _assemble(src, chain, x, n, s_src, r, q, s_dst, n_edge, eps):
    ok = np.isfinite(r)
    rr = np.where(ok, r, 0.0)
    m = x + rr[:, None] * n
    with np.errstate(invalid="ignore", divide="ignore"):
        n_dst = np.where((rr > eps)[:, None], (m - q) / rr[:, None], n_edge)
    return dict(src=x, dst=q, m=m, r=rr, ok=ok, s_src=s_src, s_dst=s_dst, n_src=n, n_dst=n_dst, chain=chain)


def _full_search(x, n, dst, chain, eps, budget=tol.CANDIDATE_BUDGET):
    """Smallest disk at each sample over all edges of its chain's target (no lacing window)."""
    rg = dst.rg
    counts = rg.n_edges[chain]
    r = np.full(len(x), np.inf)
    pos = np.zeros(len(x))
    start = 0
    cum = np.cumsum(counts)
    while start < len(x):
        stop = max(start + 1, int(np.searchsorted(cum, (cum[start - 1] if start else 0) + budget)))
        sl = slice(start, stop)
        owner, local = ragged_arange(counts[sl])
        g = rg.offsets[chain[sl]][owner] + local
        rr, uu = _candidates(x[sl][owner], n[sl][owner], rg.pts[g], rg.pts[g] + rg.edge[g], dst.enormals[g], eps)
        best = _segment_argmin(rr, owner, stop - start) if len(rr) else np.zeros(0, np.int64)
        if len(rr):
            r[sl], pos[sl] = rr[best], local[best] + uu[best]
        start = stop
    return r, pos


def _repair(one_way, src, dst, eps):
    """Redo the samples whose lacing result failed the check with an unwindowed search.

    On a pair that is not b-compatible, a wrong contact at one bisection level narrows the
    windows of the samples between it and the next anchor; those samples then fail too,
    although their true maximal disks are fine. Searching them over the whole target curve
    restores them, so reports and the composite ball-morph see only the real trouble.
    """
    idx = np.flatnonzero(one_way["bad"])
    if len(idx) == 0 or len(idx) > tol.REPAIR_LIMIT:
        return
    chain = one_way["chain"][idx]
    x, n = one_way["src"][idx], one_way["n_src"][idx]
    r, pos = _full_search(x, n, dst, chain, eps)
    q, s_dst, n_edge = _contacts(dst, chain, pos)
    better, r_new, q_new, s_new = _refine(x, n, dst, chain, pos, r, eps)
    r = np.where(better, r_new, r)
    q = np.where(better[:, None], q_new, q)
    s_dst = np.where(better, s_new, s_dst)
    # Put each repaired contact on the lap nearest its old (unwrapped) position.
    s_dst = _same_lap(s_dst, one_way["s_dst"][idx], dst.rg.length[chain], dst.rg.closed[chain])
    fixed = _assemble(src, chain, x, n, one_way["s_src"][idx], r, q, s_dst, n_edge, eps)
    for key in ("dst", "m", "r", "ok", "s_dst", "n_dst"):
        one_way[key][idx] = fixed[key]


def _local_depths(side, chain, s, centres, radii):
    """Deepest penetration of each disk by the vertices near its contact on one curve."""
    rg = side.rg
    edge, _ = rg.locate(chain, s)
    local = edge - rg.offsets[chain]
    n_v = np.maximum(rg.n[chain], 1)[:, None]
    win = local[:, None] + np.arange(-tol.LOCAL_WINDOW, tol.LOCAL_WINDOW + 2)[None, :]
    win = np.where(rg.closed[chain][:, None], np.mod(win, n_v), np.clip(win, 0, n_v - 1))
    g = rg.offsets[chain][:, None] + win
    diff = rg.pts[g] - centres[:, None, :]
    d2 = np.einsum("kwi,kwi->kw", diff, diff)
    k = np.argmin(d2, axis=1)
    rows = np.arange(len(k))
    return radii - np.sqrt(d2[rows, k]), g[rows, k]


def _check(one_way, src, dst, spacing, eps, driver, reports):
    """Mark (``one_way['bad']``) and report the maximal disks entered by either curve.

    ``spacing`` is the dense spacing per chain, shape (C,).
    """
    m, r, ok, chain = one_way["m"], one_way["r"], one_way["ok"], one_way["chain"]
    h = spacing[chain]
    d_src, w_src = _local_depths(src, chain, one_way["s_src"], m, r)
    d_dst, w_dst = _local_depths(dst, chain, one_way["s_dst"], m, r)
    n_src = len(src.rg.pts)
    n_chains = len(src.rg)
    verts = np.concatenate([src.rg.pts, dst.rg.pts])
    depth = np.maximum(d_src, d_dst)
    witness = np.where(d_src >= d_dst, w_src, w_dst + n_src)
    bad = depth > np.maximum(tol.DISK_PENETRATION * h, eps)
    # Other parts of the same chain's curves reaching into a disk.
    radius = r * (1.0 - tol.NONLOCAL_RELATIVE) - tol.NONLOCAL_PENETRATION * h
    query = np.flatnonzero((radius > 0) & ok)
    tree = CurveTree(verts, np.concatenate([src.rg.offsets, dst.rg.offsets[1:] + n_src]))
    own = np.stack([chain[query], chain[query] + n_chains], axis=1)  # the chain's two curves
    qi, pi = tree.within(m[query], radius[query], own, first_only=True)
    k = query[qi]
    far = r[k] - np.linalg.norm(verts[pi] - m[k], axis=1)
    deeper = far > np.where(bad[k], depth[k], -np.inf)
    depth[k[deeper]], witness[k[deeper]] = far[deeper], pi[deeper]
    bad[k] = True
    bad &= ok
    one_way["bad"] = bad | ~ok
    flagged = np.flatnonzero(one_way["bad"])
    if len(flagged) == 0:
        return
    other = "Q" if driver == "P" else "P"
    s_src = one_way["s_src"] % np.where(src.rg.closed, src.rg.length, np.inf)[chain]
    s_dst = one_way["s_dst"] % np.where(dst.rg.closed, dst.rg.length, np.inf)[chain]
    for k in flagged:
        pq, ss = (one_way["src"][k], one_way["dst"][k]), (float(s_src[k]), float(s_dst[k]))
        if driver == "Q":
            pq, ss = pq[::-1], ss[::-1]
        found = bool(ok[k])
        w = witness[k]
        name = (driver if w < n_src else other) if found else other
        sample = int(k - src.rg.offsets[chain[k]])
        reports[chain[k]].violations.append(
            Violation(
                driver,
                sample,
                pq[0],
                pq[1],
                ss[0],
                ss[1],
                name,
                verts[w] if found else one_way["dst"][k],
                float(depth[k]) if found else float("inf"),
            )
        )


def _checked(maps, spacing, eps, reports):
    """Check one-way maps, repair lacing failures in chains with violations, check again."""
    for one_way, src, dst, driver in maps:
        _check(one_way, src, dst, spacing, eps, driver, reports)
    failing = [c for c, rep in enumerate(reports) if rep.violations]
    if not failing:
        return
    for c in failing:
        reports[c].violations = []
    for one_way, src, dst, driver in maps:
        again = np.isin(one_way["chain"], failing)
        one_way["bad"] &= again
        _repair(one_way, src, dst, eps)
        sub = {key: val[again] for key, val in one_way.items()}
        _check(sub, src, dst, spacing, eps, driver, reports)
        one_way["bad"][again] = sub["bad"]


def _flip(d):
    return dict(
        src=d["dst"],
        dst=d["src"],
        m=d["m"],
        r=d["r"],
        ok=d["ok"],
        s_src=d["s_dst"],
        s_dst=d["s_src"],
        n_src=d["n_dst"],
        n_dst=d["n_src"],
        chain=d["chain"],
    )


def _segments(chain, n_chains):
    """Start index of each chain's run in a chain-sorted array, shape (C + 1,)."""
    return np.searchsorted(chain, np.arange(n_chains + 1))


def _merge(fwd, bwd, sp, sq, spacing, dense_spacing, reports):
    """Thin the union of both one-way maps into symmetric samples (paper approach 3).

    Per chain, the union ordered by ``s_p + s_q`` must be a monotone chain. Pairs that step
    back by round-off are dropped; a pair that steps back by more than
    ``tolerances.MAP_DISAGREEMENT`` dense spacings means the forward and backward maps
    disagree: a maximal disk touches a curve at two places (paper section 3.4), reported.
    """
    n_chains = len(sp.rg)
    len_p, len_q = sp.rg.length, sq.rg.length
    closed = sp.rg.closed
    bwd = _flip(bwd)  # now read from P to Q like fwd
    cb = bwd["chain"]
    if closed.any():
        # Bring the backward pairs of loops into the forward map's unwrapped frame: interpolate
        # the forward graph (with one extra node closing each loop's lap).
        cf = fwd["chain"]
        first = sp.rg.offsets[:-1]
        gx = np.concatenate([fwd["s_src"], fwd["s_src"][first] + len_p])
        gy = np.concatenate([fwd["s_dst"], fwd["s_dst"][first] + len_q])
        gc = np.concatenate([cf, np.arange(n_chains)])
        base = np.concatenate([[0.0], np.cumsum(len_p + 1.0)])[:-1]
        order = np.argsort(gx + base[gc], kind="stable")
        wraps = closed[cb] & (len_p[cb] > 0)  # loops of zero length (degenerate chains) do not wrap
        sp_b = np.where(wraps, np.mod(bwd["s_src"], np.where(wraps, len_p[cb], 1.0)), bwd["s_src"])
        ref = np.interp(sp_b + base[cb], (gx + base[gc])[order], gy[order])
        # Whole laps to add (loops only; a zero-length chain has none).
        laps = np.divide(ref - bwd["s_dst"], len_q[cb], out=np.zeros_like(ref), where=closed[cb] & (len_q[cb] > 0))
        sq_b = bwd["s_dst"] + len_q[cb] * np.round(laps)
        bwd = dict(bwd, s_src=sp_b, s_dst=sq_b)
    keys = ("src", "dst", "m", "r", "ok", "s_src", "s_dst", "n_src", "n_dst", "chain")
    allp = {k: np.concatenate([fwd[k], bwd[k]]) for k in keys}
    chain = allp["chain"]
    order = np.lexsort((allp["s_src"] + allp["s_dst"], chain))
    allp = {k: v[order] for k, v in allp.items()}
    chain = allp["chain"]
    sp_, sq_ = allp["s_src"], allp["s_dst"]
    # Running maxima per chain (chains sorted ascending: shift each far above the previous).
    big = 4.0 * (max(len_p.max(), len_q.max()) + 1.0)
    back_p = np.maximum.accumulate(sp_ + chain * big) - chain * big - sp_
    back_q = np.maximum.accumulate(sq_ + chain * big) - chain * big - sq_
    h = dense_spacing[chain]
    for k in np.flatnonzero(np.maximum(back_p, back_q) > tol.MAP_DISAGREEMENT * h):
        c = chain[k]
        curve = "P" if back_p[k] >= back_q[k] else "Q"
        reports[c].violations.append(
            Violation(
                "P+Q",
                int(k),
                allp["src"][k],
                allp["dst"][k],
                float(np.mod(sp_[k], len_p[c]) if closed[c] else sp_[k]),
                float(np.mod(sq_[k], len_q[c]) if closed[c] else sq_[k]),
                curve,
                allp["src"][k] if curve == "P" else allp["dst"][k],
                float(max(back_p[k], back_q[k])),
            )
        )
    mono = (back_p <= tol.ROUNDOFF * len_p[chain]) & (back_q <= tol.ROUNDOFF * len_q[chain])
    allp = {k: v[mono] for k, v in allp.items()}
    chain = allp["chain"]
    sp_, sq_ = allp["s_src"], allp["s_dst"]
    seg = _segments(chain, n_chains)
    starts, ends = seg[:-1], seg[1:] - 1
    step = np.maximum(np.abs(np.diff(sp_, prepend=sp_[:1])), np.abs(np.diff(sq_, prepend=sq_[:1])))
    step[starts] = 0.0
    tau = np.cumsum(step)
    tau -= tau[starts][chain]
    closing = np.maximum(len_p - (sp_[ends] - sp_[starts]), len_q - (sq_[ends] - sq_[starts]))
    total = tau[ends] + np.where(closed, closing, 0.0)
    count = np.maximum(np.round(total / spacing).astype(np.int64), np.where(closed, 3, 1))
    owner, local = ragged_arange(count + np.where(closed, 0, 1))
    targets = local * (total / count)[owner]
    # The node nearest each multiple of the uniform step, within its chain.
    tbase = np.concatenate([[0.0], np.cumsum(total + 1.0)])[:-1]
    g = tau + tbase[chain]
    want = targets + tbase[owner]
    hi = np.clip(np.searchsorted(g, want), starts[owner] + 1, np.maximum(ends[owner], starts[owner] + 1))
    hi = np.minimum(hi, len(g) - 1)
    lo = np.maximum(hi - 1, starts[owner])
    pick = np.where(want - g[lo] <= g[hi] - want, lo, hi)
    keep = np.unique(pick)
    return {k: v[keep] for k, v in allp.items()}


# --------------------------------------------------------------------------------------------


def _static(setup, side, c, spacing):
    """Coincident curves: every point maps to itself with a zero disk."""
    v = side.view(c)
    zeros = np.zeros(len(v.pts))
    s = v.cum[: len(v.pts)]
    report = CompatibilityReport("coincident", samples=len(v.pts))
    return Correspondence(
        v.pts,
        v.pts.copy(),
        v.pts.copy(),
        zeros,
        v.vnormals,
        v.vnormals,
        s,
        s.copy(),
        setup.closed,
        setup,
        v.pts,
        v.pts.copy(),
        spacing,
        report,
    )


def ball_maps(setups, spacing, sampling="symmetric", check=True, eps=None):
    """Ball-maps of many oriented pairs at once (the batched engine behind :func:`ball_map`).

    Parameters
    ----------
    setups : list of PairSetup
        Pairs already checked and oriented by :func:`~ballmorph_core.compat.orient_pair` (or an
        equivalent batched check).
    spacing : array_like, shape (C,)
        Output sample spacing of each pair.
    sampling : {'symmetric', 'P', 'Q'}
    check : bool
        Raise for the first pair that is not b-compatible; with False every pair's
        ``report`` says where it fails.
    eps : array_like, shape (C,), optional
        Absolute length tolerance per pair (default from each pair's size).

    Returns
    -------
    list of Correspondence
    """
    check_option("sampling", sampling, SAMPLINGS)
    n = len(setups)
    if n == 0:
        return []
    spacing = np.broadcast_to(np.asarray(spacing, dtype=np.float64), (n,)).copy()
    if eps is None:
        eps = np.array([tol.COINCIDENT * scale_of(s.P, s.Q) for s in setups])
    eps = float(np.min(eps))
    # Both one-way maps sample their source at the output spacing; the symmetric thinning then
    # keeps about one of their union's pairs per spacing (half the spacing would double the work
    # for no visible gain: every kept pair is an exact contact either way).
    dense = spacing
    closed = np.array([s.closed for s in setups], dtype=bool)
    sp = _Sides([s.P for s in setups], closed, [s.side_p for s in setups], dense)
    sq = _Sides([s.Q for s in setups], closed, [s.side_q for s in setups], dense)
    config = np.where(closed, "disjoint-loops", "quasi-disjoint-strokes")
    reports = [CompatibilityReport(str(cfg)) for cfg in config]
    fwd = _one_way(sp, sq, eps) if sampling in ("P", "symmetric") else None
    bwd = _one_way(sq, sp, eps) if sampling in ("Q", "symmetric") else None
    maps = [(m, a, b, d) for m, a, b, d in ((fwd, sp, sq, "P"), (bwd, sq, sp, "Q")) if m is not None]
    for one_way, _, _, _ in maps:
        counts = np.bincount(one_way["chain"], minlength=n)
        for c in range(n):
            reports[c].samples += int(counts[c])
    _checked(maps, dense, eps, reports)
    if sampling == "P":
        out = fwd
    elif sampling == "Q":
        out = _flip(bwd)
    else:
        out = _merge(fwd, bwd, sp, sq, spacing, dense, reports)
    seg = _segments(out["chain"], n)
    result = []
    for c, setup in enumerate(setups):
        if setup.coincident:
            result.append(_static(setup, sp, c, float(spacing[c])))
            continue
        if check and reports[c].violations:
            raise IncompatibleCurvesError(reports[c].describe(), reports[c])
        sl = slice(seg[c], seg[c + 1])
        result.append(
            Correspondence(
                out["src"][sl],
                out["dst"][sl],
                out["m"][sl],
                out["r"][sl],
                out["n_src"][sl],
                out["n_dst"][sl],
                out["s_src"][sl],
                out["s_dst"][sl],
                bool(closed[c]),
                setup,
                sp.rg.curve(c),
                sq.rg.curve(c),
                float(spacing[c]),
                reports[c],
            )
        )
    return result


@dataclass
class DenseMaps:
    """Both one-way ball-maps of a pair at the dense spacing (for the composite ball-morph).

    Attributes
    ----------
    setup : PairSetup
    side_p, side_q : _Side
        Dense samples of the oriented P and Q (``pts``, ``cum``, ``length``, normals).
    fwd, bwd : dict of ndarray
        P -> Q and Q -> P maps: ``src``, ``dst``, ``m``, ``r``, ``s_src``, ``s_dst``,
        ``n_src``, ``n_dst``, and ``bad`` (the sample's disk is entered or missing).
    spacing : float
        The dense spacing.
    eps : float
    report : CompatibilityReport
    """

    setup: PairSetup
    side_p: _Side
    side_q: _Side
    fwd: dict
    bwd: dict
    spacing: float
    eps: float
    report: CompatibilityReport


def dense_maps(P, Q, closed, spacing, setup=None):
    """Compute both one-way maps of validated curves at ``spacing`` and check them (DenseMaps).

    Unlike :func:`ball_map` this never raises for incompatibility: ``report`` and the ``bad``
    masks say where the disks fail.
    """
    setup = orient_pair(P, Q, closed) if setup is None else setup
    eps = tol.COINCIDENT * scale_of(P, Q)
    h = np.array([spacing])
    sp = _Sides([setup.P], [closed], [setup.side_p], h)
    sq = _Sides([setup.Q], [closed], [setup.side_q], h)
    fwd, bwd = _one_way(sp, sq, eps), _one_way(sq, sp, eps)
    reports = [CompatibilityReport("disjoint-loops" if closed else "quasi-disjoint-strokes")]
    reports[0].samples = len(fwd["r"]) + len(bwd["r"])
    _checked(((fwd, sp, sq, "P"), (bwd, sq, sp, "Q")), h, eps, reports)
    return DenseMaps(setup, sp.view(0), sq.view(0), fwd, bwd, spacing, eps, reports[0])


def disk_between(x0, n0, x1, n1, a, b, N, window_a, window_b, eps, iterations=40):
    """Disks tangent to a curve between two samples that touch two other edge windows equally.

    For each row, the tangent point moves along the segment from ``x0`` to ``x1`` (normal
    interpolated) until the smallest disk touching edges ``window_a`` equals the smallest one
    touching ``window_b`` (bisection): the maximal disk that touches the other curve twice,
    used to bridge an incompatible stretch (paper section 7, relative blending).

    Parameters
    ----------
    x0, n0, x1, n1 : ndarray, shape (J, 2)
        The two samples and their unit gap normals.
    a, b, N : ndarray, shape (E, 2)
        Edges ``a -> b`` of the other curve with their gap normals.
    window_a, window_b : list of ndarray of int
        Edge indices per row.
    eps : float
    iterations : int

    Returns
    -------
    x, n, r : ndarray, shapes (J, 2), (J, 2), (J,)
        Tangent point, normal and radius of each disk.
    qa, qb : ndarray, shape (J, 2)
        Its contacts in the two windows.
    """
    lo = np.zeros(len(x0))
    hi = np.ones(len(x0))

    def evaluate(lam):
        x = x0 + lam[:, None] * (x1 - x0)
        n = n0 + lam[:, None] * (n1 - n0)
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        out = []
        for window in (window_a, window_b):
            counts = np.array([len(w) for w in window])
            owner, local = ragged_arange(counts)
            e = np.concatenate(window)
            rr, uu = _candidates(x[owner], n[owner], a[e], b[e], N[e], eps)
            best = _segment_argmin(rr, owner, len(x))
            q = a[e[best]] + uu[best][:, None] * (b[e[best]] - a[e[best]])
            out.append((rr[best], q))
        return x, n, out

    for _ in range(iterations):
        mid = (lo + hi) / 2
        _, _, ((ra, _), (rb, _)) = evaluate(mid)
        # Window a is touched first at lo (ra < rb), window b first at hi.
        first_a = ra < rb
        lo = np.where(first_a, mid, lo)
        hi = np.where(first_a, hi, mid)
    x, n, ((ra, qa), (rb, qb)) = evaluate((lo + hi) / 2)
    return x, n, np.minimum(ra, rb), qa, qb


def ball_map(P, Q, closed=False, spacing=None, sampling="symmetric", check=True):
    """Ball-map correspondence between two curves (paper sections 4.1, 5.2).

    Parameters
    ----------
    P, Q : array_like, shape (N, 2) and (M, 2)
        Strokes sharing both endpoints (``closed=False``, configuration 2) or disjoint nested
        loops (``closed=True``, configuration 1). Not modified.
    closed : bool
    spacing : float, optional
        Geodesic sample spacing; default :func:`~ballmorph_core.curves.default_spacing`.
    sampling : {'symmetric', 'P', 'Q'}
        ``'symmetric'``: the paper's approach 3 (default; does not depend on which curve is
        P). ``'P'``: approach 2, uniform samples on P mapped to Q (the paper's choice for its
        fair comparison). ``'Q'``: uniform samples on Q mapped back.
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
    check_option("sampling", sampling, SAMPLINGS)
    P = as_curve(P, "P", closed)
    Q = as_curve(Q, "Q", closed)
    spacing = resolve_spacing(P, Q, closed, spacing)
    setup = orient_pair(P, Q, closed)
    return ball_maps([setup], [spacing], sampling, check)[0]
