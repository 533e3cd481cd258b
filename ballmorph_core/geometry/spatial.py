"""Spatial search in numpy: candidate pairs of boxes (uniform grid) and points within disks
(a k-d tree walked level by level for all queries at once).

Both keep the core's geometric checks near-linear in the number of vertices instead of testing
every pair, and both run without any per-pair Python loop.
"""

import numpy as np

from .. import tolerances as tol
from .ragged import budget_slices, ragged_arange

__all__ = ["box_pairs", "box_pair_chunks", "box_overlap", "PointTree", "CurveTree"]


def _columns(boxes):
    """``xmin, ymin, xmax, ymax`` of boxes given as rows (an (N, 4) array) or as a tuple of four
    columns, each a contiguous float64 array of shape (N,) (the grid gathers single values)."""
    if isinstance(boxes, tuple):
        return [np.ascontiguousarray(c, dtype=np.float64).reshape(-1) for c in boxes]
    rows = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
    return [np.ascontiguousarray(rows[:, k]) for k in range(4)]


def _cell_ranges(boxes, origin, cell):
    """First and last grid cell of every box along x and y: ``ix0, iy0, ix1, iy1``, each int64
    of shape (N,), from the boxes' four columns (:func:`_columns`)."""
    return [np.floor((boxes[k] - origin[k % 2]) / cell).astype(np.int64) for k in range(4)]


def _cells(ranges, ny):
    """Every (cell, box) entry of boxes spanning ``ranges`` (:func:`_cell_ranges`): the cells'
    keys ``cx * ny + cy`` and their boxes, box after box, shape (M,) each; and where each box's
    entries start, shape (N + 1,)."""
    ix0, iy0, ix1, iy1 = ranges
    nx, nyy = ix1 - ix0 + 1, iy1 - iy0 + 1
    per_box = nx * nyy
    owner, local = ragged_arange(per_box)
    cx = ix0[owner] + local % nx[owner]
    cy = iy0[owner] + local // nx[owner]
    first = np.zeros(len(nx) + 1, dtype=np.int64)
    np.cumsum(per_box, out=first[1:])
    return cx * ny + cy, owner, first


def _typical_size(boxes):
    x0, y0, x1, y1 = boxes
    return float(np.median(np.maximum(x1 - x0, y1 - y0)))


def _cell_entries(ranges):
    """How many cells boxes spanning ``ranges`` (:func:`_cell_ranges`) fill in all."""
    ix0, iy0, ix1, iy1 = ranges
    return float(((ix1 - ix0 + 1) * (iy1 - iy0 + 1)).sum())


#: Candidate (box, box) entries expanded at once (memory bound: about 40 bytes each). Long
#: boxes that all overlap (a scribble's edges) give O(n^2) pairs; they come in runs of this many.
PAIR_BUDGET = 1 << 18


#: Sets of boxes with at most this many pairs between them are paired directly, every pair
#: tested: for a short curve's edges (the composite morph checks a few dozen pieces of 20
#: edges each) building the grid costs several times more than testing them all.
DIRECT_PAIRS = 4096


def _grid_cell(a, b, origin, extent, cell):
    """The grid's cell size: the given one, else the larger typical box size, grown while long
    boxes would fill too many cells; and both sets' :func:`_cell_ranges` at that size."""
    n_a, n_b = len(a[0]), len(b[0])
    if cell is None:
        # The larger of the two sets' typical box sizes: tiny boxes (points) against long ones
        # (a coarse polygon's edges) must not make every long box span millions of cells.
        cell = max(_typical_size(a), _typical_size(b))
    cell = max(cell, extent / 4096.0, tol.TINY)
    # Bound the number of (box, cell) entries: grow the cells while long boxes would fill too many.
    for _ in range(16):
        ranges_a, ranges_b = _cell_ranges(a, origin, cell), _cell_ranges(b, origin, cell)
        if _cell_entries(ranges_a) + _cell_entries(ranges_b) <= 16 * (n_a + n_b) + 1024:
            break
        cell *= 2.0
    else:
        ranges_a, ranges_b = _cell_ranges(a, origin, cell), _cell_ranges(b, origin, cell)
    return cell, ranges_a, ranges_b


