"""Import the add-on's bpy-free modules in plain CPython, as the add-on holds them.

The add-on's package ``__init__`` (and ``operators/__init__``) register Blender classes, so they
import bpy. These tests stand in for both with empty packages pointing at the same directories,
then import the bpy-free modules through them: the modules' relative imports
(``from ..ballmorph_core import frame_times``, ``from . import reports``) resolve inside the
add-on, exactly as in Blender, and nothing else of the add-on runs.
"""

import importlib
import os
import sys
import types

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PACKAGE = "ballmorph_inbetween_plain"
#: The add-on's modules that must never import bpy.
MODULES = (
    "operators.pairing",
    "operators.playhead",
    "operators.reports",
    "operators.report_data",
    "operators.charts",
    "operators.id_keys",
    "operators.hint_numbers",
)


def _stand_in(name, path):
    if name not in sys.modules:
        package = types.ModuleType(name)
        package.__path__ = [path]
        sys.modules[name] = package


def load(name):
    """The add-on's module ``name`` (``'operators.pairing'``), imported without bpy."""
    _stand_in(PACKAGE, ROOT)
    _stand_in(f"{PACKAGE}.operators", os.path.join(ROOT, "operators"))
    return importlib.import_module(f"{PACKAGE}.{name}")
