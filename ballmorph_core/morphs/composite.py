"""Composite ball-morph for curves that are not b-compatible (paper section 7).

1. *Relative blending* (:mod:`.blending`): each curve's incompatible stretches are replaced by
   the arcs of the disks that bridge them, giving ``P'`` and ``Q'``.
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
   interpolating each stage's monotone correspondence, then ordered and thinned to the spacing
   exactly as the symmetric ball-map sampling is (:mod:`~ballmorph_core.ballmap.thinning`).
"""

from dataclasses import dataclass

import numpy as np

from .. import tolerances as tol
from ..ballmap.correspondence import dense_maps
from ..ballmap.thinning import running_backsteps, uniform_picks
from ..ballmap.topology import orient_pair
from ..errors import BallMorphError, IncompatibleCurvesError, InvalidCurveError
from ..geometry.polyline import curve_length, resolve_spacing, reversal_order, subcurve
from .ball import input_fractions
from .base import PathMorph, build, register, registered
from .blending import blend, bridges
from .paths import SampledPaths

__all__ = ["build_composite"]

#: Points per stage on each sampled trajectory.
_STAGE_POINTS = 24


def _extension(A, B, kind, spacing, from_b):
    """Morph a stretch into its arc (or back), with the paper's fallbacks (Morph)."""
    for method, sampling in ((f"{kind}-ball", "symmetric"), ("closest-projection", "q" if from_b else "p")):
        if method not in registered():
            continue
        try:
            return build(A, B, method, False, spacing, sampling)
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
        self.sa = (_unwrap(morph.u_p) if closed else morph.u_p) * len_a
        self.sb = (_unwrap(morph.u_q) if closed else morph.u_q) * len_b
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


@dataclass
class _Blended:
    """One curve after relative blending: the blended curve, its arcs, its kept stretches and the
    extension stages (stretch <-> arc)."""

    side: object
    bridges: list
    curve: np.ndarray
    pieces: list
    offsets: list
    stages: list = None


def _blended(side, items, closed, kind, spacing, to_arc):
    out = _Blended(side, items, *blend(side.pts, closed, side.length, items))
    out.stages = []
    for br in items:
        stretch = subcurve(side.pts, closed, br.s0, br.s1)
        a, b = (stretch, br.arc) if to_arc else (br.arc, stretch)
        morph = _extension(a, b, kind, spacing, from_b=not to_arc)
        out.stages.append((_Stage(morph, curve_length(a, False), curve_length(b, False), False), br))
    return out


def _central(bp, bq, closed, method, spacing):
    """``M0`` between the blended curves; only violations away from the arcs are real."""
    try:
        m0 = build(bp.curve, bq.curve, method, closed, spacing, "symmetric", check=False)
    except IncompatibleCurvesError as exc:
        raise IncompatibleCurvesError(f"composite ball-morph: blended curves are not morphable ({exc})") from None
    # The bridging arcs are focal for M0 (every disk tangent to an arc is the bridging disk
    # itself, touching both lips): the check flags them, as it should for a generic pair.
    slack = 2 * spacing
    report = m0.correspondence.report
    report.violations = [
        v
        for v in report.violations
        if not any(t0 - slack <= v.s_p <= t1 + slack for t0, t1 in bp.pieces)
        and not any(t0 - slack <= v.s_q <= t1 + slack for t0, t1 in bq.pieces)
    ]
    if report.violations:
        raise IncompatibleCurvesError(
            "composite ball-morph: still not b-compatible after one relative blending: " + report.describe(), report
        )
    return _Stage(m0, curve_length(bp.curve, closed), curve_length(bq.curve, closed), closed)


def _to_original(t, blended, which, closed, blended_len):
    """Map positions t on a blended curve back to the original curve (and the stage paths)."""
    s = np.full(len(t), np.nan)
    paths = np.zeros((len(t), _STAGE_POINTS, 2))
    has = np.zeros(len(t), dtype=bool)
    tt = np.mod(t, blended_len) if closed else t
    slack = tol.ROUNDOFF * blended_len
    for s0, s1, t0 in blended.offsets:
        inside = (tt >= t0 - slack) & (tt <= t0 + (s1 - s0) + slack)
        s[inside] = s0 + (tt[inside] - t0)
    for (t0, t1), (stage, br) in zip(blended.pieces, blended.stages):
        inside = (tt >= t0 - slack) & (tt <= t1 + slack)
        if not inside.any():
            continue
        sa, sb, path = stage.at(stage.lam(tt[inside] - t0, which))
        s[inside] = br.s0 + (sa if which == "b" else sb)  # the stretch's side of the stage
        paths[inside] = path
        has[inside] = True
    if closed:
        s = np.mod(s, blended.side.length)
    return s, paths, has


