"""How far in-betweens stray from what their keys suggest: what the add-on's warnings measure.

A stroke pair's in-between should have about the ink length of the keys' linear blend of
lengths, ``(1 - t) L_a + t L_b`` at morph time ``t``; :func:`length_deviation` measures how far
each pair's in-betweens are from it. :data:`FALLBACK_MORPHS` names the morphs a pair gets when
the one asked for cannot follow it (they appear in :attr:`PairReport.method
<ballmorph_core.drawing.strokes.PairReport>`). Deciding what strays too far is the caller's.
"""

import numpy as np

from ..pair_morphs.fallbacks import ALIGNED_METHOD, FALLBACK_METHOD, STRAIGHT_POINT_MOTION

__all__ = ["FALLBACK_MORPHS", "ink_lengths", "length_deviation"]

#: The morphs a pair falls back to (``drawing.fallbacks``): the composite ball-morph, linear
#: and aligned interpolation, and the straight point motion of strokes too short to morph.
FALLBACK_MORPHS = ("composite-ball", FALLBACK_METHOD, ALIGNED_METHOD, STRAIGHT_POINT_MOTION)


def ink_lengths(strokes):
    """The ink length of every stroke of a drawing, in 3D (a cyclic stroke's closing edge included).

    Parameters
    ----------
    strokes : StrokeSet
        S strokes, N points.

    Returns
    -------
    ndarray, shape (S,)

    Examples
    --------
    >>> from ..strokes import StrokeSet
    >>> square = [[0, 0], [1, 0], [1, 1], [0, 1]]
    >>> ink_lengths(StrokeSet.from_strokes([square, square], cyclic=[False, True])).tolist()
    [3.0, 4.0]
    """
    return _ink_lengths(strokes, _Work())


class _Work:
    """Work buffers of :func:`_ink_lengths`, grown as needed and kept from frame to frame (a
    fresh full-size temporary is page-faulted anew on each frame in a bpy process)."""

    def __init__(self):
        self.edges, self.term = np.empty(0), np.empty(0)

    def get(self, n):
        """``edges`` and ``term``, (n,) each."""
        if len(self.edges) < n:
            self.edges, self.term = np.empty(n), np.empty(n)
        return self.edges[:n], self.term[:n]


def _edge_lengths(positions, out, term):
    """The length of each edge between consecutive rows of ``positions`` (n + 1, 3) into ``out``
    (n,); ``term`` (n,) is a work column.

    Coordinate by coordinate, in two columns: no (n, 3) array of the steps, and no reduction
    along rows of three (slow in numpy). The squares are added x and z, then y: the order
    np.einsum("ij,ij->i") took in numpy 1.26, which this replaced, so the warnings' figures did
    not move in their last bits.
    """
    np.subtract(positions[1:, 0], positions[:-1, 0], out=out)
    np.multiply(out, out, out=out)
    for axis in (2, 1):
        np.subtract(positions[1:, axis], positions[:-1, axis], out=term)
        out += np.multiply(term, term, out=term)
    return np.sqrt(out, out=out)


def _ink_lengths(strokes, work):
    """:func:`ink_lengths` with the work buffers ``work`` (_Work)."""
    positions, offsets = strokes.positions, strokes.offsets
    count = len(offsets) - 1
    if len(positions) < 2:
        return np.zeros(count)
    # Edge i joins points i and i + 1; summed stroke by stroke with reduceat (a redo measures
    # every frame: a per-point owner array and a weighted bincount cost 5 times more).
    edges = _edge_lengths(positions, *work.get(len(positions) - 1))
    junction = offsets[1:-1] - 1  # from a stroke's last point to the next one's first
    edges[junction[(junction >= 0) & (junction < len(edges))]] = 0.0
    # Strokes with an edge start before the last point; what lies between one's end and the
    # next one's start (junctions, one-point strokes) is zero.
    lengths = np.zeros(count)
    inked = strokes.sizes >= 2
    if inked.any():
        lengths[inked] = np.add.reduceat(edges, offsets[:-1][inked])
    closing = strokes.cyclic & (strokes.sizes > 2)
    first, last = offsets[:-1][closing], offsets[1:][closing] - 1
    lengths[closing] += np.linalg.norm(positions[last] - positions[first], axis=1)
    return lengths


def length_deviation(key_a, key_b, result, times, key_lengths=None):
    """How far each stroke pair's in-betweens are from the keys' blend of ink lengths.

    Parameters
    ----------
    key_a, key_b : StrokeSet
        The keys the in-betweens were made from.
    result : InbetweenResult
        Their in-betweens: ``frames`` (one per time; each stroke's ``origin`` names its key
        strokes) and ``pairs`` (P of them).
    times : array_like, shape (T,)
        The morph time of each frame (clamped to [0, 1], as the morph clamps it).
    key_lengths : tuple of ndarray, optional
        The keys' :func:`ink_lengths`, when known (a redo of the same keys measures them once).

    Returns
    -------
    ndarray, shape (P, T)
        ``L / ((1 - t) L_a + t L_b) - 1`` for pair ``p`` at frame ``t``, ``L`` the ink length of
        the pair's in-between stroke (0.2: 20% longer than the blend); 0 where the blend and
        ``L`` are both 0, inf where only the blend is; NaN for a stroke without a partner (or a
        pair missing from a frame).

    Examples
    --------
    >>> import ballmorph_core as bm
    >>> a = bm.StrokeSet.from_strokes([[[0, 0], [1, 0]]])
    >>> b = bm.StrokeSet.from_strokes([[[0, 1], [3, 1]]])
    >>> result = bm.inbetween(a, b, [0.5], method="linear-interpolation")
    >>> length_deviation(a, b, result, [0.5]).round(6).tolist()  # 2 long, as the blend of 1 and 3
    [[0.0]]
    """
    times = np.clip(np.asarray(times, dtype=np.float64).reshape(-1), 0.0, 1.0)
    out = np.full((len(result.pairs), len(times)), np.nan)
    work = _Work()
    if key_lengths is None:
        key_lengths = _ink_lengths(key_a, work), _ink_lengths(key_b, work)
    length_a, length_b = key_lengths
    rows = [p for p, pair in enumerate(result.pairs) if pair.stroke_a is not None and pair.stroke_b is not None]
    if not rows:
        return out
    # A pair is found in each frame by its key strokes (a, b), coded as one number.
    width = len(length_b) + 1
    codes = np.array([result.pairs[p].stroke_a * width + result.pairs[p].stroke_b for p in rows], dtype=np.int64)
    order = np.argsort(codes)
    codes, rows = codes[order], np.asarray(rows)[order]
    for ti, (t, frame) in enumerate(zip(times, result.frames)):
        a, b = frame.origin[:, 0], frame.origin[:, 1]
        code = np.where((a >= 0) & (b >= 0), a * width + b, -1)
        at = np.minimum(np.searchsorted(codes, code), len(codes) - 1)
        found = codes[at] == code
        lengths = _ink_lengths(frame, work)[found]
        a, b = a[found], b[found]
        blend = (1 - t) * length_a[a] + t * length_b[b]
        with np.errstate(divide="ignore", invalid="ignore"):
            off = np.where(blend > 0, lengths / blend - 1, np.where(lengths == 0, 0.0, np.inf))
        out[rows[at[found]], ti] = off
    return out
