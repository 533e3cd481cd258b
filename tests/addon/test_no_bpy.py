"""The add-on's Blender-free logic (addon_logic: which keys pair up, what the reports say) never imports bpy."""

import doctest
import os
import subprocess
import sys

import pytest
from addon_package import MODULES, load

HERE = os.path.dirname(os.path.abspath(__file__))

SCRIPT = f"""
import sys
sys.path.insert(0, {HERE!r})
from addon_package import MODULES, load
for name in MODULES:
    load(name)
print(sorted(n for n in sys.modules if n == "bpy" or n.startswith(("bpy.", "_bpy"))))
"""


def test_importing_the_decisions_never_imports_bpy():
    # A fresh interpreter of the bpy venv (bpy is importable there): only an import of it counts.
    out = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]", out.stdout


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(load(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0
