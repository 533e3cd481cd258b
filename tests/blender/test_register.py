"""The add-on registers and unregisters cleanly, twice, in real Blender, with all its UI."""

import importlib
import importlib.util
import os
import sys

import bpy
from conftest import MODULE, ROOT, disable_addon, enable_addon

MENUS = ("DOPESHEET_MT_key", "DOPESHEET_MT_context_menu", "VIEW3D_MT_edit_greasepencil_animation")
CLASSES = (
    "BALLMORPH_OT_inbetween",
    "BALLMORPH_OT_select_warned",
    "BALLMORPH_MT_inbetween",
    "BALLMORPH_PT_dopesheet",
    "BALLMORPH_PT_view3d",
)


def _our_menu_entries():
    """Draw functions of this add-on appended to Blender's menus, per menu."""
    return {
        name: [f for f in getattr(bpy.types, name)._dyn_ui_initialize() if f.__module__.startswith(MODULE)]
        for name in MENUS
    }


def test_register_unregister_twice(addon):
    for _ in range(2):
        assert MODULE in bpy.context.preferences.addons
        disable_addon()
        assert MODULE not in bpy.context.preferences.addons
        assert not hasattr(bpy.types, "BALLMORPH_OT_inbetween")
        assert not hasattr(bpy.types.Scene, "ballmorph_inbetween")
        assert all(not entries for entries in _our_menu_entries().values())
        enable_addon()
        assert MODULE in bpy.context.preferences.addons


def test_operator_ui_and_settings_are_registered(addon):
    for name in CLASSES:
        assert hasattr(bpy.types, name), name
    assert addon.properties.BALLMORPH_PG_settings.is_registered
    assert addon.ui.preferences.BALLMORPH_AddonPreferences.is_registered
    assert all(len(entries) == 1 for entries in _our_menu_entries().values())
    assert bpy.ops.ballmorph.inbetween.idname() == "BALLMORPH_OT_inbetween"
    assert "UNDO" in bpy.types.BALLMORPH_OT_inbetween.bl_options
    assert "REGISTER" in bpy.types.BALLMORPH_OT_inbetween.bl_options
    settings = bpy.context.scene.ballmorph_inbetween
    assert (settings.method, settings.frame_count, settings.carrier) == ("CIRCULAR_BALL", 0, "SIMILARITY")
    assert bpy.context.preferences.addons[MODULE].preferences.method == "CIRCULAR_BALL"


def test_operator_options(addon):
    properties = bpy.ops.ballmorph.inbetween.get_rna_type().properties
    enum = {name: [i.identifier for i in properties[name].enum_items] for name in ("method", "easing_type", "easing")}
    assert enum["method"] == [
        "CIRCULAR_BALL",
        "LINEAR_BALL",
        "PARABOLIC_BALL",
        "LINEAR_INTERPOLATION",
        "CLOSEST_PROJECTION",
        "CURVATURE_INTERPOLATION",
        "LAPLACE_BLENDING",
        "HEAT_PROPAGATION",
    ]
    # Blender's own Interpolate Sequence easing names, its CUSTOM curve included, in its order
    interpolate = bpy.ops.grease_pencil.interpolate_sequence.get_rna_type().properties
    assert enum["easing_type"] == [i.identifier for i in interpolate["type"].enum_items]
    assert enum["easing"] == [i.identifier for i in interpolate["easing"].enum_items]
    # ... and its Back, Amplitude and Period settings: names, labels, defaults, ranges, display
    for name in ("back", "amplitude", "period"):
        ours, blenders = properties[name], interpolate[name]
        for attribute in ("name", "description", "hard_min", "hard_max", "soft_min", "soft_max", "precision"):
            assert getattr(ours, attribute) == getattr(blenders, attribute), (name, attribute)
        assert (ours.default, ours.step, ours.subtype) == (blenders.default, blenders.step, blenders.subtype), name
    # ... and its labels: Type (Linear, Sine, ...) and Easing (Ease In, ...)
    labels = (properties["easing_type"].name, properties["easing"].name)
    assert labels == (interpolate["type"].name, interpolate["easing"].name) == ("Type", "Easing")
    for name in ("frame_count", "layers", "selected_only", "carrier", "matching", "unmatched"):
        assert name in properties


def test_core_is_vendored_and_bpy_free(addon):
    core = __import__(f"{MODULE}.ballmorph_core", fromlist=["make_morph"])
    assert "circular-ball" in core.METHODS
    assert not any(name.startswith("bpy") for name in core.__dict__)
    # the paper's measures are not loaded with the add-on (and not shipped in its zip)
    assert f"{MODULE}.ballmorph_core.study" not in sys.modules


