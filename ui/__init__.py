"""User interface: Dope Sheet and 3D viewport menus, the shortcut, sidebar panels, preferences,
the path preview, the hints' numbered dots, the translation table."""

import bpy

from . import hint_dots, keymap, menus, panels, path_preview, preferences, translations

classes = (*preferences.classes, *menus.classes, *panels.classes)

_register_classes, _unregister_classes = bpy.utils.register_classes_factory(classes)


def register():
    translations.register()
    _register_classes()
    menus.register()
    keymap.register()
    path_preview.register()
    hint_dots.register()


def unregister():
    hint_dots.unregister()
    path_preview.unregister()
    keymap.unregister()
    menus.unregister()
    _unregister_classes()
    translations.unregister()
