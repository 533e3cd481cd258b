"""The one stroke-pair pipeline: every pair of strokes of two keys takes the same named steps.

Ball-morph methods::

    prepare -> own points -> polylines -> register -> settle ends -> find events
            -> choose routes -> cut chains -> map chains -> fall back -> lay out

1. *prepare* (:mod:`.curves`): validate each pair's curves; strokes with fewer than two
   distinct points move straight, point by point (riding their group's turn, or the drawing's
   when it turns and some stroke shows it: :class:`.riding.Rides`; the DOT route); a
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
9. *map chains* (:mod:`.chain_maps`): the ball-maps of every chain of every pair, in batches
   of about ``BALLMAP_BATCH_POINTS`` input points.
10. *fall back* (:mod:`.fallbacks`): a chain that is not b-compatible gets the composite
    ball-morph, then aligned interpolation.
11. *lay out* (:mod:`..frames.layout`, :class:`.pair_plans.PairPlans`): every chain's samples
    in order, evaluated at any times; each pair's PairMorphs (morphs, carrier, route).

Each step returns what it planned for the pairs it took (:class:`.pair_plans.Planned`: their
routes, segments, notes, carriers) and :func:`plan_pairs` gathers it into the plans; no step
writes into another's results. The paper's comparison morphs take *prepare*, then their own
morph with its fallback. Every step works on all pairs at once (a single pair is a batch of
one; the ball route, steps 4-10, on runs of about ``BALL_ROUTE_POINTS`` points, one after
another), and nothing here depends on the in-between times: :class:`PairPlans` is the plan,
:meth:`PairPlans.frames` its evaluation.
"""

from dataclasses import dataclass

import numpy as np

from ... import tolerances as tol
from ...geometry.intersections import simple_curves
from ...geometry.polyline import (
    coarsen,
    curve_length,
    default_spacings,
    pair_scales,
    resolve_spacing,
)
from ...geometry.ragged import Ragged, budget_slices
from ...geometry.similarity import Similarity
from ..frames.layout import Segment
from ..strokes import Route, as_written
from .carrier_choice import carrier_motions, note_shape_changes
from .chain_maps import ball_rows, map_chains, placed
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
    unsplittable,
)
from .pair_plans import PairNote, PairPlans, Planned, whole_segment
from .point_routes import dot_route, guarded, own_points_route, polyline_route
from .registration import Motions, identity_residual, moved_curves
from .riding import Rides

__all__ = ["PairCurves", "PairPlans", "PairMorph", "plan_pairs", "BALL_METHODS"]

#: Registered curves within this fraction of their size of each other (RMS) are the same stroke
#: redrawn: their points are matched by arc length and the carrier does the motion. A ball-map
#: of two curves this close would only follow the redrawing's jitter, cut at its many crossings.
NEAR = 0.01


@dataclass(frozen=True)
class _Routes:
    """What happens to each pair of a ball-route batch (a Route each: CARRIER, NEAR, WHOLE,
    LENSES, TANGENT, ALIGNED for curves lying over each other that cannot be cut into lenses,
    LINEAR) and, for the last two, why."""

    route: np.ndarray
    reason: list


