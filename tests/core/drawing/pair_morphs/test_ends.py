"""Open strokes whose registered ends do not meet (drawing/ends.py) and the sliding fit that
finds strokes lying along each other (drawing/registration.py)."""

import bench_drawings
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from shapes import distance_to_polyline

from ballmorph_core.drawing.pair_morphs import ends, sliding
from ballmorph_core.drawing.pair_morphs.carrier_choice import carrier_motions
from ballmorph_core.drawing.pair_morphs.ends import overhang_morph, settle_ends
from ballmorph_core.drawing.pair_morphs.pipeline import PairMorph
from ballmorph_core.drawing.pair_morphs.registration import FIT_SAMPLES, fit_pairs
from ballmorph_core.geometry.polyline import pair_scales, resample
from ballmorph_core.geometry.projection import nearest_within
from ballmorph_core.geometry.ragged import Ragged
from ballmorph_core.geometry.similarity import Similarity, as_complex


def arc(start, stop, n=90, radius=1.0):
    """An open arc of the circle of ``radius`` about the origin, degrees, shape (n, 2)."""
    t = np.radians(np.linspace(start, stop, n))
    return radius * np.c_[np.cos(t), np.sin(t)]


def batch(*curves):
    return Ragged.from_list(list(curves), [False] * len(curves))


def restarted_oval(scale=1.0, shift=(0.0, 0.0)):
    """An oval head outline drawn open (330 degrees) and redrawn from 100 degrees on, ``scale``
    times larger and moved by ``shift``: ``P, Q`` batches of one curve each."""
    return batch(arc(0, 330, 110) * [1.0, 0.8]), batch(scale * arc(100, 430, 110) * [1.0, 0.8] + shift)


def test_a_longer_stroke_overhangs_and_the_common_parts_share_their_ends():
    P, Q = batch(arc(0, 180)), batch(arc(0, 240))
    ends = settle_ends(P, Q, np.array([2.0]), np.array([True]))
    np.testing.assert_allclose(ends.keep_p[0], [0.0, P.length[0]], atol=1e-12)
    np.testing.assert_allclose(ends.keep_q[0], [0.0, np.pi], atol=2e-3)  # Q past 180 degrees overhangs
    rc, qc = ends.common_p.curve(0), ends.common_q.curve(0)
    np.testing.assert_allclose(rc[[0, -1]], qc[[0, -1]], atol=1e-12)


def test_overhangs_slide_along_their_curves_alone_and_joined():
    # An overhang shrinking into its curve's end and one growing out of another curve: each
    # evaluated on its own, and both joined into one evaluation (as the layout does), agree.
    a, b = arc(0, 180), arc(0, 90, n=40, radius=2.0)
    shrink = overhang_morph(a, 2.0, np.pi, 2.0, np.array([0.1, 0.0]), False, 0.05)
    grow = overhang_morph(b, 0.0, 1.5, 1.5, np.array([0.0, -0.2]), True, 0.05)
    np.testing.assert_allclose(
        shrink(0.0), batch(a).point_at(np.zeros(len(shrink.u_p), int), 2.0 + (np.pi - 2.0) * shrink.u_p), atol=1e-12
    )
    np.testing.assert_allclose(
        shrink(1.0),
        np.broadcast_to(batch(a).point_at(np.array([0]), np.array([2.0])) + [0.1, 0.0], (len(shrink.u_p), 2)),
        atol=1e-12,
    )
    np.testing.assert_allclose(
        grow(0.0),
        np.broadcast_to(batch(b).point_at(np.array([0]), np.array([1.5])) - [0.0, -0.2], (len(grow.u_p), 2)),
        atol=1e-12,
    )
    both = type(shrink.paths).join([(shrink.paths, np.arange(len(shrink.u_p))), (grow.paths, np.arange(len(grow.u_p)))])
    for t in (0.0, 0.3, 1.0):
        np.testing.assert_allclose(both.at(t), np.concatenate([shrink(t), grow(t)]), atol=1e-12)


