"""The one stroke-pair pipeline: every pair of strokes of two keys takes the same named steps.

Ball-morph methods::

    prepare -> own points -> polylines -> register -> settle ends -> find events
            -> choose routes -> cut chains -> map chains -> fall back -> lay out

1. *prepare* (:mod:`.curves`): validate each pair's curves; strokes with fewer than two
   distinct points move straight, point by point (riding their group's turn, or the drawing's
   when it turns and some stroke shows it: :class:`.registration.Rides`; the DOT route); a
   loop paired with an open stroke is morphed as two open strokes.
2. *own points* (:mod:`.point_routes`, :mod:`.exact_fit`): pairs whose points match one for
   one under a similarity keep them (OWN_POINTS).
3. *polylines* (:mod:`.point_routes`, :mod:`.polylines`): polylines with as many corners go
   corner to corner (POLYLINE).
4. *register* (:mod:`.registration`, :mod:`.carrier_choice`, paper section 1.4): a similarity
   takes P onto Q; the ball-morph runs between the registered P and Q and the carrier undoes
   the registration progressively; pairs that change shape where they lie get none, or squash
   in place (:mod:`.deforming`).
5. *settle ends* (:mod:`.ends`): open strokes whose registered ends do not meet: overhangs and
   end gaps; ends meant to be shared meet halfway.
6. *find events* (:mod:`.crossings`): where the registered curves cross or overlap.
7. *choose routes* (a :class:`~..strokes.Route` per pair, in its report): registered curves
   that coincide are the carrier alone (CARRIER); curves within ``NEAR`` of each other that
   cross (the same stroke redrawn) are matched by arc length on the carrier (NEAR); nested
   loops are ball-mapped whole (WHOLE); crossing pairs and strokes sharing their endpoints are
   cut into lenses (LENSES); pairs that change shape where they lie are tangent-aligned, their
   crossings not sought (TANGENT); pairs no ball-morph can follow take aligned interpolation
   when their curves lie over each other (ALIGNED: tangled crossings, a stroke crossing
   itself), else linear interpolation (LINEAR: loops side by side, strokes that do not share
   their endpoints without a carrier); the report says why.
8. *cut chains* (:mod:`.crossings`): the lenses, overlaps and whole pairs the ball-maps run on.
9. *map chains*: the ball-maps of every chain of every pair, in batches of about
   ``BALLMAP_BATCH_POINTS`` input points.
10. *fall back* (:mod:`.fallbacks`): a chain that is not b-compatible gets the composite
    ball-morph, then aligned interpolation.
11. *lay out* (:mod:`..frames.layout`, :class:`.pair_plans.PairPlans`): every chain's samples
    in order, evaluated at any times; each pair's PairMorphs (morphs, carrier, route).

The paper's comparison morphs take *prepare*, then their own morph with its fallback. Every
step works on all pairs at once (a single pair is a batch of one), and nothing here depends on
the in-between times: :class:`PairPlans` is the plan, :meth:`PairPlans.frames` its evaluation.
"""

from dataclasses import dataclass, fields

import numpy as np

from ... import tolerances as tol
from ...ballmap.correspondence import map_batch
from ...ballmap.onemap import OneWayMap
from ...geometry.intersections import simple_curves
from ...geometry.polyline import (
    coarsen,
    curve_length,
    default_spacings,
    pair_scales,
    resolve_spacing,
)
from ...geometry.ragged import Ragged
from ...geometry.similarity import Similarity
from ..frames.layout import BallRows
from ..strokes import Route, as_written
from .carrier_choice import carrier_motions, note_shape_changes
from .crossings import cross, cut_chains, find_events
from .curves import PairCurves, prepare_pairs
from .deforming import DEFORMING_NOTE, SQUASHED, deforms, similar_in_place, squashes_in_place, tangent_morphs
from .ends import overhang_morph, settle_ends
from .fallbacks import (
    BALL_METHODS,
    FailingChain,
    aligned_fallbacks,
    arc_length_morphs,
    chain_fallbacks,
    comparison_morph,
    linear_fallback,
    point_motion,
    unsplittable,
)
from .pair_plans import PairPlans
from .point_routes import dot_route, guarded, own_points_route, polyline_route
from .registration import Motions, Rides, identity_residual

