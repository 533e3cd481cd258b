"""Registration's own arithmetic (drawing/registration.py)."""

import numpy as np

from ballmorph_core.drawing.frames.layout import _carry
from ballmorph_core.drawing.pair_morphs import registration
from ballmorph_core.geometry.ragged import Ragged


def test_the_carriers_closed_form_inverses_are_inverses():
    rng = np.random.default_rng(5)
    A = rng.normal(size=(200, 2, 2)) * rng.uniform(0.05, 20.0, (200, 1, 1))
    inverse = registration._inverses(A)
    np.testing.assert_allclose(A @ inverse, np.broadcast_to(np.eye(2), A.shape), atol=1e-9)
    np.testing.assert_allclose(inverse, np.linalg.inv(A), rtol=1e-9, atol=1e-9)


def test_area_moments_of_a_batch_are_each_loops_own():
    from ballmorph_core.geometry.ragged import Ragged

    rect = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]])
    loops = [rect, rect[::-1] + (1.0, -3.0), np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])]
    centre, cov = registration._area_moments(Ragged.from_list(loops, [True] * 3), np.array([0, 1, 2]))
    np.testing.assert_allclose(centre[:2], [[2.0, 1.0], [3.0, -2.0]], atol=1e-12)
    # A w x h rectangle: w^2 / 12 and h^2 / 12, whichever way it runs.
    np.testing.assert_allclose(cov[:2], np.broadcast_to(np.diag([16.0, 4.0]) / 12.0, (2, 2, 2)), atol=1e-12)
    assert np.isnan(cov[2]).all()  # no area: no shape to fit


def test_carriers_apply_each_pairs_motion_to_its_points():
    # Two moving pairs and a still one: every point gets its own pair's C_t = M z + c, and the
    # still pair's points come back exactly.
    rng = np.random.default_rng(2)
    A = np.array([[[0.0, -2.0], [2.0, 0.0]], [[1.5, 0.3], [-0.3, 1.5]], [[1.0, 0.0], [0.0, 1.0]]])
    theta = np.arctan2(A[:, 1, 0], A[:, 0, 0])
    stretch = np.array([np.hypot(*A[k, :, 0]) * np.eye(2) for k in range(3)])
    motions = registration.Motions(
        A, rng.normal(size=(3, 2)), theta, stretch, rng.normal(size=(3, 2)), np.array([True, True, False])
    )
    # The layout's samples come pair after pair.
    points, pair = rng.normal(size=(60, 2)), np.sort(rng.integers(0, 3, 60))
    for t in (0.0, 0.4, 1.0):
        M, c = motions.at(t)
        want = np.where((pair == 2)[:, None], points, np.einsum("kij,kj->ki", M[pair], points) + c[pair])
        got = points.copy()
        _carry(motions, t, got, np.bincount(pair, minlength=3))
        np.testing.assert_allclose(got, want, atol=1e-12)
        np.testing.assert_array_equal(got[pair == 2], points[pair == 2])


def test_a_carrier_put_into_after_an_evaluation_evaluates_its_new_rows():
    """Motions keeps what every time shares from its first evaluation on; put (planning) writes
    other pairs' motions in, and the next evaluation is that of the motions as they are now."""
    rng = np.random.default_rng(3)

    def some(n):
        A = np.eye(2) + 0.2 * rng.normal(size=(n, 2, 2))
        theta, stretch = registration._polar(A)
        return registration.Motions(
            A, rng.normal(size=(n, 2)), theta, stretch, rng.normal(size=(n, 2)), np.ones(n, bool)
        )

    motions, other = some(4), some(2)
    motions.at(0.3)
    motions.put(np.array([1, 3]), other)
    fresh = registration.Motions(motions.A, motions.b, motions.theta, motions.stretch, motions.pivot, motions.moving)
    for got, want in zip(motions.at(0.3), fresh.at(0.3)):
        np.testing.assert_array_equal(got, want)
    np.testing.assert_allclose(motions.at(1.0)[0][[1, 3]], np.eye(2)[None].repeat(2, 0), atol=1e-12)


def test_similarity_matrices_multiply_as_complex_numbers():
    rng = np.random.default_rng(4)
    a, z = rng.normal(size=50) + 1j * rng.normal(size=50), rng.normal(size=(50, 2))
    got = np.einsum("kij,kj->ki", registration.similarity_matrices(a), z)
    np.testing.assert_allclose(got[:, 0] + 1j * got[:, 1], a * (z[:, 0] + 1j * z[:, 1]), atol=1e-12)
    assert registration.similarity_matrices(1j).shape == (2, 2)


def test_open_strokes_slide_in_batches_to_the_same_fits(monkeypatch):
    # Strokes are fitted sliding along each other a few hundred pairs at a time (memory).
    x = np.linspace(0.0, 1.0, 30)
    P = [np.c_[x, 0.2 * np.sin(3 * x + k)] for k in range(9)]
    Q = [np.c_[x * 0.8 + 0.3, 0.2 * np.sin(3 * x + k + 0.5)] for k in range(9)]  # slid along, reshaped
    rp, rq = (Ragged.from_list(side, [False] * 9) for side in (P, Q))
    whole = registration.fit_pairs(rp, rq)
    monkeypatch.setattr(registration, "SLIDE_BATCH", 2)
    batched = registration.fit_pairs(rp, rq)
    np.testing.assert_array_equal(batched.A, whole.A)
    np.testing.assert_array_equal(batched.b, whole.b)


def _blob(n=240):
    """A star-shaped loop, longer along x than along y (no symmetry of an ellipse), shape (n, 2)."""
    t = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    r = 0.3 * (1.0 + 0.12 * np.cos(2.0 * t) + 0.05 * np.cos(3.0 * t + 0.4))
    return np.c_[1.1 * r * np.cos(t), r * np.sin(t)]


def _oblique_stretch(factor, degrees):
    """The symmetric map stretching by ``factor`` along the axis at ``degrees``, shape (2, 2)."""
    a = np.radians(degrees)
    axis = np.array([np.cos(a), np.sin(a)])
    return np.eye(2) + (factor - 1.0) * np.outer(axis, axis)


def test_the_stretch_fit_finds_a_loop_stretched_along_any_axis():
    # Issue 38: a squash along the motion's diagonal. C_Q^(1/2) C_P^(-1/2) takes the moment
    # ellipses onto each other too, but turns the loop unless both share their axes; the
    # symmetric map with A C_P A = C_Q is the stretch itself, and its residual (the stretched
    # loop's own samples against Q's) nothing.
    P = _blob()
    S = _oblique_stretch(1.25, 60.0)
    centre = P.mean(axis=0) + (2.0, 1.0)
    Q = (P - P.mean(axis=0)) @ S.T + centre
    fits = registration.stretch_fits(Ragged.from_list([P], [True]), Ragged.from_list([Q], [True]))
    np.testing.assert_allclose(fits.A[0], S, atol=1e-12)
    np.testing.assert_allclose(fits.A[0] @ P.mean(axis=0) + fits.b[0], centre, atol=1e-12)
    assert fits.residual[0] < 1e-9 * 0.3, fits.residual