@pytest.mark.parametrize(("f0", "f1"), [(0.0, 0.13), (0.64, 1.0), (0.32, 0.32 + 1e-10), (0.1, 0.1 + 1 / 89)])
def test_an_overhang_keeps_only_the_stretch_of_its_curve_it_slides_along(f0, f1):
    """The plan keeps an overhang's own stretch of its curve (from the vertex at or before its
    start to the one at or after its end), not the whole curve: the same paths to round-off."""
    from ballmorph_core.drawing.pair_morphs.pipeline import _piece

    curves = batch(arc(0, 90, n=30), arc(0, 180))  # the second curve: 90 vertices, 89 equal edges
    s0, s1 = f0 * curves.length[1], f1 * curves.length[1]
    piece, start = _piece(curves, 1, s0, s1)
    s = curves.s[curves.offsets[1] : curves.offsets[2]]
    first = int(np.flatnonzero(s <= s0)[-1])
    np.testing.assert_array_equal(piece, curves.curve(1)[first : first + len(piece)])
    assert start == s[first] and s[first + len(piece) - 2] < s1 <= s[first + len(piece) - 1] + 1e-12
    assert not np.shares_memory(piece, curves.pts)
    for grow in (False, True):
        whole = overhang_morph(curves.curve(1), s0, s1, s1, np.array([0.1, -0.2]), grow, 0.01)
        kept = overhang_morph(piece, s0 - start, s1 - start, s1 - start, np.array([0.1, -0.2]), grow, 0.01)
        for t in (0.0, 0.4, 1.0):
            np.testing.assert_allclose(kept(t), whole(t), atol=1e-13)


def test_pairs_not_settled_stay_exactly_as_they_are():
    P, Q = batch(arc(0, 180), arc(0, 90)), batch(arc(0, 240), arc(10, 80))
    ends = settle_ends(P, Q, np.array([2.0, 2.0]), np.array([False, True]))
    np.testing.assert_array_equal(ends.common_p.curve(0), P.curve(0))
    np.testing.assert_array_equal(ends.common_q.curve(0), Q.curve(0))
    assert not np.any(ends.gap[0])
    # None settled (a drawing of loops): the same curves, fractions and ranges as one by one.
    none = settle_ends(P, Q, np.array([2.0, 2.0]), np.array([False, False]))
    for c in range(2):
        np.testing.assert_array_equal(none.common_p.curve(c), P.curve(c))
        np.testing.assert_array_equal(none.common_q.curve(c), Q.curve(c))
    np.testing.assert_array_equal(none.u, P.s / P.length[P.owner])
    np.testing.assert_array_equal(none.keep_p, np.c_[np.zeros(2), P.length])
    assert not np.any(none.gap) and not np.any(none.settled)


@pytest.mark.parametrize("stop", [240.0, 120.0])
def test_a_stroke_drawn_longer_or_shorter_stays_on_its_circle(stop):
    """The overhang slides along the circle: every in-between lies on it, and the free end
    moves steadily from one key's end to the other's."""
    P, Q = arc(0, 180), arc(0, stop)
    morph = PairMorph(P, Q, False)
    end_angles = []
    for t in np.linspace(0.0, 1.0, 9):
        frame = morph(t)
        assert np.abs(np.linalg.norm(frame, axis=1) - 1.0).max() < 2e-3
        end_angles.append(np.degrees(np.arctan2(frame[-1, 1], frame[-1, 0])) % 360)
    np.testing.assert_allclose(end_angles, np.linspace(180.0, stop, 9), atol=0.5)


def test_end_gaps_are_undone_exactly_at_both_keys():
    """Strokes whose registered ends stay apart: the displaced common part is undone as 1 - t,
    so the first frame ends where P ends and the last where Q ends."""
    x = np.linspace(0.0, 1.0, 60)
    P = np.c_[x, 0.3 * np.sin(np.pi * x)]
    Q = np.c_[1.1 * x + 0.05, -0.2 * np.sin(np.pi * x) + 0.1 * x]
    morph = PairMorph(P, Q, False)
    np.testing.assert_allclose(morph(0.0)[[0, -1]], P[[0, -1]], atol=1e-9)
    np.testing.assert_allclose(morph(1.0)[[0, -1]], Q[[0, -1]], atol=1e-9)


