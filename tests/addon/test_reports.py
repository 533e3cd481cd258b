"""What the add-on tells the animator (operators/reports.py), in plain CPython."""

import numpy as np
import pytest
from bpy_free import load

reports = load("operators.reports")
pairing = load("operators.pairing")


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
