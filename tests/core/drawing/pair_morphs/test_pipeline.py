"""The stroke-pair pipeline (drawing/pair_morphs/pipeline.py): the route each pair takes is a
field of its report (``PairReport.used.route``), never parsed from the report's words; steps
return what they planned (Planned) and the pipeline gathers it."""

import bench_drawings
import numpy as np
import pytest
from shapes import circle

import ballmorph_core as bm
from ballmorph_core.drawing.pair_morphs import pipeline
from ballmorph_core.drawing.pair_morphs.curves import PairCurves, prepare_pairs
from ballmorph_core.drawing.pair_morphs.fallbacks import point_motion
from ballmorph_core.drawing.pair_morphs.pair_plans import PairNote, PairPlans, Planned, whole_segment
from ballmorph_core.drawing.pair_morphs.pipeline import plan_pairs
from ballmorph_core.drawing.pair_morphs.point_routes import guarded, own_points_route
from ballmorph_core.drawing.pair_morphs.riding import Rides
from ballmorph_core.drawing.strokes import Route


def _route(a, b, cyclic, **options):
    key_a = bm.StrokeSet.from_strokes([a], cyclic=[cyclic])
    key_b = bm.StrokeSet.from_strokes([b], cyclic=[cyclic])
    (pair,) = [p for p in bm.inbetween(key_a, key_b, [0.5], **options).pairs if p.stroke_a is not None]
    return pair.used.route, pair


def _wavy(amplitude, n=60):
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x, amplitude * np.sin(3 * np.pi * x)]


def test_a_moved_copy_keeps_its_own_points():
    a = _wavy(0.2)
    route, pair = _route(a, a * 1.5 + [2.0, 1.0], False)
    assert route == Route.OWN_POINTS, pair


def test_crossing_loops_are_cut_into_lenses():
    route, pair = _route(circle(1.0, 64), circle(1.0, 64, centre=(0.8, 0.0)) * [1.0, 1.3], True, carrier="none")
    assert route == Route.LENSES and "split at" in pair.reason, pair


def _arch(height, n=60):
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x, height * np.sin(np.pi * x)]


def test_strokes_sharing_their_ends_are_one_lens():
    route, pair = _route(_arch(0.2), _arch(0.45), False)
    assert route == Route.LENSES and pair.used.morphs == ("circular-ball",) and not pair.reason, pair


def test_nested_loops_are_ball_mapped_whole():
    route, pair = _route(circle(1.0, 64), circle(2.0, 64) * [1.0, 0.8], True, carrier="none")
    assert route == Route.WHOLE and pair.used.morphs == ("circular-ball",), pair


def test_a_dot_moves_point_by_point():
    route, pair = _route(np.array([[0.0, 0.0]]), np.array([[1.0, 0.5]]), False)
    assert route == Route.DOT, pair


@pytest.mark.parametrize("method", ["laplace-blending", "heat-propagation"])
def test_the_papers_comparison_morphs_take_their_own_route(method):
    route, pair = _route(_arch(0.2), _arch(0.45), False, method=method)
    assert route == Route.COMPARISON and method in pair.used.morphs, pair


def _pair_curves(a, b, closed):
    u = [np.linspace(0.0, 1.0, len(c)) for c in (a, b)]
    return PairCurves(np.asarray(a, float), u[0], closed, np.asarray(b, float), u[1], closed)


def test_planning_leaves_the_pairs_it_is_given_as_they_were():
    """Step 1 returns prepared copies: the pairs plan_pairs receives keep no curves or notes of it."""
    pairs = [_pair_curves(circle(1.0, 40), circle(1.2, 50), True), _pair_curves([[0.0, 0.0]], [[1.0, 0.0]], False)]
    pairs.append(PairCurves(pairs[0].xy_a, pairs[0].u_a, True, pairs[0].xy_b, pairs[0].u_b, False))
    plans = plan_pairs(pairs)
    assert all(p.P is None and p.Q is None and not p.notes and p.closed is False for p in pairs)
    assert any("cyclic and the other's is not" in note for note in plans.notes[2])
    assert any("too few distinct points" in note for note in plans.notes[1])
    assert plans.used[1].route == Route.DOT and all(m.route is not None for m in plans.used)


def test_a_failing_route_takes_no_pair_and_sends_them_all_on():
    """guarded: a route that raises plans nothing (nothing to undo) and every ready pair goes on."""
    pairs = [_pair_curves(circle(1.0, 40), circle(1.0, 40) + 1.0, True)]

    def broken(pairs, ready, carrier, drawing, rides):
        raise ZeroDivisionError("simulated core bug")

    rides = Rides.of_pairs(pairs, [0], [], None)
    planned, rest = guarded(broken, pairs, [0], "similarity", None, rides)
    assert rest == [0] and len(planned.pairs) == 0 and not planned.segments and not planned.notes
    planned, rest = guarded(
        own_points_route, prepare_pairs(pairs, "circular-ball", None).pairs, [0], "similarity", None, rides
    )
    assert rest == [] and planned.routes == (Route.OWN_POINTS,) and len(planned.segments) == 1


