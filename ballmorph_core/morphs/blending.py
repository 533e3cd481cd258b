"""Relative blending (paper section 7): incompatible stretches of a curve bridged by disk arcs.

Where the maximal disks of the gap fail on Q (a notch of Q that no disk tangent to P reaches, a
valley whose disks touch Q twice), the stretch of Q is replaced by the arc of the maximal disk
that touches both of its lips and P: ``Q' = R_P(Q)``; likewise ``P' = R_Q(P)``. The bridging
disk is found by bisection along P between the samples whose images jump across the stretch
(:func:`~ballmorph_core.ballmap.candidates.disk_between`). The composite ball-morph
(:mod:`.composite`) morphs between the blended curves.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..ballmap.candidates import disk_between
from ..errors import IncompatibleCurvesError
from ..geometry.polyline import curve_length, subcurve
from ..geometry.projection import distances_to_polyline

__all__ = ["Bridge", "bridges", "bridges_of", "blend"]

#: Incompatible stretches separated by at most this many good dense samples are bridged as one
#: (a notch's walls and lips are one feature).
MERGE_GAP = 6

#: Edges searched for a bridging disk's contact on each lip.
LIP_WINDOW = 16


@dataclass
class Bridge:
    """A stretch of a curve replaced by the arc of a maximal disk.

    Attributes
    ----------
    s0, s1 : float
        Arc length of the stretch's ends (the lips) on the dense curve (``s1`` may exceed the
        length for a loop).
    arc : ndarray, shape (k, 2)
        The bridging arc from the lip at ``s0`` to the lip at ``s1``.
    """

    s0: float
    s1: float
    arc: np.ndarray


def _runs(mask, closed):
    """Maximal runs of True as (first, last) index pairs (cyclic for loops; last may wrap)."""
    n = len(mask)
    if not mask.any():
        return []
    if mask.all():
        return [(0, n - 1)]
    starts = np.flatnonzero(mask & ~np.roll(mask, 1)) if closed else np.flatnonzero(mask & ~np.r_[False, mask[:-1]])
    runs = []
    for s in starts:
        e = s
        while mask[(e + 1) % n] and (closed or e + 1 < n):
            e += 1
            if e - s >= n:
                break
        runs.append((int(s), int(e)))
    return runs


def _arc(centre, radius, a, b, avoid, spacing):
    """Points of the circle from a to b along the side that does not contain ``avoid``."""
    ta, tb, tx = (np.arctan2(*(v - centre)[::-1]) for v in (a, b, avoid))
    ccw = np.mod(tb - ta, 2 * np.pi)
    sweep = ccw - 2 * np.pi if np.mod(tx - ta, 2 * np.pi) < ccw else ccw  # around, away from the avoided contact
    n = max(2, int(np.ceil(abs(sweep) * radius / spacing)) + 1)
    ang = ta + np.linspace(0.0, sweep, n)
    pts = centre + radius * np.stack([np.cos(ang), np.sin(ang)], axis=1)
    pts[0], pts[-1] = a, b
    return pts


def _stretches(bad, closed):
    """Runs of incompatible samples, those a few good samples apart merged into one feature."""
    n = len(bad)
    bad = bad.copy()
    for first, last in _runs(~bad, closed):
        if (last - first) % n + 1 <= MERGE_GAP and (closed or (first > 0 and last < n - 1)):
            bad[np.arange(first, first + (last - first) % n + 1) % n] = True
    return _runs(bad, closed)


def _jumping_samples(img, s_a, s_b, own, closed, name):
    """The samples of the other curve whose images come last before a stretch and first after it
    (cyclically for loops): the bridging disk's tangent point lies between them."""
    if closed:
        d = np.mod(img - s_a, own.length)
        outside = np.flatnonzero(d >= (s_b - s_a) - tol.ROUNDOFF * own.length)
        if len(outside) == 0:
            raise IncompatibleCurvesError(f"composite ball-morph: no disk bridges {name} near s={s_a:.4g}")
        return int(outside[np.argmax(d[outside])]), int(outside[np.argmin(d[outside])])
    before = np.flatnonzero(img <= s_a + tol.ROUNDOFF * own.length)
    after = np.flatnonzero(img >= s_b - tol.ROUNDOFF * own.length)
    if not len(before) or not len(after):
        raise IncompatibleCurvesError(f"composite ball-morph: no disk bridges {name} near s={s_a:.4g}")
    return int(before.max()), int(after.min())


