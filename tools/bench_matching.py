"""How stroke matching's run time grows with the stroke count on look-alike strokes (issue 14:
no input superlinear), in plain CPython.

Times ``match_strokes`` on short hatch lines (2-5 points) on a grid, redrawn a little moved and
listed in another order: the case where the optimal assignment does the most work. Every stroke
looks like every other: the drawing order fitted to a shuffled key would crowd key A together
(the matching leaves that guess out, as the order accounts for nothing), and every stroke has
neighbours its pair could be mistaken for. The matching prices each stroke's neighbours first
and the whole table only where those do not settle a motion, and beyond 400 strokes a stroke's
neighbourhood follows the strokes' spacing, not the drawing's size (so it holds as many strokes
however many are drawn); the goal asks it to grow no faster than the ball-map's own bar when
the count doubles.

With ``--moving`` it times the benchmark's moving drawing instead (issue 41): open strokes on a
grid, each of key B moved, turned, scaled and wobbled (tools/bench_drawings.py), 400 to 6,400
strokes, in drawing order: the tables of more pairs than ``costs.MATCH_WHOLE_MOST`` are never
laid out whole, and each doubling of the strokes should at most about double the time.

Usage (``make bench`` runs it through tools/benchmark.py, which embeds the tables in
docs/benchmark.md)::

    $(tools/bootstrap.sh 5.0.1) tools/bench_matching.py [--moving] [--sizes 250,500,1000] [--markdown | --json]
"""

import argparse
import json
import os
import statistics
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The core from the repository root; the drawings from the test fixtures, which the tests share.
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests", "fixtures")]

from bench_drawings import make_keys, reordered_hatching  # noqa: E402  (after the path set-up)

from ballmorph_core.drawing.pairing.matching import match_strokes  # noqa: E402

SIZES = (250, 500, 1000)
#: The goal: time(1000) / time(500) at most this (the ball-map's bar, bench_ballmap.GROWTH_GOAL).
GROWTH_GOAL = 2.5
#: The moving drawing (``--moving``): stroke counts, points per stroke, and the goal: time at
#: most this many times the previous size's per doubling (issue 41).
MOVING_SIZES = (400, 800, 1600, 3200, 6400)
MOVING_POINTS = 20
MOVING_GOAL = 2.3
# Repeats: at least MIN_RUNS, then until BUDGET seconds are spent, at most MAX_RUNS.
MIN_RUNS, MAX_RUNS, BUDGET = 2, 9, 2.0


def time_matching(n):
    """Median seconds of one ``match_strokes`` of ``n`` reordered hatch lines, and the run count.

    Raises
    ------
    AssertionError
        If the matching does not pair every line with its redrawn self (a wrong answer is not
        timed).
    """
    a, b, perm = reordered_hatching(n)
    flags = [False] * n
    times = []
    while len(times) < MIN_RUNS or (sum(times) < BUDGET and len(times) < MAX_RUNS):
        start = time.perf_counter()
        m = match_strokes(a, b, flags, flags)
        times.append(time.perf_counter() - start)
    assert m.pairs == sorted((int(p), j, False) for j, p in enumerate(perm)), f"{n} lines mismatched"
    return statistics.median(times), len(times)


def time_moving(n):
    """Median seconds of one ``match_strokes`` of the moving drawing of ``n`` open strokes, the
    run count, and the most pairs priced at one motion.

    Raises
    ------
    AssertionError
        If the matching does not pair every stroke with its own moved self.
    """
    a, b = make_keys("open", n, MOVING_POINTS)
    flags = [False] * n
    times = []
    while len(times) < MIN_RUNS or (sum(times) < BUDGET and len(times) < MAX_RUNS):
        start = time.perf_counter()
        m = match_strokes(a, b, flags, flags)
        times.append(time.perf_counter() - start)
    assert m.pairs == [(i, i, False) for i in range(n)], f"{n} moving strokes mismatched"
    return statistics.median(times), len(times), m.priced


