"""Golden output: the in-betweens of a fixed set of drawings (see ``golden_cases``) stay the same.

Frames must match the stored ones to 1e-9 (positions and every attribute; stroke sizes, flags,
materials and origins exactly). A commit that changes behaviour on purpose regenerates them with
``tools/golden.py --write`` and says why.
"""

import numpy as np
import pytest
from golden_cases import FIELDS, TIMES, cases, path

import ballmorph_core as bm

_CASES = cases()


@pytest.mark.parametrize("case", _CASES, ids=[c[0] for c in _CASES])
def test_frames_are_the_stored_ones(case):
    name, key_a, key_b, options = case
    stored = np.load(path(name))
    result = bm.inbetween(key_a, key_b, TIMES, **options)
    assert len(result.frames) == len(TIMES)
    for k, frame in enumerate(result.frames):
        for field in FIELDS:
            want, got = stored[f"{k}/{field}"], getattr(frame, field)
            assert got.shape == want.shape, f"{name} t={TIMES[k]} {field}: shape {got.shape} != {want.shape}"
            if np.issubdtype(want.dtype, np.floating):
                worst = float(np.abs(got - want).max(initial=0.0))
                assert worst <= 1e-9, f"{name} t={TIMES[k]} {field}: off by {worst:.3g}"
            else:
                np.testing.assert_array_equal(got, want, err_msg=f"{name} t={TIMES[k]} {field}")


def test_the_golden_set_covers_every_route():
    """The stored cases exercise what a refactor could break: fallbacks, composite, splits."""
    used = " ".join(" ".join(np.load(path(name))["pairs"]) for name, *_ in _CASES)
    for route in (
        "composite ball-morph used",
        "split at",
        "linear-interpolation used",
        "straight point motion",
        "appear",
    ):
        assert route in used, route
