"""Real drawings (issue 5): carriers, crossing splits, overlaps, composite ball-morph, pipeline."""

import importlib

import numpy as np
import pytest
from shapes import circle, distance_to_polyline

import ballmorph_core as bm
from ballmorph_core.drawing.frames.layout import _carry
from ballmorph_core.drawing.pair_morphs.crossings import cut_chains, find_events
from ballmorph_core.drawing.pair_morphs.pipeline import PairMorph
from ballmorph_core.drawing.pair_morphs.registration import Fits, endpoint_similarity, fit_similarity, motions
from ballmorph_core.geometry.intersections import crossings, is_simple
from ballmorph_core.geometry.polyline import curve_length, orient_clockwise, resample, scale_of
from ballmorph_core.geometry.ragged import Ragged
from ballmorph_core.geometry.similarity import Similarity

# ------------------------------------------------------------------ registration


def test_similarity_power_is_a_steady_interpolation():
    s = Similarity(1.3 * np.exp(0.7j), 0.4 - 0.2j)
    pts = np.array([[0.3, -1.0], [2.0, 0.5]])
    np.testing.assert_allclose(s.power(0.0)(pts), pts, atol=1e-12)
    np.testing.assert_allclose(s.power(1.0)(pts), s(pts), atol=1e-12)
    np.testing.assert_allclose(s.power(0.5)(s.power(0.5)(pts)), s(pts), atol=1e-12)
    np.testing.assert_allclose(s.power(-1.0)(s(pts)), pts, atol=1e-12)
    # The fixed point does not move.
    c = s.b / (1 - s.a)
    np.testing.assert_allclose(s.power(0.37)(np.array([[c.real, c.imag]])), [[c.real, c.imag]], atol=1e-12)


def test_endpoint_similarity_maps_endpoints():
    P = np.array([[0.0, 0.0], [0.5, 0.3], [1.0, 0.0]])
    Q = np.array([[2.0, 1.0], [2.4, 1.9], [2.0, 3.0]])
    s = endpoint_similarity(P, Q)
    np.testing.assert_allclose(s(P[[0, -1]]), Q[[0, -1]], atol=1e-12)


@pytest.mark.parametrize("reverse", [False, True])
def test_fit_similarity_recovers_a_loop_transform_whatever_start_and_direction(reverse):
    t = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    P = np.c_[np.cos(t) + 0.3 * np.cos(2 * t), 0.6 * np.sin(t)]
    true = Similarity(0.8 * np.exp(1.1j), 2.0 + 1.0j)
    Q = np.roll(true(P), 17, axis=0)
    if reverse:
        Q = Q[::-1]
    fit = fit_similarity(P, Q, True)
    # The shift of 17 of 90 vertices falls between the fit's 128 uniform samples: a few %.
    assert abs(fit.a - true.a) < 3e-2 * abs(true.a) and abs(fit.b - true.b) < 5e-2


@pytest.mark.parametrize("kind", ["similarity", "rigid"])
def test_carrier_undoes_registration_at_start_and_is_identity_at_end(kind):
    s = Similarity(1.5 * np.exp(-0.4j), 1.0 + 2.0j)
    A = np.array([[[s.a.real, -s.a.imag], [s.a.imag, s.a.real]]])
    P = Ragged.from_list([circle(1.0, 40)], [True])
    moved = motions(P, Fits(A, np.array([[s.b.real, s.b.imag]]), np.zeros(1)), kind, np.ones(1), np.ones(1, bool))
    pts = np.array([[0.0, 1.0], [3.0, -2.0]])
    registered = np.einsum("ij,kj->ki", moved.A[0], pts) + moved.b[0]
    for t, given in ((0.0, registered), (1.0, pts)):
        frame = given.copy()
        _carry(moved, t, frame, np.array([2]))
        np.testing.assert_allclose(frame, pts, atol=1e-12)
    # The turn is steady: half-way, half the angle.
    M, _ = moved.partial(0.5)
    assert np.isclose(np.arctan2(M[0, 1, 0], M[0, 0, 0]), -0.2)


# ------------------------------------------------------------------ issue 5 must-shows


