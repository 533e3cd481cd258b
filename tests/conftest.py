"""Shared set-up of the plain-CPython suites (tests/core, tests/scenarios, tests/tools, tests/addon).

tests/core mirrors ballmorph_core's packages (the test of ``drawing/pairing/matching.py`` is
``tests/core/drawing/pairing/test_matching.py``); tests/scenarios holds whole-drawing suites
(golden frames, scenes, real drawings, bad input); tests/fixtures the drawings they share.
"""

import os
import sys

from hypothesis import HealthCheck, settings

_TESTS = os.path.dirname(os.path.abspath(__file__))
_ROOT = os.path.dirname(_TESTS)
# The core is imported as a top-level package from the repository root (and the dev tools, for
# tests/tools, as the package ``tools``); the shared drawings (shapes, the golden cases, the demo's
# shots, the benchmark's drawings, the scenes) sit in tests/fixtures, which the tools read too.
sys.path[:0] = [_ROOT, os.path.join(_TESTS, "fixtures")]

settings.register_profile("ci", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("fuzz", max_examples=3000, deadline=None, suppress_health_check=list(HealthCheck))
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
