"""TMscript's values at run time: the six types, their conversions and operators (spec §1.5-§1.8).

Representation: ``byte`` and ``int`` are Python ``int`` (wrapped when stored: byte mod 256, int
mod 2**32 signed, manual L554-L578); ``float`` is ``numpy.float32`` (every float computation is
binary32, L8889, L9081); ``double`` is ``numpy.float64``; ``bool`` and ``string`` are Python's;
an array is :class:`Array` (one dimension, typed, at most 2048 elements, L706-L718).  A plain Python
``float`` is a literal not yet typed: alone it is a float (the smallest type, L514-L552), next to a
typed operand it takes that operand's type.  A run-time fault is :class:`TMError`, the project's
"stops by error"; there is no catch in TMscript (L1095-L1148).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import NoReturn

import numpy as np

F32 = np.float32
F64 = np.float64
MAX_ARRAY = 2048


class TMError(Exception):
    """A run-time error of a TMscript program (the project stops by error)."""

    #: ``"file.tms:line"`` when known otherwise than from the traceback (a queued motion's line).
    where: str | None = None


class Unset:
    """A ``define`` global of a class type (``TPoint P1 = ...``) whose declaration has not run
    because an earlier initialiser of the section failed, as ``errorstop`` may see it: any use
    is the script's error (a primitive global has its type's default instead)."""

    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        object.__setattr__(self, "name", name)

    def _fail(self) -> NoReturn:
        raise TMError(f"'{self.name}' has no value: the define section failed before its declaration")

    def __getattr__(self, attr: str) -> NoReturn:
        if attr.startswith("__"):  # (Python's own protocol look-ups: not the script's)
            raise AttributeError(attr)
        self._fail()

    def __setattr__(self, attr: str, value: object) -> NoReturn:
        self._fail()

    def __getitem__(self, key: object) -> NoReturn:
        self._fail()

    def __setitem__(self, key: object, value: object) -> NoReturn:
        self._fail()

    def __str__(self) -> str:
        self._fail()


# --- conversions --------------------------------------------------------------------------------
def _parse_number(text: str) -> int | float:
    t = text.strip()
    low = t.lower()
    try:
        if low.startswith(("0x", "-0x", "+0x")):
            return int(low.replace("0x", "", 1), 16)
        if low.startswith(("0b", "-0b", "+0b")):
            return int(low.replace("0b", "", 1), 2)
        try:
            return int(t, 10)
        except ValueError:
            value = float(t)
    except ValueError:
        raise TMError(f'"{text}" is not a number') from None
    if not math.isfinite(value):
        raise TMError(f'"{text}" is not a number')
    return value


def _number(x: object, what: str) -> int | float:
    if isinstance(x, bool):
        raise TMError(f"a bool cannot be converted to {what}")
    if isinstance(x, str):
        return _parse_number(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        v = float(x)
        if not math.isfinite(v):
            raise TMError(f"{format_value(x)} cannot be converted to {what}")
        return v
    if isinstance(x, Array):
        raise TMError(f"an array cannot be converted to {what}")
    raise TMError(f"{x!r} cannot be converted to {what}")


def i32(v: int) -> int:
    """``v`` wrapped to a 32-bit signed int (L567-L578)."""
    v &= 0xFFFFFFFF
    return v - 0x100000000 if v & 0x80000000 else v


def to_int(x: object) -> int:
    """To ``int``: floats truncate toward zero, strings are parsed (L830-L990)."""
    if type(x) is int:
        return i32(x)
    v = _number(x, "int")
    return i32(int(v)) if isinstance(v, int) else i32(int(math.trunc(v)))


def to_byte(x: object) -> int:
    """To ``byte``: the low 8 bits (``(byte)1000`` is 232, L830-L866)."""
    if type(x) is int:
        return x & 0xFF
    v = _number(x, "byte")
    return int(math.trunc(v)) & 0xFF


def to_float(x: object) -> np.float32:
    if type(x) is F32:
        return x  # type: ignore[return-value]
    v = _number(x, "float")
    if abs(v) > 3.4028234663852886e38:
        raise TMError(f"{v} is out of the range of a float")
    return F32(v)


def to_double(x: object) -> np.float64:
    if type(x) is F64:
        return x  # type: ignore[return-value]
    if type(x) is F32:
        return F64(x)
    v = _number(x, "double")
    if isinstance(v, int) and abs(v) > 1.7976931348623157e308:  # (an int past the double's range)
        raise TMError(f"{v} is out of the range of a double")
    return F64(v)


def to_bool(x: object) -> bool:
    if isinstance(x, bool):
        return x
    if isinstance(x, str):
        return x != "false" and x != ""  # "true" true, "false" false, other non-empty true (L830ff)
    if isinstance(x, (int, float, np.number)):
        return x != 0
    raise TMError("an array cannot be converted to bool")


def to_string(x: object) -> str:
    return x if type(x) is str else format_value(x)


CONVERT = {"byte": to_byte, "int": to_int, "float": to_float, "double": to_double, "bool": to_bool,
           "string": to_string}


def cast(type_name: str, x: object, array: bool = False) -> object:
    """An explicit cast ``(type)x`` or ``(type[])x``; a bool does not cast to a number (L874)."""
    if array:
        if not isinstance(x, (Array, list)):
            raise TMError(f"a scalar cannot be cast to {type_name}[]")
        return Array(type_name, x)
    if isinstance(x, (Array, list)):
        raise TMError(f"an array cannot be cast to {type_name}")
    return CONVERT[type_name](x)


def store(type_name: str, x: object, array: bool = False) -> object:
    """``x`` as a variable of the declared type holds it (the implicit conversion of L943-L990)."""
    if array:
        if isinstance(x, Array) and x.type == type_name:
            return Array(type_name, x)  # (a copy: arrays are values)
        if not isinstance(x, (Array, list, tuple)):
            raise TMError(f"a {type_of(x)} cannot be stored in a {type_name}[]")
        return Array(type_name, x)
    if isinstance(x, (Array, list)):
        raise TMError(f"an array cannot be stored in a {type_name}")
    if type_name == "bool" and not isinstance(x, bool) and not isinstance(x, str):
        return to_bool(x)
    return CONVERT[type_name](x)


def type_of(x: object) -> str:
    """The TMscript type name of a value (a plain int literal is its smallest type)."""
    if isinstance(x, bool):
        return "bool"
    if isinstance(x, int):
        return "byte" if 0 <= x <= 255 else "int"
    if type(x) is F64:
        return "double"
    if isinstance(x, (float, np.floating)):
        return "float"
    if isinstance(x, str):
        return "string"
    if isinstance(x, Array):
        return x.type + "[]"
    return "?"


class Array(list):  # type: ignore[type-arg]
    """A TMscript array: typed elements, at most 2048, no negative index (L706-L718)."""

    __slots__ = ("type",)

    def __init__(self, type_name: str, items: Iterable[object] = ()) -> None:
        conv = CONVERT[type_name]
        super().__init__(conv(v) for v in items)
        self.type = type_name
        if len(self) > MAX_ARRAY:
            raise TMError(f"an array has at most {MAX_ARRAY} elements, not {len(self)}")

    def _check(self, i: object) -> int:
        if isinstance(i, bool) or not isinstance(i, (int, np.integer)):
            i = to_int(i)
        if not 0 <= i < len(self):
            raise TMError(f"index {i} is out of the range of an array of {len(self)} elements")
        return int(i)

    def __getitem__(self, i):  # type: ignore[no-untyped-def, override]
        return list.__getitem__(self, self._check(i))

    def __setitem__(self, i, v):  # type: ignore[no-untyped-def, override]
        list.__setitem__(self, self._check(i), CONVERT[self.type](v))

    def __repr__(self) -> str:
        return format_value(self)


# --- formatting ---------------------------------------------------------------------------------
def _exp(text: str) -> str:
    """Python's ``1e-05`` as .NET's ``1E-05``."""
    if "e" not in text:
        return text
    mant, exp = text.split("e")
    sign = "-" if exp.startswith("-") else "+"
    return f"{mant}E{sign}{exp.lstrip('+-').zfill(2)}"


def format_float(v: float, single: bool) -> str:
    """Shortest round-trip text of a binary32 (``single``) or binary64 value, .NET style:
    ``3.3333333``, ``2.1979466E+09``, ``6.309574E-05`` (spec §1.8, "Number formatting")."""
    if math.isnan(v):
        return "NaN"
    if math.isinf(v):
        return "Infinity" if v > 0 else "-Infinity"
    if v == int(v) and abs(v) < (1e7 if single else 1e15):
        return str(int(v))
    text = np.format_float_scientific(F32(v), unique=True, trim="-") if single else repr(float(v))
    if single:
        mant, exp = text.split("e")
        e = int(exp)
        if -4 <= e < 7:
            text = np.format_float_positional(F32(v), unique=True, trim="-")
        else:
            text = f"{mant}e{e:+03d}"
    elif "e" in text:
        mant, exp = text.split("e")
        e = int(exp)
        if -4 <= e < 15:
            text = np.format_float_positional(v, unique=True, trim="-")
    return _exp(text)


def format_value(x: object) -> str:
    """A value as TMscript prints it (``true``, ``1.23``, ``{1,2,3}``)."""
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if type(x) is F64:
        return format_float(float(x), single=False)
    if isinstance(x, (float, np.floating)):
        return format_float(float(x), single=True)
    if isinstance(x, str):
        return x
    if isinstance(x, (list, tuple)):
        return "{" + ",".join(format_value(v) for v in x) + "}"
    return str(x)


# --- operators ----------------------------------------------------------------------------------
def _kind(x: object) -> int:
    """0 int, 1 untyped float literal, 2 float, 3 double; raises for what is not a number."""
    t = type(x)
    if t is int:
        return 0
    if t is F32:
        return 2
    if t is F64:
        return 3
    if t is float:
        return 1
    if t is bool:
        raise TMError("a bool is not a number")
    if isinstance(x, (int, np.integer)):
        return 0
    if isinstance(x, str):
        raise TMError(f'the string "{x}" is not a number')
    raise TMError(f"{type_of(x)} is not a number")


def _floating(a: object, b: object, ka: int, kb: int) -> tuple[object, object, type]:
    k = max(ka, kb, 2)
    t = F64 if k == 3 else F32
    return t(a), t(b), t


def add(a: object, b: object) -> object:
    """``a + b``: text when either side is a string (L144 of the spec), else arithmetic."""
    if type(a) is str or type(b) is str:
        return to_string(a) + to_string(b)
    ka, kb = _kind(a), _kind(b)
    if ka == kb == 0:
        return i32(a + b)  # type: ignore[operator]
    x, y, t = _floating(a, b, ka, kb)
    return t(x + y)  # type: ignore[operator]


def sub(a: object, b: object) -> object:
    ka, kb = _kind(a), _kind(b)
    if ka == kb == 0:
        return i32(a - b)  # type: ignore[operator]
    x, y, t = _floating(a, b, ka, kb)
    return t(x - y)  # type: ignore[operator]


def mul(a: object, b: object) -> object:
    ka, kb = _kind(a), _kind(b)
    if ka == kb == 0:
        return i32(a * b)  # type: ignore[operator]
    x, y, t = _floating(a, b, ka, kb)
    return t(x * y)  # type: ignore[operator]


def div(a: object, b: object) -> object:
    """Integer ÷ integer truncates (10/3 = 3, L740-L782); by zero is an error."""
    ka, kb = _kind(a), _kind(b)
    if ka == kb == 0:
        if b == 0:
            raise TMError("division by zero")
        q = abs(a) // abs(b)  # type: ignore[arg-type, operator]
        return i32(q if (a >= 0) == (b >= 0) else -q)  # type: ignore[operator]
    x, y, t = _floating(a, b, ka, kb)
    if y == 0:
        raise TMError("division by zero")
    return t(x / y)  # type: ignore[operator]


def mod(a: object, b: object) -> object:
    ka, kb = _kind(a), _kind(b)
    if ka == kb == 0:
        if b == 0:
            raise TMError("division by zero")
        r = abs(a) % abs(b)  # type: ignore[arg-type, operator]
        return r if a >= 0 else -r  # type: ignore[operator]
    x, y, t = _floating(a, b, ka, kb)
    if y == 0:
        raise TMError("division by zero")
    return t(math.fmod(x, y))  # type: ignore[arg-type]


def neg(a: object) -> object:
    k = _kind(a)
    return i32(-a) if k == 0 else -a  # type: ignore[operator]


def _ints(a: object, b: object, op: str) -> tuple[int, int]:
    if _kind(a) != 0 or _kind(b) != 0:
        raise TMError(f"'{op}' needs integers")
    return int(a), int(b)  # type: ignore[call-overload]


def bit_and(a: object, b: object) -> int:
    x, y = _ints(a, b, "&")
    return i32(x & y)


def bit_or(a: object, b: object) -> int:
    x, y = _ints(a, b, "|")
    return i32(x | y)


def bit_xor(a: object, b: object) -> int:
    x, y = _ints(a, b, "^")
    return i32(x ^ y)


def shl(a: object, b: object) -> int:
    x, y = _ints(a, b, "<<")
    return i32(x << (y & 31))


def shr(a: object, b: object) -> int:
    x, y = _ints(a, b, ">>")
    return i32(x >> (y & 31))


def invert(a: object) -> int:
    x, _ = _ints(a, 0, "~")
    return i32(~x)


def truth(x: object) -> bool:
    """A condition: bool; a number ≠ 0; a string "true"/"True" (L1461-L1465)."""
    if isinstance(x, bool):
        return x
    if isinstance(x, str):
        return x in ("true", "True")
    if isinstance(x, (int, float, np.number)):
        return bool(x != 0)
    raise TMError("an array is not a condition")


def eq(a: object, b: object) -> bool:
    """``a == b``: numbers by value, a string against a number by the number's text."""
    if type(a) is str and type(b) is not str and not isinstance(b, Array):
        return a == to_string(b)
    if type(b) is str and type(a) is not str and not isinstance(a, Array):
        return b == to_string(a)
    return bool(a == b)


BINARY = {"+": add, "-": sub, "*": mul, "/": div, "%": mod, "&": bit_and, "|": bit_or, "^": bit_xor,
          "<<": shl, ">>": shr}
