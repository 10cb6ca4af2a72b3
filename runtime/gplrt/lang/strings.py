"""GPL String members and the legacy string functions (spec gpl-language.md §5, §14.4-14.5;
gpl-dictionary.md §10.1-10.2).

Strings are Python ``str`` restricted to code points 0-255 (8-bit ASCII/binary bytes, §5).
Two position conventions coexist and are kept apart deliberately:

* **String members** (``s.IndexOf``, ``s.Substring``) are **0-based** [000 L1153-1155, L3251];
* **legacy functions** (``InStr``, ``Mid``) are **1-based** [000 L1203-1204].

Errors (choices for the UNSPECIFIED out-of-range cases, documented per function): a position or
length outside the string is **-707 Value out-of-range** (the spec recommends an exception for
Substring; .NET throws too); ``Asc("")`` and a too-short ``FromBitString`` input are **-783 Short
string**; a bad ``ToBitString`` type keyword is **-202 Invalid argument**.

Case conversion and white-space trimming are ASCII-only: the controller's strings are 8-bit
ASCII, and Python's Unicode rules would map e.g. ``"\\xff".upper()`` outside 0-255.  White space
is space, tab, CR, LF, VT and FF (C ``isspace``).

``StringMembers`` holds the members of the String type as staticmethods taking the string first
(``s.Substring(1, 2)`` -> ``StringMembers.Substring(s, 1, 2)``); ``Compare`` is the one Shared
member (``String.Compare(a, b)``), listed in ``StringMembers.shared_members``.  ``Length`` is a
property in GPL; here it is a one-argument staticmethod like the others.
"""

from __future__ import annotations

import re
import struct
from typing import Any, Final

from gplrt.lang.arrays import GplArray
from gplrt.lang.conversions import parse_number, to_double, to_int16, to_int32, to_number, to_single, to_string, to_uint8
from gplrt.lang.errors import (
    INVALID_ARGUMENT,
    SHORT_STRING,
    VALUE_OUT_OF_RANGE,
    GplException,
)
from gplrt.lang.gpltypes import Boolean, Byte, Double, Integer, Short, Single, String

_VAL_RE: Final = re.compile(r"[+-]?(?:&[hH][0-9a-fA-F]+|&[oO][0-7]+|\d*\.?\d*(?:[eE][+-]?\d+)?)")
WHITESPACE: Final = " \t\r\n\v\f"

__all__ = [
    "StringMembers",
    "Asc",
    "Chr",
    "InStr",
    "LCase",
    "UCase",
    "Len",
    "Mid",
    "Hex",
    "ToBitString",
    "FromBitString",
    "Left",
    "Right",
    "LTrim",
    "RTrim",
    "Trim",
    "Space",
    "StrComp",
    "Val",
    "Str",
    "GPL_FUNCTIONS",
    "VB_EXTRAS",
    "ascii_upper",
    "ascii_lower",
]

_UPPER: Final = {c: c - 32 for c in range(ord("a"), ord("z") + 1)}
_LOWER: Final = {c: c + 32 for c in range(ord("A"), ord("Z") + 1)}


def _s(x: Any) -> str:
    return x if type(x) is str else to_string(x)


def _out_of_range(detail: str) -> GplException:
    return GplException(VALUE_OUT_OF_RANGE, detail=detail)


def ascii_upper(s: str) -> str:
    """Upper-case a-z only."""
    return s.upper() if s.isascii() else s.translate(_UPPER)


def ascii_lower(s: str) -> str:
    """Lower-case A-Z only."""
    return s.lower() if s.isascii() else s.translate(_LOWER)


def _trim_chars(chars: Any) -> str:
    if chars is None:
        return WHITESPACE
    if isinstance(chars, GplArray):
        return "".join(_s(c) for c in chars)
    return _s(chars)


