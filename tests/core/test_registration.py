"""Registration's own arithmetic (drawing/registration.py)."""

import numpy as np

from ballmorph_core.drawing import registration


def test_the_carriers_closed_form_inverses_are_inverses():
    rng = np.random.default_rng(5)
    A = rng.normal(size=(200, 2, 2)) * rng.uniform(0.05, 20.0, (200, 1, 1))
    inverse = registration._inverses(A)
    np.testing.assert_allclose(A @ inverse, np.broadcast_to(np.eye(2), A.shape), atol=1e-9)
    np.testing.assert_allclose(inverse, np.linalg.inv(A), rtol=1e-9, atol=1e-9)
