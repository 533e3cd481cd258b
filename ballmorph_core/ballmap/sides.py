"""The curves a ball-map runs on: every chain's curve densely resampled, with gap normals."""

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..geometry.ragged import Ragged, ragged_arange
from ..geometry.spline import densify, needs_subdivision
from ..geometry.vectors import norms

__all__ = ["Sides", "Side", "EDGE_BLOCK"]

#: Consecutive edges (by global first vertex) sharing one bounding box in :attr:`Sides.blocks`.
EDGE_BLOCK = 8


class Sides:
    """Dense samples of one curve per chain, with normals pointing into each chain's gap.

    Parameters
    ----------
    curves : list of ndarray, each shape (n_c, 2)
    closed : array_like of bool, shape (C,)
    sides : array_like, shape (C,)
        +1 where the gap lies left of the curve, -1 where it lies right.
    spacing : array_like, shape (C,)
        Sample spacing of each chain.

    Attributes
    ----------
    rg : Ragged
        The dense curves.
    vnormals, enormals : ndarray, shape (N, 2)
        Vertex normals and edge normals (by first vertex), into the gap.
    columns : tuple of ndarray, shape (2, N)
        ``rg.pts``, ``rg.edge`` and ``enormals`` coordinate by coordinate (for the searches'
        gathers, see :func:`~ballmorph_core.ballmap.candidates.tangent_disks`).
    """

    def __init__(self, curves, closed, sides, spacing):
        spacing = np.asarray(spacing, dtype=np.float64)
        raw = Ragged.from_list(curves, closed)
        # Coarse, hand-placed polylines get a few interpolating subdivision steps first: only
        # those whose longest edge densify would find too long are handed to it (the same test
        # on the same edges, batched; the others it would return unchanged).
        if len(raw):
            longest = np.maximum.reduceat(raw.length_of_edge, raw.offsets[:-1])
            coarse = needs_subdivision(longest, spacing)
            if coarse.any():
                curves = [densify(c, cl, h) if f else c for c, cl, h, f in zip(curves, closed, spacing, coarse)]
                raw = Ragged.from_list(curves, closed)
        counts = np.round(raw.length / spacing).astype(np.int64) + np.where(raw.closed, 0, 1)
        self.rg = raw.resample(counts)
        # Turned column by column, in place (numpy multiplies (N, 2) rows by an (N, 1) column
        # a row at a time, several times slower).
        side = np.repeat(np.asarray(sides, dtype=np.float64), self.rg.n)
        self.vnormals, self.enormals = self.rg.vertex_normals(), self.rg.edge_normals()
        for normals in (self.vnormals, self.enormals):
            normals[:, 0] *= side
            normals[:, 1] *= side
        self.columns = tuple(np.ascontiguousarray(v.T) for v in (self.rg.pts, self.rg.edge, self.enormals))
        self._windows = {}

    def windows(self, before, after):
        """The vertices ``before`` before to ``after`` after every vertex, on its curve (wrapping
        round a loop, stopping at a stroke's ends), laid out once per width.

        Every curve's vertices are laid out padded by its window's overhang, so the window of
        a vertex is a run of the padded layout: the disk check reads the window round every
        contact of both directions place by place, one gather per place.

        Returns
        -------
        x, y : ndarray, shape (R + W - 1,)
            Coordinates of the padded layout, ``W = before + after + 1``; the window of global
            vertex ``v`` of curve ``c`` starts at place ``v + (W - 1) c`` and holds the next
            ``W`` places.
        vertex : ndarray of int, shape (R + W - 1,)
            The global vertex at each place.
        """
        key = (before, after)
        if key not in self._windows:
            rg = self.rg
            curve, local = ragged_arange(rg.n + before + after)
            vertex = rg.offsets[curve] + local - before
            # Loops wrap round, open curves stop at their ends (rows by index: open batches
            # skip the mod).
            loops = np.flatnonzero(rg.closed[curve])
            first, n_v = rg.offsets[curve], rg.n[curve]
            wrapped = first[loops] + np.mod(vertex[loops] - first[loops], n_v[loops])
            np.clip(vertex, first, first + n_v - 1, out=vertex)
            vertex[loops] = wrapped
            # In range: take's 'wrap' mode skips the bounds check.
            x, y = (np.take(v, vertex, mode="wrap") for v in self.columns[0])
            self._windows[key] = x, y, vertex
        return self._windows[key]

    @cached_property
    def blocks(self):
        """Every run of ``EDGE_BLOCK`` edges (by global first vertex, ``g // EDGE_BLOCK``; a run
        may span two chains): its box and its longest edge, ``xmin, ymin, xmax, ymax, longest``,
        each shape (B,). The box holds each edge from ``a`` to ``a + edge`` as the lacing
        computes them (an open curve's last vertex, which starts no edge, is a point)."""
        (x, y), (ex, ey) = self.columns[0], self.columns[1]
        starts = np.arange(0, len(x), EDGE_BLOCK)
        if not len(starts):
            return tuple(np.zeros(0) for _ in range(5))
        bx, by = x + ex, y + ey
        return (
            np.minimum.reduceat(np.minimum(x, bx), starts),
            np.minimum.reduceat(np.minimum(y, by), starts),
            np.maximum.reduceat(np.maximum(x, bx), starts),
            np.maximum.reduceat(np.maximum(y, by), starts),
            np.maximum.reduceat(norms(ex, ey), starts),
        )

    @staticmethod
    def block_of(edge):
        """The block (see :attr:`blocks`) of global edges ``edge``, ndarray of int."""
        return edge // EDGE_BLOCK

    def view(self, c):
        """Curve ``c`` alone (Side)."""
        rg = self.rg
        sl = slice(rg.offsets[c], rg.offsets[c + 1])
        n_e = rg.n_edges[c]
        return Side(
            rg.pts[sl],
            self.vnormals[sl],
            self.enormals[sl][:n_e],
            np.concatenate([rg.s[sl], [rg.length[c]]]) if rg.closed[c] else rg.s[sl],
            float(rg.length[c]),
        )


@dataclass
class Side:
    """One dense curve of a chain: points, normals into the gap, arc length.

    Attributes
    ----------
    pts, vnormals : ndarray, shape (N, 2)
    enormals : ndarray, shape (E, 2)
    cum : ndarray, shape (N,) for a stroke, (N + 1,) for a loop
        Arc length at each vertex (a loop's last entry is its length).
    length : float
    """

    pts: np.ndarray
    vnormals: np.ndarray
    enormals: np.ndarray
    cum: np.ndarray
    length: float
