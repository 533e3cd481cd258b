"""Arcs through keys (ballmorph_core/drawing/arcs.py): intervals joined C1 at inner keys."""

import numpy as np
import pytest
from golden_cases import cases

import ballmorph_core as bm
from ballmorph_core.drawing.frames.arcs import (
    DERIVATIVE_STEP,
    IntervalEnds,
    hermite_bumps,
    interval_ends,
    key_places,
    key_velocities,
    smooth_chain,
)

S = np.linspace(0.0, 1.0, 11)


def test_hermite_bumps_vanish_at_both_keys_with_unit_slopes():
    h = hermite_bumps([0.0, 1.0])
    assert np.array_equal(h, np.zeros((2, 2))), h  # exactly: the keys stay the keys
    e = 1e-6
    slopes = (hermite_bumps([e, 1.0]) - hermite_bumps([0.0, 1.0 - e])) / e  # forward at 0, backward at 1
    assert np.allclose(slopes, [[1.0, 0.0], [0.0, 1.0]], atol=1e-5), slopes


def _chord(p0, p1, frames):
    """IntervalEnds of one straight path from p0 to p1 (each (K, 3))."""
    return IntervalEnds(p0, p1, p1 - p0, p1 - p0, float(frames))


def _corrected(ends, correction, s):
    """The chord paths of ``ends`` plus the correction, at times s: (T, K, 3)."""
    straight = ends.start + s[:, None, None] * (ends.end - ends.start)
    return straight + (0.0 if correction is None else correction.offsets(s))


@pytest.mark.parametrize("frames", [(6, 6), (4, 8), (10, 3)])
def test_three_keys_on_a_parabola_in_time_are_joined_on_it_exactly(frames):
    # Two samples on quadratic paths (a thrown ball's centre and a point beside it), keyed at
    # frames 0, f0, f0 + f1: straight chords become the parabola, whatever the spacing.
    f0, f1 = frames

    def at(frame):
        return np.array([[0.5 * frame, 0.0, 2.0 - 0.03 * (frame - 5) ** 2], [0.5 * frame + 1, 0.0, 1.0]])

    ends = [_chord(at(0), at(f0), f0), _chord(at(f0), at(f0 + f1), f1)]
    corrections = smooth_chain(ends, [True])
    worst = 0.0
    for e, c, start, length in zip(ends, corrections, (0, f0), frames):
        got = _corrected(e, c, S)
        want = np.stack([at(start + s * length) for s in S])
        worst = max(worst, float(np.abs(got - want).max()))
    assert worst < 1e-12, f"frames {frames}: {worst:.3g} off the parabola"


def test_a_corner_or_a_lone_interval_is_left_as_it_is():
    p = [np.array([[x, 0.0, x * x]]) for x in (-1.0, 0.0, 1.0)]
    ends = [_chord(p[0], p[1], 6), _chord(p[1], p[2], 6)]
    assert smooth_chain(ends, [False]) == [None, None]
    assert smooth_chain(ends[:1], []) == [None]
    assert smooth_chain([ends[0], None], [True]) == [None, None]  # the neighbour cannot be corrected
    with pytest.raises(ValueError, match="inner keys"):
        smooth_chain(ends, [])


def test_samples_are_matched_across_a_key_by_their_nearest():
    # The next interval samples the key more densely and in another order; a translation
    # carried by the nearest sample is exact.
    key = np.c_[np.linspace(0, 1, 5), np.zeros(5), np.zeros(5)]
    dense = np.c_[np.linspace(1, 0, 9), np.zeros(9), np.zeros(9)]
    up, right = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
    arriving = _chord(key - 6 * up, key, 6)
    leaving = _chord(dense, dense + 6 * right, 6)
    at_end, at_start = key_velocities(arriving, leaving)
    want = 0.5 * (up + right)
    assert np.allclose(at_end, want, atol=1e-15) and np.allclose(at_start, want, atol=1e-15), (at_end, at_start)


def _arc_keys(degrees=(110.0, 90.0, 70.0), radius=5.0):
    """A ball (a ring of radius 0.2) keyed on a circular arc: keys and centres (x, z)."""
    t = np.linspace(0.0, 2.0 * np.pi, 24, endpoint=False)
    ring = 0.2 * np.c_[np.cos(t), np.sin(t)]
    angles = np.radians(degrees)
    centres = radius * np.c_[np.cos(angles), np.sin(angles)]
    return [bm.StrokeSet.from_strokes([ring + c], cyclic=[True]) for c in centres], centres


