"""Which keys pair up and which frames get in-betweens (addon_logic/pairing.py), in plain CPython."""

import numpy as np
import pytest
from addon_package import load

pairing = load("addon_logic.pairing")
LayerKeys = pairing.LayerKeys


def ink(keys=(), selected=(), made=()):
    return LayerKeys("Ink", tuple(keys), tuple(selected), tuple(made))


# -- the operator's rule: selected keys, else the keys around the current frame ---------------------


@pytest.mark.parametrize(
    ("current", "pair"),
    [(1, (1, 5)), (4, (1, 5)), (5, (5, 9)), (8, (5, 9))],
    ids=["on-first-key", "between", "on-a-key", "before-last"],
)
def test_the_last_key_at_or_before_the_current_frame_and_the_first_after(current, pair):
    assert pairing.selected_or_current(ink((1, 5, 9)), current) == ([pair], [])


def test_two_selected_keys_pair_wherever_the_current_frame_is():
    assert pairing.selected_or_current(ink((1, 5, 9), selected=(1, 9)), 30) == ([(1, 9)], [])


def test_three_selected_keys_give_every_consecutive_pair_of_them():
    layer = ink((1, 5, 9, 13), selected=(1, 9, 13))
    assert pairing.selected_or_current(layer, 3) == ([(1, 9), (9, 13)], [])


def test_one_selected_key_is_no_selection():
    assert pairing.selected_or_current(ink((1, 5, 9), selected=(9,)), 2) == ([(1, 5)], [])


def test_a_selected_frame_that_is_not_a_key_does_not_count():
    # frame 5 was made by the add-on: it is not among the keys, so its selection is ignored
    layer = ink((1, 9), selected=(1, 5), made=(5,))
    assert pairing.selected_or_current(layer, 3) == ([(1, 9)], [])


@pytest.mark.parametrize("count", [0, 1])
def test_fewer_than_two_keys(count):
    layer = ink(range(1, count + 1))
    assert pairing.selected_or_current(layer, 1) == (
        [],
        [f"layer 'Ink' has {count} keyframe(s): draw a second key to in-between"],
    )


@pytest.mark.parametrize(("current", "side"), [(0, "before"), (9, "after"), (20, "after")])
def test_no_key_on_one_side_of_the_current_frame(current, side):
    assert pairing.selected_or_current(ink((1, 5, 9)), current) == (
        [],
        [
            f"layer 'Ink' has no keyframe {side} frame {current}: select two keyframes, "
            "or go to a frame between two keys"
        ],
    )


def test_keys_on_consecutive_frames_are_a_problem_when_chosen():
    problem = (
        "layer 'Ink': keys 3 and 4 have no frame between them: move them apart, "
        "or select two keys with frames between them"
    )
    assert pairing.selected_or_current(ink((1, 3, 4, 9)), 3) == ([], [problem])
    # among selected keys, the other pairs still go ahead
    assert pairing.selected_or_current(ink((1, 3, 4, 9), selected=(1, 3, 4)), 0) == ([(1, 3)], [problem])


# -- the command line's rule: every consecutive pair of keys -----------------------------------


def test_every_pair_of_consecutive_keys_ignoring_selection():
    assert pairing.every_pair(ink((1, 5, 9, 13), selected=(5, 9))) == ([(1, 5), (5, 9), (9, 13)], [])


def test_keys_on_consecutive_frames_are_quietly_not_paired():
    # a layer animated on ones with one gap: only the gap is an interval, and nothing is wrong
    assert pairing.every_pair(ink((1, 2, 3, 7, 8))) == ([(3, 7)], [])


def test_a_layer_with_keys_on_every_frame_has_nothing_to_in_between():
    assert pairing.every_pair(ink((1, 2, 3))) == (
        [],
        ["layer 'Ink': every key is on the frame after the previous one: no frame to in-between"],
    )


@pytest.mark.parametrize("count", [0, 1])
def test_every_pair_needs_two_keys(count):
    assert pairing.every_pair(ink(range(1, count + 1))) == (
        [],
        [f"layer 'Ink' has {count} keyframe(s): draw a second key to in-between"],
    )


def test_frames_the_add_on_made_are_not_keys_for_either_rule():
    layer = ink((1, 9), made=(3, 5, 7))
    assert pairing.every_pair(layer) == ([(1, 9)], [])
    assert pairing.selected_or_current(layer, 6) == ([(1, 9)], [])


# -- the frames of an interval ------------------------------------------------------------------


def one(layer, pair, frame_count):
    (interval,) = pairing.intervals(layer, [pair], frame_count)
    return interval