__all__ = ["PairCurves", "PairPlans", "PairMorph", "plan_pairs", "BALL_METHODS"]

#: The ball-maps of a drawing run in batches of about this many input points (whole pairs: each
#: pair's chains share one tolerance): one batch for a typical drawing, several for a huge one,
#: which bounds the ball-map's temporaries.
BALLMAP_BATCH_POINTS = 60_000

#: Registered curves within this fraction of their size of each other (RMS) are the same stroke
#: redrawn: their points are matched by arc length and the carrier does the motion. A ball-map
#: of two curves this close would only follow the redrawing's jitter, cut at its many crossings.
NEAR = 0.01


@dataclass
class _Routes:
    """What happens to each pair of a ball-route batch (a Route each: CARRIER, NEAR, WHOLE,
    LENSES, TANGENT, ALIGNED for curves lying over each other that cannot be cut into lenses,
    LINEAR) and, for the last two, why."""

    route: np.ndarray
    reason: list


def choose_routes(R, Q, events, coincident, near, carrier, scale):
    """Step 4: the route of every pair (see the module docstring); ``near`` marks the pairs
    within ``NEAR`` of each other that cross or overlap (the near route)."""
    n, closed = len(R), R.closed
    kind = np.where(closed & (events.count == 0), Route.WHOLE, Route.LENSES).astype(object)
    kind[near & ~coincident] = Route.NEAR
    reason = [""] * n
    end_eps = tol.SHARED_ENDPOINT * scale
    first = np.linalg.norm(R.pts[R.offsets[:-1]] - Q.pts[Q.offsets[:-1]], axis=1) <= end_eps
    last = np.linalg.norm(R.pts[R.offsets[1:] - 1] - Q.pts[Q.offsets[1:] - 1], axis=1) <= end_eps
    # Whether loops lie one inside the other: asked of the whole pairs only.
    nested = np.zeros(n, dtype=bool)
    ask = np.flatnonzero((kind == Route.WHOLE) & ~coincident)
    inside_q = Q.contains(np.take(R.pts, R.offsets[ask], axis=0), ask)
    nested[ask] = inside_q | R.contains(np.take(Q.pts, Q.offsets[ask], axis=0), ask)
    told = {}  # pairs that cannot be cut into lenses: why, said once their strokes are checked
    for c in range(n):
        if coincident[c]:
            kind[c] = Route.CARRIER
        elif kind[c] == Route.NEAR:
            continue
        elif carrier == "none" and not closed[c] and not (first[c] and last[c]):
            kind[c], reason[c] = Route.LINEAR, "the strokes do not share endpoints and no carrier is used"
        elif not events.agree[c]:
            kind[c], told[c] = Route.ALIGNED, events.why_tangled(c)
        elif kind[c] == Route.WHOLE and not nested[c]:
            kind[c], told[c] = Route.LINEAR, "the loops neither cross nor lie one inside the other"
    # Whether a key's stroke crosses itself, asked of all of them at once.
    asked = list(told)
    simple = simple_curves([c for k in asked for c in (R.curve(k), Q.curve(k))], np.repeat(closed[asked], 2))
    for c, both in zip(asked, simple.reshape(-1, 2)):
        reason[c] = unsplittable(R.curve(c), Q.curve(c), bool(closed[c]), told[c], both)
    return _Routes(kind, reason)


@dataclass
class _ChainMaps:
    """The ball-maps of every chain that was mapped (step 6), as arrays.

    Attributes
    ----------
    samples : OneWayMap
        Their samples, ``chain`` the chain's index in the Chains.
    lengths : ndarray, shape (H, 2)
        Length of each chain's dense P and Q (0 where not mapped).
    reports : list of CompatibilityReport or None
    """

    samples: OneWayMap
    lengths: np.ndarray
    reports: list