class StringMembers:
    """Members of GPL's String type; the string is the first argument."""

    __slots__ = ()

    #: Members called on the class (``String.Compare``) rather than on a string value.
    shared_members: Final = frozenset({"Compare"})

    @staticmethod
    def Compare(string_a: String, string_b: String, ignore_case: Boolean = False) -> Integer:  # type: ignore[assignment]
        """``String.Compare(a, b [, ignore_case])``: -1, 0 or 1 by character code; with
        ``ignore_case`` the ASCII letters compare case-insensitively (VB signature, §14.4)."""
        a, b = _s(string_a), _s(string_b)
        if ignore_case:
            a, b = ascii_lower(a), ascii_lower(b)
        return (a > b) - (a < b)  # type: ignore[return-value]

    @staticmethod
    def Length(s: String) -> Integer:
        """``s.Length``: number of characters."""
        return len(s)  # type: ignore[return-value]

    @staticmethod
    def IndexOf(s: String, string_s: String, start: Integer = 0) -> Integer:  # type: ignore[assignment]
        """``s.IndexOf(sub [, start])``: 0-based position of ``sub`` at or after ``start``, -1 if
        absent.  ``start`` outside 0..Length is -707."""
        start = to_int32(start)
        if not 0 <= start <= len(s):
            raise _out_of_range(f"IndexOf start {start} outside 0..{len(s)}")
        return s.find(_s(string_s), start)  # type: ignore[return-value]

    @staticmethod
    def Split(s: String, separator: String | None = None) -> GplArray[String]:
        """``s.Split(sep)``: the pieces between separator characters, as a 1-D String array.

        Every character of ``sep`` is a separator (.NET ``Split(ParamArray chars)``); without one,
        white space separates.  Adjacent separators give empty pieces, as in .NET.
        """
        seps = WHITESPACE if separator is None or separator == "" else _trim_chars(separator)
        if len(seps) == 1:
            parts = s.split(seps)
        else:
            parts = []
            start = 0
            for i, c in enumerate(s):
                if c in seps:
                    parts.append(s[start:i])
                    start = i + 1
            parts.append(s[start:])
        return GplArray.from_list(parts, String)

    @staticmethod
    def Substring(s: String, first_pos: Integer, length: Integer | None = None) -> String:
        """``s.Substring(start [, length])``: 0-based; without ``length``, to the end
        (``inp.Substring(4)`` [000 L3255]).  Any part outside the string is -707."""
        start = to_int32(first_pos)
        if not 0 <= start <= len(s):
            raise _out_of_range(f"Substring start {start} outside 0..{len(s)}")
        if length is None:
            return s[start:]  # type: ignore[return-value]
        n = to_int32(length)
        if n < 0 or start + n > len(s):
            raise _out_of_range(f"Substring({start}, {n}) of a {len(s)}-character string")
        return s[start : start + n]  # type: ignore[return-value]

    @staticmethod
    def ToLower(s: String) -> String:
        """``s.ToLower``: lower-case copy (ASCII letters)."""
        return ascii_lower(s)  # type: ignore[return-value]

    @staticmethod
    def ToUpper(s: String) -> String:
        """``s.ToUpper``: upper-case copy (ASCII letters)."""
        return ascii_upper(s)  # type: ignore[return-value]

    @staticmethod
    def Trim(s: String, trim_chars: String | None = None) -> String:
        """``s.Trim([chars])``: without the given characters (default white space) at both ends."""
        return s.strip(_trim_chars(trim_chars))  # type: ignore[return-value]

    @staticmethod
    def TrimEnd(s: String, trim_chars: String | None = None) -> String:
        """``s.TrimEnd([chars])``: trimmed at the end only."""
        return s.rstrip(_trim_chars(trim_chars))  # type: ignore[return-value]

    @staticmethod
    def TrimStart(s: String, trim_chars: String | None = None) -> String:
        """``s.TrimStart([chars])``: trimmed at the start only."""
        return s.lstrip(_trim_chars(trim_chars))  # type: ignore[return-value]


# -- legacy functions (§14.5) ---------------------------------------------------------------------


def Asc(string: String) -> Integer:
    """Character code of the first character; ``Asc("")`` is -783 Short string (the spec
    recommends an exception; "Short string" is the controller's text for too little data)."""
    string = _s(string)
    if not string:
        raise GplException(SHORT_STRING, detail="Asc of an empty string")
    return ord(string[0])  # type: ignore[return-value]


