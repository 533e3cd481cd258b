"""How the ball-map's run time grows with the vertex count (issues 2 and 6), in plain CPython.

Times ``ballmorph_core.ball_map(P, Q, closed=True)`` on two nested, disjoint wobbly loops of
500, 1000, 2000 and 4000 vertices each (the paper's configuration 1, the common case of an
outline morphing into the next key's outline) and prints the median time and its growth from
the previous size. Two spacings are timed:

- ``default``: the call as the operator makes it. The default sample spacing is the median edge
  length, but at most ``geometry.polyline.DEFAULT_SAMPLES_MAX`` samples per curve, so beyond that the
  sample count stops growing and only the vertex count does.
- ``per-vertex``: spacing = the median edge length, unclamped, so the samples grow with the
  vertices too (the harder test of the algorithm's scaling).

Usage (``make bench`` runs it through tools/benchmark.py, which embeds the table in
docs/benchmark.md)::

    $(tools/bootstrap.sh 5.0.1) tools/bench_ballmap.py [--sizes 500,1000,2000,4000] [--markdown | --json]
"""

import argparse
import json
import os
import statistics
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

import ballmorph_core as bm  # noqa: E402  (after the path set-up)
from ballmorph_core.geometry.polyline import default_spacing  # noqa: E402

SIZES = (500, 1000, 2000, 4000)
SPACINGS = ("default", "per-vertex")
#: The goal of issue 6: time(4000) / time(2000) at most this.
GROWTH_GOAL = 2.5
# Repeats: at least MIN_RUNS, then until BUDGET seconds are spent, at most MAX_RUNS.
MIN_RUNS, MAX_RUNS, BUDGET = 5, 15, 2.0


def loops(n):
    """Two nested disjoint loops of ``n`` vertices each: a wobbly outline inside a rounder one.

    Returns
    -------
    P, Q : ndarray, shape (n, 2)
    """
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    r_p = 1.0 + 0.06 * np.cos(3 * t) + 0.02 * np.sin(5 * t + 0.4)
    r_q = 1.6 + 0.05 * np.sin(2 * t) + 0.02 * np.cos(4 * t + 1.0)
    P = np.c_[1.1 * r_p * np.cos(t), r_p * np.sin(t)]
    Q = np.c_[1.1 * r_q * np.cos(t + 0.3) + 0.05, r_q * np.sin(t + 0.3)]
    return P, Q


def _spacing(P, Q, which):
    if which == "default":
        return None
    edges = np.linalg.norm(np.diff(np.concatenate([P, P[:1]]), axis=0), axis=1)
    return float(np.median(edges))


def time_ball_map(n, which):
    """Median run time of one ball-map (seconds), the run count and the correspondence size."""
    P, Q = loops(n)
    spacing = _spacing(P, Q, which)
    corr = bm.ball_map(P, Q, closed=True, spacing=spacing)  # warm-up; also checks the pair works
    times = []
    while len(times) < MIN_RUNS or (sum(times) < BUDGET and len(times) < MAX_RUNS):
        start = time.perf_counter()
        bm.ball_map(P, Q, closed=True, spacing=spacing)
        times.append(time.perf_counter() - start)
    used = default_spacing(P, Q, closed=True) if spacing is None else spacing
    return statistics.median(times), len(times), len(corr), used


def run(sizes=SIZES):
    """Rows ``{spacing, n, seconds, runs, samples, growth}`` for every spacing and size."""
    rows = []
    for which in SPACINGS:
        previous = None
        for n in sizes:
            seconds, runs, samples, used = time_ball_map(n, which)
            growth = seconds / previous if previous else None
            rows.append(
                {
                    "spacing": which,
                    "n": n,
                    "seconds": seconds,
                    "runs": runs,
                    "samples": samples,
                    "h": used,
                    "growth": growth,
                }
            )
            previous = seconds
    return rows


def description():
    """What is timed (this module's docstring without its title and usage), for reports."""
    return __doc__.split("\n\n", 1)[1].split("\n\nUsage")[0].strip()


def goal(rows, which="default", small=2000, large=4000):
    """time(large) / time(small) for one spacing, or None if either size was not run."""
    t = {r["n"]: r["seconds"] for r in rows if r["spacing"] == which}
    return t[large] / t[small] if small in t and large in t else None


def markdown(rows):
    """The results as a markdown table plus the goal lines."""
    lines = [
        "| spacing | vertices per loop | samples | median time | runs | growth vs previous size |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        growth = f"{r['growth']:.2f}x" if r["growth"] else ""
        lines.append(
            f"| {r['spacing']} | {r['n']} | {r['samples']} | {r['seconds'] * 1e3:.1f} ms | {r['runs']} | {growth} |"
        )
    lines.append("")
    for which in SPACINGS:
        ratio = goal(rows, which)
        if ratio is not None:
            verdict = "pass" if ratio <= GROWTH_GOAL else "FAIL"
            lines.append(
                f"- {which} spacing: time(4000) / time(2000) = **{ratio:.2f}x** (goal <= {GROWTH_GOAL}x: {verdict})"
            )
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", default=",".join(map(str, SIZES)), help="vertex counts, comma-separated")
    parser.add_argument("--markdown", action="store_true", help="print only the markdown table")
    parser.add_argument("--json", action="store_true", help="print the rows as JSON (tools/benchmark.py reads them)")
    args = parser.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",") if s]
    rows = run(sizes)
    if args.json:
        print(json.dumps(rows))
        return 0
    if not args.markdown:
        print(f"ball_map of two nested loops, numpy {np.__version__}, Python {sys.version.split()[0]}")
    print(markdown(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
