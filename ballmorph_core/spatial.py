"""Spatial search in numpy: candidate pairs of boxes (uniform grid) and points within disks
(a k-d tree walked level by level for all queries at once).

Both keep the core's geometric checks near-linear in the number of vertices instead of testing
every pair, and both run without any per-pair Python loop.
"""

import numpy as np

__all__ = ["ragged_arange", "box_pairs", "PointTree"]


def ragged_arange(counts):
    """Concatenated ``arange(c)`` for every count, and the owner of each entry.

    Parameters
    ----------
    counts : ndarray of int, shape (G,)

    Returns
    -------
    owner : ndarray of int, shape (sum(counts),)
        Group index of each entry.
    local : ndarray of int, shape (sum(counts),)
        Position of each entry inside its group.

    Examples
    --------
    >>> owner, local = ragged_arange(np.array([2, 0, 3]))
    >>> owner.tolist(), local.tolist()
    ([0, 0, 2, 2, 2], [0, 1, 0, 1, 2])
    """
    counts = np.asarray(counts, dtype=np.int64)
    owner = np.repeat(np.arange(len(counts)), counts)
    starts = np.cumsum(counts) - counts
    local = np.arange(int(counts.sum()), dtype=np.int64) - np.repeat(starts, counts)
    return owner, local


def _cells(boxes, origin, cell, ny):
    ix0 = np.floor((boxes[:, 0] - origin[0]) / cell).astype(np.int64)
    iy0 = np.floor((boxes[:, 1] - origin[1]) / cell).astype(np.int64)
    ix1 = np.floor((boxes[:, 2] - origin[0]) / cell).astype(np.int64)
    iy1 = np.floor((boxes[:, 3] - origin[1]) / cell).astype(np.int64)
    nx, nyy = ix1 - ix0 + 1, iy1 - iy0 + 1
    owner, local = ragged_arange(nx * nyy)
    cx = ix0[owner] + local % nx[owner]
    cy = iy0[owner] + local // nx[owner]
    return cx * ny + cy, owner


def box_pairs(boxes_a, boxes_b=None, cell=None):
    """All pairs of overlapping axis-aligned boxes.

    Parameters
    ----------
    boxes_a : ndarray, shape (A, 4)
        Rows ``(xmin, ymin, xmax, ymax)``.
    boxes_b : ndarray, shape (B, 4), optional
        If omitted, pairs within ``boxes_a`` are returned with ``i < j``.
    cell : float, optional
        Grid cell size; default the median box size.

    Returns
    -------
    i, j : ndarray of int, shape (K,)
        Indices into ``boxes_a`` and ``boxes_b`` of boxes that overlap (touching counts).
    """
    same = boxes_b is None
    a = np.asarray(boxes_a, dtype=np.float64).reshape(-1, 4)
    b = a if same else np.asarray(boxes_b, dtype=np.float64).reshape(-1, 4)
    empty = np.zeros(0, dtype=np.int64)
    if len(a) == 0 or len(b) == 0:
        return empty, empty
    both = np.concatenate([a, b])
    origin = both[:, :2].min(axis=0)
    extent = float(max((both[:, 2:] - origin).max(), 1e-300))
    if cell is None:
        sizes = np.maximum(both[:, 2] - both[:, 0], both[:, 3] - both[:, 1])
        cell = float(np.median(sizes))
    # Bound the grid so a few huge boxes cannot explode the cell count.
    cell = max(cell, extent / 4096.0, 1e-300)
    ny = int(extent / cell) + 2
    key_a, own_a = _cells(a, origin, cell, ny)
    key_b, own_b = (key_a, own_a) if same else _cells(b, origin, cell, ny)
    order = np.argsort(key_a, kind="stable")
    key_a, own_a = key_a[order], own_a[order]
    lo = np.searchsorted(key_a, key_b, side="left")
    hi = np.searchsorted(key_a, key_b, side="right")
    owner, local = ragged_arange(hi - lo)
    i = own_a[lo[owner] + local]
    j = own_b[owner]
    keep = (a[i, 0] <= b[j, 2]) & (b[j, 0] <= a[i, 2]) & (a[i, 1] <= b[j, 3]) & (b[j, 1] <= a[i, 3])
    if same:
        keep &= i < j
    code = np.unique(i[keep] * len(b) + j[keep])
    return code // len(b), code % len(b)


