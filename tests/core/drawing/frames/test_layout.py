"""The layout's evaluation (``drawing/layout.py``): every route evaluated into work columns kept
from frame to frame, gathered into frame order and carried. Whatever was evaluated before, and
however the times are chunked, each frame is the same, and no frame returned shares memory
with the buffers the next evaluation overwrites."""

import numpy as np
import pytest
from golden_cases import cases

import ballmorph_core as bm
from ballmorph_core.drawing.frames.layout import _fractions

_CASES = {name: (a, b, options) for name, a, b, options in cases()}


@pytest.mark.parametrize(
    "name",
    [
        "head-turn",  # ball rows with end gaps, joined routes, gathered, on carriers
        "mixed-index-hold",  # joined straight paths with end gaps
        "mixed-curvature-interpolation",  # morphs that are not joined
        "crossing-loops",  # frame order as evaluated: nothing gathered
    ],
)
def test_frames_do_not_depend_on_what_was_evaluated_before(name):
    key_a, key_b, options = _CASES[name]
    layout = bm.plan_inbetween(key_a, key_b, **options).pairs.layout
    motions = bm.plan_inbetween(key_a, key_b, **options).pairs.motions
    times = np.array([0.15, 0.5, 0.8, 0.0, 1.0])
    fresh = np.stack([_fresh(key_a, key_b, options, t) for t in times])
    first = layout.evaluate(times, motions)
    kept = first.copy()
    again = np.concatenate([layout.evaluate(times[i : i + 2], motions) for i in range(0, len(times), 2)])
    backwards = layout.evaluate(times[::-1], motions)[::-1]
    np.testing.assert_array_equal(first, fresh)
    np.testing.assert_array_equal(again, fresh)
    np.testing.assert_array_equal(backwards, fresh)
    np.testing.assert_array_equal(first, kept)  # later evaluations wrote into their own frames


def _fresh(key_a, key_b, options, t):
    """Frame ``t`` of a plan evaluated once, at that time only."""
    pairs = bm.plan_inbetween(key_a, key_b, **options).pairs
    return pairs.layout.evaluate([t], pairs.motions)[0]


def test_the_cases_above_take_every_branch():
    """The routes the test above relies on are there (a change of the pipeline could drop one)."""
    layouts = {
        name: bm.plan_inbetween(*_CASES[name][:2], **_CASES[name][2]).pairs.layout
        for name in ("head-turn", "mixed-index-hold", "mixed-curvature-interpolation", "crossing-loops")
    }
    assert layouts["head-turn"]._gather is not None and layouts["head-turn"]._ball_shift is not None
    assert any(j.shift is not None for j in layouts["mixed-index-hold"]._joined)
    assert layouts["mixed-curvature-interpolation"]._morphs
    assert layouts["crossing-loops"]._gather is None


def test_a_plan_stages_every_chunk_in_one_buffer_and_its_frames_own_their_memory(monkeypatch):
    """The plan keeps one buffer for the pairs' 2D frames of a chunk of times: chunk after
    chunk and evaluation after evaluation the in-betweens are the same, and those returned
    earlier are not overwritten (they are lifted out of it)."""
    from ballmorph_core.drawing import plan as plan_module

    key_a, key_b, options = _CASES["head-turn"]
    times = [0.2, 0.5, 0.9]
    whole = [f.positions for f in bm.inbetween(key_a, key_b, times, **options).frames]
    plan = bm.plan_inbetween(key_a, key_b, **options)
    monkeypatch.setattr(plan_module, "EVALUATE_SAMPLES", 1)  # one time per chunk
    first = plan.evaluate(times)
    kept = [f.positions.copy() for f in first.frames]
    staged = plan._staged
    later = plan.evaluate(times[::-1])
    assert plan._staged is staged and staged.shape[0] == 1  # one chunk's size, kept
    for k in range(len(times)):
        assert not np.shares_memory(first.frames[k].positions, staged)
        np.testing.assert_array_equal(first.frames[k].positions, kept[k])
        np.testing.assert_array_equal(first.frames[k].positions, whole[k])
        np.testing.assert_array_equal(later.frames[len(times) - 1 - k].positions, whole[k])


@pytest.mark.parametrize("seed", range(5))
def test_fractions_along_pairs_are_those_of_each_samples_own_range(seed):
    # Per-chain starts and spans gathered per sample: bit for bit the sample-by-sample
    # arithmetic, taken round loops and clipped on open curves.
    rng = np.random.default_rng(seed)
    pairs, chains, samples = 6, 15, 400
    lengths = rng.uniform(0.0, 3.0, pairs) * (rng.random(pairs) < 0.9)  # some of no length
    ranges = np.sort(rng.uniform(-0.5, 4.0, (chains, 2)), axis=1)
    chain = np.sort(rng.integers(0, chains, samples))
    owner = rng.integers(0, pairs, chains)[chain]
    loop = (rng.random(pairs) < 0.5)[owner]
    local = rng.uniform(0.0, 1.0, samples)
    u = (ranges[chain, 0] + local * (ranges[chain, 1] - ranges[chain, 0])) / np.maximum(lengths[owner], 1e-300)
    expected = np.where(loop, np.mod(u, 1.0), np.clip(u, 0.0, 1.0))
    got = _fractions(local, ranges, lengths, chain, owner, loop)
    assert np.array_equal(got.view(np.int64), expected.view(np.int64))
