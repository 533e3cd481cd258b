"""Lacing by bisection: every dense sample of a chain's source curve mapped onto its target.

For b-compatible curves the images advance monotonically along the target as the samples
advance along the source: the invariant the paper's lacing walk (section 5.2, step dStep)
relies on. We fill it in by bisection so numpy handles a whole level at once: the ends of a
stroke pair map to the shared endpoints (for a loop, one sample is mapped by a full search);
then the middle sample of every bracket is searched only over the target edges between the
images of the bracket's ends. Each level costs about ``N + M`` candidate tests and there are
``log2 N`` levels: ``O((N + M) log N)`` with no Python loop over samples or edges. Non-monotone
true images (incompatible input) show up in the disk check instead of corrupting the order.
"""

import numpy as np

from .. import tolerances as tol
from ..geometry.circles import circumcircles
from ..geometry.ragged import budget_slices
from ..geometry.vectors import norms
from .candidates import ON_EDGE, tangent_disks
from .onemap import OneWayMap
from .sides import EDGE_BLOCK

__all__ = ["one_way", "full_search", "contacts", "refine", "refined", "same_lap", "disk_map"]

#: Most (sample, edge) candidate pairs evaluated at once by the searches: bounds their
#: temporary arrays (about 0.2 KB per pair) without slowing them down noticeably.
CANDIDATE_BUDGET = 500_000

#: Samples searching more target edges than this (the first bisection levels) first measure
#: the three edges round their expected contact, then only the blocks of ``EDGE_BLOCK`` edges
#: that can hold a disk as small (:func:`_pruned`).
WIDE_WINDOW = 32

#: Relative round-off allowed when a block of edges is shown to hold no smaller disk (of the
#: radius' and the coordinates' size): far more than the few ulps the distances can be off.
SEARCH_SLACK = 1e-9


def _first_minima(values, counts, ends=None):
    """Index of the first minimum of each group of consecutive ``values``, shape (G,).

    ``counts`` (shape (G,)) sizes the groups, ``ends`` (optional) is their ``np.cumsum``; as
    :func:`~ballmorph_core.geometry.ragged.group_argmin`, a group without entries (or without a
    minimum: NaN) gets 0.
    """
    ends = np.cumsum(counts) if ends is None else ends
    starts = ends - counts
    filled = counts > 0
    if filled.all():
        # Every group has entries (the lacing's usual case): no group to mask out.
        first, filled = starts, slice(None)
    elif filled.any():
        first = starts[filled]
    else:
        return np.zeros(len(counts), dtype=np.int64)
    mins = np.minimum.reduceat(values, first)
    hits = np.flatnonzero(values == np.repeat(mins, counts[filled]))
    best = np.zeros(len(counts), dtype=np.int64)
    if not len(hits):
        return best
    # A group's first hit is the first at or after its start, if there is one before its end.
    at = np.take(hits, np.searchsorted(hits, first), mode="clip")
    best[filled] = np.where((at >= first) & (at < ends[filled]), at, 0)
    return best


def _edge_disks(x, n, dst, g, cnt, eps):
    """Tangent disks (radii, contacts' fractions ``u``) of each sample (``x``, ``n``: shape (2, K),
    coordinate by coordinate) with each of its run of target edges ``g`` (global indices, ``cnt``
    per sample, sample after sample), shape (len(g),)."""
    pts, edge, normals = dst.columns
    # The indices are in range: take's 'wrap' mode skips the bounds check.
    a = np.take(pts, g, axis=1, mode="wrap")
    return tangent_disks(
        np.repeat(x, cnt, axis=1),
        np.repeat(n, cnt, axis=1),
        a,
        a + np.take(edge, g, axis=1, mode="wrap"),
        np.take(normals, g, axis=1, mode="wrap"),
        eps,
    )


def _smallest(x, n, dst, g, cnt, eps, ends=None):
    """Smallest disk over each sample's run of target edges (see :func:`_edge_disks`; ``ends``,
    optional, is ``np.cumsum(cnt)``): radii and the index into ``g`` of each sample's first best
    edge, with its contact's fraction ``u`` along that edge."""
    rr, uu = _edge_disks(x, n, dst, g, cnt, eps)
    best = _first_minima(rr, cnt, ends)
    return rr[best], best, uu[best]


def _runs(starts, cnt, ends=None):
    """Concatenated ``arange(start, start + c)`` of every run, shape (sum(cnt),); ``ends``
    (optional) is ``np.cumsum(cnt)``."""
    ends = np.cumsum(cnt) if ends is None else ends
    total = int(ends[-1]) if len(ends) else 0
    return np.arange(total) - np.repeat(ends - cnt - starts, cnt)


