"""Strokes without a partner: what they do over the in-betweens.

A stroke of the first key with no partner in the second *goes* over the in-betweens; one of the
second key *comes*. ``unmatched`` says how (:data:`~ballmorph_core.options.UNMATCHED`):

* ``'middle'``: shown as drawn until the middle (or from it);
* ``'hold'``: shown as drawn on every in-between;
* ``'fade'``: shown as drawn, its opacity fading out (or in) over the in-betweens;
* ``'shrink'``: it slides along itself into the point at its middle (or grows out of it);
* ``'neighbour'``: it shrinks into (or grows out of) the nearest point of its nearest stroke
  that has a partner, following that point as it moves (a sweat drop leaving a cheek); with no
  such stroke, ``'shrink'``.

``tau`` below is how far gone a stroke is: ``t`` for one that goes, ``1 - t`` for one that comes.
"""

import numpy as np

from ...geometry.spatial import PointTree

__all__ = ["Anchors", "unmatched_at", "shown_strokes"]


class Anchors:
    """Where each stroke without a partner shrinks to with ``'neighbour'``: a sample of a pair.

    Parameters
    ----------
    held : list of Held
    parts : PairFrames
        Every pair's samples (their fractions along the keys' strokes as drawn).
    plan : InbetweenPlan
        Its projected keys and pairs.

    Attributes
    ----------
    sample : list of int or None
        Per held stroke: the pair sample it is anchored to (an index into the frames' samples).
    origin : list of ndarray or None
        Per held stroke: that sample's position on the held stroke's own key, shape (2,).
    """

    def __init__(self, held, parts, plan):
        self.sample, self.origin = [], []
        sizes = np.diff(parts.offsets)
        keyed = {}
        for from_a, key in ((True, plan.ka), (False, plan.kb)):
            if not sizes.sum():
                continue
            index = np.array([(a if from_a else b).index for a, b, _ in plan.strokes], dtype=np.int64)
            stroke, u = np.repeat(index, sizes), parts.u_a if from_a else parts.u_b
            s = u * key.rg.length[stroke]
            keyed[from_a] = key.rg.point_at(stroke, np.where(key.rg.closed[stroke], s, np.clip(s, 0, None)))
        trees = {side: PointTree(points) for side, points in keyed.items()}
        for h in held:
            tree = trees.get(h.from_a)
            if tree is None:
                self.sample.append(None), self.origin.append(None)
                continue
            own = h.key.rg.curve(h.index)
            d2 = tree.nearest_d2(own)
            nearest = own[int(np.argmin(d2))]
            radius = np.sqrt(d2.min()) * (1 + 1e-9) + 1e-12
            _, found = tree.within(nearest[None], np.array([radius]))
            at = int(found[np.argmin(np.sum((keyed[h.from_a][found] - nearest) ** 2, axis=1))])
            self.sample.append(at), self.origin.append(keyed[h.from_a][at])


def _slid(points, closed, tau):
    """A stroke's points slid along it by the fraction ``tau`` towards its arc-length middle."""
    pts = np.r_[points, points[:1]] if closed else points
    s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))]
    middle = 0.5 * s[-1]
    target = middle + (1.0 - tau) * (s[: len(points)] - middle)
    return np.column_stack([np.interp(target, s, pts[:, c]) for c in range(points.shape[1])])


def unmatched_at(h, stroke, t, option, frame_2d, anchors, k, plane):
    """A stroke without a partner at time ``t`` (StrokeSet of one stroke, or None: not shown).

    Parameters
    ----------
    h : Held
    stroke : StrokeSet
        The stroke as drawn (3D, with all its attributes).
    t : float
    option : str
        One of :data:`~ballmorph_core.options.UNMATCHED`.
    frame_2d : ndarray, shape (K, 2)
        The pairs' samples at ``t`` in the drawing plane (for ``'neighbour'``).
    anchors : Anchors
    k : int
        Which held stroke ``h`` is (its index in ``anchors``).
    plane : Plane
    """
    tau = t if h.from_a else 1.0 - t
    if option == "hold":
        return stroke
    if option == "middle":  # at the middle itself the coming stroke shows, the going one has gone
        return stroke if (t < 0.5 if h.from_a else t >= 0.5) else None
    if tau >= 1.0:
        return None
    if option == "fade":
        out = stroke.replace_positions(stroke.positions)
        out.opacity = stroke.opacity * (1.0 - tau)
        return out
    xy, depth = plane.to_2d(stroke.positions)
    if option == "neighbour" and anchors.sample[k] is not None:
        anchor = frame_2d[anchors.sample[k]]
        moved = anchor + (1.0 - tau) * (xy - anchors.origin[k])
        return stroke.replace_positions(plane.to_3d(moved, depth * (1.0 - tau)))
    # 'shrink', or no neighbour to shrink into: a loop sliding along itself is open meanwhile.
    out = stroke.replace_positions(plane.to_3d(_slid(xy, bool(stroke.cyclic[0]), tau), depth))
    out.cyclic = stroke.cyclic & (tau <= 0.0)
    return out


def shown_strokes(held, drawn, t, option, frame_2d, anchors, plane):
    """Every stroke without a partner shown at ``t`` (list of StrokeSet); ``drawn[k]`` is held
    stroke ``k`` as drawn (a StrokeSet of one stroke)."""
    out = []
    for k, h in enumerate(held):
        shown = unmatched_at(h, drawn[k], t, option, frame_2d, anchors, k, plane)
        if shown is not None:
            out.append(shown)
    return out
