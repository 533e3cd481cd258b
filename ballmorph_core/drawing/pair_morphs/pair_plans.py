"""The plan of every stroke pair of a drawing: its morphs laid out, ball-mapped samples and
carrier motions (:class:`PairPlans`), gathered by the pipeline from what each step planned
(:class:`Planned`) and evaluated at any times by :meth:`PairPlans.frames`."""

from dataclasses import dataclass, fields

import numpy as np

from ..frames.layout import BallRows, Layout, PairFrames, Segment
from ..strokes import PairMorphs

__all__ = ["PairNote", "Planned", "PairPlans", "whole_segment"]


@dataclass(frozen=True)
class PairNote:
    """One line of a pair's report (a fallback, a split, a missing carrier).

    Attributes
    ----------
    pair : int
        The pair, in the drawing.
    text : str
    """

    pair: int
    text: str


@dataclass(frozen=True)
class Planned:
    """What one step of the pipeline planned for the pairs it took; :meth:`PairPlans.gather`
    writes it into the plans (the steps never write into the plans themselves).

    Attributes
    ----------
    pairs : ndarray of int, shape (C,)
        The pairs the step took, in the drawing.
    routes : tuple of Route
        The route each of them took, C of them.
    closed : ndarray of bool, shape (C,)
    lengths : ndarray, shape (C, 2)
        The arc lengths of each pair's two curves, as the step morphed them.
    segments : tuple of Segment
        The morphs of the pairs' chains, in the order they are laid out.
    notes : tuple of PairNote
        What the pairs' reports say, in order.
    motions : Motions, optional
        The carriers of the pairs (C of them); None leaves the carriers as they are.
    joined : ndarray of bool, shape (C,), optional
        The loops cut at their crossings (their chains joined end to end); None for none.
    ball : BallRows, optional
        The samples of the pairs' ball-mapped chains.
    """

    pairs: np.ndarray
    routes: tuple
    closed: np.ndarray
    lengths: np.ndarray
    segments: tuple = ()
    notes: tuple = ()
    motions: object = None
    joined: np.ndarray = None
    ball: BallRows = None

    @classmethod
    def nothing(cls, notes=()):
        """A step that took no pair (``notes``, PairNotes, still say something of pairs other
        steps took)."""
        return cls(np.zeros(0, dtype=np.int64), (), np.zeros(0, dtype=bool), np.zeros((0, 2)), notes=tuple(notes))


def whole_segment(pair, morph, lengths):
    """The Segment of a morph of a whole pair whose curves are ``lengths`` (P, Q) long.

    Parameters
    ----------
    pair : int
    morph : Morph
    lengths : array_like, shape (2,)

    Returns
    -------
    Segment
    """
    length_p, length_q = np.asarray(lengths, dtype=np.float64)
    return Segment(int(pair), 0, (0.0, length_p), (0.0, length_q), morph=morph)


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

    def set_routes(self, pairs, routes):
        """Each of ``pairs`` (ints) took its Route of ``routes``."""
        for c, route in zip(pairs, routes):
            self.routes[int(c)] = route

    def gather(self, planned):
        """What one step planned (:class:`Planned`) written into the plans: the pairs' flags,
        lengths, routes and carriers, their segments and ball-mapped samples after the others',
        their notes after the notes they have."""
        pairs = np.asarray(planned.pairs, dtype=np.int64)
        if planned.motions is not None and len(pairs):
            self.motions.put(pairs, planned.motions)
        self.closed[pairs], self.lengths[pairs] = planned.closed, planned.lengths
        if planned.joined is not None:
            self.joined[pairs] = planned.joined
        self.segments.extend(planned.segments)
        if planned.ball is not None:
            self.ball.append(planned.ball)
        for note in planned.notes:
            self.notes[note.pair].append(note.text)
        self.set_routes(pairs, planned.routes)

    def finish(self, kind="circular"):
        """Name each pair's morphs and lay the segments out (step 11)."""
        ball, self.ball = _joined(self.ball), None
        methods = [set() for _ in self.used]
        for seg in self.segments:
            methods[seg.pair].add(seg.morph.method)
        for c, static in zip(ball.pair, ball.static):
            methods[c].add("static" if static else f"{kind}-ball")
        for c, names in enumerate(methods):
            moving = self.motions is not None and self.motions.moving[c]
            self.used[c] = PairMorphs(tuple(sorted(names)), self.motions.kind if moving else "", self.routes[c])
        segments, self.segments = self.segments, None
        self.layout = Layout(ball, segments, self.closed, self.joined, self.lengths, kind)
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
    """One BallRows from several (the ball route's runs of pairs), the list emptied: each
    part's arrays are let go field by field as they are joined (a drawing's ball rows are not
    held twice while the layout is made); one part is itself."""
    if not parts:
        return BallRows.empty()
    if len(parts) == 1:
        return parts.pop()
    joined = {}
    for f in fields(BallRows):
        joined[f.name] = np.concatenate([getattr(p, f.name) for p in parts])
        for p in parts:
            setattr(p, f.name, None)
    parts.clear()
    return BallRows(**joined)
