"""In-betweens of whole drawings: what the Blender operator calls.

A drawing is a :class:`StrokeSet` in Blender's own layout (flat point arrays plus stroke
offsets, like a Grease Pencil drawing's curves geometry), so the operator moves data with
``foreach_get``/``foreach_set`` and never loops over points in Python.

:func:`inbetween` pairs the strokes of two keys, morphs every pair in the plane that fits both
keys, carries per-point attributes along the correspondence, and returns one StrokeSet per
requested time plus messages for the animator. A pair that the requested morph cannot handle
falls back to a documented morph and is reported; nothing is dropped silently.
"""

from dataclasses import dataclass, field

import numpy as np

from . import tolerances as tol
from .batch import morph_pairs
from .curves import as_curve, cumulative_length
from .errors import BallMorphError, InvalidCurveError
from .matching import MODES as MATCHINGS
from .matching import match_strokes
from .morphs import make_morph
from .options import check_option
from .pair import BALL_METHODS, morph_pair
from .plane import fit_plane
from .registration import CARRIERS

__all__ = [
    "StrokeSet",
    "Message",
    "PairReport",
    "InbetweenResult",
    "inbetween",
    "FALLBACK_METHOD",
    "CARRIERS",
    "MATCHINGS",
    "UNMATCHED",
]

#: The morph used when the requested one cannot handle a stroke pair.
FALLBACK_METHOD = "linear-interpolation"


