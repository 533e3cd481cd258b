"""Tangent-aligned correspondence: the two curves' tangent directions matched along arc length.

A shape that changes where it lies (a glyph's outline growing bolder, a blob squashed in place)
keeps the *directions* of its parts: the top of an 'o' stays horizontal, a stem stays vertical,
however far its points move. Matching each piece of P to the piece of Q that runs the same way
is the correspondence a designer's masters have (Arkin et al. 1991's turning function, with the
keys left in place: absolute directions, no angle offset).

The match is a monotone warp of two sequences of ``K`` edges of uniform arc-length samples
(dynamic time warping, Sebastian, Klein & Kimia 2003): each step advances along P, along Q or
both; a cell costs ``1 - cos`` of the angle between the two edges' directions plus
``position`` times their squared distance (in units of the pair's size: it only tells apart
parts that run the same way); a step along one curve only pays ``stretch`` (uneven arc length
is allowed where the directions demand it, not for free). Loops also choose the start on Q that
P's first edge goes to: every start would cost ``K`` warps, so every start is warped on a coarse
table of ``COARSE_SAMPLES`` edges first, then the fine starts within one coarse cell of the best,
side by side in one table.

The warps run along anti-diagonals (every cell of one depends only on the two before it), for
all candidates of all pairs at once: numpy work of ``2K`` steps whatever the batch.
"""

import numpy as np

from .. import tolerances as tol
from ..geometry.ragged import Ragged

__all__ = [
    "TURNING_SAMPLES",
    "MIN_SAMPLES",
    "STRETCH",
    "POSITION",
    "COARSE_SAMPLES",
    "TangentWarp",
    "tangent_warps",
    "tangent_warp",
]

#: Edges per curve of the warp at most (its cost grows with their square); by default a pair
#: takes as many as its denser curve has points, at least ``MIN_SAMPLES``. At 128 a glyph
#: contour of 300 points was matched a cell of 1/128 of its outline off at corners: 12 glyphs
#: of Inter / Dosis, median Hausdorff 17.91 / 3.15 at 128, 14.57 / 2.42 at 256 (1/1000 em).
TURNING_SAMPLES = 256
MIN_SAMPLES = 128

#: Cost of a step along one curve only (the cell costs at most 2 + position terms): about a
#: quarter-turn's mismatch, so a part may stretch along the other where that aligns directions.
STRETCH = 0.5

#: Weight of the squared distance of matched edges (in units of the pair's RMS size), which
#: tells apart the parts running the same way (the two horizontal arms of an 'E'). Light: a
#: dot squashed from tall to wide moves its corners far, and 0.5 pulled its matches off them
#: (5-8 % of its size off the proportional in-between; 0.3 % at 0.1).
POSITION = 0.1

#: Knots of :meth:`TangentWarp.through` closer than this fraction of the denser curve's mean
#: spacing (along the warp) are merged.
KNOT_GAP = 0.85

#: Cells of warp tables made at a time (pairs are warped in groups within it): 32 MiB of costs.
TABLE_CELLS = 1 << 22

#: Cells of a table costed at a time (its temporaries stay in the cache): 512 KiB of costs.
BLOCK_CELLS = 1 << 16

#: Edges per curve of the coarse warps that choose a loop's start among all of them: the fine
#: warps then try the starts within one coarse cell of the best.
COARSE_SAMPLES = 32


