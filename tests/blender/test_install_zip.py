"""The built extension zip (what animators install) installs, runs and uninstalls in Blender."""

import glob
import os
import subprocess
import sys
import tempfile

import bpy
import gp_data
import pytest
from conftest import ADDON_ID, ROOT, addon_utils

REPO_MODULE = "ballmorph_zip_test"


def _built_zip():
    zips = glob.glob(os.path.join(ROOT, "dist", f"{ADDON_ID}-*.zip"))
    if not zips:  # tools/run_tests.sh builds it first; build it when run alone
        subprocess.run([os.path.join(ROOT, "tools", "build_extension.sh")], check=True, capture_output=True)
        zips = glob.glob(os.path.join(ROOT, "dist", f"{ADDON_ID}-*.zip"))
    return max(zips, key=os.path.getmtime)


@pytest.fixture
def zip_repo():
    """Factory settings and an empty user repository in a temp dir; removed after the test."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    directory = tempfile.mkdtemp(prefix="ballmorph-zip-repo-")
    repos = bpy.context.preferences.extensions.repos
    repo = repos.new(name="Zip test", module=REPO_MODULE, custom_directory=directory, source="USER")
    module = f"bl_ext.{REPO_MODULE}.{ADDON_ID}"
    try:
        yield module, directory
    finally:
        if module in bpy.context.preferences.addons:
            addon_utils.disable(module, default_set=True)
        repos.remove(repo)


def test_built_zip_installs_and_runs(zip_repo):
    module, directory = zip_repo
    path = _built_zip()
    result = bpy.ops.extensions.package_install_files(filepath=path, repo=REPO_MODULE, enable_on_install=True)
    assert result == {"FINISHED"}
    assert module in bpy.context.preferences.addons
    installed = os.path.join(directory, ADDON_ID)
    assert os.path.isfile(os.path.join(installed, "blender_manifest.toml"))
    assert os.path.isfile(os.path.join(installed, "ballmorph_core", "__init__.py"))
    assert os.path.isfile(os.path.join(installed, "cli.py"))  # blender -c ballmorph
    for left_out in ("tests", "tools", "Makefile", "pyproject.toml", "README.md", "ballmorph_core/study"):
        assert not os.path.exists(os.path.join(installed, left_out)), left_out

    obj = gp_data.new_object()
    layer = obj.data.layers["Ink"]
    gp_data.add_key(layer, 1, [gp_data.loop(1.0)], cyclic=[True])
    gp_data.add_key(layer, 5, [gp_data.loop(1.4, wobble=0.1)], cyclic=[True])
    bpy.context.scene.frame_current = 2
    assert bpy.ops.ballmorph.inbetween() == {"FINISHED"}
    assert [f.keyframe_type for f in layer.frames if 1 < f.frame_number < 5] == ["BREAKDOWN"] * 3
    assert bpy.types.BALLMORPH_OT_inbetween.__module__.startswith(module)
    assert sys.modules[f"{module}.cli"]._handle is not None  # the command is registered
    core = sys.modules[f"{module}.ballmorph_core"]
    with pytest.raises(ImportError, match="does not ship"):
        core.measure  # noqa: B018 (the lazy attribute is the point)
