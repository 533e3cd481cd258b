"""Write the golden in-betweens (tests/scenarios/golden/) from the current core.

Run it only in a commit that changes behaviour on purpose and says why: the golden test
(tests/scenarios/test_golden.py) holds every later change to these frames.

    python tools/golden.py --write             # every case
    python tools/golden.py --write CASE ...    # only these
"""

import argparse
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests", "fixtures")]

import golden_cases  # noqa: E402

import ballmorph_core as bm  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="overwrite the stored frames")
    parser.add_argument("cases", nargs="*", help="only these cases (default: every one)")
    args = parser.parse_args(argv)
    known = {name for name, *_ in golden_cases.cases()}
    unknown = sorted(set(args.cases) - known)
    if unknown:
        parser.error(f"unknown case(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}")
    if not args.write:
        parser.error("nothing to do: pass --write to overwrite tests/scenarios/golden/")
    os.makedirs(golden_cases.DIRECTORY, exist_ok=True)
    for name, key_a, key_b, options in golden_cases.cases():
        if args.cases and name not in args.cases:
            continue
        start = time.perf_counter()
        result = bm.inbetween(key_a, key_b, golden_cases.TIMES, **options)
        np.savez_compressed(golden_cases.path(name), **golden_cases.record(result))
        print(f"{name}: {sum(len(f.positions) for f in result.frames)} points, {time.perf_counter() - start:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
