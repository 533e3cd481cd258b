"""Menus, panels and preferences draw what exists (background mode cannot draw, so a layout
stand-in records every call and checks each property, operator, menu and icon it names)."""

import types

import bpy
import gp_data
import pytest
from conftest import MODULE

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


def test_submenu_offers_a_run_and_every_morph(ui):
    log = draw(bpy.types.BALLMORPH_MT_inbetween.draw, bpy.context)
    assert log == [
        ("operator", "ballmorph.inbetween"),
        ("operator", "ballmorph.inbetween"),
        ("set", "current_frame_only", True),
        ("operator_enum", "ballmorph.inbetween", "method"),
    ]


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
        assert [name for _, name in log] == list(options.OPTION_NAMES)
