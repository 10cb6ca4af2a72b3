"""GPL strings <-> bytes: one byte per character (Latin-1), as the controller does.

GPL strings hold code points 0-255; streams, sockets and serial ports carry 8-bit bytes, and
``Chr``/``Asc`` convert between them (D0:3653-3660).  A character above 255 cannot be sent: that
is an ``Invalid argument`` (-202) rather than a silent substitution.
"""

from __future__ import annotations

from gplrt.lang.conversions import CStr
from gplrt.lang.errors import INVALID_ARGUMENT, GplException


def to_bytes(text: str) -> bytes:
    """Encode a GPL string, one byte per character."""
    try:
        return text.encode("latin-1")
    except UnicodeEncodeError as exc:
        raise GplException(
            INVALID_ARGUMENT, detail=f"character {text[exc.start]!r} does not fit in one byte"
        ) from None


def from_bytes(data: bytes) -> str:
    """Decode bytes into a GPL string, one character per byte."""
    return data.decode("latin-1")


def as_text(value: object) -> str:
    """The text ``Write``/``Send`` output for a String or a number: what ``CStr`` gives."""
    if isinstance(value, str):
        return value
    return str(CStr(value))
