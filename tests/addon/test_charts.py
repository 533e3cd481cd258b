"""Timing charts kept with their intervals (operators/charts.py), in plain CPython.

A dict stands in for the Grease Pencil data-block: the module uses only what both offer.
"""

import numpy as np
import pytest
from addon_package import load

charts = load("addon_logic.charts")
pairing = load("addon_logic.pairing")
id_keys = load("addon_logic.id_keys")


def written(chart, layer="Ink", a=1, b=9):
    return pairing.Interval(layer, a, b, np.array([5]), np.array([0.5]), chart=chart)


def test_the_option_chart_times_every_pair_and_is_not_marked_kept():
    found, notes = charts.charts_for({}, "Ink", [(1, 9), (9, 13)], " 0.1, 0.5 0.9 ")
    assert {pair: chart.fractions for pair, chart in found.items()} == {
        (1, 9): (0.1, 0.5, 0.9),
        (9, 13): (0.1, 0.5, 0.9),
    }
    assert not any(chart.kept for chart in found.values()) and notes == []


def test_a_chart_too_long_for_one_pair_refuses_the_run_naming_the_interval():
    with pytest.raises(ValueError) as refused:
        charts.charts_for({}, "Ink", [(1, 9), (9, 12)], "0.2 0.4 0.6")
    assert str(refused.value) == (
        "Ink 9\u219212: timing_chart: 3 fractions but only 2 frame(s) between the keys (one in-between per fraction): "
        "nothing was written; give fewer fractions, or keys farther apart"
    )


def test_without_an_option_chart_the_kept_one_of_each_pair_is_used():
    data = {}
    charts.keep(data, written(pairing.Chart((0.1, 0.5, 0.9))))
    charts.keep(data, written(pairing.Chart((0.5,)), layer="Paint"))
    assert data == {charts.PROPERTY: {"Ink:1-9": "0.1 0.5 0.9", "Paint:1-9": "0.5"}}
    found, notes = charts.charts_for(data, "Ink", [(1, 9), (9, 13)], "")
    assert list(found) == [(1, 9)] and found[1, 9] == pairing.Chart((0.1, 0.5, 0.9), kept=True) and notes == []
    assert charts.charts_for(data, "Ink", [(1, 9)], "0.3")[0][1, 9] == pairing.Chart((0.3,))  # the option wins


def test_keeping_replaces_the_earlier_chart_and_an_interval_without_one_changes_nothing():
    data = {charts.PROPERTY: {"Ink:1-9": "0.1 0.5 0.9"}}
    charts.keep(data, written(pairing.Chart((0.25, 0.75))))
    charts.keep(data, written(None, a=9, b=13))
    assert data == {charts.PROPERTY: {"Ink:1-9": "0.25 0.75"}}
    empty = {}
    charts.keep(empty, written(None))
    assert empty == {}


@pytest.mark.parametrize(("kept", "problem"), [("0.5 0.2", "0.2 comes after 0.5"), ("0.1 0.2 0.3", "3 fractions")])
def test_a_kept_chart_that_no_longer_reads_is_ignored_with_a_warning(kept, problem):
    data = {charts.PROPERTY: {"Ink:1-4": kept}}
    found, notes = charts.charts_for(data, "Ink", [(1, 4)], "")
    assert found == {}
    [(level, text)] = notes
    assert level == "WARNING" and text.startswith(f"Ink 1\u21924: the timing chart kept here ('{kept}') was ignored (")
    assert problem in text and text.endswith("type the chart again")


def test_a_kept_value_that_is_not_a_chart_is_no_chart():
    data = {charts.PROPERTY: {"Ink:1-9": 7, "Ink:9-13": "  "}}
    assert charts.charts_for(data, "Ink", [(1, 9), (9, 13)], "") == ({}, [])


def test_long_layer_names_get_a_short_stand_in_key():
    name = "a layer name far longer than Blender's sixty-three bytes of an ID property name"
    key = charts.interval_key(name, 1, 9)
    assert key.startswith("~") and len(key.encode()) <= id_keys.MAX_KEY
    assert key != charts.interval_key(name, 1, 10)
    data = {}
    charts.keep(data, written(pairing.Chart((0.5,)), layer=name))
    assert charts.kept(data, name, 1, 9) == "0.5"
    assert id_keys.id_key("\u00e9" * 31) == "\u00e9" * 31 and id_keys.id_key("\u00e9" * 32).startswith("~")