class TangentWarp:
    """One pair's tangent-aligned correspondence.

    Attributes
    ----------
    u_p, u_q : ndarray, shape (L,)
        Matched arc-length fractions along P and Q, both non-decreasing from the start;
        ``u_q`` counts from Q's matched start (fraction ``start``) for loops: the point of Q is
        at fraction ``(start + u_q) % 1``.
    start : float
        Loops: the fraction along Q that P's first point goes to (0 for open strokes).
    cost : float
        The warp's mean cell cost (0 when the curves run the same way everywhere).
    """

    def __init__(self, u_p, u_q, start, cost):
        self.u_p, self.u_q, self.start, self.cost = u_p, u_q, float(start), float(cost)

    def through(self, vp, vq):
        """Matched fractions through both curves' own vertices: each vertex of P (fractions
        ``vp``) with its match on Q, and each vertex of Q (``vq``, from Q's first point) with
        its match on P, in order along the warp; the keys' corners stay corners.

        Parameters
        ----------
        vp, vq : ndarray, shape (N,), (M,)
            Arc-length fractions of the curves' vertices, in [0, 1).

        Returns
        -------
        u_p, u_q : ndarray, shape (L,)
            ``u_p`` non-decreasing in [0, 1], ``u_q`` fractions along Q from its first point;
            the last knot is the warp's end (a loop's first again). Knots closer along the
            warp than ``KNOT_GAP`` of the denser curve's mean spacing are merged: the
            in-between has about as many points as the denser key (matched vertices of
            point-compatible keys coincide), at most ``1 / KNOT_GAP`` times as many.
        """
        tq = (np.asarray(vq, dtype=np.float64) - self.start) % 1.0
        # A warp may wait on one curve (a flat step): the walk along both orders every knot.
        walk = self.u_p + self.u_q
        at_p = np.interp(vp, self.u_p, walk)
        at_q = np.interp(tq, self.u_q, walk)
        w = _thinned(np.unique(np.r_[at_p, at_q, walk[-1]]), walk[-1] / max(len(vp), len(vq), 1))
        u_p, t_q = np.interp(w, walk, self.u_p), np.interp(w, walk, self.u_q)
        # From Q's first point (an open stroke's start is 0: its end stays at 1).
        return u_p, (self.start + t_q) % 1.0 if self.start else t_q


def _thinned(w, spacing):
    """The knots ``w`` (sorted, shape (L,)) with any closer than ``KNOT_GAP * spacing`` to the
    last kept one dropped; the first and last kept."""
    keep = np.zeros(len(w), dtype=bool)
    last = -np.inf
    gap = KNOT_GAP * spacing
    for i, x in enumerate(w):
        if x - last >= gap:
            keep[i], last = True, x
    keep[-1] = True
    if len(w) > 1 and keep[-2] and w[-1] - w[-2] < gap:
        keep[-2] = False
    return w[keep]


def _edges(rg, k, closed):
    """Uniform samples of every curve of ``rg`` (batch of B) and their edges' unit directions
    and midpoints: ``k`` edges per curve (a loop's ``k`` samples close up, an open curve has
    ``k + 1``). Returns (directions (B, k, 2), midpoints (B, k, 2))."""
    counts = np.full(len(rg), k if closed else k + 1)
    pts = rg.resample(counts, smooth=False).pts.reshape(len(rg), -1, 2)
    nxt = np.roll(pts, -1, axis=1) if closed else pts[:, 1:]
    pts = pts if closed else pts[:, :-1]
    d = nxt - pts
    n = np.linalg.norm(d, axis=2, keepdims=True)
    return d / np.maximum(n, tol.TINY), (pts + nxt) / 2


def _diagonal(d, k):
    """The rows ``lo .. hi`` of anti-diagonal ``d`` of a ``k x k`` table: its cells (i, d - i) on the table."""
    return max(0, d - k + 1), min(d, k - 1)


def _sweep(cost_of, shape, k, stretch):
    """Least total cost of monotone warps through ``k x k`` cells from (0, 0) to (k-1, k-1).

    ``cost_of(d, lo, hi)`` gives the cells (i, d - i) of anti-diagonal ``d``, i from ``lo`` to
    ``hi`` (those on the table), shape ``shape + (hi - lo + 1,)``. A diagonal step counts its
    cell twice (a diagonal walk costs what two single steps cost); a single step pays
    ``stretch`` more. Returns the totals at the far corner, shape ``shape``.

    Only the cells on the table are swept (half the square of cells an anti-diagonal of the
    square spans), and a single step's cheaper source is taken before its cost is added:
    rounding is monotone, so ``min(a, b) + c + stretch`` is ``min(a + c + stretch, b + c +
    stretch)`` bit for bit. A few numpy calls a diagonal: their count, not the cells, is the
    cost of a small batch.
    """
    # Anti-diagonals d - 2 and d - 1, cell i at index i + 1 (index 0: before the table, inf
    # but at the corner before the start). Cells off the table are never written: inf.
    before = np.full(shape + (k + 1,), np.inf)
    last = before.copy()
    before[..., 0] = 0.0
    for d in range(2 * k - 1):
        lo, hi = _diagonal(d, k)
        c = cost_of(d, lo, hi)
        both = c * 2.0
        both += before[..., lo : hi + 1]
        along = np.minimum(last[..., lo : hi + 1], last[..., lo + 1 : hi + 2])
        along += c
        along += stretch
        before, last = last, before
        np.minimum(both, along, out=last[..., lo + 1 : hi + 2])
        if d == 0:
            last[..., 0] = np.inf
    return last[..., k]


