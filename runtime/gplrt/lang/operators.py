"""GPL operators whose meaning differs from Python's (spec gpl-language.md §4.4, §5).

The lowering emits plain Python where the operand types make it equivalent (``a + b`` for two
Doubles) and calls these functions otherwise.  Each function states its GPL rule; the common
rules are:

* Operands are numbers (``int``/``float``), Booleans (True = -1, False = 0, AMB-8) or Strings.
  A String where a number is expected is parsed (§4.2 rule 6; bad text is -717).
* Arithmetic is done in Double [000 L994-998].  Integer operands of ``+ - *`` give Python ints,
  which equal the Double result exactly within 2**53 and render the same through CStr.
* Division by zero (``/``, ``\\``, ``Mod``) is **-709 Division by 0** [000 L1747], never inf; a
  result that overflows the Double range is **-710 Arithmetic overflow**.
* Comparisons: two Strings compare case-sensitively by character code (Option Compare Binary
  [000 L1132-1137]); otherwise both operands are compared as numbers (a mixed String/number
  comparison parses the String: the spec's recommendation for an UNSPECIFIED case).
"""

from __future__ import annotations

import math
from typing import Any, Final

from gplrt.lang.conversions import parse_number, to_bool, to_double, to_int32, to_number, to_string
from gplrt.lang.errors import ARITHMETIC_OVERFLOW, DIVISION_BY_ZERO, VALUE_OUT_OF_RANGE, GplException

__all__ = [
    "add",
    "sub",
    "mul",
    "neg",
    "div",
    "idiv",
    "mod",
    "power",
    "shl",
    "shr",
    "concat",
    "eq",
    "ne",
    "lt",
    "le",
    "gt",
    "ge",
    "and_",
    "or_",
    "xor",
    "not_",
    "is_nothing",
]

_INF: Final = math.inf


def _num(x: Any) -> float | int:
    t = type(x)
    if t is float or t is int:
        return x
    return to_number(x)


def _finite(r: float | int, what: str) -> float | int:
    if r == _INF or r == -_INF:
        raise GplException(ARITHMETIC_OVERFLOW, detail=f"{what} overflows a Double")
    return r


def _div_zero(what: str) -> GplException:
    return GplException(DIVISION_BY_ZERO, detail=what)


# -- arithmetic -------------------------------------------------------------------------------------


def add(a: Any, b: Any) -> Any:
    """GPL ``+``: two Strings concatenate; otherwise numeric addition, a String operand being
    parsed as a number (``2.34 + "1.01"`` = 3.35 [000 L1096-1100]; ``"a" + 1`` is -717)."""
    ta = type(a)
    tb = type(b)
    if ta is str:
        if tb is str:
            return a + b
        a = parse_number(a)
    elif ta is not float and ta is not int:
        a = to_number(a)
    if tb is not float and tb is not int:
        b = to_number(b)
    return _finite(a + b, "+")


def sub(a: Any, b: Any) -> float | int:
    """GPL ``-`` on Booleans or Strings (converted to numbers first)."""
    return _finite(_num(a) - _num(b), "-")


def mul(a: Any, b: Any) -> float | int:
    """GPL ``*`` on Booleans or Strings (converted to numbers first)."""
    return _finite(_num(a) * _num(b), "*")


def neg(a: Any) -> float | int:
    """GPL unary ``-`` (``-True`` is 1)."""
    return -_num(a)


def div(a: Any, b: Any) -> float:
    """GPL ``/``: always real division (``5 / 2`` = 2.5); a zero divisor is -709."""
    b = _num(b)
    if b == 0:
        raise _div_zero("/ by zero")
    try:
        return _finite(_num(a) / b, "/")  # type: ignore[return-value]
    except OverflowError:
        raise GplException(ARITHMETIC_OVERFLOW, detail="/ overflows a Double") from None


def idiv(a: Any, b: Any) -> int:
    """GPL ``\\``: the real quotient truncated toward zero (``2.3 \\ 2`` = 1, ``-7 \\ 2`` = -3).

    Unlike VB.NET the operands are not rounded first (AMB-12: ``7.9 \\ 2`` = 3).  Zero divisor:
    -709.  The result is an int (an integral Double value).
    """
    if type(a) is int and type(b) is int and b:
        # Exact integer truncation equals trunc of the Double quotient for these operands.
        q = abs(a) // abs(b)
        return q if (a < 0) == (b < 0) else -q
    b = _num(b)
    if b == 0:
        raise _div_zero("\\ by zero")
    try:
        q = _num(a) / b
    except OverflowError:
        raise GplException(ARITHMETIC_OVERFLOW, detail="\\ overflows a Double") from None
    if q == _INF or q == -_INF or q != q:
        raise GplException(ARITHMETIC_OVERFLOW, detail="\\ overflows a Double")
    return int(q)


def mod(a: Any, b: Any) -> float | int:
    """GPL ``Mod``: the real remainder, sign of the dividend (``13.3 Mod 2`` = 1.3,
    ``-7 Mod 3`` = -1, ``7 Mod -3`` = 1); zero divisor -709 (spec recommendation)."""
    if type(a) is int and type(b) is int and b:
        r = abs(a) % abs(b)
        return -r if a < 0 else r
    a = _num(a)
    b = _num(b)
    if b == 0:
        raise _div_zero("Mod by zero")
    if type(a) is int and type(b) is int:
        r = abs(a) % abs(b)
        return -r if a < 0 else r
    return math.fmod(a, b)


