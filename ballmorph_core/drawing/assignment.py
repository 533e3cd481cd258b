"""Minimum-cost assignment (the Hungarian method), vectorised over columns.

Shortest augmenting paths with dual potentials, in the Jonker-Volgenant form, rectangular
variant as described by Crouse, "On implementing 2D rectangular assignment algorithms", IEEE
TAES 2016. Each Dijkstra step is one vectorised update over all columns; a row-reduction start
assigns every row whose cheapest column is still free.
"""

from dataclasses import dataclass

import numpy as np

from ..errors import InvalidCurveError

__all__ = ["solve_assignment"]


@dataclass
class _Duals:
    """Dual potentials and the partial assignment (rows fewer than columns)."""

    c: np.ndarray
    u: np.ndarray
    v: np.ndarray
    row4col: np.ndarray
    col4row: np.ndarray

    @classmethod
    def row_reduced(cls, c):
        """u_i = min_j c_ij, v = 0 is dual feasible (c_ij - u_i - v_j >= 0), and a row sitting on
        its cheapest column has zero reduced cost, so that partial assignment already satisfies
        complementary slackness."""
        n_rows, n_cols = c.shape
        duals = cls(c, c.min(axis=1), np.zeros(n_cols), np.full(n_cols, -1, np.int64), np.full(n_rows, -1, np.int64))
        taken, first_row = np.unique(np.argmin(c, axis=1), return_index=True)
        duals.row4col[taken] = first_row
        duals.col4row[first_row] = taken
        return duals

    def shortest_path(self, cur):
        """Dijkstra from row ``cur`` to a free column: (end column, predecessors, distances,
        scanned columns, visited rows, path length); the distances are final where scanned.

        One step is a few passes over the columns, in place: the distances of the columns not
        scanned yet (``remaining``, inf once scanned) are kept as they change, and a scanned
        column's distance is set aside as it is scanned (it never changes after)."""
        n_cols = len(self.v)
        remaining, shortest = np.full(n_cols, np.inf), np.full(n_cols, np.inf)
        path = np.full(n_cols, -1, np.int64)
        unscanned, visited = np.ones(n_cols, bool), []
        reduced, better = np.empty(n_cols), np.empty(n_cols, bool)
        free = self.row4col < 0
        i, min_val = int(cur), 0.0
        while True:
            visited.append(i)
            # min_val + c_i - u_i - v, in that order (the same rounding as written out).
            np.add(self.c[i], min_val, out=reduced)
            reduced -= self.u[i]
            reduced -= self.v
            np.less(reduced, remaining, out=better)
            better &= unscanned
            np.copyto(path, i, where=better)
            np.copyto(remaining, reduced, where=better)
            min_val = remaining.min()
            ties = np.flatnonzero(remaining == min_val)
            # Prefer a free column among equals: it ends the search at once.
            free_ties = ties[free[ties]]
            j = int(free_ties[0]) if len(free_ties) else int(ties[0])
            unscanned[j] = False
            shortest[j], remaining[j] = remaining[j], np.inf
            if free[j]:
                return j, path, shortest, ~unscanned, visited, min_val
            i = int(self.row4col[j])

    def augment(self, cur):
        """Assign row ``cur``: update the potentials so reduced costs stay >= 0 and the new path is
        tight, then flip the assignment along the path."""
        j, path, shortest, scanned, visited, min_val = self.shortest_path(cur)
        self.u[cur] += min_val
        others = np.asarray(visited[1:], np.int64)
        self.u[others] += min_val - shortest[self.col4row[others]]
        self.v[scanned] -= min_val - shortest[scanned]
        while True:
            i = int(path[j])
            self.row4col[j] = i
            self.col4row[i], j = j, int(self.col4row[i])
            if i == cur:
                return


def solve_assignment(cost):
    """Minimum-cost assignment of rows to columns (rectangular allowed).

    Parameters
    ----------
    cost : array_like, shape (R, C)
        Finite costs.

    Returns
    -------
    rows, cols : ndarray of int, shape (min(R, C),)
        Row ``rows[k]`` is assigned column ``cols[k]``; rows sorted. The sum of
        ``cost[rows, cols]`` is minimal over all assignments of ``min(R, C)`` distinct rows to
        distinct columns.

    Raises
    ------
    InvalidCurveError
        If ``cost`` is not a 2-D array of finite numbers.

    Examples
    --------
    >>> rows, cols = solve_assignment([[4.0, 1.0, 3.0], [2.0, 0.0, 5.0], [3.0, 2.0, 2.0]])
    >>> rows.tolist(), cols.tolist()
    ([0, 1, 2], [1, 0, 2])
    """
    # Read only (no copy of a float array: the matching of thousands of strokes passes tables
    # of tens of MiB); rows are read one by one, so a transposed table is made contiguous.
    c = np.asarray(cost, dtype=np.float64)
    if c.ndim != 2:
        raise InvalidCurveError(f"cost: expected a 2-D array, got shape {c.shape}")
    if not np.all(np.isfinite(c)):
        raise InvalidCurveError("cost: every entry must be finite")
    transposed = c.shape[0] > c.shape[1]
    c = np.ascontiguousarray(c.T if transposed else c)
    if c.shape[0] == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    duals = _Duals.row_reduced(c)
    for cur in np.flatnonzero(duals.col4row < 0):
        duals.augment(cur)
    rows = np.arange(c.shape[0])
    if transposed:
        order = np.argsort(duals.col4row)
        return duals.col4row[order], rows[order]
    return rows, duals.col4row.copy()