def box_overlap(a, b, i=None, j=None):
    """Whether boxes ``a[i]`` and ``b[j]`` overlap, touching counts (the grid's test), shape (K,).

    Parameters
    ----------
    a, b : sequence of four ndarray, shape (A,) and (B,)
        Columns ``xmin, ymin, xmax, ymax``.
    i, j : ndarray of int, shape (K,), optional
        The boxes compared; default box ``k`` of ``a`` with box ``k`` of ``b``.
    """

    def side(boxes, rows, k):
        return boxes[k] if rows is None else np.take(boxes[k], rows)

    # One comparison at a time: each gathered column is dropped (and its memory reused) at once.
    keep = side(a, i, 0) <= side(b, j, 2)
    keep &= side(b, j, 0) <= side(a, i, 2)
    keep &= side(a, i, 1) <= side(b, j, 3)
    keep &= side(b, j, 1) <= side(a, i, 3)
    return keep


def box_pair_chunks(boxes_a, boxes_b=None, cell=None, budget=PAIR_BUDGET, active=None):
    """All pairs of overlapping axis-aligned boxes, in runs of consecutive boxes of ``boxes_a``.

    Parameters
    ----------
    boxes_a : ndarray, shape (A, 4), or tuple of four ndarray, shape (A,)
        Rows ``(xmin, ymin, xmax, ymax)``, or those four columns (no (A, 4) array made).
    boxes_b : ndarray, shape (B, 4), or tuple of four ndarray, shape (B,), optional
        If omitted, pairs within ``boxes_a`` are returned with ``i < j``.
    cell : float, optional
        Grid cell size; default the median box size.
    budget : int
        Most candidate entries a run expands (a box with more still gets a run of its own).
    active : ndarray of bool, shape (A,), optional
        Read before each run: boxes of ``boxes_a`` cleared since are skipped (a caller that has
        seen enough of some boxes stops paying for them).

    Yields
    ------
    i, j : ndarray of int, shape (K,)
        Indices into ``boxes_a`` and ``boxes_b`` of boxes that overlap (touching counts), sorted
        by ``i`` then ``j`` within a run; runs follow each other in ``i``, so joined they are
        :func:`box_pairs`.
    """
    same = boxes_b is None
    a = _columns(boxes_a)
    b = a if same else _columns(boxes_b)
    n_a, n_b = len(a[0]), len(b[0])
    if n_a == 0 or n_b == 0:
        return
    if n_a * n_b <= min(DIRECT_PAIRS, budget):
        # Every pair tested by the grid's own test: the same pairs, in the same order, in one
        # run within the budget.
        rows = np.arange(n_a) if active is None else np.flatnonzero(active)
        i, j = np.repeat(rows, n_b), np.tile(np.arange(n_b), len(rows))
        keep = box_overlap(a, b, i, j)
        if same:
            keep &= i < j
        yield i[keep], j[keep]
        return
    origin = np.array([min(a[k].min(), b[k].min()) for k in range(2)])
    extent = max(max(float(a[k].max()), float(b[k].max())) - origin[k - 2] for k in range(2, 4))
    extent = float(max(extent, tol.TINY))
    cell, ranges_a, ranges_b = _grid_cell(a, b, origin, extent, cell)
    ny = int(extent / cell) + 2
    # The grid holds b; every run of a looks its cells up in it.
    key_a, own_a, first_entry = _cells(ranges_a, ny)
    key_b, own_b, _ = (key_a, own_a, None) if same else _cells(ranges_b, ny)
    order = np.argsort(key_b, kind="stable")
    key_b, own_b = key_b[order], own_b[order]
    # Each occupied cell of b once: a's entries look it up in that shorter list, once.
    run = np.flatnonzero(np.r_[True, key_b[1:] != key_b[:-1]])
    occupied = key_b[run]
    at = np.searchsorted(occupied, key_a)
    np.minimum(at, len(run) - 1, out=at)
    lo = run[at]
    count = np.where(occupied[at] == key_a, np.diff(np.r_[run, len(key_b)])[at], 0)
    # Entries come box after box, so a run of boxes is a run of entries.
    cost = np.add.reduceat(count, first_entry[:-1]) if len(count) else np.zeros(n_a, np.int64)
    for sl in budget_slices(cost, budget):
        if active is None or active[sl].all():
            entry = np.arange(first_entry[sl.start], first_entry[sl.stop])
        else:
            rows = np.flatnonzero(active[sl]) + sl.start
            owner, local = ragged_arange(first_entry[rows + 1] - first_entry[rows])
            entry = first_entry[rows][owner] + local
        owner, local = ragged_arange(count[entry])
        at_entry = entry[owner]
        i = own_a[at_entry]
        j = own_b[lo[at_entry] + local]
        keep = box_overlap(a, b, i, j)
        if same:
            keep &= i < j
        code = np.unique(i[keep] * n_b + j[keep])
        yield code // n_b, code % n_b


