"""Fuzz target: the core's contract on random curve pairs and drawings (issue 7).

Every example is a random curve pair or pair of drawings (smooth loops and strokes, hand
noise, sampling densities from 3 to 600 points, similarity transforms over six orders of
magnitude, then degenerate edits: duplicates, collapse to a point, spikes, collinear points,
coincident and nearly parallel partners, NaN and infinity). Each test asserts only the
contract:

* ``ball_map``, ``classify``, ``make_morph`` (every method of ``METHODS``): a valid result or a
  documented error (``InvalidCurveError`` for malformed input, ``IncompatibleCurvesError``
  otherwise), never another exception, never a NaN in the output;
* ``inbetween``: never raises on well-formed drawings, returns one finite frame per time,
  accounts for every stroke of both keys, reports every fallback, and leaves the keys intact.

The short derandomised profile runs in CI with the core tests; ``make fuzz`` runs thousands of
examples per test (HYPOTHESIS_PROFILE=fuzz).
"""

import numpy as np
import pytest
from fuzz_strategies import curve_pairs, degenerate_drawings, distinct_count, drawings, fuzz_settings
from hypothesis import event, given, note
from hypothesis import strategies as st

import ballmorph_core as bm
from ballmorph_core import FALLBACK_METHOD, StrokeSet
from ballmorph_core import tolerances as tol
from ballmorph_core.ballmap.topology import CONFIGURATIONS
from ballmorph_core.options import CARRIERS, MATCHINGS, UNMATCHED

#: Relative sizes: fewer distinct points than needed at this resolution is clearly malformed;
#: at the core's own resolution (tolerances.COINCIDENT) clearly well formed. In between,
#: either answer is allowed.
MALFORMED_AT = 1e-6
WELL_FORMED_AT = 1e-12


def _classify_input(P, Q, closed):
    """'nonfinite', 'too-few', 'ambiguous' or 'ok' for a pair of raw curves."""
    if not (np.all(np.isfinite(P)) and np.all(np.isfinite(Q))):
        return "nonfinite"
    need = 3 if closed else 2
    if min(distinct_count(P, closed, WELL_FORMED_AT), distinct_count(Q, closed, WELL_FORMED_AT)) < need:
        return "too-few"
    if min(distinct_count(P, closed, MALFORMED_AT), distinct_count(Q, closed, MALFORMED_AT)) < need:
        return "ambiguous"
    return "ok"


def _call(fn, P, Q, closed):
    """Run ``fn`` under the contract; the result, or None after a documented error."""
    kind = _classify_input(P, Q, closed)
    note(f"input kind: {kind}")
    try:
        out = fn()
    except bm.InvalidCurveError as exc:
        event(f"{kind} input -> InvalidCurveError")
        assert kind != "ok", f"well-formed input rejected as malformed: {exc}"
        assert str(exc).startswith(("P:", "Q:", "spacing")), f"message names no argument: {exc}"
        return None
    except bm.IncompatibleCurvesError as exc:
        event(f"{kind} input -> IncompatibleCurvesError")
        assert kind in ("ok", "ambiguous"), f"malformed input ({kind}) not reported as InvalidCurveError: {exc}"
        assert str(exc), "empty message"
        return None
    event(f"{kind} input -> result")
    assert kind in ("ok", "ambiguous"), f"malformed input ({kind}) accepted"
    return out


def _without_memory_error(fn):
    """``fn()``; a MemoryError (``make fuzz`` caps the address space) becomes a plain failure.

    The failure is raised outside the ``except`` block, so the frames holding the huge arrays
    are released before pytest formats the report.
    """
    try:
        return fn()
    except MemoryError:
        pass
    pytest.fail("MemoryError: the call tried to allocate more than the address-space cap")


def _finite(*arrays):
    return all(np.all(np.isfinite(np.asarray(a, dtype=np.float64))) for a in arrays)


