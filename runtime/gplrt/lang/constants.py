"""GPL predefined constants (spec gpl-language.md §14.8, gpl-dictionary.md §13.1-13.2).

All predefined constants begin with ``GPL_`` and are numeric [000 L185-198].  The manuals define
no VB-style ``vbCrLf``/``vbTab`` constants; text control characters come from ``Chr(GPL_CR)``.
``True``/``False``/``Nothing`` are keywords, lowered to Python's ``True``/``False``/``None``.
"""

from __future__ import annotations

from typing import Final

__all__ = [
    "GPL_CR",
    "GPL_LF",
    "GPL_Righty",
    "GPL_Lefty",
    "GPL_Above",
    "GPL_Below",
    "GPL_Flip",
    "GPL_NoFlip",
    "GPL_Single",
    "CONSTANTS",
]

GPL_CR: Final = 13
GPL_LF: Final = 10
# Location.Config bits (combine with Or).
GPL_Righty: Final = 0x01
GPL_Lefty: Final = 0x02
GPL_Above: Final = 0x04
GPL_Below: Final = 0x08
GPL_Flip: Final = 0x10
GPL_NoFlip: Final = 0x20
GPL_Single: Final = 0x1000

CONSTANTS: Final[dict[str, int]] = {name: globals()[name] for name in __all__ if name.startswith("GPL_")}
