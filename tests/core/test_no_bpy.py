"""The core is pure numpy: importing every module of it never imports bpy (Blender ships the
same numpy, and the core also runs in plain CPython)."""

import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

SCRIPT = """
import importlib, pkgutil, sys
import ballmorph_core
for m in pkgutil.walk_packages(ballmorph_core.__path__, prefix="ballmorph_core."):
    importlib.import_module(m.name)
print(len(sys.modules), sorted(n for n in sys.modules if n == "bpy" or n.startswith(("bpy.", "_bpy"))))
"""


def test_importing_every_core_module_never_imports_bpy():
    # A fresh interpreter: this test process may have imported anything.
    out = subprocess.run([sys.executable, "-c", SCRIPT], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().endswith("[]"), out.stdout
