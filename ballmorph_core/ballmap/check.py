"""The disk check: every maximal disk must be empty (paper sections 3.3-3.4).

The vertices near a disk's contacts may enter it by at most ``DISK_PENETRATION`` sample
spacings (polylines are never exactly b-compatible); a bounding-volume hierarchy over both
curves (:class:`~ballmorph_core.geometry.spatial.CurveTree`) finds any other part of the curves
deeper inside. Such a disk touches a curve twice: the medial axis of the gap bifurcates there
and the pair is not b-compatible at that place. Samples whose windowed lacing went wrong are
searched again without a window before the verdict.
"""

import numpy as np

from .. import tolerances as tol
from ..geometry.spatial import CurveTree
from ..geometry.vectors import norms
from .lacing import as_rows, contacts, disk_map, full_search, refine, refined, same_lap
from .report import Violation

__all__ = ["check_maps"]

#: A maximal disk may be entered by the curves by this fraction of the sample spacing before
#: the pair counts as not b-compatible: the discretisation slack of polylines.
DISK_PENETRATION = 0.05

#: Vertices within this many dense samples of a disk's contact points are checked against
#: ``DISK_PENETRATION``; farther ones (another part of a curve reaching into the disk) are found
#: by the tree search, which ignores penetrations shallower than ``NONLOCAL_RELATIVE`` of the
#: disk's radius plus ``NONLOCAL_PENETRATION`` dense spacings. Shrinking the searched disk keeps
#: the tree from refining the band where the curves hug the disk near its contacts (5x faster on
#: 4000-vertex loops); what it can miss is a distant part of a curve grazing a disk by less than
#: that: a slight bifurcation whose in-betweens overlap by less than 5 % of the local gap.
LOCAL_WINDOW = 4
NONLOCAL_RELATIVE = 0.05
NONLOCAL_PENETRATION = 1.0

#: At most this many failed samples per direction are searched again without a window (each
#: costs a pass over the whole other curve); a pair with more failures is plainly not
#: b-compatible and is reported as it is.
REPAIR_LIMIT = 2048


#: The window round a contact on edge ``e``: vertices ``e - LOCAL_WINDOW`` to ``e + LOCAL_WINDOW + 1``.
_WINDOW = (LOCAL_WINDOW, LOCAL_WINDOW + 1)
_WIDTH = sum(_WINDOW) + 1


def _window_starts(side, chain, s):
    """Where the window round each contact's edge starts in ``side.windows`` (the contacts at
    arc lengths ``s`` of their chains), shape (K,)."""
    edge, _ = side.rg.locate(chain, s)
    return edge + (_WIDTH - 1) * chain


def _vertex_window_starts(side):
    """:func:`_window_starts` of every vertex of ``side`` at its own arc length (all of them, in
    order, each on its own curve), shape (N,).

    Where the batch's shifted arc lengths (:meth:`~ballmorph_core.geometry.ragged.Ragged.global_s`)
    increase strictly and lie in their curves' ranges, the search for a vertex's own arc length
    ends on the vertex itself: its edge is the one it starts (an open curve's last vertex: its
    last edge, where a position clipped to the length ends too). Otherwise the vertices are
    located as any position.
    """
    rg = side.rg
    g, _ = rg.global_s()
    filled = np.flatnonzero(rg.n)
    first, last = rg.offsets[filled], rg.offsets[filled + 1] - 1
    # A loop's last vertex lies below its length; an open curve's last but one does.
    closed, length = rg.closed[filled], rg.length[filled]
    probe = rg.s[np.where(closed, last, np.maximum(last - 1, first))]
    in_range = (rg.s[first] >= 0.0) & np.where(closed, probe < np.maximum(length, tol.TINY), probe <= length)
    if not (in_range.all() and np.all(g[1:] > g[:-1])):
        return _window_starts(side, rg.owner, rg.s)
    edge = np.arange(len(g))
    ends = np.flatnonzero(rg.nxt < 0)
    edge[ends[rg.n[rg.owner[ends]] > 1]] -= 1
    return edge + (_WIDTH - 1) * rg.owner


