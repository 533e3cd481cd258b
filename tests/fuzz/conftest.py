"""Hypothesis profiles of the fuzz target (tests/fuzz).

``fuzz-ci`` (the default) is the short, derandomised profile CI runs with the core tests;
``HYPOTHESIS_PROFILE=fuzz`` (``make fuzz``) loads ``fuzz``: thousands of examples per test.
The fuzz tests apply the chosen profile explicitly (``fuzz_strategies.fuzz_settings``), so
running tests/core and tests/fuzz in one process leaves the core suite's own profile alone.
"""

import os
import sys

import pytest
from hypothesis import HealthCheck, Phase, settings

# No 'explain' phase: it re-runs a failing example hundreds of times, minutes on slow drawings.
PHASES = (Phase.explicit, Phase.reuse, Phase.generate, Phase.target, Phase.shrink)

# The core is imported as a top-level package from the repository root; the strategies module
# sits beside this file.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

settings.register_profile(
    "fuzz-ci",
    max_examples=int(os.environ.get("FUZZ_CI_EXAMPLES", "100")),
    deadline=None,
    derandomize=True,
    phases=PHASES,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large],
)
# The long profile draws fresh examples every run (no example database): a failure prints its
# @reproduce_failure blob, and known defects are pinned by deterministic tests in tests/core.
settings.register_profile(
    "fuzz",
    max_examples=int(os.environ.get("FUZZ_EXAMPLES", "3000")),
    deadline=None,
    database=None,
    phases=PHASES,
    print_blob=True,
    suppress_health_check=list(HealthCheck),
)
if os.environ.get("HYPOTHESIS_PROFILE") == "fuzz":
    settings.load_profile("fuzz")


def pytest_collection_modifyitems(items):
    """Every fuzz test runs with RuntimeWarnings as errors (issue 41): an overflow, a division
    by zero or an invalid value in the core is a defect even where the result comes out finite."""
    here = os.path.dirname(os.path.abspath(__file__))
    for item in items:
        if str(item.path).startswith(here):
            item.add_marker(pytest.mark.filterwarnings("error::RuntimeWarning"))
