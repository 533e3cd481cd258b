"""The in-between drawings: every pair's samples lifted back to 3D, with the attributes of the
points they come from mixed in time, plus the strokes without a partner.

Every attribute of the keys is carried. Floating-point ones (radius, opacity, vertex colour,
the offset from the drawing plane, and every extra float, vector or colour attribute) are read
on both keys where each sample comes from and goes to, and mixed as ``(1 - t) a + t b``;
the others (integers, booleans: a material, a flag, a user's ID) are the value of the point, or
stroke, of the key nearer in time (the first key before ``t = 0.5``). An extra attribute only one
key has is 0 on the other (Blender's value for a missing attribute).
"""

import sys
from dataclasses import dataclass, field

import numpy as np

from ..keys.hints import HINT
from ..strokes import StrokeSet
from .unmatched import Anchors, shown_strokes

__all__ = ["Held", "Extras", "FrameValues", "Recycled", "assemble_frames"]

#: Columns of ProjectedKey.values() before the extra floats: plane offset, radius, opacity, RGBA.
_BASE = 7

#: The most memory of one evaluation's in-betweens a plan keeps for the next (:class:`Recycled`):
#: all of a 100 x 200 x 9 drawing's (6 MB). Kept arrays stay alive while the frames are written,
#: so this adds to a big run's peak: at 16 MiB a cold 400 x 500 x 23 run of open strokes peaked
#: at 1.96 times Blender's own Interpolate Sequence (issue 14's goal: at most 2).
RECYCLED_BYTES = 8 * 2**20


@dataclass
class Held:
    """A stroke without a partner, shown as it is drawn in its key.

    Attributes
    ----------
    key : ProjectedKey
    index : int
    from_a : bool
        The stroke is in the first key (it disappears at the middle) or in the second (it appears).
    """

    key: object
    index: int
    from_a: bool


@dataclass
class Extras:
    """The extra attributes of two keys, aligned.

    Attributes
    ----------
    point, curve : dict of str to (shape, dtype)
        Every extra attribute either key has: its per-element shape and dtype.
    types : dict of str to str
        The caller's type names, passed on.
    """

    point: dict = field(default_factory=dict)
    curve: dict = field(default_factory=dict)
    types: dict = field(default_factory=dict)

    @classmethod
    def of(cls, *keys):
        """The union of the keys' extra attributes (the first key's shape and type win)."""
        out = cls()
        for key in keys:
            for target, arrays in ((out.point, key.point_attributes), (out.curve, key.curve_attributes)):
                for name, array in arrays.items():
                    if name != HINT:  # hints follow the correspondence itself (see .hints)
                        target.setdefault(name, (array.shape[1:], array.dtype))
            for name, kind in key.attribute_types.items():
                out.types.setdefault(name, kind)
        return out

    def arrays(self, key, domain):
        """A key's extra attributes of ``domain`` ('point' or 'curve'), zeros where it has none."""
        size = len(key.positions) if domain == "point" else len(key)
        own = key.point_attributes if domain == "point" else key.curve_attributes
        names = self.point if domain == "point" else self.curve
        return {
            name: own[name] if name in own else np.zeros((size, *shape), dtype)
            for name, (shape, dtype) in names.items()
        }

    def floats(self, domain):
        """Names of the interpolated attributes of ``domain``, in order."""
        names = self.point if domain == "point" else self.curve
        return [name for name, (_, dtype) in names.items() if np.issubdtype(dtype, np.floating)]

    def point_columns(self, key):
        """A key's interpolated point attributes as columns, shape (N, F) (ProjectedKey's extra values)."""
        arrays = self.arrays(key, "point")
        cols = [arrays[name].reshape(len(key.positions), -1).astype(np.float64) for name in self.floats("point")]
        return np.concatenate(cols, axis=1) if cols else np.zeros((len(key.positions), 0))

    def from_columns(self, columns):
        """Interpolated point attributes back from columns (N, F): dict of arrays."""
        out, start = {}, 0
        for name in self.floats("point"):
            shape, dtype = self.point[name]
            width = int(np.prod(shape)) if shape else 1
            out[name] = columns[:, start : start + width].reshape(-1, *shape).astype(dtype)
            start += width
        return out


