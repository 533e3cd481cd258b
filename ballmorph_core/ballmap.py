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

**Check.** Every maximal disk must be empty: a k-d tree over both curves' vertices finds any
vertex deeper than ``tolerances.DISK_PENETRATION`` sample spacings inside a disk. Such a disk
touches a curve twice, i.e. the medial axis of the gap bifurcates there (paper section 3.3), and
the pair is not b-compatible at that place.
"""

from dataclasses import dataclass

import numpy as np

from . import tolerances as tol
from .compat import CompatibilityReport, PairSetup, Violation, orient_pair
from .curves import (
    as_curve,
    cumulative_length,
    curve_length,
    default_spacing,
    densify,
    edge_normals,
    resample,
    scale_of,
    vertex_normals,
)
from .errors import IncompatibleCurvesError, InvalidCurveError
from .options import check_option
from .spatial import PointTree, ragged_arange

__all__ = ["Correspondence", "ball_map", "SAMPLINGS", "lace", "DenseMaps", "dense_maps", "disk_between"]

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
# Lacing by bisection, batched over several chains.


def lace(chains, eps):
    """Map the samples of every chain onto its target polyline (see the module docstring).

    Parameters
    ----------
    chains : list of tuple
        ``(x, n, y, N, closed)`` per chain: samples ``x`` (K, 2) with unit gap normals ``n``
        (K, 2); target vertices ``y`` (M, 2) with unit gap normals ``N`` of its edges (E, 2)
        (``E = M`` for a loop, ``M - 1`` for a stroke).
    eps : float
        Absolute length tolerance.

    Returns
    -------
    list of tuple
        ``(r, pos)`` per chain: radii (K,) (``inf`` where no disk was found) and contact
        positions (K,) in units of target edges, unwrapped for loops (``pos = e + u``: on edge
        ``e mod M`` at fraction ``u``).
    """
    # Concatenate all chains; loops get their target stored twice so unwrapped indices work.
    xs, ns, ya, yb, Ns = [], [], [], [], []
    x_off, e_off, n_edges, closed_flags = [0], [0], [], []
    for x, n, y, N, closed in chains:
        if closed:
            y2 = np.concatenate([y, y, y[:1]])
            N2 = np.concatenate([N, N])
        else:
            y2, N2 = y, N
        xs.append(x)
        ns.append(n)
        ya.append(y2[:-1])
        yb.append(y2[1:])
        Ns.append(N2)
        x_off.append(x_off[-1] + len(x))
        e_off.append(e_off[-1] + len(N2))
        n_edges.append(len(N))
        closed_flags.append(closed)
    X, Nx = np.concatenate(xs), np.concatenate(ns)
    A, B, NE = np.concatenate(ya), np.concatenate(yb), np.concatenate(Ns)
    x_off, e_off = np.array(x_off), np.array(e_off)
    n_edges, closed_flags = np.array(n_edges), np.array(closed_flags)

    total = x_off[-1]
    r = np.full(total, np.inf)
    pos = np.zeros(total)

    def solve(samples, chain, e_lo, e_hi):
        """Search edges [e_lo, e_hi] (chain-local, unwrapped) for each sample."""
        owner, local = ragged_arange(e_hi - e_lo + 1)
        s = samples[owner]
        e = e_off[chain][owner] + e_lo[owner] + local
        rr, uu = _candidates(X[s], Nx[s], A[e], B[e], NE[e], eps)
        best = _segment_argmin(rr, owner, len(samples))
        return rr[best], (e_lo[owner] + local)[best] + uu[best]

    # Anchors.
    chain_ids = np.arange(len(chains))
    lo_idx = x_off[:-1].copy()
    hi_idx = x_off[1:] - 1
    lo_pos = np.zeros(len(chains))
    hi_pos = n_edges.astype(np.float64)
    r[lo_idx[~closed_flags]] = 0.0
    r[hi_idx[~closed_flags]] = 0.0
    pos[hi_idx[~closed_flags]] = n_edges[~closed_flags]
    loops = chain_ids[closed_flags]
    if len(loops):
        rr, pp = solve(lo_idx[loops], loops, np.zeros(len(loops), np.int64), n_edges[loops] - 1)
        r[lo_idx[loops]], pos[lo_idx[loops]] = rr, pp
        lo_pos[loops] = pp
        # A loop's chain closes on its first sample, one lap later.
        hi_idx[loops] = x_off[1:][loops]
        hi_pos[loops] = pp + n_edges[loops]

    intervals = (chain_ids, lo_idx, hi_idx, lo_pos, hi_pos)
    while True:
        chain, lo, hi, plo, phi = intervals
        open_ = hi - lo > 1
        chain, lo, hi, plo, phi = chain[open_], lo[open_], hi[open_], plo[open_], phi[open_]
        if len(chain) == 0:
            break
        mid = (lo + hi) // 2
        n_e = np.where(closed_flags[chain], 2 * n_edges[chain], n_edges[chain])
        e_lo = np.clip(np.floor(plo).astype(np.int64), 0, n_e - 1)
        e_hi = np.clip(np.ceil(phi).astype(np.int64) - 1, e_lo, n_e - 1)
        rr, pp = solve(mid, chain, e_lo, e_hi)
        # No disk in the bracket: keep the order (the check will report the place).
        pp = np.where(np.isfinite(rr), np.clip(pp, plo, phi), plo)
        r[mid], pos[mid] = rr, pp
        intervals = (
            np.concatenate([chain, chain]),
            np.concatenate([lo, mid]),
            np.concatenate([mid, hi]),
            np.concatenate([plo, pp]),
            np.concatenate([pp, phi]),
        )
    return [(r[x_off[c] : x_off[c + 1]], pos[x_off[c] : x_off[c + 1]]) for c in range(len(chains))]


# --------------------------------------------------------------------------------------------


@dataclass
class _Side:
    """One curve prepared for lacing: dense samples, normals, arc length."""

    pts: np.ndarray
    vnormals: np.ndarray
    enormals: np.ndarray
    cum: np.ndarray
    length: float


def _prepare(curve, closed, side, spacing):
    dense = resample(densify(curve, closed, spacing), closed, spacing)
    return _Side(
        dense,
        side * vertex_normals(dense, closed),
        side * edge_normals(dense, closed),
        cumulative_length(dense, closed),
        curve_length(dense, closed),
    )


def _contacts(target, closed, pos):
    """Points, arc lengths (unwrapped) and edge normals at contact positions."""
    m = len(target.enormals)
    e = np.floor(pos).astype(np.int64)
    e = np.clip(e, 0, (2 * m if closed else m) - 1)
    u = pos - e
    e_mod = e % m if closed else e
    lens = target.cum[1:] - target.cum[:-1]
    nxt = (e_mod + 1) % len(target.pts) if closed else e_mod + 1
    pts = target.pts[e_mod] + u[:, None] * (target.pts[nxt] - target.pts[e_mod])
    s = target.cum[e_mod] + u * lens[e_mod] + (e // m) * target.length if closed else target.cum[e] + u * lens[e]
    return pts, s, target.enormals[e_mod]


def _refine(x, n, dst, closed, pos, r, eps):
    """Refine polyline contacts on the circle through the three nearest target vertices.

    On a polygon the ball-map is a staircase (every disk touches a flat edge at the foot of its
    centre). Treating the target locally as the circular arc through three consecutive
    vertices (the paper's exact construction for piecewise-circular curves, section 5.1,
    equations 1-2) makes the map exact on circles and second-order accurate on smooth curves.
    A refined contact is kept only if it stays within the arc's span and near the polyline one.
    """
    m_v = len(dst.pts)
    j = np.floor(pos + 0.5).astype(np.int64)
    if closed:
        jm, j0, jp = (j - 1) % m_v, j % m_v, (j + 1) % m_v
        ok = np.isfinite(r) & (r > eps)
    else:
        ok = np.isfinite(r) & (r > eps) & (j >= 1) & (j <= m_v - 2)
        j0 = np.clip(j, 1, m_v - 2)
        jm, jp = j0 - 1, j0 + 1
    a, b, c = dst.pts[jm], dst.pts[j0], dst.pts[jp]
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
    ok &= (np.abs(det) > 1e-9 * ab2 + 1e-300) & (np.hypot(cx, cy) < 1e4 * np.sqrt(ac2))
    w = x - centre
    wn = np.einsum("ij,ij->i", w, n)
    inside = np.einsum("ij,ij->i", dst.vnormals[j0], centre - b) > 0
    den = 2.0 * wn + np.where(inside, 2.0, -2.0) * rad
    with np.errstate(divide="ignore", invalid="ignore"):
        r_new = (rad * rad - np.einsum("ij,ij->i", w, w)) / den
        m = x + r_new[:, None] * n
        dm = m - centre
        q_new = centre + rad[:, None] * dm / np.linalg.norm(dm, axis=1, keepdims=True)
        chord = c - a
        t = np.einsum("ij,ij->i", q_new - b, chord) / np.einsum("ij,ij->i", chord, chord)
    r_safe = np.where(np.isfinite(r), r, 0.0)
    ok &= np.isfinite(r_new) & (r_new >= 0) & (np.abs(t) <= 0.5)
    ok &= np.abs(r_new - r_safe) <= 0.25 * r_safe + np.linalg.norm(chord, axis=1)
    s_mid = dst.cum[j0]
    s_new = s_mid + t * (dst.cum[np.minimum(j0 + 1, len(dst.cum) - 1)] - dst.cum[np.maximum(j0 - 1, 0)])
    return ok, r_new, q_new, s_new


def _one_way(src, dst, closed, eps):
    """Map every dense sample of src onto dst: dict of arrays."""
    ((r, pos),) = lace([(src.pts, src.vnormals, dst.pts, dst.enormals, closed)], eps)
    q, s_dst, n_edge = _contacts(dst, closed, pos)
    better, r_new, q_new, s_new = _refine(src.pts, src.vnormals, dst, closed, pos, r, eps)
    if closed:
        lap = np.floor(s_dst / dst.length)
        s_new = np.mod(s_new, dst.length) + lap * dst.length
        # A refined contact near the seam may land on the other side of it.
        s_new = np.where(s_new - s_dst > dst.length / 2, s_new - dst.length, s_new)
        s_new = np.where(s_dst - s_new > dst.length / 2, s_new + dst.length, s_new)
    # Refining must not break the monotone order lacing produced: where refined neighbours
    # would step back, both fall back to their polyline contacts (which are in order).
    for _ in range(8):
        s_try = np.where(better, s_new, s_dst)
        steps = np.diff(np.r_[s_try, s_try[0] + dst.length] if closed else s_try)
        back = np.flatnonzero(steps < 0)
        if len(back) == 0:
            break
        better[back] = False
        better[(back + 1) % len(better)] = False
    r = np.where(better, r_new, r)
    q = np.where(better[:, None], q_new, q)
    s_dst = np.where(better, s_new, s_dst)
    ok = np.isfinite(r)
    rr = np.where(ok, r, 0.0)
    m = src.pts + rr[:, None] * src.vnormals
    with np.errstate(invalid="ignore", divide="ignore"):
        n_dst = np.where((rr > eps)[:, None], (m - q) / rr[:, None], n_edge)
    return dict(
        src=src.pts,
        dst=q,
        m=m,
        r=rr,
        ok=ok,
        s_src=src.cum[: len(src.pts)],
        s_dst=s_dst,
        n_src=src.vnormals,
        n_dst=n_dst,
    )


def _full_search(x, n, dst, closed, eps, budget=2_000_000):
    """Smallest disk at each sample over *all* target edges (no lacing window), chunked.

    Returns r (inf where none) and positions in [0, E).
    """
    n_edges = len(dst.enormals)
    a = dst.pts[:n_edges]
    b = np.roll(dst.pts, -1, axis=0)[:n_edges] if closed else dst.pts[1:]
    r = np.full(len(x), np.inf)
    pos = np.zeros(len(x))
    chunk = max(1, budget // max(n_edges, 1))
    for start in range(0, len(x), chunk):
        sl = slice(start, start + chunk)
        k = len(x[sl])
        owner = np.repeat(np.arange(k), n_edges)
        e = np.tile(np.arange(n_edges), k)
        rr, uu = _candidates(x[sl][owner], n[sl][owner], a[e], b[e], dst.enormals[e], eps)
        best = _segment_argmin(rr, owner, k)
        r[sl], pos[sl] = rr[best], e[best] + uu[best]
    return r, pos


def _repair(one_way, src, dst, closed, eps):
    """Redo the samples whose lacing result failed the check with an unwindowed search.

    On a pair that is not b-compatible, a wrong contact at one bisection level narrows the
    windows of the samples between it and the next anchor; those samples then fail too,
    although their true maximal disks are fine. Searching them over the whole target curve
    restores them, so reports and the composite ball-morph see only the real trouble.
    """
    idx = np.flatnonzero(one_way["bad"])
    if len(idx) == 0:
        return
    x, n = src.pts[idx], src.vnormals[idx]
    r, pos = _full_search(x, n, dst, closed, eps)
    q, s_dst, n_edge = _contacts(dst, closed, pos)
    better, r_new, q_new, s_new = _refine(x, n, dst, closed, pos, r, eps)
    r = np.where(better, r_new, r)
    q = np.where(better[:, None], q_new, q)
    s_dst = np.where(better, s_new, s_dst)
    if closed:
        # Put each repaired contact on the lap nearest its old (unwrapped) position.
        old = one_way["s_dst"][idx]
        s_dst = s_dst + dst.length * np.round((old - s_dst) / dst.length)
    ok = np.isfinite(r)
    rr = np.where(ok, r, 0.0)
    m = x + rr[:, None] * n
    with np.errstate(invalid="ignore", divide="ignore"):
        n_dst = np.where((rr > eps)[:, None], (m - q) / rr[:, None], n_edge)
    for key, val in (("dst", q), ("m", m), ("r", rr), ("ok", ok), ("s_dst", s_dst), ("n_dst", n_dst)):
        one_way[key][idx] = val


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
    )


def _merge(fwd, bwd, spacing, closed, len_p, len_q, dense_spacing, report):
    """Thin the union of both one-way maps into symmetric samples (paper approach 3).

    The union, ordered by ``s_p + s_q``, must be a monotone chain. Pairs that step back by round-off
    are dropped; a pair that steps back by more than ``tolerances.MAP_DISAGREEMENT`` dense
    spacings means the forward and backward maps disagree: a maximal disk touches a curve at
    two places (paper section 3.4), which is reported as a violation.
    """
    bwd = _flip(bwd)  # now read from P to Q like fwd
    if closed:
        # Bring the backward pairs into the forward map's unwrapped frame.
        sp = np.mod(bwd["s_src"], len_p)
        ref = np.interp(sp, fwd["s_src"], fwd["s_dst"], period=None)
        sq = bwd["s_dst"] + len_q * np.round((ref - bwd["s_dst"]) / len_q)
        bwd = dict(bwd, s_src=sp, s_dst=sq)
    keys = ("src", "dst", "m", "r", "ok", "s_src", "s_dst", "n_src", "n_dst")
    allp = {k: np.concatenate([fwd[k], bwd[k]]) for k in keys}
    order = np.argsort(allp["s_src"] + allp["s_dst"], kind="stable")
    allp = {k: v[order] for k, v in allp.items()}
    sp, sq = allp["s_src"], allp["s_dst"]
    back_p = np.maximum.accumulate(sp) - sp
    back_q = np.maximum.accumulate(sq) - sq
    for k in np.flatnonzero(np.maximum(back_p, back_q) > tol.MAP_DISAGREEMENT * dense_spacing):
        curve = "P" if back_p[k] >= back_q[k] else "Q"
        report.violations.append(
            Violation(
                "P+Q",
                int(k),
                allp["src"][k],
                allp["dst"][k],
                float(np.mod(sp[k], len_p) if closed else sp[k]),
                float(np.mod(sq[k], len_q) if closed else sq[k]),
                curve,
                allp["src"][k] if curve == "P" else allp["dst"][k],
                float(max(back_p[k], back_q[k])),
            )
        )
    mono = (back_p <= 1e-12 * len_p) & (back_q <= 1e-12 * len_q)
    allp = {k: v[mono] for k, v in allp.items()}
    sp, sq = allp["s_src"], allp["s_dst"]
    step = np.maximum(np.abs(np.diff(sp)), np.abs(np.diff(sq)))
    tau = np.concatenate([[0.0], np.cumsum(step)])
    total = tau[-1] + (max(len_p - (sp[-1] - sp[0]), len_q - (sq[-1] - sq[0])) if closed else 0.0)
    count = max(int(round(total / spacing)), 3 if closed else 1)
    # The node nearest each multiple of the uniform step (ends included for strokes).
    targets = np.arange(count + (0 if closed else 1)) * (total / count)
    hi = np.clip(np.searchsorted(tau, targets), 1, len(tau) - 1)
    keep = np.where(targets - tau[hi - 1] <= tau[hi] - targets, hi - 1, hi)
    keep = np.unique(keep)
    return {k: v[keep] for k, v in allp.items()}


def _local_depths(side, closed, s, centres, radii):
    """Deepest penetration of a disk by the vertices near its contact on one curve."""
    n = len(side.pts)
    pos = np.mod(s, side.length) if closed else s
    j = np.searchsorted(side.cum[:n], pos)
    win = j[:, None] + np.arange(-tol.LOCAL_WINDOW, tol.LOCAL_WINDOW + 1)[None, :]
    win = np.mod(win, n) if closed else np.clip(win, 0, n - 1)
    depth = radii[:, None] - np.linalg.norm(side.pts[win] - centres[:, None, :], axis=2)
    k = np.argmax(depth, axis=1)
    rows = np.arange(len(k))
    return depth[rows, k], win[rows, k]


def _check(one_way, src, dst, closed, spacing, eps, driver, report):
    """Add to ``report`` the maximal disks of a one-way map entered by either curve."""
    m, r, ok = one_way["m"], one_way["r"], one_way["ok"]
    d_src, w_src = _local_depths(src, closed, one_way["s_src"], m, r)
    d_dst, w_dst = _local_depths(dst, closed, one_way["s_dst"], m, r)
    verts = np.concatenate([src.pts, dst.pts])
    depth = np.maximum(d_src, d_dst)
    witness = np.where(d_src >= d_dst, w_src, w_dst + len(src.pts))
    bad = depth > max(tol.DISK_PENETRATION * spacing, eps)
    # Other parts of the curves reaching into a disk.
    radius = r - tol.NONLOCAL_PENETRATION * spacing
    query = np.flatnonzero((radius > 0) & ok)
    qi, pi = PointTree(verts, leaf_size=4).within(m[query], radius[query], first_only=True)
    k = query[qi]
    far = r[k] - np.linalg.norm(verts[pi] - m[k], axis=1)
    deeper = far > np.where(bad[k], depth[k], -np.inf)
    depth[k[deeper]], witness[k[deeper]] = far[deeper], pi[deeper]
    bad[k] = True
    bad &= ok
    one_way["bad"] = bad | ~ok
    other = "Q" if driver == "P" else "P"
    names = np.where(witness < len(src.pts), driver, other)
    s_src = np.mod(one_way["s_src"], src.length) if closed else one_way["s_src"]
    s_dst = np.mod(one_way["s_dst"], dst.length) if closed else one_way["s_dst"]
    for k in np.flatnonzero(bad | ~ok):
        pq = (one_way["src"][k], one_way["dst"][k])
        ss = (float(s_src[k]), float(s_dst[k]))
        if driver == "Q":
            pq, ss = pq[::-1], ss[::-1]
        found = bool(ok[k])
        report.violations.append(
            Violation(
                driver,
                int(k),
                pq[0],
                pq[1],
                ss[0],
                ss[1],
                str(names[k]) if found else other,
                verts[witness[k]] if found else one_way["dst"][k],
                float(depth[k]) if found else float("inf"),
            )
        )


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
    sp = _prepare(setup.P, closed, setup.side_p, spacing)
    sq = _prepare(setup.Q, closed, setup.side_q, spacing)
    fwd = _one_way(sp, sq, closed, eps)
    bwd = _one_way(sq, sp, closed, eps)
    report = _checked(((fwd, sp, sq, "P"), (bwd, sq, sp, "Q")), closed, spacing, eps)
    return DenseMaps(setup, sp, sq, fwd, bwd, spacing, eps, report)


def _checked(maps, closed, spacing, eps):
    """Check one-way maps, repair lacing failures, check again (CompatibilityReport)."""
    config = "disjoint-loops" if closed else "quasi-disjoint-strokes"
    report = CompatibilityReport(config)
    for one_way, src, dst, driver in maps:
        _check(one_way, src, dst, closed, spacing, eps, driver, report)
    if not report.violations:
        report.samples = sum(len(m[0]["r"]) for m in maps)
        return report
    report = CompatibilityReport(config, samples=sum(len(m[0]["r"]) for m in maps))
    for one_way, src, dst, driver in maps:
        _repair(one_way, src, dst, closed, eps)
        _check(one_way, src, dst, closed, spacing, eps, driver, report)
    return report


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
    if spacing is None:
        spacing = default_spacing(P, Q, closed=closed)
    elif not (np.isfinite(spacing) and spacing > 0):
        raise InvalidCurveError(f"spacing must be a positive finite number, got {spacing!r}")
    setup = orient_pair(P, Q, closed)
    scale = scale_of(P, Q)
    eps = tol.COINCIDENT * scale
    dense_spacing = spacing / 2.0 if sampling == "symmetric" else spacing
    sp = _prepare(setup.P, closed, setup.side_p, dense_spacing)
    sq = _prepare(setup.Q, closed, setup.side_q, dense_spacing)
    if setup.coincident:
        return _static(setup, sp, sq, spacing)
    fwd = _one_way(sp, sq, closed, eps) if sampling in ("P", "symmetric") else None
    bwd = _one_way(sq, sp, closed, eps) if sampling in ("Q", "symmetric") else None
    maps = [(m, a, b, d) for m, a, b, d in ((fwd, sp, sq, "P"), (bwd, sq, sp, "Q")) if m is not None]
    report = _checked(maps, closed, dense_spacing, eps)
    if sampling == "P":
        out = fwd
    elif sampling == "Q":
        out = _flip(bwd)
    else:
        out = _merge(fwd, bwd, spacing, closed, sp.length, sq.length, dense_spacing, report)
    if check and report.violations:
        raise IncompatibleCurvesError(report.describe(), report)
    return Correspondence(
        out["src"],
        out["dst"],
        out["m"],
        out["r"],
        out["n_src"],
        out["n_dst"],
        out["s_src"],
        out["s_dst"],
        closed,
        setup,
        sp.pts,
        sq.pts,
        spacing,
        report,
    )


def _static(setup, sp, sq, spacing):
    """Coincident curves: every point maps to itself with a zero disk."""
    pts = sp.pts
    zeros = np.zeros(len(pts))
    s = sp.cum[: len(pts)]
    report = CompatibilityReport("coincident", samples=len(pts))
    return Correspondence(
        pts,
        pts.copy(),
        pts.copy(),
        zeros,
        sp.vnormals,
        sp.vnormals,
        s,
        s.copy(),
        setup.closed,
        setup,
        sp.pts,
        sq.pts,
        spacing,
        report,
    )
