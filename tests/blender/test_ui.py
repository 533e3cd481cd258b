"""Menus, panels and preferences draw what exists (background mode cannot draw, so a layout
stand-in records every call and checks each property, operator, menu and icon it names)."""

import types

import bpy
import gp_data
import pytest
from conftest import MODULE, disable_addon

ICONS = set(bpy.types.UILayout.bl_rna.functions["prop"].parameters["icon"].enum_items.keys())


class OperatorProperties:
    """What ``layout.operator`` returns: records each property a menu entry sets, checking it exists."""

    def __init__(self, idname, log):
        category, name = idname.split(".")
        object.__setattr__(self, "_properties", getattr(getattr(bpy.ops, category), name).get_rna_type().properties)
        object.__setattr__(self, "_log", log)

    def __setattr__(self, name, value):
        assert name in self._properties, f"the operator has no property {name!r}"
        self._log.append(("set", name, value))


class Layout:
    """Records what a draw function puts in a layout and checks that every name is real."""

    def __init__(self, log):
        self.log = log
        self.use_property_split = self.use_property_decorate = self.active = False
        self.operator_context = "INVOKE_DEFAULT"

    def _icon(self, icon):
        assert icon in ICONS, icon

    def _sub(self, *args, **kwargs):
        return Layout(self.log)

    column = row = box = split = _sub

    def separator(self, **kwargs):
        pass

    def label(self, text="", icon="NONE", **kwargs):
        self._icon(icon)
        self.log.append(("label", text))

    def prop(self, data, name, icon="NONE", **kwargs):
        self._icon(icon)
        assert name in data.bl_rna.properties, f"{type(data).__name__} has no property {name!r}"
        self.log.append(("prop", name))

    def template_curve_mapping(self, data, name, **kwargs):
        assert data.bl_rna.properties[name].fixed_type.identifier == "CurveMapping", name
        expected = bpy.types.UILayout.bl_rna.functions["template_curve_mapping"].parameters
        assert set(kwargs) <= set(expected.keys()), kwargs
        self.log.append(("curve", name))

    def operator(self, idname, icon="NONE", **kwargs):
        self._icon(icon)
        category, name = idname.split(".")
        assert getattr(getattr(bpy.ops, category), name).idname(), idname
        self.log.append(("operator", idname))
        return OperatorProperties(idname, self.log)

    def operator_enum(self, idname, prop, **kwargs):
        category, name = idname.split(".")
        assert prop in getattr(getattr(bpy.ops, category), name).get_rna_type().properties
        self.log.append(("operator_enum", idname, prop))

    def menu(self, idname, icon="NONE", **kwargs):
        self._icon(icon)
        assert hasattr(bpy.types, idname), idname
        self.log.append(("menu", idname))


def draw(draw_function, context):
    log = []
    draw_function(types.SimpleNamespace(layout=Layout(log)), context)
    return log


@pytest.fixture
def ui(addon):
    return __import__(f"{MODULE}.ui", fromlist=["menus", "panels", "preferences"])


def test_dopesheet_entries_only_in_grease_pencil_mode(ui):
    entry = ui.menus._draw_dopesheet_entry
    gpencil = types.SimpleNamespace(space_data=types.SimpleNamespace(mode="GPENCIL"), active_object=None)
    action = types.SimpleNamespace(space_data=types.SimpleNamespace(mode="ACTION"), active_object=None)
    assert draw(entry, gpencil) == [("menu", "BALLMORPH_MT_inbetween")]
    assert draw(entry, action) == []


def test_submenu_offers_a_run_a_run_at_the_current_frame_and_the_animators_morphs(ui):
    log = draw(bpy.types.BALLMORPH_MT_inbetween.draw, bpy.context)
    animators = ["CIRCULAR_BALL", "LINEAR_BALL", "PARABOLIC_BALL", "LINEAR_INTERPOLATION"]
    assert log == [
        ("operator", "ballmorph.inbetween"),
        ("operator", "ballmorph.inbetween"),
        ("set", "current_frame_only", True),
        *[entry for method in animators for entry in (("operator", "ballmorph.inbetween"), ("set", "method", method))],
    ]
    # the paper's comparison morphs stay in the sidebar's Morph list
    methods = [item.identifier for item in bpy.context.scene.ballmorph_inbetween.bl_rna.properties["method"].enum_items]
    assert len(methods) == 8 and set(animators) < set(methods)


