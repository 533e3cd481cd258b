"""The hint operators' numbering (operators/hint_numbers.py), in plain CPython."""

import numpy as np
import pytest
from addon_package import load

hn = load("addon_logic.hint_numbers")


def test_selected_points_get_the_next_free_numbers_in_drawing_order():
    values = np.array([0, 1, 0, 3, 0, 0])
    selected = np.array([True, False, False, False, True, True])
    new, given = hn.add_hints(values, selected)
    assert new.tolist() == [2, 1, 0, 3, 4, 5]
    assert given == [(0, 2), (4, 4), (5, 5)]


def test_a_chosen_number_moves_to_the_one_selected_point():
    values = np.array([0, 2, 0, 0])
    new, given = hn.add_hints(values, np.array([False, False, True, False]), chosen=2)
    assert new.tolist() == [0, 0, 2, 0] and given == [(2, 2)]
    with pytest.raises(ValueError, match="one point"):
        hn.add_hints(values, np.array([True, False, True, False]), chosen=2)
    with pytest.raises(ValueError, match="select"):
        hn.add_hints(values, np.zeros(4, bool))


def test_clearing_takes_the_selected_points_hints_or_all():
    values = np.array([0, 2, 5, 1])
    new, cleared = hn.clear_hints(values, np.array([False, True, True, False]))
    assert new.tolist() == [0, 0, 0, 1] and cleared == [2, 5]
    assert hn.clear_hints(values)[0].tolist() == [0, 0, 0, 0]
    assert hn.free_numbers([1, 2, 4], 3) == [3, 5, 6]
