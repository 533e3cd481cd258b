"""Crossing pairs (drawing/splitting.py): the near road's one question."""

import numpy as np

from ballmorph_core.drawing.splitting import cross, find_events
from ballmorph_core.geometry.ragged import Ragged

from .shapes import circle


def test_cross_says_which_pairs_meet_as_find_events_counts_them():
    x = np.linspace(0.0, 1.0, 50)
    arch, flat = np.c_[x, 0.2 * np.sin(np.pi * x)], np.c_[x, np.zeros(50)]
    wave = np.c_[x, 0.05 * np.sin(3 * np.pi * x)]
    R = Ragged.from_list([arch, wave, circle(1.0, 80), circle(1.0, 80)], [False, False, True, True])
    # The arch meets the line only at their shared ends; the wave crosses it; the loops cross
    # (shifted) or lie one inside the other.
    Q = Ragged.from_list([flat, flat, circle(1.0, 80) + [0.3, 0.0], circle(0.5, 80)], R.closed)
    scale = np.ones(4)
    everything = np.ones(4, dtype=bool)
    got = cross(R, Q, scale, everything)
    np.testing.assert_array_equal(got, [False, True, True, False])
    np.testing.assert_array_equal(got, find_events(R, Q, scale, np.full(4, 0.01), everything).count > 0)
    assert not cross(R, Q, scale, np.array([False, False, True, False]))[1]
