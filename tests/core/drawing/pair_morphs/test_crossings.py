"""Crossing pairs (drawing/splitting.py): the near route's one question."""

import numpy as np
from shapes import circle

from ballmorph_core.drawing.pair_morphs.crossings import _open_area, cross, find_events
from ballmorph_core.geometry.ragged import Ragged


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


def test_cross_is_the_grid_search_whether_the_matched_look_finds_the_crossing_or_not():
    # A loop against a wobbled copy started half a turn on (matched fractions still find the
    # crossings), a loop crossing one far off (matched fractions do not: only the grid does), a
    # loop inside the wobbled one, and an arch meeting a line at their shared ends only (hits
    # there are no crossing).
    t = np.linspace(0, 2 * np.pi, 120, endpoint=False)
    loop = circle(1.0, 120)
    wobbled = loop * (1 + 0.05 * np.sin(5 * t))[:, None]
    x = np.linspace(0.0, 1.0, 60)
    arch, flat = np.c_[x, 0.01 * np.sin(np.pi * x)], np.c_[x, np.zeros(60)]
    R = Ragged.from_list([loop, loop, 0.5 * loop, arch], [True, True, True, False])
    Q = Ragged.from_list([np.roll(wobbled, 60, axis=0), loop + [1.5, 0.0], wobbled, flat], R.closed)
    scale, everything = np.ones(4), np.ones(4, dtype=bool)
    searched = find_events(R, Q, scale, np.full(4, 0.01), everything).count > 0
    np.testing.assert_array_equal(cross(R, Q, scale, everything), searched)
    np.testing.assert_array_equal(searched, [True, True, False, False])


def test_open_area_of_a_piece_and_its_chord_is_the_shoelace_area():
    # The upper half of a unit circle against its diameter, then a square's three sides against
    # its fourth (backwards: the other orientation), batched one after the other.
    half = circle(1.0, 40)[:21]
    square = np.array([[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]])
    pieces = Ragged.from_list([half, square], [False, False])
    chords = Ragged.from_list([half[[0, -1]], square[[0, -1]]], [False, False])
    area = _open_area(pieces) - _open_area(chords)
    np.testing.assert_allclose(area, [0.5 * 20 * np.sin(np.pi / 20), -1.0], rtol=1e-12)
