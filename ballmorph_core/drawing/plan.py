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

from .. import tolerances as tol
from ..errors import InvalidCurveError
from ..geometry.plane import fit_plane
from ..geometry.polyline import as_curve
from ..geometry.ragged import Ragged
from ..morphs import make_morph
from ..options import check_option, check_positive
from .batch import BatchResult, plan_pairs
from .matching import MODES as MATCHINGS
from .matching import match_strokes
from .pair import BALL_METHODS, morph_pair
from .registration import CARRIERS

__all__ = [
    "StrokeSet",
    "Message",
    "PairReport",
    "InbetweenResult",
    "InbetweenPlan",
    "inbetween",
    "plan_inbetween",
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


class _Key:
    """A key projected into the drawing plane, with everything a stroke carries.

    Attributes
    ----------
    rg : Ragged
        The strokes' 2D points (arc lengths and fractions come from it).
    values : ndarray, shape (N, 7)
        Per point: offset from the plane, radius, opacity, vertex colour (RGBA).
    """

    def __init__(self, strokes, plane):
        xy, depth = plane.to_2d(strokes.positions)
        self.rg = Ragged(xy, strokes.offsets, strokes.cyclic)
        self.strokes = strokes
        self.values = np.column_stack([depth, strokes.radius, strokes.opacity, strokes.vertex_color])
        length = self.rg.length[self.rg.owner]
        local = np.arange(len(xy)) - strokes.offsets[:-1][self.rg.owner]
        n = self.rg.n[self.rg.owner]
        even = np.divide(local, np.maximum(n - 1, 1))
        self.u = np.where(length > 0, np.divide(self.rg.s, np.where(length > 0, length, 1.0)), even)
        # Interpolation table: every stroke's fractions shifted by 2 per stroke, loops closed by
        # their first point at fraction 1, so one np.interp serves all strokes at once.
        first = strokes.offsets[:-1][self.rg.n > 0]
        closing = first[self.rg.closed[self.rg.n > 0] | (self.rg.n[self.rg.n > 0] == 1)]
        owner = np.concatenate([self.rg.owner, self.rg.owner[closing]])
        x = np.concatenate([self.u, np.ones(len(closing))]) + 2.0 * owner
        order = np.argsort(x, kind="stable")
        self._x = x[order]
        self._v = np.concatenate([self.values, self.values[closing]])[order]
        self._last = None  # (stroke, u, values): a plan evaluated again asks for the same

    def stroke(self, i, flip=False):
        """Stroke ``i`` for morphing (``_Stroke``), reversed if ``flip``."""
        sl = self.strokes.points(i)
        xy = self.rg.pts[sl]
        u = self.u[sl]
        closed = bool(self.rg.closed[i])
        if flip:
            order = np.r_[0, np.arange(len(xy) - 1, 0, -1)] if closed else np.arange(len(xy))[::-1]
            xy, u = xy[order], np.mod(1.0 - u[order], 1.0) if closed else 1.0 - u[order]
        return _Stroke(i, xy, u, closed, int(self.strokes.material_index[i]))

    def sample(self, stroke, u):
        """Per-point values at fractions ``u`` of given strokes (vectorised), shape (K, 7)."""
        last = self._last
        if last is not None and np.array_equal(stroke, last[0]) and np.array_equal(u, last[1]):
            return last[2]
        x = np.clip(u, 0.0, 1.0) + 2.0 * stroke
        values = np.column_stack([np.interp(x, self._x, self._v[:, c]) for c in range(self._v.shape[1])])
        self._last = (stroke, u, values)
        return values


@dataclass
class _Stroke:
    """One stroke as the morphs see it: index, 2D points, vertex fractions, cyclic, material."""

    index: int
    xy: np.ndarray
    u: np.ndarray
    closed: bool
    material: int


def _along_original(u, flip, closed):
    """Fractions along a reversed stroke, expressed along the stroke as drawn."""
    if not flip:
        return u
    return np.mod(-u, 1.0) if closed else 1.0 - u


def _dot_frames(a, b, times):
    """Strokes with fewer than two distinct points: move them straight, point by point."""
    k = max(len(a.xy), len(b.xy))
    u = np.linspace(0.0, 1.0, k)

    def along(s):
        if len(s.xy) == 1:
            return np.repeat(s.xy, k, axis=0)
        return np.column_stack([np.interp(u, s.u, s.xy[:, c]) for c in range(2)])

    xa, xb = along(a), along(b)
    return np.stack([(1 - t) * xa + t * xb for t in times]), u, u


class _PairPlan:
    """The general road for one stroke pair: its morph, built once, evaluated at any times.

    Never raises :class:`BallMorphError`: a pair the requested morph cannot handle (or whose
    frames fail or are not finite at the requested times) falls back to
    :data:`FALLBACK_METHOD`, then to straight point motion, and says why.
    """

    def __init__(self, a, b, method, carrier, spacing):
        self.a, self.b, self.method, self.spacing = a, b, method, spacing
        self.closed = a.closed and b.closed
        self.notes = []
        if a.closed != b.closed:
            self.notes.append("one key's stroke is cyclic and the other's is not: morphed as open strokes")
        self.curves = self.morph = self.used = self.failure = self._fallback = None
        try:
            self.curves = (as_curve(a.xy, "P", self.closed), as_curve(b.xy, "Q", self.closed))
        except InvalidCurveError as exc:
            self.failure = f"too few distinct points ({exc})"
            return
        try:
            outcome = morph_pair(*self.curves, self.closed, method, carrier, spacing)
        except Exception as exc:
            self.failure = f"{method} failed ({type(exc).__name__}: {exc})"
            return
        self.morph, self.used = outcome.morph, outcome.used
        self.notes += outcome.notes

    def frames(self, times):
        """Frames, attribute fractions and report at ``times``.

        Returns
        -------
        frames : ndarray, shape (T, K, 2)
        u_a, u_b : ndarray, shape (K,)
        closed : bool
        used : str
        notes : list of str
        """
        if self.curves is None:
            frames, ua, ub = _dot_frames(self.a, self.b, times)
            return frames, ua, ub, False, "straight point motion", [self.failure]
        notes, morph, used, frames = list(self.notes), self.morph, self.used, None
        if morph is None:
            notes.append(self.failure)
        else:
            try:
                frames = morph.frames(times)
            except Exception as exc:
                notes.append(f"{self.method} failed ({type(exc).__name__}: {exc})")
        if frames is None:
            try:
                if self._fallback is None:
                    self._fallback = make_morph(*self.curves, FALLBACK_METHOD, closed=self.closed, spacing=self.spacing)
                morph, used = self._fallback, FALLBACK_METHOD
                frames = morph.frames(times)
            except Exception as exc:
                frames, ua, ub = _dot_frames(self.a, self.b, times)
                return frames, ua, ub, False, "straight point motion", notes + [f"{type(exc).__name__}: {exc}"]
        if not np.all(np.isfinite(frames)):
            frames, ua, ub = _dot_frames(self.a, self.b, times)
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
    """In-between drawings of two keys: ``plan_inbetween(key_a, key_b, ...).evaluate(times)``.

    Parameters
    ----------
    key_a, key_b : StrokeSet
        The two keys (not modified).
    times : array_like, shape (T,)
        Morph times in [0, 1] (already eased; values outside are clamped).
    method, carrier, matching, unmatched, spacing
        See :func:`plan_inbetween`.

    Returns
    -------
    InbetweenResult
    """
    method, carrier, matching, unmatched = _check_inputs(key_a, key_b, method, carrier, matching, unmatched)
    times = _check_times(times)
    spacing = None if spacing is None else check_positive("spacing", spacing)
    # The inputs are checked: build the plan directly rather than check the keys twice.
    return InbetweenPlan(key_a, key_b, method, carrier, matching, unmatched, spacing).evaluate(times)


def plan_inbetween(
    key_a,
    key_b,
    method="circular-ball",
    carrier="SIMILARITY",
    matching="AUTO",
    unmatched="MIDDLE",
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
    InbetweenPlan

    Notes
    -----
    Strokes are paired by :func:`~ballmorph_core.matching.match_strokes` (by index when the
    counts agree and the shapes fit, as Blender does; otherwise by an optimal assignment on a
    shape distance); a stroke of the second key running the other way is flipped first. The
    ball-morphs of all eligible pairs are planned at once (:func:`~ballmorph_core.batch.plan_pairs`);
    every other pair goes through :func:`~ballmorph_core.pair.morph_pair` (carrier, crossing
    splits, composite and linear fallbacks), so a pair never aborts the others. The matching,
    the correspondences and the carriers are computed here, once; the plan's
    :meth:`~InbetweenPlan.evaluate` only moves samples along their paths, which is what lets
    the operator's redo (another frame count or easing) skip the expensive part.
    """
    method, carrier, matching, unmatched = _check_inputs(key_a, key_b, method, carrier, matching, unmatched)
    spacing = None if spacing is None else check_positive("spacing", spacing)
    return InbetweenPlan(key_a, key_b, method, carrier, matching, unmatched, spacing)


class InbetweenPlan:
    """The in-betweens of two keys, ready to evaluate at any times (see :func:`plan_inbetween`).

    Evaluating a plan at ``times`` gives exactly what :func:`inbetween` gives for the same keys,
    options and times.
    """

    def __init__(self, key_a, key_b, method, carrier, matching, unmatched, spacing):
        self.method, self.carrier, self.unmatched, self.spacing = method, carrier, unmatched, spacing
        self.plane = plane = fit_plane(np.concatenate([key_a.positions, key_b.positions]))
        self.messages = []  # the plan's own, before the per-pair reports
        self.ka, self.kb = ka, kb = _Key(key_a, plane), _Key(key_b, plane)
        # Strokes without points have nothing to morph or show: leave them out, and say so.
        live_a, live_b = np.flatnonzero(key_a.sizes > 0), np.flatnonzero(key_b.sizes > 0)
        for name, key in (("first", key_a), ("second", key_b)):
            for i in np.flatnonzero(key.sizes == 0):
                self.messages.append(Message("INFO", f"stroke {i} of the {name} key has no points: left out"))
        pairing = match_strokes(
            [ka.rg.curve(i) for i in live_a],
            [kb.rg.curve(j) for j in live_b],
            ka.rg.closed[live_a],
            kb.rg.closed[live_b],
            mode=matching,
        )
        matched = [(int(live_a[i]), int(live_b[j]), flip) for i, j, flip in pairing.pairs]
        self.unmatched_a = [int(live_a[i]) for i in pairing.unmatched_a]
        self.unmatched_b = [int(live_b[j]) for j in pairing.unmatched_b]
        if pairing.method != "index" or self.unmatched_a or self.unmatched_b:
            self.messages.append(Message("INFO", f"strokes paired by {pairing.method}: {pairing.reason}"))
        self.pairs = [(ka.stroke(i), kb.stroke(j, flip), flip) for i, j, flip in matched]
        self.fast, self.fast_pairs = _fast_plan(self.pairs, method, carrier, spacing)
        fast = np.zeros(len(self.pairs), dtype=bool)
        if self.fast is not None:
            fast[self.fast_pairs[self.fast.done]] = True
        # Pairs off the fast path are planned now; the fast ones only if their frames fail.
        self._general = {
            k: _PairPlan(a, b, method, carrier, spacing) for k, (a, b, _) in enumerate(self.pairs) if not fast[k]
        }
        self.planarity = _planarity_messages(key_a, key_b, plane)

    def _general_plan(self, k):
        if k not in self._general:
            a, b, _ = self.pairs[k]
            self._general[k] = _PairPlan(a, b, self.method, self.carrier, self.spacing)
        return self._general[k]

    def evaluate(self, times):
        """The in-betweens at ``times``.

        Parameters
        ----------
        times : array_like, shape (T,)
            Morph times in [0, 1] (already eased; values outside are clamped).

        Returns
        -------
        InbetweenResult
        """
        times = _check_times(times)
        result = InbetweenResult(frames=[], messages=list(self.messages))
        fast = _spread(self.fast, self.fast_pairs, len(self.pairs), times)
        parts = []  # per pair: frames (T, K, 2), fractions on A and B, cyclic, the two strokes
        for k, (a, b, flip) in enumerate(self.pairs):
            if fast.done[k]:
                frames, ua, ub = fast.pair(k)
                closed, used, notes = a.closed, fast.used[k], fast.notes[k]
            else:
                frames, ua, ub, closed, used, notes = self._general_plan(k).frames(times)
            parts.append((frames, ua, _along_original(ub, flip, b.closed), closed, a, b))
            _report_pair(result, a, b, flip, used, notes)
        held = [(self.ka, i, True) for i in self.unmatched_a] + [(self.kb, j, False) for j in self.unmatched_b]
        for _, i, from_a in held:
            _report_unmatched(result, i, from_a, self.unmatched)
        # Every pair from the fast path, in order: its frames are already the concatenation.
        whole = fast.frames if fast.done.all() else None
        result.frames = _assemble(parts, held, self.ka, self.kb, times, self.plane, self.unmatched, whole)
        result.messages.extend(self.planarity)
        return result


def _check_inputs(key_a, key_b, method, carrier, matching, unmatched):
    from ..morphs import METHODS  # local: the registry is complete once the package is imported

    options = (
        check_option("method", method, METHODS),
        check_option("carrier", carrier, CARRIERS),
        check_option("matching", matching, MATCHINGS),
        check_option("unmatched", unmatched, UNMATCHED),
    )
    for name, key in (("key_a", key_a), ("key_b", key_b)):
        _check_key(name, key)
    return options


def _check_times(times):
    """Times as a float array clamped to [0, 1] (a morph has nothing before or after its keys)."""
    try:
        times = np.asarray(times, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        raise InvalidCurveError(f"times: must be numbers in [0, 1], got {times!r}") from None
    if not np.all(np.isfinite(times)):
        raise InvalidCurveError("times: must be finite numbers in [0, 1]")
    return np.clip(times, 0.0, 1.0)


def _check_key(name, key):
    """Reject what cannot be a drawing, naming the key, the attribute and the strokes."""
    if not isinstance(key, StrokeSet):
        raise InvalidCurveError(f"{name}: expected a StrokeSet, got {type(key).__name__}")
    for attr, values in (
        ("positions", key.positions),
        ("radius", key.radius),
        ("opacity", key.opacity),
        ("vertex_color", key.vertex_color),
    ):
        if values.size and not np.all(np.isfinite(values)):
            points = np.flatnonzero(~np.all(np.isfinite(values.reshape(len(values), -1)), axis=1))
            bad = np.unique(np.searchsorted(key.offsets, points, "right") - 1).tolist()
            what = "coordinates" if attr == "positions" else attr
            raise InvalidCurveError(f"{name}: stroke(s) {bad[:10]} have NaN or infinite {what}: redraw or delete them")


def _fast_plan(pairs, method, carrier, spacing):
    """Batched ball-morph plan of every eligible pair (see :mod:`~ballmorph_core.batch`).

    Returns
    -------
    plan : BatchPlan or None
    todo : ndarray of int
        The pairs the plan covers, in its order.
    """
    todo, curves = [], []
    if method in BALL_METHODS:
        for k, (a, b, _) in enumerate(pairs):
            if a.closed != b.closed or len(a.xy) < 2 or len(b.xy) < 2:
                continue
            try:
                curves.append((as_curve(a.xy, "P", a.closed), as_curve(b.xy, "Q", a.closed), a.closed))
            except InvalidCurveError:
                continue
            todo.append(k)
    if not todo:
        return None, np.zeros(0, dtype=np.int64)
    try:
        return plan_pairs(curves, method[: -len("-ball")], carrier, spacing), np.asarray(todo)
    except Exception:  # the general road handles (and reports) every pair instead
        return None, np.zeros(0, dtype=np.int64)


def _spread(plan, todo, n_pairs, times):
    """The fast plan's frames at ``times``, spread over all pairs; pairs whose frames are not
    finite take the general road (not done here)."""
    out = BatchResult.empty(n_pairs, len(times))
    if plan is None:
        return out
    fast = plan.frames(times)
    good = fast.done.copy()
    if not np.isfinite(fast.frames.sum()):  # (a sum of finite frames cannot overflow: MAX_COORDINATE)
        bad = np.concatenate([[0], np.cumsum(~np.isfinite(fast.frames).all(axis=(0, 2)))])
        good &= bad[fast.offsets[1:]] == bad[fast.offsets[:-1]]  # no non-finite sample
    sizes = np.zeros(n_pairs, dtype=np.int64)
    sizes[todo[good]] = np.diff(fast.offsets)[good]
    keep = np.repeat(good, np.diff(fast.offsets))
    out.done[todo[good]] = True
    out.offsets = np.concatenate([[0], np.cumsum(sizes)])
    # Samples are grouped by pair in the batch's order, which follows ``pairs``.
    if keep.all():  # the usual case: no copy
        out.frames, out.u_p, out.u_q = fast.frames, fast.u_p, fast.u_q
    else:
        out.frames, out.u_p, out.u_q = fast.frames[:, keep], fast.u_p[keep], fast.u_q[keep]
    for c, k in enumerate(todo):
        out.used[k], out.notes[k] = fast.used[c], fast.notes[c]
    return out


def _report_pair(result, a, b, flipped, used, notes):
    result.pairs.append(PairReport(a.index, b.index, used, "; ".join(notes)))
    if flipped:
        notes = ["the second key's stroke runs the other way: flipped", *notes]
    fell_back = used.startswith(FALLBACK_METHOD) or used == "straight point motion"
    for note in notes:
        level = "WARNING" if fell_back and note is notes[-1] else "INFO"
        result.messages.append(Message(level, f"stroke {a.index} -> {b.index}: {note}"))


def _report_unmatched(result, index, from_a, unmatched):
    if from_a:
        what = "held" if unmatched == "HOLD" else "disappears at the middle"
    else:
        what = "held" if unmatched == "HOLD" else "appears at the middle"
    key = "first" if from_a else "second"
    method = "hold" if unmatched == "HOLD" else ("disappear" if from_a else "appear")
    result.pairs.append(PairReport(index if from_a else None, None if from_a else index, method))
    result.messages.append(Message("WARNING", f"stroke {index} of the {key} key has no partner: {what}"))


def _assemble(parts, held, ka, kb, times, plane, unmatched, frames=None):
    """One StrokeSet per time from every pair's frames and the unmatched strokes (vectorised).

    ``frames``, shape (T, K, 2), is the pairs' frames concatenated when the caller has it.
    """
    if parts:
        frames = np.concatenate([p[0] for p in parts], axis=1) if frames is None else frames  # (T, K, 2)
        sizes = np.array([p[0].shape[1] for p in parts])
        stroke_a = np.repeat([p[4].index for p in parts], sizes)
        stroke_b = np.repeat([p[5].index for p in parts], sizes)
        va = ka.sample(stroke_a, np.concatenate([p[1] for p in parts]))
        vb = kb.sample(stroke_b, np.concatenate([p[2] for p in parts]))
        cyclic = np.array([p[3] for p in parts], dtype=bool)
        mat_a = np.array([p[4].material for p in parts], dtype=np.int64)
        mat_b = np.array([p[5].material for p in parts], dtype=np.int64)
        origin = np.array([(p[4].index, p[5].index) for p in parts], dtype=np.int64)
    else:
        frames, sizes = np.zeros((len(times), 0, 2)), np.zeros(0, np.int64)
        va = vb = np.zeros((0, 7))
        cyclic, origin = np.zeros(0, bool), np.zeros((0, 2), np.int64)
        mat_a = mat_b = np.zeros(0, np.int64)
    # Attributes the two keys agree on (often radius, opacity, colour and the offset from the
    # plane) are shared by every frame, not mixed: a redo of a big drawing is mostly this loop.
    differ = np.any(va != vb, axis=0)  # (7,)
    va_d, vb_d = va[:, differ], vb[:, differ]
    depth = va[:, 0] if np.any(va[:, 0]) else None
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    out = []
    for ti, t in enumerate(times):
        mix = va
        if differ.any():
            mix = va.copy()
            mix[:, differ] = (1 - t) * va_d + t * vb_d
            depth = mix[:, 0] if differ[0] else depth
        lifted = plane.to_3d(frames[ti], depth)
        shown = [h for h in held if unmatched == "HOLD" or (t < 0.5 if h[2] else t >= 0.5)]
        mats = mat_a if t < 0.5 else mat_b
        if not shown:
            out.append(StrokeSet(lifted, offsets, cyclic, mats, mix[:, 1], mix[:, 2], mix[:, 3:7], origin=origin))
            continue
        pts, vals, size_list = [lifted], [mix[:, 1:]], [sizes]
        cyc, mats, orig = [cyclic], [mats], [origin]
        for key, i, from_a in shown:
            sl = key.strokes.points(i)
            pts.append(key.strokes.positions[sl])
            vals.append(key.values[sl, 1:])
            size_list.append([sl.stop - sl.start])
            cyc.append([key.strokes.cyclic[i]])
            mats.append([key.strokes.material_index[i]])
            orig.append([(i, -1) if from_a else (-1, i)])
        v = np.concatenate(vals)
        size = np.concatenate([np.asarray(x, dtype=np.int64) for x in size_list])
        out.append(
            StrokeSet(
                np.concatenate(pts),
                np.concatenate([[0], np.cumsum(size)]),
                np.concatenate([np.asarray(x, dtype=bool) for x in cyc]),
                np.concatenate([np.asarray(x, dtype=np.int64) for x in mats]),
                v[:, 0],
                v[:, 1],
                v[:, 2:6],
                origin=np.concatenate([np.asarray(x, dtype=np.int64).reshape(-1, 2) for x in orig]),
            )
        )
    return out


def _planarity_messages(key_a, key_b, plane):
    """A warning when the keys are not flat, as a list (empty when they are)."""
    pts = np.concatenate([key_a.positions, key_b.positions])
    if len(pts) < 3:
        return []
    scale = float(np.linalg.norm(np.ptp(pts, axis=0)))
    _, depth = plane.to_2d(pts)
    worst = float(np.abs(depth).max())
    if scale > 0 and worst > tol.PLANARITY * scale:
        return [
            Message(
                "WARNING",
                f"the keys are not flat (points up to {worst:.3g} off the drawing plane): strokes were "
                "morphed in the best-fit plane, keeping each point's offset from it",
            )
        ]
    return []
