"""V+ operators and numeric functions (spec §2.3, §3.2-§3.3; L4198-4349, L5417-5503).

Relational and logical results are -1.0 (true) / 0.0 (false); any nonzero value is true.  Logical
operators evaluate both operands (their callers pass values, so nothing short-circuits: L4326-4328).
Bitwise operators work on 32-bit two's complement integers ([D] the Guide shows 6 bits only, Q11).
String comparison ignores case while the UPPER switch is on (its default, L5916-5919).
Trigonometry is in degrees.
"""

from __future__ import annotations

import math
import random as _random
from typing import Any

from gplrt.vplus.errors import DIVIDE_BY_ZERO, ILLEGAL_VALUE, STRING_TOO_LONG, TYPE_MISMATCH, VError
from gplrt.vplus.system import switch
from gplrt.vplus.values import MAX_STRING, round_half_away

TRUE = -1.0
FALSE = 0.0
PI = math.pi


def num(x: Any) -> float:
    """A real operand: a string or location where a number is needed is *Data type mismatch*
    (a V+ error REACTE can trap, never a Python TypeError)."""
    if type(x) is float:
        return x
    if isinstance(x, (int, float)) and not isinstance(x, bool):
        return float(x)
    if isinstance(x, bool):
        return -1.0 if x else 0.0
    raise VError(TYPE_MISMATCH, detail=f"a number was needed, not {type(x).__name__}")


def truth(x: Any) -> bool:
    return x != 0


def _b(flag: bool) -> float:
    return -1.0 if flag else 0.0


def to_int(x: Any) -> int:
    """An integer argument: rounded half away from zero (L333-335)."""
    return int(round_half_away(num(x)))


def _i32(x: Any) -> int:
    n = to_int(x) & 0xFFFFFFFF
    return n - (1 << 32) if n & 0x80000000 else n


def add(a: Any, b: Any) -> Any:
    if isinstance(a, str) or isinstance(b, str):
        if not (isinstance(a, str) and isinstance(b, str)):
            raise VError(ILLEGAL_VALUE, detail="string + number")
        s = a + b
        if len(s) > MAX_STRING:
            raise VError(STRING_TOO_LONG, detail=f"{len(s)} characters")
        return s
    return num(a) + num(b)


def sub(a: Any, b: Any) -> float:
    return num(a) - num(b)


def mul(a: Any, b: Any) -> float:
    return num(a) * num(b)


def div(a: Any, b: Any) -> float:
    a, b = num(a), num(b)
    if b == 0:
        raise VError(DIVIDE_BY_ZERO)
    return a / b


def mod(a: Any, b: Any) -> float:
    """Remainder with the sign of the dividend ([D] as C fmod; ``9 MOD 6`` = 3, L3929)."""
    a, b = num(a), num(b)
    if b == 0:
        raise VError(DIVIDE_BY_ZERO)
    return math.fmod(a, b)


def neg(a: Any) -> float:
    return -num(a)


def _cmp_operands(a: Any, b: Any) -> tuple[Any, Any]:
    if isinstance(a, str) and isinstance(b, str):
        if switch("UPPER"):
            return a.upper(), b.upper()
    return a, b


def eq(a: Any, b: Any) -> float:
    a, b = _cmp_operands(a, b)
    return _b(a == b)


def ne(a: Any, b: Any) -> float:
    a, b = _cmp_operands(a, b)
    return _b(a != b)


def lt(a: Any, b: Any) -> float:
    a, b = _cmp_operands(a, b)
    return _b(a < b)


def le(a: Any, b: Any) -> float:
    a, b = _cmp_operands(a, b)
    return _b(a <= b)


def gt(a: Any, b: Any) -> float:
    a, b = _cmp_operands(a, b)
    return _b(a > b)


def ge(a: Any, b: Any) -> float:
    a, b = _cmp_operands(a, b)
    return _b(a >= b)


def and_(a: Any, b: Any) -> float:
    return _b(a != 0 and b != 0)


def or_(a: Any, b: Any) -> float:
    return _b(a != 0 or b != 0)


def xor_(a: Any, b: Any) -> float:
    return _b((a != 0) != (b != 0))


def not_(a: Any) -> float:
    return _b(a == 0)


def band(a: Any, b: Any) -> float:
    return float(_i32(a) & _i32(b))


def bor(a: Any, b: Any) -> float:
    return float(_i32(_i32(a) | _i32(b)))


def bxor(a: Any, b: Any) -> float:
    return float(_i32(_i32(a) ^ _i32(b)))


def com(a: Any) -> float:
    return float(_i32(~_i32(a)))


def bmask(first: Any, last: Any = None) -> float:
    """``BMASK(b1[, b2])``: bits b1..b2 set (bit 1 = value 1)."""
    lo = to_int(first)
    hi = to_int(last) if last is not None else lo
    lo, hi = min(lo, hi), max(lo, hi)
    if lo < 1 or hi > 32:
        raise VError(ILLEGAL_VALUE, detail=f"BMASK({lo}, {hi})")
    return float(_i32(((1 << hi) - 1) ^ ((1 << (lo - 1)) - 1)))


# -- numeric functions (L5417-5457) -----------------------------------------------------------------

def abs_(x: Any) -> float:
    return abs(float(x))


def sin(deg: Any) -> float:
    return math.sin(math.radians(float(deg)))


def cos(deg: Any) -> float:
    return math.cos(math.radians(float(deg)))


def tan(deg: Any) -> float:
    return math.tan(math.radians(float(deg)))


def atan2(y: Any, x: Any) -> float:
    return math.degrees(math.atan2(float(y), float(x)))


def sqrt(x: Any) -> float:
    if x < 0:
        raise VError(ILLEGAL_VALUE, detail=f"SQRT({x})")
    return math.sqrt(float(x))


def sqr(x: Any) -> float:
    """``SQR``: the square (``SQR(2) - 1`` = 3, L3928)."""
    return float(x) * float(x)


def cubrt(x: Any) -> float:
    x = float(x)
    return math.copysign(abs(x) ** (1.0 / 3.0), x)


def int_(x: Any) -> float:
    """``INT``: the integer part (truncated toward zero)."""
    return float(math.trunc(float(x)))


def fract(x: Any) -> float:
    x = float(x)
    return x - math.trunc(x)


def sign(x: Any) -> float:
    x = float(x)
    return 1.0 if x > 0 else -1.0 if x < 0 else 0.0


def max_(*xs: Any) -> float:
    return float(max(float(x) for x in xs))


def min_(*xs: Any) -> float:
    return float(min(float(x) for x in xs))


def outside(low: Any, x: Any, high: Any) -> float:
    """``OUTSIDE(low, value, high)``: -1 when value is not within [low, high]."""
    return _b(not float(low) <= float(x) <= float(high))


def random() -> float:
    """``RANDOM``: a number in [0, 1)."""
    return _random.random()
