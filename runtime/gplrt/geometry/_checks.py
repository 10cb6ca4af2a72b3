"""Argument checks shared by Location and RefFrame, raising the controller's error codes.

Generated code already passes GPL-typed values, but the same members are called from hand-written
Python (setup files, notebooks), where ``loc.X = "12"`` or ``loc.ZWorld = "False"`` are easy to
write.  Every conversion therefore goes through ``gplrt.lang.conversions``, the runtime's one place
for GPL's conversion rules, so that such calls behave as GPL would (a numeric String is parsed, a
Boolean is -1/0) or fail with a GPL error (-717 bad number text, -202 an object where a number is
required, -782 Nothing) instead of a bare Python ``ValueError``/``AttributeError``.
The fast paths (an ``int`` or ``float`` argument) allocate nothing: X/Y/Z writes sit in hot loops.
"""

from __future__ import annotations

import math
from typing import Any

from gplrt.lang.conversions import to_bool, to_int32, to_number, to_string
from gplrt.lang.errors import INVALID_ARGUMENT, NOTHING_VALUE, VALUE_INFINITE_OR_NAN, VALUE_OUT_OF_RANGE, GplException


def to_integer(value: Any, what: str) -> int:
    """GPL's conversion of an argument to Integer: round half away from zero (D0:1242).

    Booleans are -1/0 and numeric Strings are parsed (conversions rules); NaN and infinities are
    -708 *Value infinite or NAN* (the value names no element at all), a finite value beyond
    32 bits -710 *Arithmetic overflow* like any Integer conversion.
    """
    if type(value) is int:
        return value
    v = value if type(value) is float else to_number(value)
    if type(v) is float and not math.isfinite(v):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{what} = {v}")
    return to_int32(v)


def finite(value: Any, what: str) -> float:
    """``value`` as a Double; NaN and infinities are GPL error -708 (conversion rules as above)."""
    v = value if type(value) is float else float(to_number(value))
    if not math.isfinite(v):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{what} = {v}")
    return v


def boolean(value: Any) -> bool:
    """GPL Boolean of ``value`` (0 False, other numbers True, "True"/"False" text)."""
    return value if type(value) is bool else to_bool(value)


def text(value: Any) -> str:
    """GPL String of ``value`` (CStr rules: ``1.0`` is "1", True is "-1"... see conversions)."""
    return value if type(value) is str else to_string(value)


def in_range(value: int, low: int, high: int, what: str) -> int:
    """``value`` if ``low <= value <= high``, else GPL error -707 *Value out-of-range*."""
    if not low <= value <= high:
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"{what} = {value}, expected {low}..{high}")
    return value


def not_nothing(obj: object, what: str) -> None:
    """GPL error -782 *Object value is Nothing* when ``obj`` is GPL's Nothing (None)."""
    if obj is None:
        raise GplException(NOTHING_VALUE, detail=f"{what} is Nothing")


def wrong_object(obj: object, what: str, expected: str) -> GplException:
    """The error for an argument that is not the object a member needs.

    Nothing is -782 *Object value is Nothing*; any other wrong object (a number, a String, a
    RefFrame where a Location is needed) is -202 *Invalid argument*, the code the conversions
    use for "a number is required, not X".  The transpiler's type check stops this in GPL source;
    it is reached from Python only.
    """
    if obj is None:
        return GplException(NOTHING_VALUE, detail=f"{what} is Nothing")
    return GplException(INVALID_ARGUMENT, detail=f"{what} must be a {expected}, not {type(obj).__name__}")
