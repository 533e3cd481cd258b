"""Minimum-cost assignment (the Hungarian method), vectorised over columns.

Shortest augmenting paths with dual potentials, in the Jonker-Volgenant form, rectangular
variant as described by Crouse, "On implementing 2D rectangular assignment algorithms", IEEE
TAES 2016. Each Dijkstra step is one vectorised update over all columns; a row-reduction start
assigns every row whose cheapest column is still free. A table that is one value but at a few
entries (:class:`SparseCosts`) is read row by row as it is needed, never laid out whole.
"""

from dataclasses import dataclass

import numpy as np

from ...errors import InvalidCurveError

__all__ = ["SparseCosts", "solve_assignment"]

# Rows of distances the searches first make room for (see _Duals.rows).
_ROWS_FIRST = 64


@dataclass
class SparseCosts:
    """A cost table that is ``fill`` everywhere but at a few entries.

    Attributes
    ----------
    shape : tuple of int
        ``(R, C)``.
    rows, cols : ndarray of int, shape (K,)
        The entries, each at most once.
    values : ndarray, shape (K,)
    fill : float
    """

    shape: tuple
    rows: np.ndarray
    cols: np.ndarray
    values: np.ndarray
    fill: float

    def at(self, rows, cols):
        """The table's values at ``(rows[k], cols[k])``, shape (K,)."""
        code = self.rows * self.shape[1] + self.cols
        order = np.argsort(code, kind="stable")
        want = np.asarray(rows) * self.shape[1] + np.asarray(cols)
        at = np.minimum(np.searchsorted(code[order], want), max(len(code) - 1, 0))
        found = code[order][at] == want if len(code) else np.zeros(len(want), bool)
        return np.where(found, self.values[order][at] if len(code) else 0.0, self.fill)


class _DenseRows:
    """The rows of a dense table (C-contiguous, shape (R, C))."""

    def __init__(self, c):
        self.c = c

    def reduced(self):
        """Each row's least value and the first column holding it, shapes (R,)."""
        return self.c.min(axis=1), np.argmin(self.c, axis=1)

    def add(self, i, x, out):
        """``out = row i + x`` (float), shape (C,)."""
        np.add(self.c[i], x, out=out)


class _SparseRows:
    """The rows of a :class:`SparseCosts` (its entries sorted by row, then column): the same
    values as the dense table's, every one computed by the same operation."""

    def __init__(self, table, transposed):
        rows, cols = (table.cols, table.rows) if transposed else (table.rows, table.cols)
        self.shape = table.shape[::-1] if transposed else tuple(table.shape)
        order = np.lexsort((cols, rows))
        self.rows, self.cols, self.values = rows[order], cols[order], np.asarray(table.values, np.float64)[order]
        self.start = np.searchsorted(self.rows, np.arange(self.shape[0] + 1))
        self.fill = float(table.fill)

    def reduced(self):
        """As :meth:`_DenseRows.reduced`: the least of a row's entries and, where it has columns
        left out, ``fill``; the first column at that value, an entry's or one left out."""
        n_rows, n_cols = self.shape
        counts = np.diff(self.start)
        least = np.full(n_rows, np.inf)
        np.minimum.at(least, self.rows, self.values)
        gaps = counts < n_cols
        least[gaps] = np.minimum(least[gaps], self.fill)
        first = np.full(n_rows, n_cols)
        at_least = self.values == least[self.rows]
        np.minimum.at(first, self.rows[at_least], self.cols[at_least])
        # A row's first column left out: the first place k where its k-th entry is not column
        # k (entries sorted), else the column after its entries.
        local = np.arange(len(self.rows)) - self.start[self.rows]
        gap = counts.copy()
        skipped = self.cols != local
        np.minimum.at(gap, self.rows[skipped], local[skipped])
        first = np.where(gaps & (least == self.fill), np.minimum(first, gap), first)
        return least, first

    def add(self, i, x, out):
        """``out = row i + x`` (float), shape (C,)."""
        out.fill(self.fill + x)
        at = slice(self.start[i], self.start[i + 1])
        out[self.cols[at]] = self.values[at] + x


