"""The in-between drawings: every pair's samples lifted back to 3D, with the attributes of the
points they come from mixed in time, plus the strokes without a partner."""

from dataclasses import dataclass

import numpy as np

from .strokes import StrokeSet

__all__ = ["Held", "assemble_frames"]


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


def _pair_values(parts, strokes_a, strokes_b, ka, kb):
    """Per sample: the values (plane offset, radius, opacity, colour) on both keys, shape (K, 7) each."""
    sizes = np.diff(parts.offsets)
    if not sizes.sum():
        return np.zeros((0, 7)), np.zeros((0, 7))
    va = ka.sample(np.repeat(strokes_a, sizes), parts.u_a)
    vb = kb.sample(np.repeat(strokes_b, sizes), parts.u_b)
    return va, vb


def _held_strokes(held, t, unmatched):
    """The held strokes shown at time ``t`` as (points, values, size, cyclic, material, origin)."""
    out = []
    for h in held:
        if unmatched != "hold" and (t >= 0.5 if h.from_a else t < 0.5):
            continue
        s = h.key.strokes
        sl = s.points(h.index)
        origin = (h.index, -1) if h.from_a else (-1, h.index)
        out.append(
            (
                s.positions[sl],
                h.key.values[sl, 1:],
                sl.stop - sl.start,
                s.cyclic[h.index],
                s.material_index[h.index],
                origin,
            )
        )
    return out


def _with_held(drawing, shown):
    """A frame's StrokeSet with the held strokes appended."""
    if not shown:
        return drawing
    values = np.concatenate([np.c_[drawing.radius, drawing.opacity, drawing.vertex_color], *[v for _, v, *_ in shown]])
    sizes = np.r_[drawing.sizes, [size for _, _, size, *_ in shown]].astype(np.int64)
    return StrokeSet(
        positions=np.concatenate([drawing.positions, *[p for p, *_ in shown]]),
        offsets=np.concatenate([[0], np.cumsum(sizes)]),
        cyclic=np.r_[drawing.cyclic, [c for *_, c, _, _ in shown]],
        material_index=np.r_[drawing.material_index, [m for *_, m, _ in shown]],
        radius=values[:, 0],
        opacity=values[:, 1],
        vertex_color=values[:, 2:6],
        origin=np.concatenate([drawing.origin, np.array([o for *_, o in shown], dtype=np.int64).reshape(-1, 2)]),
    )


def assemble_frames(parts, plan, times):
    """One StrokeSet per time from every pair's frames and the strokes without a partner.

    Parameters
    ----------
    parts : PairFrames
        Every pair's samples at ``times`` (the second strokes' fractions along them as drawn).
    plan : InbetweenPlan
        Its ``strokes`` (each pair's two KeyStrokes), projected keys ``ka`` and ``kb``, ``held``
        strokes, drawing ``plane`` and ``unmatched`` choice.
    times : ndarray, shape (T,)

    Returns
    -------
    list of StrokeSet
    """
    strokes_a, strokes_b = [a for a, _, _ in plan.strokes], [b for _, b, _ in plan.strokes]
    ka, kb, held, plane, unmatched = plan.ka, plan.kb, plan.held, plan.plane, plan.unmatched
    index_a = np.array([a.index for a in strokes_a], dtype=np.int64)
    index_b = np.array([b.index for b in strokes_b], dtype=np.int64)
    va, vb = _pair_values(parts, index_a, index_b, ka, kb)
    mat_a = np.array([a.material for a in strokes_a], dtype=np.int64)
    mat_b = np.array([b.material for b in strokes_b], dtype=np.int64)
    origin = np.c_[index_a, index_b].astype(np.int64).reshape(-1, 2)
    # Attributes the two keys agree on (often radius, opacity, colour and the offset from the
    # plane) are shared by every frame, not mixed: a redo of a big drawing is mostly this loop.
    differ = np.any(va != vb, axis=0)  # (7,)
    va_d, vb_d = va[:, differ], vb[:, differ]
    depth = va[:, 0] if np.any(va[:, 0]) else None
    out = []
    for ti, t in enumerate(times):
        mix = va
        if differ.any():
            mix = va.copy()
            mix[:, differ] = (1 - t) * va_d + t * vb_d
            depth = mix[:, 0] if differ[0] else depth
        drawing = StrokeSet(
            positions=plane.to_3d(parts.frames[ti], depth),
            offsets=parts.offsets,
            cyclic=parts.closed,
            material_index=mat_a if t < 0.5 else mat_b,
            radius=mix[:, 1],
            opacity=mix[:, 2],
            vertex_color=mix[:, 3:7],
            origin=origin,
        )
        out.append(_with_held(drawing, _held_strokes(held, t, unmatched)))
    return out
