"""GPL value conversions: the one place that decides how a value changes type.

GPL evaluates arithmetic in Double and converts when a value is stored, passed or explicitly
converted (spec gpl-language.md §4.2).  The rules implemented here:

* **To Integer/Short/Byte** rounds to nearest, ties **away from zero** (AMB-10: only "7.875 is
  rounded and stored as 8" is documented [000 L1239-1243]; C-based runtimes round half away from
  zero, and the spec's recommendation is that default).  A result outside the target range is
  **-710 Arithmetic overflow** (§4.2 rule 4: overflow is an error, never a wrap; the dictionary
  infers -710 for CInt & co, §10.2).  NaN also overflows (-710): it has no integer value.
* **To Single** rounds to the nearest IEEE single; a finite value too large for a single is -710
  (§4.2 rule 5 recommends an overflow error).
* **To Boolean**: 0 is False, anything else True (§4.2 rule 8); Strings are parsed as numbers, and
  "True"/"False" (any case) are accepted too (§14.1 recommendation).
* **Boolean to number**: True is -1, False is 0 (§4.1, AMB-8).
* **String to number** (§4.2 rule 6): optional blanks, sign, decimal digits with an optional
  point and exponent, or ``&H``/``&O`` literals (32-bit two's complement like the source literals,
  AMB-36) -- and **whatever follows the number is ignored**: the controller reads ``CInt("20)")``
  as 20 and ``CDbl("180)")`` as 180, which TCS relies on to read every ``.gpo`` file
  (``Class_gpofile.gpl:188-190``, docs/design/real-code.md).  Text that does not start with a
  number, including the empty string, is **-717 Invalid number format** (the controller's text for
  exactly this fault).
* **Number to String** (CStr, ``&``, Console; AMB-22): integral values print without a decimal
  point; other Doubles print with at most 15 significant digits, trailing zeros dropped, switching
  to ``d.dddE+XX`` form when the decimal exponent is below -5 or at least 15 (the .NET "G15" rule
  the spec's recommendation describes: ``CStr(10.2)`` = "10.2", ``CStr(1/3)`` = "0.333333333333333",
  ``CStr(1E+32)`` = "1E+32").  Singles use 7 significant digits (``to_string_single``).  ``-0.0``
  prints "0".  **Booleans print their integer value, "-1" for True and "0" for False.**  The
  manual does not show a Boolean's text, but it does say everything needed to derive it: Boolean
  is one of "all integer types (Boolean, Byte, Short, Integer)" [000 L157], ``CStr`` "converts
  any numeric type to String" [000 L169], True is -1 [000 L944], and ``Console.Write`` takes
  "one number or one String" (spec §14.7), so ``Console.WriteLine(flag)`` [000 L3531] is the
  number overload.  The spec's recommendation for AMB-22 (integral values without a decimal
  point) then gives "-1"/"0".  VB.NET's "True"/"False" was the earlier choice; it contradicts the
  manual's type table, and real GPL code spells the words out itself when it wants them
  (``If p.Straight Then s &= "True" Else s &= "False"``).

Run-time representation (gpltypes): Boolean ``bool``, integer types ``int``, Single/Double
``float``, String ``str``.  ``bool`` is tested with ``type(x) is bool`` before ``int`` because
Python's True is 1, GPL's is -1.

The hot functions (``to_int32`` and friends) test the common case first and allocate nothing.
"""

from __future__ import annotations

import math
import numbers
import re
import struct
from collections.abc import Callable
from typing import Any, Final

from gplrt.lang import errors as _errors
from gplrt.lang.errors import (
    ARITHMETIC_OVERFLOW,
    INVALID_ARGUMENT,
    INVALID_DATA_TYPE,
    INVALID_NUMBER_FORMAT,
    NOTHING_VALUE,
    VALUE_INFINITE_OR_NAN,
    GplException,
)
from gplrt.lang.gpltypes import Boolean, Byte, Double, Integer, Short, Single, String


_INT32_MIN: Final = -2147483648
_INT32_MAX: Final = 2147483647