def test_an_outline_started_elsewhere_registers_as_itself():
    """An open outline whose start moved 100 degrees along it: the end-to-end fit would turn it
    by about 100 degrees; the sliding fit finds that it did not move."""
    P, Q = restarted_oval()
    fits = fit_pairs(P, Q)
    np.testing.assert_allclose(fits.A[0], np.eye(2), atol=5e-3)
    np.testing.assert_allclose(fits.b[0], 0.0, atol=5e-3)


def test_a_straight_line_drawn_longer_is_scaled_not_slid():
    """A line fits end to end exactly (scaled): sliding must not win on a self-similar shape."""
    x = np.linspace(0.0, 1.0, 30)
    P, Q = batch(np.c_[x, 0.0 * x]), batch(np.c_[1.5 * x + 0.2, 0.0 * x])
    fits = fit_pairs(P, Q)
    np.testing.assert_allclose(fits.A[0], 1.5 * np.eye(2), atol=1e-9)


def _full_sliding_fits(monkeypatch):
    """Record the pairs of every full sliding fit (all samples against Q itself, not the
    gate's coarse curve, which it fits with its own overlap rule)."""
    calls = []
    real = sliding._sliding_fits

    def spy(xp, *args, **kwargs):
        if xp.shape[1] == FIT_SAMPLES and "overlap" not in kwargs:
            calls.append(len(xp))
        return real(xp, *args, **kwargs)

    monkeypatch.setattr(sliding, "_sliding_fits", spy)
    return calls


def test_an_outline_started_elsewhere_passes_the_coarse_gate(monkeypatch):
    """The coarse sliding fit lets a pair that needs sliding through to the full fit."""
    calls = _full_sliding_fits(monkeypatch)
    P, Q = restarted_oval()
    fits = fit_pairs(P, Q)
    assert calls == [1]
    np.testing.assert_allclose(fits.A[0], np.eye(2), atol=5e-3)


@pytest.mark.parametrize("bad", [0.0, np.nan])
def test_an_outline_started_elsewhere_in_a_drawing_scaled_twice_slides_at_its_scale(bad):
    """The sliding fit turns and moves P at the drawing's scale before it frees the scale: in
    a drawing scaled 2 times, an outline redrawn from another start registers as twice itself.
    At scale 1 its first iterations would place P at the wrong size, and the end-to-end fit
    (turned by 166 degrees) would stay. A drawing motion of no size counts as scale 1."""
    P, Q = restarted_oval(2.0)
    fits = fit_pairs(P, Q, scale=2.0)
    np.testing.assert_allclose(fits.A[0], 2.0 * np.eye(2), atol=0.01)
    assert fits.residual[0] < 0.01
    unscaled = fit_pairs(P, Q, scale=1.0)
    assert unscaled.residual[0] > 0.1  # the same pair at the wrong scale does not slide
    for name in ("A", "b", "residual"):
        np.testing.assert_array_equal(getattr(fit_pairs(P, Q, scale=bad), name), getattr(unscaled, name))


def test_the_carrier_slides_at_the_scale_of_the_drawing_motion():
    """The carrier of that outline reads the scale from the drawing's motion (the stroke
    matching's): twice the outline in a drawing scaled 2 times, turned by it too."""
    P, Q = restarted_oval(2.0)
    drawing = Similarity(2.0 + 0j)
    assert (drawing.scale, drawing.turn) == (2.0, 0.0)
    assert Similarity(-2j).scale == 2.0 and Similarity(-2j).turn == -np.pi / 2
    scale = pair_scales(P, Q)
    motion, _ = carrier_motions(P, Q, "similarity", scale, drawing)
    np.testing.assert_allclose(motion.A[0], 2.0 * np.eye(2), atol=0.01)
    unscaled, _ = carrier_motions(P, Q, "similarity", scale, Similarity())
    assert np.abs(unscaled.A[0] - 2.0 * np.eye(2)).max() > 0.1