def map_chains(chains, spacing, eps):
    """Step 6: the ball-maps of every chain but the static overlaps, in batches of whole pairs."""
    mapped = np.flatnonzero(~chains.static)
    sizes = [len(chains.setups[k].P) + len(chains.setups[k].Q) for k in mapped]
    starts = np.cumsum([0] + sizes)[:-1] // BALLMAP_BATCH_POINTS
    pair = chains.pair[mapped]
    first_of_pair = np.r_[True, pair[1:] != pair[:-1]]
    batch_of = np.maximum.accumulate(np.where(first_of_pair, starts, 0)) if len(mapped) else starts
    parts, lengths, reports = [], np.zeros((len(chains), 2)), [None] * len(chains)
    for number in np.unique(batch_of):
        members = mapped[batch_of == number]
        samples, lengths[members], batch_reports = _mapped_batch(chains, members, spacing, eps)
        samples.chain = members[samples.chain]
        parts.append(samples)
        for i, report in zip(members, batch_reports):
            reports[i] = report
    return _ChainMaps(OneWayMap.concatenate(parts) if parts else OneWayMap.empty(), lengths, reports)


def _mapped_batch(chains, members, spacing, eps):
    """What :func:`map_chains` keeps of the ball-maps of chains ``members``: their samples
    (OneWayMap), the lengths of their dense curves (shape (K, 2)) and their reports. The rest of
    the batch (its dense curves and their tables, tens of MiB for a big drawing) goes before the
    next batch is made."""
    owners = chains.pair[members]
    batch = map_batch([chains.setups[i] for i in members], spacing[owners], "symmetric", eps[owners])
    return batch.samples, np.c_[batch.sides_p.rg.length, batch.sides_q.rg.length], batch.reports


def _ball_rows(chains, maps, index, good, ends):
    """The ball route's samples (BallRows): the chains whose ball-maps hold, and the overlaps
    (ranges on the pairs' whole curves, offsets undoing the end gaps' displacement)."""
    rows = maps.samples.take(good[maps.samples.chain])
    statics = np.flatnonzero(chains.static)
    overlap = Ragged.from_list([chains.setups[k].P for k in statics], False)
    chain = np.r_[rows.chain, statics[overlap.owner]].astype(np.int64)
    order = np.argsort(chain, kind="stable")
    # An overlap stays where it is: its fractions along the piece are its own.
    along = overlap.s / np.maximum(overlap.length, tol.TINY)[overlap.owner]
    lengths = np.maximum(maps.lengths[rows.chain], tol.TINY)
    u_p, u_q = np.r_[rows.s_src / lengths[:, 0], along], np.r_[rows.s_dst / lengths[:, 1], along]
    p, m, q = (np.concatenate([getattr(rows, f), overlap.pts]) for f in ("src", "m", "dst"))
    chain, kept = chain[order], np.flatnonzero(good | chains.static)
    first = np.searchsorted(chains.pair, chains.pair[kept])
    u_p, offset, on_whole = _on_whole(ends, chains.pair, chains.range_p, u_p[order], chain)
    owner = chains.pair[kept]
    return BallRows(
        pair=index[owner],
        order=kept - first,
        sizes=np.bincount(chain, minlength=len(chains))[kept],
        range_p=on_whole[kept],
        range_q=ends.on_q(owner[:, None], chains.range_q[kept]),
        static=chains.static[kept],
        u_p=u_p,
        u_q=u_q[order],
        p=np.take(p, order, axis=0),
        m=np.take(m, order, axis=0),
        q=np.take(q, order, axis=0),
        offset=offset,
    )


def _on_whole(ends, pair, range_p, u_p, chain):
    """Samples at fractions ``u_p`` of chains at ``range_p`` on the common parts, placed on the
    whole registered curves: their fractions of the chains' ranges there, the offsets undoing
    the displacement, and those ranges.

    Parameters
    ----------
    ends : Ends
    pair : ndarray of int, shape (G,)
        Each chain's pair.
    range_p : ndarray, shape (G, 2)
        Each chain's range on its pair's common part.
    u_p : ndarray, shape (K,)
    chain : ndarray of int, shape (K,)
        Each sample's chain.

    Returns
    -------
    u_p, offset, range_p : ndarrays, shapes (K,), (K, 2), (G, 2)
    """
    s = range_p[chain, 0] + u_p * (range_p[chain, 1] - range_p[chain, 0])
    ranges = ends.on_p(pair[:, None], range_p)
    at, offset = ends.place(pair[chain], s)
    start = ranges[chain, 0]
    span = ranges[chain, 1] - start
    u = np.divide(at - start, span, out=u_p.astype(np.float64), where=np.abs(span) > 0)
    return u, offset, ranges