def test_rotated_stroke_keeps_its_length_but_linear_interpolation_shrinks():
    x = np.linspace(-1.0, 1.0, 80)
    P = np.c_[x, 0.0 * x]
    Q = np.c_[3.0 + 0.0 * x, 1.0 + x]  # turned 90 degrees about its centre and moved
    key = curve_length(P, False)
    ours = PairMorph(P, Q, False, "circular-ball", "similarity")
    lengths = np.array([curve_length(ours(t), False) for t in np.linspace(0, 1, 11)])
    assert np.all(np.abs(lengths / key - 1) < 0.05)
    lerp = bm.make_morph(P, Q, "linear-interpolation")
    mid = curve_length(lerp(0.5), False) / key
    assert abs(mid - np.sqrt(0.5)) < 0.01  # 71 %, as Blender's own interpolation


def test_translated_circle_stays_a_circle_on_the_default_carrier():
    c = circle(1.0, 120)
    shift = np.array([1.2, 0.4])
    morph = PairMorph(c, c + shift, True, "circular-ball", "similarity")
    for t in np.linspace(0.1, 0.9, 9):
        frame = morph(t)
        np.testing.assert_allclose(np.linalg.norm(frame - t * shift, axis=1), 1.0, atol=1e-6)


def test_translated_circle_without_carrier_passes_through_the_crossings():
    c = circle(1.0, 160)
    Q = c + [1.2, 0.4]
    cx = crossings(c, True, Q, True)
    assert len(cx) == 2
    outcome = PairMorph(c, Q, True, "circular-ball", "none")
    assert any("split" in note for note in outcome.notes)
    for t in np.linspace(0.1, 0.9, 9):
        frame = outcome(t)
        assert is_simple(frame, True)
        assert distance_to_polyline(cx.points, frame, True).max() < 1e-6


def _pear_and_notched_circle():
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    r = 1.6 + 0.25 * np.cos(t - np.pi / 2) + 0.1 * np.cos(2 * t)
    pear = np.c_[0.9 * r * np.cos(t), 1.2 * r * np.sin(t)]
    notch = 1.0 - 0.6 * np.maximum(0, 1 - np.abs(np.angle(np.exp(1j * (t - 0.3)))) / 0.12)
    return np.c_[notch * np.cos(t), notch * np.sin(t)], pear


def test_pear_against_notched_circle_composite_frames_never_self_intersect():
    notched, pear = _pear_and_notched_circle()
    with pytest.raises(bm.IncompatibleCurvesError):
        bm.ball_map(notched, pear, closed=True)
    morph = bm.make_morph(notched, pear, "composite-ball", closed=True)
    assert len(morph.stages["bridges_p"]) == 1  # the notch is bridged by one disk
    assert distance_to_polyline(morph(0.0), notched, True).max() < 1e-2
    assert distance_to_polyline(morph(1.0), pear, True).max() < 1e-2
    for t in np.linspace(0.0, 1.0, 21):
        frame = morph(t)
        assert np.all(np.isfinite(frame))
        assert is_simple(frame, True)
    # Every sample moves at constant speed along its (piecewise circular) trajectory: at time
    # t it has covered the fraction t of its path's length.
    paths = morph.paths.points  # (K, S, 2)
    seg = np.linalg.norm(np.diff(paths, axis=1), axis=2)
    total = seg.sum(axis=1)
    cum = np.concatenate([np.zeros((len(paths), 1)), np.cumsum(seg, axis=1)], axis=1)
    for t in (0.2, 0.5, 0.8):
        pos = morph(t)
        # Arc length of each position along its own path (nearest segment).
        a, b = paths[:, :-1], paths[:, 1:]
        ab = b - a
        u = np.clip(
            np.einsum("ksi,ksi->ks", pos[:, None] - a, ab) / np.maximum(np.einsum("ksi,ksi->ks", ab, ab), 1e-300), 0, 1
        )
        d = np.linalg.norm(a + u[..., None] * ab - pos[:, None], axis=2)
        j = np.argmin(d, axis=1)
        rows = np.arange(len(paths))
        s = cum[rows, j] + u[rows, j] * seg[rows, j]
        moving = total > 1e-9
        np.testing.assert_allclose(s[moving] / total[moving], t, atol=1e-6)


def test_composite_of_a_compatible_pair_is_the_ball_morph():
    c = circle(1.0, 100)
    a = bm.make_morph(c, 2 * c, "composite-ball", closed=True)
    b = bm.make_morph(c, 2 * c, "circular-ball", closed=True)
    np.testing.assert_allclose(a(0.5), b(0.5), atol=1e-12)


