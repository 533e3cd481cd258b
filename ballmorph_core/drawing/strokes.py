"""The data a drawing is made of, in Blender's own layout, and what an in-between run returns.

A drawing is a :class:`StrokeSet`: flat point arrays plus stroke offsets, like a Grease Pencil
drawing's curves geometry, so the operator moves data with ``foreach_get``/``foreach_set`` and
never loops over points in Python.
"""

from dataclasses import dataclass, field
from enum import Enum

import numpy as np

from ..errors import InvalidCurveError

__all__ = ["StrokeSet", "Message", "as_written", "Route", "PairMorphs", "PairOutcome", "PairReport", "InbetweenResult"]


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
    point_attributes, curve_attributes : dict of str to ndarray
        Every other attribute, by name: shape (N,) or (N, w) per point, (S,) or (S, w) per
        stroke. In-betweens interpolate floating-point ones along the correspondence and take
        the others (integers, booleans) from the key nearer in time.
    attribute_types : dict of str to str
        The caller's type of each extra attribute (Blender's data type), passed on unchanged.
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
    point_attributes: dict = None
    curve_attributes: dict = None
    attribute_types: dict = None

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
        self.point_attributes = _extras(self.point_attributes, n, "point")
        self.curve_attributes = _extras(self.curve_attributes, s, "curve")
        self.attribute_types = dict(self.attribute_types or {})
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
        return cls(
            positions=np.zeros((0, 3)),
            offsets=[0],
            cyclic=[],
            material_index=[],
            radius=[],
            opacity=[],
            vertex_color=np.zeros((0, 4)),
        )

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
            positions=np.concatenate(pts) if pts else np.zeros((0, 3)),
            offsets=np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64),
            cyclic=np.zeros(len(pts), bool) if cyclic is None else cyclic,
            material_index=np.zeros(len(pts), np.int64) if material_index is None else material_index,
            radius=per_point(radius, 0.01),
            opacity=per_point(opacity, 1.0),
            vertex_color=per_point(vertex_color, 0.0, 4).reshape(-1, 4),
        )

    @classmethod
    def concatenate(cls, parts):
        """Join StrokeSets into one (strokes in order); an extra attribute some parts lack is 0
        on their points (Blender's value for a missing attribute). One part is returned as it is,
        not copied: in-betweens share the attribute arrays their keys agree on."""
        parts = list(parts)
        if not parts:
            return cls.empty()
        if len(parts) == 1:
            return parts[0]
        sizes = np.concatenate([p.sizes for p in parts])
        types = {}
        for p in parts:
            types.update(p.attribute_types)
        return cls(
            offsets=np.concatenate([[0], np.cumsum(sizes)]),
            **{name: np.concatenate([getattr(p, name) for p in parts]) for name in _FIELDS if name != "offsets"},
            point_attributes=_joined([p.point_attributes for p in parts], [len(p.positions) for p in parts]),
            curve_attributes=_joined([p.curve_attributes for p in parts], [len(p) for p in parts]),
            attribute_types=types,
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
            offsets=np.concatenate([[0], np.cumsum(sizes)]),
            **{name: getattr(self, name)[pts] for name in _POINT_FIELDS},
            **{name: getattr(self, name)[idx] for name in _CURVE_FIELDS},
            point_attributes={name: v[pts] for name, v in self.point_attributes.items()},
            curve_attributes={name: v[idx] for name, v in self.curve_attributes.items()},
            attribute_types=self.attribute_types,
        )

    def replace_positions(self, positions):
        """The same strokes with other positions, shape (N, 3) (StrokeSet)."""
        fields = {name: getattr(self, name) for name in _FIELDS if name != "positions"}
        extras = {name: getattr(self, name) for name in ("point_attributes", "curve_attributes", "attribute_types")}
        return StrokeSet(positions=positions, **fields, **extras)


@dataclass
class Message:
    """Something the animator should know. ``level`` is INFO, WARNING or ERROR.

    ``strokes``: the strokes it is about, as ``(key, index)`` pairs (key 0 the first key, 1 the
    second; indices from 0, as in the data), so a caller can show them (the add-on selects
    them); empty when it is about no stroke in particular.
    """

    level: str
    text: str
    strokes: tuple = ()


def as_written(index):
    """A stroke's number in the messages: as an animator counts the strokes of a key, from 1
    (the stroke at index 0 is stroke 1). Indices in the data (PairReport, Matching) stay 0-based.

    >>> as_written(0)
    1
    """
    return int(index) + 1


