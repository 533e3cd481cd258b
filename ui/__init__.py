"""User interface: Dope Sheet and 3D viewport menus, sidebar panels, preferences."""

import bpy

from . import menus, panels, preferences

classes = (*preferences.classes, *menus.classes, *panels.classes)

_register_classes, _unregister_classes = bpy.utils.register_classes_factory(classes)


def register():
    _register_classes()
    menus.register()


def unregister():
    menus.unregister()
    _unregister_classes()