def _lip_windows(lip_a, lip_b, n_edges, closed):
    wa = np.arange(lip_a - LIP_WINDOW, lip_a + 1)
    wb = np.arange(lip_b - 1, lip_b + LIP_WINDOW)
    if closed:
        return wa % n_edges, wb % n_edges
    return wa[(wa >= 0) & (wa < n_edges)], wb[(wb >= 0) & (wb < n_edges)]


@dataclass
class _Stretch:
    """An incompatible stretch of one curve, ready for its bridging disk (see :func:`_bridge`)."""

    maps: object
    own: object
    other: object
    closed: bool
    s_a: float
    ends: tuple
    windows: tuple


def _stretch(maps, side, first, last):
    """The stretch of samples ``first..last`` of curve ``side`` (_Stretch): its lips, the two
    samples of the other curve between which its bridging disk touches, and the lips' windows.

    Raises
    ------
    IncompatibleCurvesError
        If the stretch reaches a stroke's shared endpoint or no sample of the other curve maps
        past it.
    """
    closed = maps.setup.closed
    own, other = (maps.side_p, maps.side_q) if side == "P" else (maps.side_q, maps.side_p)
    other_map = maps.bwd if side == "P" else maps.fwd  # disks tangent to the other curve
    n, n_edges = len(own.pts), len(own.enormals)
    lip_a, lip_b = first - 1, last + 1
    if not closed and (lip_a < 0 or lip_b > n - 1):
        raise IncompatibleCurvesError(
            f"composite ball-morph: the incompatible stretch of {side} reaches a shared endpoint"
        )
    lip_a, lip_b = lip_a % n, lip_b % n
    s_a = own.cum[lip_a]
    s_b = own.cum[lip_b] + (own.length if closed and lip_b <= lip_a else 0.0)
    i, j = _jumping_samples(other_map.s_dst, s_a, s_b, own, closed, side)
    src, nrm_src = other_map.src, other_map.n_src
    ends = (src[i : i + 1], nrm_src[i : i + 1], src[j : j + 1], nrm_src[j : j + 1])
    windows = _lip_windows(lip_a, lip_b, n_edges, closed)
    return _Stretch(maps, own, other, closed, s_a, ends, windows)


def _bridge(stretch, side, x, nrm, r, qa, qb):
    """The Bridge over a stretch from its bridging disk (tangent point ``x``, normal ``nrm``,
    radius ``r``, contacts ``qa``, ``qb`` on the lips; each one row of :func:`disk_between`).

    Raises
    ------
    IncompatibleCurvesError
        If no disk bridges it.
    """
    own, other, maps = stretch.own, stretch.other, stretch.maps
    # A bridging disk larger than both curves together bridges nothing drawable.
    if not np.isfinite(r) or r <= 0 or r > own.length + other.length:
        raise IncompatibleCurvesError(f"composite ball-morph: no disk bridges {side} near s={stretch.s_a:.4g}")
    _, s_lips = distances_to_polyline(np.stack([qa, qb]), own.pts, stretch.closed, 2 * maps.spacing)
    s0, s1 = float(s_lips[0]), float(s_lips[1])
    if stretch.closed and s1 < s0:
        s1 += own.length
    return Bridge(s0, s1, _arc(x + r * nrm, r, qa, qb, x, maps.spacing))


def bridges(maps, side):
    """Relative blending of one curve against the other (list of Bridge).

    Parameters
    ----------
    maps : DenseMaps
    side : {'P', 'Q'}
        The curve whose incompatible stretches are bridged.

    Raises
    ------
    IncompatibleCurvesError
        If a stretch reaches a stroke's shared endpoint or no bridging disk is found.
    """
    (out,) = bridges_of([maps], side)
    if isinstance(out, IncompatibleCurvesError):
        raise out
    return out


