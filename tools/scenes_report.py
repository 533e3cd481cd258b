"""Every scene of tests/fixtures/scenes/ through the core and the Blender-like baseline: one table.

    python tools/scenes_report.py [NAME_PART ...] [--messages]
    python tools/scenes_report.py --xfail-table

Prints ``scene | figure | ours | baseline | goal | ok`` (ok: the core meets the goal; ``info``
for an informative figure; ``xfail`` marks a scene the tests expect to fail today) and a
summary line. Always exits 0: this is a measuring stick, not a test (tests/scenarios/test_scenes.py
asserts the figures). ``--messages`` adds the core's pairs and messages under each scene;
``--xfail-table`` prints ``scenes.XFAIL_TODAY`` as today's core would have it.
"""

import os
import sys
import textwrap
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The core from the repository root; the scenes from the test fixtures (the tests assert them).
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests", "fixtures")]

import scenes  # noqa: E402


def _rows(scene):
    keys = scene.key_drawings()
    start = time.perf_counter()
    frames, result = scene.run_core()
    seconds = time.perf_counter() - start
    ours = scene.figures(keys, frames)
    theirs = scene.figures(keys, scene.run_baseline())
    return ours, theirs, result, seconds


def print_table(lines):
    """Print rows of strings as a table (the first row is the header)."""
    widths = [max(len(row[i]) for row in lines) for i in range(len(lines[0]))]
    for n, row in enumerate(lines):
        print(" | ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip())
        if n == 0:
            print("-+-".join("-" * w for w in widths))


def xfail_table():
    """Print ``XFAIL_TODAY`` as it should read for today's core (to paste into tests/fixtures/scenes/registry.py)."""
    print("XFAIL_TODAY = {")
    for name, scene in scenes.SCENES.items():
        frames, _ = scene.run_core()
        missed = [str(f) for f in scene.figures(scene.key_drawings(), frames) if not (f.ok or f.informative)]
        if missed:
            lines = textwrap.wrap("; ".join(missed), 96, drop_whitespace=False)
            print(f"    {name!r}: (\n" + "".join(f"        {line!r}\n" for line in lines) + "    ),")
    print("}")
    return 0


def main(argv):
    if "--xfail-table" in argv:
        return xfail_table()
    show_messages = "--messages" in argv
    wanted = [a for a in argv if not a.startswith("--")]
    chosen = [s for name, s in scenes.SCENES.items() if not wanted or any(w in name for w in wanted)]
    lines = [("scene", "figure", "ours", "baseline", "goal", "ok")]
    failed, total, started = [], 0.0, time.perf_counter()
    for scene in chosen:
        ours, theirs, result, seconds = _rows(scene)
        total += seconds
        for n, (mine, base) in enumerate(zip(ours, theirs)):
            mark = "info" if mine.informative else ("ok" if mine.ok else "FAIL")
            if n == 0 and scene.name in scenes.XFAIL_TODAY:
                mark += " (xfail)"
            name = f"{scene.name} ({seconds:.1f}s)" if n == 0 else ""
            lines.append((name, mine.name, mine.shown, base.shown + ("" if base.ok else " ✗"), mine.goal, mark))
        if not all(f.ok or f.informative for f in ours):
            failed.append(scene.name)
        if show_messages:
            pairs = ", ".join(f"{p.stroke_a}->{p.stroke_b} {p.method}" for p in result.pairs)
            lines.append(("", "pairs", pairs[:100], "", "", ""))
            lines += [("", m.level.lower(), m.text[:100], "", "", "") for m in result.messages]
    print_table(lines)
    print(
        f"\n{len(chosen) - len(failed)} of {len(chosen)} scenes meet every goal; core time {total:.1f}s, "
        f"whole run {time.perf_counter() - started:.1f}s. Failing: {', '.join(failed) or 'none'}"
    )
    stale = sorted(set(scenes.XFAIL_TODAY) - set(failed) & {s.name for s in chosen})
    if stale:
        print(f"Marked xfail but passing now (remove the marker): {', '.join(stale)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
