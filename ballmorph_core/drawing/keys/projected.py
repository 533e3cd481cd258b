"""A key as the pipeline sees it: its strokes projected into the drawing plane, and every
point attribute ready to be read at any fraction along any stroke."""

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ...geometry.polyline import reversal_order, reversed_fractions
from ...geometry.ragged import Ragged

__all__ = ["KeyStroke", "StrokePair", "ProjectedKey"]


@dataclass
class KeyStroke:
    """One stroke as the morphs see it.

    Attributes
    ----------
    index : int
        Its index in the key.
    xy : ndarray, shape (N, 2)
        Its points in the drawing plane (reversed when the pairing flipped it).
    u : ndarray, shape (N,)
        Their arc-length fractions along the stroke as morphed.
    closed : bool
    material : int
    """

    index: int
    xy: np.ndarray
    u: np.ndarray
    closed: bool
    material: int


class StrokePair(NamedTuple):
    """A stroke of each key that morph into each other: ``a`` of the first key, ``b`` of the
    second as morphed (reversed when ``flipped``: it was drawn the other way)."""

    a: KeyStroke
    b: KeyStroke
    flipped: bool


class ProjectedKey:
    """A key projected into the drawing plane, with everything a stroke carries.

    Parameters
    ----------
    strokes : StrokeSet
    plane : Plane
    extra_values : ndarray, shape (N, F), optional
        More per-point values to read along the strokes (the interpolated extra attributes).

    Attributes
    ----------
    rg : Ragged
        The strokes' 2D points (arc lengths and fractions come from it).
    width : int
        Values per point (7 + F): offset from the plane, radius, opacity, vertex colour (RGBA),
        the extra values (:meth:`values` reads them). A key whose strokes are all open is read
        from its own arrays (``strokes``: not to be modified while the key is in use); a key
        with loops from a table that closes them.
    """

    def __init__(self, strokes, plane, extra_values=None):
        xy, depth = plane.to_2d(strokes.positions)
        self.rg = Ragged(xy, strokes.offsets, strokes.cyclic)
        self.strokes = strokes
        extra = np.zeros((len(xy), 0)) if extra_values is None else np.asarray(extra_values, dtype=np.float64)
        columns = [depth, strokes.radius, strokes.opacity, *np.asarray(strokes.vertex_color).T, *extra.T]
        self.width = len(columns)
        self.u = self._fractions(strokes.offsets)
        # Interpolation table: every stroke's fractions shifted by 2 per stroke, loops closed by
        # their first point at fraction 1, so one np.interp serves all strokes at once.
        first = strokes.offsets[:-1][self.rg.n > 0]
        closing = first[self.rg.closed[self.rg.n > 0] | (self.rg.n[self.rg.n > 0] == 1)]
        owner = np.concatenate([self.rg.owner, self.rg.owner[closing]])
        x = np.concatenate([self.u, np.ones(len(closing))]) + 2.0 * owner
        order = np.argsort(x, kind="stable")
        if len(closing) == 0 and np.array_equal(order, np.arange(len(order))):
            # Every stroke open (each point its own row, in order, the table the key itself):
            # the values are read from the key's own arrays, not copied (at 250,000 points, 17
            # MiB a key that a plan would keep until it is dropped).
            self._x, self._point, self._row = x, None, None
            self._columns = [np.asarray(column, dtype=np.float64) for column in columns]
            return
        self._x = x[order]
        self._point = np.concatenate([np.arange(len(xy)), closing])[order]
        # The values are kept once, in this table: a contiguous row per value (np.interp reads
        # one at a time), and each point's row in it (its first: a loop's closing copy follows).
        # Gathered value by value straight into it (no (N, width) stack, gather and transpose);
        # the points are in range: mode="wrap" skips take's bounds checks.
        table = np.empty((self.width, len(order)))
        for column, row in zip(columns, table):
            np.take(np.asarray(column, dtype=np.float64), self._point, out=row, mode="wrap")
        self._columns = list(table)
        self._row = np.empty(len(xy), dtype=np.int64)
        own = np.flatnonzero(order < len(xy))
        self._row[order[own]] = own

    def _fractions(self, offsets):
        """Each point's arc-length fraction along its stroke, evenly spaced along a stroke of no
        length, shape (N,) (the even spacing only made when some stroke needs it)."""
        rg = self.rg
        length = rg.length[rg.owner]
        if np.all(rg.length[rg.n > 0] > 0):
            return np.divide(rg.s, length)
        local = np.arange(len(rg.pts)) - offsets[:-1][rg.owner]
        even = np.divide(local, np.maximum(rg.n[rg.owner] - 1, 1))
        return np.where(length > 0, np.divide(rg.s, np.where(length > 0, length, 1.0)), even)

    def stroke(self, i, flip=False):
        """Stroke ``i`` for morphing (KeyStroke), reversed if ``flip``."""
        sl = self.strokes.points(i)
        xy, u = self.rg.pts[sl], self.u[sl]
        closed = bool(self.rg.closed[i])
        if flip:
            order = reversal_order(len(xy), closed)
            xy, u = xy[order], reversed_fractions(u[order], closed)
        return KeyStroke(i, xy, u, closed, int(self.strokes.material_index[i]))

    def nearest(self, stroke, u):
        """The point nearest (in arc length) to fractions ``u`` of given strokes, shape (K,) of int
        (indices into the key's points)."""
        x = np.clip(u, 0.0, 1.0) + 2.0 * np.asarray(stroke)
        right = np.clip(np.searchsorted(self._x, x), 0, len(self._x) - 1)
        left = np.maximum(right - 1, 0)
        pick = np.where(np.abs(self._x[left] - x) <= np.abs(self._x[right] - x), left, right)
        return pick if self._point is None else self._point[pick]

    def sample(self, stroke, u):
        """Per-point values at fractions ``u`` of given strokes (vectorised), shape (K, 7 + F)."""
        return np.column_stack(list(self.sampled(stroke, u)))

    def sampled(self, stroke, u):
        """:meth:`sample`'s columns one at a time, each made when it is asked for (a caller that
        keeps some never holds them all): an iterator of ``width`` arrays of shape (K,)."""
        x = np.clip(u, 0.0, 1.0) + 2.0 * stroke
        for column in self._columns:
            yield np.interp(x, self._x, column)

    def values(self, points):
        """The values of some of the key's points (an index or a slice), shape (K, 7 + F)."""
        rows = points if self._row is None else self._row[points]
        return np.array([column[rows] for column in self._columns]).T