@dataclass
class StrokeSet:
    """The strokes of one drawing, in Blender's curves-geometry layout.

    Attributes
    ----------
    positions : ndarray, shape (N, 3)
    offsets : ndarray of int, shape (S + 1,)
        Stroke ``i`` owns points ``offsets[i]:offsets[i + 1]``.
    cyclic : ndarray of bool, shape (S,)
    material_index : ndarray of int, shape (S,)
    radius : ndarray, shape (N,)
    opacity : ndarray, shape (N,)
    vertex_color : ndarray, shape (N, 4)
    selected : ndarray of bool, shape (S,)
    origin : ndarray of int, shape (S, 2)
        For an in-between: the strokes of the first and second key it comes from (-1 for
        none), so the caller can carry attributes the core does not interpolate.
    """

    positions: np.ndarray
    offsets: np.ndarray
    cyclic: np.ndarray
    material_index: np.ndarray
    radius: np.ndarray
    opacity: np.ndarray
    vertex_color: np.ndarray
    selected: np.ndarray = None
    origin: np.ndarray = None

    def __post_init__(self):
        self.positions = np.asarray(self.positions, dtype=np.float64).reshape(-1, 3)
        self.offsets = np.asarray(self.offsets, dtype=np.int64).reshape(-1)
        n, s = len(self.positions), len(self.offsets) - 1
        if s < 0 or self.offsets[0] != 0 or self.offsets[-1] != n or np.any(np.diff(self.offsets) < 0):
            raise InvalidCurveError(
                f"offsets: must rise from 0 to the point count {n}, got {self.offsets.tolist()[:8]}"
            )
        self.cyclic = np.asarray(self.cyclic, dtype=bool).reshape(-1)
        self.material_index = np.asarray(self.material_index, dtype=np.int64).reshape(-1)
        self.radius = np.asarray(self.radius, dtype=np.float64).reshape(-1)
        self.opacity = np.asarray(self.opacity, dtype=np.float64).reshape(-1)
        self.vertex_color = np.asarray(self.vertex_color, dtype=np.float64).reshape(-1, 4)
        self.selected = np.ones(s, dtype=bool) if self.selected is None else np.asarray(self.selected, dtype=bool)
        self.origin = (
            np.full((s, 2), -1, dtype=np.int64)
            if self.origin is None
            else np.asarray(self.origin, dtype=np.int64).reshape(-1, 2)
        )
        for name, arr, size in (
            ("cyclic", self.cyclic, s),
            ("material_index", self.material_index, s),
            ("selected", self.selected, s),
            ("origin", self.origin, s),
            ("radius", self.radius, n),
            ("opacity", self.opacity, n),
            ("vertex_color", self.vertex_color, n),
        ):
            if len(arr) != size:
                raise InvalidCurveError(f"{name}: expected {size} values, got {len(arr)}")

    def __len__(self):
        return len(self.offsets) - 1

    @property
    def sizes(self):
        """Points per stroke, shape (S,)."""
        return np.diff(self.offsets)

    def points(self, i):
        """Slice of the point arrays for stroke ``i``."""
        return slice(int(self.offsets[i]), int(self.offsets[i + 1]))

    @classmethod
    def empty(cls):
        """A drawing with no strokes."""
        return cls(np.zeros((0, 3)), [0], [], [], [], [], np.zeros((0, 4)))

    @classmethod
    def from_strokes(cls, strokes, cyclic=None, material_index=None, radius=None, opacity=None, vertex_color=None):
        """Build from a list of (n_i, 3) or (n_i, 2) arrays (2D points get y = 0: the XZ canvas).

        Per-stroke attributes default to open strokes, material 0, radius 0.01, opacity 1 and
        transparent black; per-point attributes may be given as lists of per-stroke arrays.
        """
        pts = []
        for s in strokes:
            s = np.asarray(s, dtype=np.float64)
            if s.ndim == 2 and s.shape[1] == 2:
                s = np.c_[s[:, 0], np.zeros(len(s)), s[:, 1]]
            pts.append(s.reshape(-1, 3))
        sizes = [len(p) for p in pts]
        n = int(sum(sizes))

        def per_point(values, default, width=None):
            if values is None:
                shape = (n,) if width is None else (n, width)
                return np.full(shape, default, dtype=np.float64)
            return np.concatenate([np.asarray(v, dtype=np.float64) for v in values]) if len(values) else np.zeros(0)

        return cls(
            np.concatenate(pts) if pts else np.zeros((0, 3)),
            np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64),
            np.zeros(len(pts), bool) if cyclic is None else cyclic,
            np.zeros(len(pts), np.int64) if material_index is None else material_index,
            per_point(radius, 0.01),
            per_point(opacity, 1.0),
            per_point(vertex_color, 0.0, 4).reshape(-1, 4),
        )

    @classmethod
    def concatenate(cls, parts):
        """Join StrokeSets into one (strokes in order)."""
        parts = list(parts)
        if not parts:
            return cls.empty()
        sizes = np.concatenate([p.sizes for p in parts])
        return cls(
            np.concatenate([p.positions for p in parts]),
            np.concatenate([[0], np.cumsum(sizes)]),
            np.concatenate([p.cyclic for p in parts]),
            np.concatenate([p.material_index for p in parts]),
            np.concatenate([p.radius for p in parts]),
            np.concatenate([p.opacity for p in parts]),
            np.concatenate([p.vertex_color for p in parts]),
            np.concatenate([p.selected for p in parts]),
            np.concatenate([p.origin for p in parts]),
        )

    def subset(self, indices):
        """The strokes at ``indices``, in that order (StrokeSet)."""
        idx = np.asarray(indices, dtype=np.int64)
        sizes = self.sizes[idx]
        pts = (
            np.concatenate([np.arange(self.offsets[i], self.offsets[i + 1]) for i in idx])
            if len(idx)
            else np.zeros(0, np.int64)
        )
        return StrokeSet(
            self.positions[pts],
            np.concatenate([[0], np.cumsum(sizes)]),
            self.cyclic[idx],
            self.material_index[idx],
            self.radius[pts],
            self.opacity[pts],
            self.vertex_color[pts],
            self.selected[idx],
            self.origin[idx],
        )


@dataclass
class Message:
    """Something the animator should know. ``level`` is INFO, WARNING or ERROR."""

    level: str
    text: str


@dataclass
class PairReport:
    """What happened to one stroke pair.

    Attributes
    ----------
    stroke_a, stroke_b : int or None
        Stroke indices in the two keys (None for a stroke with no partner).
    method : str
        The morph actually used (or 'appear' / 'disappear' / 'hold').
    reason : str
        Why a fallback was used ('' when the requested morph worked).
    """

    stroke_a: int
    stroke_b: int
    method: str
    reason: str = ""


