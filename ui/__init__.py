"""User interface: Dope Sheet and 3D viewport menus, sidebar panels, preferences, the path preview."""

import bpy

from . import menus, panels, path_preview, preferences

classes = (*preferences.classes, *menus.classes, *panels.classes)

_register_classes, _unregister_classes = bpy.utils.register_classes_factory(classes)


def register():
    _register_classes()
    menus.register()
    path_preview.register()


def unregister():
    path_preview.unregister()
    menus.unregister()
    _unregister_classes()