# ------------------------------------------------------------------ splitting


def _lenses(P, Q, closed, spacing):
    """Steps 6 and 8 of the pipeline on one pair: its events (find_events) and the chains it is
    cut into (cut_chains), with the pair lensed."""
    R, Qr = Ragged.from_list([P], [closed]), Ragged.from_list([Q], [closed])
    scale = np.array([scale_of(P, Q)])
    events = find_events(R, Qr, scale, np.array([float(spacing)]), np.ones(1, dtype=bool))
    if not events.agree[0]:
        return events, None
    chains = cut_chains(R, Qr, events, np.ones(1, dtype=bool), np.zeros(0, np.int64), np.zeros(1, bool), scale)
    return events, chains


def test_crossing_strokes_split_into_lenses_that_share_endpoints():
    x = np.linspace(0, 1, 200)
    P = np.c_[x, 0.2 * np.sin(2 * np.pi * x)]
    Q = np.c_[x, 0.05 * np.sin(np.pi * x)]
    _, chains = _lenses(P, Q, False, 0.01)
    assert len(chains) == 2 and not chains.static.any()  # two lenses, no overlap
    for lens in chains.setups:
        np.testing.assert_array_equal(lens.P[[0, -1]], lens.Q[[0, -1]])
        assert bm.classify(lens.P, lens.Q) == "quasi-disjoint-strokes"
    np.testing.assert_allclose(chains.setups[0].P[-1], chains.setups[1].P[0])


def test_overlapping_portion_stays_static():
    x = np.linspace(0, 1, 201)
    bump = np.where(x < 0.5, 0.0, np.sin(2 * np.pi * (x - 0.5)))
    P, Q = np.c_[x, 0.3 * bump], np.c_[x, -0.2 * bump]
    outcome = PairMorph(P, Q, False, "circular-ball", "none")
    flat = x < 0.45
    for t in (0.3, 0.7):
        frame = outcome(t)
        on_flat = frame[frame[:, 0] < 0.45]
        assert len(on_flat) > 10
        np.testing.assert_allclose(on_flat[:, 1], 0.0, atol=1e-9)
    assert flat.any()


def test_tangled_crossings_are_rejected():
    c = orient_clockwise(circle(1.0, 200))
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    wobble = orient_clockwise(np.c_[(1 + 0.3 * np.cos(5 * t)) * np.cos(t), (1 + 0.3 * np.cos(5 * t)) * np.sin(t)])
    # Five lobes crossing a circle ten times in the same order still split...
    events, chains = _lenses(c, wobble, True, 0.02)
    assert events.agree[0] and len(chains) == 10
    # ...but a stroke crossing a line at 0.7, then 0.3, then 0.5 of it does not (the line
    # meets those crossings in another order), and the pair says why.
    corners = [(0, 0), (0.2, 0.3), (0.7, 0.3), (0.7, -0.3), (0.3, -0.3), (0.3, 0.15), (0.5, 0.15), (0.5, -0.15), (1, 0)]
    tangled = resample(np.array(corners, dtype=np.float64), False, count=300, smooth=False)
    line = np.c_[np.linspace(0, 1, 200), np.zeros(200)]
    events, chains = _lenses(line, tangled, False, 0.01)
    assert not events.agree[0] and chains is None
    assert "order" in events.why_tangled(0)


# ------------------------------------------------------------------ the pipeline


def _drawing_4_and_5():
    x = np.linspace(0, 1, 60)
    a = [
        np.c_[x, 0.3 * np.sin(np.pi * x)],
        np.c_[x, 2 + 0.1 * x],
        circle(0.3, 50, centre=(3.0, 1.0)),
        np.c_[x + 5, 0.5 * x],
    ]
    b = [
        np.c_[x, -0.2 * np.sin(np.pi * x)],
        np.c_[x + 0.4, 2.3 - 0.1 * x][::-1],  # drawn the other way
        circle(0.35, 50, centre=(3.2, 1.1)),  # crosses its first position
        np.c_[x + 5.2, 0.4 + 0.3 * x],
        np.c_[x + 8, np.sin(3 * x)],  # new stroke
    ]
    cyc_a = np.array([False, False, True, False])
    cyc_b = np.array([False, False, True, False, False])
    return bm.StrokeSet.from_strokes(a, cyclic=cyc_a), bm.StrokeSet.from_strokes(b, cyclic=cyc_b)


