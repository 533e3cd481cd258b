"""In-betweens of whole drawings: what the Blender operator calls.

:func:`plan_inbetween` pairs the strokes of two keys (:mod:`.matching`), plans every pair through
the one stroke-pair pipeline (:mod:`.pipeline`) in the plane that fits both keys, and returns an
:class:`InbetweenPlan`; its :meth:`~InbetweenPlan.evaluate` gives one :class:`StrokeSet` per
requested time, per-point attributes carried along the correspondence (:mod:`.attributes`), plus
messages for the animator. A pair that the requested morph cannot handle falls back to a
documented morph and is reported; nothing is dropped silently. :func:`inbetween` is both at once.
"""

import numpy as np

from ..geometry.plane import fit_plane
from ..geometry.polyline import reversed_fractions
from .frames.attributes import Extras, FrameValues, Held, Recycled, assemble_frames
from .frames.layout import PairFrames
from .keys.checked import check_inputs, check_times
from .keys.hints import END_HINT, HINT, Pieces, common_hints, hinted_fit, key_hints, pair_hints
from .keys.projected import KeyStroke, ProjectedKey, StrokePair
from .pair_morphs.fallbacks import STRAIGHT_POINT_MOTION, point_motion
from .pair_morphs.pipeline import PairCurves, plan_pairs
from .pairing.groups import ride_groups
from .pairing.matching import match_strokes, pair_direction
from .pairing.redrawn import Joined, cut_frame, join_pieces, joined_stroke
from .reports.pair_reports import pair_report, piece_report, unmatched_report
from .strokes import InbetweenResult, Message, PairMorphs, Route, as_written

__all__ = ["InbetweenPlan", "inbetween", "plan_inbetween"]

#: Strokes whose points lie farther than this (times scale) from the fitted drawing plane are
#: reported as non-planar.
PLANARITY = 1e-3

#: In-betweens are evaluated a few times at once: about this many samples x times per chunk
#: (16 MiB of staged 2D frames), however big the drawing.
EVALUATE_SAMPLES = 1_000_000


def inbetween(key_a, key_b, times, *options, **named):
    """In-between drawings of two keys: ``plan_inbetween(key_a, key_b, ...).evaluate(times)``.

    Parameters
    ----------
    key_a, key_b : StrokeSet
        The two keys (not modified).
    times : array_like, shape (T,)
        Morph times in [0, 1] (already eased; values outside are clamped).
    *options, **named
        ``method``, ``carrier``, ``matching``, ``unmatched``, ``spacing``: see
        :func:`plan_inbetween`.

    Returns
    -------
    InbetweenResult
    """
    times = check_times(times)  # before the expensive part
    return plan_inbetween(key_a, key_b, *options, **named).evaluate(times)


def plan_inbetween(
    key_a,
    key_b,
    method="circular-ball",
    carrier="similarity",
    matching="auto",
    unmatched="middle",
    spacing=None,
):
    """Everything about the in-betweens of two keys that does not depend on the times.

    Parameters
    ----------
    key_a, key_b : StrokeSet
        The two keys (not modified; the plan keeps them, so do not modify them either while
        the plan is in use).
    method : str
        A method of :data:`~ballmorph_core.METHODS`.
    carrier : {'similarity', 'rigid', 'none'}
        Carrier motion for strokes that do not share endpoints (see
        :mod:`~ballmorph_core.drawing.pair_morphs.registration`); 'none' is the paper's pure ball-morph.
    matching : {'auto', 'index'}
        How strokes of the two keys are paired (see :mod:`~ballmorph_core.drawing.pairing.matching`).
    unmatched : {'middle', 'hold', 'fade', 'shrink', 'neighbour'}
        What a stroke without a partner does (see :mod:`.unmatched`): appears (or disappears)
        at t = 0.5, is held on every in-between, fades in (or out), grows out of (or shrinks
        into) the point at its middle, or out of (into) the nearest point of its nearest paired
        stroke.
    spacing : float, optional
        Geodesic sample spacing for every pair (default: each pair's own).

    Every option also accepts Blender's enum spelling ('SIMILARITY', 'CIRCULAR_BALL').

    Returns
    -------
    InbetweenPlan

    Notes
    -----
    Strokes are paired by :func:`~ballmorph_core.drawing.pairing.matching.match_strokes` (by index when
    the counts agree and the shapes fit, as Blender does; otherwise by an optimal assignment on
    a shape distance); a stroke of the second key running the other way is flipped first. Every
    pair then goes through :func:`~ballmorph_core.drawing.pair_morphs.pipeline.plan_pairs`, all at once. The
    matching, the correspondences and the carriers are computed here, once; the plan's
    :meth:`~InbetweenPlan.evaluate` only moves samples along their paths, which is what lets the
    operator's redo (another frame count or easing) skip the expensive part.
    """
    return InbetweenPlan(key_a, key_b, *check_inputs(key_a, key_b, method, carrier, matching, unmatched, spacing))


