"""The sliding fit (paper section 1.4's registration of strokes that lie partly along each other).

An outline started elsewhere, a line drawn longer, an open circle whose gap changed: fitted end
to end, such strokes turn or shrink for nothing. Where the end-to-end fit leaves much, P's
samples are also fitted onto Q where they overlap, by trimmed iterative closest points, and
that fit wins when it explains the pair far better. It turns and moves P at the drawing's scale
first and frees the scale only for its last iterations, and keeps the freed scale only where it
fits clearly better: free from the start, the closest points shrink P onto some other part of Q
that a smaller copy fits.
"""

from typing import NamedTuple

import numpy as np

from ... import tolerances as tol
from ...geometry.projection import FollowedQueries, NearestEdges
from ...geometry.ragged import Ragged
from ...geometry.similarity import as_complex

__all__ = ["slide"]

#: Strokes whose end-to-end fit leaves more than this fraction of their size are also fitted
#: sliding along each other; that fit wins when its residual (over the overlap, which must
#: cover ``SLIDE_OVERLAP`` of both strokes) is below ``SLIDE_GAIN`` of the end-to-end one.
SLIDE_FROM = 0.01
SLIDE_OVERLAP = 0.6
SLIDE_GAIN = 0.25
#: Iterations of the sliding fit, and how far (in sizes) a sample looks for the other stroke.
#: The first ``SLIDE_RIGID_ITERATIONS`` keep the drawing's scale (turn and move only), the
#: others free it (see :func:`_weighted_fit`), and their pose is kept only where its residual
#: comes below ``SLIDE_FREE_GAIN`` of the one the drawing's scale reached (see :func:`_iterate`).
SLIDE_ITERATIONS = 8
SLIDE_RIGID_ITERATIONS = 6
SLIDE_FREE_GAIN = 0.7
SLIDE_REACH = 0.3
#: A sample's nearest-edge search keeps the edges this much (in sizes) farther than it needs:
#: a settling fit moves samples by about 0.002 sizes an iteration, so the next iterations
#: find their closest edges among those (FollowedQueries) instead of in the tree.
SLIDE_FOLLOW = 0.01
#: ... and, where Q's edges are long (short strokes of few points: hair, grass), this share of
#: Q's mean edge, up to ``SLIDE_FOLLOW_MOST`` sizes: a drift of a fraction of an edge would send
#: a sample back to the tree every few iterations, while keeping an edge more costs little. The
#: cap keeps a scribble's samples (its edges span the drawing) from keeping every piece near them.
SLIDE_FOLLOW_EDGES = 0.5
SLIDE_FOLLOW_MOST = 0.03

#: The sliding fit is first run on every ``SLIDE_COARSE``-th sample against every
#: ``SLIDE_COARSE``-th vertex of Q (see ``SLIDE_COARSE_SHARE``), from the same starts, with a
#: looser overlap rule (``SLIDE_GATE_OVERLAP`` of both strokes); only pairs whose coarse residual comes below
#: ``SLIDE_MARGIN`` times the accepted residual (``SLIDE_GAIN`` of the end-to-end one) get the
#: full fit: most loose pairs (a stroke redrawn with a wobble) slide to no gain, and a quarter of
#: the samples on a quarter of the edges tells. The margin is a heuristic, not a bound. The coarse
#: fit is the same trimmed ICP on a uniform quarter of the same samples, so its residual
#: estimates the full one's. Q's coarse polyline lies within its vertices' distance to their
#: chords of Q, and that much is granted back. The looser overlap only drops fits the full rule
#: rejects anyway: a start that finds no overlap at all (a drawing moved farther than
#: ``SLIDE_REACH``) weighs no sample and would otherwise leave a residual of 0. Of the starts the
#: full fit accepts (3,906 among 5,000 random pieces of arcs, spirals and wandering curves lying
#: partly along each other, turned, scaled and noisy, 1,000 of them of 5-40 points, and the
#: benchmark's drawings), 99.9 % have a coarse residual below 1.5 times their limit and 5 lie
#: over it; on 12,000 such pairs (seeds 1-8 of the tests' generator, 400 points and 5-40) the
#: gated fits differ from the full fit's on 10. A start blind at a quarter of the samples is
#: judged again with all of them (see :func:`_worth_sliding`). The gate judges each start on its
#: own, and the full fit runs only from the starts that pass it: the benchmark's wobbly open
#: strokes mostly pass from one start only, if any (open 400x500: 38 of 658 starts, 13 slides).
SLIDE_COARSE = 4
SLIDE_MARGIN = 1.5
SLIDE_GATE_OVERLAP = 0.1
#: A coarse curve lying farther from Q than this share of the gate's limit (``SLIDE_MARGIN``
#: times the accepted residual) would grant back most of the limit and let the pair through
#: for nothing: short strokes of few points (hair, grass, hatching), whose coarse curve keeps
#: a few vertices (4 of 10). The gate fits such pairs against Q itself, still with the coarse samples
#: (1,000 strokes of 10 points: 804 of 805 loose pairs went on to the full fit, now 100, and the
#: plan takes 2.7 s instead of 4.5). On 3,000 random pieces of 5-40 points lying partly along
#: each other (1,769 sliding), the gated fits are the full fit's on every loose pair, where
#: every fourth vertex missed two slides; on 1,000 pieces of 400 points nothing changes.
SLIDE_COARSE_SHARE = 0.25


