"""Issue 39 item 5: stroke ends within tolerances.NEAR_SHARED_END of each other are treated as
shared: the in-betweens' ends stay between the keys' ends, and consecutive in-betweens do not
cross there."""

import numpy as np
import pytest
import scenes

import ballmorph_core as bm
from ballmorph_core import tolerances as tol


def _run(a, b):
    keys = scenes.key([a], False), scenes.key([b], False)
    result = bm.inbetween(keys[0].stroke_set(), keys[1].stroke_set(), scenes.TIMES)
    return tuple(scenes.as_drawing(k) for k in keys), [scenes.as_drawing(f) for f in result.frames], result


@pytest.mark.parametrize(
    "sag_a, sag_b, off, span",
    [
        (0.3, 1.0, (0.012, 0.006, -0.0084, -0.012), 4.0),  # the scene: 0.3% of the drawing
        (0.2, 0.7, (-0.009, 0.012, 0.006, 0.0), 3.0),  # held back: 0.5% and less, other span
        (0.6, 0.2, (0.0, -0.008, 0.004, 0.004), 5.0),  # held back: rising, one end pinned exactly in x
    ],
)
def test_ends_a_hair_off_their_pins_stay_between_and_the_sweep_never_crosses(sag_a, sag_b, off, span):
    keys, frames, result = _run(scenes.pinned_rope(sag_a, span=span), scenes.pinned_rope(sag_b, off, span))
    size = scenes.drawing_size(*keys)
    worst_off = max(np.hypot(*off[:2]), np.hypot(*off[2:])) / size
    assert worst_off <= tol.NEAR_SHARED_END, worst_off
    ends = scenes.figure_pinned_ends(keys, frames, scenes.TIMES)
    sweep = scenes.figure_sweep_crossings(keys, frames, scenes.TIMES)
    assert ends.ok and sweep.ok, f"rope ends {worst_off:.2%} of the drawing off their pins: {ends}; {sweep}"
    # Taken as drawn (no carrier), the ends meet halfway: one point on every in-between.
    assert all("carrier" not in p.method for p in result.pairs), [p.method for p in result.pairs]
    first = np.array([f[0].xy[0] for f in frames])
    assert np.ptp(first, axis=0).max() <= 1e-12 * size


def test_ends_farther_apart_than_the_tolerance_still_move():
    """Ends 2% of the drawing apart are the animator's: they travel from key to key."""
    keys, frames, _ = _run(scenes.pinned_rope(0.3), scenes.pinned_rope(1.0, (0.08, 0.0, 0.0, 0.0)))
    first = np.array([f[0].xy[0] for f in frames])
    assert np.ptp(first[:, 0]) >= 0.5 * 0.08, first[:, 0]
