"""Stroke descriptors for matching: each key's strokes cleaned and resampled to ``MATCH_SAMPLES``
points, centred, with their sizes and the drawings' dot spread (see :mod:`.matching`)."""

import numpy as np

from ... import tolerances as tol
from ...errors import InvalidCurveError
from ...geometry.polyline import as_curve, curve_length, resample
from ...geometry.ragged import Ragged, ragged_arange

__all__ = ["KeyDescriptors", "complex_samples", "dot_spread"]


#: Samples per stroke in the matching descriptor.
MATCH_SAMPLES = 32


#: Two dots have no size: their distance counts relative to this fraction of the drawings' size
#: (the floor of every pair's spread, so also of tiny strokes'). In a drawing of more than
#: ``DOT_SPREAD_STROKES`` strokes the fraction shrinks with one over the square root of the
#: count: the floor stays the strokes' spacing (the size over that root; 0.05 x 20 at 400).
#: Relative to the drawing's size only, each of a thousand hatch lines would reach hundreds of
#: candidates, a share of the drawing that stays put as the count grows (quadratic matching).
DOT_SPREAD = 0.05
DOT_SPREAD_STROKES = 400


def _clean(points, name, closed):
    """Distinct points of one stroke: shape (K, 2) with K >= 2, (1, 2) for a dot, None if empty.

    A loop with fewer than three distinct points is kept as the open polyline it is.
    """
    try:
        return as_curve(points, name, closed)
    except InvalidCurveError as exc:
        error = exc
    try:
        arr = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise error from None
    if arr.size == 0 and (arr.ndim == 1 or arr.shape[-1] == 2):
        return None
    if arr.ndim != 2 or arr.shape[1] != 2 or not np.all(np.isfinite(arr)):
        raise error
    if closed and len(arr) > 1:
        try:
            return as_curve(arr, name, False)
        except InvalidCurveError:
            pass
    return arr[:1].copy()  # every point coincides: a dot