@dataclass
class InbetweenResult:
    """Frames and what happened.

    Attributes
    ----------
    frames : list of StrokeSet
        One per requested time.
    messages : list of Message
    pairs : list of PairReport
    """

    frames: list
    messages: list = field(default_factory=list)
    pairs: list = field(default_factory=list)


def _fractions(points2d, closed):
    """Arc-length fraction of each vertex of a stroke, shape (n,) (all 0 for a dot)."""
    if len(points2d) < 2:
        return np.zeros(len(points2d))
    cum = cumulative_length(points2d, closed)
    total = cum[-1]
    return cum[: len(points2d)] / total if total > 0 else np.linspace(0.0, 1.0, len(points2d))


def _sample(values, fractions, u, closed):
    """Per-point values of a stroke at arc-length fractions ``u`` (periodic for loops)."""
    if len(values) == 1:
        return np.repeat(values, len(u), axis=0)
    if values.ndim == 1:
        return np.interp(u, fractions, values, period=1.0 if closed else None)
    return np.stack(
        [np.interp(u, fractions, values[:, c], period=1.0 if closed else None) for c in range(values.shape[1])], axis=1
    )


class _Stroke:
    """One stroke of a key, projected into the drawing plane."""

    def __init__(self, strokes, index, plane):
        sl = strokes.points(index)
        self.index = index
        self.xy, self.depth = plane.to_2d(strokes.positions[sl])
        self.closed = bool(strokes.cyclic[index])
        self.material = int(strokes.material_index[index])
        self.radius = strokes.radius[sl]
        self.opacity = strokes.opacity[sl]
        self.color = strokes.vertex_color[sl]
        self.u = _fractions(self.xy, self.closed)

    def reversed(self):
        """The same stroke traversed backwards (a loop keeps its first point)."""
        out = object.__new__(_Stroke)
        out.__dict__.update(self.__dict__)
        order = np.r_[0, np.arange(len(self.xy) - 1, 0, -1)] if self.closed else np.arange(len(self.xy))[::-1]
        for name in ("xy", "depth", "radius", "opacity", "color"):
            setattr(out, name, getattr(self, name)[order])
        out.u = _fractions(out.xy, out.closed)
        return out

    def attributes_at(self, u):
        return (
            _sample(self.depth, self.u, u, self.closed),
            _sample(self.radius, self.u, u, self.closed),
            _sample(self.opacity, self.u, u, self.closed),
            _sample(self.color, self.u, u, self.closed),
        )


def _dot_frames(a, b, times):
    """Strokes with fewer than two distinct points: move them straight, point by point."""
    k = max(len(a.xy), len(b.xy))
    u = np.linspace(0.0, 1.0, k)
    xa, xb = _sample(a.xy, a.u, u, False), _sample(b.xy, b.u, u, False)
    return [(1 - t) * xa + t * xb for t in times], u, u


def _pair_frames(a, b, times, method, carrier, spacing):
    """Frames, attribute fractions and report of one stroke pair; never raises BallMorphError.

    Returns (frames, u_a, u_b, closed, used, notes).
    """
    closed = a.closed and b.closed
    notes = []
    if a.closed != b.closed:
        notes.append("one key's stroke is cyclic and the other's is not: morphed as open strokes")
    try:
        P = as_curve(a.xy, "P", closed)
        Q = as_curve(b.xy, "Q", closed)
    except InvalidCurveError as exc:
        frames, ua, ub = _dot_frames(a, b, times)
        return frames, ua, ub, False, "straight point motion", [f"too few distinct points ({exc})"]
    try:
        outcome = morph_pair(P, Q, closed, method, carrier, spacing)
        morph, used = outcome.morph, outcome.used
        notes += outcome.notes
    except BallMorphError as exc:  # the fallback itself failed: never lose the pair
        morph = make_morph(P, Q, FALLBACK_METHOD, closed=closed, spacing=spacing)
        used = FALLBACK_METHOD
        notes.append(str(exc))
    frames = [morph(t) for t in times]
    if not all(np.all(np.isfinite(f)) for f in frames):
        frames, ua, ub = _dot_frames(a, b, times)
        return frames, ua, ub, False, "straight point motion", notes + ["the morph produced non-finite points"]
    return frames, morph.u_p, morph.u_q, morph.closed, used, notes


