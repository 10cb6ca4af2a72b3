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
from typing import Any, TypeVar

from gplrt.geometry.transforms import Pose
from gplrt.lang.conversions import to_bool, to_double, to_int32, to_number, to_string
from gplrt.lang.errors import (
    ARITHMETIC_OVERFLOW,
    INVALID_ARGUMENT,
    NOTHING_VALUE,
    VALUE_INFINITE_OR_NAN,
    VALUE_OUT_OF_RANGE,
    GplException,
)


_INF = math.inf
_P = TypeVar("_P", bound=tuple[float, ...])


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
    v = value if type(value) is float else to_double(value)
    if not math.isfinite(v):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{what} = {v}")
    return v


def finite_pose(pose: _P, what: str) -> _P:
    """``pose`` (a 12-float pose tuple, or any tuple of floats) if every component is finite.

    The result of Location/RefFrame arithmetic goes through here, so that a pose leaving the
    Double range is the error ordinary arithmetic gives for an infinite result
    (``gplrt.lang.operators``): -710 *Arithmetic overflow*.  A NaN component is -710 too: the
    operands are finite (setters and ``valid_pose`` see to that), so a NaN is an overflowed
    intermediate cancelling another (``inf - inf`` in ``Inverse(a) · b``), not a NaN operand.
    Fast path: the sum of finite components is finite (``s - s == 0``) except when the sum alone
    overflows; only then, or for a bad pose, are the components looked at one by one.  This runs on
    every ``Mul``, so it must cost little next to the 36 multiplications of the product.
    """
    s = sum(pose)
    if s - s == 0.0:
        return pose
    for v in pose:
        if not math.isfinite(v):
            raise GplException(ARITHMETIC_OVERFLOW, detail=f"{what} overflows a Double")
    return pose


def valid_pose(pose: Any, what: str) -> Pose:
    """``pose`` built by Python (``Location.from_pose``) if it is 12 finite numbers.

    A non-finite component is -708 *Value infinite or NAN*: a bad *input*, like ``loc.X = NaN``.
    Anything but a tuple of 12 numbers (None, a short tuple, Strings) is -202 *Invalid argument*,
    the code ``wrong_object`` gives Python callers, rather than a TypeError or unpacking error
    from deep inside the first computation that uses it.
    """
    try:
        s = sum(pose)
        n = len(pose)
    except TypeError:
        code = NOTHING_VALUE if pose is None else INVALID_ARGUMENT
        raise GplException(code, detail=f"{what} must be 12 numbers, not {pose!r:.60}") from None
    if n != 12:
        raise GplException(INVALID_ARGUMENT, detail=f"{what} has {n} components, not 12")
    if type(pose) is not tuple:
        pose = tuple(pose)
    if s - s == 0.0 or all(math.isfinite(v) for v in pose):
        return pose  # type: ignore[no-any-return]
    raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{what} has a non-finite component")


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
