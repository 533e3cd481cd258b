"""Where every pair's samples sit in a drawing's frames, and how they are evaluated.

The pipeline hands over the samples of every *chain* (a lens, an overlap, a whole pair): those
of the ball route as arrays of ball-map contacts ``(p, m, q)`` (:class:`BallRows`), evaluated
together as one :class:`~ballmorph_core.morphs.paths.BallPaths`, and the others as
:class:`Segment`\\ s holding a :class:`~ballmorph_core.morphs.base.Morph` (a fallback, a
comparison morph, straight point motion). Consecutive chains of a pair share an endpoint (a
crossing, the end of an overlap), kept once; the last chain of a loop cut into pieces ends where
the first starts.
"""

from dataclasses import dataclass, field

import numpy as np

from ... import tolerances as tol
from ...geometry.ragged import ragged_arange
from ...morphs.base import PathMorph, morph_time
from ...morphs.paths import BallPaths, LinearPaths

__all__ = ["BallRows", "Segment", "PairFrames", "Layout"]


@dataclass
class BallRows:
    """The ball route's chains as arrays, chain after chain.

    Attributes
    ----------
    pair, order : ndarray of int, shape (H,)
        Each chain's pair and position along it.
    sizes : ndarray of int, shape (H,)
        Samples per chain.
    range_p, range_q : ndarray, shape (H, 2)
        Arc-length start and end of each chain's pieces on its pair's curves.
    static : ndarray of bool, shape (H,)
        Overlaps (their contacts are the piece's own points).
    u_p, u_q : ndarray, shape (K,)
        Each sample's fraction along its chain's pieces of P and Q (as given).
    p, m, q : ndarray, shape (K, 2)
        Contacts and disk centres.
    offset : ndarray, shape (K, 2)
        Added as ``(1 - t)`` times this to each sample (the end gaps of open strokes).
    """

    pair: np.ndarray
    order: np.ndarray
    sizes: np.ndarray
    range_p: np.ndarray
    range_q: np.ndarray
    static: np.ndarray
    u_p: np.ndarray
    u_q: np.ndarray
    p: np.ndarray
    m: np.ndarray
    q: np.ndarray
    offset: np.ndarray

    @classmethod
    def empty(cls):
        """No chain at all."""
        ints, points = np.zeros(0, np.int64), np.zeros((0, 2))
        return cls(
            ints,
            ints,
            ints,
            points,
            points,
            np.zeros(0, bool),
            np.zeros(0),
            np.zeros(0),
            points,
            points,
            points,
            points,
        )


@dataclass
class Segment:
    """A chain whose samples a morph makes.

    Attributes
    ----------
    pair, order : int
        Its pair and its position along it.
    range_p, range_q : tuple of float
        Arc-length start and end of its pieces on the pair's curves.
    morph : Morph
        ``morph.u_p`` and ``u_q`` are the fractions along the pieces, unless ``u_p`` says otherwise.
    offset : ndarray, shape (K, 2), optional
        Added as ``(1 - t)`` times this to each sample (the end gaps of open strokes).
    u_p : ndarray, shape (K,), optional
        The samples' fractions along the piece of P when they are not the morph's own (a morph of
        a common part placed on the whole curve, see :func:`..pair_morphs.chain_maps.placed`).
    """

    pair: int
    order: int
    range_p: tuple
    range_q: tuple
    morph: object
    offset: np.ndarray = None
    u_p: np.ndarray = None

    @property
    def fractions_p(self):
        """The samples' fractions along the piece of P, shape (K,)."""
        return self.morph.u_p if self.u_p is None else self.u_p


@dataclass
class PairFrames:
    """Every pair's in-betweens at some times: the frames of a drawing before attributes.

    Attributes
    ----------
    frames : ndarray, shape (T, K, 2)
        All samples of all pairs, pair after pair.
    offsets : ndarray of int, shape (C + 1,)
        Pair ``c`` owns samples ``offsets[c]:offsets[c + 1]``.
    u_a, u_b : ndarray, shape (K,)
        Where each sample comes from on the first stroke and goes to on the second, as
        arc-length fractions along the strokes (the second as it was morphed, i.e. flipped when
        the pair is).
    closed : ndarray of bool, shape (C,)
    used : list of str
        The morph each pair used.
    notes : list of list of str
        What each pair's report says.
    """

    frames: np.ndarray
    offsets: np.ndarray
    u_a: np.ndarray
    u_b: np.ndarray
    closed: np.ndarray
    used: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    #: Each sample's key strokes (set by the plan: a pair drawn in pieces reads attributes piece
    #: by piece); None: each pair's own strokes.
    stroke_a: np.ndarray = None
    stroke_b: np.ndarray = None

    def pair(self, c):
        """``(frames (T, K_c, 2), u_a, u_b)`` of pair ``c``."""
        sl = slice(self.offsets[c], self.offsets[c + 1])
        return self.frames[:, sl], self.u_a[sl], self.u_b[sl]