def test_pipeline_on_mismatched_drawing_reports_and_keeps_strokes_simple():
    key_a, key_b = _drawing_4_and_5()
    times = np.linspace(0, 1, 7)[1:-1]
    result = bm.inbetween(key_a, key_b, times)
    texts = " ".join(m.text for m in result.messages)
    assert "stroke 5 of the second key has no partner" in texts
    assert "flipped" in texts
    for k, frame in enumerate(result.frames):
        assert len(frame) == (4 if times[k] < 0.5 else 5)
        for i in range(len(frame)):
            pts = frame.positions[frame.points(i)][:, [0, 2]]
            assert is_simple(pts, bool(frame.cyclic[i]))
    assert all(np.isfinite(f.positions).all() for f in result.frames)


def test_attributes_follow_the_correspondence():
    x = np.linspace(0, 1, 80)
    key_a = bm.StrokeSet.from_strokes([np.c_[x, 0.3 * np.sin(np.pi * x)]], radius=[np.linspace(0.0, 1.0, 80)])
    key_b = bm.StrokeSet.from_strokes([np.c_[x, -0.3 * np.sin(np.pi * x)]], radius=[np.full(80, 2.0)])
    frame = bm.inbetween(key_a, key_b, [0.5], method="linear-ball").frames[0]
    # Mirror pair with straight paths: the sample at x comes from the point of A at x, whose
    # radius is x (vertices are evenly spaced in x), and from its mirror on B (radius 2).
    np.testing.assert_allclose(frame.radius, 0.5 * frame.positions[:, 0] + 1.0, atol=1e-3)
    np.testing.assert_allclose(frame.opacity, 1.0)


def test_keys_are_not_modified():
    key_a, key_b = _drawing_4_and_5()
    before = [k.positions.copy() for k in (key_a, key_b)]
    bm.inbetween(key_a, key_b, [0.5])
    for k, b in zip((key_a, key_b), before):
        np.testing.assert_array_equal(k.positions, b)


def _same_drawing(got, want):
    """Two InbetweenResults are the same, bit for bit, reports included."""
    assert len(got.frames) == len(want.frames)
    for g, w in zip(got.frames, want.frames):
        for name in ("positions", "offsets", "cyclic", "material_index", "radius", "opacity", "vertex_color", "origin"):
            np.testing.assert_array_equal(getattr(g, name), getattr(w, name), err_msg=name)
    assert [(m.level, m.text) for m in got.messages] == [(m.level, m.text) for m in want.messages]
    assert got.pairs == want.pairs


@pytest.mark.parametrize("method", ["circular-ball", "parabolic-ball", "laplace-blending"])
def test_a_plan_evaluates_to_what_inbetween_gives_at_any_times(method, monkeypatch):
    """The operator's redo reuses a plan with other times: each evaluation must be exactly the
    in-betweens computed from scratch, including fallbacks, and must plan nothing again."""
    key_a, key_b = _drawing_4_and_5()
    t = np.linspace(0, 4 * np.pi, 90)
    curl = 0.2 * np.c_[t - 2 * np.sin(t), 1 - 2 * np.cos(t)]  # a prolate cycloid: crosses itself
    extra_a = bm.StrokeSet.from_strokes([curl + (12, 0), np.array([[15.0, 0.0]])])
    extra_b = bm.StrokeSet.from_strokes([curl * (1.0, 1.4) + (12.5, 0.2), np.array([[15.0, 0.0], [15.5, 0.3]])])
    key_a = bm.StrokeSet.concatenate([key_a, extra_a])
    key_b = bm.StrokeSet.concatenate([key_b, extra_b])
    plan = bm.plan_inbetween(key_a, key_b, method)
    pipeline = importlib.import_module("ballmorph_core.drawing.pair_morphs.pipeline")
    fallbacks = importlib.import_module("ballmorph_core.drawing.pair_morphs.fallbacks")
    planned = []
    for times in ([0.5], np.linspace(0, 1, 9), [0.1, 0.9, 0.3], [-1.0, 2.0]):
        with monkeypatch.context() as patch:
            for module, name in ((pipeline, "map_chains"), (pipeline, "plan_pairs"), (fallbacks, "make_morph")):
                patch.setattr(module, name, lambda *args, _name=name, **kwargs: planned.append(_name))
            got = plan.evaluate(times)
        assert not planned, f"evaluating a plan planned again: {planned}"
        want = bm.inbetween(key_a, key_b, times, method)
        _same_drawing(got, want)
    used = [p.method for p in got.pairs]
    if method.endswith("-ball"):
        assert any(u.startswith("aligned-interpolation") for u in used)  # the curl: a fallback
    assert "straight point motion" in used  # the dot