def _pruned(x, n, dst, first, last, guess, eps):
    """:func:`_smallest` over target edges ``first..last`` (global) of each sample, skipping
    blocks of edges that provably hold no disk as small as the guessed edges' (radii, best edges).

    Disks tangent at ``x`` along ``n`` are nested, so an edge whose disk has radius ``r <= R``
    has its contact in the disk of radius ``R`` (centre ``x + R n``): a block whose box lies
    farther from that centre than ``R`` (plus the contact test's slack) holds only larger disks,
    never the first smallest one. ``R`` is the smallest of the three edges round ``guess``.
    """
    lo, hi = dst.block_of(first), dst.block_of(last)
    near = np.clip(np.floor(guess).astype(np.int64)[None, :] + np.array([-1, 0, 1])[:, None], first, last)
    ring = np.ascontiguousarray(near.T).ravel()
    # Only the smallest radius is wanted (not which edge): a minimum over rows of three.
    r_guess = _edge_disks(x, n, dst, ring, 3, eps)[0].reshape(-1, 3).min(axis=1)
    # The rows' (sample, block) pairs, and the distance from each block's box to the centre.
    nb = hi - lo + 1
    owner = np.repeat(np.arange(len(first)), nb)
    block = _runs(lo, nb)
    finite = np.isfinite(r_guess)
    radius = np.where(finite, r_guess, 0.0)
    mx, my = (np.take(x[i] + radius * n[i], owner, mode="wrap") for i in (0, 1))
    x0, y0, x1, y1, longest = (np.take(v, block, mode="wrap") for v in dst.blocks)
    dx = np.maximum(np.maximum(x0 - mx, mx - x1), 0.0)
    dy = np.maximum(np.maximum(y0 - my, my - y1), 0.0)
    reach = np.take(radius, owner) + 2.0 * eps + ON_EDGE * longest
    reach += SEARCH_SLACK * (reach + np.abs(mx) + np.abs(my))
    keep = (dx * dx + dy * dy <= reach * reach) | ~np.take(finite, owner)
    owner, block = owner[keep], block[keep]
    # The kept blocks' edges within each sample's run, in order.
    e0 = np.maximum(block * EDGE_BLOCK, first[owner])
    e1 = np.minimum(block * EDGE_BLOCK + EDGE_BLOCK - 1, last[owner])
    g = _runs(e0, e1 - e0 + 1)
    cnt = np.bincount(owner, weights=e1 - e0 + 1, minlength=len(first)).astype(np.int64)
    r, best, u = _smallest(x, n, dst, g, cnt, eps)
    return r, g[best], u


def _search(x, n, dst, chain, e_lo, e_hi, eps, guess=None):
    """Smallest disk at each sample over target edges ``e_lo..e_hi`` of its chain (laps unrolled).

    ``x``, ``n`` (shape (2, K), coordinate by coordinate) are the samples and their normals.
    ``guess`` (edge units, optional) is where each contact is expected: samples with more than
    ``WIDE_WINDOW`` edges skip the blocks of edges that cannot hold their smallest disk
    (:func:`_pruned`; the same answer). Returns radii (inf where none) and contact positions in
    units of target edges (``e + u``).
    """
    rg = dst.rg
    counts = e_hi - e_lo + 1
    r, pos = np.full(x.shape[1], np.inf), np.zeros(x.shape[1])
    # Without loops a sample's edges are one run of the target's: no lap to wrap round.
    # In range: take's 'wrap' mode skips the bounds check.
    wraps = bool(np.take(rg.closed, chain, mode="wrap").any())
    base = np.take(rg.offsets, chain, mode="wrap")
    wide = np.zeros(len(counts), bool) if wraps or guess is None else counts > WIDE_WINDOW
    narrow = np.where(wide, 0, counts)
    for sl in budget_slices(narrow, CANDIDATE_BUDGET):
        cnt = narrow[sl]
        ends = np.cumsum(cnt)
        if not ends[-1]:
            continue
        if wraps:
            e_local = _runs(e_lo[sl], cnt, ends)
            c = np.repeat(chain[sl], cnt)
            g = rg.offsets[c] + np.where(rg.closed[c], e_local % np.maximum(rg.n_edges[c], 1), e_local)
        else:
            # One run of global edges per sample; its local edges are ``g - base``.
            e_local = None
            g = _runs(e_lo[sl] + base[sl], cnt, ends)
        rr, best, uu = _smallest(x[:, sl], n[:, sl], dst, g, cnt, eps, ends)
        r[sl], pos[sl] = rr, (g[best] - base[sl] if e_local is None else e_local[best]) + uu
    rows = np.flatnonzero(wide)
    for sl in budget_slices(counts[rows], CANDIDATE_BUDGET):
        k = rows[sl]
        rr, g, uu = _pruned(x[:, k], n[:, k], dst, base[k] + e_lo[k], base[k] + e_hi[k], base[k] + guess[k], eps)
        r[k], pos[k] = rr, (g - base[k]) + uu
    return r, pos


