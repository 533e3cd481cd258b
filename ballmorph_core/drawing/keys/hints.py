"""Correspondence hints: points the animator pins to each other across the keys.

A key drawing's INT point attribute ``ballmorph_hint`` (:data:`HINT`) numbers points: 0 for
none, ``k >= 1`` for hint ``k``. The point with hint ``k`` on the first key corresponds to the
point with hint ``k`` on the second: it travels there, and every in-between carries hint ``k``
on exactly one point, that point's image.

* A hint on two strokes makes them a pair, whatever the automatic matching says.
* A hinted pair is registered by the similarity that best takes its first stroke onto the
  second with the hints corresponding (arc length mapped piecewise linearly between hints), and
  cut at its hints into pieces; each piece goes down the ball route on that one carrier, its ends
  (the hinted points) moved straight to their partners, so the pieces stay joined and the
  hinted points travel exactly where the animator said.
* Bad hints are reported with what to fix and ignored, never failing the run: a number on one
  key only, a number on several points of one key, a stroke hinted to several strokes, hints
  out of order along a pair (the longest run in order is kept).
"""

from dataclasses import dataclass, field, replace

import numpy as np

from ... import tolerances as tol
from ...geometry.polyline import curve_length, subcurve
from ...geometry.procrustes import similarity_fit
from ...geometry.ragged import Ragged
from ...geometry.similarity import as_complex, from_complex
from ..frames.layout import PairFrames
from ..pair_morphs.registration import FIT_SAMPLES, Fits, Motions, motions, similarity_matrices
from ..strokes import Message, PairMorphs, as_written

__all__ = [
    "HINT",
    "END_HINT",
    "Hint",
    "hinted_fit",
    "KeyHints",
    "PairHints",
    "Pieces",
    "key_hints",
    "common_hints",
    "pair_hints",
]

#: The point attribute holding hint numbers (a contract: outside checks write and read it).
HINT = "ballmorph_hint"


@dataclass
class Hint:
    """Hint ``number`` at point ``point_a`` of stroke ``stroke_a`` and its partner on key B."""

    number: int
    stroke_a: int
    point_a: int
    stroke_b: int
    point_b: int


@dataclass
class KeyHints:
    """The usable hints of one key: number -> (stroke, point)."""

    where: dict = field(default_factory=dict)


def key_hints(strokes, name, messages):
    """The hints of one key (KeyHints); a number on several points is reported and dropped.

    Parameters
    ----------
    strokes : StrokeSet
    name : str
        'first' or 'second', for the messages.
    messages : list of Message
        Appended to.
    """
    values = strokes.point_attributes.get(HINT)
    out = KeyHints()
    if values is None:
        return out
    values = np.asarray(values).reshape(len(strokes.positions), -1)[:, 0].astype(np.int64)
    points = np.flatnonzero(values > 0)
    owner = np.searchsorted(strokes.offsets, points, side="right") - 1
    for number in np.unique(values[points]):
        at = points[values[points] == number]
        if len(at) > 1:
            messages.append(
                Message("WARNING", f"hint {number} is on {len(at)} points of the {name} key: keep it on one (ignored)")
            )
            continue
        out.where[int(number)] = (int(owner[points == at[0]][0]), int(at[0]))
    return out


def common_hints(ha, hb, messages):
    """Hints on both keys (list of Hint, by number); one-key hints are reported and dropped, and
    so are the hints of a stroke hinted to several strokes but the most numerous."""
    for name, only in (("first", ha.where.keys() - hb.where.keys()), ("second", hb.where.keys() - ha.where.keys())):
        for number in sorted(only):
            other = "second" if name == "first" else "first"
            messages.append(
                Message("WARNING", f"hint {number} is on the {name} key only: add it on the {other} key too (ignored)")
            )
    hints = [Hint(k, *ha.where[k], *hb.where[k]) for k in sorted(ha.where.keys() & hb.where.keys())]
    keep = []
    for attr, other in (("stroke_a", "stroke_b"), ("stroke_b", "stroke_a")):
        keep = []
        for stroke in sorted({getattr(h, attr) for h in hints}):
            mine = [h for h in hints if getattr(h, attr) == stroke]
            partners = [getattr(h, other) for h in mine]
            best = max(set(partners), key=lambda s: (partners.count(s), -s))
            for h in mine:
                if getattr(h, other) == best:
                    keep.append(h)
                else:
                    messages.append(
                        Message(
                            "WARNING",
                            f"hint {h.number} pairs stroke {as_written(h.stroke_a)} with stroke "
                            f"{as_written(h.stroke_b)}, but other hints pair them otherwise: move it (ignored)",
                        )
                    )
        hints = sorted(keep, key=lambda h: h.number)
    return hints


