"""A line redrawn in pieces: one stroke of a key matched to two or three of the other.

The animator drew a line whole in one key and in two strokes along it in the other (or the
other way round). The matching pairs the whole line with one piece and leaves the others
without a partner, which would pop. Here the pieces that lie end to end (small gaps) along the
whole stroke are *joined* into one stroke, the gaps bridged by straight segments, and morphed
with the whole one as any pair; each in-between is then cut at the gaps, which open from
nothing to their size as the morph goes (or close, from two pieces to one), so the ink length
follows the keys' blend and nothing pops.

A held stroke joins a pair's stroke of its own key when an end of each lies within ``GAP`` of
the whole stroke's length of the other, the joined length is within ``LENGTHS`` of the whole
one's, its shape agrees with the whole one's (``sqrt(e) <= tolerances.SHAPES_AGREE``) and its
length is nearer the whole one's than the pieces' before (``|log(length / whole length)|``;
between lengths as near, within ``EQUAL_LENGTHS``, the better shape). The length decides, not
the shape: a line that bends between the keys is, in part, more like its less bent whole.

Pieces re-stroked with an overlap (the next piece starts back along the one before, as animators
re-stroke) are joined without going back: the stroke before is cut where the next one starts,
and its span along the joined stroke reaches to where it ended on the next. Its gap is then
negative: the in-betweens' pieces overlap by the keys' overlap times the morph's time, so the
ink follows the keys' blend.
"""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...geometry.polyline import curve_length, resample
from ..strokes import StrokeSet

__all__ = ["GAP", "LENGTHS", "Joined", "join_pieces", "cut_frame"]

#: Largest gap between pieces, as a fraction of the whole stroke's length.
GAP = 0.15
#: The joined pieces' length over the whole stroke's: within these.
LENGTHS = (0.6, 1.6)
#: Joined lengths whose ``|log(length / whole length)|`` differ by less than this are as near.
EQUAL_LENGTHS = 0.02
#: Pieces a whole stroke may be redrawn in.
MAX_PIECES = 3
#: Samples of the shape comparison.
_SAMPLES = 32


@dataclass
class Joined:
    """Pieces of one key joined into one stroke for a pair.

    Attributes
    ----------
    pair : int
        The pair (index into the plan's strokes).
    side : str
        ``'a'`` (the first key was drawn in pieces: gaps close) or ``'b'`` (gaps open).
    strokes : list of int
        The pieces' stroke indices in their key, in order along the joined stroke.
    spans : list of (float, float)
        Each piece's fraction range along the joined stroke.
    flipped : list of bool
        Whether each piece runs backwards in the joined stroke.
    """

    pair: int
    side: str
    strokes: list
    spans: list
    flipped: list

    def gaps(self):
        """The bridges' fraction ranges along the joined stroke."""
        return [(self.spans[i][1], self.spans[i + 1][0]) for i in range(len(self.spans) - 1)]

    def sources(self, u):
        """Each joined fraction's piece (stroke index) and fraction along it as drawn, shape (K,) each.

        A fraction on a bridge belongs to the nearer piece's end.
        """
        u = np.asarray(u, dtype=np.float64)
        starts = np.array([a for a, _ in self.spans])
        ends = np.array([b for _, b in self.spans])
        piece = np.clip(np.searchsorted(starts, u, side="right") - 1, 0, len(starts) - 1)
        # On a bridge (past a piece's end): the nearer of that end and the next piece's start.
        past = u > ends[piece]
        nxt = np.minimum(piece + 1, len(starts) - 1)
        piece = np.where(past & (u - ends[piece] > starts[nxt] - u), nxt, piece)
        local = np.clip((u - starts[piece]) / np.maximum(ends[piece] - starts[piece], tol.TINY), 0.0, 1.0)
        local = np.where(np.array(self.flipped)[piece], 1.0 - local, local)
        return np.array(self.strokes)[piece], local


def _shape_residual(p, q):
    """Normalised similarity residual of two strokes' uniform samples, best direction (float)."""
    a, b = (resample(c, False, count=_SAMPLES, smooth=False) for c in (p, q))
    za, zb = (z[:, 0] + 1j * z[:, 1] for z in (a, b))
    za, zb = za - za.mean(), zb - zb.mean()
    norm = max(float(np.vdot(za, za).real * np.vdot(zb, zb).real), tol.TINY)
    return 1.0 - max(abs(np.vdot(za, zb)) ** 2, abs(np.vdot(za, zb[::-1])) ** 2) / norm


def _fit_cost(whole, xy, length):
    """How well ``xy`` stands for the ``whole`` stroke (of ``length``): ``(length term, shape
    term)``, compared in that order (see the module notes); the length term is inf where the
    shapes do not agree."""
    ratio = max(curve_length(xy, False), tol.TINY) / max(length, tol.TINY)
    shape = float(np.sqrt(max(_shape_residual(whole, xy), 0.0)))
    return (abs(np.log(ratio)) if shape <= tol.SHAPES_AGREE else np.inf), shape