def _chains(ball, segments):
    """Every chain (ball rows first, then the segments): pair, order, size, ranges (arrays)."""
    sizes = [len(s.fractions_p) for s in segments]
    pair = np.r_[ball.pair, [s.pair for s in segments]].astype(np.int64)
    order = np.r_[ball.order, [s.order for s in segments]].astype(np.int64)
    ranges = [
        np.concatenate([getattr(ball, f"range_{k}"), np.reshape([getattr(s, f"range_{k}") for s in segments], (-1, 2))])
        for k in "pq"
    ]
    return pair, order, np.r_[ball.sizes, sizes].astype(np.int64), ranges


def _fractions(local, ranges, lengths, chain, owner, loop):
    """Fractions along a pair's curve of samples at fractions ``local`` (K,) along their chains'
    pieces (arc-length ``ranges`` (H, 2) on curves of ``lengths`` (C,)), taken round a loop
    (``loop``, shape (K,)), clipped to [0, 1] on an open curve, shape (K,).

    Each chain's start and span and each pair's length are gathered, not (K, 2) ranges: the
    same values, elementwise, as reading them sample by sample."""
    start, span = ranges[:, 0], ranges[:, 1] - ranges[:, 0]
    u = np.take(span, chain)
    u *= local
    u += np.take(start, chain)
    u /= np.take(np.maximum(lengths, tol.TINY), owner)
    out = np.clip(u, 0.0, 1.0)
    if loop.any():
        out[loop] = np.mod(u[loop], 1.0)
    return out


def _run(rows):
    """Indices as a slice when they run in order (cheaper to read and write), else as they are."""
    rows = np.asarray(rows, dtype=np.int64)
    if len(rows) and np.array_equal(rows, np.arange(rows[0], rows[0] + len(rows))):
        return slice(int(rows[0]), int(rows[0]) + len(rows))
    return rows


@dataclass
class _Shift:
    """Samples of a block moved by ``(1 - t)`` times an offset (the end gaps of open strokes).

    Attributes
    ----------
    rows : slice or ndarray of int
        The J samples, within their block.
    offset : ndarray, shape (2, J)
        Their offsets, column by column.
    """

    rows: object
    offset: np.ndarray

    @classmethod
    def of(cls, rows, offset):
        """From rows (J,) and offsets (J, 2); None for no row."""
        if not len(rows):
            return None
        return cls(_run(rows), np.ascontiguousarray(np.reshape(offset, (-1, 2)).T))

    def apply(self, block, t, term):
        """``block`` (2, n) plus ``(1 - t)`` times the offsets at the rows; ``term``: a work
        buffer of at least J values."""
        for column, offset in zip(block, self.offset):
            column[self.rows] += np.multiply(offset, 1.0 - t, out=term[: len(offset)])


def _joinable(morph):
    """Whether a segment's samples travel along paths whose class joins many (``join``)."""
    return type(morph) is PathMorph and hasattr(type(morph.paths), "join")


@dataclass
class _Joined:
    """Segments whose paths are of one joinable class (straight paths of the fallbacks,
    arc-length and own-point pairs; overhangs sliding along their strokes), joined: one
    evaluation for all of them instead of one per segment (hundreds of small morphs).

    Attributes
    ----------
    morph : PathMorph
        Their kept samples' paths, segment after segment.
    block : slice
        Their samples' place in the layout's work columns.
    shift : _Shift or None
        Those with an offset.
    """

    morph: PathMorph
    block: slice
    shift: _Shift = None

    @classmethod
    def join(cls, items, start):
        """From ``(morph, kept samples, rows, offset or None)`` of each segment (one paths class),
        their samples from ``start`` in the work columns on."""
        paths = type(items[0][0].paths).join([(m.paths, keep) for m, keep, _, _ in items])
        starts = np.cumsum([0] + [len(keep) for _, keep, _, _ in items])
        shifted = [np.arange(a, a + len(keep)) for a, (_, keep, _, off) in zip(starts, items) if off is not None]
        offsets = [off for _, _, _, off in items if off is not None]
        return cls(
            PathMorph("joined", False, paths, np.zeros(starts[-1]), np.zeros(starts[-1])),
            slice(start, start + int(starts[-1])),
            _Shift.of(np.concatenate(shifted), np.concatenate(offsets)) if shifted else None,
        )

    def write(self, stage, t, term):
        """Their samples at time ``t`` into the work columns ``stage`` (2, K_all)."""
        block = stage[:, self.block]
        if isinstance(self.morph.paths, LinearPaths):  # straight into the buffer
            self.morph.paths.at(morph_time(t), out=block.T)
        else:
            block.T[...] = self.morph(t)
        if self.shift is not None:
            self.shift.apply(block, t, term)