@dataclass
class _Duals:
    """Dual potentials and the partial assignment (rows fewer than columns)."""

    #: The table's rows (:class:`_DenseRows` or :class:`_SparseRows`).
    c: object
    u: np.ndarray
    v: np.ndarray
    row4col: np.ndarray
    col4row: np.ndarray
    #: Row k: the distances of the k-th row a search visits (kept from search to search, so
    #: its memory is reused; doubled when a search goes deeper, never beyond the table's size).
    rows: np.ndarray

    @classmethod
    def row_reduced(cls, c, shape):
        """u_i = min_j c_ij, v = 0 is dual feasible (c_ij - u_i - v_j >= 0), and a row sitting on
        its cheapest column has zero reduced cost, so that partial assignment already satisfies
        complementary slackness. ``c``: the table's rows (:class:`_DenseRows` or
        :class:`_SparseRows`), of shape ``shape``."""
        n_rows, n_cols = shape
        least, first = c.reduced()
        duals = cls(
            c,
            least,
            np.zeros(n_cols),
            np.full(n_cols, -1, np.int64),
            np.full(n_rows, -1, np.int64),
            np.empty((min(_ROWS_FIRST, n_rows), n_cols)),
        )
        taken, first_row = np.unique(first, return_index=True)
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
            self.c.add(i, min_val, reduced)
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


class _Walk:
    """The columns one sparse search has reached (:func:`_sparse_augment`), in the order reached:
    each one's distance (inf once scanned), its final distance once scanned, the row it was
    first reached from at that distance."""

    def __init__(self, slot):
        self.slot, self.count = slot, 0  # slot: -1 for every column (given back so at the end)
        self.cols, self.pred = np.zeros(_ROWS_FIRST, np.int64), np.zeros(_ROWS_FIRST, np.int64)
        self.dist, self.shortest = np.full(_ROWS_FIRST, np.inf), np.full(_ROWS_FIRST, np.inf)

    @property
    def reached(self):
        """Distances of the columns reached so far (inf once scanned), shape (R,)."""
        return self.dist[: self.count]

    def reach(self, i, cols, dist):
        """Row ``i`` reaches columns ``cols`` at distances ``dist`` (shapes (K,)): keep the lower."""
        new = cols[self.slot[cols] < 0]
        if len(new):
            end = self.count + len(new)
            if end > len(self.cols):
                grow = max(end, 2 * len(self.cols)) - len(self.cols)
                ints, floats = np.zeros(grow, np.int64), np.full(grow, np.inf)
                self.cols, self.pred = (np.concatenate([a, ints]) for a in (self.cols, self.pred))
                self.dist, self.shortest = (np.concatenate([a, floats]) for a in (self.dist, self.shortest))
            self.slot[new] = np.arange(self.count, end)
            self.cols[self.count : end] = new
            self.count = end
        at = self.slot[cols]
        # A scanned column's distance is inf here: never lowered again.
        better = (dist < self.dist[at]) & np.isinf(self.shortest[at])
        self.dist[at[better]] = dist[better]
        self.pred[at[better]] = i


