"""The composite ball-morph built for many chains at once (morphs/composite.build_composites),
the stage ball-morphs and dense maps it batches (morphs/ball.ball_morphs,
ballmap/correspondence.dense_map_batch), and the fallback step that hands it every failing chain
of a plan (drawing/fallbacks.chain_fallbacks).

A batch gives each pair what it gets alone: the same errors, word for word, and the same
morphs up to the round-off of the batch's layout (its curves' arc lengths are one running sum).
"""

import bench_drawings
import numpy as np
import pytest
from shapes import circle

import ballmorph_core as bm
from ballmorph_core.ballmap import candidates
from ballmorph_core.ballmap.correspondence import dense_map_batch, dense_maps
from ballmorph_core.ballmap.topology import orient_pair
from ballmorph_core.drawing.pair_morphs import fallbacks, pipeline
from ballmorph_core.drawing.strokes import StrokeSet
from ballmorph_core.errors import BallMorphError, IncompatibleCurvesError, InvalidCurveError
from ballmorph_core.morphs import blending, composite
from ballmorph_core.morphs.ball import ball_morphs
from ballmorph_core.morphs.composite import build_composite, build_composites

#: Morphs of one pair built in a batch and alone agree to this (their arc lengths are summed
#: along the batch, not along the pair alone).
ROUNDOFF = 1e-12
TIMES = (0.0, 0.3, 0.5, 1.0)


def _notched(depth=0.6, at=0.3, n=300):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    notch = 1.0 - depth * np.maximum(0, 1 - np.abs(np.angle(np.exp(1j * (t - at)))) / 0.12)
    return np.c_[notch * np.cos(t), notch * np.sin(t)]


def _pear(n=300):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1.6 + 0.25 * np.cos(t - np.pi / 2) + 0.1 * np.cos(2 * t)
    return np.c_[0.9 * r * np.cos(t), 1.2 * r * np.sin(t)]


def _arch(height, n=60):
    x = np.linspace(0.0, 1.0, n)
    return np.c_[x, height * np.sin(np.pi * x)]


def _alone_or_error(build):
    try:
        return build()
    except BallMorphError as exc:
        return exc


def _assert_same(batched, alone):
    """The same error (type and words), or morphs whose frames agree to round-off."""
    if isinstance(alone, BallMorphError):
        assert type(batched) is type(alone) and str(batched) == str(alone)
        return
    assert not isinstance(batched, BallMorphError), batched
    assert len(batched) == len(alone)
    np.testing.assert_allclose(batched.frames(TIMES), alone.frames(TIMES), atol=ROUNDOFF, rtol=0)
    np.testing.assert_allclose(batched.u_p, alone.u_p, atol=ROUNDOFF, rtol=0)
    np.testing.assert_allclose(batched.u_q, alone.u_q, atol=ROUNDOFF, rtol=0)


def test_ball_morphs_give_each_pair_its_own_morph_or_error():
    wavy = _arch(0.3) + np.c_[np.zeros(60), 0.05 * np.sin(9 * np.pi * np.linspace(0, 1, 60))]
    pairs = [
        (_arch(0.2), _arch(0.5), False, None),  # compatible strokes sharing both ends
        (circle(1.0, 80), circle(2.0, 90), True, 0.05),  # nested loops
        (_arch(0.2), _arch(0.5) + [0.0, 0.1], False, None),  # no shared endpoints
        (_notched(), _pear(), True, None),  # not b-compatible
        (_arch(0.2), wavy, False, None),  # the wavy one crosses the arch: another configuration
        (np.full((5, 2), np.nan), _arch(0.5, 5), False, None),  # malformed
    ]
    for check in (True, False):
        batched = ball_morphs(pairs, "parabolic", check=check)
        for (P, Q, closed, h), got in zip(pairs, batched):
            want = _alone_or_error(
                lambda P=P, Q=Q, closed=closed, h=h, check=check: bm.make_morph(
                    P, Q, "parabolic-ball", closed, h, check=check
                )
            )
            _assert_same(got, want)
    kinds = [type(m) for m in ball_morphs(pairs, "circular")]
    assert kinds[2:] == [IncompatibleCurvesError, IncompatibleCurvesError, IncompatibleCurvesError, InvalidCurveError]
    assert ball_morphs([], "circular") == []