def power(a: Any, b: Any) -> float:
    """GPL ``^`` in Double: a negative base needs an integral exponent (else -707, never NaN
    [000 L869-875]); ``0 ^ -1`` is -709; a result beyond the Double range is -710."""
    x = to_double(a)
    y = to_double(b)
    if x < 0.0 and y != math.floor(y):
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"{x} ^ {y}: negative base needs an integral power")
    if x == 0.0 and y < 0.0:
        raise _div_zero(f"0 ^ {y}")
    try:
        return _finite(math.pow(x, y), "^")  # type: ignore[return-value]
    except OverflowError:
        raise GplException(ARITHMETIC_OVERFLOW, detail=f"{x} ^ {y} overflows a Double") from None


# -- shifts ------------------------------------------------------------------------------------------


def shl(a: Any, n: Any) -> int:
    """GPL ``<<``: arithmetic left shift of a 32-bit Integer, zeros shifted in [000 L923-930].

    Both operands go through the Integer conversion (rounding, -710 on overflow); the count is
    taken modulo 32 and the result wraps to 32-bit two's complement (spec recommendation).
    """
    r = (to_int32(a) << (to_int32(n) & 31)) & 0xFFFFFFFF
    return r - 0x100000000 if r & 0x80000000 else r


def shr(a: Any, n: Any) -> int:
    """GPL ``>>``: arithmetic right shift (the sign bit is shifted in for negatives)."""
    return to_int32(a) >> (to_int32(n) & 31)


# -- strings ----------------------------------------------------------------------------------------


def concat(a: Any, b: Any) -> str:
    """GPL ``&``: concatenation; numbers and Booleans are rendered with CStr rules (AMB-11)."""
    return (a if type(a) is str else to_string(a)) + (b if type(b) is str else to_string(b))


# -- comparisons -------------------------------------------------------------------------------------


def _pair(a: Any, b: Any) -> tuple[Any, Any]:
    ta = type(a)
    tb = type(b)
    if ta is str and tb is str:
        return a, b
    return _num(a), _num(b)


def eq(a: Any, b: Any) -> bool:
    """GPL ``=`` (case-sensitive for Strings; numbers compared as Double)."""
    a, b = _pair(a, b)
    return a == b


def ne(a: Any, b: Any) -> bool:
    """GPL ``<>``."""
    a, b = _pair(a, b)
    return a != b


def lt(a: Any, b: Any) -> bool:
    """GPL ``<`` (Strings by character code: ``"B" < "a"``; ``True < False`` as -1 < 0)."""
    a, b = _pair(a, b)
    return a < b


def le(a: Any, b: Any) -> bool:
    """GPL ``<=``."""
    a, b = _pair(a, b)
    return a <= b


def gt(a: Any, b: Any) -> bool:
    """GPL ``>``."""
    a, b = _pair(a, b)
    return a > b


def ge(a: Any, b: Any) -> bool:
    """GPL ``>=``."""
    a, b = _pair(a, b)
    return a >= b


# -- Nothing ----------------------------------------------------------------------------------------


def is_nothing(x: Any) -> bool:
    """GPL ``x Is Nothing`` on a value whose type is known only at run time (a stub's result).

    An object is Nothing when it is ``None``.  A String is Nothing when it is empty: GPL code tests
    ``s Is Nothing`` on Strings and means "has no text", and gpl2py stores Nothing into a String as
    "" (docs/design/real-code.md), so both spellings of "no string" answer True here."""
    return x is None or (type(x) is str and not x)


# -- logical / bitwise ----------------------------------------------------------------------------------


def and_(a: Any, b: Any) -> bool | int:
    """GPL ``And``: logical when both operands are Boolean, else bitwise on 32-bit Integers
    (True = -1; non-integral operands are rounded) [000 L947-962].  Both are always evaluated."""
    if type(a) is bool and type(b) is bool:
        return a and b
    return to_int32(a) & to_int32(b)


def or_(a: Any, b: Any) -> bool | int:
    """GPL ``Or``: logical for two Booleans, else bitwise (``5 Or 2`` = 7, ``True Or 2`` = -1)."""
    if type(a) is bool and type(b) is bool:
        return a or b
    return to_int32(a) | to_int32(b)


def xor(a: Any, b: Any) -> bool | int:
    """GPL ``Xor``: logical for two Booleans, else bitwise."""
    if type(a) is bool and type(b) is bool:
        return a is not b
    return to_int32(a) ^ to_int32(b)


def not_(a: Any) -> bool:
    """GPL ``Not``: always logical, even on Integers (AMB-13, [000 L944-945]):
    0 -> True (-1), any non-zero -> False (0).  ``Not 5`` is False, unlike VB's bitwise Not."""
    t = type(a)
    if t is bool:
        return not a
    if t is int or t is float:
        return a == 0
    return not to_bool(a)