@pytest.mark.parametrize("move", [0.1, 3.0])
@pytest.mark.parametrize("n", [200, 10])
def test_a_wobbly_redraw_is_fitted_end_to_end_without_the_full_sliding_fit(monkeypatch, move, n):
    """A stroke redrawn with a wobble fits loosely end to end and sliding cannot help: the
    coarse fit says so, the full one never runs, and the fit is the one it would have left.
    Moved far (3 lengths), the start from where P lies finds no overlap: that is no fit. Drawn
    with 10 points, the stroke is judged against its own points (every fourth vertex of Q lies
    too far from Q for a gate)."""
    s = np.linspace(0.0, 1.0, n)
    P = np.c_[s, 0.2 * np.sin(np.pi * s)]
    Q = np.c_[1.05 * s + move, 0.2 * np.sin(np.pi * s) + 0.04 * np.sin(3 * np.pi * s + 0.5)]
    with monkeypatch.context() as ungated:
        _ungate(ungated)
        calls = _full_sliding_fits(ungated)
        want = fit_pairs(batch(P), batch(Q))
        assert calls == [1]  # loose: the full fit runs without the gate, and loses
    calls = _full_sliding_fits(monkeypatch)
    fits = fit_pairs(batch(P), batch(Q))
    assert not any(calls)  # the full fit does not run (or runs on no pair)
    for name in ("A", "b", "residual"):
        np.testing.assert_array_equal(getattr(fits, name), getattr(want, name))


def _lying_partly_along(rng, n_pairs, truth=False):
    """Pairs of pieces of one arc, spiral or wandering curve, overlapping by 55-85 % of them,
    the second turned (up to 20 degrees), scaled (up to 10 %), moved and a little noisy; with
    ``truth``, also the scale taking each P onto its Q and the kind of curve (0 arc, 1 spiral,
    2 wandering), shape (n_pairs,) each."""
    pairs, scale, kinds = [], [], []
    for _ in range(n_pairs):
        u = np.linspace(0.0, 1.0, 400)
        kind = rng.integers(3)
        if kind == 0:
            span = rng.uniform(1.0, 5.0)
            base = np.c_[np.cos(span * u), np.sin(span * u)]
        elif kind == 1:
            angle = rng.uniform(4.0, 9.0) * u
            base = (0.3 + u)[:, None] * np.c_[np.cos(angle), np.sin(angle)]
        else:
            steps = np.cumsum(rng.normal(size=(400, 2)), axis=0)
            kernel = np.hanning(41) / np.hanning(41).sum()
            base = np.c_[[np.convolve(c, kernel, mode="same") for c in steps.T]].T[20:-20]
            u = np.linspace(0.0, 1.0, len(base))
        cut = rng.uniform(0.15, 0.45)
        p, q = base[u <= 1.0 - cut * rng.uniform(0.3, 1.0)], base[u >= cut]
        size = np.ptp(base, axis=0).max()
        turn = np.radians(rng.uniform(-20, 20))
        a = rng.uniform(0.9, 1.1) * np.exp(1j * turn)
        z = a * as_complex(q) + size * complex(*rng.uniform(-0.2, 0.2, 2))
        q = np.c_[z.real, z.imag] + 0.002 * size * rng.normal(size=q.shape)
        first = rng.integers(2)
        pairs.append((p, q) if first else (q, p))
        scale.append(abs(a) if first else 1.0 / abs(a))
        kinds.append(kind)
    return (pairs, np.array(scale), np.array(kinds)) if truth else pairs


GATE_MISSES = 0.005  # a fraction of the pairs the coarse gate may fit differently from the full fit
GATE_MISS_RATIO = 1.25  # ... and then its residual at most this many times the full fit's


def _ungate(patch):
    """Every loose pair through to the full sliding fit. (An infinite margin would not do: a
    pair whose coarse fit finds no overlap has an infinite coarse residual, never below it.)"""
    patch.setattr(sliding, "_worth_sliding", lambda xp, *args: np.ones((2, len(xp)), bool))


def _end_to_end(monkeypatch, P, Q):
    """The fits with no sliding fit at all (every pair fitted end to end)."""
    with monkeypatch.context() as no_sliding:
        no_sliding.setattr(sliding, "SLIDE_FROM", np.inf)
        return fit_pairs(P, Q)