__all__ = [
    "INVALID_NUMBER_FORMAT",
    "to_int32",
    "to_int16",
    "to_uint8",
    "chk_int32",
    "chk_int16",
    "chk_uint8",
    "chk_double",
    "to_single",
    "to_double",
    "to_number",
    "to_bool",
    "bool_num",
    "to_string",
    "to_string_single",
    "parse_number",
    "round_half_away",
    "convert",
    "converter_for",
    "CBool",
    "CByte",
    "CShort",
    "CInt",
    "CSng",
    "CDbl",
    "CStr",
]


# -- helpers --------------------------------------------------------------------------------------

# the number a text starts with; what follows it is not read (real code: module docstring)
_NUMBER_RE: Final = re.compile(
    r"[ \t\r\n]*([+-]?)[ \t]*(?:(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|&[hH]([0-9a-fA-F]+)|&[oO]([0-7]+))"
)


def parse_number(text: str) -> float | int:
    """The number a String stands for when GPL expects a number (§4.2 rule 6).

    Decimal text gives a float (arithmetic is in Double); ``&H``/``&O`` text gives the 32-bit
    two's complement int (``"&HFFFFFFFF"`` is -1, AMB-36).  Characters after the number are
    ignored (``"20)"`` is 20, as on the controller); text that does not start with a number
    raises -717; a number too large for its type (``"1E400"`` for a Double, as ``"&H1FFFFFFFF"``
    for 32 bits) -710.
    """
    m = _NUMBER_RE.match(text)
    if m is None:
        raise GplException(INVALID_NUMBER_FORMAT, detail=f"not a number: {text!r}")
    sign, dec, exp, hexd, octd = m.groups()
    if dec is not None:
        value: float | int = float(dec + (exp or ""))
        if value == math.inf:
            raise GplException(ARITHMETIC_OVERFLOW, detail=f"number too large for a Double: {text!r}")
    else:
        raw = int(hexd, 16) if hexd is not None else int(octd, 8)
        if raw > 0xFFFFFFFF:
            raise GplException(ARITHMETIC_OVERFLOW, detail=f"literal too large: {text!r}")
        value = raw - 0x100000000 if raw > _INT32_MAX else raw
    return -value if sign == "-" else value


def to_number(x: Any) -> float | int:
    """``x`` as a GPL number: Booleans become -1/0, Strings are parsed (§4.2 rules 6, 9).

    Ints and floats are returned unchanged; Nothing is -782 Object value is Nothing and any other
    object -202 Invalid argument.
    """
    t = type(x)
    if t is float or t is int:
        return x
    if t is bool:
        return -1 if x else 0
    if t is str:
        return parse_number(x)
    if isinstance(x, numbers.Integral):  # numpy integers and other numeric types
        return int(x)
    if isinstance(x, numbers.Real):
        return float(x)
    if x is None:
        raise GplException(NOTHING_VALUE, detail="Nothing where a number is required")
    raise GplException(INVALID_ARGUMENT, detail=f"a number is required, not {_describe(x)}")


def bool_num(b: bool) -> int:
    """A Boolean used as a number: True is -1, False is 0 (§4.1, AMB-8)."""
    return -1 if b else 0


def round_half_away(x: float) -> int:
    """Round a finite float to the nearest integer, ties away from zero (AMB-10).

    ``x - int(x)`` is exact for every float, so no 0.49999999999999994 + 0.5 = 1.0 trap.
    """
    t = int(x)
    f = x - t
    if f >= 0.5:
        return t + 1
    if f <= -0.5:
        return t - 1
    return t


def _describe(x: Any) -> str:
    return "Nothing" if x is None else type(x).__name__


def _rounded(x: Any) -> int:
    """Slow path of the integer conversions: any GPL value to a rounded Python int."""
    t = type(x)
    if t is bool:
        return -1 if x else 0
    if t is str:
        x = parse_number(x)
        if type(x) is int:
            return x
    elif t is not float and t is not int:
        x = to_number(x)
        if type(x) is int:
            return x
    if x != x or x in (math.inf, -math.inf):
        raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} has no integer value")
    return round_half_away(x)


# -- integer targets --------------------------------------------------------------------------------


