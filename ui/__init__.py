"""User interface: Dope Sheet menus, sidebar panel, preferences."""

import bpy

classes = ()

register, unregister = bpy.utils.register_classes_factory(classes)