def _better(cost, than):
    """Whether :func:`_fit_cost` ``cost`` beats ``than`` (bool)."""
    if abs(cost[0] - than[0]) <= EQUAL_LENGTHS or not np.isfinite(cost[0]):
        return cost[1] < than[1]
    return cost[0] < than[0]


def _arc(xy):
    """Cumulative arc length of a polyline's points, shape (n,)."""
    return np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))]


def _projection(xy, point):
    """Arc length along polyline ``xy`` (shape (n, 2)) of its point nearest ``point``, and the
    distance to it: (float, float)."""
    if len(xy) < 2:
        return 0.0, float(np.linalg.norm(point - xy[0]))
    a, d = xy[:-1], np.diff(xy, axis=0)
    f = np.clip(np.einsum("ij,ij->i", point - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), tol.TINY), 0.0, 1.0)
    gaps = np.linalg.norm(a + f[:, None] * d - point, axis=1)
    k = int(np.argmin(gaps))
    return float(_arc(xy)[k] + f[k] * np.linalg.norm(d[k])), float(gaps[k])


def _cut_at(xy, s):
    """Polyline ``xy`` up to arc length ``s`` (its point there added), shape (m, 2)."""
    arc = _arc(xy)
    k = int(np.searchsorted(arc, s, side="right"))
    if k >= len(xy):
        return xy
    f = (s - arc[k - 1]) / max(arc[k] - arc[k - 1], tol.TINY)
    return np.r_[xy[:k], [xy[k - 1] + f * (xy[k] - xy[k - 1])]]


def _joined(parts):
    """Pieces ``(xy, flipped)`` joined in order: the joined polyline (shape (n, 2)) and each
    piece's span along it in arc length, list of (float, float).

    A piece starting back along the joined stroke (an overlap: its start lies on the stroke
    before, nearer it than to its end) cuts the stroke there, and the piece before spans up to
    where it ended along the new one; else a bridge (the segment between them) joins them."""
    joined, spans = None, []
    for xy, flip in parts:
        xy = xy[::-1] if flip else xy
        if joined is None:
            joined, spans = xy, [(0.0, float(_arc(xy)[-1]))]
            continue
        along, off = _projection(joined, xy[0])
        total = float(_arc(joined)[-1])
        if along < total and off < np.linalg.norm(joined[-1] - xy[0]):
            # An overlap: the piece before ends where its end lies along this one.
            reach, _ = _projection(xy, joined[-1])
            joined = _cut_at(joined, along)
            spans[-1] = (spans[-1][0], along + reach)
            start = along
        else:
            start = total + float(np.linalg.norm(joined[-1] - xy[0]))
        spans.append((start, start + float(_arc(xy)[-1])))
        joined = np.r_[joined, xy]
    return joined, spans


def _joined_xy(parts):
    """Pieces ``(xy, flipped)`` joined (see :func:`_joined`), shape (n, 2)."""
    return _joined(parts)[0]


def _best_join(whole, pieces):
    """The order and directions joining ``pieces`` (list of (index, xy)) with the smallest gaps:
    ``(indices, flips, gap)``, trying the two ends of each new piece against the joined ends."""
    (first, xy0), rest = pieces[0], list(pieces[1:])
    order, flips, joined, widest = [first], [False], xy0, 0.0
    for index, xy in rest:
        options = [
            (np.linalg.norm(joined[-1] - xy[0]), "end", False),
            (np.linalg.norm(joined[-1] - xy[-1]), "end", True),
            (np.linalg.norm(joined[0] - xy[-1]), "start", False),
            (np.linalg.norm(joined[0] - xy[0]), "start", True),
        ]
        gap, where, flip = min(options, key=lambda o: o[0])
        piece = xy[::-1] if flip else xy
        if where == "end":
            order, flips, joined = [*order, index], [*flips, flip], np.r_[joined, piece]
        else:
            order, flips, joined = [index, *order], [flip, *flips], np.r_[piece, joined]
        widest = max(widest, gap)
    return order, flips, widest