def _local_depths(side, start, centres, radii):
    """Deepest penetration of each disk by the vertices of its window (starting at ``start``,
    see :func:`_window_starts`) on one curve, shape (K,).

    Place by place, the running minimum of the squared distances (each the same value as
    from a (K, W) table of the windows, whose rows numpy would reduce a row at a time).
    """
    x, y, _ = side.windows(*_WINDOW)
    cx, cy = (np.ascontiguousarray(v) for v in centres.T)
    nearest = None
    for j in range(_WIDTH):
        # Place j of each window: ``x[start + j]``, read from the layout shifted by j (no sum of
        # the indices); in range: take's 'wrap' mode skips the bounds check.
        dx, dy = np.take(x[j:], start, mode="wrap"), np.take(y[j:], start, mode="wrap")
        dx -= cx
        dy -= cy
        d2 = np.square(dx, out=dx)
        d2 += np.square(dy, out=dy)
        nearest = d2 if nearest is None else np.minimum(nearest, d2, out=nearest)
    return radii - np.sqrt(nearest)


def _nearest_vertices(side, start, centres):
    """The first vertex of each window (see :func:`_local_depths`) nearest its disk's centre:
    the global vertex index, shape (K,). Asked only for the disks the check flags."""
    x, y, vertex = side.windows(*_WINDOW)
    at = start[:, None] + np.arange(_WIDTH)
    dx, dy = x[at] - centres[:, :1], y[at] - centres[:, 1:]
    k = np.argmin(dx * dx + dy * dy, axis=1)
    return vertex[at[np.arange(len(at)), k]]


#: The nonlocal search asks runs of this many consecutive disks of a chain as one disk holding
#: them all (their centres lie about a spacing apart, the searched disks at least a spacing
#: inside the curves): at 400 open strokes x 500 points 7 in 100 runs of 3 hold a vertex (and
#: are asked again disk by disk), runs of 4 mostly do.
COVER_RUN = 3

#: Relative round-off allowed when one disk is taken to hold others (of the disks' and the
#: coordinates' size): far more than the few ulps their distances can be off.
COVER_SLACK = 1e-9


def _entered(tree, centres, radii, curves, chain):
    """Vertices strictly inside disks, as ``tree.within(centres, radii, curves, first_only=True)``.

    Neighbouring samples of a chain have nearly the same disk, so the disks are first asked in
    runs of ``COVER_RUN``, each run as one disk holding them all; only the runs whose disk holds
    a vertex are asked disk by disk (on the benchmark 40 % of the tree nodes visited before). A
    disk's traversal does not depend on the others asked with it, so every disk gets the same
    vertices, in the same order, as when all are asked at once; only the order between
    different disks changes (its readers take each disk's vertices in their order).

    Parameters
    ----------
    tree : CurveTree
    centres : ndarray, shape (K, 2)
    radii : ndarray, shape (K,)
    curves : ndarray of int, shape (K, J)
        The curves searched for each disk (the same for disks of the same chain).
    chain : ndarray of int, shape (K,)
        Each disk's chain, non-decreasing: only disks of the same chain share a run.

    Returns
    -------
    query, point : ndarray of int, shape (M,)
    """
    if len(centres) == 0:
        return tree.within(centres, radii, curves, first_only=True)
    # Runs of consecutive disks of a chain, each asked as one disk about their mean centre that
    # holds them all (and a little more, for round-off).
    k = np.arange(len(centres))
    chain_start = np.flatnonzero(np.r_[True, chain[1:] != chain[:-1]])
    since = k - np.repeat(chain_start, np.diff(np.r_[chain_start, len(k)]))
    starts = np.flatnonzero(since % COVER_RUN == 0)
    size = np.diff(np.r_[starts, len(k)])
    # Column by column, rows by take (numpy runs (K, 2) rows' norms, products by a (K, 1)
    # column and fancy indexing a row at a time); the same values as row-wise.
    cx, cy = centres.T
    mx, my = (np.add.reduceat(v, starts) / size for v in (cx, cy))
    dx, dy = cx - np.repeat(mx, size), cy - np.repeat(my, size)
    reach = np.maximum.reduceat(norms(dx, dy) + radii, starts)
    reach += COVER_SLACK * (reach + np.maximum(np.abs(mx), np.abs(my)))
    hit, _ = tree.within(as_rows(mx, my), reach, np.take(curves, starts, axis=0), first_only=True)
    held = np.zeros(len(starts), dtype=bool)
    held[hit] = True
    again = np.flatnonzero(np.repeat(held, size))
    qi, pi = tree.within(*(np.take(v, again, axis=0) for v in (centres, radii, curves)), first_only=True)
    return again[qi], pi