class Layout:
    """The samples of every pair, laid out pair after pair and chain after chain.

    Each frame is evaluated route by route into work columns kept from frame to frame (every
    full-size temporary is a fresh mapping, page-faulted anew, in a bpy process), gathered into
    frame order and carried by the pairs' carriers there.

    Parameters
    ----------
    ball : BallRows
    segments : list of Segment
    closed : ndarray of bool, shape (C,)
        Whether each pair's in-betweens are loops.
    joined : ndarray of bool, shape (C,)
        Loops cut into pieces (their last piece's last sample is their first).
    lengths : ndarray, shape (C, 2)
        Length of each pair's P and Q (the ranges are arc lengths along them).
    kind : str
        The ball-morph path of the contacts (see :class:`~ballmorph_core.morphs.paths.BallPaths`).
    """

    def __init__(self, ball, segments, closed, joined, lengths, kind="circular"):
        self.closed = np.asarray(closed, dtype=bool)
        pair, order, sizes, (range_p, range_q) = _chains(ball, segments)
        rank = np.empty(len(pair), dtype=np.int64)
        rank[np.lexsort((order, pair))] = np.arange(len(pair))
        ordered = np.argsort(rank)
        first = np.r_[True, pair[ordered][1:] != pair[ordered][:-1]][rank]
        last = np.r_[pair[ordered][1:] != pair[ordered][:-1], True][rank]
        chain, local = ragged_arange(sizes)
        keep = ~((local == 0) & ~first[chain]) & ~((local == sizes[chain] - 1) & last[chain] & joined[pair[chain]])
        # Rows as given (ball rows, then each segment's) -> their place in the frames: chain
        # after chain in frame order, each chain's rows in order (each chain's run of rows as
        # given, no sort of every row).
        block, along = ragged_arange(sizes[ordered])
        rows = (np.cumsum(sizes) - sizes)[ordered][block] + along
        rows = rows[keep[rows]]
        position = np.full(len(chain), -1, dtype=np.int64)  # not kept: only the rows below are
        position[rows] = np.arange(len(rows))
        c = chain[rows]
        owner = pair[c]
        self.offsets = np.searchsorted(owner, np.arange(len(self.closed) + 1))
        u_p = np.concatenate([ball.u_p, *[s.fractions_p for s in segments]])[rows]
        u_q = np.concatenate([ball.u_q, *[s.morph.u_q for s in segments]])[rows]
        loop = self.closed[owner]
        self.u_a = _fractions(u_p, range_p, lengths[:, 0], c, owner, loop)
        self.u_b = _fractions(u_q, range_q, lengths[:, 1], c, owner, loop)
        # A sample's worth each, not needed by the routes: let go before they are made.
        del chain, local, block, along, rows, c, owner, u_p, u_q, loop
        self._routes(ball, segments, keep, position, kind)
        self._work = self._carrier = None

    def _routes(self, ball, segments, keep, position, kind):
        """Each route's evaluation and its samples' place in the work columns: the ball rows
        first, then each joined class, then the other morphs; gathered into frame order by
        ``_gather`` (None: they are in frame order already)."""
        n_ball = len(ball.u_p)
        kept = np.flatnonzero(keep[:n_ball])
        staged = [position[kept]]
        self._ball = slice(0, len(kept))

        def rows(a):  # the kept ball rows of (K, 2) values: np.take, ~8x faster than a mask
            return np.take(a, kept, axis=0)

        self._paths = BallPaths(rows(ball.p), rows(ball.m), rows(ball.q), kind) if len(kept) else None
        offset = rows(ball.offset)
        self._ball_shift = _Shift.of(np.arange(self._ball.stop), offset) if offset.any() else None
        # Each segment's kept rows (local to it) and their place in the frames, from one search
        # of every segment's rows at once (a drawing has hundreds of segments: its overhangs).
        sizes = np.array([len(s.fractions_p) for s in segments], dtype=np.int64)
        starts = np.cumsum(sizes) - sizes
        kept_rows = np.flatnonzero(keep[n_ball:])
        frame_rows = position[n_ball:][kept_rows]
        bounds = np.r_[np.searchsorted(kept_rows, starts), len(kept_rows)].tolist()
        others, joinable = [], {}
        for k, (seg, a) in enumerate(zip(segments, starts.tolist())):
            run = slice(bounds[k], bounds[k + 1])
            local = kept_rows[run] - a
            offset = None if seg.offset is None or not np.any(seg.offset) else seg.offset[local]
            item = (seg.morph, local, frame_rows[run], offset)
            if _joinable(seg.morph):
                joinable.setdefault(type(seg.morph.paths), []).append(item)
            else:
                others.append(item)
        self._joined, self._morphs, start = [], [], self._ball.stop
        for items in joinable.values():
            self._joined.append(_Joined.join(items, start))
            staged += [item[2] for item in items]
            start = self._joined[-1].block.stop
        for morph, local, frame_rows, offset in others:
            block = slice(start, start + len(local))
            shift = None if offset is None else _Shift.of(np.arange(len(local)), offset)
            self._morphs.append((morph, local, block, shift))
            staged.append(frame_rows)
            start = block.stop
        staged = np.concatenate(staged).astype(np.int64)
        self._gather = np.empty(len(staged), dtype=np.int64)
        self._gather[staged] = np.arange(len(staged))
        if np.array_equal(self._gather, np.arange(len(staged))):
            self._gather = None

    def _buffers(self, motions):
        """The work columns (5, K), made once, and the carrier of ``motions`` (None without)."""
        if self._work is None:
            self._work = np.empty((5, len(self.u_a)))
        if motions is None:
            self._carrier = None
        elif self._carrier is None or self._carrier.motions is not motions:
            self._carrier = _Carrier(motions, np.diff(self.offsets))
        return self._work, self._carrier

    def evaluate(self, times, motions=None, out=None):
        """Every sample at every time, shape (T, K, 2) (``out`` when given); ``motions`` carries
        registered pairs along."""
        frames = np.empty((len(times), len(self.u_a), 2)) if out is None else out
        work, carry = self._buffers(motions)
        # stage: the routes' samples; columns: in frame order (the same when staged so);
        # scratch: free while the carrier runs; term: the offsets' work column.
        stage, term = work[0:2], work[4]
        columns, scratch = (stage, work[2:4]) if self._gather is None else (work[2:4], stage)
        for ti, t in enumerate(times):
            if self._paths is not None:
                self._paths.at(t, out=stage[:, self._ball].T)
                if self._ball_shift is not None:
                    self._ball_shift.apply(stage[:, self._ball], t, term)
            for joined in self._joined:
                joined.write(stage, t, term)
            for morph, keep, block, shift in self._morphs:
                stage[:, block].T[...] = morph(t)[keep]
                if shift is not None:
                    shift.apply(stage[:, block], t, term)
            if self._gather is not None:
                for source, column in zip(stage, columns):
                    source.take(self._gather, out=column, mode="wrap")  # in range: no bounds check
            if carry is None or not carry(t, frames[ti], columns, scratch):
                frames[ti, :, 0], frames[ti, :, 1] = columns
        return frames