def _pair_values(parts, strokes_a, strokes_b, ka, kb):
    """Per sample: the values (plane offset, radius, opacity, colour, extras) on both keys,
    column by column: two iterators of ``ka.width`` arrays of shape (K,), each column read
    when it is asked for (:meth:`ProjectedKey.sampled <..keys.projected.ProjectedKey.sampled>`)."""
    sizes = np.diff(parts.offsets)
    if not sizes.sum():
        return (iter([np.zeros(0)] * ka.width) for _ in "ab")
    va = ka.sampled(np.repeat(strokes_a, sizes) if parts.stroke_a is None else parts.stroke_a, parts.u_a)
    vb = kb.sampled(np.repeat(strokes_b, sizes) if parts.stroke_b is None else parts.stroke_b, parts.u_b)
    return va, vb


def _as_drawn(h, extras):
    """A stroke without a partner as drawn in its key: the StrokeSet of its one stroke."""
    s, i = h.key.strokes, h.index
    sl = s.points(i)
    values = h.key.values(sl)
    points = extras.from_columns(values[:, _BASE:])
    own = extras.arrays(s, "point")
    points.update({name: own[name][sl] for name in extras.point if name not in points})
    curves = {name: array[i : i + 1] for name, array in extras.arrays(s, "curve").items()}
    return StrokeSet(
        positions=s.positions[sl],
        offsets=[0, sl.stop - sl.start],
        cyclic=s.cyclic[i : i + 1],
        material_index=s.material_index[i : i + 1],
        radius=values[:, 1],
        opacity=values[:, 2],
        vertex_color=values[:, 3:_BASE],
        origin=[(i, -1) if h.from_a else (-1, i)],
        point_attributes=points,
        curve_attributes=curves,
        attribute_types=extras.types,
    )


class _Discrete:
    """The attributes taken from the nearer key: per point (at the nearest point of each sample)
    and per stroke, for both keys."""

    def __init__(self, parts, plan, index_a, index_b, extras):
        sizes = np.diff(parts.offsets)
        floats_p, floats_c = set(extras.floats("point")), set(extras.floats("curve"))
        self.point = {}
        if any(name not in floats_p for name in extras.point):
            near_a = plan.ka.nearest(np.repeat(index_a, sizes) if parts.stroke_a is None else parts.stroke_a, parts.u_a)
            near_b = plan.kb.nearest(np.repeat(index_b, sizes) if parts.stroke_b is None else parts.stroke_b, parts.u_b)
            arrays_a = extras.arrays(plan.ka.strokes, "point")
            arrays_b = extras.arrays(plan.kb.strokes, "point")
            self.point = {
                name: (arrays_a[name][near_a], arrays_b[name][near_b]) for name in extras.point if name not in floats_p
            }
        arrays_a, arrays_b = extras.arrays(plan.ka.strokes, "curve"), extras.arrays(plan.kb.strokes, "curve")
        self.curve = {name: (arrays_a[name][index_a], arrays_b[name][index_b]) for name in extras.curve}
        self.curve_floats = floats_c

    def at(self, t):
        """(point attributes, curve attributes) of the discrete values and curve floats at ``t``."""
        points = {name: a if t < 0.5 else b for name, (a, b) in self.point.items()}
        curves = {
            name: ((1 - t) * a + t * b).astype(a.dtype) if name in self.curve_floats else (a if t < 0.5 else b)
            for name, (a, b) in self.curve.items()
        }
        return points, curves