def full_search(x, n, dst, chain, eps):
    """Smallest disk at each sample (``x``, ``n``: shape (K, 2)) over all edges of its chain's
    target (no lacing window).

    Returns radii (inf where none) and contact positions in target edge units.
    """
    n_e = dst.rg.n_edges[chain]
    x, n = np.ascontiguousarray(x.T), np.ascontiguousarray(n.T)
    r, pos = _search(x, n, dst, chain, np.zeros(len(chain), np.int64), n_e - 1, eps)
    return np.where(n_e > 0, r, np.inf), np.where(n_e > 0, pos, 0.0)


def _lace(src, dst, eps):
    """Radii and contact positions (target edge units, unwrapped for loops) of every source sample."""
    s_rg, d_rg = src.rg, dst.rg
    X, NX = s_rg.pts, src.vnormals
    n_e, closed = d_rg.n_edges, d_rg.closed
    r, pos = np.full(len(X), np.inf), np.zeros(len(X))
    chains = np.arange(len(s_rg))
    lo, hi = s_rg.offsets[:-1].copy(), s_rg.offsets[1:] - 1
    p_lo, p_hi = np.zeros(len(chains)), n_e.astype(np.float64)
    opened, loops = ~closed, chains[closed]
    laps_of = np.where(closed, 2 * n_e, n_e)
    r[lo[opened]] = r[hi[opened]] = 0.0
    pos[hi[opened]] = n_e[opened]
    if len(loops):
        rr, pp = full_search(X[lo[loops]], NX[lo[loops]], dst, loops, eps)
        r[lo[loops]], pos[lo[loops]] = rr, pp
        # A loop's chain closes on its first sample, one lap later.
        p_lo[loops], hi[loops], p_hi[loops] = pp, s_rg.offsets[1:][loops], pp + n_e[loops]
    columns = (src.columns[0], np.ascontiguousarray(NX.T))
    chain = chains
    while True:
        keep = hi - lo > 1
        chain, lo, hi, p_lo, p_hi = (np.compress(keep, v) for v in (chain, lo, hi, p_lo, p_hi))
        if not len(chain):
            return r, pos
        mid = (lo + hi) // 2
        laps = np.take(laps_of, chain, mode="wrap")
        e_lo = np.clip(np.floor(p_lo).astype(np.int64), 0, laps - 1)
        e_hi = np.clip(np.ceil(p_hi).astype(np.int64) - 1, e_lo, laps - 1)
        # The contact is expected in proportion between its bracket's (only a hint: see _search).
        guess = p_lo + (p_hi - p_lo) * ((mid - lo) / (hi - lo))
        # Columns by take (in range: 'wrap' skips the bounds check), as the search reads them.
        rr, pp = _search(*(np.take(v, mid, axis=1, mode="wrap") for v in columns), dst, chain, e_lo, e_hi, eps, guess)
        # The window is whole edges, so the best contact may lie just outside the bracket: then
        # the true image does not advance monotonically (or sits on the bracket's end). Clipping
        # it would move the contact off its disk, so beyond round-off it counts as no disk found
        # here; the check reports the sample and the repair searches it without a window.
        outside = (pp < p_lo - tol.ROUNDOFF * laps) | (pp > p_hi + tol.ROUNDOFF * laps)
        rr = np.where(outside, np.inf, rr)
        pp = np.where(np.isfinite(rr), np.clip(pp, p_lo, p_hi), p_lo)
        r[mid], pos[mid] = rr, pp
        chain, lo, hi = np.concatenate([chain, chain]), np.concatenate([lo, mid]), np.concatenate([mid, hi])
        p_lo, p_hi = np.concatenate([p_lo, pp]), np.concatenate([pp, p_hi])


def as_rows(x, y):
    """The (K, 2) array of columns ``x`` and ``y`` (np.stack on axis 1 copies value by value,
    several times slower)."""
    out = np.empty((len(x), 2), dtype=np.result_type(x, y))
    out[:, 0], out[:, 1] = x, y
    return out


