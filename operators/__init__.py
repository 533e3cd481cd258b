"""Operators: thin glue that reads Grease Pencil data, calls the core, writes the result.

``inbetween`` holds the operator; ``keys`` finds key intervals, ``morph`` computes them with
the core, ``writer`` writes the frames all or nothing, ``generated`` remembers which frames
the add-on made, ``grease_pencil`` is the only code that moves stroke data, ``options``
declares the options once for the operator, the scene settings and the preferences, and
``plans`` keeps the last run's plans for a redo.
"""

import bpy

from .inbetween import BALLMORPH_OT_inbetween
from .plans import PLANS

classes = (BALLMORPH_OT_inbetween,)

_register_classes, _unregister_classes = bpy.utils.register_classes_factory(classes)


def register():
    _register_classes()


def unregister():
    _unregister_classes()
    PLANS.clear()  # the plans hold the last run's keys and correspondences: free them