class _Mix:
    """Per-sample values at any time, block of columns by block: the first key's own columns
    where the keys agree (shared by every frame), ``(1 - t) a + t b`` where they differ.

    Each block is kept contiguous, and each differing column as its two keys' columns (mixing
    the strided columns of the samples' values every frame was most of a redo's attribute
    time); the samples' values themselves are not kept, nor all read at once: the columns are
    taken one pair at a time (at 260,000 samples, both keys' seven columns held together
    were 29 MiB of an evaluation's peak).

    Parameters
    ----------
    va, vb : iterable of ndarray, shape (K,)
        The W columns of the samples' values on each key, in order.
    blocks : sequence of (int, int)
        The column ranges ``(lo, hi)`` asked for, in order, covering ``0..W``.
    size : int
        K.
    """

    def __init__(self, va, vb, blocks, size):
        columns, differ, self._blocks = zip(va, vb), [], {}
        for lo, hi in blocks:
            shared, mixed = None, {}
            for j in range(hi - lo):
                a, b = next(columns)
                differ.append(bool(np.any(a != b)))
                if differ[-1]:
                    mixed[j] = a, b
                if hi - lo > 1 or not differ[-1]:
                    shared = np.empty((size, hi - lo)) if shared is None else shared
                    shared[:, j] = a
            self._blocks[lo] = (np.empty((size, 0)) if hi == lo else shared), mixed
        self.differ = np.array(differ, dtype=bool)
        # t b's work column, kept: a fresh one each frame is page-faulted anew in a bpy process.
        self._term = np.empty(size) if self.differ.any() else None

    def block(self, lo, t, out=None):
        """The block starting at column ``lo`` at time ``t``, shape (K, hi - lo); a mixed block
        of one column is written into ``out`` (K,) when given (else a new array)."""
        shared, mixed = self._blocks[lo]
        if not mixed:
            return shared
        if shared is None:
            ((a, b),) = mixed.values()
            return self._mixed(a, b, t, np.empty(len(a)) if out is None else out)[:, None]
        out = shared.copy()
        for j, (a, b) in mixed.items():
            self._mixed(a, b, t, out[:, j])
        return out

    def _mixed(self, a, b, t, out):
        """``(1 - t) a + t b`` into ``out``."""
        np.multiply(a, 1 - t, out=out)
        out += np.multiply(b, t, out=self._term)
        return out


class Recycled:
    """The arrays an evaluation hands out (each in-between's positions, its mixed radius and
    opacity), given again to the next evaluation once nothing else refers to them.

    A redo's frames are written to Blender and dropped; in a bpy process a fresh array of their
    size is a fresh mapping, page-faulted anew (about 2 us a page: a tenth of a redo). An array
    is reused only when this pool holds its one reference (no frame, no view of it is alive),
    and only the last evaluation's are kept, up to :data:`RECYCLED_BYTES`: kept memory is not
    let go while the frames are written (the writer drops each frame once Blender has its copy,
    which bounds a big run's peak memory).
    """

    def __init__(self):
        self._free, self._given = [], []

    def begin(self):
        """An evaluation starts: the arrays of the last one are candidates."""
        self._free, self._given = self._free + self._given, []

    def end(self):
        """It ended: keep its arrays only (the first of them, up to RECYCLED_BYTES)."""
        kept, total = [], 0
        for array in self._given:
            total += array.nbytes
            if total > RECYCLED_BYTES:
                break
            kept.append(array)
        self._free, self._given = [], kept

    def empty(self, shape):
        """A float array of ``shape``: one nothing refers to any more, else a new one."""
        free = self._free
        for i in range(len(free)):
            # Two references: the list's and getrefcount's argument.
            if free[i].shape == shape and sys.getrefcount(free[i]) == 2:
                array = free.pop(i)
                break
        else:
            array = np.empty(shape)
        self._given.append(array)
        return array