def _add_piece(plans, ends, index, c, morph, closed, order, ranges):
    """A morph of chain ``order`` of (local) pair ``c`` whose pieces lie at ``ranges`` along
    the common parts: placed on the whole curves, its samples' displacement undone."""
    _add_pieces(plans, ends, index, [c], [morph], [closed], [order], np.asarray(ranges, dtype=np.float64)[None])


def _add_pieces(plans, ends, index, pairs, morphs, closed, orders, ranges):
    """:func:`_add_piece` of several morphs at once (their samples placed together).

    Parameters
    ----------
    plans : PairPlans
    ends : Ends
    index : ndarray of int, shape (C,)
        The batch's pairs in the drawing.
    pairs : array_like of int, shape (G,)
        The (local) pair of each morph.
    morphs : list of Morph
        G morphs; their ``u_p`` are replaced by fractions on the whole curves.
    closed : array_like of bool, shape (G,)
    orders : array_like of int, shape (G,)
        Each morph's chain order within its pair.
    ranges : ndarray, shape (G, 2, 2)
        Each morph's arc-length ranges on the common parts of P and of Q.
    """
    pairs = np.asarray(pairs, dtype=np.int64)
    counts = np.array([len(m.u_p) for m in morphs], dtype=np.int64)
    u_p = np.concatenate([m.u_p for m in morphs]) if morphs else np.zeros(0)
    u_p, offset, range_p = _on_whole(ends, pairs, ranges[:, 0], u_p, np.repeat(np.arange(len(pairs)), counts))
    range_q = ends.on_q(pairs[:, None], ranges[:, 1])
    stops = np.cumsum(counts)
    for g, morph in enumerate(morphs):
        lo, hi = stops[g] - counts[g], stops[g]
        morph.u_p = u_p[lo:hi]
        piece = (tuple(range_p[g]) if hi > lo else tuple(ranges[g, 0]), tuple(range_q[g]))
        c = int(index[pairs[g]])
        plans.add_morph(c, morph, bool(closed[g]), order=int(orders[g]), ranges=piece, offset=offset[lo:hi])


def _fall_back(plans, chains, maps, events, index, kind, spacing, ends):
    """Step 7 for chains that are not b-compatible: composite, then aligned interpolation (the notes say which).

    Returns the chains whose ball-maps hold, shape (H,) of bool.
    """
    counts = np.bincount(chains.pair, minlength=len(index))
    good = np.array([r is not None and not r.violations for r in maps.reports], dtype=bool)
    failing = np.flatnonzero(~good & ~chains.static)
    if not len(failing):
        return good
    orders = failing - np.searchsorted(chains.pair, chains.pair[failing])
    wanted = []
    for k, order in zip(failing, orders):
        c, setup = chains.pair[k], chains.setups[k]
        where = f"lens {order + 1}/{counts[c]}" if events.count[c] else ("loops" if setup.closed else "stroke")
        wanted.append(FailingChain(setup.P, setup.Q, setup.closed, spacing[c], where, maps.reports[k].describe()))
    # Every failing chain's composite ball-morph at once: one at a time, each paid a dozen
    # small ball-maps' fixed costs.
    for k, order, (morph, note) in zip(failing, orders, chain_fallbacks(wanted, kind)):
        c = chains.pair[k]
        plans.notes[index[c]].append(note)
        closed = chains.setups[k].closed
        _add_piece(plans, ends, index, c, morph, closed, order, (chains.range_p[k], chains.range_q[k]))
    return good


