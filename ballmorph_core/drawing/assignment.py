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

# Rows of distances the searches first make room for (see _Duals.rows).
_ROWS_FIRST = 64


@dataclass
class _Duals:
    """Dual potentials and the partial assignment (rows fewer than columns)."""

    c: np.ndarray
    u: np.ndarray
    v: np.ndarray
    row4col: np.ndarray
    col4row: np.ndarray
    #: Row k: the distances of the k-th row a search visits (kept from search to search, so
    #: its memory is reused; doubled when a search goes deeper, never beyond the table's size).
    rows: np.ndarray

    @classmethod
    def row_reduced(cls, c):
        """u_i = min_j c_ij, v = 0 is dual feasible (c_ij - u_i - v_j >= 0), and a row sitting on
        its cheapest column has zero reduced cost, so that partial assignment already satisfies
        complementary slackness."""
        n_rows, n_cols = c.shape
        duals = cls(
            c,
            c.min(axis=1),
            np.zeros(n_cols),
            np.full(n_cols, -1, np.int64),
            np.full(n_rows, -1, np.int64),
            np.empty((min(_ROWS_FIRST, n_rows), n_cols)),
        )
        taken, first_row = np.unique(np.argmin(c, axis=1), return_index=True)
        duals.row4col[taken] = first_row
        duals.col4row[first_row] = taken
        return duals

    def shortest_path(self, cur):
        """Dijkstra from row ``cur`` to a free column: (end column, visited rows, their distance
        rows, distances, scanned columns, path length); the distances are final where scanned.

        One step is a few passes over the columns, in place: the least distance of each column
        not scanned yet (``remaining``) is kept as the rows are visited. A scanned column's
        distance is set aside, and its potential taken as -inf for the rest of the search, so
        the later rows' distances to it come out inf and it never is the least again. Which
        row reached a column first at its distance (its predecessor) is read off the visited
        rows' distances only for the columns of the path (:func:`_predecessor`)."""
        n_cols = len(self.v)
        remaining, shortest = np.full(n_cols, np.inf), np.full(n_cols, np.inf)
        v = self.v.copy()
        unscanned, visited = np.ones(n_cols, bool), []
        rows = self.rows
        free = self.row4col < 0
        # The free columns in order: the first of them at the least distance is the one an
        # exact tie with a taken column goes to (a gather, not a pass over every column).
        free_cols = np.flatnonzero(free)
        i, min_val = int(cur), 0.0
        while True:
            if len(visited) == len(rows):
                rows = self.rows = np.concatenate([rows, np.empty((min(len(rows), len(self.u) - len(rows)), n_cols))])
            reduced = rows[len(visited)]
            visited.append(i)
            # min_val + c_i - u_i - v, in that order (the same rounding as written out).
            np.add(self.c[i], min_val, out=reduced)
            reduced -= self.u[i]
            reduced -= v
            np.minimum(remaining, reduced, out=remaining)
            j = int(remaining.argmin())
            min_val = remaining[j]
            if not free[j]:
                # Prefer a free column among equals: it ends the search at once.
                k = int(free_cols[remaining[free_cols].argmin()])
                if remaining[k] == min_val:
                    j = k
            unscanned[j] = False
            shortest[j], remaining[j], v[j] = min_val, np.inf, -np.inf
            if free[j]:
                return j, visited, rows[: len(visited)], shortest, ~unscanned, min_val
            i = int(self.row4col[j])

    def augment(self, cur):
        """Assign row ``cur``: update the potentials so reduced costs stay >= 0 and the new path is
        tight, then flip the assignment along the path."""
        j, visited, rows, shortest, scanned, min_val = self.shortest_path(cur)
        self.u[cur] += min_val
        others = np.asarray(visited[1:], np.int64)
        self.u[others] += min_val - shortest[self.col4row[others]]
        self.v[scanned] -= min_val - shortest[scanned]
        while True:
            i = _predecessor(visited, rows, j)
            self.row4col[j] = i
            self.col4row[i], j = j, int(self.col4row[i])
            if i == cur:
                return


def _predecessor(visited, rows, j):
    """The first of the ``visited`` rows (int) whose distance to column ``j`` (``rows``, shape
    (V, C)) is the least: the row a search step reached ``j`` from (a later row at the same
    distance does not replace it; those visited after ``j`` was scanned have inf there)."""
    return visited[int(rows[:, j].argmin())]


def solve_assignment(cost, duals=False):
    """Minimum-cost assignment of rows to columns (rectangular allowed).

    Parameters
    ----------
    cost : array_like, shape (R, C)
        Finite costs.
    duals : bool
        Also return the optimal dual potentials.

    Returns
    -------
    rows, cols : ndarray of int, shape (min(R, C),)
        Row ``rows[k]`` is assigned column ``cols[k]``; rows sorted. The sum of
        ``cost[rows, cols]`` is minimal over all assignments of ``min(R, C)`` distinct rows to
        distinct columns.
    u, v : ndarray, shape (R,), (C,)
        Only with ``duals``: potentials with ``u_i + v_j <= cost_ij`` for every pair, equal on
        the pairs assigned, and 0 on the rows or columns left out (the larger side's). So any
        other table ``c >= u_i + v_j`` everywhere has the same assignment among its optimal
        ones (the certificate a solve on part of a table is checked with).

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
    shape, transposed = c.shape, c.shape[0] > c.shape[1]
    c = np.ascontiguousarray(c.T if transposed else c)
    if c.shape[0] == 0:
        none = np.zeros(0, np.int64)
        return (none, none, np.zeros(shape[0]), np.zeros(shape[1])) if duals else (none, none)
    solved = _Duals.row_reduced(c)
    for cur in np.flatnonzero(solved.col4row < 0):
        solved.augment(cur)
    rows = np.arange(c.shape[0])
    if transposed:
        order = np.argsort(solved.col4row)
        rows, cols, u, v = solved.col4row[order], rows[order], solved.v, solved.u
    else:
        rows, cols, u, v = rows, solved.col4row.copy(), solved.u, solved.v
    return (rows, cols, u, v) if duals else (rows, cols)