def _sparse_augment(duals, cur, free_first):
    """:meth:`_Duals.augment` on a :class:`_SparseRows` table, walking each row's entries only.

    A row reaches every column left out of its entries at ``fill``: a free column (potential 0,
    the highest: potentials of columns only fall) at least as near as any taken one, so those
    entries are one candidate, the first free column, at the least ``dist + fill - u`` of the
    rows visited. Each step then costs the row's entries and the columns reached so far, not
    the table's width. ``free_first`` (int): no column before it is free. Returns the next one.
    """
    c, u, v, row4col, col4row = duals.c, duals.u, duals.v, duals.row4col, duals.col4row
    while row4col[free_first] >= 0:
        free_first += 1
    walk, visited = _Walk(duals.slot), []
    i, min_val, fill_best, fill_pred = int(cur), 0.0, np.inf, -1
    while True:
        visited.append(i)
        at = slice(c.start[i], c.start[i + 1])
        cols = c.cols[at]
        dist = c.values[at] + min_val
        dist -= u[i]
        dist -= v[cols]
        walk.reach(i, cols, dist)
        via_fill = c.fill + min_val - u[i]
        if via_fill < fill_best:
            fill_best, fill_pred = via_fill, i
        k = int(walk.reached.argmin()) if walk.count else -1
        if k < 0 or fill_best < walk.dist[k] or (fill_best == walk.dist[k] and row4col[walk.cols[k]] >= 0):
            j, min_val, end_pred = free_first, fill_best, fill_pred
            break
        j, min_val = int(walk.cols[k]), float(walk.dist[k])
        walk.shortest[k], walk.dist[k] = min_val, np.inf
        if row4col[j] < 0:
            end_pred = int(walk.pred[k])
            break
        i = int(row4col[j])
    scanned = np.isfinite(walk.shortest[: walk.count])
    u[cur] += min_val
    others = np.asarray(visited[1:], np.int64)
    u[others] += min_val - walk.shortest[walk.slot[col4row[others]]]
    v[walk.cols[: walk.count][scanned]] -= min_val - walk.shortest[: walk.count][scanned]
    i = end_pred
    while True:
        row4col[j] = i
        col4row[i], j = j, int(col4row[i])
        if i == cur:
            duals.slot[walk.cols[: walk.count]] = -1
            return free_first
        i = int(walk.pred[walk.slot[j]])


def _predecessor(visited, rows, j):
    """The first of the ``visited`` rows (int) whose distance to column ``j`` (``rows``, shape
    (V, C)) is the least: the row a search step reached ``j`` from (a later row at the same
    distance does not replace it; those visited after ``j`` was scanned have inf there)."""
    return visited[int(rows[:, j].argmin())]


def solve_assignment(cost, duals=False, walk_entries=False):
    """Minimum-cost assignment of rows to columns (rectangular allowed).

    Parameters
    ----------
    cost : array_like, shape (R, C), or SparseCosts
        Finite costs.
    duals : bool
        Also return the optimal dual potentials.
    walk_entries : bool
        For a SparseCosts whose ``fill`` is at least every entry: each search walks the rows'
        entries only (its steps cost the entries reached, not the table's width: the bounded
        tables' solves). The same optimal total; between optimal assignments that tie, another
        may be returned.

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
    if isinstance(cost, SparseCosts):
        shape = tuple(cost.shape)
        if not (np.all(np.isfinite(cost.values)) and np.isfinite(cost.fill)):
            raise InvalidCurveError("cost: every entry must be finite")
        transposed = shape[0] > shape[1]
        c = _SparseRows(cost, transposed)
    else:
        # Read only (no copy of a float array: the matching of thousands of strokes passes
        # tables of tens of MiB); rows are read one by one, so a transposed table is made
        # contiguous.
        c = np.asarray(cost, dtype=np.float64)
        if c.ndim != 2:
            raise InvalidCurveError(f"cost: expected a 2-D array, got shape {c.shape}")
        if not np.all(np.isfinite(c)):
            raise InvalidCurveError("cost: every entry must be finite")
        shape, transposed = c.shape, c.shape[0] > c.shape[1]
        c = _DenseRows(np.ascontiguousarray(c.T if transposed else c))
    solved_shape = shape[::-1] if transposed else shape
    if solved_shape[0] == 0:
        none = np.zeros(0, np.int64)
        return (none, none, np.zeros(shape[0]), np.zeros(shape[1])) if duals else (none, none)
    solved = _Duals.row_reduced(c, solved_shape)
    if walk_entries and isinstance(c, _SparseRows):
        free_first, solved.slot = 0, np.full(solved_shape[1], -1, np.int64)
        for cur in np.flatnonzero(solved.col4row < 0):
            free_first = _sparse_augment(solved, cur, free_first)
    else:
        for cur in np.flatnonzero(solved.col4row < 0):
            solved.augment(cur)
    rows = np.arange(solved_shape[0])
    if transposed:
        order = np.argsort(solved.col4row)
        rows, cols, u, v = solved.col4row[order], rows[order], solved.v, solved.u
    else:
        rows, cols, u, v = rows, solved.col4row.copy(), solved.u, solved.v
    return (rows, cols, u, v) if duals else (rows, cols)
