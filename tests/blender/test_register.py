"""The add-on registers and unregisters cleanly, twice, in real Blender."""

import bpy
from conftest import MODULE, disable_addon, enable_addon


def test_register_unregister_twice(addon):
    for _ in range(2):
        assert MODULE in bpy.context.preferences.addons
        disable_addon()
        assert MODULE not in bpy.context.preferences.addons
        enable_addon()
        assert MODULE in bpy.context.preferences.addons


def test_core_is_vendored_and_bpy_free(addon):
    core = __import__(f"{MODULE}.ballmorph_core", fromlist=["make_morph"])
    assert "circular-ball" in core.METHODS
    assert not any(name.startswith("bpy") for name in core.__dict__)
