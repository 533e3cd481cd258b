"""What the add-on tells the animator (operators/reports.py), in plain CPython."""

import numpy as np
import pytest
from addon_package import load

reports = load("addon_logic.reports")
pairing = load("addon_logic.pairing")
core = load("ballmorph_core")


@pytest.mark.parametrize(
    ("numbers", "text"),
    [
        ([5], "5"),
        ([2, 3], "2, 3"),
        ([2, 3, 4], "2\u20134"),
        (np.arange(2, 9), "2\u20138"),
        ([3, 5, 7], "3, 5, 7"),
        ([2, 3, 5, 6], "2, 3, 5, 6"),
        ([], ""),
    ],
)
def test_frames_text(numbers, text):
    assert reports.frames_text(numbers) == text


@pytest.mark.parametrize(
    ("chain", "text"),
    [
        ([(None, False, False)], ""),
        ([(None, True, False)], "layer 'Paint' is locked: unlock it to in-between it"),
        ([(None, False, True)], "layer 'Paint' is hidden: show it to in-between it"),
        ([(None, True, True)], "layer 'Paint' is locked: unlock it to in-between it"),
        (
            [(None, False, False), ("Outer", True, False)],
            "layer 'Paint' is locked (group 'Outer'): unlock it to in-between it",
        ),
        (
            [(None, False, False), ("Inner", False, False), ("Outer", False, True)],
            "layer 'Paint' is hidden (group 'Outer'): show it to in-between it",
        ),
        (
            [(None, False, False), ("Inner", False, True), ("Outer", True, False)],
            "layer 'Paint' is hidden (group 'Inner'): show it to in-between it",
        ),
        ([(None, False, False), ("Inner", False, False), ("Outer", False, False)], ""),
    ],
    ids=["plain", "locked", "hidden", "both", "locked-group", "hidden-outer", "innermost-first", "groups-fine"],
)
def test_a_layer_is_blocked_by_the_first_lock_or_hide_on_the_way_up(chain, text):
    assert reports.layer_blocked("Paint", chain) == text


def test_no_object_says_what_is_active_instead():
    assert reports.no_object() == ("No Grease Pencil object is active: select one and run Ball-morph In-between again")
    assert reports.no_object("Cube", "MESH") == (
        "The active object 'Cube' is a mesh, not a Grease Pencil object: make a Grease Pencil object "
        "active and run Ball-morph In-between again"
    )
    assert "is a light probe, not" in reports.no_object("Probe", "LIGHT_PROBE")


def test_no_layers_depends_on_the_layers_option():
    assert reports.no_layers("Drawing", "active") == "'Drawing' has no active layer: add or select a layer"
    assert reports.no_layers("Drawing", "all") == "'Drawing' has no layers: add a layer and draw keys on it"


def test_invalid_coordinates_lists_at_most_six_strokes():
    assert reports.invalid_coordinates(1, np.array([1])) == (
        "the key on frame 1 has points with invalid (NaN or infinite) coordinates in stroke(s) 1: "
        "redraw or delete those strokes"
    )
    assert "stroke(s) 0, 1, 2, 3, 4, 5: redraw" in reports.invalid_coordinates(3, range(9))


def test_fallback_texts():
    failed = reports.failure(FloatingPointError("simulated core bug"))
    assert failed == "FloatingPointError: simulated core bug"
    assert reports.fell_back("Laplace Blending", failed, "Linear Interpolation") == (
        "the Laplace Blending morph failed (FloatingPointError: simulated core bug): every in-between here "
        "was made with Linear Interpolation instead; please report this drawing"
    )
    assert reports.morph_failed("Ink 1\u21929", failed) == (
        "Ink 1\u21929: the morph failed (FloatingPointError: simulated core bug): nothing was written between "
        "these keys; try another morph, or simplify the strokes, and please report this drawing"
    )


def interval(keys=(1, 9), made=(), frame_count=0):
    layer = pairing.LayerKeys("Ink", tuple(keys), (), tuple(made))
    (found,) = pairing.intervals(layer, [(keys[0], keys[-1])], frame_count)
    return found


def test_what_was_written():
    assert reports.interval_reports(interval(), "Circular Ball-morph", []) == [
        ("INFO", "Ink 1\u21929: 7 in-between(s) on frame(s) 2\u20138 (Circular Ball-morph)")
    ]
    again = interval(made=(3, 5, 7), frame_count=3)
    assert reports.interval_reports(again, "Linear Ball-morph", []) == [
        ("INFO", "Ink 1\u21929: 3 in-between(s) on frame(s) 3, 5, 7 (Linear Ball-morph, replacing 3 earlier)")
    ]


def test_drawn_frames_warn_when_they_were_asked_for_and_inform_otherwise():
    skipped = reports.interval_reports(interval(keys=(1, 5, 9)), "Circular Ball-morph", [])
    assert skipped[1] == ("WARNING", "Ink 1\u21929: frame(s) 5 already drawn: left untouched")
    aside = reports.interval_reports(interval(keys=(1, 4, 9), frame_count=3), "Circular Ball-morph", [])
    assert aside[1] == ("INFO", "Ink 1\u21929: frame(s) 4 between the keys left untouched")