class FrameValues:
    """What the in-betweens take from the keys at the pairs' samples, whatever the time: their
    attributes on both keys (:class:`_Mix`), the discrete ones, the strokes without a partner.

    A plan makes it once for its samples and assembles every later frame from it.

    Parameters
    ----------
    parts : PairFrames
        Every pair's samples (the second strokes' fractions along them as drawn); their frames
        are not read.
    plan : InbetweenPlan
        Its ``strokes`` (each pair's two KeyStrokes), projected keys ``ka`` and ``kb``, ``held``
        strokes, ``unmatched`` choice and aligned ``extras``.
    """

    def __init__(self, parts, plan):
        strokes_a, strokes_b = [a for a, _, _ in plan.strokes], [b for _, b, _ in plan.strokes]
        held, extras = plan.held, plan.extras
        index_a = np.array([a.index for a in strokes_a], dtype=np.int64)
        index_b = np.array([b.index for b in strokes_b], dtype=np.int64)
        va, vb = _pair_values(parts, index_a, index_b, plan.ka, plan.kb)
        self.discrete = _Discrete(parts, plan, index_a, index_b, extras)
        self.anchors = Anchors(held, parts, plan) if plan.unmatched == "neighbour" and held else None
        self.drawn = [_as_drawn(h, extras) for h in held]
        self.materials = (
            np.array([a.material for a in strokes_a], dtype=np.int64),
            np.array([b.material for b in strokes_b], dtype=np.int64),
        )
        self.origin = np.c_[index_a, index_b].astype(np.int64).reshape(-1, 2)
        # Attributes the two keys agree on (often radius, opacity, colour and the offset from
        # the plane) are shared by every frame, not mixed: a redo of a big drawing is mostly
        # the frames' loop. Each block (depth, radius, opacity, colour, extras) is mixed only
        # where it differs.
        blocks = ((0, 1), (1, 2), (2, 3), (3, _BASE), (_BASE, plan.ka.width))
        self.mix = _Mix(va, vb, blocks, len(parts.u_a))
        self.depth = None if self.mix.differ[0] or not np.any(self.mix.block(0, 0.0)) else self.mix.block(0, 0.0)[:, 0]

    def frames(self, parts, plan, times, recycled=None):
        """One StrokeSet per time (:func:`assemble_frames`)."""
        held, plane, unmatched, extras, mix = plan.held, plan.plane, plan.unmatched, plan.extras, self.mix
        recycled = Recycled() if recycled is None else recycled
        size, out = len(parts.u_a), []
        # The plane offsets are lifted at once: one work column for every frame's.
        depth = np.empty(len(parts.u_a)) if mix.differ[0] else self.depth
        for ti, t in enumerate(times):
            if mix.differ[0]:
                mix.block(0, t, out=depth)
            points, curves = self.discrete.at(t)
            points.update(extras.from_columns(mix.block(_BASE, t)))
            drawing = StrokeSet(
                positions=plane.to_3d(parts.frames[ti], depth, out=recycled.empty((size, 3))),
                offsets=parts.offsets,
                cyclic=parts.closed,
                material_index=self.materials[0] if t < 0.5 else self.materials[1],
                radius=mix.block(1, t, out=recycled.empty((size,)) if mix.differ[1] else None)[:, 0],
                opacity=mix.block(2, t, out=recycled.empty((size,)) if mix.differ[2] else None)[:, 0],
                vertex_color=mix.block(3, t),
                origin=self.origin,
                point_attributes=points,
                curve_attributes=curves,
                attribute_types=extras.types,
            )
            shown = shown_strokes(held, self.drawn, t, unmatched, parts.frames[ti], self.anchors, plane)
            out.append(StrokeSet.concatenate([drawing, *shown]))
        return out


def assemble_frames(parts, plan, times, values=None, recycled=None):
    """One StrokeSet per time from every pair's frames and the strokes without a partner.

    Parameters
    ----------
    parts : PairFrames
        Every pair's samples at ``times`` (the second strokes' fractions along them as drawn).
    plan : InbetweenPlan
        Its ``strokes`` (each pair's two KeyStrokes), projected keys ``ka`` and ``kb``, ``held``
        strokes, drawing ``plane``, ``unmatched`` choice and aligned ``extras``.
    times : ndarray, shape (T,)
    values : FrameValues, optional
        Made from these samples before (else made here).
    recycled : Recycled, optional
        Where the frames' arrays come from (the plan's, kept from one evaluation to the next).

    Returns
    -------
    list of StrokeSet
    """
    return (FrameValues(parts, plan) if values is None else values).frames(parts, plan, times, recycled)