def _centres(plans, corrections, steps=6):
    """The ball's centre (x, z) on every frame of both intervals (6 frames each), keys included."""
    s = np.arange(steps) / steps
    out = [f.positions.mean(axis=0) for p, c in zip(plans, corrections) for f in p.evaluate(s, c).frames]
    out.append(plans[-1].evaluate([1.0]).frames[0].positions.mean(axis=0))
    return np.array(out)[:, [0, 2]]


def _turn(a, b):
    return float(np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1, 1))))


def test_a_ball_keyed_on_an_arc_runs_on_it_through_the_middle_key():
    keys, centres = _arc_keys()
    plans = [bm.plan_inbetween(keys[0], keys[1]), bm.plan_inbetween(keys[1], keys[2])]
    size = float(np.ptp(centres, axis=0).max())
    figures = {}
    for motion in ("per-interval", "smooth"):
        corrections = bm.chain_corrections(plans, [6, 6], [True], motion)
        c = _centres(plans, corrections)
        off = float(np.abs(np.linalg.norm(c, axis=1) - 5.0).max()) / size
        before, after = c[6] - c[5], c[7] - c[6]
        ratio = float(np.linalg.norm(after) / np.linalg.norm(before))
        figures[motion] = (off, ratio, _turn(before, after))
    off, ratio, turn = figures["smooth"]
    message = f"(off the arc, step ratio, turn at the key) {figures}"
    # On the circle itself each frame turns 40/12 = 3.33 degrees.
    assert off < 0.002 and abs(ratio - 1) < 0.01 and turn < 3.5, message
    assert figures["per-interval"][0] > 0.02 and figures["per-interval"][2] > 19, message


def test_per_interval_and_the_keys_are_bit_for_bit_unchanged():
    keys, _ = _arc_keys()
    plans = [bm.plan_inbetween(keys[0], keys[1]), bm.plan_inbetween(keys[1], keys[2])]
    assert bm.chain_corrections(plans, [6, 6], [True], "PER_INTERVAL") == [None, None]
    corrections = bm.chain_corrections(plans, [6, 6], [True])
    assert all(c is not None for c in corrections)
    for plan, correction in zip(plans, corrections):
        plain = plan.evaluate([0.0, 1.0]).frames
        moved = plan.evaluate([0.0, 1.0], correction).frames
        for a, b in zip(plain, moved):
            assert np.array_equal(a.positions, b.positions), np.abs(a.positions - b.positions).max()


def test_interval_ends_measure_derivatives_and_refuse_non_finite_paths():
    def samples(times):
        s = np.asarray(times)[:, None, None]
        return np.concatenate([s * s, np.sin(s), s], axis=2)  # one sample, (T, 1, 3)

    ends = interval_ends(samples, 4)
    assert np.allclose(ends.d_start, [[[0.0, 1.0, 1.0]]], atol=DERIVATIVE_STEP**2), ends.d_start
    assert np.allclose(ends.d_end, [[[2.0, np.cos(1.0), 1.0]]], atol=DERIVATIVE_STEP**2), ends.d_end
    assert interval_ends(lambda times: samples(times) + np.nan, 4) is None


def test_bad_options_are_refused_by_name():
    keys, _ = _arc_keys()
    plans = [bm.plan_inbetween(keys[0], keys[1])] * 2
    with pytest.raises(bm.InvalidCurveError, match="key_motion='curvy'"):
        bm.chain_corrections(plans, [6, 6], [True], "curvy")
    with pytest.raises(bm.InvalidCurveError, match="lengths"):
        bm.chain_corrections(plans, [6, 0], [True])


def _hook():
    """An open stroke with no symmetry (a hook), shape (30, 2)."""
    x = np.linspace(0.0, 1.0, 30)
    return np.c_[x, 0.4 * x**3 - 0.1 * np.sin(4.0 * x)]


def _similar(z, w):
    """Residual of the best complex fit ``w ~ a z + b`` (both (K,) complex), relative to w's size."""
    zc, wc = z - z.mean(), w - w.mean()
    a = np.vdot(zc, wc) / np.vdot(zc, zc)
    return float(np.abs(wc - a * zc).max() / np.ptp(np.abs(wc)))