def test_the_morphs_messages_are_grouped_warnings_first_errors_as_warnings():
    messages = [
        ("INFO", "strokes paired by index"),
        ("WARNING", "stroke 2 of the second key has no partner: appears at the middle"),
        ("ERROR", "stroke 0 -> 0: failed"),
    ]
    got = reports.interval_reports(interval(), "Circular Ball-morph", messages)
    assert got[1:] == [
        (
            "WARNING",
            "Ink 1\u21929: stroke 2 of the second key has no partner: appears at the middle; stroke 0 -> 0: failed",
        ),
        ("INFO", "Ink 1\u21929: strokes paired by index"),
    ]


def test_long_message_lists_end_with_how_many_more():
    messages = [("INFO", f"note {i}") for i in range(9)]
    (_, (level, text)) = reports.interval_reports(interval(), "Circular Ball-morph", messages)
    assert level == "INFO"
    assert text == "Ink 1\u21929: note 0; note 1; note 2; note 3; note 4; note 5; and 3 more"


def test_summary_is_a_warning_when_anything_warned():
    assert reports.summary(7, 1, 0) == ("INFO", "Ball-morph In-between: 7 frame(s) on 1 layer(s)")
    assert reports.summary(6, 2, 1) == (
        "WARNING",
        "Ball-morph In-between: 6 frame(s) on 2 layer(s), 1 warning(s): see the Info editor",
    )
    assert [reports.is_warning(level) for level in reports.LEVELS] == [False, True, True]


def test_nothing_to_do_joins_every_reason():
    assert reports.nothing_to_do(["layer 'Ink' is locked", "layer 'Paint' has 1 keyframe(s)"]) == (
        "Nothing to in-between: layer 'Ink' is locked; layer 'Paint' has 1 keyframe(s)"
    )
    assert reports.write_failed(MemoryError("full")) == "Writing the in-betweens failed, nothing was changed: full"


# -- timing charts --------------------------------------------------------------------------------


def test_a_chart_is_named_in_what_was_written_and_a_kept_one_says_so():
    chart = pairing.Chart((0.1, 0.5, 0.9))
    (found,) = pairing.intervals(pairing.LayerKeys("Ink", (1, 9)), [(1, 9)], 0, {(1, 9): chart})
    assert reports.interval_reports(found, "Circular Ball-morph", []) == [
        ("INFO", "Ink 1\u21929: 3 in-between(s) on frame(s) 3, 5, 7 (Circular Ball-morph, timing chart 0.1 0.5 0.9)")
    ]
    (kept,) = pairing.intervals(pairing.LayerKeys("Ink", (1, 9)), [(1, 9)], 0, {(1, 9): pairing.Chart((0.5,), True)})
    assert reports.interval_reports(kept, "Circular Ball-morph", []) == [
        ("INFO", "Ink 1\u21929: 1 in-between(s) on frame(s) 5 (Circular Ball-morph)"),
        (
            "INFO",
            "Ink 1\u21929: timed by the chart 0.5 kept from an earlier run on these keys (type a chart to change it)",
        ),
    ]


def test_a_malformed_chart_says_what_is_wrong_and_what_a_chart_looks_like():
    assert reports.bad_chart("timing_chart: 'x' is not a number") == (
        "timing_chart: 'x' is not a number: nothing was written; write fractions between 0 and 1 in rising order, "
        "such as '0.1 0.3 0.6 0.9', or leave the chart empty"
    )


# -- pairs that stray from their keys --------------------------------------------------------------

TIMES, FRAMES = np.array([0.25, 0.5, 0.75]), np.array([3, 5, 7])


def pair(a, b, morphs=("circular-ball",), carrier=""):
    """A pair's report made with ``morphs`` on a ``carrier`` (a stroke without a partner when
    ``a`` or ``b`` is None)."""
    if a is None or b is None:
        outcome = core.PairOutcome.APPEAR if a is None else core.PairOutcome.DISAPPEAR
        return core.PairReport(a, b, outcome.value, outcome=outcome)
    used = core.PairMorphs(tuple(morphs), carrier)
    return core.PairReport(a, b, str(used), used=used)


@pytest.mark.parametrize(
    ("row", "stray"),
    [
        ([0.1, 0.2, 0.15], None),  # within 20% everywhere (20% itself is not beyond)
        ([0.1, -0.21, 0.05], ("ink 21% shorter than the keys' blend of lengths", 5)),
        ([0.3, 0.1, 0.05], ("ink 30% longer than the keys' blend of lengths", 3)),
        ([0.0, 0.1, np.inf], ("ink far longer than the keys' blend of lengths", 7)),
        ([np.nan, np.nan, 0.5], ("ink 50% longer than the keys' blend of lengths", 7)),
    ],
    ids=["on-the-blend", "shorter", "longer", "from-nothing", "missing-frames"],
)
def test_a_pair_strays_when_its_length_is_off_the_blend_by_more_than_a_fifth(row, stray):
    found = reports.strays([pair(0, 1)], "circular-ball", [row], TIMES, FRAMES)
    assert found == ([] if stray is None else [reports.Stray("stroke 1 -> 2", *stray)])
    assert reports.LENGTH_STRAY == 0.2