@dataclass
class PairHints:
    """The hints of one pair, in order along it.

    Attributes
    ----------
    u_a, u_b : ndarray, shape (K,)
        Arc-length fractions of the hinted points along the two strokes as morphed.
    numbers : ndarray of int, shape (K,)
    """

    u_a: np.ndarray
    u_b: np.ndarray
    numbers: np.ndarray


def _longest_increasing(values):
    """Indices of a longest strictly increasing subsequence of ``values`` (list of int)."""
    best = []
    n = len(values)
    length, prev = [1] * n, [-1] * n
    for i in range(n):
        for j in range(i):
            if values[j] < values[i] and length[j] + 1 > length[i]:
                length[i], prev[i] = length[j] + 1, j
    if not n:
        return best
    i = int(np.argmax(length))
    while i >= 0:
        best.append(i)
        i = prev[i]
    return best[::-1]


def pair_hints(hints, pairs, ka, kb, messages):
    """The hints of every matched pair, in order (dict pair index -> PairHints).

    Parameters
    ----------
    hints : list of Hint
    pairs : list of (KeyStroke, KeyStroke, bool)
        The plan's stroke pairs (the second as morphed: flipped where the matching flipped it).
    ka, kb : ProjectedKey
    messages : list of Message
    """
    out = {}
    by_strokes = {(a.index, b.index): k for k, (a, b, _) in enumerate(pairs)}
    for (sa, sb), k in by_strokes.items():
        mine = [h for h in hints if (h.stroke_a, h.stroke_b) == (sa, sb)]
        if not mine:
            continue
        a, b, flip = pairs[k]
        u_a = np.array([ka.u[h.point_a] for h in mine])
        u_b = np.array([kb.u[h.point_b] for h in mine])
        if flip:
            u_b = (1.0 - u_b) % 1.0 if b.closed else 1.0 - u_b
        order = np.argsort(u_a, kind="stable")
        u_a, u_b, numbers = u_a[order], u_b[order], np.array([mine[i].number for i in order])
        if b.closed and len(u_b) > 1:  # read B's fractions from where A's first hint lands
            u_b = np.where(u_b < u_b[0], u_b + 1.0, u_b)
        keep = _longest_increasing(u_b.tolist())
        for i in sorted(set(range(len(numbers))) - set(keep)):
            messages.append(
                Message(
                    "WARNING",
                    f"hint {numbers[i]} is out of order along strokes {as_written(sa)} -> {as_written(sb)}: "
                    "move it (ignored)",
                )
            )
        out[k] = PairHints(u_a[keep], u_b[keep], numbers[keep])
    return out


def _along(xy, u, closed, fractions):
    """Points at arc-length fractions of a stroke whose points sit at fractions ``u``."""
    length = curve_length(xy, closed)
    ring = Ragged.from_list([xy], [closed])
    s = np.asarray(fractions, dtype=np.float64) * length
    return ring.point_at(np.zeros(len(s), np.int64), np.mod(s, length) if closed else s)