class Route(Enum):
    """How the pipeline made a pair's in-betweens (:mod:`.pair_morphs.pipeline`)."""

    OWN_POINTS = "own points"  # its points match one for one under a similarity
    POLYLINE = "polyline"  # polylines with as many corners: corner to corner
    DOT = "dot"  # fewer than two distinct points: point by point
    CARRIER = "carrier"  # the registered curves coincide: the carrier alone
    NEAR = "near"  # the same stroke redrawn: matched by arc length on the carrier
    WHOLE = "whole"  # ball-mapped whole (shared ends, nested loops)
    LENSES = "lenses"  # cut at its crossings into lenses, each ball-mapped
    TANGENT = "tangent-aligned"  # changes shape where it lies: tangent-aligned, straight paths
    ALIGNED = "aligned"  # curves lying over each other that cannot be cut into lenses
    LINEAR = "linear"  # no ball-morph can follow: linear interpolation
    COMPARISON = "comparison"  # one of the paper's comparison morphs, as asked
    POINT_MOTION = "point motion"  # the morph was not finite somewhere: point by point


@dataclass(frozen=True)
class PairMorphs:
    """What made one pair's in-betweens: the morphs its chains used and the carrier moving them.

    Attributes
    ----------
    morphs : tuple of str
        The morphs' names, sorted ('circular-ball', 'linear-interpolation', 'static',
        'polyline', 'straight point motion', ...).
    carrier : str
        The kind of the carrier moving the pair ('rigid', 'similarity', ...), '' for none.
    route : Route or None
        How the pipeline made the pair.

    Examples
    --------
    >>> str(PairMorphs(("circular-ball", "linear-interpolation"), "rigid"))
    'circular-ball+linear-interpolation on a rigid carrier'
    """

    morphs: tuple = ()
    carrier: str = ""
    route: Route | None = None

    def __str__(self):
        text = "+".join(self.morphs)
        return f"{text} on a {self.carrier} carrier" if self.carrier else text

    @classmethod
    def union(cls, parts):
        """The morphs of several pieces of one pair (the pieces cut at its hints), one carrier."""
        parts = list(parts)
        morphs = sorted({m for part in parts for m in part.morphs})
        carrier = next((p.carrier for p in parts if p.carrier), "")
        return cls(tuple(morphs), carrier, next((p.route for p in parts if p.route is not None), None))


class PairOutcome(Enum):
    """What became of a stroke of a key: morphed with its partner, a piece of a line drawn in
    pieces (morphed with the line), or without a partner (appears, disappears, is held)."""

    MORPHED = "morphed"
    PIECE = "piece"
    APPEAR = "appear"
    DISAPPEAR = "disappear"
    HOLD = "hold"


@dataclass
class PairReport:
    """What happened to one stroke pair.

    Attributes
    ----------
    stroke_a, stroke_b : int or None
        Stroke indices in the two keys (None for a stroke with no partner).
    method : str
        The morph actually used, in words (or 'appear' / 'disappear' / 'hold').
    reason : str
        Why a fallback was used ('' when the requested morph worked).
    outcome : PairOutcome
    used : PairMorphs
        The morphs and carrier, as fields (``method`` words them): read these, never the text.
    travelled : bool
        Whether the pair was made by the drawing's motion: left over by the assignment (too far
        apart for it), paired because the shapes agree (see :mod:`.travelling`).
    """

    stroke_a: int
    stroke_b: int
    method: str
    reason: str = ""
    outcome: PairOutcome = PairOutcome.MORPHED
    used: PairMorphs = PairMorphs()
    travelled: bool = False


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


def _extras(values, size, domain):
    """Extra attributes checked: a dict of arrays whose first axis has ``size`` entries."""
    out = {}
    for name, array in (values or {}).items():
        array = np.asarray(array)
        if array.ndim not in (1, 2) or len(array) != size:
            raise InvalidCurveError(f"{domain} attribute {name!r}: expected {size} values, got shape {array.shape}")
        out[str(name)] = array
    return out


def _joined(dicts, sizes):
    """Per-name concatenation of attribute dicts; a part without an attribute contributes zeros."""
    names = {}
    for d in dicts:
        for name, array in d.items():
            names.setdefault(name, array)
    return {
        name: np.concatenate(
            [d[name] if name in d else np.zeros((size, *like.shape[1:]), like.dtype) for d, size in zip(dicts, sizes)]
        )
        for name, like in names.items()
    }


#: StrokeSet fields per point and per stroke (besides positions' offsets).
_POINT_FIELDS = ("positions", "radius", "opacity", "vertex_color")
_CURVE_FIELDS = ("cyclic", "material_index", "selected", "origin")
_FIELDS = ("offsets", *_POINT_FIELDS, *_CURVE_FIELDS)