def register(P, Q, carrier, scale, drawing=None, given=None, rides=None):
    """Step 2: each pair's registration and carrier (see :mod:`.registration`).

    Pairs the ball-morph follows as drawn, loops that change shape where they lie (see
    :mod:`.carrier_choice`) and every pair with carrier 'none' get none;
    ``drawing`` (a Similarity) is the keys' overall motion, the prior of symmetric shapes;
    ``given`` (list of Motions of one pair or None, per pair) are carriers already chosen;
    ``rides`` (Rides) what the strokes without an orientation of their own ride.

    Returns
    -------
    motions : Motions
    R : Ragged
        The registered P.
    residual : ndarray, shape (C,)
        RMS distance left between the registered P and Q (uniform samples).
    shape_change : ndarray, shape (C,)
        Loops left without a carrier because they changed shape (:mod:`.carrier_choice`):
        the fraction of their distance the registration left; NaN for the other pairs.
    warps : dict
        Pair -> TangentWarp of the loops squashed in place (:mod:`.deforming`).
    """
    motion, kept = carrier_motions(P, Q, carrier, scale, drawing, rides)
    # The motion of least travel: a loop squashed in place rather than turned (:mod:`.deforming`).
    stretched, stretch, squashed, warps = squashes_in_place(P, Q, motion, scale, drawing, rides)
    motion.put(stretched, stretch)
    motion.put(squashed, Motions.identity(len(squashed), motion.kind))
    kept[squashed] = SQUASHED
    for c, own in enumerate(given or []):
        if own is not None:
            motion.put(np.array([c]), own)
    pts = np.einsum("kij,kj->ki", np.take(motion.A, P.owner, axis=0), P.pts) + np.take(motion.b, P.owner, axis=0)
    R = Ragged(np.where(motion.moving[P.owner][:, None], pts, P.pts), P.offsets, P.closed)
    return motion, R, identity_residual(R, Q), kept, warps


def _ball_route(plans, pairs, index, kind, carrier, spacing, drawing=None, rides=None):
    """Steps 2-7 for the pairs ``index`` of ``pairs`` (validated); returns their Motions."""
    closed = np.array([pairs[c].closed for c in index], dtype=bool)
    # Curves drawn far more densely than they will be sampled are resampled first, each at its
    # own default spacing (the keys may differ in size a lot).
    P = coarsen(Ragged.from_list([pairs[c].P for c in index], closed), spacing)
    Q = coarsen(Ragged.from_list([pairs[c].Q for c in index], closed), spacing)
    given = [pairs[c].motion for c in index]
    ridden = None if rides is None else rides.take(index)
    motions, R, residual, shape_change, warps = register(P, Q, carrier, pair_scales(P, Q), drawing, given, ridden)
    note_shape_changes(plans.notes, index, motions, shape_change)
    scale = pair_scales(R, Q)
    # Sample where the morph happens: between the registered P (Q's size) and Q.
    h = default_spacings(R, Q) if spacing is None else np.full(len(index), float(spacing))
    coincident = residual <= tol.OVERLAP * scale
    pieces = np.array([m is not None for m in given], dtype=bool)
    settle = ~closed & ~coincident & ((carrier != "none") | pieces)
    ends = settle_ends(R, Q, scale, settle, trim=settle & ~pieces, pin=~motions.moving)
    Rc, Qc = ends.common_p, ends.common_q
    # Of the common parts: only settled pairs have other curves than the whole ones measured above.
    settled = np.flatnonzero(settle)
    if len(settled):
        residual[settled] = identity_residual(Rc.take(settled), Qc.take(settled))
    coincident |= residual <= tol.OVERLAP * scale
    near = (residual <= NEAR * scale) & motions.moving & ~coincident
    # A near pair that crosses takes the near route whatever its events: they are not sought.
    crossing_near = cross(Rc, Qc, scale, near)
    # Loops that change shape where they lie slide through their crossings: not sought.
    deforming = deforms(motions, shape_change) & ~coincident & ~crossing_near
    events = find_events(Rc, Qc, scale, h / 2, ~coincident & ~crossing_near & ~deforming)
    routes = choose_routes(Rc, Qc, events, coincident, crossing_near | (near & (events.count > 0)), carrier, scale)
    # Nested loops as drawn with carrier 'none': the paper's ball-morph, asked for.
    routes.route[
        deforming
        | similar_in_place(P, Q, (routes.route == Route.WHOLE) & ~motions.moving & closed & (carrier != "none"))
    ] = Route.TANGENT
    plans.set_routes(index, routes.route)
    plans.closed[index], plans.lengths[index] = closed, np.c_[R.length, Q.length]
    whole_ranges = np.stack([np.c_[np.zeros(len(index)), Rc.length], np.c_[np.zeros(len(index)), Qc.length]], 1)
    _no_ball_routes(plans, ends, index, routes, (Rc, Qc, closed), h, whole_ranges)
    _tangent_route(
        plans, ends, index, np.flatnonzero(routes.route == Route.TANGENT), (Rc, Qc, closed, warps), whole_ranges
    )
    near = np.flatnonzero(routes.route == Route.NEAR)
    if len(near):
        morphs = arc_length_morphs(Rc.take(near), Qc.take(near), h[near])
        _add_pieces(plans, ends, index, near, morphs, closed[near], np.zeros(len(near)), whole_ranges[near])
    lensed = routes.route == Route.LENSES
    whole = np.flatnonzero((routes.route == Route.WHOLE) | (routes.route == Route.CARRIER))
    chains = cut_chains(Rc, Qc, events, lensed, whole, coincident, scale)
    plans.joined[index] = closed & lensed
    maps = map_chains(chains, h, tol.COINCIDENT * scale)
    good = _fall_back(plans, chains, maps, events, index, kind, h, ends)
    plans.ball.append(_ball_rows(chains, maps, index, good, ends))
    _add_overhangs(plans, index, R, Q, ends, h)
    pieces = np.bincount(chains.pair, minlength=len(index))
    for c in np.flatnonzero(lensed & (pieces > 1)):
        plans.notes[index[c]].append(f"split at {pieces[c]} crossing/overlap pieces")
    return motions


