"""The add-on registers and unregisters cleanly, twice, in real Blender, with all its UI."""

import bpy
from conftest import MODULE, disable_addon, enable_addon

MENUS = (
    "DOPESHEET_MT_key",
    "DOPESHEET_MT_context_menu",
    "VIEW3D_MT_paint_grease_pencil",
    "VIEW3D_MT_edit_greasepencil",
)
CLASSES = (
    "BALLMORPH_OT_inbetween",
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
    # Blender's own Interpolate Sequence easing names (all but its CUSTOM curve)
    interpolate = bpy.ops.grease_pencil.interpolate_sequence.get_rna_type().properties
    assert enum["easing_type"] == [i.identifier for i in interpolate["type"].enum_items if i.identifier != "CUSTOM"]
    assert enum["easing"] == [i.identifier for i in interpolate["easing"].enum_items]
    for name in ("frame_count", "layers", "selected_only", "carrier", "matching", "unmatched"):
        assert name in properties


def test_core_is_vendored_and_bpy_free(addon):
    core = __import__(f"{MODULE}.ballmorph_core", fromlist=["make_morph"])
    assert "circular-ball" in core.METHODS
    assert not any(name.startswith("bpy") for name in core.__dict__)
