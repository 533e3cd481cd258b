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
from ..ballmap.correspondence import dense_map_batch
from ..ballmap.thinning import running_backsteps, uniform_picks
from ..ballmap.topology import orient_pairs
from ..errors import BallMorphError, IncompatibleCurvesError, InvalidCurveError
from ..geometry.polyline import curve_length, resolve_spacing, reversal_order, subcurve
from .ball import ball_morphs, input_fractions
from .base import PathMorph, build, register, registered
from .blending import blend, bridges_of
from .paths import SampledPaths

__all__ = ["build_composite", "build_composites"]

#: Points per stage on each sampled trajectory.
_STAGE_POINTS = 24


def _extension_fallback(A, B, kind, spacing, from_b):
    """The paper's fallbacks of an extension stage whose ball-morph failed (Morph): the
    closest-projection morph if it is a homeomorphism, else linear interpolation."""
    if "closest-projection" in registered():
        try:
            return build(A, B, "closest-projection", False, spacing, "q" if from_b else "p")
        except BallMorphError:
            pass
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


def _stretches_and_arcs(side, items, closed, to_arc):
    """Each bridge's extension pair: ``(a, b)``, stretch -> arc (``to_arc``) or arc -> stretch."""
    pairs = []
    for br in items:
        stretch = subcurve(side.pts, closed, br.s0, br.s1)
        pairs.append((stretch, br.arc) if to_arc else (br.arc, stretch))
    return pairs


def _blended(side, items, closed, kind, spacing, to_arc, pairs, morphs):
    """One curve blended (:func:`~.blending.blend`) with its extension stages, from the
    extension ``pairs`` and their ball-morphs (or errors) ``morphs``."""
    out = _Blended(side, items, *blend(side.pts, closed, side.length, items))
    out.stages = []
    for br, (a, b), morph in zip(items, pairs, morphs):
        if isinstance(morph, BallMorphError):
            morph = _extension_fallback(a, b, kind, spacing, from_b=not to_arc)
        out.stages.append((_Stage(morph, curve_length(a, False), curve_length(b, False), False), br))
    return out


def _central(bp, bq, closed, spacing, m0):
    """``M0`` between the blended curves (its ball-morph, or the error building it raised);
    only violations away from the arcs are real."""
    if isinstance(m0, IncompatibleCurvesError):
        raise IncompatibleCurvesError(f"composite ball-morph: blended curves are not morphable ({m0})") from None
    if isinstance(m0, BallMorphError):
        raise m0
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
    one = np.zeros(len(up), dtype=np.int64)
    mono = (running_backsteps(up, one) <= tol.ROUNDOFF * sp.length) & (
        running_backsteps(uq, one) <= tol.ROUNDOFF * sq.length
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
    (morph,) = build_composites([(P, Q, closed, spacing, sampling)], kind)
    if isinstance(morph, BallMorphError):
        raise morph
    return morph


class _Pair:
    """One pair of :func:`build_composites` on its way: what its stages made so far."""

    def __init__(self, k, P, Q, closed, spacing, sampling, setup):
        self.k, self.P, self.Q, self.closed, self.spacing, self.sampling = k, P, Q, closed, spacing, sampling
        self.setup, self.maps, self.blended = setup, None, {}


class _Results:
    """Each pair's result of :func:`build_composites`: its morph or its first error."""

    def __init__(self, n):
        self.out = [None] * n

    def attempt(self, pair, step, *args):
        """``step(*args)`` for ``pair``; should it raise, its error is the pair's result (and None returned)."""
        try:
            return step(*args)
        except BallMorphError as exc:
            self.out[pair.k] = exc
            return None

    def settle(self, pair, step, *args):
        """The pair's result: ``step(*args)``, or the error it raises."""
        morph = self.attempt(pair, step, *args)
        if morph is not None:
            self.out[pair.k] = morph


def build_composites(pairs, kind="circular"):
    """Composite ball-morphs of many pairs at once, stage by stage: every small ball-map of a
    stage (the dense maps, the extension stages of each side, the central morphs) in one batch.

    Parameters
    ----------
    pairs : list of (ndarray, ndarray, bool, float or None, str)
        Each pair's validated P (N, 2) and Q (M, 2), whether they are loops, its spacing and
        its sampling (for a pair the plain ball-morph follows).
    kind : str
        The path of every stage's ball-morph ('circular', ...).

    Returns
    -------
    list of Morph or BallMorphError
        Per pair, its composite ball-morph, or the error :func:`build_composite` raises for it
        alone (each pair's stages run in the same order, so its first failure is the same).
    """
    method = f"{kind}-ball"
    results, live = _Results(len(pairs)), []
    setups = orient_pairs([(P, Q, closed) for P, Q, closed, _, _ in pairs])
    for k, ((P, Q, closed, spacing, sampling), setup) in enumerate(zip(pairs, setups)):
        pair = _Pair(k, P, Q, closed, None, sampling, setup)
        if isinstance(setup, BallMorphError):
            results.out[k] = setup
            continue
        pair.spacing = results.attempt(pair, resolve_spacing, P, Q, closed, spacing)
        if pair.spacing is None:
            continue
        if pair.setup.coincident:
            results.settle(pair, build, P, Q, method, closed, pair.spacing, sampling)
        else:
            live.append(pair)
    for pair, maps in zip(live, dense_map_batch([p.setup for p in live], [p.spacing / 2.0 for p in live])):
        pair.maps = maps
        if not maps.report.violations:
            results.settle(pair, build, pair.P, pair.Q, method, pair.closed, pair.spacing, pair.sampling)
    live = [p for p in live if p.maps.report.violations]
    # Relative blending, P's side and then Q's (the order a pair alone takes them in).
    for side in ("P", "Q"):
        live = _blend_side(results, live, side, kind)
    centrals = ball_morphs(
        [(p.blended["P"].curve, p.blended["Q"].curve, p.closed, p.spacing) for p in live], kind, check=False
    )
    for pair, m0 in zip(live, centrals):
        results.settle(pair, _assembled, pair, m0)
    return results.out


def _blend_side(results, live, side, kind):
    """Bridge and blend curve ``side`` ('P' or 'Q') of every pair in ``live``, every extension
    stage's ball-morph in one batch; returns the pairs that got through."""
    to_arc = side == "P"
    work = []
    for pair, items in zip(live, bridges_of([p.maps for p in live], side)):
        if isinstance(items, BallMorphError):
            results.out[pair.k] = items
        else:
            work.append((pair, items, _stretches_and_arcs(_side(pair, side), items, pair.closed, to_arc)))
    morphs = iter(ball_morphs([(a, b, False, p.spacing) for p, _, pieces in work for a, b in pieces], kind))
    done = []
    for pair, items, pieces in work:
        mine = [next(morphs) for _ in pieces]
        args = (_side(pair, side), items, pair.closed, kind, pair.spacing, to_arc, pieces, mine)
        pair.blended[side] = results.attempt(pair, _blended, *args)
        if pair.blended[side] is not None:
            done.append(pair)
    return done


def _side(pair, side):
    """The pair's dense curve ``side`` ('P' or 'Q')."""
    return pair.maps.side_p if side == "P" else pair.maps.side_q


def _assembled(pair, m0):
    """A pair's composite ball-morph from its blended curves and central morph ``m0`` (PathMorph)."""
    closed, spacing, setup = pair.closed, pair.spacing, pair.setup
    bp, bq = pair.blended["P"], pair.blended["Q"]
    sp, sq = pair.maps.side_p, pair.maps.side_q
    central = _central(bp, bq, closed, spacing, m0)
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
