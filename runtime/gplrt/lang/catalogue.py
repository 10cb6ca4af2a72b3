"""What ``gplrt.lang`` contributes to the GPL built-in catalogue (``gplrt/builtins.py``).

One table per kind, GPL spelling -> Python object, so the lead can merge them into
``gplrt.builtins`` without re-listing names.  ``VB_EXTRAS`` are VB functions the GPL manuals do
not list (Left, Right, Val, ...): provided for hand-written code and deliberately kept out of
``FUNCTIONS`` (a GPL program may declare its own ``Left``; spec §1.8 "Predefined names").
"""

from __future__ import annotations

from typing import Any, Final

from gplrt.lang import conversions, strings
from gplrt.lang.arrays import GplArray
from gplrt.lang.console import Console
from gplrt.lang.constants import CONSTANTS
from gplrt.lang.format import Format
from gplrt.lang.mathlib import Fix, Int, Math, Rnd
from gplrt.lang.strings import StringMembers

__all__ = ["FUNCTIONS", "GLOBAL_CLASSES", "CONSTANTS", "TYPE_MEMBERS", "VB_EXTRAS"]

FUNCTIONS: Final[dict[str, Any]] = {
    # §14.1 conversion functions
    "CBool": conversions.CBool,
    "CByte": conversions.CByte,
    "CShort": conversions.CShort,
    "CInt": conversions.CInt,
    "CSng": conversions.CSng,
    "CDbl": conversions.CDbl,
    "CStr": conversions.CStr,
    "Hex": strings.Hex,
    # §14.3 numeric functions
    "Fix": Fix,
    "Int": Int,
    "Rnd": Rnd,
    # §14.5 legacy string functions
    "Asc": strings.Asc,
    "Chr": strings.Chr,
    "Format": Format,
    "FromBitString": strings.FromBitString,
    "ToBitString": strings.ToBitString,
    "InStr": strings.InStr,
    "LCase": strings.LCase,
    "UCase": strings.UCase,
    "Len": strings.Len,
    "Mid": strings.Mid,
}

GLOBAL_CLASSES: Final[dict[str, Any]] = {
    "Math": Math,
    "Console": Console,
}

TYPE_MEMBERS: Final[dict[str, Any]] = {
    "String": StringMembers,
    "Array": GplArray,
}

VB_EXTRAS: Final[dict[str, Any]] = {name: getattr(strings, name) for name in strings.VB_EXTRAS}