def _gated_ungated_end_to_end(monkeypatch, P, Q):
    """The fits with the coarse gate, with the full sliding fit on every loose pair, and with
    no sliding fit at all."""
    gated = fit_pairs(P, Q)
    with monkeypatch.context() as ungated:
        _ungate(ungated)
        want = fit_pairs(P, Q)
    return gated, want, _end_to_end(monkeypatch, P, Q)


@pytest.mark.parametrize(("seed", "count", "few", "least"), [(11, 60, False, 30), (1, 200, True, 85)])
def test_the_coarse_gate_keeps_every_fit_the_full_sliding_fit_makes(monkeypatch, seed, count, few, least):
    """Strokes lying partly along each other (turned, scaled, noisy): the fits with the gate
    are the fits of the full sliding fit run on every loose pair, and about half of them slide
    (34 of 60, 98 of 200).

    Also drawn with 5-40 points (hair, grass, hatching): every fourth vertex of such a stroke
    lies so far from it that the gate would grant back its whole limit, so it fits them
    against the stroke itself (with every fourth vertex, 2 of 1,000 such pairs did not slide:
    a 5- or 7-point Q's coarse curve lay too far from it for any overlap)."""
    rng = np.random.default_rng(seed)
    pairs = _lying_partly_along(rng, count)
    if few:
        pairs = [
            tuple(resample(c, False, count=int(rng.integers(5, 41)), smooth=False) for c in pair) for pair in pairs
        ]
    P, Q = batch(*[p for p, _ in pairs]), batch(*[q for _, q in pairs])
    gated, want, end_to_end = _gated_ungated_end_to_end(monkeypatch, P, Q)
    differ = (
        (gated.A != want.A).any(axis=(1, 2))
        | (gated.b != want.b).reshape(count, -1).any(axis=1)
        | (gated.residual != want.residual)
    )
    # The gate is a heuristic: over 12,000 such pairs its fit differs from the full fit's on 10
    # (sliding.SLIDE_MARGIN's comment), and which ones depends on the BLAS's round-off (seed 1's pair 75 on
    # one machine: residual 1.36 gated, 1.22 full, 6.44 end to end). So: the same fit on all
    # but GATE_MISSES of the pairs, and where it differs, still a slide close to the full fit's.
    assert differ.sum() <= max(1, GATE_MISSES * count), (
        f"{differ.sum()} of {count} fits differ: {np.nonzero(differ)[0]}"
    )
    ratio = gated.residual[differ] / want.residual[differ]
    assert np.all(ratio <= GATE_MISS_RATIO), f"gated residuals {ratio} x the full fit's"
    assert np.all(gated.residual[differ] < end_to_end.residual[differ])
    slid = want.residual < end_to_end.residual
    assert slid.sum() >= least


def test_the_coarse_gate_keeps_a_slide_whose_start_overlaps_by_a_few_samples(monkeypatch):
    """One pair of 4,000 random ones (the 212th of seed 3; 2,785 of them slide): from where P
    lies, fewer than two of the gate's 32 coarse samples find Q's interior within reach, so that
    start cannot move, while the full fit's 128 samples find it and slide (residual 0.0016
    against 0.0105 end to end, accepted). The other start's coarse residual is 2.4 times the
    accepted limit, over the margin of 1.5: judged by its coarse samples alone, the gate rejected
    the pair and it was fitted end to end. A start that blind is judged again with every sample."""
    p, q = _lying_partly_along(np.random.default_rng(3), 212)[-1]
    P, Q = batch(p), batch(q)
    gated, want, end_to_end = _gated_ungated_end_to_end(monkeypatch, P, Q)
    assert want.residual[0] < sliding.SLIDE_GAIN * end_to_end.residual[0]  # the full fit slides
    np.testing.assert_array_equal(gated.residual, want.residual)


def _slid(monkeypatch, P, Q):
    """The fits of pairs ``P``, ``Q`` and which of them slid (fit better than end to end)."""
    fits = fit_pairs(P, Q)
    return fits, fits.residual < _end_to_end(monkeypatch, P, Q).residual