def _recorded_sweep(cost_of, count, k, stretch):
    """:func:`_sweep` of ``count`` warps (``cost_of`` shape (count, 1, n)) that also records the
    steps taken into every cell (0 both, 1 along P, 2 along Q; the first of these that is
    least), shape (2k - 1, count, k) (cells off the table left 0): the totals (count,) and the
    steps."""
    before = np.full((count, k + 1), np.inf)
    last = before.copy()
    before[:, 0] = 0.0
    steps = np.zeros((2 * k - 1, count, k), dtype=np.int8)
    for d in range(2 * k - 1):
        lo, hi = _diagonal(d, k)
        c = cost_of(d, lo, hi)[:, 0]
        both = before[:, lo : hi + 1] + 2.0 * c
        along_p = last[:, lo : hi + 1] + c + stretch
        along_q = last[:, lo + 1 : hi + 2] + c + stretch
        low = np.minimum(np.minimum(both, along_p), along_q)
        steps[d, :, lo : hi + 1] = np.where(both == low, 0, np.where(along_p == low, 1, 2))
        before, last = last, before
        last[:, lo + 1 : hi + 2] = low
        if d == 0:
            last[:, 0] = np.inf
    return last[:, k], steps


def _cell_costs(p, q, size, position, out=None):
    """Cost of cells: tangent mismatch plus position, broadcast (into ``out`` if given).

    Parameters
    ----------
    p, q : tuple of 4 ndarray
        Direction (x, y) and midpoint (x, y) of the cells' edges of P and of Q, arrays
        broadcasting to the cells' shape (leading axis B, one per pair).
    size : ndarray, shape (B,)
    position : float
    out : ndarray, optional
        Of the cells' shape.

    The very operations of ``1 - einsum('bid,bjd->bij', tp, tq) + position * sum((mp_i -
    mq_j)^2, axis=-1) / size^2``, coordinate by coordinate: the same costs bit for bit, without
    temporaries of two coordinates a cell.
    """
    out = np.multiply(p[0], q[0], out=out)
    out += p[1] * q[1]
    np.subtract(1.0, out, out=out)
    if position <= 0.0:
        return out
    gap = p[2] - q[2]
    dy = p[3] - q[3]
    np.square(gap, out=gap)
    np.square(dy, out=dy)
    gap += dy
    gap *= position
    gap /= np.square(size).reshape((-1,) + (1,) * (gap.ndim - 1))
    out += gap
    return out


def tangent_warps(ps, qs, closed, samples=None, stretch=STRETCH, position=POSITION):
    """Tangent-aligned correspondences of a batch of curve pairs (see the module docstring).

    Parameters
    ----------
    ps, qs : list of ndarray
        B pairs of curves, ``ps[b]`` shape (N_b, 2), ``qs[b]`` shape (M_b, 2), Q running the
        way P does; at least two distinct points each.
    closed : array_like of bool, shape (B,)
        Loops (a start on Q is chosen) or open strokes (ends to ends).
    samples : int, optional
        Edges per curve of the warp (at least 3); default: each pair's own (the denser
        curve's point count, within ``MIN_SAMPLES .. TURNING_SAMPLES``).
    stretch, position : float
        See :data:`STRETCH`, :data:`POSITION`.

    Returns
    -------
    list of TangentWarp
    """
    closed = np.asarray(closed, dtype=bool).reshape(-1)
    out = [None] * len(ps)
    for loop in (False, True):
        rows = np.flatnonzero(closed == loop)
        if not len(rows):
            continue
        ks = np.array([_edge_count(len(ps[b]), len(qs[b]), samples) for b in rows])
        for k in np.unique(ks):
            group = rows[ks == k]
            rp = Ragged.from_list([np.asarray(ps[b], dtype=np.float64) for b in group], [loop] * len(group))
            rq = Ragged.from_list([np.asarray(qs[b], dtype=np.float64) for b in group], [loop] * len(group))
            for b, warp in zip(group, _warps(rp, rq, loop, int(k), stretch, position)):
                out[b] = warp
    return out