def box_pairs(boxes_a, boxes_b=None, cell=None):
    """All pairs of overlapping axis-aligned boxes (:func:`box_pair_chunks` joined).

    Parameters
    ----------
    boxes_a, boxes_b, cell
        As for :func:`box_pair_chunks`.

    Returns
    -------
    i, j : ndarray of int, shape (K,)
        Indices into ``boxes_a`` and ``boxes_b`` of boxes that overlap (touching counts),
        sorted by ``i`` then ``j``.
    """
    runs = list(box_pair_chunks(boxes_a, boxes_b, cell))
    if not runs:
        empty = np.zeros(0, dtype=np.int64)
        return empty, empty
    return np.concatenate([i for i, _ in runs]), np.concatenate([j for _, j in runs])


def _box_reach(boxes, centres):
    """Squared distances from each point to the nearest and to the farthest point of its box.

    Parameters
    ----------
    boxes : ndarray, shape (4, K)
        ``xmin, ymin, xmax, ymax`` rows (NaN for an empty node): coordinate by coordinate, so
        the tree's searches gather single values (faster than rows of four).
    centres : ndarray, shape (2, K)

    Returns
    -------
    near2, far2 : ndarray, shape (K,)
        NaN where the box is empty.
    """
    (x0, y0, x1, y1), (cx, cy) = boxes, centres
    near2, far2 = _side_reach(x0, x1, cx)
    near_y, far_y = _side_reach(y0, y1, cy)
    near2 += near_y
    far2 += far_y
    return near2, far2


def _side_reach(lo, hi, c):
    """Along one axis: the squared distances from ``c`` to the nearest and to the farthest
    point of ``[lo, hi]`` (each shape (K,)), from the two offsets computed once and in place
    (|hi - c| is |c - hi| exactly)."""
    below, above = np.subtract(lo, c), np.subtract(c, hi)
    far = np.abs(below)
    np.maximum(below, above, out=below)
    np.maximum(below, 0.0, out=below)
    np.maximum(far, np.abs(above, out=above), out=far)
    return np.square(below, out=below), np.square(far, out=far)