def to_int32(x: Any) -> int:
    """Convert to Integer (32-bit signed): round half away from zero, -710 on overflow (§4.2)."""
    if type(x) is int:
        if _INT32_MIN <= x <= _INT32_MAX:
            return x
    elif type(x) is float and -2147483648.5 < x < 2147483647.5:
        t = int(x)
        f = x - t
        if f >= 0.5:
            return t + 1
        if f <= -0.5:
            return t - 1
        return t
    else:
        x = _rounded(x)
        if _INT32_MIN <= x <= _INT32_MAX:
            return x
    raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} does not fit an Integer")


#: GplException converts the member values hand-written Python gives it (``ex.Qualifier = "3"``)
#: with this, the one Integer conversion (``gplrt.lang.errors.integer_conversion``).
_errors.integer_conversion = to_int32


def to_int16(x: Any) -> int:
    """Convert to Short (16-bit signed): round half away from zero, -710 on overflow (§4.2)."""
    if type(x) is not int:
        x = _rounded(x)
    if -32768 <= x <= 32767:
        return x
    raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} does not fit a Short")


def to_uint8(x: Any) -> int:
    """Convert to Byte (0..255): round half away from zero, -710 on overflow (§4.2)."""
    if type(x) is not int:
        x = _rounded(x)
    if 0 <= x <= 255:
        return x
    raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} does not fit a Byte")


def chk_int32(x: int) -> int:
    """Range check of an int result stored into an Integer (``i = chk_int32(i + 1)``): -710."""
    if _INT32_MIN <= x <= _INT32_MAX:
        return x
    raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} does not fit an Integer")


def chk_int16(x: int) -> int:
    """Range check of an int result stored into a Short: -710."""
    if -32768 <= x <= 32767:
        return x
    raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} does not fit a Short")


def chk_double(x: float) -> float:
    """Range check of a Double result (``if`` in generated code calls it only for a non-finite
    value): ±Infinity is -710 Arithmetic overflow, NaN is -708 Value infinite or NAN."""
    if x != x:
        raise GplException(VALUE_INFINITE_OR_NAN, detail="the result is not a number")
    if x == math.inf or x == -math.inf:
        raise GplException(ARITHMETIC_OVERFLOW, detail="the result overflows a Double")
    return x


def chk_uint8(x: int) -> int:
    """Range check of an int result stored into a Byte: -710."""
    if 0 <= x <= 255:
        return x
    raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} does not fit a Byte")


# -- real targets -------------------------------------------------------------------------------------

_F32: Final = struct.Struct("f")


def to_double(x: Any) -> float:
    """Convert to Double: Booleans -1/0, Strings parsed (-717 on bad text).

    An integer beyond the Double range (only Python callers can pass one, e.g. ``10**400``) is
    -710 Arithmetic overflow, as for any value that does not fit its type, not Python's
    OverflowError.  Every float conversion of a GPL value goes through here for that reason.
    """
    if type(x) is float:
        return x
    try:
        return float(x if type(x) is int else to_number(x))
    except OverflowError:
        raise GplException(ARITHMETIC_OVERFLOW, detail="the value does not fit a Double") from None


def to_single(x: Any) -> float:
    """Convert to Single: nearest IEEE single (held in a Python float); -710 if too large."""
    if type(x) is not float:
        x = to_double(x)
    try:
        r: float = _F32.unpack(_F32.pack(x))[0]
    except OverflowError:
        r = math.inf
    if (r == math.inf or r == -math.inf) and x == x and x not in (math.inf, -math.inf):
        raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} does not fit a Single")
    return r


# -- Boolean --------------------------------------------------------------------------------------------


def to_bool(x: Any) -> bool:
    """Convert to Boolean: 0 is False, any other number True; "True"/"False" text accepted."""
    t = type(x)
    if t is bool:
        return x
    if t is int or t is float:
        return x != 0
    if t is str:
        low = x.strip().lower()
        if low == "true":
            return True
        if low == "false":
            return False
        return parse_number(x) != 0
    return to_number(x) != 0


# -- String -----------------------------------------------------------------------------------------------


