"""Composite ball-morph for curves that are not b-compatible (paper section 7).

1. *Relative blending.* Where the maximal disks of the gap fail on Q (a notch of Q that no disk
   tangent to P reaches, a valley whose disks touch Q twice), the stretch of Q is replaced by
   the arc of the maximal disk that touches both of its lips and P: ``Q' = R_P(Q)``. Likewise
   ``P' = R_Q(P)``. The bridging disk is found by bisection along P between the samples whose
   images jump across the stretch (:func:`~ballmorph_core.ballmap.disk_between`).
2. *Central morph.* ``M0`` is the ball-morph from ``P'`` to ``Q'``.
3. *Extension morphs.* Each replaced stretch is a stroke pair sharing its endpoints with its
   bridging arc. ``M1`` goes from each arc of ``Q'`` to its stretch of ``Q`` and ``M-1`` from
   each stretch of ``P`` to its arc of ``P'``: a ball-morph if that pair is b-compatible, else
   the closest-projection morph (straight lines, the paper's Fig. 21 left) if it is a
   homeomorphism, else linear interpolation. (The paper recurses on the stretch instead of the
   last fallback; one level of relative blending per side is what we implement.)
4. *Synchronisation.* Every sample's trajectory is the concatenation of its paths through
   ``M-1``, ``M0`` and ``M1`` (piecewise circular for the circular kind), traversed at constant
   speed over [0, 1], the paper's simplest choice. Samples come from all three stages (P's
   stretches, both curves through ``M0``, Q's stretches), pushed through the others by
   interpolating each stage's monotone correspondence, then ordered and thinned to the
   spacing like the symmetric ball-map sampling.
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..ballmap.candidates import disk_between
from ..ballmap.correspondence import dense_maps
from ..ballmap.topology import orient_pair
from ..errors import BallMorphError, IncompatibleCurvesError, InvalidCurveError
from ..geometry.polyline import curve_length, resolve_spacing, subcurve
from ..geometry.projection import distances_to_polyline
from .ball import input_fractions
from .base import PathMorph, build, register, registered
from .paths import SampledPaths

__all__ = ["Bridge", "bridges", "blend"]

#: Points per stage on each sampled trajectory.
_STAGE_POINTS = 24


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
    if np.mod(tx - ta, 2 * np.pi) < ccw:
        sweep = ccw - 2 * np.pi  # go clockwise around, away from the avoided contact
    else:
        sweep = ccw
    n = max(2, int(np.ceil(abs(sweep) * radius / spacing)) + 1)
    ang = ta + np.linspace(0.0, sweep, n)
    pts = centre + radius * np.stack([np.cos(ang), np.sin(ang)], axis=1)
    pts[0], pts[-1] = a, b
    return pts


def bridges(maps, side, window=16):
    """Relative blending of one curve against the other (list of Bridge).

    Parameters
    ----------
    maps : DenseMaps
    side : {'P', 'Q'}
        The curve whose incompatible stretches are bridged.
    window : int
        Edges searched on each lip.

    Raises
    ------
    IncompatibleCurvesError
        If a stretch reaches a stroke's shared endpoint or no bridging disk is found.
    """
    closed = maps.setup.closed
    own, other = (maps.side_p, maps.side_q) if side == "P" else (maps.side_q, maps.side_p)
    own_map = maps.fwd if side == "P" else maps.bwd  # disks tangent to this curve
    other_map = maps.bwd if side == "P" else maps.fwd  # disks tangent to the other curve
    n = len(own.pts)
    # Incompatible stretches a few samples apart are one feature (a notch's two walls and
    # its lips): bridge them together.
    bad = own_map.bad.copy()
    for first, last in _runs(~bad, closed):
        if (last - first) % n + 1 <= tol.COMPOSITE_MERGE_GAP and (closed or (first > 0 and last < n - 1)):
            bad[np.arange(first, first + (last - first) % n + 1) % n] = True
    runs = _runs(bad, closed)
    if not runs:
        return []
    n_edges = len(own.enormals)
    a_e, b_e = own.pts[:n_edges], np.roll(own.pts, -1, axis=0)[:n_edges] if closed else own.pts[1:]
    out = []
    for first, last in runs:
        lip_a, lip_b = first - 1, last + 1
        if not closed and (lip_a < 0 or lip_b > n - 1):
            raise IncompatibleCurvesError(
                f"composite ball-morph: the incompatible stretch of {side} reaches a shared endpoint"
            )
        lip_a, lip_b = lip_a % n, lip_b % n
        s_a = own.cum[lip_a]
        s_b = own.cum[lip_b] + (own.length if closed and lip_b <= lip_a else 0.0)
        # The samples of the other curve whose images come last before the stretch and first
        # after it (cyclically for loops): the bridging disk's tangent point lies between.
        img = other_map.s_dst
        width = s_b - s_a
        if closed:
            d = np.mod(img - s_a, own.length)
            outside = np.flatnonzero(d >= width - tol.ROUNDOFF * own.length)
            if len(outside) == 0:
                raise IncompatibleCurvesError(f"composite ball-morph: no disk bridges {side} near s={s_a:.4g}")
            i, j = int(outside[np.argmax(d[outside])]), int(outside[np.argmin(d[outside])])
        else:
            before, after = (
                np.flatnonzero(img <= s_a + tol.ROUNDOFF * own.length),
                np.flatnonzero(img >= s_b - tol.ROUNDOFF * own.length),
            )
            if not len(before) or not len(after):
                raise IncompatibleCurvesError(f"composite ball-morph: no disk bridges {side} near s={s_a:.4g}")
            i, j = int(before.max()), int(after.min())
        wa = np.arange(lip_a - window, lip_a + 1)
        wb = np.arange(lip_b - 1, lip_b + window)
        if closed:
            wa, wb = wa % n_edges, wb % n_edges
        else:
            wa, wb = wa[(wa >= 0) & (wa < n_edges)], wb[(wb >= 0) & (wb < n_edges)]
        src = other_map.src
        x, nrm, r, qa, qb = disk_between(
            src[i : i + 1],
            other_map.n_src[i : i + 1],
            src[j : j + 1],
            other_map.n_src[j : j + 1],
            a_e,
            b_e,
            own.enormals,
            [wa],
            [wb],
            maps.eps,
        )
        # A bridging disk larger than both curves together bridges nothing drawable.
        if not np.isfinite(r[0]) or r[0] <= 0 or r[0] > own.length + other.length:
            raise IncompatibleCurvesError(f"composite ball-morph: no disk bridges {side} near s={s_a:.4g}")
        centre = x[0] + r[0] * nrm[0]
        dist, s_lips = distances_to_polyline(np.stack([qa[0], qb[0]]), own.pts, closed, 2 * maps.spacing)
        s0, s1 = float(s_lips[0]), float(s_lips[1])
        if closed and s1 < s0:
            s1 += own.length
        arc = _arc(centre, r[0], qa[0], qb[0], x[0], maps.spacing)
        out.append(Bridge(s0, s1, arc))
    return out


def blend(curve, closed, cum, length, items):
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
    items = sorted(items, key=lambda b: b.s0)
    order = []
    if closed:
        # A loop alternates arcs and kept stretches, starting at the first bridge.
        for k, br in enumerate(items):
            nxt = items[k + 1].s0 if k + 1 < len(items) else items[0].s0 + length
            order += [("arc", br), ("kept", (br.s1, nxt))]
    else:
        start = 0.0
        for br in items:
            order += [("kept", (start, br.s0)), ("arc", br)]
            start = br.s1
        order.append(("kept", (start, length)))
    parts, pieces, offsets = [], [], []
    t = 0.0
    for what, item in order:
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
    if closed:
        blended = blended[:-1]  # the last kept stretch ends where the first arc starts
    return blended, pieces, offsets


def _extension(A, B, kind, spacing, from_b):
    """Morph a stretch into its arc (or back), with the paper's fallbacks (Morph)."""
    for method, opts in ((f"{kind}-ball", {}), ("closest-projection", {"sampling": "q" if from_b else "p"})):
        if method not in registered():
            continue
        try:
            return build(A, B, method, False, spacing, opts.get("sampling", "symmetric"))
        except BallMorphError:
            continue
    try:
        return build(A, B, "linear-interpolation", False, spacing, "symmetric")
    except InvalidCurveError as exc:  # a stretch or arc collapsed to a point
        raise IncompatibleCurvesError(f"composite ball-morph: degenerate bridge ({exc})") from None