class _Trees:
    """One :class:`CurveTree` over the curves of both sides, shared by both directions' checks.

    Built for the first (source, target) asked; the other direction names the same curves the
    other way round. A disk's traversal depends only on its curves' subtrees and the order it
    names them in, so either tree gives the same vertices in the same order.
    """

    def __init__(self):
        self._built = {}

    def entered(self, src, dst, centres, radii, chain):
        """Vertices of each disk's chain strictly inside it (:func:`_entered`), numbered as in
        ``concatenate([src.rg.pts, dst.rg.pts])``: query, point, shape (M,)."""
        flipped = (id(dst), id(src)) in self._built
        first, second = (dst, src) if flipped else (src, dst)
        key = (id(first), id(second))
        if key not in self._built:
            n_first = len(first.rg.pts)
            verts = np.concatenate([first.rg.pts, second.rg.pts])
            self._built[key] = CurveTree(verts, np.concatenate([first.rg.offsets, second.rg.offsets[1:] + n_first]))
        tree, n_chains = self._built[key], len(src.rg)
        # The chain's two curves, the source first (in the tree, the first side's come first).
        at_src, at_dst = (chain + n_chains, chain) if flipped else (chain, chain + n_chains)
        qi, pi = _entered(tree, centres, radii, as_rows(at_src, at_dst), chain)
        if flipped:
            n_dst = len(dst.rg.pts)
            pi = np.where(pi < n_dst, pi + len(src.rg.pts), pi - n_dst)
        return qi, pi


def _depths(one_way, src, dst, spacing, eps, trees):
    """How deep each disk is entered, by which vertex (index into both curves' vertices), and
    whether that fails the check."""
    m, r, ok, chain = one_way.m, one_way.r, one_way.ok, one_way.chain
    h = np.take(spacing, chain, mode="wrap")  # in range: 'wrap' skips the bounds check
    # A map of every source vertex in order (as lacing made it) has the source's own arc lengths.
    every_vertex = one_way.s_src is src.rg.s and chain is src.rg.owner
    at_src = _vertex_window_starts(src) if every_vertex else _window_starts(src, chain, one_way.s_src)
    at_dst = _window_starts(dst, chain, one_way.s_dst)
    d_src = _local_depths(src, at_src, m, r)
    d_dst = _local_depths(dst, at_dst, m, r)
    n_src = len(src.rg.pts)
    verts = np.concatenate([src.rg.pts, dst.rg.pts])
    depth = np.maximum(d_src, d_dst)
    bad = depth > np.maximum(DISK_PENETRATION * h, eps)
    # The deepest vertex, where a found disk fails locally (the only ones a report names).
    witness = np.zeros(len(r), dtype=np.int64)
    failing = np.flatnonzero(bad & ok)
    if len(failing):
        w_src = _nearest_vertices(src, at_src[failing], m[failing])
        w_dst = _nearest_vertices(dst, at_dst[failing], m[failing])
        witness[failing] = np.where(d_src[failing] >= d_dst[failing], w_src, w_dst + n_src)
    # Other parts of the same chain's curves reaching into a disk.
    radius = r * (1.0 - NONLOCAL_RELATIVE) - NONLOCAL_PENETRATION * h
    query = np.flatnonzero((radius > 0) & ok)
    qi, pi = trees.entered(src, dst, *(np.take(v, query, axis=0) for v in (m, radius, chain)))
    k = query[qi]
    far = r[k] - np.linalg.norm(verts[pi] - m[k], axis=1)
    deeper = far > np.where(bad[k], depth[k], -np.inf)
    depth[k[deeper]], witness[k[deeper]] = far[deeper], pi[deeper]
    bad[k] = True
    return depth, witness, verts, bad & ok