def test_dense_map_batch_gives_each_pair_its_maps_alone():
    curves = [(_notched(), _pear(), True), (_arch(0.2), _arch(0.5), False), (_notched(0.5, 2.0), 1.5 * circle(), True)]
    setups = [orient_pair(P, Q, closed) for P, Q, closed in curves]
    batch = dense_map_batch(setups, [0.02, 0.01, 0.03])
    for setup, h, got in zip(setups, [0.02, 0.01, 0.03], batch):
        want = dense_maps(setup.P, setup.Q, setup.closed, h, setup)
        assert got.setup is setup and got.spacing == want.spacing and got.eps == want.eps
        assert got.report.describe() == want.report.describe()
        for side in ("side_p", "side_q"):
            np.testing.assert_allclose(getattr(got, side).pts, getattr(want, side).pts, atol=ROUNDOFF, rtol=0)
        for name in ("fwd", "bwd"):
            mine, theirs = getattr(got, name), getattr(want, name)
            np.testing.assert_array_equal(mine.bad, theirs.bad)
            np.testing.assert_array_equal(mine.chain, theirs.chain)  # its own chain 0, as alone
            np.testing.assert_allclose(mine.r, theirs.r, atol=ROUNDOFF, rtol=0)
            # Where a disk touches a nearly straight stretch is ill-conditioned (its radius is
            # not): round-off may slide a contact by a little.
            np.testing.assert_allclose(mine.s_dst, theirs.s_dst, atol=1e-6, rtol=0)
    assert sum(bool(m.report.violations) for m in batch) == 2  # the notched pairs fail
    assert dense_map_batch([], []) == []


def test_composites_built_together_are_those_built_alone():
    pairs = [
        (_notched(), _pear(), True, None, "symmetric"),  # a notch bridged by one disk
        (circle(1.0, 100), 2 * circle(1.0, 100), True, None, "symmetric"),  # compatible: the ball-morph
        (_notched(0.5, 2.0), 1.5 * circle(1.0, 300), True, 0.03, "symmetric"),  # another notch, own spacing
        (_arch(0.2), _arch(0.5) + [0.0, 0.1], False, None, "symmetric"),  # no shared endpoints
        (circle(1.0, 100), circle(1.0, 100) + [3.0, 0.0], True, None, "symmetric"),  # loops side by side
    ]
    batched = build_composites(pairs, "circular")
    for (P, Q, closed, h, sampling), got in zip(pairs, batched):
        want = _alone_or_error(lambda P=P, Q=Q, c=closed, h=h, s=sampling: build_composite(P, Q, c, h, s))
        _assert_same(got, want)
    assert len(batched[0].stages["bridges_p"]) == 1 and not isinstance(batched[2], BallMorphError)
    assert [isinstance(m, IncompatibleCurvesError) for m in batched[3:]] == [True, True]


def test_one_batch_builds_every_stage_ball_morph_of_a_side(monkeypatch):
    """Two notched pairs: their dense maps in one batch, each side's extension stages in one
    batch, their central morphs in one: four ball-morph batches in all, not one per stage."""
    calls = []
    real = composite.ball_morphs
    monkeypatch.setattr(
        composite, "ball_morphs", lambda pairs, *a, **k: calls.append(len(pairs)) or real(pairs, *a, **k)
    )
    maps = []
    real_dense = composite.dense_map_batch
    monkeypatch.setattr(composite, "dense_map_batch", lambda s, h: maps.append(len(s)) or real_dense(s, h))
    pairs = [
        (_notched(), _pear(), True, None, "symmetric"),
        (_notched(0.5, 2.0), 1.5 * circle(1.0, 300), True, None, "symmetric"),
    ]
    assert not any(isinstance(m, BallMorphError) for m in build_composites(pairs, "circular"))
    assert maps == [2]
    assert len(calls) == 3 and calls[-1] == 2  # P's stages, Q's stages (none here), both centrals


def _jagged(n, seed, points=60):
    """The benchmark's jagged redraws (tests/fixtures/bench_drawings.py): wavy strokes redrawn with a
    tremor that crosses the first drawing again and again, as two StrokeSets on the XZ canvas."""
    keys = bench_drawings.make_keys("jagged", n, points, seed)
    return tuple(StrokeSet.from_strokes([np.c_[s[:, 0], np.zeros(len(s)), s[:, 1]] for s in key]) for key in keys)