def test_the_viewport_entry_sits_in_the_animation_menu_just_above_interpolate_sequence(ui):
    """Blender's Draw (Draw mode) and Grease Pencil (Edit mode) menus show the Animation submenu and
    then Interpolate Sequence; the add-on's entry closes that Animation submenu."""
    owners = {name for name, draw in ui.menus.MENU_ENTRIES if draw is ui.menus._draw_entry}
    assert owners == {"VIEW3D_MT_edit_greasepencil_animation"}
    for menu in ("VIEW3D_MT_paint_grease_pencil", "VIEW3D_MT_edit_greasepencil"):
        obj = types.SimpleNamespace(mode="PAINT_GREASE_PENCIL")
        context = types.SimpleNamespace(active_object=obj, object=obj, tool_settings=bpy.context.tool_settings)
        log = []
        try:
            getattr(bpy.types, menu).draw(types.SimpleNamespace(layout=Layout(log)), context)
        except AttributeError:  # what the stand-in context lacks comes after the entries checked here
            pass
        shown = [entry[1] for entry in log if entry[0] in ("menu", "operator")]
        at = shown.index("VIEW3D_MT_edit_greasepencil_animation")
        assert shown[at + 1] == "grease_pencil.interpolate_sequence", (menu, shown)
    log = draw(ui.menus._draw_entry, bpy.context)
    assert log == [("menu", "BALLMORPH_MT_inbetween")]


def test_sidebar_panels_show_the_scene_settings_and_run(ui):
    obj = gp_data.new_object()
    assert ui.panels.BALLMORPH_PT_dopesheet.poll(bpy.context)
    log = draw(ui.panels.BALLMORPH_PT_dopesheet.draw, bpy.context)
    assert ("prop", "method") in log and ("prop", "frame_count") in log
    assert ("prop", "path_preview") in log
    assert log[-1] == ("operator", "ballmorph.inbetween")
    more = draw(ui.panels.BALLMORPH_PT_dopesheet_pairing.draw, bpy.context)
    assert [name for _, name in more] == ["carrier", "matching", "unmatched"]
    bpy.context.view_layer.objects.active = None
    assert not ui.panels.BALLMORPH_PT_view3d.poll(bpy.context)
    del obj


def test_redo_panel_and_preferences_draw_every_option(ui):
    options = __import__(f"{MODULE}.operators.options", fromlist=["OPTION_NAMES"])
    # the redo panel, the preferences and the scene settings share one drawing of the options
    for data in (
        bpy.context.preferences.addons[MODULE].preferences,
        bpy.context.scene.ballmorph_inbetween,
    ):
        log = []
        options.draw_options(Layout(log), data)
        # a type's own settings only with that type (Type is Linear by default)
        type_settings = ("back", "amplitude", "period")
        assert [name for _, name in log] == [name for name in options.OPTION_NAMES if name not in type_settings]


@pytest.mark.parametrize(
    ("easing_type", "shown"),
    [("LINEAR", []), ("QUAD", []), ("BACK", ["back"]), ("ELASTIC", ["amplitude", "period"]), ("CUSTOM", [])],
)
def test_a_types_own_settings_are_drawn_only_with_that_type(ui, easing_type, shown):
    options = __import__(f"{MODULE}.operators.options", fromlist=["OPTION_NAMES"])
    settings = bpy.context.scene.ballmorph_inbetween
    settings.easing_type = easing_type
    log = []
    options.draw_options(Layout(log), settings, scene=bpy.context.scene)
    drawn = [name for kind, name in log if kind == "prop"]
    assert [name for name in drawn if name in ("back", "amplitude", "period")] == shown
    assert "easing" in drawn
    if easing_type == "CUSTOM":  # no curve in a new scene: the panel says how to get one
        assert bpy.context.scene.tool_settings.gpencil_interpolate.interpolation_curve is None
        assert any(kind == "label" and "No Custom curve" in text for kind, text in log)


