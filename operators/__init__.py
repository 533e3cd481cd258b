"""Operators: thin glue that reads Grease Pencil data, calls the core, writes the result."""

import bpy

classes = ()

register, unregister = bpy.utils.register_classes_factory(classes)