@pytest.mark.parametrize(
    ("morphs", "carrier", "asked", "why"),
    [
        (("circular-ball", "linear-interpolation"), "similarity", "circular-ball", "linear-interpolation"),
        (("composite-ball", "static"), "", "circular-ball", "composite-ball"),
        (("straight point motion",), "", "linear-ball", "straight point motion"),
        (("composite-ball", "linear-interpolation"), "", "parabolic-ball", "composite-ball and linear-interpolation"),
        (("linear-interpolation",), "", "linear-interpolation", None),  # asked for: no fallback
        (("arc-length",), "rigid", "circular-ball", None),
        (("circular-ball", "static"), "similarity", "circular-ball", None),
    ],
)
def test_a_pair_strays_when_it_fell_back_and_its_worst_frame_is_the_middle_when_its_length_is_fine(
    morphs, carrier, asked, why
):
    found = reports.strays([pair(2, 2, morphs, carrier)], asked, [[0.0, 0.0, 0.0]], TIMES, FRAMES)
    assert found == ([] if why is None else [reports.Stray("stroke 3 -> 3", f"made with {why} (a fallback)", 5)])


def test_a_fallback_that_also_strays_in_length_says_both_at_its_worst_frame():
    found = reports.strays(
        [pair(0, 0, ("linear-interpolation",))], "circular-ball", [[-0.2, -0.1, -0.3]], TIMES, FRAMES
    )
    assert found == [
        reports.Stray(
            "stroke 1 -> 1",
            "made with linear-interpolation (a fallback); ink 30% shorter than the keys' blend of lengths",
            7,
        )
    ]


@pytest.mark.parametrize(
    ("times", "frames", "middle"),
    [([0.25, 0.5, 0.75], [3, 5, 7], 5), ([0.2, 0.4, 0.6, 0.8], [2, 3, 4, 5], 4), ([0.1, 0.2], [2, 3], 3)],
)
def test_a_stroke_without_a_partner_is_not_a_stray_its_morph_warning_says_it_once(times, frames, middle):
    pairs = [pair(3, None), pair(None, 1)]
    found = reports.strays(pairs, "circular-ball", np.full((2, len(times)), np.nan), times, frames)
    assert found == []


def test_strays_come_worst_first_fallbacks_and_lost_partners_before_lengths():
    pairs = [pair(0, 0), pair(1, 1), pair(2, 2, ("linear-interpolation",)), pair(3, 3), pair(None, 4)]
    rows = [[0.25, 0, 0], [0, 0.6, 0], [0, 0, 0], [0.01, 0, 0], [np.nan] * 3]
    found = reports.strays(pairs, "circular-ball", rows, TIMES, FRAMES)
    assert [s.what for s in found] == ["stroke 3 -> 3", "stroke 2 -> 2", "stroke 1 -> 1"]
    assert [s.indices for s in found] == [(2, 2), (1, 1), (0, 0)]
    assert reports.strays(pairs, "circular-ball", np.zeros((5, 0)), [], []) == []


def test_stray_reports_list_a_few_and_sum_up_the_rest():
    found = [
        reports.Stray(f"stroke {i} -> {i}", "ink 30% shorter than the keys' blend of lengths", 3 + i % 3)
        for i in range(7)
    ]
    got = reports.stray_reports("Ink 1\u21929", found)
    assert len(got) == reports.STRAYS_LISTED + 1 and all(level == "WARNING" for level, _ in got)
    assert got[0][1] == (
        "Ink 1\u21929: stroke 0 -> 0 strays from its keys (ink 30% shorter than the keys' blend of lengths), "
        "most on frame 3: draw a breakdown key on frame 3"
    )
    assert got[-1][1] == (
        "Ink 1\u21929: 4 more stroke pair(s) stray from their keys, most on frame(s) 3\u20135: "
        "breakdown keys there would help"
    )
    assert reports.stray_reports("Ink 1\u21929", found[:3]) == got[:3]
    assert reports.stray_reports("Ink 1\u21929", []) == []


def test_what_was_written_ends_with_the_strays():
    found = [reports.Stray("stroke 0 -> 0", "no partner", 5)]
    got = reports.interval_reports(interval(), "Circular Ball-morph", [("INFO", "note")], found)
    assert got[-1] == reports.stray_reports("Ink 1\u21929", found)[0] and got[-2] == ("INFO", "Ink 1\u21929: note")


def test_joined_smoothly_names_the_smooth_keys_and_the_corners():
    assert reports.joined_smoothly([7], []) == "arcs through the keys: joined smoothly at frame 7"
    assert reports.joined_smoothly([], [7]) == "arcs through the keys: the Extreme key at frame 7 keeps its corner"
    assert reports.joined_smoothly([13], [7]).endswith("frame 13; the Extreme key at frame 7 keeps its corner")
    assert reports.joined_smoothly([], []) == ""