def test_a_step_s_plan_is_gathered_in_order():
    """PairPlans.gather writes what a step planned: routes, flags, notes after the pair's own."""
    pairs = [_pair_curves(circle(1.0, 40), circle(1.0, 40), True) for _ in range(3)]
    plans = PairPlans(pairs)
    morph = point_motion(circle(1.0, 8), np.linspace(0, 1, 8), circle(1.0, 8), np.linspace(0, 1, 8))
    notes = (PairNote(2, "first"), PairNote(0, "zero"), PairNote(2, "second"))
    segments = (whole_segment(2, morph, (3.0, 4.0)), whole_segment(0, morph, (1.0, 2.0)))
    closed, lengths = np.array([True, False]), np.array([[3.0, 4.0], [1.0, 2.0]])
    plans.gather(Planned(np.array([2, 0]), (Route.LINEAR, Route.NEAR), closed, lengths, segments, notes))
    assert plans.routes == [Route.NEAR, None, Route.LINEAR]
    assert plans.notes == [["zero"], [], ["first", "second"]]
    np.testing.assert_array_equal(plans.closed, [False, False, True])
    np.testing.assert_array_equal(plans.lengths, [[1.0, 2.0], [1.0, 1.0], [3.0, 4.0]])
    assert [s.pair for s in plans.segments] == [2, 0] and plans.segments[0].range_q == (0.0, 4.0)


def _bench_keys(kind, strokes, points):
    key_a, key_b = bench_drawings.make_keys(kind, strokes, points)
    closed = kind in ("loops", "deforming")
    return [
        bm.StrokeSet.from_strokes([np.c_[p[:, 0], np.zeros(len(p)), p[:, 1]] for p in key], cyclic=[closed] * len(key))
        for key in (key_a, key_b)
    ]


@pytest.mark.parametrize(("kind", "strokes", "points"), [("open", 120, 30), ("loops", 80, 30), ("jagged", 24, 40)])
def test_the_ball_route_in_runs_of_pairs_gives_each_pair_its_own_answer(monkeypatch, kind, strokes, points):
    """Runs of a few pairs plan every pair as one run of all does: the same routes, morphs,
    reports and samples, frames within 1e-9 (the strokes are on a unit grid). Not bit for bit:
    a batch's arc lengths are sums along every curve before a pair's (``Ragged.s``), so a pair's
    round-off depends on where it sits in its run."""
    key_a, key_b = _bench_keys(kind, strokes, points)
    times = [0.25, 0.5, 0.75]
    monkeypatch.setattr(pipeline, "BALL_ROUTE_POINTS", 10**12)
    whole = bm.inbetween(key_a, key_b, times)
    monkeypatch.setattr(pipeline, "BALL_ROUTE_POINTS", 20 * points)
    runs = bm.inbetween(key_a, key_b, times)
    assert [(p.used, p.reason) for p in runs.pairs] == [(p.used, p.reason) for p in whole.pairs]
    assert [m.text for m in runs.messages] == [m.text for m in whole.messages]
    for got, want in zip(runs.frames, whole.frames):
        np.testing.assert_array_equal(got.offsets, want.offsets)
        np.testing.assert_allclose(got.positions, want.positions, rtol=0.0, atol=1e-9)


def test_the_ball_route_runs_cover_the_ready_pairs_in_order(monkeypatch):
    """Each run holds about BALL_ROUTE_POINTS points of both curves; a pair with more runs alone."""
    line = np.c_[np.linspace(0.0, 1.0, 10), np.zeros(10)]
    pairs = [PairCurves(line, None, False, line, None, False, line, line) for _ in range(7)]
    pairs[3] = PairCurves(line, None, False, line, None, False, np.repeat(line, 5, 0), line)
    monkeypatch.setattr(pipeline, "BALL_ROUTE_POINTS", 40)
    runs = pipeline._ball_runs(pairs, [0, 1, 2, 3, 4, 5, 6])
    assert [r.tolist() for r in runs] == [[0, 1], [2], [3], [4, 5], [6]]


def test_a_failing_run_of_pairs_goes_pair_by_pair_and_the_other_runs_are_untouched(monkeypatch):
    """A bug in the ball route with a run of pairs: that run's pairs are planned one by one (a
    pair failing alone takes linear interpolation and says why); the other runs as they were."""
    key_a, key_b = _bench_keys("open", 12, 30)
    times = [0.5]
    monkeypatch.setattr(pipeline, "BALL_ROUTE_POINTS", 4 * 60)  # runs of 4 pairs
    want = bm.inbetween(key_a, key_b, times)
    real, calls = pipeline._ball_route, []

    def buggy(pairs, index, *args):
        calls.append(index.tolist())
        if 5 in index.tolist():
            raise ZeroDivisionError("simulated core bug")
        return real(pairs, index, *args)

    monkeypatch.setattr(pipeline, "_ball_route", buggy)
    got = bm.inbetween(key_a, key_b, times)
    assert calls == [[0, 1, 2, 3], [4, 5, 6, 7], [4], [5], [6], [7], [8, 9, 10, 11]]
    for c, (g, w) in enumerate(zip(got.pairs, want.pairs)):
        if c == 5:
            assert g.used.route == Route.LINEAR and "with the others: ZeroDivisionError" in g.reason, g
        else:
            assert (g.used, g.reason) == (w.used, w.reason), c
