"""Ball-morph In-between: tight Grease Pencil in-betweens along ball-morph trajectories.

This file only registers: it walks the add-on's submodules in order, and in reverse on
unregister. The maths lives in the vendored, bpy-free ``ballmorph_core`` package, the add-on's
Blender-free logic in ``addon_logic``; ``cli`` registers the ``blender -c ballmorph`` command.
The bpy modules are imported when Blender registers the add-on, not when the package is
imported, so ``addon_logic`` and ``ballmorph_core`` import without Blender (tests/addon).
"""


def _modules():
    from . import cli, operators, properties, ui

    return (properties, operators, ui, cli)


def register():
    for module in _modules():
        module.register()


def unregister():
    for module in reversed(_modules()):
        module.unregister()