def join_pieces(pairs, held, ka, kb):
    """Join the strokes without a partner that are pieces of a paired stroke's line.

    Parameters
    ----------
    pairs : list of (int, int, bool)
        The matching's pairs ``(i, j, flip)``.
    held : list of (int, bool)
        Strokes without a partner: ``(index, from_a)``.
    ka, kb : ProjectedKey

    Returns
    -------
    joined : dict of int to list of int
        Per pair: the held strokes of the same key joined to its stroke (in no order).
    side : dict of int to str
        Per joined pair: ``'a'`` or ``'b'``, the key drawn in pieces.
    """
    joined, side = {}, {}
    free = list(held)
    for k, (i, j, _) in enumerate(pairs):
        for from_a, key, mine, other in ((False, kb, j, (ka, i)), (True, ka, i, (kb, j))):
            if not free or key.rg.closed[mine] or other[0].rg.closed[other[1]]:
                continue
            whole = other[0].rg.curve(other[1])
            length = curve_length(whole, False)
            pieces = [(mine, key.rg.curve(mine))]
            base = _fit_cost(whole, pieces[0][1], length)
            for index, side_a in list(free):
                if side_a != from_a or key.rg.closed[index] or len(pieces) >= MAX_PIECES or index == mine:
                    continue
                trial = [*pieces, (index, key.rg.curve(index))]
                order, flips, gap = _best_join(whole, trial)
                xy = _joined_xy([(dict(trial)[o], f) for o, f in zip(order, flips)])
                ratio = curve_length(xy, False) / max(length, tol.TINY)
                if gap <= GAP * length and LENGTHS[0] <= ratio <= LENGTHS[1]:
                    fit = _fit_cost(whole, xy, length)
                    if _better(fit, base):
                        pieces, base = trial, fit
                        free.remove((index, side_a))
            if len(pieces) > 1:
                joined[k] = [index for index, _ in pieces[1:]]
                side[k] = "a" if from_a else "b"
    return joined, side


def joined_stroke(key, first, extra):
    """The KeyStroke-like ``(xy, u, order, flips, spans)`` of stroke ``first`` and ``extra`` joined."""
    trial = [(first, key.rg.curve(first)), *[(e, key.rg.curve(e)) for e in extra]]
    order, flips, _ = _best_join(None, trial)
    parts = [(dict(trial)[o], f) for o, f in zip(order, flips)]
    xy, arcs = _joined(parts)
    s = _arc(xy)
    total = max(s[-1], tol.TINY)
    u = s / total
    spans = [(float(a / total), float(b / total)) for a, b in arcs]
    return xy, u, order, flips, spans


def _interpolated(values, x):
    """Per-point values at fractional point indices ``x`` (floats linearly, others nearest)."""
    lo = np.clip(np.floor(x).astype(np.int64), 0, len(values) - 1)
    hi = np.minimum(lo + 1, len(values) - 1)
    if not np.issubdtype(values.dtype, np.floating):
        return values[np.where(x - lo >= 0.5, hi, lo)]
    f = (x - lo).reshape(-1, *([1] * (values.ndim - 1)))
    return values[lo] + f * (values[hi] - values[lo])


def cut_frame(frame, windows):
    """An in-between with stretches of its strokes removed, each stroke cut there (StrokeSet).

    Parameters
    ----------
    frame : StrokeSet
    windows : dict of int to list of (float, float)
        Per stroke of ``frame``: stretches ``(lo, hi)`` in fractional point indices along it
        (``2.5`` is halfway between its points 2 and 3) to leave out. The pieces end exactly at
        ``lo`` and start at ``hi``, their attributes interpolated there; an empty stretch
        (``hi == lo``) cuts nothing, a reversed one (``hi < lo``, pieces re-stroked with an
        overlap) cuts the stroke into pieces that overlap there.
    """
    windows = {s: [(lo, hi) for lo, hi in w if hi != lo] for s, w in windows.items()}
    if not any(windows.values()):
        return frame
    rows, sizes, stroke_of = [], [], []
    for s in range(len(frame)):
        first, n = int(frame.offsets[s]), int(frame.offsets[s + 1] - frame.offsets[s])
        begin = 0.0
        bounds = [*sorted(windows.get(s, [])), (float(n - 1), float(n - 1) + 1.0)]
        for lo, hi in bounds:
            lo = min(lo, n - 1.0)
            inner = np.arange(np.floor(begin) + 1, np.ceil(lo)) if lo > begin else np.zeros(0)
            x = np.r_[begin, inner, lo] if lo > begin else np.zeros(0)
            if len(x) >= 2:
                rows.append(first + x), sizes.append(len(x)), stroke_of.append(s)
            begin = hi if hi < lo else max(begin, hi)
    x = np.concatenate(rows)
    stroke_of = np.array(stroke_of, dtype=np.int64)
    cut = np.array([bool(windows.get(int(s))) for s in stroke_of], dtype=bool)
    return StrokeSet(
        positions=_interpolated(frame.positions, x),
        offsets=np.r_[0, np.cumsum(sizes)],
        cyclic=frame.cyclic[stroke_of] & ~cut,
        material_index=frame.material_index[stroke_of],
        radius=_interpolated(frame.radius, x),
        opacity=_interpolated(frame.opacity, x),
        vertex_color=_interpolated(frame.vertex_color, x),
        selected=frame.selected[stroke_of],
        origin=frame.origin[stroke_of],
        point_attributes={name: _interpolated(v, x) for name, v in frame.point_attributes.items()},
        curve_attributes={name: v[stroke_of] for name, v in frame.curve_attributes.items()},
        attribute_types=frame.attribute_types,
    )
