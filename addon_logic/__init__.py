"""The add-on's logic that needs no Blender: which keys pair up and which frames to write
(``pairing``), timing charts kept with their intervals (``charts``), ID property names
(``id_keys``), hint numbers (``hint_numbers``) and every report's wording (``reports``).

Nothing here imports bpy (``tests/addon`` imports it in plain CPython); ``operators/`` is the
bpy side that calls it.
"""