def Chr(expression: Any) -> String:
    """One-character string with code ``expression``: Integer conversion (rounding), then the
    low 8 bits (AMB-23: ``Chr(block/256) & Chr(block)`` packs bytes [000 L3259])."""
    return chr(to_int32(expression) & 0xFF)  # type: ignore[return-value]


def InStr(start: Any, string_t: Any, string_s: Any = None) -> Integer:
    """``InStr(start, string_t, string_s)``: 1-based position of ``string_s`` in ``string_t`` at or
    after ``start``, 0 if absent [000 L1203-1204].  ``start`` < 1 is -707; beyond the end gives 0.
    The VB two-argument form ``InStr(string_t, string_s)`` (start 1) is accepted as well."""
    if string_s is None:
        start, string_t, string_s = 1, start, string_t
    first = to_int32(start)
    if first < 1:
        raise _out_of_range(f"InStr start {first} must be 1 or more")
    t = _s(string_t)
    if first > len(t) + 1:
        return 0  # type: ignore[return-value]
    return t.find(_s(string_s), first - 1) + 1  # type: ignore[return-value]


def LCase(string: String) -> String:
    """Lower-case copy (ASCII letters)."""
    return ascii_lower(_s(string))  # type: ignore[return-value]


def UCase(string: String) -> String:
    """Upper-case copy (ASCII letters)."""
    return ascii_upper(_s(string))  # type: ignore[return-value]


def Len(string: String) -> Integer:
    """Number of characters (a number is measured as its CStr text)."""
    return len(_s(string))  # type: ignore[return-value]


def Mid(string: String, first: Integer, length: Integer | None = None) -> String:
    """``Mid(s, first [, length])``: 1-based ``first``; an over-long ``length`` is clipped and a
    ``first`` past the end gives "" (spec recommendation); ``first`` < 1 or ``length`` < 0 is -707."""
    s = _s(string)
    f = to_int32(first)
    if f < 1:
        raise _out_of_range(f"Mid start {f} must be 1 or more")
    if length is None:
        return s[f - 1 :]  # type: ignore[return-value]
    n = to_int32(length)
    if n < 0:
        raise _out_of_range(f"Mid length {n} is negative")
    return s[f - 1 : f - 1 + n]  # type: ignore[return-value]


def Hex(number: Any) -> String:
    """Hexadecimal text: Integer conversion, upper case, no prefix, 32-bit two's complement for
    negatives (§14.1 recommendation: ``Hex(-1)`` = "FFFFFFFF", ``Hex(255)`` = "FF")."""
    return format(to_int32(number) & 0xFFFFFFFF, "X")  # type: ignore[return-value]


# -- binary packing (ToBitString / FromBitString, gpl-dictionary §10.2, Table 19-103) --------------

_BIT_TYPES: Final[dict[object, tuple[str, Any]]] = {
    Byte: ("B", to_uint8),
    Short: ("h", to_int16),
    Integer: ("i", to_int32),
    Single: ("f", to_single),
    Double: ("d", to_double),
}
_BIT_NAMES: Final = {"byte": Byte, "short": Short, "integer": Integer, "single": Single, "double": Double}


def _bit_type(type_: Any) -> tuple[str, Any]:
    key = _BIT_NAMES.get(type_.lower()) if isinstance(type_, str) else type_
    try:
        return _BIT_TYPES[key]
    except (KeyError, TypeError):
        raise GplException(INVALID_ARGUMENT, detail=f"bit-string type {type_!r}") from None


def ToBitString(expression: Any, type_: Any, big_endian: Any) -> String:
    """Pack ``expression`` converted to ``type_`` (the keyword Byte/Short/Integer/Single/Double,
    passed as the gpltypes type or its name) into a 1/2/4/8-character string; ``big_endian``
    non-zero puts the most significant byte first.  Out-of-range conversion is -710."""
    code, conv = _bit_type(type_)
    order = ">" if to_number(big_endian) != 0 else "<"
    return struct.pack(order + code, conv(expression)).decode("latin-1")  # type: ignore[return-value]