def test_a_turning_growing_stroke_keeps_its_shape_and_turns_and_grows_smoothly_through_the_key():
    # Turn 0, 10, 30 degrees, scale 1, 1.2, 1.5, moving on an arc: per interval the turn per
    # frame jumps from 1.7 to 3.3 degrees at the middle key; smooth it does not.
    poses = [(0.0, 1.0, (0.0, 0.0)), (10.0, 1.2, (1.5, 0.6)), (30.0, 1.5, (3.0, 0.3))]
    keys = []
    for degrees, scale, (x, y) in poses:
        w = scale * np.exp(1j * np.radians(degrees)) * (_hook() @ [1, 1j]) + complex(x, y)
        keys.append(bm.StrokeSet.from_strokes([np.c_[w.real, w.imag]]))
    plans = [bm.plan_inbetween(keys[0], keys[1]), bm.plan_inbetween(keys[1], keys[2])]
    s = np.arange(7) / 6
    figures = {}
    for motion in ("per-interval", "smooth"):
        corrections = bm.chain_corrections(plans, [6, 6], [True], motion)
        turns, sizes, worst = [], [], 0.0
        for k, (plan, correction) in enumerate(zip(plans, corrections)):
            frames = [f.positions[:, [0, 2]] @ [1, 1j] for f in plan.evaluate(s, correction).frames]
            worst = max(worst, max(_similar(frames[0], f) for f in frames))
            chords = [f[-1] - f[0] for f in frames]  # an open stroke's ends stay its ends
            turns += list(np.degrees(np.angle(chords)))[: 7 if k else 6]
            sizes += list(np.abs(chords))[: 7 if k else 6]
        turn_steps, growth = np.diff(turns), np.diff(np.log(sizes))
        figures[motion] = (worst, turn_steps[5], turn_steps[6], growth[5], growth[6])
    message = "(shape residual, turn before/after the key, log growth before/after) " + str(figures)
    worst, turn_in, turn_out, grow_in, grow_out = figures["smooth"]
    assert worst < 0.01, message
    # Frame steps, not derivatives: the turn speeds up over the chain (1.7 to 3.3 degrees a
    # frame on average), so even smooth consecutive steps differ by about 10%.
    assert abs(turn_out - turn_in) < 0.15 * abs(turn_in) and abs(grow_out - grow_in) < 0.15 * abs(grow_in), message
    _, turn_in, turn_out, _, _ = figures["per-interval"]
    assert turn_out > 1.8 * turn_in, message


def test_samples_are_matched_along_their_key_stroke():
    # Two strokes lying on each other at the key, one going up, one going right afterwards, the
    # second sampled three times as densely, in the other order: each sample takes the motion
    # of its own stroke at its own place (not its nearest neighbour's on the other stroke).
    u, dense = np.linspace(0, 1, 6), np.linspace(0, 1, 16)
    key = np.c_[u, np.zeros(6), np.zeros(6)]
    both = np.concatenate([key, key + 1e-9])
    places = key_places(np.repeat([0, 1], 6), np.tile(u, 2))
    up, right = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
    # (By position, stroke 0's samples would take stroke 1's: they lie exactly there.)
    later = np.concatenate([np.c_[dense, np.zeros((16, 2))], np.c_[dense, np.zeros((16, 2))] + 1e-6])
    motion = np.repeat([right, up], 16, axis=0)  # stroke 1 (listed first) goes right
    later_places = key_places(np.repeat([1, 0], 16), np.tile(dense, 2))
    arriving = IntervalEnds(both - 6 * up, both, 0 * both + 6 * up, 0 * both + 6 * up, 6.0, places, places)
    leaving = IntervalEnds(later, later + 6 * motion, 6 * motion, 6 * motion, 6.0, later_places, later_places)
    at_end, at_start = key_velocities(arriving, leaving)
    assert np.allclose(at_end, np.repeat([up, 0.5 * (up + right)], 6, axis=0), atol=1e-9), at_end
    assert np.allclose(at_start, np.repeat([0.5 * (up + right), up], 16, axis=0), atol=1e-9), at_start
    no_strokes = IntervalEnds(both, both, 0 * both, 0 * both, 6.0)
    assert smooth_chain([no_strokes, IntervalEnds(*(np.zeros((0, 3)),) * 4, 6.0)], [True]) == [None, None]


def test_a_sample_whose_stroke_has_no_partner_across_the_key_keeps_its_own_velocity_there():
    key = np.c_[np.linspace(0, 1, 5), np.zeros(5), np.zeros(5)]
    up, right = np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])
    arriving = IntervalEnds(
        key - 6 * up, key, 6 * up + 0 * key, 2 * up + 0 * key, 6.0, None, key_places(np.zeros(5), key[:, 0])
    )
    leaving = IntervalEnds(key, key + 6 * right, 0 * key, 0 * key, 6.0, key_places(np.full(5, 3), key[:, 0]), None)
    at_end, at_start = key_velocities(arriving, leaving)
    assert np.allclose(at_end, up / 3.0, atol=1e-15) and np.allclose(at_start, 0.0), (at_end, at_start)