def _chained(central, bp, bq, closed):
    """Every sample's whole trajectory (stretch -> arc, M0, arc -> stretch) and its positions on
    the original P and Q."""
    lam0 = [np.arange(len(central.sa), dtype=np.float64)]
    lam0 += [central.lam(t0 + stage.sb, "a") for (t0, _), (stage, _) in zip(bp.pieces, bp.stages)]
    lam0 += [central.lam(t0 + stage.sa, "b") for (t0, _), (stage, _) in zip(bq.pieces, bq.stages)]
    t_p1, t_q1, path0 = central.at(np.unique(np.concatenate(lam0)))
    s_p, path_p, has_p = _to_original(t_p1, bp, "b", closed, central.len_a)
    s_q, path_q, has_q = _to_original(t_q1, bq, "a", closed, central.len_b)
    # A sample without an extension stage waits at its start (or end) meanwhile.
    before = np.where(has_p[:, None, None], path_p, np.repeat(path0[:, :1], _STAGE_POINTS, axis=1))
    after = np.where(has_q[:, None, None], path_q, np.repeat(path0[:, -1:], _STAGE_POINTS, axis=1))
    ok = np.isfinite(s_p) & np.isfinite(s_q)
    return np.concatenate([before, path0, after], axis=1)[ok], s_p[ok], s_q[ok]


def _thinned(full, s_p, s_q, sp, sq, closed, spacing):
    """Order the chained samples along both curves and thin them to the spacing."""
    up = _unwrap(s_p / sp.length) * sp.length if closed else s_p
    uq = _unwrap(s_q / sq.length) * sq.length if closed else s_q
    order = np.argsort(up + uq, kind="stable")
    full, up, uq, s_p, s_q = full[order], up[order], uq[order], s_p[order], s_q[order]
    one, span = np.zeros(len(up), dtype=np.int64), 4.0 * (max(sp.length, sq.length) + 1.0)
    mono = (running_backsteps(up, one, span) <= tol.ROUNDOFF * sp.length) & (
        running_backsteps(uq, one, span) <= tol.ROUNDOFF * sq.length
    )
    lengths = (np.array([sp.length]), np.array([sq.length]))
    keep = np.flatnonzero(mono)[
        uniform_picks(up[mono], uq[mono], one[mono], 1, *lengths, np.array([closed]), np.array([spacing]))
    ]
    return full[keep], s_p[keep], s_q[keep]


@register("composite-ball")
def build_composite(P, Q, closed, spacing, sampling, kind="circular"):
    """Composite ball-morph (see the module docstring). ``kind`` is the path of every stage's
    ball-morph ('circular', 'linear', 'parabolic', 'hat', 'tangent')."""
    setup = orient_pair(P, Q, closed)
    spacing = resolve_spacing(P, Q, closed, spacing)
    method = f"{kind}-ball"
    if setup.coincident:
        return build(P, Q, method, closed, spacing, sampling)
    maps = dense_maps(setup.P, setup.Q, closed, spacing / 2.0, setup)
    if not maps.report.violations:
        return build(P, Q, method, closed, spacing, sampling)
    sp, sq = maps.side_p, maps.side_q
    bp = _blended(sp, bridges(maps, "P"), closed, kind, spacing, to_arc=True)
    bq = _blended(sq, bridges(maps, "Q"), closed, kind, spacing, to_arc=False)
    central = _central(bp, bq, closed, method, spacing)
    full, s_p, s_q = _thinned(*_chained(central, bp, bq, closed), sp, sq, closed, spacing)
    u_p = input_fractions(s_p, sp.pts, closed, setup.reversed_p)
    u_q = input_fractions(s_q, sq.pts, closed, setup.reversed_q)
    if setup.reversed_p:
        flip = reversal_order(len(full), closed)
        full, u_p, u_q = full[flip], u_p[flip], u_q[flip]
    if len(full) < (3 if closed else 2):
        raise IncompatibleCurvesError("composite ball-morph: the chained correspondence kept too few samples")
    morph = PathMorph("composite-ball", closed, SampledPaths(full), u_p, u_q)
    morph.stages = {"P'": bp.curve, "Q'": bq.curve, "bridges_p": bp.bridges, "bridges_q": bq.bridges}
    return morph