def _edge_count(n, m, samples):
    """Edges per curve of one pair's warp: ``samples`` if given, else the denser curve's point
    count rounded up to a multiple of ``COARSE_SAMPLES``, within ``MIN_SAMPLES ..
    TURNING_SAMPLES`` (a pair's own: the same alone as in any batch)."""
    if samples is not None:
        return max(int(samples), 3)
    step = COARSE_SAMPLES
    return int(np.clip(-(-max(n, m) // step) * step, MIN_SAMPLES, TURNING_SAMPLES))


def tangent_warp(P, Q, closed, **options):
    """:func:`tangent_warps` of one pair (TangentWarp)."""
    return tangent_warps([P], [Q], [closed], **options)[0]


def _warps(rp, rq, loop, k, stretch, position):
    """The warps of pairs of one kind (all loops or all open strokes), list of TangentWarp.

    A loop's start is chosen on tables of at most ``MIN_SAMPLES`` edges (the candidates cost a
    warp each), its warp then made on ``k``: the finer table places corners, not the start.
    """
    b_count = len(rp)
    if not loop:
        return _best_warps(rp, rq, k, np.zeros(b_count, dtype=np.int64), 1, stretch, position, loop)
    level = min(k, MIN_SAMPLES)
    first, count = _start_candidates(rp, rq, level, stretch, position)
    if level < k:
        best = _best_starts(_pair_edges(rp, rq, level, True), first, count, stretch, position)
        first, count = np.rint(best * (k / level)).astype(np.int64) % k, 1
    return _best_warps(rp, rq, k, first, count, stretch, position, loop)


def _start_candidates(rp, rq, k, stretch, position):
    """The starts worth a warp on tables of ``k`` edges: ``count`` consecutive ones from
    ``first`` (B,) on, every one of a small table, else those within a coarse cell of the best
    start on ``COARSE_SAMPLES`` edges."""
    b_count = len(rp)
    if k <= COARSE_SAMPLES:
        return np.zeros(b_count, dtype=np.int64), k
    edges = _pair_edges(rp, rq, COARSE_SAMPLES, True)
    coarse = _best_starts(edges, np.zeros(b_count, dtype=np.int64), COARSE_SAMPLES, stretch, position)
    ratio = k / COARSE_SAMPLES
    reach = int(np.ceil(ratio))
    return (np.rint(coarse * ratio).astype(np.int64) - reach) % k, 2 * reach + 1


def _pair_edges(rp, rq, k, loop):
    """Both curves' edges on ``k`` of them (:func:`_edges`) and each pair's RMS size: (tp, mp,
    tq, mq, size), shapes (B, k, 2) and (B,)."""
    tp, mp = _edges(rp, k, loop)
    tq, mq = _edges(rq, k, loop)
    both = np.concatenate([mp, mq], axis=1)
    size = np.sqrt(np.mean(np.sum(np.square(both - both.mean(axis=1, keepdims=True)), axis=2), axis=1))
    return tp, mp, tq, mq, np.maximum(size, tol.TINY)


def _groups(edges, first, count):
    """The pairs in groups whose tables (:func:`_diagonal_costs`) hold at most ``TABLE_CELLS``
    cells: (edges, first) of each group."""
    b_count, k = edges[0].shape[:2]
    size = max(1, TABLE_CELLS // ((2 * k + count - 2) * k))
    for g in range(0, b_count, size):
        yield tuple(a[g : g + size] for a in edges), first[g : g + size]


def _diagonal_costs(edges, first, count, position):
    """``cost_of(d, lo, hi)`` for :func:`_sweep` of ``count`` starts a pair, consecutive from
    ``first`` (B,) on: the cells (i, d - i) of every start's table, i from lo to hi, shape
    (B, count, hi - lo + 1).

    One table a pair laid out by anti-diagonals: row ``e`` holds P's edge i against Q's edge
    ``first + e - i`` (cyclically), the cell (i, d - i) of the warp from start ``first + s``
    in row ``d + s``; so every start's anti-diagonal d is a contiguous slice of the table (no
    gather per diagonal), and the table is made in one go (Q's edges read as a view running
    backwards along i).
    """
    tp, mp, tq, mq, size = edges
    b_count, k = tp.shape[:2]
    rows = 2 * k + count - 2
    # Q's edges backwards from first + rows - 1: row e, column i reads edge rows - 1 - e + i
    # of these (the inner loops run forwards along i).
    span = rows + k - 1
    at = (first[:, None] + (rows - 1) - np.arange(span)) % k

    def skewed(a):
        laid = np.take_along_axis(a, at, axis=1)  # (B, span), contiguous
        step = laid.itemsize
        return np.lib.stride_tricks.as_strided(
            laid[:, rows - 1 :], shape=(b_count, rows, k), strides=(span * step, -step, step), writeable=False
        )

    q = tuple(skewed(a[:, :, x]) for a in (tq, mq) for x in (0, 1))
    p = tuple(np.ascontiguousarray(a[:, :, x])[:, None, :] for a in (tp, mp) for x in (0, 1))

    def p_of(lo, hi):
        return tuple(a[:, :, lo:hi] for a in p)

    table = np.empty((b_count, rows, k))
    # A few rows at a time (the temporaries stay in the cache), of each only the cells some
    # start's warp reads: row e's cells i from e - (k + count - 2) to e (the rest is never read).
    step = max(1, BLOCK_CELLS // (b_count * k))
    for e in range(0, rows, step):
        lo, hi = max(0, e - (k + count - 2)), min(k, e + step)
        cells = (slice(None), slice(e, e + step), slice(lo, hi))
        _cell_costs(p_of(lo, hi), tuple(a[cells] for a in q), size, position, out=table[cells])

    def cost_of(d, lo, hi):
        return table[:, d : d + count, lo : hi + 1]

    return cost_of


def _best_starts(edges, first, count, stretch, position):
    """Of ``count`` candidate starts from ``first`` (B,) on, each loop pair's least costly, shape
    (B,) (the first of equals)."""
    k = edges[0].shape[1]
    best = []
    for group, start in _groups(edges, first, count):
        totals = _sweep(_diagonal_costs(group, start, count, position), (len(start), count), k, stretch)
        best.append((start + np.argmin(totals, axis=1)) % k)
    return np.concatenate(best)


def _best_warps(rp, rq, k, first, count, stretch, position, loop):
    """The warps from the best of ``count`` candidate starts from ``first`` (B,) on, list of TangentWarp."""
    edges = _pair_edges(rp, rq, k, loop)
    best = _best_starts(edges, first, count, stretch, position) if count > 1 else first
    out = []
    for group, start in _groups(edges, best, 1):
        totals, steps = _recorded_sweep(_diagonal_costs(group, start, 1, position), len(start), k, stretch)
        for b in range(len(start)):
            i_path, j_path = _trace(steps[:, b], k)
            out.append(_warp_of(i_path, j_path, k, start[b] / k if loop else 0.0, totals[b], loop))
    return out


def _trace(steps, k):
    """The cells of one warp (i, j), shape (L,) each, from (0, 0) to (k-1, k-1)."""
    di, dj = (1, 1, 0), (1, 0, 1)
    i = j = k - 1
    path = [(i, j)]
    while i > 0 or j > 0:
        code = steps[i + j, i]
        i, j = i - di[code], j - dj[code]
        path.append((i, j))
    return np.array(path[::-1]).T


def _warp_of(i, j, k, start, total, loop):
    """The TangentWarp of a warp's cells: a cell (i, j) matches edge i of P to edge j of Q, so
    the map between fractions runs through the cells' far corners, from (0, 0)."""
    u_p = np.r_[0.0, (i + 1) / k]
    u_q = np.r_[0.0, (j + 1) / k]
    return TangentWarp(u_p, u_q, start, total / (2 * len(i)))