class PointTree:
    """A balanced k-d tree over points (or small boxes), queried for all disks at once.

    Parameters
    ----------
    points : ndarray, shape (N, 2)
        The points, or the low corners of the boxes when ``highs`` is given.
    leaf_size : int
        Points per leaf at most.
    highs : ndarray, shape (N, 2), optional
        The boxes' high corners: the tree then holds boxes, split at their centres.
    groups : ndarray of int, shape (C + 1,), optional
        Group ``c`` is ``points[groups[c]:groups[c + 1]]``: each group is a tree of its own
        (root ``c`` of level 0), so a query that names its group never meets the others.
        Groups and boxes are for :meth:`nearest_candidates`: the other queries start from root
        0 and measure to the points (or the boxes' centres).

    Notes
    -----
    The tree is implicit: at every level node ``k`` owns ``perm[start[k]:end[k]]`` and its
    children are nodes ``2k`` and ``2k + 1`` of the next level. Queries keep a frontier of
    (query, node) pairs, drop nodes that lie outside the disk and report nodes that lie wholly
    inside it, so only nodes crossing a disk's boundary are refined.
    """

    def __init__(self, points, leaf_size=8, highs=None, groups=None):
        self.points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        n = len(self.points)
        self.lows = self.points
        self.highs = self.points if highs is None else np.asarray(highs, dtype=np.float64).reshape(-1, 2)
        if highs is not None:
            # Boxes split at their centres (points are their own centres).
            self.points = 0.5 * (self.lows + self.highs)
        if groups is None:
            starts, ends = np.array([0]), np.array([n])
        else:
            groups = np.asarray(groups, dtype=np.int64)
            starts, ends = groups[:-1], groups[1:]
        # Leaves' items as boxes, for nearest_candidates, coordinate by coordinate (see _box_reach).
        corners = np.concatenate([self.lows.T, self.highs.T])
        self.item_boxes = corners if highs is not None else None
        self.xy = np.ascontiguousarray(self.points.T)
        # Coordinates as dense ranks (equal ones share theirs): one stable argsort of
        # (node, rank) orders exactly as lexsort by (node, coordinate), several times faster.
        ranks = np.stack([np.unique(c, return_inverse=True)[1].reshape(-1) for c in self.xy])
        span = int(ranks.max(initial=0)) + 1
        # The items' corners and ranks in tree order (perm), carried from level to level.
        perm = np.arange(n)
        self.levels = []
        while True:
            boxes = _node_boxes(corners, starts, ends)
            self.levels.append((starts, ends, boxes))
            if (ends - starts).max(initial=0) <= leaf_size:
                break
            # Split every node at its median along its wider side.
            axis = boxes[2] - boxes[0] < boxes[3] - boxes[1]
            node_of = np.repeat(np.arange(len(starts)), ends - starts)
            order = np.argsort(node_of * span + np.where(axis[node_of], ranks[1], ranks[0]), kind="stable")
            perm, corners, ranks = perm[order], np.take(corners, order, axis=1), np.take(ranks, order, axis=1)
            mids = (starts + ends) // 2
            starts = np.stack([starts, mids], axis=1).ravel()
            ends = np.stack([mids, ends], axis=1).ravel()
        self.perm = perm

    def _descend(self, depth, q, node):
        """The children of the surviving (query, node) pairs, below level ``depth``."""
        if depth + 1 == len(self.levels):
            return q, node
        return np.repeat(q, 2), np.stack([2 * node, 2 * node + 1], axis=1).ravel()

    def _leaf_points(self, q, node):
        """Every (query, point) of the (query, leaf) pairs ``q``, ``node``, pair after pair, with
        in-range gathers by take(mode="wrap") and the queries repeated, not gathered."""
        starts, ends, _ = self.levels[-1]
        first = np.take(starts, node, mode="wrap")
        counts = np.take(ends, node, mode="wrap") - first
        # Entry e (counted over all pairs) of pair p is perm[first[p] + e - entries before p].
        at = np.arange(int(counts.sum())) + np.repeat(first - (np.cumsum(counts) - counts), counts)
        return np.repeat(q, counts), np.take(self.perm, at, mode="wrap")

    def nearest_d2(self, x):
        """Squared distance from each query point to its nearest point of the tree, shape (K,).

        All queries walk the tree level by level at once; a node is dropped when its box is
        farther than the nearest *farthest corner* of the query's surviving nodes (a box holding
        points has one within that distance), so only nodes near the minimum reach the leaves,
        whose points are then measured.
        """
        x = np.asarray(x, dtype=np.float64).reshape(-1, 2)
        k, xy = len(x), np.ascontiguousarray(x.T)
        q = np.arange(k)
        node = np.zeros(k, dtype=np.int64)
        for depth, (_, _, boxes) in enumerate(self.levels):
            bx = np.take(boxes, node, axis=1)
            near, far = _box_reach(bx, np.take(xy, q, axis=1))
            empty = np.isnan(bx[0])
            near, far = np.where(empty, np.inf, near), np.where(empty, np.inf, far)
            bound = np.full(k, np.inf)
            np.minimum.at(bound, q, far)
            keep = near <= bound[q]
            q, node = self._descend(depth, q[keep], node[keep])
        pq, pts = self._leaf_points(q, node)
        best = np.full(k, np.inf)
        np.minimum.at(best, pq, np.sum(np.square(self.points[pts] - x[pq]), axis=1))
        return best

    def nearest_candidates(self, x, reach, group, slack=0.0):
        """Items that may hold the closest point of its group to each query, within a reach.

        Parameters
        ----------
        x : ndarray, shape (K, 2)
        reach : ndarray, shape (K,)
            Items farther than this are not candidates.
        group : ndarray of int, shape (K,)
            The group (see ``groups``) each query searches.
        slack : float or ndarray, shape (K,)
            Added to every bound: an exact distance computed by the caller may fall short of
            the true one by round-off (a caller keeping candidates for later adds a margin).

        Returns
        -------
        query, item : ndarray of int, shape (M,)
            Sorted by query. Among them is every item of the query's group whose box lies
            within ``reach`` and within the nearest far corner of the group's boxes (each plus
            slack): the closest item within reach is.

        Notes
        -----
        Like :meth:`nearest_d2`: every non-empty box holds an item within its far corner, so
        the nearest far corner among a query's nodes bounds its closest distance; nodes (and
        at last items) beyond the bound are dropped level by level.
        """
        x = np.ascontiguousarray(np.asarray(x, dtype=np.float64).reshape(-1, 2).T)
        q, node = np.arange(x.shape[1]), np.asarray(group, dtype=np.int64)
        slack = np.asarray(slack, dtype=np.float64)
        limit = np.asarray(reach, dtype=np.float64) + slack
        # Nodes and items are in range: mode="wrap" skips the bounds checks (2-3x faster gathers).
        for depth, (_, _, boxes) in enumerate(self.levels):
            q, node = self._nearer(x, q, node, np.take(boxes, node, axis=1, mode="wrap"), limit, slack)
            q, node = self._descend(depth, q, node)
        q, item = self._leaf_points(q, node)
        if self.item_boxes is None:
            boxes = np.tile(np.take(self.xy, item, axis=1, mode="wrap"), (2, 1))
        else:
            boxes = np.take(self.item_boxes, item, axis=1, mode="wrap")
        q, item = self._nearer(x, q, item, boxes, limit, slack)
        return q, item

    @staticmethod
    def _nearer(x, q, node, boxes, limit, slack):
        """The (query, node) pairs, sorted by query, whose box lies within the query's bound
        (``x``, shape (2, K), and ``boxes``, shape (4, M), coordinate by coordinate)."""
        # An empty node's NaNs: fmin passes them over, and NaN <= bound drops the node.
        near2, far2 = _box_reach(boxes, np.take(x, q, axis=1, mode="wrap"))
        bound = limit.copy()
        if len(q):
            first = np.flatnonzero(np.concatenate(([True], q[1:] != q[:-1])))
            head = q[first]
            bound[head] = np.fmin(
                bound[head],
                np.sqrt(np.fmin.reduceat(far2, first)) + (slack if slack.ndim == 0 else slack[head]),
            )
        # Squared per query, then gathered (the same values as gathered, then squared).
        keep = near2 <= np.take(np.square(bound, out=bound), q, mode="wrap")
        return q[keep], node[keep]

    def within(self, centres, radii, first_only=False):
        """Points strictly inside disks.

        Parameters
        ----------
        centres : ndarray, shape (K, 2)
        radii : ndarray, shape (K,)
        first_only : bool
            Report at most about one point per wholly-covered node (enough to prove a disk is
            not empty, and much cheaper for large disks).

        Returns
        -------
        query, point : ndarray of int, shape (M,)
            Each pair is a query index and the index of a point with
            ``|point - centre| < radius``.
        """
        centres = np.asarray(centres, dtype=np.float64).reshape(-1, 2)
        r2 = np.square(np.asarray(radii, dtype=np.float64)).reshape(-1)
        found_q, found_p = [], []
        q = np.arange(len(centres))
        node = np.zeros(len(centres), dtype=np.int64)
        xy = np.ascontiguousarray(centres.T)
        for depth, (starts, ends, boxes) in enumerate(self.levels):
            near2, far2 = _box_reach(np.take(boxes, node, axis=1), np.take(xy, q, axis=1))
            near = near2 < r2[q]
            inside = near & (far2 < r2[q])
            if inside.any():
                iq, inode = q[inside], node[inside]
                counts = np.ones(len(iq), np.int64) if first_only else ends[inode] - starts[inode]
                owner, local = ragged_arange(counts)
                found_q.append(iq[owner])
                found_p.append(self.perm[starts[inode][owner] + local])
            keep = near & ~inside
            q, node = self._descend(depth, q[keep], node[keep])
        # Leaves that cross a boundary: test their points one by one.
        pq, pp = self._leaf_points(q, node)
        d2 = np.sum(np.square(self.points[pp] - centres[pq]), axis=1)
        hit = d2 < r2[pq]
        found_q.append(pq[hit])
        found_p.append(pp[hit])
        return np.concatenate(found_q), np.concatenate(found_p)


