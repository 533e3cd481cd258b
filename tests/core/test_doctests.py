"""Run the examples in the core's docstrings (imported as the top-level package)."""

import doctest
import importlib
import pkgutil

import pytest

import ballmorph_core

MODULES = sorted(m.name for m in pkgutil.walk_packages(ballmorph_core.__path__, prefix="ballmorph_core."))


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