@pytest.mark.parametrize("carrier", ["similarity", "rigid", "none"])
@pytest.mark.parametrize("method", ["circular-ball", "linear-ball", "parabolic-ball"])
def test_a_pair_alone_is_morphed_as_in_its_drawing(method, carrier):
    """A single pair is a batch of one: morphed alone, each pair of a drawing gets exactly the
    in-betweens it gets among the others."""
    key_a, key_b = _drawing_4_and_5()
    times = np.linspace(0, 1, 5)
    plan = bm.plan_inbetween(key_a, key_b, method, carrier)
    together = plan.pairs.frames(times)
    for k, (a, b, _) in enumerate(plan.strokes):
        frames, u_a, _ = together.pair(k)
        alone = PairMorph(a.xy, b.xy, a.closed and b.closed, method, carrier)
        assert alone.used == together.used[k]
        np.testing.assert_allclose(alone.frames(times), frames, atol=1e-9)
        np.testing.assert_allclose(alone.u_p, u_a, atol=1e-9)


def test_ball_mapping_in_batches_changes_nothing(monkeypatch):
    """A huge drawing's lenses are ball-mapped in batches (chain_maps.BALLMAP_BATCH_POINTS):
    cutting the same drawing into one batch per pair gives the same in-betweens."""
    chain_maps = importlib.import_module("ballmorph_core.drawing.pair_morphs.chain_maps")

    key_a, key_b = _drawing_4_and_5()
    times = np.linspace(0, 1, 5)
    one = bm.inbetween(key_a, key_b, times)
    monkeypatch.setattr(chain_maps, "BALLMAP_BATCH_POINTS", 10)  # every pair a batch of its own
    many = bm.inbetween(key_a, key_b, times)
    assert [p.method for p in many.pairs] == [p.method for p in one.pairs]
    for a, b in zip(one.frames, many.frames):
        np.testing.assert_array_equal(a.offsets, b.offsets)
        np.testing.assert_allclose(a.positions, b.positions, atol=1e-9)


def test_a_bug_in_the_batched_route_stops_only_its_pair(monkeypatch):
    """The ball route runs every pair at once; if it raises (a bug), the pairs are planned one by
    one, so only the failing pair falls back, and its report names the error."""
    pipeline = importlib.import_module("ballmorph_core.drawing.pair_morphs.pipeline")
    key_a, key_b = _drawing_4_and_5()
    # The second key's loop squashed: not a similar copy, so it takes the ball route.
    loop = key_b.points(2)
    key_b.positions[loop, 0] = 3.2 + 1.3 * (key_b.positions[loop, 0] - 3.2)
    real = pipeline.find_events

    def flaky(R, Q, *args, **kwargs):
        if len(R) == 1 and R.closed[0]:  # the loop, planned alone
            raise ZeroDivisionError("simulated core bug")
        if len(R) > 1:
            raise ZeroDivisionError("simulated core bug")
        return real(R, Q, *args, **kwargs)

    monkeypatch.setattr(pipeline, "find_events", flaky)
    result = bm.inbetween(key_a, key_b, [0.5])
    used = {(p.stroke_a, p.stroke_b): p.used.morphs for p in result.pairs}
    assert used[(2, 2)][0] == "linear-interpolation"
    others = [m for k, m in used.items() if k not in ((2, 2), (None, 4))]
    assert all(m[0] in ("circular-ball", "own points") for m in others) and any("circular-ball" in m for m in others)
    texts = [m.text for m in result.messages if m.level == "WARNING"]
    assert any("circular-ball morph failed (ZeroDivisionError: simulated core bug" in t for t in texts), texts