def _carry(motions, t, frame, sizes):
    """Each pair's carrier ``C_t`` (:meth:`Motions.at <.registration.Motions.at>`) applied to its
    samples in place (pairs that do not move keep theirs exactly).

    Parameters
    ----------
    motions : Motions
        C pairs.
    t : float
    frame : ndarray, shape (K, 2)
        The samples, pair after pair; overwritten.
    sizes : ndarray of int, shape (C,)
        Samples per pair.
    """
    columns = np.array(frame.T)
    _Carrier(motions, sizes)(t, frame, columns, np.empty_like(columns))


class _Carrier:
    """:func:`_carry` frame after frame: each pair's coefficients are gathered over its run of
    samples (instead of a (K, 2, 2) gather and einsum: 5 times faster at 20,000 samples) into
    work buffers the caller keeps, as every full-size temporary is a fresh allocation that glibc
    maps and unmaps anew (3 times the arithmetic's cost in a bpy process)."""

    def __init__(self, motions, sizes):
        self.motions = motions
        self.owner = np.repeat(np.arange(len(sizes)), sizes)

    def __call__(self, t, frame, columns, scratch):
        """``frame`` (K, 2) := the samples ``columns`` (2, K) carried; ``scratch``: two work
        columns (2, K). False, and nothing written, when no pair moves."""
        motions = self.motions
        if not motions.moving.any():
            return False
        M, c = motions.at(t)
        still = ~motions.moving  # exactly the identity (in place: at's arrays are fresh)
        M[still], c[still] = np.eye(2), 0.0
        (x, y), (column, term) = columns, scratch
        # Every owner is in range: mode='wrap' skips take's bounds check (2-3 times faster);
        # the method, not np.take (its Python wrapper is a tenth of a small take).
        owner = self.owner
        for i in range(2):
            # M_i0 x + M_i1 y + c_i, summed in that order (the last sum straight into the frame).
            M[:, i, 0].take(owner, out=column, mode="wrap")
            column *= x
            M[:, i, 1].take(owner, out=term, mode="wrap")
            term *= y
            column += term
            np.add(column, c[:, i].take(owner, out=term, mode="wrap"), out=frame[:, i])
        return True