def _unwrap(u):
    """Unwrap cyclic fractions in [0, 1) into a non-decreasing sequence."""
    step = np.mod(np.diff(u), 1.0)
    step = np.where(step > 0.5, step - 1.0, step)
    return np.concatenate([[u[0]], u[0] + np.cumsum(step)])


class _Stage:
    """A morph between two curve stretches as a monotone graph with sampled paths."""

    def __init__(self, morph, len_a, len_b, closed):
        ts = np.linspace(0.0, 1.0, _STAGE_POINTS)
        self.paths = np.transpose(morph.frames(ts), (1, 0, 2))  # (K, S, 2)
        self.sa = morph.u_p * len_a
        self.sb = morph.u_q * len_b
        if closed:
            self.sa = _unwrap(morph.u_p) * len_a
            self.sb = _unwrap(morph.u_q) * len_b
        self.len_a, self.len_b, self.closed = len_a, len_b, closed

    def lam(self, s, which):
        """Fractional node index reaching position s on curve 'a' or 'b'."""
        ref = self.sa if which == "a" else self.sb
        length = self.len_a if which == "a" else self.len_b
        if self.closed:
            s = np.mod(s - ref[0], length) + ref[0]
        return np.interp(s, ref, np.arange(len(ref), dtype=np.float64))

    def at(self, lam):
        """Positions on both curves and the path at fractional nodes."""
        i = np.clip(np.floor(lam).astype(np.int64), 0, len(self.sa) - 1)
        j = np.minimum(i + 1, len(self.sa) - 1)
        f = (lam - i)[:, None]
        sa = (1 - f[:, 0]) * self.sa[i] + f[:, 0] * self.sa[j]
        sb = (1 - f[:, 0]) * self.sb[i] + f[:, 0] * self.sb[j]
        path = (1 - f[:, :, None]) * self.paths[i] + f[:, :, None] * self.paths[j]
        return sa, sb, path