class InbetweenPlan:
    """The in-betweens of two keys, ready to evaluate at any times (see :func:`plan_inbetween`).

    Evaluating a plan at ``times`` gives exactly what :func:`inbetween` gives for the same keys,
    options and times.

    Attributes
    ----------
    strokes : list of StrokePair
        The paired strokes, in the order of the plan's pairs.
    """

    def __init__(self, key_a, key_b, method, carrier, matching, unmatched, spacing):
        self.method, self.unmatched = method, unmatched
        points = np.concatenate([key_a.positions, key_b.positions])
        self.plane = plane = fit_plane(points)
        # Said now: both keys' points together are not kept through the planning.
        self.planarity = _planarity_messages(points, plane)
        del points
        self.extras = extras = Extras.of(key_a, key_b)
        ka = ProjectedKey(key_a, plane, extras.point_columns(key_a))
        kb = ProjectedKey(key_b, plane, extras.point_columns(key_b))
        self.ka, self.kb = ka, kb
        self.messages = []  # the plan's own, before the per-pair reports
        hints = common_hints(
            key_hints(key_a, "first", self.messages), key_hints(key_b, "second", self.messages), self.messages
        )
        matched, drawing = self._match(key_a, key_b, matching, hints)
        hinted_strokes = {h.stroke_a for h in hints}, {h.stroke_b for h in hints}
        self.joined = self._join_pieces(matched, hinted_strokes)
        groups = self._groups(matched, drawing, hinted_strokes, matching)
        matched = groups.matched
        self.strokes = [self._pair_strokes(k, i, j, flip, drawing) for k, (i, j, flip) in enumerate(matched)]
        hinted = pair_hints(hints, self.strokes, ka, kb, self.messages)
        self.strokes, hinted = self._orient_by_hints(hinted, hints)
        self.has_hints = HINT in key_a.point_attributes or HINT in key_b.point_attributes
        curves = [_curves(a, b) for a, b, _ in self.strokes]
        for k, group in groups.members.items():
            curves[k].group = group
        self.pieces = Pieces(curves, self.strokes, hinted, carrier, drawing, _curves)
        self.pairs = plan_pairs(self.pieces.curves, method, carrier, spacing, drawing)
        self._samples = None  # _Samples, from the first evaluation
        self._staged = np.empty((0, 0, 2))  # the pairs' frames of a chunk of times (see _frames)
        self._recycled = Recycled()  # the arrays of the last evaluation's in-betweens

    def _groups(self, matched, drawing, hinted_strokes, matching):
        """The groups that move together (:mod:`.pairing.groups`), their strokes paired again
        under the group's motion where the matching paired them a symmetry step off (never
        hinted, travelled, joined or index-matched pairs)."""
        fixed = {
            k
            for k, (i, j, _) in enumerate(matched)
            if matching == "index"
            or k in self.joined
            or i in hinted_strokes[0]
            or j in hinted_strokes[1]
            or (i, j) in self.travelled
        }
        groups = ride_groups(self.ka.rg, self.kb.rg, matched, drawing, fixed)
        for loop, count in groups.repaired:
            self.messages.append(
                Message(
                    "INFO",
                    f"the strokes inside stroke {as_written(loop)} of the first key move together: "
                    f"{count} of them paired again under their group's motion",
                )
            )
        return groups

    def _hinted_motion(self, forced, hints):
        """How the hints say the drawing moves (complex ``a, b``): the hinted registration of
        the longest pair the hints join, or None. A wheel hinted to turn a quarter turn turns its
        unhinted spokes with it."""
        best, longest = None, 0.0
        for i, j in forced:
            ka, kb = self.ka, self.kb
            flip = pair_direction(ka.rg.curve(i), kb.rg.curve(j), ka.rg.closed[i], kb.rg.closed[j])
            a, b = ka.stroke(i), kb.stroke(j, flip)
            found = pair_hints(hints, [(a, b, flip)], ka, kb, [])
            length = float(ka.rg.length[i] + kb.rg.length[j])
            if 0 in found and length > longest:
                best, longest = hinted_fit(a, b, found[0]), length
        return best

    def _join_pieces(self, matched, hinted_strokes):
        """Strokes without a partner that are pieces of a paired stroke's line (see
        :mod:`.redrawn`), joined to it: dict pair index -> Joined; they are no longer held."""
        held = [(h.index, h.from_a) for h in self.held]
        free = [
            (k, (i, j, f))
            for k, (i, j, f) in enumerate(matched)
            if i not in hinted_strokes[0] and j not in hinted_strokes[1]
        ]
        extra, side = join_pieces([p for _, p in free], held, self.ka, self.kb)
        out = {}
        for local, pieces in extra.items():
            k, (i, j, _) = free[local]
            from_a = side[local] == "a"
            key, first = (self.ka, i) if from_a else (self.kb, j)
            xy, u, order, flips, spans = joined_stroke(key, first, pieces)
            out[k] = Joined(k, side[local], order, spans, flips), (xy, u)
            self.held = [h for h in self.held if not (h.from_a == from_a and h.index in pieces)]
            names = ", ".join(str(as_written(o)) for o in order)
            self.messages.append(
                Message(
                    "INFO",
                    f"strokes {names} of the {'first' if from_a else 'second'} key are one line drawn in pieces: "
                    f"the gaps {'close' if from_a else 'open'} along the in-betweens",
                )
            )
        return out

    def _pair_strokes(self, k, i, j, flip, drawing):
        """The two KeyStrokes of pair ``k`` (the pieced side joined), and whether B is flipped."""
        if k not in self.joined:
            return StrokePair(self.ka.stroke(i), self.kb.stroke(j, flip), flip)
        joined, (xy, u) = self.joined[k]
        first = joined.strokes[0]
        if joined.side == "a":
            a = KeyStroke(first, xy, u, False, int(self.ka.strokes.material_index[first]))
            b_xy = self.kb.rg.curve(j)
            flip = pair_direction(xy, b_xy, False, bool(self.kb.rg.closed[j]), drawing.turn)
            return StrokePair(a, self.kb.stroke(j, flip), flip)
        a = self.ka.stroke(i)
        flip = pair_direction(a.xy, xy, a.closed, False, drawing.turn)
        b = KeyStroke(
            first,
            xy[::-1] if flip else xy,
            1.0 - u[::-1] if flip else u,
            False,
            int(self.kb.strokes.material_index[first]),
        )
        return StrokePair(a, b, flip)

    def _orient_by_hints(self, hinted, hints):
        """Open pairs whose hints run backwards along the second stroke are flipped (the hints
        say which way it runs): the strokes and their hints again."""
        strokes = list(self.strokes)
        flipped = False
        for k, h in hinted.items():
            a, b, flip = strokes[k]
            backwards = len(h.u_b) >= 2 and h.u_b[-1] < h.u_b[0]
            # A hint on an end of one stroke and the other end of the other: reversed too.
            on_end = np.abs(h.u_a - 0.5) >= 0.5 - END_HINT
            crossed = bool(np.any(on_end & (np.abs(h.u_a - (1.0 - h.u_b)) <= END_HINT)))
            if not b.closed and (backwards or crossed):
                strokes[k] = StrokePair(a, self.kb.stroke(b.index, not flip), not flip)
                flipped = True
        if not flipped:
            return strokes, hinted
        return strokes, pair_hints(hints, strokes, self.ka, self.kb, [])

    def _match(self, key_a, key_b, matching, hints):
        """Pairs (i, j, flip) of strokes with points (strokes without a partner are held), and
        the keys' overall motion (a Similarity). Strokes a hint joins are paired first."""
        ka, kb = self.ka, self.kb
        # Strokes without points have nothing to morph or show: leave them out, and say so.
        live_a, live_b = np.flatnonzero(key_a.sizes > 0), np.flatnonzero(key_b.sizes > 0)
        for name, key in (("first", key_a), ("second", key_b)):
            for i in np.flatnonzero(key.sizes == 0):
                self.messages.append(
                    Message("INFO", f"stroke {as_written(i)} of the {name} key has no points: left out")
                )
        forced = sorted({(h.stroke_a, h.stroke_b) for h in hints})
        live_a = np.array([i for i in live_a if i not in {a for a, _ in forced}], dtype=np.int64)
        live_b = np.array([j for j in live_b if j not in {b for _, b in forced}], dtype=np.int64)
        pairing = match_strokes(
            _live_strokes(ka.rg, live_a),
            _live_strokes(kb.rg, live_b),
            ka.rg.closed[live_a],
            kb.rg.closed[live_b],
            mode=matching,
            motion=self._hinted_motion(forced, hints),
        )
        self.held = [Held(ka, int(live_a[i]), True) for i in pairing.unmatched_a]
        self.held += [Held(kb, int(live_b[j]), False) for j in pairing.unmatched_b]
        if pairing.method != "index" or self.held:
            self.messages.append(Message("INFO", f"strokes paired by {pairing.method}: {pairing.reason}"))
        drawing = pairing.drawing
        matched = [(int(live_a[i]), int(live_b[j]), flip) for i, j, flip in pairing.pairs]
        self.travelled = {(int(live_a[i]), int(live_b[j])) for i, j in pairing.travelled}
        for i, j in sorted(self.travelled):
            self.messages.append(
                Message(
                    "INFO",
                    f"stroke {as_written(i)} -> {as_written(j)}: paired by the drawing's motion "
                    "(the shapes agree, far apart)",
                )
            )
        for i, j in forced:
            flip = pair_direction(ka.rg.curve(i), kb.rg.curve(j), ka.rg.closed[i], kb.rg.closed[j], drawing.turn)
            matched.append((i, j, flip))
        if forced:
            self.messages.append(Message("INFO", f"{len(forced)} stroke pair(s) joined by hints"))
        return sorted(matched), drawing

    def samples(self, times):
        """Every sample of every pair at morph ``times`` (T,), lifted to 3D: shape (T, K, 3).

        The samples the in-betweens are made of, the same at every time, before any pair not
        finite somewhere is moved point by point (for :mod:`.arcs`, which joins intervals)."""
        times = check_times(times)
        frames = self.pieces.merge(self.pairs.frames(times))[0].frames
        if len(times) == 0:
            return np.zeros((0, frames.shape[1], 3))
        return np.stack([self.plane.to_3d(frame) for frame in frames])

    def sample_sources(self):
        """Where every sample (:meth:`samples`) leaves and reaches the keys, as drawn: its key
        strokes (indices into ``key_a`` and ``key_b``; a line drawn in pieces: its piece) and
        arc-length fractions along them.

        Returns
        -------
        stroke_a, u_a, stroke_b, u_b : ndarray, shape (K,)
        """
        parts = self.pieces.merge(self.pairs.frames([0.0]))[0]
        # As an evaluation reads them (the fractions copied first: they may be the layout's own).
        parts.u_a, parts.u_b = parts.u_a.copy(), _as_drawn(parts, self.strokes)
        self._sources(parts)
        return parts.stroke_a, parts.u_a, parts.stroke_b, parts.u_b

    def _frames(self, times, finite_only=True, correction=None):
        """The pairs' frames at ``times`` (PairFrames) and the in-betweens (list of StrokeSet);
        ``(None, None)`` if some pair is not finite there and ``finite_only``. A ``correction``
        (:class:`.arcs.PathCorrection`) moves the samples first.

        The pairs' 2D frames never leave an evaluation (the in-betweens are lifted out of them),
        so every chunk of every evaluation stages them in one buffer the plan keeps (at most
        EVALUATE_SAMPLES samples): fresh, they would be page-faulted anew chunk after chunk in a
        bpy process."""
        staged = None
        if finite_only:  # (all times at once, for a pair not finite somewhere: fresh frames)
            size = (len(times), self.pairs.layout.offsets[-1], 2)
            if self._staged.shape[0] < size[0] or self._staged.shape[1] != size[1]:
                self._staged = np.empty(size)
            staged = self._staged[: size[0]]
        raw, marks = self.pieces.merge(self.pairs.frames(times, out=staged))
        if correction is not None:  # in the plane: the offsets' parts along its axes
            raw.frames += correction.offsets(times) @ np.stack([self.plane.u, self.plane.v], axis=1)
        parts = _finite(raw, self.strokes, times)
        if finite_only and parts is not raw:
            return None, None
        if parts is raw and self._samples is not None:
            along, values = self._samples.restore(parts)
        else:
            # The second key's fractions are along its stroke as morphed: read them back as drawn.
            # Both are rewritten here, and may be the layout's own arrays: copied first (only
            # here: a later evaluation restores the kept ones instead).
            parts.u_a, parts.u_b = parts.u_a.copy(), _as_drawn(parts, self.strokes)
            along = self._sources(parts)
            values = FrameValues(parts, self)
            if parts is raw:  # the plan's own samples, whatever the times: kept for the next frames
                self._samples = _Samples(parts, along, values)
        frames = assemble_frames(parts, self, times, values, self._recycled)
        if self.has_hints:
            for frame in frames:
                _mark_hints(frame, marks)
        if self.joined:
            frames = [cut_frame(f, self._windows(parts, along, t)) for f, t in zip(frames, times)]
        return parts, frames

    def _sources(self, parts):
        """Every sample's key strokes and fractions along them as drawn (``parts.stroke_a``,
        ``stroke_b``, ``u_a``, ``u_b``), the joined pieces read back piece by piece; returns the
        joined fractions of the pieced side, per joined pair (for the gaps)."""
        parts.stroke_a, parts.stroke_b = _sources_default(parts, self.strokes)
        along = {}
        for k, (joined, _) in self.joined.items():
            sl = slice(parts.offsets[k], parts.offsets[k + 1])
            name = "a" if joined.side == "a" else "b"
            u = getattr(parts, f"u_{name}")[sl].copy()
            along[k] = u
            stroke, local = joined.sources(u)
            getattr(parts, f"stroke_{name}")[sl] = stroke
            getattr(parts, f"u_{name}")[sl] = local
        return along

    def _windows(self, parts, along, t):
        """The stretches of each joined pair's in-between that its gaps leave out at ``t``: dict
        stroke -> list of ``(lo, hi)`` fractional sample indices (gaps open from their middles in
        the second key drawn in pieces, close to them in the first)."""
        out = {}
        for k, (joined, _) in self.joined.items():
            grow = t if joined.side == "b" else 1.0 - t
            u = along[k]
            ranges = []
            index = np.arange(len(u), dtype=np.float64)
            backwards = len(u) > 1 and u[-1] < u[0]  # the samples run against the joined stroke
            for g0, g1 in joined.gaps():
                m = 0.5 * (g0 + g1)
                ends = [m - grow * (m - g0), m + grow * (g1 - m)]
                if backwards:
                    hi, lo = len(u) - 1 - np.interp(ends, u[::-1], index)
                else:
                    lo, hi = np.interp(ends, u, index)
                ranges.append((float(lo), float(hi)))
            out[k] = ranges
        return out

    def evaluate(self, times, correction=None):
        """The in-betweens at ``times``.

        Parameters
        ----------
        times : array_like, shape (T,)
            Morph times in [0, 1] (already eased; values outside are clamped).
        correction : arcs.PathCorrection, optional
            Offsets of every sample (:meth:`samples`) along its path, zero at both keys: the
            paths joined smoothly to the neighbouring intervals' (:func:`.arcs.smooth_chain`).

        Returns
        -------
        InbetweenResult
        """
        times = check_times(times)
        result = InbetweenResult(frames=[], messages=list(self.messages))
        self._recycled.begin()
        # A few times at once: one chunk's samples are staged, not every frame's (their 3D
        # frames are what the result keeps). Should a chunk turn out not finite, every time is
        # taken at once, so that the pairs' reports are the same whatever the chunking.
        step = max(1, EVALUATE_SAMPLES // max(self.pairs.layout.offsets[-1], 1))
        chunks = [times[i : i + step] for i in range(0, len(times), step)] or [times]
        for chunk in chunks:
            parts, frames = self._frames(chunk, correction=correction)
            if parts is None:
                parts, result.frames = self._frames(times, finite_only=False, correction=correction)
                break
            result.frames += frames
        for k, (a, b, flip) in enumerate(self.strokes):
            travelled = (a.index, b.index) in self.travelled
            report, messages = pair_report(a, b, flip, parts.used[k], parts.notes[k], travelled)
            result.pairs.append(report)
            result.messages += messages
            if k in self.joined:  # the other pieces of a line drawn in pieces: part of this pair
                joined = self.joined[k][0]
                whole = b.index if joined.side == "a" else a.index
                result.pairs += [piece_report(piece, joined.side, whole) for piece in joined.strokes[1:]]
        for h in self.held:
            report, message = unmatched_report(h.index, h.from_a, self.unmatched)
            result.pairs.append(report)
            result.messages.append(message)
        result.messages.extend(self.planarity)
        self._recycled.end()
        return result


class _Samples:
    """What a plan's samples take from the keys, the same at every time (they only move): their
    fractions and key strokes as drawn, the joined pieces' fractions (``along``) and their
    FrameValues. Made at the first evaluation, so later ones (a redo, the next chunk of times)
    only move the samples and mix. A pair moved point by point instead (not finite at some
    time) has other samples: those are made afresh each time."""

    def __init__(self, parts, along, values):
        self.sources = parts.u_a, parts.u_b, parts.stroke_a, parts.stroke_b
        self.along, self.values = along, values

    def restore(self, parts):
        """Give ``parts`` (the plan's samples at other times) the kept sources; ``(along, values)``."""
        parts.u_a, parts.u_b, parts.stroke_a, parts.stroke_b = self.sources
        return self.along, self.values


def _live_strokes(rg, live):
    """The strokes ``live`` (ndarray of int) of a key's Ragged ``rg``, for matching: the Ragged
    itself when that is all of them (no per-stroke list to batch again), else a list of arrays."""
    if len(live) == len(rg):
        return rg
    return [rg.curve(i) for i in live]


def _mark_hints(frame, marks):
    """Give an in-between the hint attribute: hint k on the one sample that is its image."""
    values = np.zeros(len(frame.positions), dtype=np.int64)
    for index, number in marks:
        values[index] = number
    frame.point_attributes[HINT] = values
    frame.attribute_types.setdefault(HINT, "INT")


def _sources_default(parts, strokes):
    sizes = np.diff(parts.offsets)
    return (
        np.repeat(np.array([a.index for a, _, _ in strokes], dtype=np.int64), sizes),
        np.repeat(np.array([b.index for _, b, _ in strokes], dtype=np.int64), sizes),
    )


def _curves(a, b):
    return PairCurves(a.xy, a.u, a.closed, b.xy, b.u, b.closed)


def _as_drawn(parts, strokes):
    """``u_b`` along each second stroke as drawn (the pipeline sees flipped strokes reversed)."""
    u_b = parts.u_b.copy()
    for k, (_, b, flip) in enumerate(strokes):
        if flip:
            sl = slice(parts.offsets[k], parts.offsets[k + 1])
            u_b[sl] = reversed_fractions(u_b[sl], b.closed)
    return u_b


def _finite(parts, strokes, times):
    """The pairs' frames with any pair whose frames are not finite moved point by point instead."""
    if np.isfinite(parts.frames.sum()):  # (a sum of finite frames cannot overflow: MAX_COORDINATE)
        return parts
    frames, u_a, u_b, closed, used, notes = (
        [],
        [],
        [],
        parts.closed.copy(),
        list(parts.used),
        [list(n) for n in parts.notes],
    )
    for k, (a, b, _) in enumerate(strokes):
        f, ua, ub = parts.pair(k)
        if not np.all(np.isfinite(f)):
            morph = point_motion(a.xy, a.u, b.xy, b.u)
            f, ua, ub = morph.frames(times), morph.u_p, morph.u_q
            closed[k], used[k] = False, PairMorphs((STRAIGHT_POINT_MOTION,), route=Route.POINT_MOTION)
            notes[k].append("the morph produced non-finite points")
        frames.append(f), u_a.append(ua), u_b.append(ub)
    offsets = np.concatenate([[0], np.cumsum([f.shape[1] for f in frames])])
    return PairFrames(
        np.concatenate(frames, axis=1), offsets, np.concatenate(u_a), np.concatenate(u_b), closed, used, notes
    )


def _planarity_messages(pts, plane):
    """A warning when the keys (both keys' points, shape (N, 3)) are not flat, as a list (empty
    when they are)."""
    if len(pts) < 3:
        return []
    # Column by column (a reduction along axis 0 of an (N, 3) array is many times slower).
    scale = float(np.linalg.norm([np.ptp(pts[:, k]) for k in range(3)]))
    worst = plane.farthest(pts)
    if scale > 0 and worst > PLANARITY * scale:
        return [
            Message(
                "WARNING",
                f"the keys are not flat (points up to {worst:.3g} off the drawing plane): strokes were "
                "morphed in the best-fit plane, keeping each point's offset from it",
            )
        ]
    return []