def test_manifest_has_no_dead_link_and_declares_file_access():
    import tomllib

    with open(os.path.join(ROOT, "blender_manifest.toml"), "rb") as f:
        manifest = tomllib.load(f)
    assert "example.invalid" not in manifest.get("website", "")
    assert "blender -c ballmorph" in manifest["permissions"]["files"]
    assert "/ballmorph_core/study/" in manifest["build"]["paths_exclude_pattern"]


# -- the shortcut ----------------------------------------------------------------------------------

SHORTCUT = {"type": "E", "ctrl": True, "alt": True, "shift": False}
SHORTCUT_SPACES = {"Dopesheet": "DOPESHEET_EDITOR", "3D View": "VIEW_3D"}


def _our_keymap_items():
    """``{keymap name: [(type, ctrl, alt, shift), ...]}`` of the add-on keyconfig's ballmorph items."""
    found = {}
    for keymap in bpy.context.window_manager.keyconfigs.addon.keymaps:
        for item in keymap.keymap_items:
            if item.idname == "ballmorph.inbetween":
                found.setdefault(keymap.name, []).append((item.type, item.ctrl, item.alt, item.shift))
    return found


def test_shortcut_is_added_on_register_and_removed_on_unregister(addon):
    want = [(SHORTCUT["type"], True, True, False)]
    assert _our_keymap_items() == dict.fromkeys(SHORTCUT_SPACES, want)
    keymaps = bpy.context.window_manager.keyconfigs.addon.keymaps
    assert {name: keymaps[name].space_type for name in SHORTCUT_SPACES} == SHORTCUT_SPACES
    disable_addon()
    assert _our_keymap_items() == {}, "the shortcut outlived unregister()"
    enable_addon()
    assert _our_keymap_items() == dict.fromkeys(SHORTCUT_SPACES, want), "registered twice, or not again"
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        assert "**Ctrl+Alt+E** in the 3D viewport or the Dope Sheet" in f.read()


def _default_keymaps():
    """Blender's default keyconfig as data (background mode leaves the real keyconfig's items empty)."""
    path = os.path.join(bpy.utils.system_resource("SCRIPTS"), "presets", "keyconfig", "keymap_data")
    spec = importlib.util.spec_from_file_location("blender_default", os.path.join(path, "blender_default.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.generate_keymaps(module.Params())


def test_shortcut_is_free_in_blenders_default_keymap():
    keymaps = _default_keymaps()
    names = {name for name, _, _ in keymaps}
    assert {"Dopesheet", "3D View", "Grease Pencil Edit Mode", "Grease Pencil Paint Mode"} <= names
    # (modal keymaps, such as walk navigation's, only act while their modal operator runs)
    clashes = [
        (name, idname)
        for name, params, items in keymaps
        if not params.get("modal")
        for idname, event, _ in items["items"]
        if event.get("type") == SHORTCUT["type"]
        and (event.get("any") or all(bool(event.get(key, False)) == SHORTCUT[key] for key in ("ctrl", "alt", "shift")))
        and not event.get("oskey")
    ]
    assert clashes == [], f"Ctrl+Alt+E is bound in Blender's default keymap: {clashes}"
    interpolate = {
        idname: (event["type"], bool(event.get("ctrl")), bool(event.get("shift")))
        for name, _, items in keymaps
        if name == "Grease Pencil Edit Mode"
        for idname, event, _ in items["items"]
        if idname.startswith("grease_pencil.interpolate")
    }
    # next to Blender's own in-betweeners, Ctrl+E and Shift+Ctrl+E
    assert interpolate == {
        "grease_pencil.interpolate": ("E", True, False),
        "grease_pencil.interpolate_sequence": ("E", True, True),
    }


def test_the_translation_table_is_registered_and_removed_under_the_addons_name(addon, monkeypatch):
    import types

    module = importlib.import_module(f"{MODULE}.ui.translations")
    assert module.DOMAIN == MODULE
    calls = []
    recorder = types.SimpleNamespace(
        register=lambda name, table: calls.append(("+", name, table)), unregister=lambda name: calls.append(("-", name))
    )
    # (bpy.app.translations' functions are read-only: the module's view of bpy is replaced instead)
    monkeypatch.setattr(module, "bpy", types.SimpleNamespace(app=types.SimpleNamespace(translations=recorder)))
    module.register()
    module.unregister()
    assert calls == [("+", MODULE, module.TRANSLATIONS), ("-", MODULE)]