def _check(one_way, src, dst, spacing, eps, driver, reports, trees):
    """Mark (``one_way.bad``) and report the maximal disks entered by either curve.

    ``spacing`` is the dense spacing per chain, shape (C,); ``driver`` the source curve's name;
    ``trees`` the :class:`_Trees` of the check.
    """
    depth, witness, verts, bad = _depths(one_way, src, dst, spacing, eps, trees)
    ok, chain = one_way.ok, one_way.chain
    one_way.bad = bad | ~ok
    flagged = np.flatnonzero(one_way.bad)
    if len(flagged) == 0:
        return
    other, n_src = ("Q" if driver == "P" else "P"), len(src.rg.pts)
    s_src = one_way.s_src % np.where(src.rg.closed, src.rg.length, np.inf)[chain]
    s_dst = one_way.s_dst % np.where(dst.rg.closed, dst.rg.length, np.inf)[chain]
    for k in flagged:
        pq, ss = (one_way.src[k], one_way.dst[k]), (float(s_src[k]), float(s_dst[k]))
        if driver == "Q":
            pq, ss = pq[::-1], ss[::-1]
        found = bool(ok[k])
        w = witness[k]
        reports[chain[k]].violations.append(
            Violation(
                driver=driver,
                sample=int(k - src.rg.offsets[chain[k]]),
                p=pq[0],
                q=pq[1],
                s_p=ss[0],
                s_q=ss[1],
                witness_curve=(driver if w < n_src else other) if found else other,
                witness=verts[w] if found else one_way.dst[k],
                depth=float(depth[k]) if found else float("inf"),
            )
        )


def _repair(one_way, src, dst, eps):
    """Redo the samples whose lacing result failed the check with an unwindowed search.

    On a pair that is not b-compatible, a wrong contact at one bisection level narrows the
    windows of the samples between it and the next anchor; those samples then fail too,
    although their true maximal disks are fine. Searching them over the whole target curve
    restores them, so reports and the composite ball-morph see only the real trouble.
    """
    idx = np.flatnonzero(one_way.bad)
    if len(idx) == 0 or len(idx) > REPAIR_LIMIT:
        return
    chain = one_way.chain[idx]
    x, n = one_way.src[idx], one_way.n_src[idx]
    r, pos = full_search(x, n, dst, chain, eps)
    q, s_dst, n_edge = contacts(dst, chain, pos)
    better, *refinement = refine(x, n, dst, chain, pos, r, eps)
    r, q, s_dst = refined(better, refinement, r, q, s_dst)
    # Put each repaired contact on the lap nearest its old (unwrapped) position.
    s_dst = same_lap(s_dst, one_way.s_dst[idx], dst.rg.length[chain], dst.rg.closed[chain])
    one_way.put(idx, disk_map((x, n, one_way.s_src[idx], chain), r, q, s_dst, n_edge, eps))


def check_maps(maps, spacing, eps, reports):
    """Check one-way maps, repair lacing failures in chains with violations, check again.

    Parameters
    ----------
    maps : list of (OneWayMap, Sides, Sides, str)
        Each map with its source and target curves and the source's name ('P' or 'Q').
    spacing : ndarray, shape (C,)
        Dense spacing per chain.
    eps : float
    reports : list of CompatibilityReport
        One per chain; violations are appended. Every map's ``bad`` is set.
    """
    trees = _Trees()
    for one_way, src, dst, driver in maps:
        _check(one_way, src, dst, spacing, eps, driver, reports, trees)
    failing = [c for c, rep in enumerate(reports) if rep.violations]
    if not failing:
        return
    for c in failing:
        reports[c].violations = []
    for one_way, src, dst, driver in maps:
        again = np.isin(one_way.chain, failing)
        one_way.bad &= again
        _repair(one_way, src, dst, eps)
        sub = one_way.take(again)
        _check(sub, src, dst, spacing, eps, driver, reports, trees)
        one_way.bad[again] = sub.bad