def _slides_off_their_drawn_scale(monkeypatch):
    """Of 300 pieces lying partly along each other (seed 1), drawn at 0.9-1.1 of each other:
    which slid, which of those came out more than 12 % off the drawn scale, and each one's kind
    of curve (0 arc, 1 spiral, 2 wandering), shape (300,) each."""
    pairs, scale, kind = _lying_partly_along(np.random.default_rng(1), 300, truth=True)
    fits, slid = _slid(monkeypatch, batch(*[p for p, _ in pairs]), batch(*[q for _, q in pairs]))
    off = np.abs(np.log(np.sqrt(np.abs(np.linalg.det(fits.A))) / scale)) > 0.12
    return slid, slid & off, kind


def test_a_wandering_stroke_slides_at_the_scale_it_was_drawn_at(monkeypatch):
    """Wandering curves have no stretch that a smaller copy of another fits: their slides keep
    the drawn scale. The free iterations' scale counts only where it fits clearly better than
    the drawing's (``sliding.SLIDE_FREE_GAIN``): 1 of 58 slides is off; kept whenever it fitted
    at all better, 16 of 63 were."""
    slid, off, kind = _slides_off_their_drawn_scale(monkeypatch)
    wandering = kind == 2
    assert (slid & wandering).sum() >= 50
    assert (off & wandering).sum() <= 0.05 * (slid & wandering).sum()


@pytest.mark.xfail(strict=True, reason="a spiral's slides still land on stretches a smaller copy fits")
def test_a_slide_keeps_the_scale_the_strokes_were_drawn_at(monkeypatch):
    """Pieces of one curve lying partly along each other, the second scaled by 0.9-1.1: a slide
    should take one onto the other at about that scale, as drawn. The sliding fit turns and
    moves P at the drawing's scale, then frees the scale for its last iterations and keeps it
    where it fits clearly better (see ``sliding._iterate``): of these 300 pairs 141 slide, 8 of
    them more than 12 % off the drawn scale (no arc, 7 of 42 spirals, 1 of 58 wandering
    curves; of 1,000 pairs, 25 of 527). Keeping every freed scale they were 23 of 154 and 67
    of 566, and with the scale free throughout 114 of 217 and 367 of 716. A spiral's stretch
    further out, scaled, lies close to a stretch further in: the drawn scale is what an animator
    means. A strict xfail until the sliding fit prefers it there too (measured in issue 14's
    notes of 2026-12-05)."""
    slid, off, _ = _slides_off_their_drawn_scale(monkeypatch)
    assert slid.sum() >= 130
    assert off.sum() <= 0.05 * slid.sum()


@pytest.mark.xfail(strict=True, reason="wobbly redraws slide where a shorter overlap fits their wobble better")
def test_no_wobbly_redraw_of_the_benchmark_slides(monkeypatch):
    """The benchmark's open strokes: key B redraws every stroke of key A with a wobble across it
    (up to 6 % of its size), moved, turned and scaled a little, so end to end is the truth.
    Stroke 71 of these 100 slides all the same (400 strokes of 500 points: 13 slide; with the
    sliding fit's scale free throughout, 2 and 18, one end moved by 56 % of its size): fitted on
    60 % of the stroke, a motion follows the wobble far better than on all of it, and the
    acceptance compares the two as they are. A strict xfail until the sliding fit tells a
    redraw from a slide (measured in issue 14's note of 2026-12-05)."""
    key_a, key_b = bench_drawings.make_keys("open", 100, 200)
    _, slid = _slid(monkeypatch, batch(*key_a), batch(*key_b))
    assert not slid.any(), np.flatnonzero(slid)


def test_the_full_sliding_fit_runs_only_from_the_starts_the_gate_lets_through(monkeypatch):
    """An outline started elsewhere and moved three sizes away: from where P lies no sample
    finds Q (the gate judges that start again with every sample, and it still fails), so the
    full fit runs from the end-to-end fit alone, and fits as it does from both starts."""
    runs = []
    real = sliding._fits

    def spy(xp, Q, index, search, starts, size, overlap=sliding.SLIDE_OVERLAP, run=None):
        if xp.shape[1] == FIT_SAMPLES and overlap == sliding.SLIDE_OVERLAP:
            runs.append(run)
        return real(xp, Q, index, search, starts, size, overlap, run)

    P, Q = restarted_oval(shift=(3.0, 0.0))
    with monkeypatch.context() as ungated:
        _ungate(ungated)
        want = fit_pairs(P, Q)
    monkeypatch.setattr(sliding, "_fits", spy)
    fits = fit_pairs(P, Q)
    assert len(runs) == 1 and runs[0].tolist() == [[False], [True]]
    for name in ("A", "b", "residual"):
        np.testing.assert_array_equal(getattr(fits, name), getattr(want, name))
    assert want.residual[0] < 0.05  # it slides


