"""Import the add-on's bpy-free modules in plain CPython, from the add-on package itself.

The checkout's folder may have any name, so the add-on's own ``__init__`` is loaded under the
name ``PACKAGE`` (it imports no bpy until ``register()``); then ``addon_logic`` and the vendored
core import through it with their relative imports (``from ..ballmorph_core import
frame_times``) resolved inside the add-on, exactly as in Blender.
"""

import importlib
import importlib.util
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PACKAGE = "ballmorph_inbetween_plain"
#: The add-on's modules that must never import bpy.
MODULES = (
    "addon_logic.pairing",
    "addon_logic.playhead",
    "addon_logic.reports",
    "addon_logic.report_data",
    "addon_logic.charts",
    "addon_logic.id_keys",
    "addon_logic.hint_numbers",
    "addon_logic.warned",
)


def load(name):
    """The add-on's module ``name`` (``'addon_logic.pairing'``), imported without bpy."""
    if PACKAGE not in sys.modules:
        spec = importlib.util.spec_from_file_location(
            PACKAGE, os.path.join(ROOT, "__init__.py"), submodule_search_locations=[ROOT]
        )
        package = importlib.util.module_from_spec(spec)
        sys.modules[PACKAGE] = package
        spec.loader.exec_module(package)
    return importlib.import_module(f"{PACKAGE}.{name}")