class _Pose(NamedTuple):
    """Rows of :func:`_iterate` at one iteration: their indices, similarities ``a``, ``b``
    (complex, shape (R,)), distances ``d`` and weights ``w`` (shape (R, k)) and arc lengths on
    Q ``s_q`` (shape (R, k))."""

    rows: np.ndarray
    a: np.ndarray
    b: np.ndarray
    d: np.ndarray
    w: np.ndarray
    s_q: np.ndarray


def _weighted_fit(xp, xq, w, a, b, rigid):
    """The least-squares motion ``z -> a' z + b'`` of samples ``xp -> xq`` with weights ``w``
    (all shape (L, k)) from the current one ``(a, b)`` (complex, shape (L,) each): a similarity,
    or with ``rigid`` a turn and a move at the current scale (``|a'| = |a|``); ``(a, b)`` itself
    where fewer than two samples weigh.

    Free from the start, the scale lets trimmed closest points shrink P onto a part of Q wherever
    a smaller copy fits better: of 2,000 random pieces lying partly along each other (the tests'
    generator, seeds 1-2), 699 of 1,420 slides came out more than 12 % off the scale they were
    drawn at (spirals and wandering curves). Turned and moved at the drawing's scale first and
    freed for the last iterations, 114 of 1,158 do, and 1,044 slide at about their scale
    against 721; a ring opened and redrawn 1.2 times larger still slides at 1.19. (These are
    the iterations' own figures; :func:`_iterate` then keeps the freed scale only where it
    fits clearly better, and gives those after that rule.)"""
    total = np.maximum(w.sum(axis=1), tol.TINY)
    cp, cq = (w * xp).sum(axis=1) / total, (w * xq).sum(axis=1) / total
    p, q = xp - cp[:, None], xq - cq[:, None]
    dot = (w * np.conj(p) * q).sum(axis=1)
    norm = np.abs(dot) / np.maximum(np.abs(a), tol.TINY) if rigid else (w * np.abs(p) ** 2).sum(axis=1)
    ok = (norm > 0) & ((w > 0).sum(axis=1) >= 2)
    fitted = np.where(ok, dot / np.where(ok, norm, 1.0), a)
    return fitted, np.where(ok, cq - fitted * cp, b)