#: What happens to a stroke without a partner in the other key.
UNMATCHED = ("MIDDLE", "HOLD")


def inbetween(
    key_a,
    key_b,
    times,
    method="circular-ball",
    carrier="SIMILARITY",
    matching="AUTO",
    unmatched="MIDDLE",
    spacing=None,
):
    """In-between drawings of two keys.

    Parameters
    ----------
    key_a, key_b : StrokeSet
        The two keys (not modified).
    times : array_like, shape (T,)
        Morph times in [0, 1] (already eased).
    method : str
        A method of :data:`~ballmorph_core.METHODS`.
    carrier : {'SIMILARITY', 'RIGID', 'NONE'}
        Carrier motion for strokes that do not share endpoints (see
        :mod:`~ballmorph_core.registration`); 'NONE' is the paper's pure ball-morph.
    matching : {'AUTO', 'INDEX'}
        How strokes of the two keys are paired (see :mod:`~ballmorph_core.matching`).
    unmatched : {'MIDDLE', 'HOLD'}
        A stroke without a partner appears (or disappears) at t = 0.5 ('MIDDLE'), or is held
        on every in-between ('HOLD').
    spacing : float, optional
        Geodesic sample spacing for every pair (default: each pair's own).

    Returns
    -------
    InbetweenResult

    Notes
    -----
    Strokes are paired by :func:`~ballmorph_core.matching.match_strokes` (by index when the
    counts agree and the shapes fit, as Blender does; otherwise by an optimal assignment on a
    shape distance); a stroke of the second key running the other way is flipped first. Each
    pair goes through :func:`~ballmorph_core.pair.morph_pair` (carrier, crossing splits,
    composite and linear fallbacks), so a pair never aborts the others.
    """
    from .morphs import METHODS  # local: the registry is complete once the package is imported

    check_option("method", method, METHODS)
    check_option("carrier", carrier, CARRIERS)
    check_option("matching", matching, MATCHINGS)
    check_option("unmatched", unmatched, UNMATCHED)
    times = np.asarray(times, dtype=np.float64).reshape(-1)
    if not np.all(np.isfinite(times)):
        raise InvalidCurveError("times: must be finite numbers in [0, 1]")
    plane = fit_plane(np.concatenate([key_a.positions, key_b.positions]))
    result = InbetweenResult(frames=[[] for _ in times])
    strokes_a = [_Stroke(key_a, i, plane) for i in range(len(key_a))]
    strokes_b = [_Stroke(key_b, i, plane) for i in range(len(key_b))]
    pairing = match_strokes(
        [s.xy for s in strokes_a],
        [s.xy for s in strokes_b],
        np.array([s.closed for s in strokes_a], dtype=bool),
        np.array([s.closed for s in strokes_b], dtype=bool),
        mode=matching,
    )
    if pairing.method != "index" or pairing.unmatched_a or pairing.unmatched_b:
        result.messages.append(Message("INFO", f"strokes paired by {pairing.method}: {pairing.reason}"))
    pairs = [(strokes_a[i], strokes_b[j].reversed() if flip else strokes_b[j], flip) for i, j, flip in pairing.pairs]
    fast = _fast_path(pairs, times, method, carrier, spacing)
    for (a, b, flip), done in zip(pairs, fast):
        if done is None:
            frames, ua, ub, closed, used, notes = _pair_frames(a, b, times, method, carrier, spacing)
        else:
            frames, ua, ub, closed, used, notes = done.frames, done.u_p, done.u_q, done.closed, done.used, done.notes
        _emit_pair(result, a, b, times, plane, flip, frames, ua, ub, closed, used, notes)
    for i in pairing.unmatched_a:
        _emit_unmatched(result, strokes_a[i], True, times, unmatched, plane)
    for j in pairing.unmatched_b:
        _emit_unmatched(result, strokes_b[j], False, times, unmatched, plane)
    _check_planarity(result, key_a, key_b, plane)
    result.frames = [_assemble(parts) for parts in result.frames]
    return result