def hinted_fit(a, b, hints):
    """The similarity ``z -> alpha z + beta`` (complex) best taking stroke ``a`` onto ``b`` with
    the hints corresponding: arc length mapped piecewise linearly between them."""
    knots_a, knots_b = hints.u_a, hints.u_b
    if a.closed:  # one lap on from the first hint, on both
        knots_a, knots_b = np.r_[knots_a, knots_a[0] + 1.0], np.r_[knots_b, knots_b[0] + 1.0]
        f = knots_a[0] + np.arange(FIT_SAMPLES) / FIT_SAMPLES
    else:
        knots_a, knots_b = np.r_[0.0, knots_a, 1.0], np.r_[0.0, knots_b, 1.0]
        f = np.linspace(0.0, 1.0, FIT_SAMPLES)
    g = np.interp(f, knots_a, knots_b)
    za, zb = as_complex(_along(a.xy, a.u, a.closed, f)), as_complex(_along(b.xy, b.u, b.closed, g))
    ca, cb = za.mean(), zb.mean()
    if len(hints.numbers) == 1 and not a.closed:
        # One hint on a stroke: it maps onto its partner exactly, the rest by least squares.
        ca, cb = as_complex(_along(a.xy, a.u, False, hints.u_a)), as_complex(_along(b.xy, b.u, False, hints.u_b))
        ca, cb = complex(ca[0]), complex(cb[0])
    return similarity_fit(za, zb, ca, cb)


#: A hint within this fraction of a stroke's end is on that end.
END_HINT = 1e-9


@dataclass
class _Group:
    """The pieces of one pair: their indices in the expanded list, ranges along the pair's
    strokes (fractions, possibly past 1 on loops), the hint number at each breakpoint (0: none;
    ``numbers[i]`` at the start of piece ``i``, the last at the end of the last piece), and
    whether the pair is a loop."""

    first: int
    count: int
    ranges_a: list
    ranges_b: list
    numbers: list
    loop: bool = False
    cut: bool = False


class Pieces:
    """The plan's pairs with the hinted ones cut at their hints.

    Parameters
    ----------
    curves : list of PairCurves
        One per pair.
    pairs : list of (KeyStroke, KeyStroke, bool)
    hinted : dict of int to PairHints
    carrier : str
    drawing : Similarity
    make_curves : callable
        ``(KeyStroke, KeyStroke) -> PairCurves``.

    Attributes
    ----------
    curves : list of PairCurves
        What the pipeline plans: unhinted pairs as given, hinted ones as their pieces.
    """

    def __init__(self, curves, pairs, hinted, carrier, drawing, make_curves):
        self.groups, self.curves = [], []
        self.plain = not hinted  # no pair is cut: merging is the identity
        for k, pc in enumerate(curves):
            if k not in hinted:
                self.groups.append(_Group(len(self.curves), 1, [(0.0, 1.0)], [(0.0, 1.0)], [0, 0], pc.closed_a))
                self.curves.append(pc)
                continue
            a, b, _ = pairs[k]
            motion = _pair_motion(a, b, hinted[k], carrier, drawing)
            group = _cut(a, hinted[k], len(self.curves))
            for (u0, u1), (v0, v1) in zip(group.ranges_a, group.ranges_b):
                piece = make_curves(_piece(a, u0, u1), _piece(b, v0, v1))
                piece.motion = motion
                self.curves.append(piece)
            self.groups.append(group)

    def merge(self, parts):
        """The pieces' frames joined back into their pairs' (PairFrames), and the samples that
        carry each hint: list of (sample index, number) over the joined samples.

        Consecutive pieces share their breakpoint (kept once); a loop's last piece ends where
        its first starts.
        """
        if self.plain:  # the same frames and fractions (not copied), the same notes once each
            notes = [list(dict.fromkeys(n)) for n in parts.notes]
            return replace(parts, used=list(parts.used), notes=notes), []
        frames, u_a, u_b, used, notes, closed, marks = [], [], [], [], [], [], []
        start = 0
        for g in self.groups:
            loop, cut = (g.loop, True) if g.cut else (bool(parts.closed[g.first]), False)
            f_all, ua_all, ub_all, last = [], [], [], 0
            for i in range(g.count):
                f, ua, ub = parts.pair(g.first + i)
                (a0, a1), (b0, b1) = g.ranges_a[i], g.ranges_b[i]
                stop = f.shape[1] - (1 if loop and cut and i == g.count - 1 else 0)
                keep = slice(1 if i else 0, stop)
                if g.numbers[i]:  # the piece's first sample: the previous piece's last
                    marks.append((start + (last if i else 0), g.numbers[i]))
                f_all.append(f[:, keep])
                ua_all.append((a0 + ua * (a1 - a0))[keep])
                ub_all.append((b0 + ub * (b1 - b0))[keep])
                last = sum(x.shape[1] for x in f_all) - 1
            if g.numbers[-1] and not (loop and cut):
                marks.append((start + last, g.numbers[-1]))
            f = np.concatenate(f_all, axis=1)
            frames.append(f)
            u_a.append(np.mod(np.concatenate(ua_all), 1.0) if loop and cut else np.concatenate(ua_all))
            u_b.append(np.mod(np.concatenate(ub_all), 1.0) if loop and cut else np.concatenate(ub_all))
            used.append(PairMorphs.union(parts.used[g.first + i] for i in range(g.count)))
            notes.append(list(dict.fromkeys(n for i in range(g.count) for n in parts.notes[g.first + i])))
            closed.append(loop)
            start += f.shape[1]
        merged = PairFrames(
            np.concatenate(frames, axis=1) if frames else parts.frames[:, :0],
            np.concatenate([[0], np.cumsum([f.shape[1] for f in frames])]).astype(np.int64),
            np.concatenate(u_a) if u_a else np.zeros(0),
            np.concatenate(u_b) if u_b else np.zeros(0),
            np.array(closed, dtype=bool),
            used,
            notes,
        )
        return merged, marks


