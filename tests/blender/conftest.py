"""Blender tests: run inside ``bpy`` (Blender as a Python module) in background mode.

Every test starts from factory settings with the add-on enabled from a development extension
repository (a symlink to this checkout), and disables it afterwards: bpy 4.5 hangs at process
exit while a Python operator class is still registered.
"""

import importlib
import os
import sys
import tempfile

import bpy
import pytest

# Blender's own script modules are importable once bpy is.
addon_utils = importlib.import_module("addon_utils")

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ADDON_ID = "ballmorph_inbetween"
REPO_MODULE = "ballmorph_dev"
MODULE = f"bl_ext.{REPO_MODULE}.{ADDON_ID}"

sys.path.insert(0, ROOT)  # the core as a top-level package, to compare with the add-on's output
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

_repo_dir = tempfile.mkdtemp(prefix="ballmorph-repo-")
os.symlink(ROOT, os.path.join(_repo_dir, ADDON_ID))


def enable_addon():
    """Register the development repo (prefs are reset by factory settings) and enable."""
    repos = bpy.context.preferences.extensions.repos
    if REPO_MODULE not in {r.module for r in repos}:
        repos.new(name="Ball-morph dev", module=REPO_MODULE, custom_directory=_repo_dir, source="USER")
    return addon_utils.enable(MODULE, default_set=True, handle_error=_raise)


def disable_addon():
    addon_utils.disable(MODULE, default_set=True, handle_error=_raise)


def _raise(exc):
    raise exc


@pytest.fixture
def addon():
    """Factory settings, then the add-on enabled; disabled again after the test."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    module = enable_addon()
    try:
        yield module
    finally:
        if MODULE in bpy.context.preferences.addons:
            disable_addon()


@pytest.fixture
def shot(addon):
    """A Grease Pencil object whose layer 'Ink' has keys on frames 1 and 9 (a loop and an arc each).

    The current frame is 4, between the keys.
    """
    import gp_data

    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [gp_data.loop(1.0), gp_data.arc(0.5)], cyclic=[True, False], materials=[0, 1])
    gp_data.add_key(
        layer,
        9,
        [gp_data.loop(1.3, wobble=0.08, centre=(0.2, 0.1)), gp_data.arc(-0.3)],
        cyclic=[True, False],
        materials=[0, 1],
    )
    bpy.context.scene.frame_current = 4
    return obj
