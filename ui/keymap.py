"""The add-on's shortcut: Ctrl+Alt+E runs Ball-morph In-between in the Dope Sheet and the 3D viewport.

Why Ctrl+Alt+E: Blender's Interpolate is Ctrl+E and Interpolate Sequence Shift+Ctrl+E (Grease
Pencil Draw and Edit modes), so the third in-betweener sits next to them; and no keymap of
Blender's default keyconfig binds Ctrl+Alt+E (checked on 4.5.15 and 5.0.1 against
``presets/keyconfig/keymap_data/blender_default.py``; tests/blender/test_register.py checks it
again). Shift+Alt+E was the other free candidate in the Dope Sheet and the viewport, but Pose
mode's Blend to Neighbour uses it.

The items go into the add-on keyconfig (``window_manager.keyconfigs.addon``), where the
animator can rebind them in Preferences > Keymap, and are removed on unregister.
"""

import bpy

from ..operators.inbetween import BALLMORPH_OT_inbetween

__all__ = ["KEY", "KEYMAPS", "register", "unregister"]

#: The shortcut, as keymap item keywords.
KEY = {"type": "E", "value": "PRESS", "ctrl": True, "alt": True}
#: (keymap name, space type) of Blender's keymaps the shortcut is added to.
KEYMAPS = (("Dopesheet", "DOPESHEET_EDITOR"), ("3D View", "VIEW_3D"))

_items = []  # (keymap, keymap item) added by register()


def register():
    keyconfig = bpy.context.window_manager.keyconfigs.addon
    if keyconfig is None:  # Blender started without keyconfigs: no shortcut to add
        return
    for name, space_type in KEYMAPS:
        keymap = keyconfig.keymaps.new(name=name, space_type=space_type)
        _items.append((keymap, keymap.keymap_items.new(BALLMORPH_OT_inbetween.bl_idname, **KEY)))


def unregister():
    for keymap, item in _items:
        keymap.keymap_items.remove(item)
    _items.clear()