@fuzz_settings
@given(pair=curve_pairs(allow_nonfinite=True))
def test_ball_map_contract(pair):
    P, Q, closed, how = pair
    note(f"closed={closed} relation/edits={how} sizes={len(P)},{len(Q)}")
    corr = _call(lambda: _without_memory_error(lambda: bm.ball_map(P, Q, closed=closed)), P, Q, closed)
    if corr is None:
        return
    k = len(corr)
    assert k >= 2
    for name in ("p", "q", "centers", "normal_p", "normal_q"):
        arr = getattr(corr, name)
        assert arr.shape == (k, 2), name
        assert _finite(arr), f"non-finite {name}"
    assert corr.radii.shape == (k,) and _finite(corr.radii, corr.s_p, corr.s_q)
    assert np.all(corr.radii >= 0)
    # Every contact is on its disk (the definition of the correspondence), up to the slack of
    # strokes whose endpoints count as shared (a zero disk at p, q within SHARED_ENDPOINT).
    slack = 1e-4 * corr.radii.max() + tol.SHARED_ENDPOINT * bm.geometry.polyline.scale_of(P, Q)
    for contact in (corr.p, corr.q):
        gap = np.abs(np.linalg.norm(corr.centers - contact, axis=1) - corr.radii)
        assert gap.max() <= slack, "a contact is off its disk"


@fuzz_settings
@given(pair=curve_pairs(allow_nonfinite=True))
def test_classify_contract(pair):
    P, Q, closed, how = pair
    note(f"closed={closed} relation/edits={how}")
    config = _call(lambda: _without_memory_error(lambda: bm.classify(P, Q, closed=closed)), P, Q, closed)
    if config is not None:
        assert config in CONFIGURATIONS


@fuzz_settings
@given(pair=curve_pairs(allow_nonfinite=True), method=st.sampled_from(bm.METHODS))
def test_make_morph_contract(pair, method):
    P, Q, closed, how = pair
    note(f"closed={closed} relation/edits={how} sizes={len(P)},{len(Q)}")
    morph = _call(lambda: _without_memory_error(lambda: bm.make_morph(P, Q, method, closed=closed)), P, Q, closed)
    if morph is None:
        return
    frames = [morph(t) for t in (0.0, 0.25, 0.5, 0.75, 1.0)]
    k = len(frames[0])
    assert k >= 2
    for f in frames:
        assert f.shape == (k, 2), "frames must keep their sample count"
        assert _finite(f), "NaN or infinity in a frame"
    assert morph.u_p.shape == (k,) and morph.u_q.shape == (k,)
    assert _finite(morph.u_p, morph.u_q)
    assert morph.u_p.min() >= -1e-9 and morph.u_p.max() <= 1 + 1e-9
    assert morph.u_q.min() >= -1e-9 and morph.u_q.max() <= 1 + 1e-9


def _strokeset(strokes, rng):
    """A StrokeSet with random per-point attributes from [(points (N, 3), cyclic)]."""
    sizes = [len(p) for p, _ in strokes]
    n = int(sum(sizes))
    return StrokeSet(
        np.concatenate([p for p, _ in strokes]) if strokes else np.zeros((0, 3)),
        np.r_[0, np.cumsum(sizes)].astype(np.int64),
        [c for _, c in strokes],
        rng.integers(0, 4, len(strokes)),
        rng.uniform(0.001, 0.1, n),
        rng.uniform(0.0, 1.0, n),
        rng.uniform(0.0, 1.0, (n, 4)),
    )


def _copy(s):
    return {k: np.array(getattr(s, k), copy=True) for k in ("positions", "offsets", "cyclic", "radius", "opacity")}


def _unchanged(s, before):
    return all(np.array_equal(getattr(s, k), v) for k, v in before.items())


@fuzz_settings
@given(
    keys=drawings(),
    method=st.sampled_from(bm.METHODS),
    carrier=st.sampled_from(CARRIERS),
    matching=st.sampled_from(MATCHINGS),
    unmatched=st.sampled_from(UNMATCHED),
    times=st.lists(st.floats(0.0, 1.0), min_size=0, max_size=4),
    seed=st.integers(0, 2**32 - 1),
)
def test_inbetween_contract(keys, method, carrier, matching, unmatched, times, seed):
    _check_inbetween(keys, (method, carrier, matching, unmatched), times, seed)


@fuzz_settings
@given(
    keys=degenerate_drawings(),
    method=st.sampled_from(bm.METHODS),
    matching=st.sampled_from(MATCHINGS),
    times=st.lists(st.floats(0.0, 1.0), min_size=0, max_size=2),
    seed=st.integers(0, 2**32 - 1),
)
def test_inbetween_contract_on_degenerate_keys(keys, method, matching, times, seed):
    """Strokes drawn again in place, sharing one centroid, one far from the rest, float32
    coordinates (issue 41: an OverflowError in the matching's turn guess)."""
    _check_inbetween(keys, (method, "similarity", matching, "middle"), times, seed)


