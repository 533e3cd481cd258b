"""Where every pair's samples sit in a drawing's frames, and how they are evaluated.

The pipeline hands over *segments*: the samples of one chain of one pair (a lens, an overlap, a
whole pair), either as ball-map contacts ``(p, m, q)`` -- all of them evaluated together as one
:class:`~ballmorph_core.morphs.paths.BallPaths` -- or as a :class:`~ballmorph_core.morphs.base.Morph`
(a fallback, a comparison morph, straight point motion). Consecutive chains of a pair share an
endpoint (a crossing, the end of an overlap), kept once; the last chain of a loop cut into
pieces ends where the first starts.
"""

from dataclasses import dataclass, field

import numpy as np

from ..morphs.paths import BallPaths

__all__ = ["Segment", "PairFrames", "Layout"]


@dataclass
class Segment:
    """The samples of one chain.

    Attributes
    ----------
    pair : int
    order : int
        Position of the chain along its pair.
    u_p, u_q : ndarray, shape (K,)
        Fractions along the chain's pieces of P and Q (as given).
    range_p, range_q : tuple of float
        Arc-length start and end of the pieces on the pair's curves.
    contacts : tuple of ndarray, optional
        ``(p, m, q)``, each shape (K, 2): ball-map contacts and disk centres.
    morph : Morph, optional
        Or the morph whose frames are these samples.
    method : str, optional
        What made contacts that are not the ball-morph's own ('static' for an overlap).
    """

    pair: int
    order: int
    u_p: np.ndarray
    u_q: np.ndarray
    range_p: tuple
    range_q: tuple
    contacts: tuple = None
    morph: object = None
    method: str = None

    def __len__(self):
        return len(self.u_p)


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

    def pair(self, c):
        """``(frames (T, K_c, 2), u_a, u_b)`` of pair ``c``."""
        sl = slice(self.offsets[c], self.offsets[c + 1])
        return self.frames[:, sl], self.u_a[sl], self.u_b[sl]


def _fractions(local, rng, length, closed):
    u = (rng[0] + local * (rng[1] - rng[0])) / max(length, 1e-300)
    return np.mod(u, 1.0) if closed else np.clip(u, 0.0, 1.0)


class Layout:
    """The samples of every pair, laid out pair after pair and chain after chain.

    Parameters
    ----------
    segments : list of Segment
    closed : ndarray of bool, shape (C,)
        Whether each pair's in-betweens are loops.
    joined : ndarray of bool, shape (C,)
        Loops cut into pieces (their last piece's last sample is their first).
    lengths : ndarray, shape (C, 2)
        Length of each pair's P and Q (the arc lengths of the ranges are along them).
    kind : str
        The ball-morph path of the contacts (see :class:`~ballmorph_core.morphs.paths.BallPaths`).
    """

    def __init__(self, segments, closed, joined, lengths, kind="circular"):
        n = len(closed)
        segments = sorted(segments, key=lambda s: (s.pair, s.order))
        pair = np.array([s.pair for s in segments], dtype=np.int64)
        first = np.r_[True, pair[1:] != pair[:-1]]
        last = np.r_[pair[1:] != pair[:-1], True]
        self.closed = np.asarray(closed, dtype=bool)
        keeps, u_a, u_b, sizes = [], [], [], np.zeros(n, dtype=np.int64)
        for k, seg in enumerate(segments):
            keep = np.arange(len(seg))[(0 if first[k] else 1) : len(seg) - (1 if last[k] and joined[seg.pair] else 0)]
            keeps.append(keep)
            sizes[seg.pair] += len(keep)
            length_p, length_q = lengths[seg.pair]
            u_a.append(_fractions(seg.u_p[keep], seg.range_p, length_p, self.closed[seg.pair]))
            u_b.append(_fractions(seg.u_q[keep], seg.range_q, length_q, self.closed[seg.pair]))
        self.offsets = np.concatenate([[0], np.cumsum(sizes)])
        self.u_a = np.concatenate(u_a) if u_a else np.zeros(0)
        self.u_b = np.concatenate(u_b) if u_b else np.zeros(0)
        start = np.cumsum([0] + [len(k) for k in keeps])
        self.pair_of = np.repeat(pair, [len(k) for k in keeps]).astype(np.int64)
        ball = [k for k, s in enumerate(segments) if s.contacts is not None]
        self._ball_rows = np.concatenate([np.arange(start[k], start[k + 1]) for k in ball]) if ball else None
        self._paths = (
            BallPaths(*(np.concatenate([segments[k].contacts[i][keeps[k]] for k in ball]) for i in range(3)), kind)
            if ball
            else None
        )
        self._morphs = [
            (segments[k].morph, keeps[k], slice(start[k], start[k + 1]))
            for k, s in enumerate(segments)
            if s.morph is not None
        ]

    def evaluate(self, times, motions=None):
        """Every sample at every time, shape (T, K, 2); ``motions`` carries registered pairs along."""
        frames = np.empty((len(times), len(self.u_a), 2))
        for ti, t in enumerate(times):
            if self._paths is not None:
                frames[ti, self._ball_rows] = self._paths.at(t)
            for morph, keep, rows in self._morphs:
                frames[ti, rows] = morph(t)[keep]
            if motions is not None:
                frames[ti] = motions.apply(t, frames[ti], self.pair_of)
        return frames