def _finite_median(d):
    """Median of each row's finite values, shape (L,) (0 for a row with none)."""
    finite = np.isfinite(d)
    ranked = np.sort(np.where(finite, d, np.inf), axis=1)
    count = finite.sum(axis=1)
    middle = ranked[np.arange(len(d)), np.maximum(count - 1, 0) // 2]
    return np.where(count > 0, middle, 0.0)


def _starts(xp, a, b, scale):
    """The sliding fit's two starts for pairs of P's samples ``xp`` (complex, shape (L, k))
    whose end-to-end fits are ``a``, ``b`` (complex, shape (L,)), at the drawing's scale
    ``scale`` (shape (L,)): from where P lies, and from where the end-to-end fit takes it, each
    scaled to ``scale`` about P's centre; as ``[(a, b), (a, b)]``."""
    centre = xp.mean(axis=1)
    turn = np.divide(a, np.abs(a), out=np.ones(len(a), complex), where=np.abs(a) > 0)
    a_end = scale * turn
    return [(scale + 0j, (1.0 - scale) * centre), (a_end, a * centre + b - a_end * centre)]


def _fits(xp, Q, index, search, starts, size, overlap=SLIDE_OVERLAP, run=None):
    """Strokes that lie partly along each other (an outline started elsewhere, a line drawn
    longer, an open circle whose gap changed): from each start, the similarity taking P's
    samples onto Q where they overlap, by trimmed iterative closest points.

    Samples of P that land on Q's ends (P's overhang) or far from Q are left out of each fit.
    Every (start, pair) is fitted at once (rows of one batch: each row's fit is its own).

    Parameters
    ----------
    xp : ndarray of complex, shape (L, k)
        P's uniform samples.
    Q : Ragged
    index : ndarray of int, shape (L,)
        The pairs (curves of Q).
    search : NearestEdges
        The edges of ``Q.take(index)``: pair ``i`` searches its curve ``i`` (Q stays put
        through every start and iteration: its search is built once, for these curves only).
    starts : list of (ndarray, ndarray)
        ``n`` starting similarities ``(a, b)``, complex, shape (L,) each.
    size : ndarray, shape (L,)
    overlap : float
        The part of both strokes a fit must overlap (a shorter overlap is dropped).
    run : ndarray of bool, shape (n, L), optional
        The starts fitted for each pair (all by default); the others stay at their start, with
        an infinite residual (no fit).

    Returns
    -------
    a, b : ndarray of complex, shape (n, L)
    residual : ndarray, shape (n, L)
        RMS distance of the overlapping samples (inf where the overlap is too short, or the
        start was not run).
    blind : ndarray of bool, shape (n, L)
        Starts from which fewer than two samples weighed at the first step (see :func:`_iterate`).
    """
    (L, k), n = xp.shape, len(starts)
    a = np.concatenate([np.asarray(a, dtype=complex) for a, _ in starts])
    b = np.concatenate([np.asarray(b, dtype=complex) for _, b in starts])
    residual, blind = np.full(n * L, np.inf), np.zeros(n * L, bool)
    cells = np.arange(n * L) if run is None else np.flatnonzero(run)
    pair = cells % L
    xp, index, size = xp[pair], index[pair], size[pair]
    fit_a, fit_b = a[cells], b[cells]
    d, w, s_q, blind[cells] = _iterate(xp, Q, index, search, pair, size, fit_a, fit_b)
    a[cells], b[cells] = fit_a, fit_b
    covered_p = w.mean(axis=1)
    s_kept = np.where(w > 0, s_q.reshape(len(cells), k), np.nan)
    span_q = (np.nanmax(s_kept, axis=1, initial=-np.inf) - np.nanmin(s_kept, axis=1, initial=np.inf)) / np.maximum(
        Q.length[index], tol.TINY
    )
    residual[cells] = np.where((covered_p >= overlap) & (span_q >= overlap), _trimmed_rms(d, w), np.inf)
    return a.reshape(n, L), b.reshape(n, L), residual.reshape(n, L), blind.reshape(n, L)


def _trimmed_rms(d, w):
    """RMS of each row's distances ``d`` weighted by ``w`` (shape (L, k) each; an infinite
    distance weighs 0), shape (L,)."""
    return np.sqrt((w * np.where(np.isfinite(d), d, 0.0) ** 2).sum(axis=1) / np.maximum(w.sum(axis=1), 1))


def _best(a, b, residual, size):
    """Each pair's best fit of :func:`_fits` (its arrays, shape (n, L)): ``a``, ``b``,
    ``residual``, shape (L,) each (the identity, at inf, where no start fits)."""
    L = a.shape[1]
    best = (np.ones(L, complex), np.zeros(L, complex), np.full(L, np.inf))
    for fit in zip(a, b, residual):
        # Equally good fits (a circle slides along itself): the one turning less.
        both = np.isfinite(fit[2]) & np.isfinite(best[2])
        gap = np.subtract(fit[2], best[2], out=np.zeros(L), where=both)
        tie = both & (np.abs(gap) <= tol.EQUAL_FIT * size)
        better = np.where(tie, np.abs(np.angle(fit[0])) < np.abs(np.angle(best[0])), fit[2] < best[2])
        best = tuple(np.where(better, new, old) for new, old in zip(fit, best))
    return best


def _sliding_fits(xp, Q, index, search, starts, size, overlap=SLIDE_OVERLAP, run=None):
    """Each pair's best sliding fit from its starts (arguments as for :func:`_fits`).

    Returns
    -------
    a, b : ndarray of complex, shape (L,)
    residual : ndarray, shape (L,)
        RMS distance of the overlapping samples (inf where no start overlaps enough).
    blind : ndarray of bool, shape (n, L)
        As :func:`_fits` returns it.
    """
    a, b, residual, blind = _fits(xp, Q, index, search, starts, size, overlap, run)
    return (*_best(a, b, residual, size), blind)


def _iterate(xp, Q, index, search, local, size, a, b):
    """The trimmed iterative closest points of :func:`_fits` (arguments as there, one start
    per row, row ``i`` searching the search's curve ``local[i]``): ``a``,
    ``b`` updated in place; returns the last iteration's distances ``d`` (inf off Q's
    interior) and weights ``w``, shape (L, k), arc lengths on Q, shape (L k,), and the rows
    whose first step weighed fewer than two samples, shape (L,) of bool (no fit from there).

    A row whose free iterations (the scale let go) do not bring its residual below
    ``SLIDE_FREE_GAIN`` of the one it had at the drawing's scale goes back to that pose, with
    its distances: the drawing's scale is what an animator drew, and a scale that explains the
    pair only a little better mostly shrinks P onto another part of Q. Of 2,000 random pieces
    lying partly along each other (the tests' generator, seeds 1-2, drawn at 0.9-1.1), the
    slides more than 12 % off their drawn scale go from 115 to 42 (wandering curves 83 -> 12;
    spirals, whose scale is a turn along them, stay at about 30), the right ones from 1,042 to
    1,050; a ring opened and redrawn 1.2 times larger still slides at its scale."""
    L, k = xp.shape
    # The search's vertices are Q's, curve by curve: its edge e is Q's e + shift.
    shift = np.repeat(Q.offsets[index] - search.curves.offsets[local], k)
    owner = np.repeat(local, k)
    end_eps = tol.SHARED_ENDPOINT * np.repeat(size, k)
    length_q = np.repeat(Q.length[index], k)
    reach = SLIDE_REACH * np.repeat(size, k)
    cols = np.arange(k)
    d, w, s_q = np.full((L, k), np.inf), np.zeros((L, k)), np.zeros(L * k)
    foot = np.full(L * k, np.nan, dtype=complex)
    mean_edge = Q.length[index] / np.maximum(Q.n_edges[index], 1)
    margin = np.clip(SLIDE_FOLLOW_EDGES * mean_edge, SLIDE_FOLLOW * size, SLIDE_FOLLOW_MOST * size)
    followed = FollowedQueries(search, owner, np.repeat(margin, k))
    active = np.arange(L)
    blind, rigid = np.zeros(L, bool), None
    for step in range(SLIDE_ITERATIONS):
        if not len(active):
            break
        # Rows, queries and edges are in range: take(mode="wrap") skips the bounds checks
        # (2-3x faster gathers than fancy indexing).
        q = (active[:, None] * k + cols).ravel()
        xa, aa, ba = (np.take(v, active, axis=0, mode="wrap") for v in (xp, a, b))
        z = (aa[:, None] * xa + ba[:, None]).ravel()
        reach_q = np.take(reach, q, mode="wrap")
        # The last iteration's foot is still on Q: the closest point lies no farther than it,
        # which bounds the search as the fit settles (the same answer, found sooner; fmin: a
        # query that found nothing keeps its reach).
        bound = reach_q
        if step:
            bound = np.fmin(reach_q, np.abs(z - np.take(foot, q, mode="wrap")) * (1.0 + 1e-9) + tol.TINY)
        # z's (real, imaginary) pairs are the points' (x, y) rows.
        dist, edge, frac = followed.within(q, z.view(np.float64).reshape(-1, 2), bound)
        found = np.isfinite(dist)
        np.add(edge, np.take(shift, q, mode="wrap"), out=edge, where=found)
        along = np.take(Q.s, edge, mode="wrap") + frac * np.take(Q.length_of_edge, edge, mode="wrap")
        s_q[q] = along
        eps = np.take(end_eps, q, mode="wrap")
        inner = found & (along > eps) & (along < np.take(length_q, q, mode="wrap") - eps)
        d_a = np.where(inner, dist, np.inf).reshape(-1, k)
        d[active] = d_a
        limit = np.maximum(3.0 * _finite_median(d_a), 1e-3 * np.take(size, active, mode="wrap"))
        w_a = (d_a <= limit[:, None]).astype(np.float64)
        w[active] = w_a
        if not step:
            blind = w_a.sum(axis=1) < 2
        if step == SLIDE_RIGID_ITERATIONS:
            # The pose the drawing's scale reached, measured (the others stopped moving there).
            rigid = _Pose(active, aa, ba, d_a, w_a, s_q.reshape(L, k)[active])
        target = np.take(Q.pts, edge, axis=0, mode="wrap")
        target += frac[:, None] * np.take(Q.edge, edge, axis=0, mode="wrap")
        target = as_complex(target)
        foot[q] = np.where(found, target, np.nan)
        new_a, new_b = _weighted_fit(xa, target.reshape(-1, k), w_a, aa, ba, step < SLIDE_RIGID_ITERATIONS)
        # A fit that did not move is a fixed point: every later iteration would repeat it.
        moved = (new_a != aa) | (new_b != ba)
        a[active], b[active] = new_a, new_b
        active = active[moved]
    if rigid is not None:
        _back_to_the_drawn_scale(rigid, a, b, d, w, s_q.reshape(L, k))
    return d, w, s_q, blind


def _back_to_the_drawn_scale(rigid, a, b, d, w, s_q):
    """Rows of :func:`_iterate` whose free iterations did not fit clearly better (see there)
    put back at the pose ``rigid`` (a :class:`_Pose`, the one the drawing's scale reached) in
    place (``s_q`` shape (L, k) here)."""
    back = ~(_trimmed_rms(d[rigid.rows], w[rigid.rows]) < SLIDE_FREE_GAIN * _trimmed_rms(rigid.d, rigid.w))
    rows = rigid.rows[back]
    a[rows], b[rows], d[rows], w[rows], s_q[rows] = (
        rigid.a[back],
        rigid.b[back],
        rigid.d[back],
        rigid.w[back],
        rigid.s_q[back],
    )


def _coarse(Q, index, step, most=np.inf):
    """Every ``step``-th vertex (and the last) of open curves ``index`` of ``Q``: the batch
    (curve ``i`` is ``Q``'s ``index[i]``) and how far each lies from its curve at most, shape (L,).

    Each dropped vertex lies within that distance of its chord, and then so do its edges (the
    distance to a segment is convex) and the chord of them (the curve crosses every line across
    the chord between its ends). A curve that would lie farther than ``most`` (float or shape
    (L,)) from its own keeps every vertex (and lies at 0).
    """
    sub = Q.take(index)
    local = np.arange(len(sub.pts)) - sub.offsets[sub.owner]
    last = sub.n[sub.owner] - 1
    kept = (local % step == 0) | (local == last)
    before = sub.offsets[sub.owner] + local // step * step
    after = np.minimum(before + step, sub.offsets[sub.owner] + last)
    u, chord = sub.pts[before], sub.pts[after] - sub.pts[before]
    along = np.einsum("ij,ij->i", sub.pts - u, chord) / np.maximum(np.einsum("ij,ij->i", chord, chord), tol.TINY)
    f = np.clip(along, 0, 1)
    off = np.hypot(*(u + f[:, None] * chord - sub.pts).T)
    deviation = np.zeros(len(sub))
    np.maximum.at(deviation, sub.owner, np.where(kept, 0.0, off))
    whole = deviation > most
    deviation[whole] = 0.0
    kept |= whole[sub.owner]
    counts = np.bincount(sub.owner[kept], minlength=len(sub))
    return Ragged(sub.pts[kept], np.concatenate([[0], np.cumsum(counts)]), sub.closed), deviation


def _worth_sliding(xp, Q, index, size, starts, residual):
    """The starts (see :func:`_starts`) of loose pairs whose coarse sliding fit (every
    ``SLIDE_COARSE``-th sample against every ``SLIDE_COARSE``-th vertex of Q, or Q itself: see
    ``SLIDE_COARSE_SHARE``) comes within ``SLIDE_MARGIN`` of being accepted, shape (2, L) of
    bool (arguments as for :func:`slide`). The full fit runs only from those: by the gate's own
    premise the full fit would not accept a start the gate turns down, and a pair's best fit
    counts only if accepted, so leaving that start out changes no pair's outcome.

    A start from which fewer than two of the coarse samples weigh cannot move: where P only just
    reaches Q from there (an overlap a few samples long), a quarter of the samples misses what
    the full fit finds (1 of 2,785 pairs that slide among 4,000 random ones; see
    ``test_the_coarse_gate_keeps_a_slide_whose_start_overlaps_by_a_few_samples``). Such a start
    is judged again from every sample, still against the coarse curve; most of them lie far from
    Q for every sample too, and stop at once.
    """
    limit = SLIDE_MARGIN * SLIDE_GAIN * residual
    coarse_q, deviation = _coarse(Q, index, SLIDE_COARSE, SLIDE_COARSE_SHARE * limit)

    def fits(rows, step, run=None):
        search = NearestEdges(coarse_q.take(rows))
        chosen = [(start_a[rows], start_b[rows]) for start_a, start_b in starts]
        _, _, fit, blind = _fits(xp[rows, ::step], coarse_q, rows, search, chosen, size[rows], SLIDE_GATE_OVERLAP, run)
        return fit - deviation[rows] < limit[rows], blind

    worth, blind = fits(np.arange(len(xp)), SLIDE_COARSE)
    again = blind & ~worth
    rows = np.flatnonzero(again.any(axis=0))
    if len(rows):
        # Every blind start that failed, judged again in one batch (the others are not run).
        worth[:, rows] |= fits(rows, 1, again[:, rows])[0]
    return worth


def slide(xp, Q, index, size, a, b, residual, scale=1.0):
    """Pairs whose end-to-end fit leaves more than ``SLIDE_FROM`` of their size also fitted
    sliding along each other; that fit replaces theirs where it is clearly better.

    Parameters
    ----------
    xp : ndarray of complex, shape (L, k)
        P's uniform samples.
    Q : Ragged
    index : ndarray of int, shape (L,)
        The pairs (curves of Q).
    size : ndarray, shape (L,)
    a, b : ndarray of complex, shape (L,)
        The end-to-end similarities, updated in place.
    residual : ndarray, shape (L,)
        Their residuals, updated in place.
    scale : float
        The drawing's scale, which a slide keeps until its last iterations (see
        :func:`_weighted_fit`).
    """
    loose = residual > SLIDE_FROM * size
    if not loose.any():
        return
    rows = np.flatnonzero(loose)
    scale = float(scale) if np.isfinite(scale) and scale > 0 else 1.0  # a degenerate drawing motion: as drawn
    starts = _starts(xp[rows], a[rows], b[rows], np.full(len(rows), scale))
    worth = _worth_sliding(xp[rows], Q, index[rows], size[rows], starts, residual[rows])
    some = worth.any(axis=0)
    rows, worth = rows[some], worth[:, some]
    starts = [(start_a[some], start_b[some]) for start_a, start_b in starts]
    if not len(rows):
        return
    # A tree over the few pairs' curves of Q only, not over all of them (400 strokes of 500
    # points: 26 ms against 150).
    search = NearestEdges(Q.take(index[rows]))
    sa, sb, sr, _ = _sliding_fits(xp[rows], Q, index[rows], search, starts, size[rows], run=worth)
    better = sr < SLIDE_GAIN * residual[rows]
    rows = rows[better]
    a[rows], b[rows], residual[rows] = sa[better], sb[better], sr[better]
