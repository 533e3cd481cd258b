"""Ready for translation, as Blender add-ons are: the add-on's translation table, registered with
``bpy.app.translations`` under the add-on's package name.

The table is empty (English only). A translator adds ``{locale: {(context, msgid): msgstr}}``
entries here; Blender then translates the add-on's labels, descriptions and menu texts (the UI
translates them itself) and the operator's reports (passed through ``pgettext_rpt``).
"""

import bpy

__all__ = ["TRANSLATIONS", "DOMAIN", "register", "unregister"]

#: ``{locale: {(context, msgid): msgstr}}``, e.g. ``{"fr_FR": {("*", "In-between"): "Intervalle"}}``.
TRANSLATIONS = {}
#: The add-on's package (``bl_ext.<repo>.ballmorph_inbetween``): the table's name in Blender.
DOMAIN = __package__.rpartition(".")[0]


def register():
    bpy.app.translations.register(DOMAIN, TRANSLATIONS)


def unregister():
    bpy.app.translations.unregister(DOMAIN)