def _pair_motion(a, b, hints, carrier, drawing):
    """The carrier of a hinted pair (Motions of one pair), from :func:`hinted_fit`."""
    if carrier == "none":
        return Motions.identity(1)
    P = Ragged.from_list([a.xy], [a.closed])
    alpha, beta = hinted_fit(a, b, hints)
    if abs(alpha) <= 1e-9:  # the hints squeeze the stroke to a point: move it, do not squash it
        alpha, beta = 1.0 + 0j, complex(as_complex(b.xy).mean() - as_complex(a.xy).mean())
    fits = Fits(similarity_matrices(np.array([alpha])), from_complex(np.array([beta])), np.zeros(1))
    size = np.array([max(float(np.ptp(np.r_[a.xy, b.xy], axis=0).max()), tol.TINY)])
    still = abs(alpha - 1.0) <= 1e-12 and abs(beta) <= 1e-12 * size[0]
    kind = "rigid" if carrier == "rigid" else "similarity"
    return motions(P, fits, kind, size, np.array([not still]), drawing, turned=np.ones(1, bool))


def _cut(a, hints, first):
    """A hinted pair's pieces (a _Group): fraction ranges on both strokes, hints at breakpoints."""
    ka, kb, numbers = list(hints.u_a), list(hints.u_b), [int(n) for n in hints.numbers]
    if a.closed:
        ka, kb, numbers = ka + [ka[0] + 1.0], kb + [kb[0] + 1.0], numbers + [numbers[0]]
        return _Group(first, len(ka) - 1, list(zip(ka[:-1], ka[1:])), list(zip(kb[:-1], kb[1:])), numbers, True, True)
    # A stroke's ends are breakpoints too; a hint on an end is that end's number.
    head = numbers.pop(0) if ka[0] <= END_HINT or kb[0] <= END_HINT else 0
    if head:
        ka, kb = ka[1:], kb[1:]
    tail = numbers.pop() if ka and (ka[-1] >= 1.0 - END_HINT or kb[-1] >= 1.0 - END_HINT) else 0
    if tail:
        ka, kb = ka[:-1], kb[:-1]
    ka, kb = [0.0, *ka, 1.0], [0.0, *kb, 1.0]
    ranges_a, ranges_b = list(zip(ka[:-1], ka[1:])), list(zip(kb[:-1], kb[1:]))
    return _Group(first, len(ranges_a), ranges_a, ranges_b, [head, *numbers, tail], False, True)


def _piece(stroke, u0, u1):
    """The part of a KeyStroke between fractions ``u0`` and ``u1`` (may pass 1 on a loop), as a
    KeyStroke of an open stroke with its own fractions."""
    length = curve_length(stroke.xy, stroke.closed)
    xy = subcurve(stroke.xy, stroke.closed, u0 * length, u1 * length)
    s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))]
    u = s / s[-1] if s[-1] > 0 else np.linspace(0.0, 1.0, len(xy))
    return type(stroke)(stroke.index, xy, u, False, stroke.material)
