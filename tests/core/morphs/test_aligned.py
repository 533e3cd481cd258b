"""Aligned interpolation (morphs/aligned.py): the fallback of curves lying over each other."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from shapes import circle

from ballmorph_core.morphs.aligned import align, aligned_morph
from ballmorph_core.morphs.linear import uniform_correspondence


def test_a_sequence_aligns_with_itself_one_to_one():
    p = circle(1.0, 40)
    [(i, j)] = align([p], [p])
    np.testing.assert_array_equal(i, np.arange(40))
    np.testing.assert_array_equal(j, np.arange(40))


@settings(max_examples=60, deadline=None)
@given(
    arrays(np.float64, st.tuples(st.integers(2, 30), st.just(2)), elements=st.floats(-5, 5)),
    arrays(np.float64, st.tuples(st.integers(2, 30), st.just(2)), elements=st.floats(-5, 5)),
)
def test_an_alignment_pins_both_ends_and_steps_by_one(p, q):
    [(i, j)] = align([p], [q])
    assert (i[0], j[0]) == (0, 0) and (i[-1], j[-1]) == (len(p) - 1, len(q) - 1)
    di, dj = np.diff(i), np.diff(j)
    assert set(zip(di.tolist(), dj.tolist())) <= {(1, 1), (1, 0), (0, 1)}


def test_pairs_aligned_together_are_aligned_as_each_alone():
    rng = np.random.default_rng(3)
    ps = [rng.normal(size=(n, 2)) for n in (5, 40, 17, 2)]
    qs = [rng.normal(size=(m, 2)) for m in (30, 3, 17, 9)]
    together = align(ps, qs)
    for p, q, (i, j) in zip(ps, qs, together):
        [(i1, j1)] = align([p], [q])
        np.testing.assert_array_equal(i, i1)
        np.testing.assert_array_equal(j, j1)


def _spiked(radius, n=400, spike=0.6, width=0.02):
    """A circle with a thin spike out and back at angle 0 (a stem only this key has)."""
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    r = radius + spike * np.maximum(0.0, 1.0 - np.abs(np.angle(np.exp(1j * t))) / width)
    return np.c_[r * np.cos(t), r * np.sin(t)]


def _drift(start, middle):
    """Largest turn about the origin from a sample's start to its middle, away from angle 0."""
    a, b = start @ [1, 1j], middle @ [1, 1j]
    return np.abs(np.angle(b / a))[np.abs(np.angle(a)) > 0.3].max()


def test_a_part_only_one_key_has_does_not_drag_the_rest_along():
    # Q is a slightly larger circle with a spike: arc length slides every point after the
    # spike round the circle by the spike's length; the aligned match keeps them at their angle.
    P, Q = circle(1.0, 400), _spiked(1.1)
    morph = aligned_morph(P, Q, True, 0.01)
    assert _drift(morph(0.0), morph(0.5)) < 0.02
    p, q, _, _ = uniform_correspondence(P, Q, True, 400)
    assert _drift(p, 0.5 * (p + q)) > 0.1  # what arc length does


def test_the_aligned_morph_starts_on_p_and_ends_on_q():
    x = np.linspace(0.0, 1.0, 50)
    P, Q = np.c_[x, 0.2 * np.sin(np.pi * x)], np.c_[x**2, 0.3 * np.sin(np.pi * x)]
    morph = aligned_morph(P, Q, False, 0.02)
    np.testing.assert_allclose(morph(0.0)[[0, -1]], P[[0, -1]], atol=1e-12)
    np.testing.assert_allclose(morph(1.0)[[0, -1]], Q[[0, -1]], atol=1e-12)
    assert np.all(np.diff(morph.u_p) >= 0) and np.all(np.diff(morph.u_q) >= 0)
    assert morph.method == "aligned-interpolation" and not morph.closed


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=80))
def test_a_smoothed_warp_still_rises_and_keeps_its_ends(steps):
    from ballmorph_core.morphs.aligned import _smoothed

    f = np.cumsum(steps) / max(np.sum(steps), 1e-12)
    f = np.r_[0.0, f]
    g = _smoothed(f)
    assert len(g) == len(f) and g[0] == f[0] and g[-1] == f[-1]
    assert np.all(np.diff(g) >= -1e-12)