def _no_ball_routes(plans, ends, index, routes, curves, h, ranges):
    """The pairs of ``routes`` (_Routes) no ball-morph can follow: LINEAR, ALIGNED, each with
    the note that says why; ``curves`` are the batch's ``(R, Q, closed)``."""
    R, Q, closed = curves
    for c in np.flatnonzero(routes.route == Route.LINEAR):
        morph, note = linear_fallback(R.curve(c), Q.curve(c), bool(closed[c]), h[c], routes.reason[c])
        plans.notes[index[c]].append(note)
        _add_piece(plans, ends, index, c, morph, bool(closed[c]), 0, ranges[c])
    aligned = np.flatnonzero(routes.route == Route.ALIGNED)
    if len(aligned):
        pairs = [(R.curve(c), Q.curve(c), bool(closed[c])) for c in aligned]
        morphs, notes = aligned_fallbacks(pairs, h[aligned], [routes.reason[c] for c in aligned])
        for c, note in zip(aligned, notes):
            plans.notes[index[c]].append(note)
        _add_pieces(plans, ends, index, aligned, morphs, closed[aligned], np.zeros(len(aligned)), ranges[aligned])


def _tangent_route(plans, ends, index, rows, curves, ranges):
    """The pairs ``rows`` that change shape where they lie: tangent-aligned, straight paths
    (:mod:`.deforming`), warped together. ``curves``: the common parts R and Q (Ragged), the
    loops' flags and the warps already made (pair -> TangentWarp: a squash's, see
    :func:`register`)."""
    R, Q, closed, known = curves
    if not len(rows):
        return
    pairs = [(R.curve(c), Q.curve(c), bool(closed[c])) for c in rows]
    morphs = tangent_morphs(pairs, [known.get(int(c)) for c in rows])
    for c in rows:
        plans.notes[index[c]].append(DEFORMING_NOTE)
    _add_pieces(plans, ends, index, rows, morphs, closed[rows], np.zeros(len(rows)), ranges[rows])