def test_a_plan_says_which_key_stroke_each_sample_leaves_and_reaches():
    t = np.linspace(0.0, 2.0 * np.pi, 30, endpoint=False)
    ring, line = np.c_[np.cos(t), np.sin(t)], np.c_[np.linspace(2, 4, 20), np.zeros(20)]
    key_a = bm.StrokeSet.from_strokes([ring, line], cyclic=[True, False])
    key_b = bm.StrokeSet.from_strokes([line + 0.5, 1.2 * ring], cyclic=[False, True])  # swapped order
    plan = bm.plan_inbetween(key_a, key_b)
    stroke_a, u_a, stroke_b, u_b = plan.sample_sources()
    k = plan.samples([0.0]).shape[1]
    assert stroke_a.shape == u_a.shape == stroke_b.shape == u_b.shape == (k,)
    assert np.array_equal(stroke_b, 1 - stroke_a), (stroke_a, stroke_b)  # the ring is stroke 1 of B
    assert sorted(set(stroke_a.tolist())) == [0, 1]
    line = stroke_a == 1  # the line moved by (0.5, 0.5): the same fraction along both keys
    assert np.allclose(u_a[line], u_b[line], atol=1e-9) and np.allclose([u_a[line].min(), u_a[line].max()], [0, 1])


def test_a_bouncing_ball_runs_on_one_parabola_per_bounce_with_its_contacts_as_corners():
    # Contacts on frames 0, 12, 24 (typed Extreme: corners), apexes on 6 and 18: each bounce
    # through contact, apex, contact is the parabola a thrown ball follows, exactly.
    t = np.linspace(0.0, 2.0 * np.pi, 24, endpoint=False)
    ring = 0.2 * np.c_[np.cos(t), np.sin(t)]

    def centre(frame):
        return np.array([0.25 * frame, 2.0 * (1.0 - ((frame % 12) - 6.0) ** 2 / 36.0)])

    keys = [bm.StrokeSet.from_strokes([ring + centre(f)], cyclic=[True]) for f in (0, 6, 12, 18, 24)]
    plans = [bm.plan_inbetween(a, b) for a, b in zip(keys[:-1], keys[1:])]
    corrections = bm.chain_corrections(plans, [6] * 4, [True, False, True])
    s = np.arange(7) / 6
    frames = [f for p, c in zip(plans, corrections) for f in p.evaluate(s, c).frames]
    got = np.array([f.positions.mean(axis=0)[[0, 2]] for f in frames])
    want = np.array([centre(6 * (k + x)) for k in range(4) for x in s])
    off = float(np.abs(got - want).max())
    assert off < 1e-9, f"{off:.3g} off the bounces' parabolas"


#: The golden drawings, the mixed one once (its other cases only change the morph).
GOLDEN = [c for c in cases() if not c[0].startswith("mixed-") or c[0] == "mixed-circular-ball"]


@pytest.mark.parametrize("case", GOLDEN, ids=lambda c: c[0])
def test_there_and_back_through_the_golden_drawings_keeps_every_guarantee(case):
    # key_a -> key_b -> key_a: pieces, hints, strokes without a partner, loops, non-planar keys.
    name, key_a, key_b, options = case
    plans = [bm.plan_inbetween(key_a, key_b, **options), bm.plan_inbetween(key_b, key_a, **options)]
    corrections = bm.chain_corrections(plans, [4, 4], [True])
    times = np.array([0.0, 0.25, 0.5, 0.75, 1.0])
    size = float(np.ptp(np.concatenate([key_a.positions, key_b.positions]), axis=0).max())
    for plan, correction in zip(plans, corrections):
        plain, moved = plan.evaluate(times).frames, plan.evaluate(times, correction).frames
        for t, a, b in zip(times, plain, moved):
            assert np.array_equal(a.offsets, b.offsets), f"{name} t={t}: strokes changed"
            assert np.isfinite(b.positions).all(), f"{name} t={t}: not finite"
            moved_by = float(np.abs(a.positions - b.positions).max(initial=0.0))
            if t in (0.0, 1.0):
                assert moved_by == 0.0, f"{name}: the key at t={t} moved by {moved_by:.3g}"
            assert moved_by <= size, f"{name} t={t}: moved {moved_by:.3g}, drawing size {size:.3g}"
