"""The one similarity fit (geometry/procrustes.py): analytic cases and the batch against one by one."""

import numpy as np
import pytest

from ballmorph_core.geometry.procrustes import cyclic_correlation, similarity_fit, similarity_fits


def _samples(rng, n):
    return rng.normal(size=n) + 1j * rng.normal(size=n)


@pytest.mark.parametrize("seed", range(5))
def test_a_similarity_is_recovered_exactly(seed):
    rng = np.random.default_rng(seed)
    za = _samples(rng, 40)
    a, b = complex(rng.normal(), rng.normal()), complex(rng.normal(), rng.normal())
    fa, fb = similarity_fit(za, a * za + b)
    assert abs(fa - a) < 1e-12 and abs(fb - b) < 1e-12, (fa, a, fb, b)


def test_the_fit_turns_about_the_given_centre():
    za = np.array([0, 1, 1 + 1j, 1j])
    a, b = similarity_fit(za, 1j * za, ca=0j, cb=0j)  # a quarter turn about the origin
    assert abs(a - 1j) < 1e-12 and abs(b) < 1e-12


def test_samples_without_extent_fit_the_identity_turn():
    a, b = similarity_fit(np.full(5, 2 + 1j), np.arange(5) + 0j)
    assert a == 1.0 and abs(b - (2 - (2 + 1j))) < 1e-12


def test_the_batch_is_the_one_by_one_fit():
    rng = np.random.default_rng(7)
    p = np.array([_samples(rng, 16) for _ in range(6)] + [np.zeros(16, complex)])
    q = np.array([_samples(rng, 16) for _ in range(7)])
    p, q = p - p.mean(axis=1, keepdims=True), q - q.mean(axis=1, keepdims=True)
    a, norm = similarity_fits(p, q)
    for k in range(len(p)):
        want, _ = similarity_fit(p[k], q[k], 0j, 0j)
        assert abs(a[k] - want) < 1e-12, k
    np.testing.assert_allclose(norm, (np.abs(p) ** 2).sum(axis=1))


def test_the_correlation_is_every_cyclic_shift_summed_directly():
    rng = np.random.default_rng(3)
    p, q = _samples(rng, 9), _samples(rng, 9)
    want = [np.sum(np.conj(p) * np.roll(q, -k)) for k in range(9)]
    np.testing.assert_allclose(cyclic_correlation(p, q), want, atol=1e-12)
    batch = cyclic_correlation(np.array([p, q]), np.array([q, p]))
    np.testing.assert_allclose(batch[0], want, atol=1e-12)