def test_the_custom_type_draws_the_scenes_interpolate_curve(ui):
    options = __import__(f"{MODULE}.operators.options", fromlist=["OPTION_NAMES"])
    gp_data.ensure_interpolate_curve()
    settings = bpy.context.scene.ballmorph_inbetween
    settings.easing_type = "CUSTOM"
    log = []
    options.draw_options(Layout(log), settings, scene=bpy.context.scene)
    assert ("curve", "interpolation_curve") in log


def test_hint_dots_follow_the_overlays_and_their_toggle_and_scale_with_the_ui(ui):
    hint_dots = ui.hint_dots
    settings = bpy.context.scene.ballmorph_inbetween
    viewport = types.SimpleNamespace(overlay=types.SimpleNamespace(show_overlays=True))
    context = types.SimpleNamespace(scene=bpy.context.scene, space_data=viewport)
    assert settings.hint_dots and hint_dots.shown(context)
    viewport.overlay.show_overlays = False
    assert not hint_dots.shown(context), "drawn with the viewport's overlays off"
    assert not ui.overlay.overlays_shown(context)  # the path preview asks the same
    viewport.overlay.show_overlays = True
    settings.hint_dots = False
    assert not hint_dots.shown(context), "drawn with its toggle off"
    assert ui.overlay.ui_scale(bpy.context) == 1.0  # background Blender reads 0: drawn unscaled
    dot, text, offset = hint_dots.sizes(2.0)
    assert (dot, text, offset) == (2 * hint_dots.DOT_SIZE, 2 * hint_dots.TEXT_SIZE, (12.0, 12.0))
    # the toggle is in the Overlays popover (Grease Pencil Options), and only while enabled
    panel = getattr(bpy.types, hint_dots.TOGGLE_PANEL)
    assert hint_dots.draw_toggle in panel._dyn_ui_initialize()
    assert draw(hint_dots.draw_toggle, bpy.context) == [("prop", "hint_dots")]
    disable_addon()
    assert all(f.__module__ != hint_dots.__name__ for f in panel._dyn_ui_initialize())


def _readme_block(start, end):
    import os

    from conftest import ROOT

    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        text = f.read()
    return text.split(f"<!-- {start} -->")[1].split(f"<!-- {end} -->")[0].strip().strip("`").strip()


def test_the_readmes_menu_picture_is_the_submenu(ui):
    lines = _readme_block("menu", "panel").splitlines()
    shown = [line.rpartition(">")[2].split("(")[0].strip() for line in lines]
    shown = [entry for entry in shown if entry and not entry.startswith("-")]
    expected = ["In-between", "In-between at Current Frame", *(item.label for item in ui.menus.QUICK_METHODS)]
    assert shown == expected


def test_the_readmes_panel_picture_lists_the_panels_settings_in_order(ui):
    gp_data.new_object()
    settings = bpy.context.scene.ballmorph_inbetween
    labels = [
        settings.bl_rna.properties[entry[1]].name
        for entry in draw(ui.panels.BALLMORPH_PT_dopesheet.draw, bpy.context)
        if entry[0] == "prop"
    ]
    picture = _readme_block("panel", "end")
    at = 0
    for label in labels:
        found = picture.find(label, at)
        assert found >= 0, f"the README's panel lacks {label!r} after position {at}"
        at = found + len(label)
    pairing = [
        settings.bl_rna.properties[name].name
        for _, name in draw(ui.panels.BALLMORPH_PT_dopesheet_pairing.draw, bpy.context)
    ]
    assert picture.splitlines()[-1].endswith(": " + ", ".join(pairing))