def test_the_fallback_step_builds_every_failing_chain_together_as_it_would_alone(monkeypatch):
    """A plan hands all its failing chains (of every pair) to one chain_fallbacks call, and each
    chain gets what it gets alone: the same note and morph."""
    seen = []
    real = fallbacks.chain_fallbacks

    def spy(chains, kind):
        seen.append(chains)
        return real(chains, kind)

    monkeypatch.setattr(pipeline, "chain_fallbacks", spy)
    key_a, key_b = _jagged(6, seed=0)
    plan = bm.plan_inbetween(key_a, key_b)
    assert len(seen) == 1 and len(seen[0]) >= 4, "expected several failing chains in one call"
    outcomes = real(seen[0], "circular")
    composites = [m for m, note in outcomes if "composite ball-morph used" in note]
    assert composites and len(composites) < len(outcomes)  # some chains followed, some aligned
    for chain, (morph, note) in zip(seen[0], outcomes):
        alone_morph, alone_note = fallbacks.chain_fallbacks([chain], "circular")[0]
        assert note == alone_note
        _assert_same(morph, alone_morph)
    assert len(plan.evaluate([0.5]).frames[0]) == 6


@pytest.mark.parametrize("bad", [np.zeros((0, 2)), np.full((4, 2), np.inf)])
def test_a_malformed_chain_falls_back_alone(bad):
    """A chain whose curve cannot be read gets its own error; the batch's other chain still
    gets its composite ball-morph."""
    good = (_notched(), _pear(), True, None)
    out = fallbacks.composite_morphs([(bad, _pear(), True, None), good], "circular")
    assert isinstance(out[0], InvalidCurveError)
    assert not isinstance(out[1], BallMorphError) and out[1].method == "composite-ball"


def _notched_maps():
    """Dense maps of two notched circles against a pear and a circle, and of one with two notches."""
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    bump = lambda at: np.maximum(0, 1 - np.abs(np.angle(np.exp(1j * (t - at)))) / 0.12)  # noqa: E731
    two = (1.0 - 0.6 * bump(0.3) - 0.5 * bump(2.5))[:, None] * np.c_[np.cos(t), np.sin(t)]
    curves = [(_notched(), _pear()), (_notched(0.5, 2.0), 1.5 * circle(1.0, 300)), (two, _pear())]
    setups = [orient_pair(P, Q, True) for P, Q in curves]
    return [dense_maps(s.P, s.Q, True, 0.01, s) for s in setups]


def test_bridges_of_many_pairs_are_each_pairs_bridges_alone():
    maps = _notched_maps()
    together = blending.bridges_of(maps + maps[:1], "P")
    for one, got in zip(maps + maps[:1], together):
        alone = blending.bridges(one, "P")
        assert len(got) == len(alone) >= 1
        for a, b in zip(got, alone):
            assert (a.s0, a.s1) == (b.s0, b.s1)
            np.testing.assert_array_equal(a.arc, b.arc)
    assert sum(len(b) for b in together) > len(together)  # some pair has several stretches


def test_a_pair_gets_its_first_failing_stretchs_error(monkeypatch):
    """Stretches fail before their disk (no sample past them) or after it (no disk bridges
    them): a pair gets the error of the first failing one along the curve, whichever kind, and
    the other pairs their bridges."""
    maps = _notched_maps()
    several = next(k for k, m in enumerate(maps) if len(blending.bridges(m, "P")) > 1)
    real_stretch, real_bridge = blending._stretch, blending._bridge
    seen = {}

    def stretch(m, side, first, last):
        k = seen.setdefault(id(m), [0])
        k[0] += 1
        if m is maps[several] and k[0] == 2:
            raise IncompatibleCurvesError("second stretch: no sample past it")
        return real_stretch(m, side, first, last)

    monkeypatch.setattr(blending, "_stretch", stretch)
    got = blending.bridges_of(maps, "P")
    assert str(got[several]) == "second stretch: no sample past it"
    assert all(isinstance(g, list) for k, g in enumerate(got) if k != several)

    def bridge(st, side, *disk):
        if st.maps is maps[several]:
            raise IncompatibleCurvesError(f"no disk at {st.s_a:.6f}")
        return real_bridge(st, side, *disk)

    seen.clear()
    monkeypatch.setattr(blending, "_bridge", bridge)
    got = blending.bridges_of(maps, "P")
    first = real_stretch(maps[several], "P", *blending._stretches(maps[several].fwd.bad, True)[0])
    assert str(got[several]) == f"no disk at {first.s_a:.6f}"  # the first stretch's, before the second's


