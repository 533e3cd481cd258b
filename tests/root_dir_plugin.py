"""pytest plugin (``-p tests.root_dir_plugin``): the repository root is the add-on, not a test package.

The root holds the add-on's ``__init__.py`` (Blender's entry point, which imports bpy), so pytest
would collect the root as a package named after the checkout directory and import it: bpy loaded
into the core tests, and a collection error wherever that name is not a valid module name (a
clone in ``/tmp/tmp.XXXX``). A conftest.py cannot say otherwise for the directory it sits in, so
this is a plugin, loaded by the test commands (pyproject.toml, tools/run_tests.sh).
"""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.hookimpl(tryfirst=True)
def pytest_collect_directory(path, parent):
    """Collect the repository root as a plain directory."""
    if Path(path).resolve() == ROOT:
        return pytest.Dir.from_parent(parent, path=path)
    return None