def choose_routes(R, Q, events, coincident, near, carrier, scale):
    """Step 7: the route of every pair (see the module docstring); ``near`` marks the pairs
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


@dataclass(frozen=True)
class _FellBack:
    """What step 10, *fall back*, did with a batch's chains.

    Attributes
    ----------
    good : ndarray of bool, shape (H,)
        The chains whose ball-maps hold.
    segments : list of Segment
        The fallbacks of the others (composite, else aligned interpolation).
    notes : list of PairNote
        Which fallback each took, and why.
    """

    good: np.ndarray
    segments: list
    notes: list


def _fall_back(chains, maps, events, index, kind, spacing, ends):
    """Step 10 for chains that are not b-compatible: composite, then aligned interpolation (the
    notes say which); a _FellBack."""
    counts = np.bincount(chains.pair, minlength=len(index))
    good = maps.held()
    failing = np.flatnonzero(~good & ~chains.static)
    if not len(failing):
        return _FellBack(good, [], [])
    orders = failing - np.searchsorted(chains.pair, chains.pair[failing])
    wanted = []
    for k, order in zip(failing, orders):
        c, setup = chains.pair[k], chains.setups[k]
        where = f"lens {order + 1}/{counts[c]}" if events.count[c] else ("loops" if setup.closed else "stroke")
        wanted.append(FailingChain(setup.P, setup.Q, setup.closed, spacing[c], where, maps.reports[k].describe()))
    # Every failing chain's composite ball-morph at once: one at a time, each paid a dozen
    # small ball-maps' fixed costs.
    segments, notes = [], []
    for k, order, (morph, note) in zip(failing, orders, chain_fallbacks(wanted, kind)):
        c = chains.pair[k]
        notes.append(PairNote(int(index[c]), note))
        segments += placed(ends, index, [c], [morph], [order], [(chains.range_p[k], chains.range_q[k])])
    return _FellBack(good, segments, notes)


@dataclass(frozen=True)
class Registered:
    """What step 4, *register*, made of a batch of pairs.

    Attributes
    ----------
    motions : Motions
        Each pair's carrier.
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

    motions: Motions
    R: Ragged
    residual: np.ndarray
    shape_change: np.ndarray
    warps: dict