def run(sizes=SIZES, moving=False):
    """Rows ``{n, seconds, runs, growth}`` (and ``priced`` when ``moving``), one per stroke count."""
    rows, previous = [], None
    for n in sizes:
        if moving:
            seconds, runs, priced = time_moving(n)
        else:
            (seconds, runs), priced = time_matching(n), None
        row = {"n": n, "seconds": seconds, "runs": runs, "growth": seconds / previous if previous else None}
        if moving:
            row["priced"] = priced
        rows.append(row)
        previous = seconds
    return rows


def moving_goal(rows):
    """The largest time ratio per doubling of the strokes (float), or None if fewer than two sizes."""
    growth = [r["growth"] for r in rows if r["growth"] is not None]
    return max(growth) if growth else None


def markdown_moving(rows):
    """The moving drawing's results as a markdown table plus the goal line."""
    lines = [
        "| strokes | median time | runs | pairs priced per stroke (most at one motion) | ratio per doubling |",
        "|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        growth = f"{r['growth']:.2f}x" if r["growth"] else ""
        lines.append(
            f"| {r['n']:,} | {r['seconds'] * 1e3:.0f} ms | {r['runs']} | {r['priced'] / r['n']:.1f} | {growth} |"
        )
    worst = moving_goal(rows)
    if worst is not None:
        verdict = "pass" if worst <= MOVING_GOAL else "FAIL"
        lines += ["", f"- largest ratio per doubling = **{worst:.2f}x** (goal <= {MOVING_GOAL}x: {verdict})"]
    return "\n".join(lines)


def description():
    """What is timed (this module's docstring without its title and usage), for reports."""
    return __doc__.split("\n\n", 1)[1].split("\n\nUsage")[0].strip()


def moving_description():
    """What ``--moving`` times (the docstring's paragraph on it), for reports."""
    text = __doc__.split("With ``--moving`` ", 1)[1].split("\n\nUsage")[0]
    return text.replace("it times", "Times", 1).replace(" instead", "", 1).strip()


def goal(rows, small=500, large=1000):
    """time(large) / time(small), or None if either count was not run."""
    t = {r["n"]: r["seconds"] for r in rows}
    return t[large] / t[small] if small in t and large in t else None


def markdown(rows):
    """The results as a markdown table plus the goal line."""
    lines = ["| hatch lines | median time | runs | growth vs previous size |", "|---:|---:|---:|---:|"]
    for r in rows:
        growth = f"{r['growth']:.2f}x" if r["growth"] else ""
        lines.append(f"| {r['n']} | {r['seconds'] * 1e3:.0f} ms | {r['runs']} | {growth} |")
    ratio = goal(rows)
    if ratio is not None:
        verdict = "pass" if ratio <= GROWTH_GOAL else "FAIL"
        lines += ["", f"- time(1000) / time(500) = **{ratio:.2f}x** (goal <= {GROWTH_GOAL}x: {verdict})"]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--moving", action="store_true", help="time the moving drawing (issue 41) instead")
    parser.add_argument("--sizes", help="stroke counts, comma-separated (default: the kind's own)")
    parser.add_argument("--markdown", action="store_true", help="print only the markdown table")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON (tools/benchmark.py reads them)")
    args = parser.parse_args(argv)
    if args.sizes is None:
        args.sizes = ",".join(map(str, MOVING_SIZES if args.moving else SIZES))
    try:
        sizes = [int(s) for s in args.sizes.split(",") if s]
    except ValueError:
        parser.error(f"--sizes: expected comma-separated stroke counts, got {args.sizes!r}")
    if not sizes or min(sizes) < 1:
        parser.error(f"--sizes: expected positive stroke counts, got {args.sizes!r}")
    rows = run(sizes, args.moving)
    if args.json:
        print(json.dumps(rows))
        return 0
    what = "the moving drawing" if args.moving else "reordered hatch lines"
    if not args.markdown:
        print(f"match_strokes of {what}, numpy {np.__version__}, Python {sys.version.split()[0]}")
    print(markdown_moving(rows) if args.moving else markdown(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