def _fast_path(pairs, times, method, carrier, spacing):
    """Batched ball-morph of every eligible pair (None where the general road is needed)."""
    out = [None] * len(pairs)
    if method not in BALL_METHODS:
        return out
    todo, curves = [], []
    for k, (a, b, _) in enumerate(pairs):
        if a.closed != b.closed or len(a.xy) < 2 or len(b.xy) < 2:
            continue
        try:
            curves.append((as_curve(a.xy, "P", a.closed), as_curve(b.xy, "Q", a.closed), a.closed))
        except InvalidCurveError:
            continue
        todo.append(k)
    if todo:
        for k, done in zip(todo, morph_pairs(curves, times, method[: -len("-ball")], carrier, spacing)):
            if done is not None and np.all(np.isfinite(done.frames)):
                out[k] = done
    return out


def _emit_pair(result, a, b, times, plane, flipped, frames, ua, ub, closed, used, notes):
    da, ra, oa, ca = a.attributes_at(ua)
    db, rb, ob, cb = b.attributes_at(ub)
    for k, t in enumerate(times):
        result.frames[k].append(
            (
                plane.to_3d(frames[k], (1 - t) * da + t * db),
                closed,
                a.material if t < 0.5 else b.material,
                (1 - t) * ra + t * rb,
                (1 - t) * oa + t * ob,
                (1 - t) * ca + t * cb,
                (a.index, b.index),
            )
        )
    result.pairs.append(PairReport(a.index, b.index, used, "; ".join(notes)))
    if flipped:
        notes = ["the second key's stroke runs the other way: flipped", *notes]
    fell_back = used.startswith(FALLBACK_METHOD) or used == "straight point motion"
    for note in notes:
        level = "WARNING" if fell_back and note is notes[-1] else "INFO"
        result.messages.append(Message(level, f"stroke {a.index} -> {b.index}: {note}"))


def _emit_unmatched(result, stroke, from_a, times, unmatched, plane):
    pos = plane.to_3d(stroke.xy, stroke.depth)
    for k, t in enumerate(times):
        visible = unmatched == "HOLD" or (t < 0.5 if from_a else t >= 0.5)
        if visible:
            origin = (stroke.index, -1) if from_a else (-1, stroke.index)
            result.frames[k].append(
                (pos, stroke.closed, stroke.material, stroke.radius, stroke.opacity, stroke.color, origin)
            )
    what = (
        ("held" if unmatched == "HOLD" else "disappears at the middle")
        if from_a
        else ("held" if unmatched == "HOLD" else "appears at the middle")
    )
    key = "first" if from_a else "second"
    result.pairs.append(
        PairReport(
            stroke.index if from_a else None,
            None if from_a else stroke.index,
            "hold" if unmatched == "HOLD" else ("disappear" if from_a else "appear"),
        )
    )
    result.messages.append(Message("WARNING", f"stroke {stroke.index} of the {key} key has no partner: {what}"))


def _check_planarity(result, key_a, key_b, plane):
    pts = np.concatenate([key_a.positions, key_b.positions])
    if len(pts) < 3:
        return
    scale = float(np.linalg.norm(np.ptp(pts, axis=0)))
    _, depth = plane.to_2d(pts)
    worst = float(np.abs(depth).max())
    if scale > 0 and worst > tol.PLANARITY * scale:
        result.messages.append(
            Message(
                "WARNING",
                f"the keys are not flat (points up to {worst:.3g} off the drawing plane): strokes were "
                "morphed in the best-fit plane, keeping each point's offset from it",
            )
        )


def _assemble(parts):
    if not parts:
        return StrokeSet.empty()
    sizes = [len(p[0]) for p in parts]
    return StrokeSet(
        np.concatenate([p[0] for p in parts]),
        np.concatenate([[0], np.cumsum(sizes)]),
        [p[1] for p in parts],
        [p[2] for p in parts],
        np.concatenate([p[3] for p in parts]),
        np.concatenate([p[4] for p in parts]),
        np.concatenate([p[5] for p in parts]),
        origin=np.array([p[6] for p in parts], dtype=np.int64).reshape(-1, 2),
    )