def test_evaluating_a_few_times_at_a_time_changes_nothing(monkeypatch):
    """A plan evaluates its times in chunks (plan.EVALUATE_SAMPLES): one time per chunk gives
    the same in-betweens and reports, bit for bit, on every golden drawing (hints, splits,
    fallbacks, every method)."""
    import golden_cases

    plan_module = importlib.import_module("ballmorph_core.drawing.plan")
    times = np.linspace(0.0, 1.0, 7)
    for _name, key_a, key_b, options in golden_cases.cases():
        plan = bm.plan_inbetween(key_a, key_b, **options)
        whole = plan.evaluate(times)
        with monkeypatch.context() as patch:
            patch.setattr(plan_module, "EVALUATE_SAMPLES", 1)
            chunked = plan.evaluate(times)
        _same_drawing(chunked, whole)


def test_a_pair_not_finite_at_some_times_only_is_reported_as_when_evaluated_at_once(monkeypatch):
    """A chunk whose frames are not finite sends every time through the point-by-point motion
    together, so the report does not depend on how the times were chunked."""
    plan_module = importlib.import_module("ballmorph_core.drawing.plan")
    key_a, key_b = _drawing_4_and_5()
    plan = bm.plan_inbetween(key_a, key_b)
    real = type(plan.pairs).frames

    def late_nan(self, times, out=None):
        parts = real(self, times, out)
        late = np.asarray(times) > 0.6
        parts.frames[late, parts.offsets[0] : parts.offsets[1]] = np.nan
        return parts

    monkeypatch.setattr(type(plan.pairs), "frames", late_nan)
    times = np.linspace(0.0, 1.0, 6)
    whole = plan.evaluate(times)
    monkeypatch.setattr(plan_module, "EVALUATE_SAMPLES", 1)
    chunked = plan.evaluate(times)
    _same_drawing(chunked, whole)
    assert chunked.pairs[0].method == "straight point motion"
    assert "non-finite" in chunked.pairs[0].reason
    assert all(np.isfinite(f.positions).all() for f in chunked.frames)


def test_a_plan_reads_its_samples_on_the_keys_once_and_stays_exact(monkeypatch):
    """A plan reads what its samples take from the keys (attributes, sources, pieces) at its
    first evaluation and afterwards only moves and mixes: later evaluations at other times, in
    chunks, read nothing again and are bit for bit a fresh plan's, on every golden drawing."""
    import golden_cases

    plan_module = importlib.import_module("ballmorph_core.drawing.plan")
    keys_module = importlib.import_module("ballmorph_core.drawing.keys.projected")
    real, sampled = keys_module.ProjectedKey.sample, []
    later = [0.9, 0.15, 0.5, 0.0]
    for _name, key_a, key_b, options in golden_cases.cases():
        plan = bm.plan_inbetween(key_a, key_b, **options)
        plan.evaluate(np.linspace(0.0, 1.0, 5))
        with monkeypatch.context() as patch:
            patch.setattr(keys_module.ProjectedKey, "sample", lambda key, *args: sampled.append(1) or real(key, *args))
            patch.setattr(plan_module, "EVALUATE_SAMPLES", 1)
            again = plan.evaluate(later)
        assert not sampled, "a plan read its samples on the keys again"
        _same_drawing(again, bm.plan_inbetween(key_a, key_b, **options).evaluate(later))


def test_a_pair_not_finite_at_some_times_leaves_the_kept_samples_alone(monkeypatch):
    """An evaluation where a pair goes point by point (other samples) neither uses nor spoils
    what the plan kept of its own samples: before, during and after, each evaluation is a
    fresh plan's."""
    key_a, key_b = _drawing_4_and_5()
    frames_of = type(bm.plan_inbetween(key_a, key_b).pairs).frames
    times = np.linspace(0.0, 1.0, 6)

    def late_nan(self, at, out=None):
        parts = frames_of(self, at, out)
        parts.frames[np.asarray(at) > 0.6, parts.offsets[0] : parts.offsets[1]] = np.nan
        return parts

    plan = bm.plan_inbetween(key_a, key_b)
    _same_drawing(plan.evaluate(times), bm.inbetween(key_a, key_b, times))
    with monkeypatch.context() as patch:
        patch.setattr(type(plan.pairs), "frames", late_nan)
        broken = plan.evaluate(times)
        _same_drawing(broken, bm.plan_inbetween(key_a, key_b).evaluate(times))
    assert broken.pairs[0].method == "straight point motion"
    _same_drawing(plan.evaluate(times[::-1]), bm.inbetween(key_a, key_b, times[::-1]))