def _to_original(t, offsets, pieces, stages, which, closed, blended_len, length):
    """Map positions t on a blended curve back to the original curve (and stage paths)."""
    s = np.full(len(t), np.nan)
    paths = np.zeros((len(t), _STAGE_POINTS, 2))
    has = np.zeros(len(t), dtype=bool)
    tt = np.mod(t, blended_len) if closed else t
    slack = tol.ROUNDOFF * blended_len
    for s0, s1, t0 in offsets:
        inside = (tt >= t0 - slack) & (tt <= t0 + (s1 - s0) + slack)
        s[inside] = s0 + (tt[inside] - t0)
    for (t0, t1), (stage, br) in zip(pieces, stages):
        inside = (tt >= t0 - slack) & (tt <= t1 + slack)
        if not inside.any():
            continue
        lam = stage.lam(tt[inside] - t0, which)
        sa, sb, path = stage.at(lam)
        local = sa if which == "b" else sb  # the stretch's side of the stage
        s[inside] = br.s0 + local
        paths[inside] = path
        has[inside] = True
    if closed:
        s = np.mod(s, length)
    return s, paths, has


@register("composite-ball")
def build_composite(P, Q, closed, spacing, sampling, kind="circular"):
    """Composite ball-morph (see the module docstring). ``kind`` is the path of every stage's
    ball-morph ('circular', 'linear', 'parabolic', 'hat', 'tangent')."""
    setup = orient_pair(P, Q, closed)
    spacing = resolve_spacing(P, Q, closed, spacing)
    method = f"{kind}-ball"
    if setup.coincident:
        return build(P, Q, method, closed, spacing, sampling)
    h = spacing / 2.0
    maps = dense_maps(setup.P, setup.Q, closed, h, setup)
    if not maps.report.violations:
        return build(P, Q, method, closed, spacing, sampling)
    sp, sq = maps.side_p, maps.side_q
    bridges_p, bridges_q = bridges(maps, "P"), bridges(maps, "Q")
    P1, pieces_p, off_p = (
        blend(sp.pts, closed, sp.cum, sp.length, bridges_p) if bridges_p else (sp.pts, [], [(0.0, sp.length, 0.0)])
    )
    Q1, pieces_q, off_q = (
        blend(sq.pts, closed, sq.cum, sq.length, bridges_q) if bridges_q else (sq.pts, [], [(0.0, sq.length, 0.0)])
    )
    # The bridging arcs are focal for M0 (every disk tangent to an arc is the bridging disk
    # itself, touching both lips): the check flags them, as it should for a generic pair.
    # Only violations away from the arcs mean the blended curves are still incompatible.
    try:
        m0 = build(P1, Q1, method, closed, spacing, "symmetric", check=False)
    except IncompatibleCurvesError as exc:
        raise IncompatibleCurvesError(f"composite ball-morph: blended curves are not morphable ({exc})") from None
    slack = 2 * spacing
    real = [
        v
        for v in m0.correspondence.report.violations
        if not any(t0 - slack <= v.s_p <= t1 + slack for t0, t1 in pieces_p)
        and not any(t0 - slack <= v.s_q <= t1 + slack for t0, t1 in pieces_q)
    ]
    if real:
        m0.correspondence.report.violations = real
        raise IncompatibleCurvesError(
            "composite ball-morph: still not b-compatible after one relative blending: "
            + m0.correspondence.report.describe(),
            m0.correspondence.report,
        )
    len_p1, len_q1 = curve_length(P1, closed), curve_length(Q1, closed)
    central = _Stage(m0, len_p1, len_q1, closed)
    # Extension stages: P stretch -> P' arc (M-1), Q' arc -> Q stretch (M1).
    ext_p = []
    for br in bridges_p:
        stretch = subcurve(sp.pts, closed, br.s0, br.s1)
        morph = _extension(stretch, br.arc, kind, spacing, from_b=False)
        ext_p.append((_Stage(morph, curve_length(stretch, False), curve_length(br.arc, False), False), br))
    ext_q = []
    for br in bridges_q:
        stretch = subcurve(sq.pts, closed, br.s0, br.s1)
        morph = _extension(br.arc, stretch, kind, spacing, from_b=True)
        ext_q.append((_Stage(morph, curve_length(br.arc, False), curve_length(stretch, False), False), br))

    # Sample positions on P' and Q' from every stage.
    lam0 = [np.arange(len(central.sa), dtype=np.float64)]
    for (t0, _), (stage, _) in zip(pieces_p, ext_p):
        lam0.append(central.lam(t0 + stage.sb, "a"))
    for (t0, _), (stage, _) in zip(pieces_q, ext_q):
        lam0.append(central.lam(t0 + stage.sa, "b"))
    lam0 = np.unique(np.concatenate(lam0))
    t_p1, t_q1, path0 = central.at(lam0)
    s_p, path_p, has_p = _to_original(t_p1, off_p, pieces_p, ext_p, "b", closed, len_p1, sp.length)
    s_q, path_q, has_q = _to_original(t_q1, off_q, pieces_q, ext_q, "a", closed, len_q1, sq.length)
    ok = np.isfinite(s_p) & np.isfinite(s_q)
    # Whole trajectory: stretch -> arc (M-1), then M0, then arc -> stretch (M1).
    start = path0[:, :1]  # no M-1 stage: the sample waits at its start
    parts = [np.where(has_p[:, None, None], path_p, np.repeat(start, _STAGE_POINTS, axis=1)), path0]
    end = path0[:, -1:]
    parts.append(np.where(has_q[:, None, None], path_q, np.repeat(end, _STAGE_POINTS, axis=1)))
    full = np.concatenate(parts, axis=1)[ok]
    s_p, s_q = s_p[ok], s_q[ok]
    # Order along both curves and thin to the spacing (as the symmetric ball-map does).
    up = _unwrap(s_p / sp.length) * sp.length if closed else s_p
    uq = _unwrap(s_q / sq.length) * sq.length if closed else s_q
    order = np.argsort(up + uq, kind="stable")
    full, up, uq, s_p, s_q = full[order], up[order], uq[order], s_p[order], s_q[order]
    mono = (up >= np.maximum.accumulate(up) - tol.ROUNDOFF * sp.length) & (
        uq >= np.maximum.accumulate(uq) - tol.ROUNDOFF * sq.length
    )
    full, up, uq, s_p, s_q = full[mono], up[mono], uq[mono], s_p[mono], s_q[mono]
    tau = np.concatenate([[0.0], np.cumsum(np.maximum(np.diff(up), np.diff(uq)))])
    count = max(int(round(tau[-1] / spacing)), 2)
    targets = np.linspace(0.0, tau[-1], count + 1)
    if closed:
        targets = targets[:-1]
    keep = np.unique(np.clip(np.searchsorted(tau, targets), 0, len(tau) - 1))
    full, s_p, s_q = full[keep], s_p[keep], s_q[keep]
    u_p = input_fractions(s_p, sp.pts, closed, setup.reversed_p)
    u_q = input_fractions(s_q, sq.pts, closed, setup.reversed_q)
    if setup.reversed_p:
        flip = np.r_[0, np.arange(len(full) - 1, 0, -1)] if closed else np.arange(len(full))[::-1]
        full, u_p, u_q = full[flip], u_p[flip], u_q[flip]
    if len(full) < (3 if closed else 2):
        raise IncompatibleCurvesError("composite ball-morph: the chained correspondence kept too few samples")
    morph = PathMorph("composite-ball", closed, SampledPaths(full), u_p, u_q)
    morph.stages = {"P'": P1, "Q'": Q1, "bridges_p": bridges_p, "bridges_q": bridges_q}
    return morph