def _add_overhangs(plans, index, R, Q, ends, spacing):
    """The parts of open strokes beyond their common part (see :mod:`.ends`): first and last
    chains of their pairs, sliding into the common part's ends or growing out of them."""
    for c in range(len(index)):
        for which, order in ((0, -1), (1, np.iinfo(np.int32).max)):
            start_or_end = (0.0, R.length[c]), (0.0, Q.length[c])
            for curve, keep, grow in ((R, ends.keep_p, False), (Q, ends.keep_q, True)):
                edge = start_or_end[int(grow)][which]
                attach = keep[c, which]
                if abs(attach - edge) <= 0.0:
                    continue
                s0, s1 = sorted((edge, attach))
                piece, at = _piece(curve, c, s0, s1)
                gap = ends.gap[c, which]
                morph = overhang_morph(piece, s0 - at, s1 - at, attach - at, gap, grow, spacing[c])
                other = ends.keep_q[c, which] if not grow else ends.keep_p[c, which]
                ranges = ((s0, s1), (other, other)) if not grow else ((other, other), (s0, s1))
                plans.add_morph(int(index[c]), morph, False, order=int(order), ranges=ranges)


def _piece(curves, c, s0, s1):
    """The vertices of curve ``c`` of ``curves`` (Ragged) spanning arc lengths ``s0`` to ``s1``
    (from the last at or before ``s0`` to the first at or after ``s1``), as a copy, and the
    arc length of its first vertex.

    An overhang slides along this stretch only: kept whole, every overhang's curve (and, as a
    view, the batch it lies in) would stay in the plan (38 MiB of a 400x500 open drawing's).
    The curve's own vertices, not the stretch of :meth:`Ragged.pieces`, which cuts new end
    points and drops vertices within round-off of them: the overhang slides along the very
    polyline it slid along before.
    """
    s = curves.s[curves.offsets[c] : curves.offsets[c + 1]]
    first = max(int(np.searchsorted(s, s0, side="right")) - 1, 0)
    last = max(min(int(np.searchsorted(s, s1, side="left")), len(s) - 1), first + 1)
    return curves.curve(c)[first : last + 1].copy(), float(s[first])


def _isolated_ball_route(plans, pairs, ready, kind, carrier, spacing, drawing=None, rides=None):
    """The ball route for every ready pair at once; should it fail (a bug), pair by pair, so one
    pair never stops the others: a failing pair takes linear interpolation and says why."""
    index = np.asarray(ready)
    kept = {c: len(plans.notes[c]) for c in ready}
    try:
        return _ball_route(plans, pairs, index, kind, carrier, spacing, drawing, rides)
    except Exception as exc:  # reported below, pair by pair
        batch_error = f"{type(exc).__name__}: {exc}"
    plans.drop(set(ready), kept)
    parts = []
    for c in ready:
        try:
            parts.append(_ball_route(plans, pairs, np.array([c]), kind, carrier, spacing, drawing, rides))
        except Exception as exc:
            plans.drop({c}, kept)
            pair = pairs[c]
            reason = f"the {kind}-ball morph failed ({type(exc).__name__}: {exc}; with the others: {batch_error})"
            morph, note = linear_fallback(
                pair.P, pair.Q, pair.closed, resolve_spacing(pair.P, pair.Q, pair.closed, None), reason
            )
            plans.notes[c].append(note)
            plans.add_morph(c, morph, pair.closed, pair.lengths)
            plans.set_route([c], Route.LINEAR)
            parts.append(Motions.identity(1))
    names = [f.name for f in fields(Motions) if f.name != "kind"]
    return Motions(*(np.concatenate([getattr(m, name) for m in parts]) for name in names), parts[-1].kind)


def _comparison_route(plans, pairs, ready, method, spacing):
    """The paper's comparison morphs, pair by pair, each with its fallback."""
    if not ready:
        return
    closed = np.array([pairs[c].closed for c in ready], dtype=bool)
    Ps = coarsen(Ragged.from_list([pairs[c].P for c in ready], closed), spacing)
    Qs = coarsen(Ragged.from_list([pairs[c].Q for c in ready], closed), spacing)
    for k, c in enumerate(ready):
        P, Q, loop = Ps.curve(k), Qs.curve(k), bool(closed[k])
        morph, notes = comparison_morph(P, Q, loop, method, resolve_spacing(P, Q, loop, spacing))
        plans.notes[c] += notes
        plans.add_morph(c, morph, loop, (Ps.length[k], Qs.length[k]))
    plans.set_route(ready, Route.COMPARISON)