class PointTree:
    """A balanced k-d tree over points, queried for all disks at once.

    Parameters
    ----------
    points : ndarray, shape (N, 2)
    leaf_size : int
        Points per leaf at most.

    Notes
    -----
    The tree is implicit: at every level node ``k`` owns ``perm[start[k]:end[k]]`` and its
    children are nodes ``2k`` and ``2k + 1`` of the next level. Queries keep a frontier of
    (query, node) pairs, drop nodes that lie outside the disk and report nodes that lie wholly
    inside it, so only nodes crossing a disk's boundary are refined.
    """

    def __init__(self, points, leaf_size=8):
        self.points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        n = len(self.points)
        perm = np.arange(n)
        starts, ends = np.array([0]), np.array([n])
        self.levels = []
        while True:
            boxes = self._boxes(perm, starts, ends)
            self.levels.append((starts, ends, boxes))
            if (ends - starts).max(initial=0) <= leaf_size:
                break
            # Split every node at its median along its wider side.
            axis = (boxes[:, 2] - boxes[:, 0] < boxes[:, 3] - boxes[:, 1]).astype(np.int64)
            node_of = np.repeat(np.arange(len(starts)), ends - starts)
            coord = self.points[perm, axis[node_of]]
            perm = perm[np.lexsort((coord, node_of))]
            mids = (starts + ends) // 2
            starts = np.stack([starts, mids], axis=1).ravel()
            ends = np.stack([mids, ends], axis=1).ravel()
        self.perm = perm

    def _boxes(self, perm, starts, ends):
        if len(perm) == 0:
            return np.full((len(starts), 4), np.nan)
        pts = self.points[perm]
        nonempty = ends > starts
        boxes = np.full((len(starts), 4), np.nan)
        idx = starts[nonempty]
        boxes[nonempty, 0] = np.minimum.reduceat(pts[:, 0], idx)
        boxes[nonempty, 1] = np.minimum.reduceat(pts[:, 1], idx)
        boxes[nonempty, 2] = np.maximum.reduceat(pts[:, 0], idx)
        boxes[nonempty, 3] = np.maximum.reduceat(pts[:, 1], idx)
        return boxes

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
        for depth, (starts, ends, boxes) in enumerate(self.levels):
            bx = boxes[node]
            c = centres[q]
            dx = np.maximum(np.maximum(bx[:, 0] - c[:, 0], c[:, 0] - bx[:, 2]), 0.0)
            dy = np.maximum(np.maximum(bx[:, 1] - c[:, 1], c[:, 1] - bx[:, 3]), 0.0)
            near = dx * dx + dy * dy < r2[q]
            fx = np.maximum(np.abs(bx[:, 0] - c[:, 0]), np.abs(bx[:, 2] - c[:, 0]))
            fy = np.maximum(np.abs(bx[:, 1] - c[:, 1]), np.abs(bx[:, 3] - c[:, 1]))
            inside = near & (fx * fx + fy * fy < r2[q])
            if inside.any():
                iq, inode = q[inside], node[inside]
                counts = np.ones(len(iq), np.int64) if first_only else ends[inode] - starts[inode]
                owner, local = ragged_arange(counts)
                found_q.append(iq[owner])
                found_p.append(self.perm[starts[inode][owner] + local])
            keep = near & ~inside
            q, node = q[keep], node[keep]
            if depth + 1 < len(self.levels):
                q = np.repeat(q, 2)
                node = np.stack([2 * node, 2 * node + 1], axis=1).ravel()
        # Leaves that cross a boundary: test their points one by one.
        starts, ends, _ = self.levels[-1]
        owner, local = ragged_arange(ends[node] - starts[node])
        pq, pp = q[owner], self.perm[starts[node][owner] + local]
        d2 = np.sum(np.square(self.points[pp] - centres[pq]), axis=1)
        hit = d2 < r2[pq]
        found_q.append(pq[hit])
        found_p.append(pp[hit])
        return np.concatenate(found_q), np.concatenate(found_p)
