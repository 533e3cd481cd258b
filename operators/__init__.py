"""Operators: thin glue that reads Grease Pencil data, calls the core, writes the result.

``inbetween`` holds the operator; ``keys`` finds key intervals, ``morph`` computes them with
the core, ``writer`` writes the frames all or nothing, ``generated`` remembers which frames
the add-on made, ``grease_pencil`` is the only code that moves stroke data, and ``options``
declares the options once for the operator, the scene settings and the preferences.
"""

import bpy

from .inbetween import BALLMORPH_OT_inbetween

classes = (BALLMORPH_OT_inbetween,)

register, unregister = bpy.utils.register_classes_factory(classes)