def test_disk_between_with_a_tolerance_per_row_bisects_each_row_as_alone():
    rng = np.random.default_rng(2)
    t = np.linspace(0, np.pi, 40)
    curve = np.c_[np.cos(t), 0.3 + np.sin(t) + 0.02 * rng.normal(size=40)]
    a, b = curve[:-1], curve[1:]
    d = b - a
    N = np.c_[d[:, 1], -d[:, 0]] / np.hypot(*d.T)[:, None]
    x0 = np.c_[rng.uniform(-0.5, 0.0, 3), np.zeros(3)]
    x1 = x0 + [0.4, 0.0]
    up = np.tile([0.0, 1.0], (3, 1))
    windows = ([np.arange(2, 12), np.arange(5, 15), np.arange(0, 10)], [np.arange(25, 35)] * 3)
    eps = np.array([1e-9, 1e-3, 1e-1])
    together = candidates.disk_between((x0, up, x1, up), (a, b, N), windows, eps)
    for row in range(3):
        one = candidates.disk_between(
            (x0[[row]], up[[row]], x1[[row]], up[[row]]), (a, b, N), ([windows[0][row]], [windows[1][row]]), eps[row]
        )
        for mine, alone in zip(together, one):
            np.testing.assert_array_equal(mine[row], alone[0])


class _Frames:
    """A stand-in composite ball-morph with given in-betweens (T, K, 2)."""

    def __init__(self, frames):
        self.given = np.asarray(frames)

    def frames(self, ts):
        return self.given[: len(ts)]


def test_chains_are_checked_together_each_as_alone(monkeypatch):
    """Composites that stray out of their chains' box, loop where neither chain does, fail, or
    are fine, checked in one batch: each chain's note is the one it gets alone."""
    x = np.linspace(0.0, 1.0, 20)
    P, Q = np.c_[x, np.zeros(20)], np.c_[x, np.full(20, 0.5)]
    middle = 0.5 * (P + Q)
    looped = middle.copy()
    looped[[5, 12]] = looped[[12, 5]] + [0.0, 0.1]
    stands = {
        0: _Frames([P + [0.0, -1.0]] * 5),  # far outside
        1: _Frames([looped] + [middle] * 4),  # crosses itself at t = 1/8
        2: _Frames([middle] * 5),  # followed
        3: IncompatibleCurvesError("composite ball-morph: no disk bridges P near s=0.5"),
    }
    chains = [fallbacks.FailingChain(P, Q, False, 0.05, f"lens {k + 1}/4", "why") for k in range(4)]

    monkeypatch.setattr(fallbacks, "composite_morphs", lambda pairs, kind: [stands[k] for k in range(len(pairs))])
    together = [note for _, note in fallbacks.chain_fallbacks(chains, "circular")]
    alone = []
    for k, chain in enumerate(chains):
        monkeypatch.setattr(fallbacks, "composite_morphs", lambda pairs, kind, k=k: [stands[k]])
        alone.append(fallbacks.chain_fallbacks([chain], "circular")[0][1])
    assert together == alone
    assert "leave the chains' box" in alone[0] and "cross themselves" in alone[1]
    assert "composite ball-morph used" in alone[2] and "no disk bridges P" in alone[3]


def test_pairs_that_cannot_be_cut_into_lenses_say_so_together_as_alone():
    """Pairs tangled beyond lenses say whether a key's stroke crosses itself; asked of every
    such pair of a drawing at once, each says what it says alone."""
    t = np.linspace(0, 4 * np.pi, 90)
    curl = 0.2 * np.c_[t - 2 * np.sin(t), 1 - 2 * np.cos(t)]  # a prolate cycloid: crosses itself
    arc = np.c_[np.linspace(0, 2.5, 60), 0.3 * np.sin(np.linspace(0, np.pi, 60))]
    pairs = [(curl, curl * (1.0, 1.4) + (0.5, 0.2)), (curl, arc), (arc, arc * (1.0, -1.0) + (0.1, 0.0))]

    def key(strokes):
        return StrokeSet.from_strokes(
            [np.c_[s[:, 0] + 10 * k, np.zeros(len(s)), s[:, 1]] for k, s in enumerate(strokes)]
        )

    together = bm.inbetween(key([a for a, _ in pairs]), key([b for _, b in pairs]), [0.5]).pairs
    for (a, b), got in zip(pairs, together):
        alone = bm.inbetween(key([a]), key([b]), [0.5]).pairs[0]
        assert (got.method, got.reason) == (alone.method, alone.reason)
    assert [got.reason.startswith("the first key's stroke crosses itself") for got in together] == [True, True, False]
    assert fallbacks.unsplittable(arc, curl, False, "why", (True, False)).startswith("the second key's stroke")
    assert fallbacks.unsplittable(arc, curl, False, "why") == fallbacks.unsplittable(
        arc, curl, False, "why", (True, False)
    )