def _format_real(x: float, fmt: str) -> str:
    if x == 0.0:
        return "0"  # also -0.0 (.NET Framework prints "0")
    if x != x:
        return "NaN"
    if x == math.inf:
        return "Infinity"
    if x == -math.inf:
        return "-Infinity"
    s = fmt % x
    if "e" in s:
        s = s.replace("e", "E")
    return s


def to_string(x: Any) -> str:
    """CStr rules (AMB-22): how numbers and Booleans become text (see module docstring)."""
    t = type(x)
    if t is str:
        return x
    if t is float:
        return _format_real(x, "%.15g")
    if t is int:
        return str(x)
    if t is bool:
        return "-1" if x else "0"  # an integer type: True is -1 (module docstring)
    if x is None:
        raise GplException(NOTHING_VALUE, detail="Nothing cannot be converted to a String")
    if isinstance(x, float):
        return _format_real(float(x), "%.15g")
    if isinstance(x, int):
        return str(int(x))
    raise GplException(INVALID_ARGUMENT, detail=f"a {_describe(x)} cannot be converted to a String")


def to_string_single(x: Any) -> str:
    """CStr of a Single-typed value: 7 significant digits (``CSng(0.1)`` prints "0.1")."""
    if type(x) is float:
        return _format_real(x, "%.7g")
    return to_string(x)


# -- the generic entry point ----------------------------------------------------------------------------


def _identity(x: Any) -> Any:
    return x


_CONVERTERS: Final[dict[object, Callable[[Any], Any]]] = {
    Integer: to_int32,
    Short: to_int16,
    Byte: to_uint8,
    Single: to_single,
    Double: to_double,
    Boolean: to_bool,
    String: to_string,
    int: to_int32,
    float: to_double,
    bool: to_bool,
    str: to_string,
}
_BY_NAME: Final[dict[str, Callable[[Any], Any]]] = {
    "integer": to_int32,
    "short": to_int16,
    "byte": to_uint8,
    "single": to_single,
    "double": to_double,
    "boolean": to_bool,
    "string": to_string,
}


def converter_for(gpl_type: object) -> Callable[[Any], Any]:
    """The conversion function for a GPL type (a gpltypes NewType, its name, or a class).

    Object types (classes) convert by identity: GPL has no object conversions (§4.2 rule 12).
    """
    conv = _CONVERTERS.get(gpl_type)
    if conv is not None:
        return conv
    if isinstance(gpl_type, str):
        conv = _BY_NAME.get(gpl_type.lower())
        if conv is not None:
            return conv
        raise GplException(INVALID_DATA_TYPE, detail=f"unknown data type {gpl_type!r}")
    return _identity


def convert(value: Any, gpl_type: object) -> Any:
    """Convert ``value`` to ``gpl_type`` as an assignment would (§4.2 rule 3)."""
    return converter_for(gpl_type)(value)


# -- GPL conversion functions (§14.1) ------------------------------------------------------------------


def CBool(value: Any) -> Boolean:
    """GPL ``CBool``: number or String to Boolean (0 -> False)."""
    return to_bool(value)  # type: ignore[return-value]


def CByte(value: Any) -> Byte:
    """GPL ``CByte``: round half away from zero, -710 outside 0..255."""
    return to_uint8(value)  # type: ignore[return-value]


def CShort(value: Any) -> Short:
    """GPL ``CShort``: round half away from zero, -710 outside -32768..32767."""
    return to_int16(value)  # type: ignore[return-value]


def CInt(value: Any) -> Integer:
    """GPL ``CInt``: round half away from zero, -710 outside the 32-bit range."""
    return to_int32(value)  # type: ignore[return-value]


def CSng(value: Any) -> Single:
    """GPL ``CSng``: nearest single-precision value."""
    return to_single(value)  # type: ignore[return-value]


def CDbl(value: Any) -> Double:
    """GPL ``CDbl``: Double; bad text is -717."""
    return to_double(value)  # type: ignore[return-value]


def CStr(value: Any) -> String:
    """GPL ``CStr``: text of a number (``CStr(10.2)`` = "10.2" [000 L1119]) or Boolean."""
    return to_string(value)  # type: ignore[return-value]
