"""The plan of every stroke pair of a drawing: its morphs laid out, ball-mapped samples and
carrier motions (:class:`PairPlans`), which the pipeline's routes fill and :meth:`PairPlans.frames`
evaluates at any times."""

from dataclasses import fields

import numpy as np

from ..frames.layout import BallRows, Layout, PairFrames, Segment
from ..strokes import PairMorphs

__all__ = ["PairPlans"]


class PairPlans:
    """The plan of every pair of a drawing: laid-out samples, carriers, reports.

    Built by :func:`plan_pairs`; :meth:`frames` evaluates it at any times.

    Attributes
    ----------
    used : list of PairMorphs
        The morphs each pair's chains used, and its carrier.
    notes : list of list of str
        What each pair's report says (fallbacks, splits).
    closed : ndarray of bool, shape (C,)
    """

    def __init__(self, pairs):
        n = len(pairs)
        self.segments, self.ball, self.used, self.notes = [], [], [PairMorphs()] * n, [list(p.notes) for p in pairs]
        self.closed, self.joined = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
        self.lengths = np.ones((n, 2))
        self.motions, self.layout = None, None
        self.routes = [None] * n  # each pair's Route, set by the route that takes it

    def add_morph(self, c, morph, closed, lengths=(1.0, 1.0), order=0, ranges=None, offset=None):
        """A morph for (a chain of) pair ``c``; ``ranges`` are its pieces' arc lengths on the pair
        (default: the whole pair, of ``lengths``); ``offset`` see :class:`~.layout.Segment`."""
        if ranges is None:
            self.closed[c], self.lengths[c] = closed, lengths
            ranges = ((0.0, self.lengths[c, 0]), (0.0, self.lengths[c, 1]))
        self.segments.append(Segment(c, order, *ranges, morph=morph, offset=offset))

    def set_route(self, pairs, route):
        """``pairs`` (ints) took ``route`` (a Route)."""
        self.set_routes(pairs, [route] * len(pairs))

    def set_routes(self, pairs, routes):
        """Each of ``pairs`` (ints) took its Route of ``routes``."""
        for c, route in zip(pairs, routes):
            self.routes[int(c)] = route

    def drop(self, pairs, notes_kept):
        """Forget what was planned for ``pairs`` (keeping their first ``notes_kept[c]`` notes)."""
        self.segments = [s for s in self.segments if s.pair not in pairs]
        self.ball = [rows.without(pairs) for rows in self.ball]
        for c in pairs:
            del self.notes[c][notes_kept[c] :]
            self.routes[c] = None

    def finish(self, kind="circular"):
        """Name each pair's morphs and lay the segments out (step 8)."""
        ball = _joined(self.ball)
        methods = [set() for _ in self.used]
        for seg in self.segments:
            methods[seg.pair].add(seg.morph.method)
        for c, static in zip(ball.pair, ball.static):
            methods[c].add("static" if static else f"{kind}-ball")
        for c, names in enumerate(methods):
            moving = self.motions is not None and self.motions.moving[c]
            self.used[c] = PairMorphs(tuple(sorted(names)), self.motions.kind if moving else "", self.routes[c])
        self.layout = Layout(ball, self.segments, self.closed, self.joined, self.lengths, kind)
        self.segments = self.ball = None
        return self

    def frames(self, times, out=None):
        """Every pair's in-betweens at ``times`` (PairFrames), their frames written into ``out``
        (T, K, 2) when given."""
        times = np.asarray(times, dtype=np.float64).reshape(-1)
        frames = self.layout.evaluate(times, self.motions, out)
        return PairFrames(
            frames, self.layout.offsets, self.layout.u_a, self.layout.u_b, self.closed, self.used, self.notes
        )


def _joined(parts):
    """One BallRows from several (the ball route's batches)."""
    if not parts:
        return BallRows.empty()
    return BallRows(*(np.concatenate([getattr(p, f.name) for p in parts]) for f in fields(BallRows)))