def _check_inbetween(keys, options, times, seed):
    """The contract of ``plan_inbetween(*keys, *options).evaluate(times)`` (see the module notes)."""
    method = options[0]
    rng = np.random.default_rng(seed)
    key_a, key_b = _strokeset(keys[0], rng), _strokeset(keys[1], rng)
    note(f"strokes {len(key_a)} -> {len(key_b)}, sizes {key_a.sizes.tolist()} -> {key_b.sizes.tolist()}")
    times = [0.0, *times, 1.0]
    before_a, before_b = _copy(key_a), _copy(key_b)
    # ``inbetween`` is ``plan_inbetween(...).evaluate(times)``; the plan is what the operator
    # keeps for a redo, so evaluate it twice.
    plan = _without_memory_error(lambda: bm.plan_inbetween(key_a, key_b, *options))
    result = plan.evaluate(times)
    again = plan.evaluate(times[::-1])
    for frame, other in zip(result.frames, again.frames[::-1]):
        assert np.array_equal(frame.positions, other.positions), "a plan's second evaluation differs"
        assert np.array_equal(frame.offsets, other.offsets), "a plan's second evaluation differs"
    # The keys are never touched.
    assert _unchanged(key_a, before_a) and _unchanged(key_b, before_b), "a key was modified"
    assert len(result.frames) == len(times)
    for frame in result.frames:
        assert isinstance(frame, StrokeSet)
        assert _finite(frame.positions, frame.radius, frame.opacity, frame.vertex_color), "NaN in an in-between"
        assert np.all(frame.sizes >= 1), "an in-between has a stroke with no point"
    # Every stroke of both keys is accounted for exactly once.
    from_a = sorted(p.stroke_a for p in result.pairs if p.stroke_a is not None)
    from_b = sorted(p.stroke_b for p in result.pairs if p.stroke_b is not None)
    assert from_a == list(range(len(key_a))) and from_b == list(range(len(key_b)))
    # A morphed pair keeps a real stroke: at least two points in every in-between (loops three),
    # unless it was reported as moving point by point.
    straight = {(p.stroke_a, p.stroke_b) for p in result.pairs if p.method == "straight point motion"}
    for frame in result.frames:
        for (i, j), size, cyclic in zip(frame.origin.tolist(), frame.sizes, frame.cyclic):
            if i >= 0 and j >= 0 and (i, j) not in straight:
                assert size >= (3 if cyclic else 2), f"stroke {i} -> {j} became {size} point(s)"
    # A fallback is always reported, with its reason.
    for p in result.pairs:
        fell_back = FALLBACK_METHOD in p.method or p.method == "straight point motion"
        if fell_back and method != FALLBACK_METHOD:
            assert p.reason, f"fallback without a reason: {p}"
            # (a lens falling back inside an otherwise morphed pair is an INFO message.)
            assert any(f"stroke {p.stroke_a + 1} -> {p.stroke_b + 1}" in m.text for m in result.messages), (
                "not reported"
            )


@fuzz_settings
@given(keys=drawings(max_strokes=3), seed=st.integers(0, 2**32 - 1), bad=st.sampled_from([np.nan, np.inf, -np.inf]))
def test_inbetween_rejects_nonfinite_positions_naming_the_stroke(keys, seed, bad):
    rng = np.random.default_rng(seed)
    key_a, key_b = _strokeset(keys[0], rng), _strokeset(keys[1], rng)
    name, target = ("key_a", key_a) if len(key_a.positions) else ("key_b", key_b)
    if len(target.positions) == 0:
        return
    point = int(rng.integers(0, len(target.positions)))
    target.positions[point, int(rng.integers(0, 3))] = bad
    stroke = int(np.searchsorted(target.offsets, point, side="right"))  # as the animator counts, from 1
    with pytest.raises(bm.InvalidCurveError, match=rf"^{name}: stroke\(s\) \[{stroke}\] have NaN or infinite"):
        bm.inbetween(key_a, key_b, [0.0, 0.5, 1.0])