# The arithmetic below runs on the x and y columns of (K, 2) arrays: numpy takes a (K, 2)
# array's row-wise sums (einsum, linalg.norm) and its products by a (K, 1) column a row at a
# time, several times slower. Each value comes from the same operations in the same order, so
# the results are bit for bit those of the row-wise forms: ``norm`` is ``sqrt(x * x + y * y)``,
# and an einsum's dot product differs from ``x0 * x1 + y0 * y1`` only by the sign of a zero
# (einsum sums from +0), which only ever meets ``> 0`` or the division of a refinement that
# is dropped.


def contacts(dst, chain, pos):
    """Contact points, unwrapped arc lengths and edge normals at positions on target edges.

    Returns
    -------
    q : ndarray, shape (K, 2)
    s : ndarray, shape (K,)
    normal : ndarray, shape (K, 2)
    """
    rg = dst.rg
    # In range: take's 'wrap' mode skips the bounds check (the chains' values and the edges').
    n_e, closed, first, length = (
        np.take(v, chain, mode="wrap") for v in (rg.n_edges, rg.closed, rg.offsets, rg.length)
    )
    np.maximum(n_e, 1, out=n_e)
    e = np.clip(np.floor(pos).astype(np.int64), 0, np.where(closed, 2 * n_e, n_e) - 1)
    u = np.clip(pos - e, 0.0, 1.0)
    if closed.any():
        lap, g = np.where(closed, e // n_e, 0), first + np.where(closed, e % n_e, e)
    else:
        # Open curves only: no lap to unwrap (lap * length is then 0 * length, as row by row).
        lap, g = 0, first + e
    (ax, ay), (ex, ey) = (np.take(v, g, axis=1, mode="wrap") for v in dst.columns[:2])
    ex *= u
    ey *= u
    s = np.take(rg.s, g, mode="wrap") + u * np.take(rg.length_of_edge, g, mode="wrap") + lap * length
    return as_rows(ax + ex, ay + ey), s, np.take(dst.enormals, g, axis=0, mode="wrap")


def refine(x, n, dst, chain, pos, r, eps):
    """Refine polyline contacts on the circle through the three nearest target vertices.

    On a polygon the ball-map is a staircase (every disk touches a flat edge at the foot of its
    centre). Treating the target locally as the circular arc through three consecutive
    vertices (the paper's exact construction for piecewise-circular curves, section 5.1,
    equations 1-2) makes the map exact on circles and second-order accurate on smooth curves.
    A refined contact is kept only if it stays within the arc's span and near the polyline one.

    Returns
    -------
    ok : ndarray of bool, shape (K,)
    r_new : ndarray, shape (K,)
    q_new : ndarray, shape (K, 2)
    s_new : ndarray, shape (K,)
        Arc length on the target, within one lap.
    """
    rg = dst.rg
    # In range: take's 'wrap' mode skips the bounds check (the chains' values and the vertices').
    n_v, closed, first = (np.take(v, chain, mode="wrap") for v in (rg.n, rg.closed, rg.offsets))
    j = np.floor(pos + 0.5).astype(np.int64)
    jl = np.minimum(np.maximum(j, 1), np.maximum(n_v - 2, 1))
    if closed.any():
        jl = np.where(closed, j % np.maximum(n_v, 1), jl)
    ok = np.isfinite(r) & (r > eps) & (closed | ((j >= 1) & (j <= n_v - 2)))
    g0 = first + jl
    gm, gp = (np.take(v, g0, mode="wrap") for v in (rg.prv, rg.nxt))
    ok &= (gm >= 0) & (gp >= 0)
    gm, gp = np.maximum(gm, 0), np.maximum(gp, 0)
    # Rows by take (several times faster than fancy indexing on (K, 2) arrays; in range).
    a, b, c = (np.take(rg.pts, v, axis=0, mode="wrap") for v in (gm, g0, gp))
    centre, rad, round_enough = circumcircles(a, b, c)
    # Columns read more than once copied contiguous (numpy runs arithmetic on strided columns
    # element by element); the same values.
    (ax, ay), (cx, cy) = a.T, c.T
    (xx, xy), (nx, ny), (bx, by), (ox, oy) = (np.ascontiguousarray(v.T) for v in (x, n, b, centre))
    chord_x, chord_y = cx - ax, cy - ay
    chord2 = chord_x * chord_x + chord_y * chord_y
    chord_length = np.sqrt(chord2)
    # Nearly straight: the polyline contact is already right, and the circle would cancel badly.
    ok &= round_enough & (rad < 1e4 * chord_length)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        wx, wy = xx - ox, xy - oy
        vx, vy = np.take(dst.vnormals, g0, axis=0, mode="wrap").T
        inside = vx * (ox - bx) + vy * (oy - by) > 0
        den = 2.0 * (wx * nx + wy * ny) + np.where(inside, 2.0, -2.0) * rad
        r_new = (rad * rad - (wx * wx + wy * wy)) / den
        dx, dy = xx + r_new * nx - ox, xy + r_new * ny - oy
        d = norms(dx, dy)
        qx, qy = ox + rad * dx / d, oy + rad * dy / d
        t = ((qx - bx) * chord_x + (qy - by) * chord_y) / chord2
        r_safe = np.where(np.isfinite(r), r, 0.0)
        ok &= np.isfinite(r_new) & (r_new >= 0) & (np.abs(t) <= 0.5)
        ok &= np.abs(r_new - r_safe) <= 0.25 * r_safe + chord_length
    s_new = np.take(rg.s, g0, mode="wrap") + t * (
        np.take(rg.length_of_edge, gm, mode="wrap") + np.take(rg.length_of_edge, g0, mode="wrap")
    )
    return ok, r_new, as_rows(qx, qy), s_new


def refined(better, refinement, r, q, s_dst):
    """Radii, contacts and their arc lengths with the ``better`` rows of a refinement
    ``(r_new, q_new, s_new)`` (see :func:`refine`) taken instead: r, q (in place), s_dst."""
    r_new, q_new, s_new = refinement
    for i in (0, 1):
        np.copyto(q[:, i], q_new[:, i], where=better)
    return np.where(better, r_new, r), q, np.where(better, s_new, s_dst)


def same_lap(s_new, s_ref, length, closed):
    """Loop positions moved onto the lap of reference (unwrapped) positions, shape (K,)."""
    if not np.any(closed):
        return s_new.copy()  # no loop: np.where's values, without the laps computed for none
    return np.where(closed, s_new + length * np.round((s_ref - s_new) / np.maximum(length, tol.TINY)), s_new)


def _keep_order(better, s_new, s_dst, src, length, chain):
    """Drop refinements that would make neighbouring contacts step back along the target.

    Refining must not break the monotone order lacing produced: where refined neighbours would
    step back, both fall back to their polyline contacts (which are in order).
    """
    nxt = src.rg.nxt
    has_next, nxt_safe = nxt >= 0, np.maximum(nxt, 0)
    # In range: take's 'wrap' mode skips the bounds check.
    wraps = has_next & (nxt_safe == np.take(src.rg.offsets, chain, mode="wrap"))
    lap = np.where(wraps, length, 0.0)
    for _ in range(8):
        s_try = np.where(better, s_new, s_dst)
        step = np.take(s_try, nxt_safe, mode="wrap") + lap - s_try
        back = np.flatnonzero(has_next & (step < 0))
        if len(back) == 0:
            break
        better[back] = False
        better[nxt_safe[back]] = False
    return better


def disk_map(samples, r, q, s_dst, n_edge, eps):
    """A OneWayMap from samples ``(x, n, s_src, chain)``, radii (inf: none) and contacts."""
    x, n, s_src, chain = samples
    ok = np.isfinite(r)
    rr = np.where(ok, r, 0.0)
    (xx, xy), (nx, ny), (qx, qy), (ex, ey) = (v.T for v in (x, n, q, n_edge))
    mx, my = xx + rr * nx, xy + rr * ny
    has_disk = rr > eps
    with np.errstate(invalid="ignore", divide="ignore"):
        n_dst = as_rows(np.where(has_disk, (mx - qx) / rr, ex), np.where(has_disk, (my - qy) / rr, ey))
    return OneWayMap(
        src=x, dst=q, m=as_rows(mx, my), r=rr, ok=ok, s_src=s_src, s_dst=s_dst, n_src=n, n_dst=n_dst, chain=chain
    )


def one_way(src, dst, eps):
    """Map every dense sample of each chain's source onto its target (OneWayMap).

    Parameters
    ----------
    src, dst : Sides
        The chains' source and target curves.
    eps : float
        Length tolerance.
    """
    r, pos = _lace(src, dst, eps)
    chain = src.rg.owner
    q, s_dst, n_edge = contacts(dst, chain, pos)
    better, r_new, q_new, s_new = refine(src.rg.pts, src.vnormals, dst, chain, pos, r, eps)
    # In range: take's 'wrap' mode skips the bounds check.
    length, closed = (np.take(v, chain, mode="wrap") for v in (dst.rg.length, dst.rg.closed))
    s_new = same_lap(s_new, s_dst, length, closed)
    better = _keep_order(better, s_new, s_dst, src, length, chain)
    r, q, s_dst = refined(better, (r_new, q_new, s_new), r, q, s_dst)
    return disk_map((src.rg.pts, src.vnormals, src.rg.s, chain), r, q, s_dst, n_edge, eps)