def _node_boxes(corners, starts, ends):
    """Each node's box, shape (4, nodes) (see :func:`_box_reach`), from its items' corners in
    tree order, shape (4, N) (nodes tile them: ``starts``, ``ends``)."""
    boxes = np.full((4, len(starts)), np.nan)
    nonempty = ends > starts
    if not corners.shape[1] or not nonempty.any():
        return boxes
    # Nodes tile the items, so reduceat over the non-empty ones' starts takes exactly each node.
    idx = starts[nonempty]
    boxes[:2, nonempty] = np.minimum.reduceat(corners[:2], idx, axis=1)
    boxes[2:, nonempty] = np.maximum.reduceat(corners[2:], idx, axis=1)
    return boxes


def _union_boxes(lows, highs, start):
    """Bounding boxes of consecutive ranges ``[start[k], start[k + 1])``, shape (len(start), 4).

    ``lows`` and ``highs``, shape (N, 2), are the corners (the same array for points).
    """
    return np.concatenate([np.minimum.reduceat(lows, start, axis=0), np.maximum.reduceat(highs, start, axis=0)], axis=1)


class CurveTree:
    """A bounding-volume hierarchy over polylines, built from runs of consecutive vertices.

    Consecutive vertices of a curve are close to each other, so runs of them make tight boxes
    without any sorting: leaves are runs of ``leaf_size`` vertices, and every level above merges
    pairs of neighbouring nodes *of the same curve* until each curve has one root. Building is
    linear in the number of vertices (a k-d tree sorts at every level), and a query only
    descends the curves it names, which is what a batch of unrelated stroke pairs needs.

    Parameters
    ----------
    points : ndarray, shape (N, 2)
    offsets : ndarray of int, shape (C + 1,)
        Curve ``c`` owns ``points[offsets[c]:offsets[c + 1]]``.
    leaf_size : int
    """

    def __init__(self, points, offsets, leaf_size=8):
        self.points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        offsets = np.asarray(offsets, dtype=np.int64)
        sizes = np.diff(offsets)
        runs = -(-sizes // leaf_size)  # ceil
        owner, local = ragged_arange(runs)
        start = offsets[:-1][owner] + local * leaf_size
        end = np.minimum(start + leaf_size, offsets[1:][owner])
        boxes = self._boxes(start, end)
        # levels[l] = (child_start, child_end, boxes) with children in level l - 1 (leaves:
        # vertex ranges); nodes of a curve are contiguous at every level.
        self.levels = [(start, end, boxes)]
        count = runs
        while count.max(initial=0) > 1:
            first = np.concatenate([[0], np.cumsum(count)])[:-1]
            parents = -(-count // 2)
            owner, local = ragged_arange(parents)
            c_start = first[owner] + 2 * local
            c_end = np.minimum(c_start + 2, first[owner] + count[owner])
            prev = self.levels[-1][2]
            boxes = _union_boxes(prev[:, :2], prev[:, 2:], c_start)
            # reduceat over [c_start, next c_start): the last parent of a curve may have one child.
            single = c_end - c_start == 1
            boxes[single] = prev[c_start[single]]
            self.levels.append((c_start, c_end, boxes))
            count = parents
        self.roots = np.concatenate([[0], np.cumsum(count)])[:-1]  # root node of each curve
        self.has_points = sizes > 0
        # Queried coordinate by coordinate (see _box_reach): boxes as (4, nodes) rows.
        self.levels = [(c_start, c_end, np.ascontiguousarray(boxes.T)) for c_start, c_end, boxes in self.levels]
        self.xy = np.ascontiguousarray(self.points.T)

    def _boxes(self, start, end):
        if len(start) == 0:
            return np.zeros((0, 4))
        # Runs tile the point array, so reduceat's ranges are exactly the runs.
        return _union_boxes(self.points, self.points, start)

    def within(self, centres, radii, curves, first_only=False):
        """Vertices of given curves strictly inside disks.

        Parameters
        ----------
        centres : ndarray, shape (K, 2)
        radii : ndarray, shape (K,)
        curves : ndarray of int, shape (K, J)
            The curves searched for each disk.
        first_only : bool
            Report one vertex per node lying wholly inside a disk (enough to prove it is not
            empty).

        Returns
        -------
        query, point : ndarray of int, shape (M,)
        """
        centres = np.asarray(centres, dtype=np.float64).reshape(-1, 2)
        r2 = np.square(np.asarray(radii, dtype=np.float64)).reshape(-1)
        if len(centres) == 0:
            return np.zeros(0, np.int64), np.zeros(0, np.int64)
        curves = np.asarray(curves, dtype=np.int64).reshape(len(centres), -1)
        q = np.repeat(np.arange(len(centres)), curves.shape[1])
        c = curves.ravel()
        keep = self.has_points[c]
        q, node = q[keep], self.roots[c[keep]]
        found_q, found_p = [], []
        xy = np.ascontiguousarray(centres.T)
        for depth in range(len(self.levels) - 1, -1, -1):
            c_start, c_end, boxes = self.levels[depth]
            near2, far2 = _box_reach(np.take(boxes, node, axis=1), np.take(xy, q, axis=1))
            near = near2 < r2[q]
            inside = near & (far2 < r2[q])
            if depth == 0:
                q, node = q[near], node[near]
                break
            if inside.any() and first_only:
                leaf = node[inside]
                for lower in range(depth, 0, -1):
                    leaf = self.levels[lower][0][leaf]
                found_q.append(q[inside])
                found_p.append(self.levels[0][0][leaf])
                near &= ~inside
            q, node = q[near], node[near]
            owner, local = ragged_arange(c_end[node] - c_start[node])
            q, node = q[owner], c_start[node][owner] + local
        start, end, _ = self.levels[0]
        owner, local = ragged_arange(end[node] - start[node])
        pq, pp = q[owner], start[node][owner] + local
        dx, dy = np.take(self.xy, pp, axis=1) - np.take(xy, pq, axis=1)
        d2 = dx * dx + dy * dy
        hit = d2 < r2[pq]
        found_q.append(pq[hit])
        found_p.append(pp[hit])
        return np.concatenate(found_q), np.concatenate(found_p)
