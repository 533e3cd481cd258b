"""Operators: thin glue that reads Grease Pencil data, calls the core, writes the result.

``inbetween`` holds the operator, a thin caller of ``service``, which in-betweens one object
(the command line, ``cli.py``, calls it too). The service's steps: ``keys`` reads which layers
and keys there are, ``pairing`` decides which keys pair up and which frames to write,
``morph`` computes an interval with the core, ``writer`` writes the frames all or nothing, and
``reports`` words what happened; ``playhead`` narrows a run to one in-between on the current
frame (``current_frame_only``). ``generated`` remembers which frames the add-on made,
``grease_pencil`` is the only code that moves stroke data, ``options`` declares the options
once (with their core values) for the operator, the scene settings, the preferences and the
command line, and ``plans`` keeps the last run's plans for a redo. ``preview`` keeps the path
preview's trajectories (drawn by ``ui/path_preview.py``); ``hints`` holds the two hint
operators (their numbering is ``hint_numbers``); ``select_warned`` selects the strokes the last
run's warnings name (kept by ``warned``). ``pairing``, ``playhead`` and ``reports`` never
import bpy: plain CPython tests them (tests/addon).
"""

import bpy

from .hints import BALLMORPH_OT_hint_add, BALLMORPH_OT_hint_clear
from .inbetween import BALLMORPH_OT_inbetween
from .plans import PLANS
from .select_warned import BALLMORPH_OT_select_warned

classes = (BALLMORPH_OT_inbetween, BALLMORPH_OT_hint_add, BALLMORPH_OT_hint_clear, BALLMORPH_OT_select_warned)

_register_classes, _unregister_classes = bpy.utils.register_classes_factory(classes)


def register():
    _register_classes()


def unregister():
    _unregister_classes()
    PLANS.clear()  # the plans hold the last run's keys and correspondences: free them