def test_sliding_fits_from_some_starts_are_those_from_every_start():
    """Fitting only some (start, pair) cells fits each as the full batch does, and leaves the
    others at their start, with an infinite residual (no fit), not blind."""
    rng = np.random.default_rng(5)
    pairs = _lying_partly_along(rng, 8)
    Q = batch(*[q for _, q in pairs])
    index = np.arange(8)
    xp = as_complex(np.stack([resample(c, False, count=FIT_SAMPLES, smooth=False) for c, _ in pairs]))
    size = np.array([np.ptp(q, axis=0).max() for _, q in pairs])
    a, b = rng.normal(size=8) * 0.05 + 1 + 0j, np.zeros(8, complex)
    search = sliding.NearestEdges(Q.take(index))
    starts = sliding._starts(xp, a, b, np.ones(8))
    every = sliding._fits(xp, Q, index, search, starts, size)
    run = rng.random((2, 8)) < 0.5
    some = sliding._fits(xp, Q, index, search, starts, size, run=run)
    for full, part in zip(every, some):
        np.testing.assert_allclose(part[run], full[run], rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(some[0][~run], np.stack([s for s, _ in starts])[~run])
    np.testing.assert_array_equal(some[1][~run], np.stack([s for _, s in starts])[~run])
    assert np.isinf(some[2][~run]).all() and not some[3][~run].any()
    assert np.isfinite(every[2]).sum() >= 8  # most cells fit: the comparison means something


def _dense(curve, per_edge=8):
    """Points along a polyline's edges, ``per_edge`` per edge, shape (K, 2)."""
    f = np.arange(per_edge)[:, None, None] / per_edge
    return (curve[:-1] + f * np.diff(curve, axis=0)).reshape(-1, 2)


@given(st.integers(0, 2**32 - 1), st.integers(2, 7), st.sampled_from([np.inf, 0.0, 0.5, 1.5]))
@settings(max_examples=30)
def test_the_gates_coarse_curve_lies_within_its_stated_distance(seed, step, most):
    """Every ``step``-th vertex of a wandering stroke (and its last): each curve lies within
    the returned deviation of the other, and its kept vertices are the original ones; a curve
    that would lie farther than ``most`` keeps every vertex, at 0."""
    rng = np.random.default_rng(seed)
    curves = [np.cumsum(rng.normal(size=(n, 2)), axis=0) for n in rng.integers(2, 40, 3)]
    coarse, deviation = sliding._coarse(Ragged.from_list(curves, [False] * 3), np.array([2, 0]), step, most)
    _, free = sliding._coarse(Ragged.from_list(curves, [False] * 3), np.array([2, 0]), step)
    np.testing.assert_array_equal(deviation, np.where(free > most, 0.0, free))
    for c, original in enumerate([curves[2], curves[0]]):
        mine = coarse.curve(c)
        every = 1 if free[c] > most else step
        np.testing.assert_array_equal(mine, original[np.unique(np.r_[0 : len(original) : every, len(original) - 1])])
        slack = 1e-9 * (1 + np.abs(original).max())
        assert distance_to_polyline(_dense(original), mine, False).max() <= deviation[c] + slack
        assert distance_to_polyline(_dense(mine), original, False).max() <= deviation[c] + slack


def test_the_full_sliding_fit_searches_its_pairs_curves_only_and_fits_each_as_alone(monkeypatch):
    """Two pairs of four Q curves, out of order: the full fit's search holds those two curves
    only, and each pair gets the fit it gets alone (its edges mapped back to Q's)."""
    searched = []
    real = sliding.NearestEdges
    monkeypatch.setattr(sliding, "NearestEdges", lambda curves: searched.append(len(curves)) or real(curves))
    oval = [1.0, 0.8]
    Q = batch(arc(0, 90, 40), arc(100, 430, 110) * oval, arc(-50, 200, 70), arc(30, 380, 120) * 1.3)
    index = np.array([3, 1])
    xp = as_complex(np.stack([arc(0, 330, FIT_SAMPLES) * 1.3, arc(-20, 300, FIT_SAMPLES) * oval]))
    size = np.full(2, 2.0)
    a, b, residual = np.ones(2, complex), np.zeros(2, complex), np.ones(2)
    sliding.slide(xp, Q, index, size, a, b, residual)
    assert searched[-1] == 2 and residual.max() < 1e-2  # both pairs slide

    def start(n):
        return [(np.ones(n, complex), np.zeros(n, complex))]

    both = sliding._sliding_fits(xp, Q, index, real(Q.take(index)), start(2), size)
    for i, c in enumerate(index):
        one = batch(Q.curve(c))
        alone = sliding._sliding_fits(xp[[i]], one, np.array([0]), real(one), start(1), size[[i]])
        np.testing.assert_allclose([x[i] for x in both[:3]], [x[0] for x in alone[:3]], rtol=1e-12, atol=1e-12)
        np.testing.assert_array_equal(both[3][:, i], alone[3][:, 0])


@given(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.integers(2, 500))
@example(0.0, 5e-324, 4)  # a subnormal span: its step underflows (numpy divides, then scales)
def test_overhang_samples_are_numpys_linspace_bit_for_bit(start, stop, count):
    from ballmorph_core.drawing.pair_morphs.ends import _even

    np.testing.assert_array_equal(_even(start, stop, count), np.linspace(start, stop, count))
    np.testing.assert_array_equal(_even(start, start, count), np.linspace(start, start, count))


def _curves(rng, count, closed):
    """Random walks (some of them scribbles with one long edge), as a Ragged."""
    curves = []
    for _ in range(count):
        walk = np.cumsum(rng.normal(size=(int(rng.integers(2, 40)), 2)) * rng.uniform(0.01, 1.0), axis=0)
        if rng.random() < 0.2:
            walk[len(walk) // 2 :] += rng.normal(size=2) * 20.0  # one long edge
        curves.append(walk + rng.normal(size=2) * rng.choice([1.0, 1e4]))
    return Ragged.from_list(curves, closed)


@given(st.integers(0, 2**32 - 1), st.floats(1e-6, 30.0))
@settings(max_examples=60, deadline=None)
def test_ends_searched_along_stretches_are_those_of_the_whole_curves(seed, reach):
    # Each end searches only the stretch of the other curve that may lie within reach: the same
    # distance, edge and fraction as a search of the whole curve, bit for bit.
    rng = np.random.default_rng(seed)
    count = int(rng.integers(1, 12))
    closed = rng.random(count) < 0.3
    A, B = _curves(rng, count, closed), _curves(rng, count, closed)
    if rng.random() < 0.5:  # ends on the other curve's vertices and edges: ties and zero distances
        B.pts[B.offsets[:-1]] = A.pts[A.offsets[:-1]]
        B = Ragged(B.pts, B.offsets, B.closed)
    # Last ends next to the middle of the other curve's last edge (a loop's closing edge).
    last = B.offsets[1:] - 1
    closing = np.where(B.closed, B.offsets[:-1], last - 1)
    A.pts[A.offsets[1:] - 1] = 0.5 * (B.pts[last] + B.pts[closing]) + rng.normal(size=(count, 2)) * 1e-3
    A = Ragged(A.pts, A.offsets, A.closed)
    rows = np.flatnonzero(rng.random(count) < 0.8)
    reaches = np.full(count, reach) * rng.uniform(0.1, 10.0, count)
    found, dist = ends._ends_onto(A, B, reaches, rows)
    points = np.take(A.pts, np.r_[A.offsets[rows], A.offsets[rows + 1] - 1], axis=0)
    d, e, f = nearest_within(points, np.r_[rows, rows], B, np.r_[reaches[rows], reaches[rows]])
    assert np.array_equal(dist.ravel(), d)
    assert np.array_equal(found.ravel(), B.s[e] + f * B.length_of_edge[e])
