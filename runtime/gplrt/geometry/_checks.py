"""Argument checks shared by Location and RefFrame, raising the controller's error codes."""

from __future__ import annotations

import math

from gplrt.lang.errors import NOTHING_VALUE, VALUE_INFINITE_OR_NAN, VALUE_OUT_OF_RANGE, GplException


def to_integer(value: float, what: str) -> int:
    """GPL's conversion of a numeric argument to Integer: round half away from zero (D0:1242)."""
    if isinstance(value, int):  # bool is an int: True -> 1 would be wrong for GPL (-1), keep as is
        return int(value)
    v = float(value)
    if not math.isfinite(v):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{what} = {v}")
    return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)


def finite(value: float, what: str) -> float:
    """``value`` as a float; NaN and infinities are GPL error -708."""
    v = float(value)
    if not math.isfinite(v):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{what} = {v}")
    return v


def in_range(value: int, low: int, high: int, what: str) -> int:
    """``value`` if ``low <= value <= high``, else GPL error -707 *Value out-of-range*."""
    if not low <= value <= high:
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"{what} = {value}, expected {low}..{high}")
    return value


def not_nothing(obj: object, what: str) -> None:
    """GPL error -782 *Object value is Nothing* when ``obj`` is GPL's Nothing (None)."""
    if obj is None:
        raise GplException(NOTHING_VALUE, detail=f"{what} is Nothing")
