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
# The core is imported as a top-level package from the repository root; the shared drawings
# (shapes, the golden cases) sit in tests/fixtures.
sys.path[:0] = [_ROOT, os.path.join(_TESTS, "fixtures")]
# The dev tools' modules (the benchmark's drawings, the scenes, the real-data reader) for the tests of them.
sys.path.append(os.path.join(_ROOT, "tools"))

settings.register_profile("ci", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("fuzz", max_examples=3000, deadline=None, suppress_health_check=list(HealthCheck))
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