def FromBitString(string: String, type_: Any, big_endian: Any) -> Any:
    """Unpack a number packed by ToBitString (the first 1/2/4/8 characters of ``string``); a
    shorter string is -783 Short string."""
    code, _ = _bit_type(type_)
    order = ">" if to_number(big_endian) != 0 else "<"
    size = struct.calcsize(code)
    if len(string) < size:
        raise GplException(SHORT_STRING, detail=f"{len(string)} characters, {size} needed")
    try:
        raw = string[:size].encode("latin-1")
    except UnicodeEncodeError:
        raise GplException(INVALID_ARGUMENT, detail="bit string holds characters above 255") from None
    return struct.unpack(order + code, raw)[0]


# -- VB compatibility functions not in the GPL manuals ---------------------------------------------
# The brief asks for them; the manuals do not list them (§14.5), so they are exported separately
# (VB_EXTRAS) and the catalogue may leave them out: a GPL program that defines its own ``Left``
# must not clash with a built-in the real controller does not have.


def Left(string: String, length: Integer) -> String:
    """VB ``Left(s, n)``: the first ``n`` characters (clipped); ``n`` < 0 is -707."""
    n = to_int32(length)
    if n < 0:
        raise _out_of_range(f"Left length {n} is negative")
    return _s(string)[:n]  # type: ignore[return-value]


def Right(string: String, length: Integer) -> String:
    """VB ``Right(s, n)``: the last ``n`` characters (clipped); ``n`` < 0 is -707."""
    n = to_int32(length)
    if n < 0:
        raise _out_of_range(f"Right length {n} is negative")
    s = _s(string)
    return s[len(s) - n :] if n < len(s) else s  # type: ignore[return-value]


def LTrim(string: String) -> String:
    """VB ``LTrim``: leading spaces removed (VB trims spaces only)."""
    return _s(string).lstrip(" ")  # type: ignore[return-value]


def RTrim(string: String) -> String:
    """VB ``RTrim``: trailing spaces removed."""
    return _s(string).rstrip(" ")  # type: ignore[return-value]


def Trim(string: String) -> String:
    """VB ``Trim``: leading and trailing spaces removed."""
    return _s(string).strip(" ")  # type: ignore[return-value]


def Space(number: Integer) -> String:
    """VB ``Space(n)``: ``n`` spaces; ``n`` < 0 is -707."""
    n = to_int32(number)
    if n < 0:
        raise _out_of_range(f"Space({n})")
    return " " * n  # type: ignore[return-value]


def StrComp(string1: String, string2: String, compare: Integer = 0) -> Integer:  # type: ignore[assignment]
    """VB ``StrComp(a, b [, compare])``: -1/0/1; ``compare`` 1 is case-insensitive (text)."""
    return StringMembers.Compare(string1, string2, to_int32(compare) == 1)


def Val(string: String) -> Double:
    """VB ``Val(s)``: the number at the start of ``s`` (blanks ignored), 0 if none; never fails."""
    m = _VAL_RE.match(_s(string).replace(" ", "").replace("\t", ""))
    if m is None or not m.group(0) or m.group(0) in "+-":
        return 0.0  # type: ignore[return-value]
    try:
        return float(parse_number(m.group(0)))  # type: ignore[return-value]
    except GplException:  # a bare "." or "1e" prefix: retry without the dangling part
        text = m.group(0).rstrip("eE+-.")
        return float(parse_number(text)) if text and text not in "+-" else 0.0  # type: ignore[return-value]


def Str(number: Any) -> String:
    """VB ``Str(x)``: CStr text with a leading space for non-negative numbers."""
    text = to_string(to_number(number))
    return (text if text.startswith("-") else " " + text)  # type: ignore[return-value]


GPL_FUNCTIONS: Final = ("Asc", "Chr", "InStr", "LCase", "UCase", "Len", "Mid", "Hex", "ToBitString", "FromBitString")
VB_EXTRAS: Final = ("Left", "Right", "LTrim", "RTrim", "Trim", "Space", "StrComp", "Val", "Str")