class KeyDescriptors:
    """Matching descriptors of the strokes of one key.

    Attributes
    ----------
    loop : ndarray of bool, shape (S,)
        The cyclic flags as given.
    open : ndarray, shape (S, m, 2)
        Arc-length samples along each stroke's vertices, closing edge excluded (how a loop is
        morphed when its partner is open); a dot repeats its point.
    ring : ndarray, shape (S, m, 2)
        For loops, samples around the whole loop; for open strokes the same as ``open``.
    valid : ndarray of bool, shape (S,)
        False for strokes with no points.
    length : ndarray, shape (S,)
    diagonal : float
        Bounding-box diagonal of all the key's points (0 when none).
    """

    def __init__(self, strokes, closed, name, closed_name, m):
        strokes = strokes if isinstance(strokes, Ragged) else list(strokes)
        s = len(strokes)
        closed = np.asarray(closed, dtype=bool).reshape(-1)
        if len(closed) != s:
            raise InvalidCurveError(f"{closed_name}: expected one flag per stroke ({s}), got {len(closed)}")
        self.count = s
        self.loop = closed
        self.open = np.zeros((s, m, 2))
        self.ring = np.zeros((s, m, 2))
        self.valid = np.zeros(s, bool)
        self.length = np.zeros(s)
        if self._batched(strokes, closed, m):
            return
        if isinstance(strokes, Ragged):
            strokes = [strokes.curve(i) for i in range(s)]
        lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
        for i, points in enumerate(strokes):
            clean = _clean(points, f"{name}[{i}]", bool(closed[i]))
            if clean is None:
                continue
            self.valid[i] = True
            lo, hi = np.minimum(lo, clean.min(axis=0)), np.maximum(hi, clean.max(axis=0))
            if len(clean) == 1:
                self.open[i] = self.ring[i] = clean[0]
                continue
            self.open[i] = resample(clean, False, count=m, smooth=False)
            self.ring[i] = resample(clean, True, count=m, smooth=False) if closed[i] else self.open[i]
            self.length[i] = curve_length(clean, bool(closed[i]))
        self.diagonal = float(np.linalg.norm(hi - lo)) if self.valid.any() else 0.0

    def _batched(self, strokes, closed, m):
        """All descriptors at once for well-formed keys (finite points); False to go one by one."""
        given = strokes if isinstance(strokes, Ragged) else None
        flat = (given.pts, given.n, given.offsets) if given is not None else _flattened(strokes)
        if flat is None:
            return False  # the per-stroke route names the malformed stroke
        pts, sizes, offsets = flat
        if not np.all(np.isfinite(pts)):
            return False  # the per-stroke route names the bad stroke
        self.valid = sizes > 0
        if not self.valid.any():
            self.diagonal = 0.0
            return True
        # Column by column: a reduction along axis 0 of an (N, 2) array is ~25 times slower.
        x, y = pts[:, 0], pts[:, 1]
        self.diagonal = float(np.linalg.norm(np.array([x.max() - x.min(), y.max() - y.min()])))
        # A batch given read open is the one read open here (the same arithmetic on the same points).
        if given is not None and not given.closed.any():
            line = given
        else:
            line = Ragged(pts, offsets, np.zeros(len(sizes), dtype=bool))
        # Dots (one point, or all points the same) repeat their point.
        dot = self.valid & (line.length <= tol.COINCIDENT * max(self.diagonal, tol.TINY))
        first = pts[np.minimum(offsets[:-1], max(len(pts) - 1, 0))]
        self.open[dot] = self.ring[dot] = first[dot][:, None, :]
        keep = np.flatnonzero(self.valid & ~dot)
        if len(keep):
            # Usually every stroke is kept: then the batch read open is ``line`` itself, and
            # read as drawn it is the same again unless a stroke is a loop.
            if len(keep) == len(sizes):
                opened = line
            else:
                owner, local = ragged_arange(sizes[keep])
                sub = np.concatenate([[0], np.cumsum(sizes[keep])])
                opened = Ragged(pts[offsets[keep][owner] + local], sub, np.zeros(len(keep), dtype=bool))
            if not closed[keep].any():
                looped = opened
            elif opened is line and given is not None and np.array_equal(given.closed, closed):
                looped = given  # the batch given, read as drawn
            else:
                looped = Ragged(opened.pts, opened.offsets, closed[keep])
            self._read(keep, opened, looped, closed[keep], m)
        return True

    def _read(self, keep, opened, looped, closed, m):
        """The descriptors of strokes ``keep`` (shape (K,)) from their batch read open and as
        drawn (Ragged, the same one when no stroke is a loop: then the ring is the open read)."""
        self.open[keep] = opened.resample(np.full(len(keep), m), smooth=False).pts.reshape(-1, m, 2)
        if looped is opened:
            self.ring[keep] = self.open[keep]
        else:
            ring = looped.resample(np.full(len(keep), m), smooth=False).pts.reshape(-1, m, 2)
            self.ring[keep] = np.where(closed[:, None, None], ring, self.open[keep])
        self.length[keep] = looped.length

    def centroids(self):
        """Sample centroid of each stroke's own descriptor (ring for loops), shape (S, 2)."""
        return np.where(self.loop[:, None], self.ring.mean(axis=1), self.open.mean(axis=1))

    def sizes(self):
        """Each stroke's own size: RMS distance of its samples from their centroid, shape (S,)
        (exactly 0 for dots, whatever the round-off of their centroid)."""
        samples = np.where(self.loop[:, None, None], self.ring, self.open)
        rms = np.sqrt(np.mean(np.sum((samples - self.centroids()[:, None]) ** 2, axis=2), axis=1))
        return np.where(self.length > 0, rms, 0.0)

    def areas(self):
        """Signed area of each loop's samples (counter-clockwise positive; 0 for strokes), shape (S,)."""
        x, y = self.ring[..., 0], self.ring[..., 1]
        area = 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)
        return np.where(self.loop, area, 0.0)

    def _ink(self):
        """The stroke centroids with points and their weights, their lengths (the dots' equal
        where no stroke has ink): shapes (V, 2), (V,)."""
        ctr, w = self.centroids()[self.valid], self.length[self.valid]
        return ctr, (w if w.sum() > 0 else np.ones(len(ctr)))

    def ink_spread(self):
        """Weighted RMS distance of the stroke centroids from :meth:`ink_centroid`, weighted
        as there (float)."""
        ctr, w = self._ink()
        return float(np.sqrt(np.sum(w * np.sum((ctr - self.ink_centroid()) ** 2, axis=1)) / w.sum()))

    def ink_centroid(self):
        """Length-weighted mean of the stroke centroids, shape (2,) (dots weigh in if no ink)."""
        ctr, w = self._ink()
        return (w[:, None] * ctr).sum(axis=0) / w.sum()


def _flattened(strokes):
    """Points, sizes and offsets of a list of strokes, shapes (N, 2), (S,), (S + 1,); None when
    a stroke is not an array of 2D points."""
    try:
        arrays = [np.asarray(p, dtype=np.float64) for p in strokes]
    except (TypeError, ValueError):
        return None
    if any(a.ndim != 2 or a.shape[1] != 2 for a in arrays if a.size):
        return None
    arrays = [a.reshape(-1, 2) for a in arrays]
    sizes = np.array([len(a) for a in arrays], dtype=np.int64)
    pts = np.concatenate(arrays) if arrays else np.zeros((0, 2))
    return pts, sizes, np.concatenate([[0], np.cumsum(sizes)])


def complex_samples(samples):
    return samples[..., 0] + 1j * samples[..., 1]


def dot_spread(key_a, key_b):
    """The floor of every pair's spread (see ``DOT_SPREAD``): a float."""
    strokes = max(np.count_nonzero(key_a.valid), np.count_nonzero(key_b.valid), 1)
    spacing = min(1.0, np.sqrt(DOT_SPREAD_STROKES / strokes))
    return DOT_SPREAD * spacing * max(key_a.diagonal, key_b.diagonal, tol.TINY)