@pytest.mark.parametrize(
    ("count", "targets"),
    [(0, [2, 3, 4, 5, 6, 7, 8]), (1, [5]), (3, [3, 5, 7]), (7, [2, 3, 4, 5, 6, 7, 8]), (50, [2, 3, 4, 5, 6, 7, 8])],
)
def test_frame_count_spreads_in_betweens_evenly_at_most_one_per_frame(count, targets):
    interval = one(ink((1, 9)), (1, 9), count)
    assert interval.targets.tolist() == targets
    np.testing.assert_allclose(interval.fractions, (np.array(targets) - 1) / 8)
    assert (interval.replace, interval.occupied, interval.skipped) == ([], [], [])


def test_a_drawn_frame_between_the_keys_is_never_a_target():
    layer = ink((1, 5, 9), selected=(1, 9))
    every = one(layer, (1, 9), 0)
    assert every.targets.tolist() == [2, 3, 4, 6, 7, 8]
    assert (every.occupied, every.skipped) == ([5], [5])
    np.testing.assert_allclose(every.fractions, (every.targets - 1) / 8)  # its fraction is dropped with it
    # three in-betweens land on 3, 5, 7: frame 5 is drawn, so it is skipped
    three = one(layer, (1, 9), 3)
    assert (three.targets.tolist(), three.skipped, three.occupied) == ([3, 7], [5], [5])
    # frame 4 drawn, in-betweens on 3, 5, 7: nothing skipped, frame 4 left alone
    other = one(ink((1, 4, 9)), (1, 9), 3)
    assert (other.targets.tolist(), other.skipped, other.occupied) == ([3, 5, 7], [], [4])


def test_every_frame_between_the_keys_drawn():
    interval = one(ink((1, 2, 3, 4, 5)), (1, 5), 0)
    assert interval.targets.tolist() == [] and interval.skipped == [2, 3, 4]


def test_the_add_ons_earlier_frames_between_the_keys_are_replaced_and_no_others():
    layer = ink((1, 9, 13), made=(3, 5, 7, 11))
    interval = one(layer, (1, 9), 1)
    assert interval.replace == [3, 5, 7]
    assert interval.targets.tolist() == [5]  # its own earlier frame 5 is no obstacle
    assert interval.skipped == [] and interval.occupied == []


def test_one_interval_per_pair_named_after_layer_and_keys():
    found = pairing.intervals(ink((1, 5, 9)), [(1, 5), (5, 9)], 1)
    assert [(i.layer, i.frame_a, i.frame_b, i.targets.tolist()) for i in found] == [
        ("Ink", 1, 5, [3]),
        ("Ink", 5, 9, [7]),
    ]
    assert [i.name for i in found] == ["Ink 1\u21925", "Ink 5\u21929"]
    assert pairing.intervals(ink((1, 5)), [], 0) == []


# -- timing charts --------------------------------------------------------------------------------


def test_a_chart_gives_one_in_between_per_fraction_whatever_the_frame_count():
    chart = pairing.Chart((0.1, 0.5, 0.9))
    (charted, plain) = pairing.intervals(ink((1, 9, 17)), [(1, 9), (9, 17)], 1, {(1, 9): chart})
    assert charted.targets.tolist() == [3, 5, 7] and charted.chart is chart
    assert charted.chart_times.tolist() == [0.1, 0.5, 0.9]
    np.testing.assert_allclose(charted.fractions, [0.25, 0.5, 0.75])  # where the frames are
    assert plain.targets.tolist() == [13] and plain.chart is None and plain.chart_times is None


def test_a_charted_frame_that_is_drawn_is_skipped_with_its_fraction():
    (charted,) = pairing.intervals(
        ink((1, 5, 9), selected=(1, 9)), [(1, 9)], 0, {(1, 9): pairing.Chart((0.1, 0.5, 0.9))}
    )
    assert (charted.targets.tolist(), charted.skipped) == ([3, 7], [5])
    assert charted.chart_times.tolist() == [0.1, 0.9]


def test_a_chart_with_more_fractions_than_frames_between_the_keys_is_an_error():
    with pytest.raises(ValueError, match="Ink 1\u21924: 3 fractions do not fit"):
        pairing.intervals(ink((1, 4)), [(1, 4)], 0, {(1, 4): pairing.Chart((0.2, 0.5, 0.8))})


def test_a_chart_spells_itself_as_the_option_does():
    assert pairing.Chart((0.1, 0.25, 0.9)).text == "0.1 0.25 0.9"
    assert pairing.Chart((1 / 3,)).text == repr(1 / 3)  # kept exactly


# -- chains: consecutive intervals joined smoothly at the keys they share (issue 39) ---------------


def test_chains_are_runs_of_intervals_sharing_keys_with_extreme_keys_as_corners():
    found = pairing.intervals(ink(keys=(1, 7, 13, 20, 30, 40)), [(1, 7), (7, 13), (20, 30), (30, 40)], 0)
    assert pairing.chains(found) == [([0, 1], [True]), ([2, 3], [True])]
    assert pairing.chains(found, corners=(7, 40)) == [([0, 1], [False]), ([2, 3], [True])]
    assert pairing.chains(found[:1]) == [] and pairing.chains([]) == []