def _note_rides(plans, pairs, rides):
    """Say, in its notes, that a stroke without an orientation of its own rode its group's turn."""
    for c in np.flatnonzero(~np.isnan(rides.a) & ~np.isnan(rides.group) & plans.motions.moving):
        group = pairs[c].group
        plans.notes[c].append(
            f"rode its group's motion (stroke {as_written(group.loop)} and the strokes inside it,"
            f" turning {np.degrees(group.motion.turn):.0f}°)"
        )


def plan_pairs(pairs, method="circular-ball", carrier="similarity", spacing=None, drawing=None):
    """Plan every stroke pair of a drawing (see the module docstring).

    Parameters
    ----------
    pairs : list of PairCurves
    method : str
        One of :data:`~ballmorph_core.METHODS` (validated).
    carrier : {'similarity', 'rigid', 'none'}
    spacing : float, optional
        Geodesic sample spacing for every pair (default: each pair's own).
    drawing : Similarity, optional
        The keys' overall motion (from the stroke matching): symmetric shapes turn with it.

    Returns
    -------
    PairPlans
    """
    ready = prepare_pairs(pairs, method, spacing)
    plans = PairPlans(pairs)
    dots = [c for c, pair in enumerate(pairs) if pair.P is None]
    if method not in BALL_METHODS:
        for c in dots:
            plans.add_morph(c, point_motion(pairs[c].xy_a, pairs[c].u_a, pairs[c].xy_b, pairs[c].u_b), False)
        plans.set_route(dots, Route.DOT)
        _comparison_route(plans, pairs, ready, method, spacing)
        return plans.finish()
    kind = method[: -len("-ball")]
    plans.motions = Motions.identity(len(pairs), "rigid" if carrier == "rigid" else "similarity")
    rides = Rides.of_pairs(pairs, ready, dots, drawing)
    if drawing is not None and not rides.witnessed:
        # Nothing shows the drawing's turn (circles and dots alone: their centroids fit any):
        # no prior of symmetric fits either; its scale still counts (strokes sliding start at it).
        drawing = Similarity(drawing.scale)
    dot_route(plans, pairs, dots, carrier, drawing, rides)
    # Pieces of hinted pairs share their pair's carrier: only the ball route takes them.
    pieces = [c for c in ready if pairs[c].motion is not None]
    ready = [c for c in ready if pairs[c].motion is None]
    for route in (own_points_route, polyline_route):
        ready = guarded(route, plans, pairs, ready, carrier, drawing, rides)
    ready = sorted(ready + pieces)
    if ready:
        motions = _isolated_ball_route(plans, pairs, ready, kind, carrier, spacing, drawing, rides)
        plans.motions.put(np.asarray(ready), motions)
    _note_rides(plans, pairs, rides)
    return plans.finish(kind)


class PairMorph:
    """One stroke pair through the pipeline (a batch of one), evaluated like a Morph.

    Parameters
    ----------
    P, Q : array_like, shape (N, 2), (M, 2)
        The two strokes, running the same way.
    closed : bool
    method, carrier, spacing
        See :func:`plan_pairs`.

    Attributes
    ----------
    used : str
        The morphs the pair's chains used, and its carrier.
    notes : list of str
        Fallbacks and splits.
    u_p, u_q : ndarray, shape (K,)
        Arc-length fractions of the samples along P and Q.
    """

    def __init__(self, P, Q, closed, method="circular-ball", carrier="similarity", spacing=None):
        P, Q = np.asarray(P, dtype=np.float64), np.asarray(Q, dtype=np.float64)
        u_p, u_q = (Ragged.from_list([c], [closed]).s / max(curve_length(c, closed), tol.TINY) for c in (P, Q))
        self.plans = plan_pairs([PairCurves(P, u_p, closed, Q, u_q, closed)], method, carrier, spacing)
        self.used, self.notes = self.plans.used[0], self.plans.notes[0]
        parts = self.plans.frames([0.0])
        self.u_p, self.u_q, self.closed = parts.u_a, parts.u_b, bool(parts.closed[0])

    def __call__(self, t):
        """The in-between at ``t``, shape (K, 2)."""
        return self.plans.frames([t]).frames[0]

    def frames(self, times):
        """The in-betweens at several times, shape (T, K, 2)."""
        return self.plans.frames(times).frames