def bridges_of(all_maps, side):
    """:func:`bridges` of many pairs at once, every bridging disk in one bisection.

    Parameters
    ----------
    all_maps : list of DenseMaps
    side : {'P', 'Q'}

    Returns
    -------
    list of (list of Bridge) or IncompatibleCurvesError
        Per pair, its bridges or the error :func:`bridges` raises for it (its first failing
        stretch's, in order along the curve). Each row of the bisection is its own stretch's,
        with its pair's tolerance: the same disks as alone.
    """
    out, stretches = [None] * len(all_maps), []
    first_error = {}
    for c, maps in enumerate(all_maps):
        own_map = maps.fwd if side == "P" else maps.bwd  # disks tangent to this curve
        for first, last in _stretches(own_map.bad, maps.setup.closed):
            try:
                stretches.append((c, _stretch(maps, side, first, last)))
            except IncompatibleCurvesError as exc:
                first_error[c] = exc  # the stretches before it may fail first, on their disks
                break
    disks = _disks([st for _, st in stretches])
    found = {c: [] for c in range(len(all_maps))}
    for (c, st), disk in zip(stretches, disks):
        if c in found:
            try:
                found[c].append(_bridge(st, side, *disk))
            except IncompatibleCurvesError as exc:
                first_error[c] = exc
                del found[c]
    for c in range(len(all_maps)):
        out[c] = first_error[c] if c in first_error else found[c]
    return out


def _disks(stretches):
    """Every stretch's bridging disk by one :func:`disk_between` (rows of their curves' edges,
    each curve's laid once, one after the other): ``(x, nrm, r, qa, qb)`` per stretch, each one
    row."""
    if not stretches:
        return []
    laid, first, base, count = [], {}, [], 0  # each curve (a stretch's own side, by identity) once
    for st in stretches:
        if id(st.own) not in first:
            first[id(st.own)] = count
            laid.append(_edges(st.own, st.closed))
            count += len(laid[-1][0])
        base.append(first[id(st.own)])
    edges = tuple(np.concatenate([e[k] for e in laid]) for k in range(3))
    ends = tuple(np.concatenate([st.ends[k] for st in stretches]) for k in range(4))
    windows = tuple([st.windows[k] + b for st, b in zip(stretches, base)] for k in range(2))
    eps = np.array([st.maps.eps for st in stretches])
    x, nrm, r, qa, qb = disk_between(ends, edges, windows, eps)
    return list(zip(x, nrm, r, qa, qb))


def _edges(own, closed):
    """A dense curve's edges ``a -> b`` and their gap normals, shapes (E, 2) each."""
    n_edges = len(own.enormals)
    b = np.roll(own.pts, -1, axis=0)[:n_edges] if closed else own.pts[1:]
    return own.pts[:n_edges], b, own.enormals


def _blend_order(items, closed, length):
    """Arcs and kept stretches in order along the blended curve: ('arc', Bridge) / ('kept', (s0, s1))."""
    order = []
    if closed:
        # A loop alternates arcs and kept stretches, starting at the first bridge.
        for k, br in enumerate(items):
            nxt = items[k + 1].s0 if k + 1 < len(items) else items[0].s0 + length
            order += [("arc", br), ("kept", (br.s1, nxt))]
        return order
    start = 0.0
    for br in items:
        order += [("kept", (start, br.s0)), ("arc", br)]
        start = br.s1
    return [*order, ("kept", (start, length))]


def blend(curve, closed, length, items):
    """The curve with each bridged stretch replaced by its arc.

    Returns
    -------
    blended : ndarray, shape (M, 2)
        For a loop it starts at the first bridge's first lip.
    pieces : list of tuple
        Per bridge (sorted by ``s0``) ``(t0, t1)``: where its arc starts and ends on the
        blended curve.
    offsets : list of tuple
        ``(s_start, s_end, t_start)`` of every kept stretch: position ``s`` of the curve (for a
        loop, unwrapped from the first bridge) maps to ``t_start + (s - s_start)``.
    """
    if not items:
        return curve, [], [(0.0, length, 0.0)]
    parts, pieces, offsets, t = [], [], [], 0.0
    for what, item in _blend_order(sorted(items, key=lambda b: b.s0), closed, length):
        if what == "arc":
            pts = item.arc
            pieces.append((t, t + curve_length(pts, False)))
        else:
            s0, s1 = item
            if s1 - s0 <= 0:
                continue
            pts = subcurve(curve, closed, s0, s1)
            offsets.append((s0, s1, t))
        parts.append(pts if not parts else pts[1:])
        t += curve_length(pts, False)
    blended = np.concatenate(parts)
    return (blended[:-1] if closed else blended), pieces, offsets  # a loop's last stretch ends at its first arc
