"""Ball-morph In-between: tight Grease Pencil in-betweens along ball-morph trajectories.

This file only registers: it walks the add-on's submodules in order, and in reverse on
unregister. The maths lives in the vendored, bpy-free ``ballmorph_core`` package; ``cli``
registers the ``blender -c ballmorph`` command.
"""

from . import cli, operators, properties, ui

_modules = (properties, operators, ui, cli)


def register():
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
