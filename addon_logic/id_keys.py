"""Names of the add-on's ID properties (its records on the Grease Pencil data-block).

No bpy here (plain CPython imports it: ``tests/addon``). Blender keeps at most 63 bytes of an ID
property's name, so a longer name (a long layer name) is replaced by a stand-in made from it.
"""

import zlib

__all__ = ["MAX_KEY", "id_key"]

#: Bytes of an ID property name Blender keeps.
MAX_KEY = 63


def id_key(text):
    """``text`` when Blender can keep it as an ID property name, else ``'~'`` and its CRC-32.

    Examples
    --------
    >>> id_key("Ink")
    'Ink'
    >>> id_key("x" * 64)
    '~3ad2ac12'
    """
    if len(text.encode()) <= MAX_KEY:
        return text
    return f"~{zlib.crc32(text.encode()):08x}"
