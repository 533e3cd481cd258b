"""The strokes the last run warned about, kept for Select Warned Strokes (addon_logic/warned.py).

A dict stands in for the Grease Pencil data-block: the module uses only what both offer.
"""

from addon_package import load

warned = load("addon_logic.warned")
report_data = load("addon_logic.report_data")
reports = load("addon_logic.reports")
Report, StrokeRef = report_data.Report, report_data.StrokeRef


def test_only_warnings_with_a_layer_and_strokes_are_kept_once_each_in_order():
    found = [
        Report(reports.WARNING, "a", layer="Ink", strokes=(StrokeRef(9, 3), StrokeRef(1, 2))),
        Report(reports.ERROR, "b", layer="Ink", strokes=(StrokeRef(1, 2),)),
        Report(reports.INFO, "c", layer="Ink", strokes=(StrokeRef(1, 1),)),  # information names no problem
        Report(reports.WARNING, "d", strokes=(StrokeRef(1, 4),)),  # no layer: cannot be found
        (reports.WARNING, "a plain pair"),
        Report(reports.WARNING, "e", layer="Paint", strokes=(StrokeRef(2, 1),)),
    ]
    assert warned.warned_strokes(found) == {"Ink": ((1, 2), (9, 3)), "Paint": ((2, 1),)}


def test_a_run_replaces_the_record_and_one_without_warned_strokes_removes_it():
    data = {}
    warned.keep(data, [Report(reports.WARNING, "a", layer="Ink", strokes=(StrokeRef(1, 2),))])
    assert data == {warned.PROPERTY: {"Ink": [1, 2]}}
    warned.keep(data, [Report(reports.WARNING, "b", layer="Paint", strokes=(StrokeRef(5, 1),))])
    assert warned.strokes_of(data, "Ink") == () and warned.strokes_of(data, "Paint") == ((5, 1),)
    warned.keep(data, [Report(reports.WARNING, "no stroke", layer="Ink")])
    assert data == {}


def test_a_long_layer_name_is_kept_under_its_stand_in_and_found_again():
    name = "a layer named at great length " * 3
    data = {}
    warned.keep(data, [Report(reports.WARNING, "a", layer=name, strokes=(StrokeRef(3, 7),))])
    assert all(len(key.encode()) <= 63 for key in data[warned.PROPERTY])
    assert warned.strokes_of(data, name) == ((3, 7),)


def test_interval_reports_lend_the_morphs_messages_strokes_to_the_warning_that_says_them():
    pairing = load("addon_logic.pairing")
    import numpy as np

    interval = pairing.Interval("Ink", 1, 9, np.array([5]), np.array([0.5]))
    messages = [
        Report(reports.WARNING, "stroke 2 of the first key has no partner: ...", strokes=(StrokeRef(1, 2),)),
        Report(reports.INFO, "stroke 1 -> 1: flipped", strokes=(StrokeRef(1, 1), StrokeRef(9, 1))),
        (reports.WARNING, "a plain warning"),
    ]
    found = reports.interval_reports(interval, "Circular Ball-morph", messages)
    morph = [report for report in found if report.kind == "morph"]
    assert [(report.level, report.strokes) for report in morph] == [
        (reports.WARNING, ((1, 2),)),
        (reports.INFO, ((1, 1), (9, 1))),
    ]
    assert warned.warned_strokes(found) == {"Ink": ((1, 2),)}