def register(P, Q, carrier, scale, drawing=None, given=None, rides=None):
    """Step 4: each pair's registration and carrier (see :mod:`.registration`), a Registered.

    Pairs the ball-morph follows as drawn, loops that change shape where they lie (see
    :mod:`.carrier_choice`) and every pair with carrier 'none' get none;
    ``drawing`` (a Similarity) is the keys' overall motion, the prior of symmetric shapes;
    ``given`` (list of Motions of one pair or None, per pair) are carriers already chosen;
    ``rides`` (Rides) what the strokes without an orientation of their own ride.
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
    pts = moved_curves(P, motion.A, motion.b).pts
    R = Ragged(np.where(motion.moving[P.owner][:, None], pts, P.pts), P.offsets, P.closed)
    return Registered(motion, R, identity_residual(R, Q), kept, warps)


def _ball_route(pairs, index, kind, carrier, spacing, drawing=None, rides=None):
    """Steps 4-10 for the pairs ``index`` of ``pairs`` (validated): what they planned (Planned)."""
    closed = np.array([pairs[c].closed for c in index], dtype=bool)
    # Curves drawn far more densely than they will be sampled are resampled first, each at its
    # own default spacing (the keys may differ in size a lot).
    P = coarsen(Ragged.from_list([pairs[c].P for c in index], closed), spacing)
    Q = coarsen(Ragged.from_list([pairs[c].Q for c in index], closed), spacing)
    given = [pairs[c].motion for c in index]
    ridden = None if rides is None else rides.take(index)
    registered = register(P, Q, carrier, pair_scales(P, Q), drawing, given, ridden)
    motions, R, shape_change, warps = registered.motions, registered.R, registered.shape_change, registered.warps
    residual = registered.residual.copy()  # measured again below on the common parts
    notes = list(note_shape_changes(index, motions, shape_change))
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
    in_place = similar_in_place(P, Q, (routes.route == Route.WHOLE) & ~motions.moving & closed & (carrier != "none"))
    routes = _Routes(np.where(deforming | in_place, Route.TANGENT, routes.route), routes.reason)
    lensed = routes.route == Route.LENSES
    whole = np.flatnonzero(routes.route == Route.WHOLE)
    chains = cut_chains(Rc, Qc, events, lensed, whole, coincident, scale)
    maps = map_chains(chains, h, tol.COINCIDENT * scale)
    off_ball, why = _loops_off_the_ball(chains, maps, closed)
    if off_ball.any():
        routes = _Routes(np.where(off_ball, Route.TANGENT, routes.route), routes.reason)
        lensed &= ~off_ball
        keep = ~off_ball[chains.pair]
        chains, maps = chains.keeping(keep), maps.keeping(keep)
    segments, direct_notes = _direct_routes(ends, index, routes, (Rc, Qc, closed, warps), h, why)
    fell_back = _fall_back(chains, maps, events, index, kind, h, ends)
    ball = ball_rows(chains, maps, index, fell_back.good, ends)
    segments += fell_back.segments + _overhangs(index, R, Q, ends, h)
    cut = np.bincount(chains.pair, minlength=len(index))
    notes += direct_notes + fell_back.notes
    notes += [
        PairNote(int(index[c]), f"split at {cut[c]} crossing/overlap pieces")
        for c in np.flatnonzero(lensed & (cut > 1))
    ]
    lengths = np.c_[R.length, Q.length]
    return Planned(
        index, tuple(routes.route), closed, lengths, tuple(segments), tuple(notes), motions, closed & lensed, ball
    )


#: What the report says of a pair of loops no ball-map follows (see :func:`_loops_off_the_ball`).
OFF_THE_BALL = "tangent-aligned correspondence used, straight paths"


def _loops_off_the_ball(chains, maps, closed):
    """Pairs of loops some chain of which no ball-map follows (not b-compatible), shape (C,) of
    bool, and what their reports say (dict: pair in the batch -> note): they take the
    tangent-aligned route (TANGENT) instead of the composite ball-morph.

    A pair of loops the ball-map cannot follow differs in shape where the disks must bridge: an
    outline grown bolder across its own corners (a 'B' whose Thin stem corner lies on the Black
    outline's edge), an 's' whose terminals swell. The composite ball-morph bridges the failing
    stretch with disks that chamfer corners and raise bumps (Karla's 'B', 'D', 's': 13-16/1000
    em off the designer's in-between, whose own straight blend is 0.2); the tangent-aligned
    correspondence matches the parts that run the same way, corners to corners (1.7-2.8).
    Open strokes keep the fallback: their ends settle first (:mod:`.ends`), and a failing lens
    of theirs is a local event.
    """
    failing = ~maps.held() & ~chains.static
    off = np.zeros(len(closed), dtype=bool)
    off[chains.pair[failing]] = True
    off &= closed
    why = {}
    for k in np.flatnonzero(failing & off[chains.pair]):
        why.setdefault(int(chains.pair[k]), f"loops {maps.reports[k].describe()}; {OFF_THE_BALL}")
    return off, why


def _direct_routes(ends, index, routes, curves, h, said=None):
    """The segments and notes of the pairs of ``routes`` (_Routes) whose morphs take the whole
    common parts directly, no ball-map of theirs asked: LINEAR and ALIGNED (each with the note
    that says why), TANGENT and NEAR. ``curves`` are the batch's common parts R and Q (Ragged),
    its loops' flags and the warps already made (pair -> TangentWarp); ``said`` the notes of
    TANGENT pairs that are not changing shape where they lie (pair -> note, see
    :func:`_loops_off_the_ball`).

    Returns
    -------
    segments : list of Segment
    notes : list of PairNote
    """
    R, Q, closed, warps = curves
    ranges = np.stack([np.c_[np.zeros(len(index)), R.length], np.c_[np.zeros(len(index)), Q.length]], 1)
    segments, notes = [], []
    for c in np.flatnonzero(routes.route == Route.LINEAR):
        morph, note = linear_fallback(R.curve(c), Q.curve(c), bool(closed[c]), h[c], routes.reason[c])
        notes.append(PairNote(int(index[c]), note))
        segments += placed(ends, index, [c], [morph], [0], ranges[c])
    aligned = np.flatnonzero(routes.route == Route.ALIGNED)
    if len(aligned):
        pairs = [(R.curve(c), Q.curve(c), bool(closed[c])) for c in aligned]
        morphs, said = aligned_fallbacks(pairs, h[aligned], [routes.reason[c] for c in aligned])
        notes += [PairNote(int(index[c]), note) for c, note in zip(aligned, said)]
        segments += placed(ends, index, aligned, morphs, np.zeros(len(aligned)), ranges[aligned])
    tangent = np.flatnonzero(routes.route == Route.TANGENT)
    if len(tangent):
        # Changing shape where they lie: tangent-aligned, straight paths (:mod:`.deforming`),
        # warped together (a squash's warps made by :func:`register`).
        pairs = [(R.curve(c), Q.curve(c), bool(closed[c])) for c in tangent]
        morphs = tangent_morphs(pairs, [warps.get(int(c)) for c in tangent])
        notes += [PairNote(int(index[c]), (said or {}).get(int(c), DEFORMING_NOTE)) for c in tangent]
        segments += placed(ends, index, tangent, morphs, np.zeros(len(tangent)), ranges[tangent])
    near = np.flatnonzero((routes.route == Route.NEAR) | (routes.route == Route.CARRIER))
    if len(near):
        morphs = arc_length_morphs(R.take(near), Q.take(near), h[near])
        segments += placed(ends, index, near, morphs, np.zeros(len(near)), ranges[near])
    return segments, notes


def _overhangs(index, R, Q, ends, spacing):
    """The parts of open strokes beyond their common part (see :mod:`.ends`): first and last
    chains of their pairs, sliding into the common part's ends or growing out of them; their
    Segments (list)."""
    segments = []
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
                segments.append(Segment(int(index[c]), int(order), *ranges, morph=morph))
    return segments


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


def _isolated_ball_route(pairs, ready, kind, carrier, spacing, drawing=None, rides=None):
    """The ball route for the ready pairs, run of pairs after run of pairs (about
    ``BALL_ROUTE_POINTS`` points each, see :func:`_ball_runs`); should a run fail (a bug), pair
    by pair, so one pair never stops the others: a failing pair takes linear interpolation and
    says why.

    Returns
    -------
    list of Planned
        What the route planned: one per run, or one per pair of a failing run.
    """
    parts = []
    for run in _ball_runs(pairs, ready):
        parts += _guarded_ball_route(pairs, run, kind, carrier, spacing, drawing, rides)
    return parts


#: The ball route takes the ready pairs in runs of about this many points (both curves', as
#: drawn), one run after another: every step of the route holds arrays over the points of the
#: pairs it takes (samples, lens pieces, ball-map rows), so only one run's are held at once (the
#: plan's traced peak at 5,000 pairs of 50-point strokes: 318 MiB in one run, 233 MiB in runs).
#: Each pair's answer is its own up to round-off: a batch's arc lengths are sums along every
#: curve before a pair's (``Ragged.s``, ``Ragged.global_s``), so where a pair sits in its run
#: moves its samples by round-off (at most 7e-11 on the benchmark's 5,000 strokes, 0.5-0.8
#: long; the same routes, morphs, reports and sample counts).
BALL_ROUTE_POINTS = 50_000


def _ball_runs(pairs, ready):
    """The ready pairs (sorted ints) cut into consecutive runs of about ``BALL_ROUTE_POINTS``
    points (a pair with more takes a run of its own): list of ndarray of int."""
    ready = np.asarray(ready, dtype=np.int64)
    sizes = [len(pairs[c].P) + len(pairs[c].Q) for c in ready]
    return [ready[run] for run in budget_slices(sizes, BALL_ROUTE_POINTS)]


def _guarded_ball_route(pairs, run, kind, carrier, spacing, drawing=None, rides=None):
    """:func:`_ball_route` for the pairs ``run`` at once, else pair by pair (a failing pair
    takes linear interpolation and says why): list of Planned."""
    try:
        return [_ball_route(pairs, run, kind, carrier, spacing, drawing, rides)]
    except Exception as exc:  # reported below, pair by pair
        batch_error = f"{type(exc).__name__}: {exc}"
    parts = []
    for c in run.tolist():
        try:
            parts.append(_ball_route(pairs, np.array([c]), kind, carrier, spacing, drawing, rides))
        except Exception as exc:
            pair = pairs[c]
            reason = f"the {kind}-ball morph failed ({type(exc).__name__}: {exc}; with the others: {batch_error})"
            morph, note = linear_fallback(
                pair.P, pair.Q, pair.closed, resolve_spacing(pair.P, pair.Q, pair.closed, None), reason
            )
            segments, lengths = (whole_segment(c, morph, pair.lengths),), np.array([pair.lengths], dtype=np.float64)
            closed = np.array([pair.closed])
            notes = (PairNote(c, note),)
            parts.append(Planned(np.array([c]), (Route.LINEAR,), closed, lengths, segments, notes, Motions.identity(1)))
    return parts


def _comparison_route(pairs, ready, method, spacing):
    """The paper's comparison morphs, pair by pair, each with its fallback (a Planned)."""
    if not ready:
        return Planned.nothing()
    closed = np.array([pairs[c].closed for c in ready], dtype=bool)
    Ps = coarsen(Ragged.from_list([pairs[c].P for c in ready], closed), spacing)
    Qs = coarsen(Ragged.from_list([pairs[c].Q for c in ready], closed), spacing)
    segments, notes = [], []
    for k, c in enumerate(ready):
        P, Q, loop = Ps.curve(k), Qs.curve(k), bool(closed[k])
        morph, said = comparison_morph(P, Q, loop, method, resolve_spacing(P, Q, loop, spacing))
        notes += [PairNote(c, text) for text in said]
        segments.append(whole_segment(c, morph, (Ps.length[k], Qs.length[k])))
    lengths = np.c_[Ps.length, Qs.length]
    return Planned(np.asarray(ready), (Route.COMPARISON,) * len(ready), closed, lengths, tuple(segments), tuple(notes))


def _ride_notes(pairs, rides, moving):
    """Notes saying that a stroke without an orientation of its own rode its group's turn
    (PairNotes; ``moving``: each pair's carrier moves it, shape (C,) of bool)."""
    return tuple(
        PairNote(
            int(c),
            f"rode its group's motion (stroke {as_written(pairs[c].group.loop)} and the strokes inside it,"
            f" turning {np.degrees(pairs[c].group.motion.turn):.0f}°)",
        )
        for c in np.flatnonzero(~np.isnan(rides.a) & ~np.isnan(rides.group) & moving)
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
    prepared = prepare_pairs(pairs, method, spacing)
    pairs, ready = prepared.pairs, prepared.ready
    plans = PairPlans(pairs)
    dots = [c for c, pair in enumerate(pairs) if pair.P is None]
    if method not in BALL_METHODS:
        # Their dots move straight, point by point, with no carrier (nothing to ride).
        plans.gather(dot_route(pairs, dots, "none", None, None))
        plans.gather(_comparison_route(pairs, ready, method, spacing))
        return plans.finish()
    kind = method[: -len("-ball")]
    plans.motions = Motions.identity(len(pairs), "rigid" if carrier == "rigid" else "similarity")
    rides = Rides.of_pairs(pairs, ready, dots, drawing)
    if drawing is not None and not rides.witnessed:
        # Nothing shows the drawing's turn (circles and dots alone: their centroids fit any):
        # no prior of symmetric fits either; its scale still counts (strokes sliding start at it).
        drawing = Similarity(drawing.scale)
    plans.gather(dot_route(pairs, dots, carrier, drawing, rides))
    # Pieces of hinted pairs share their pair's carrier: only the ball route takes them.
    pieces = [c for c in ready if pairs[c].motion is not None]
    ready = [c for c in ready if pairs[c].motion is None]
    for route in (own_points_route, polyline_route):
        planned, ready = guarded(route, pairs, ready, carrier, drawing, rides)
        plans.gather(planned)
    ready = sorted(ready + pieces)
    for planned in _isolated_ball_route(pairs, ready, kind, carrier, spacing, drawing, rides) if ready else ():
        plans.gather(planned)
    plans.gather(Planned.nothing(notes=_ride_notes(pairs, rides, plans.motions.moving)))
    del prepared, pairs, planned  # their curves are not needed to lay the samples out (held while it runs)
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
