"""V+ string functions, binary packing and the output formats shared by TYPE, WRITE and $ENCODE.

Strings are Python ``str`` with one character per byte 0..255 (Latin-1), at most 128 characters
(L3826-3833).  Binary packing (``$LNGB``, ``$INTB``, ``$FLTB``, ``$DBLB`` and their inverses,
L5300-5340) stores **most significant byte first**: the Guide names the functions but not the
order; ``ros.v2`` reverses every packed field "to match ROS", whose messages are little-endian
(docs/design/vplus.md, "byte order"), which only makes sense if V+ packs big-endian.

Numbers without a format print as an integer when they are one (``27``, L7102-7106), else with up
to 6 decimals, trailing zeros dropped (``0.5``, ``1.414214``); [D] the Guide gives no default.
Format specifiers (``vp.fmt("/I0")``) are the V+ text: /Cn /S /Xn /Un /B /N /In /Fw.d /Ew.d
/Gw.d /Hn /D.
"""

from __future__ import annotations

import math
import re
import struct
from dataclasses import dataclass
from typing import Any

from gplrt.geometry.location import Location
from gplrt.vplus.errors import ILLEGAL_VALUE, STRING_TOO_LONG, VError, error_text
from gplrt.vplus.operators import to_int
from gplrt.vplus.transforms import trans
from gplrt.vplus.values import MAX_STRING


def _check(s: str) -> str:
    if len(s) > MAX_STRING:
        raise VError(STRING_TOO_LONG, detail=f"{len(s)} characters")
    return s


def _bytes_of(s: str, n: int, what: str) -> bytes:
    if len(s) < n:
        raise VError(ILLEGAL_VALUE, detail=f"{what} needs {n} bytes, the string has {len(s)}")
    return s[:n].encode("latin-1")


# -- characters and substrings --------------------------------------------------------------------

def s_chr(code: Any) -> str:
    n = to_int(code)
    if not 0 <= n <= 255:
        raise VError(ILLEGAL_VALUE, detail=f"$CHR({n})")
    return chr(n)


def asc(s: str, index: Any = 1) -> float:
    """``ASC(s[, i])``: the code of character i (1-based); -1 past the end."""
    i = to_int(index)
    if i < 1 or i > len(s):
        return -1.0
    return float(ord(s[i - 1]))


def len_(s: str) -> float:
    return float(len(s))


def s_mid(s: str, start: Any, length: Any = MAX_STRING) -> str:
    """``$MID(s, start, n)``: n characters from position ``start`` (1-based)."""
    i, n = to_int(start), to_int(length)
    if i < 1 or n < 0:
        raise VError(ILLEGAL_VALUE, detail=f"$MID start {i}, length {n}")
    return s[i - 1:i - 1 + n]


def pos(s: str, sub: str, start: Any = 1) -> float:
    """``POS(s, sub[, start])``: where ``sub`` starts in ``s`` (1-based), 0 if absent."""
    i = max(1, to_int(start))
    return float(s.find(sub, i - 1) + 1)


_NUMBER = re.compile(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def val(s: str) -> float:
    """``VAL(s)``: the number at the start of ``s`` (after spaces); 0 when there is none."""
    m = _NUMBER.match(s)
    return float(m.group(0)) if m else 0.0


def s_decode(ref: Any, breaks: str, mode: Any = 0) -> str:
    """``$DECODE(var, breaks, mode)``: remove and return the leading part of the string variable:
    mode 0 the characters before the first break character, else the run of break characters."""
    s: str = ref.v
    upper = breaks
    i = 0
    if to_int(mode) == 0:
        while i < len(s) and s[i] not in upper:
            i += 1
    else:
        while i < len(s) and s[i] in upper:
            i += 1
    ref.v = s[i:]
    return s[:i]


def s_truncate(s: str) -> str:
    """``$TRUNCATE(s)``: ``s`` up to (not including) its first NUL."""
    return s.split("\0", 1)[0]


def s_error(code: Any) -> str:
    return error_text(to_int(code))


# -- binary packing (most significant byte first) ----------------------------------------------------

def s_lngb(x: Any) -> str:
    n = to_int(x) & 0xFFFFFFFF
    return struct.pack(">I", n).decode("latin-1")


def lngb(s: str, start: Any = 1) -> float:
    return float(struct.unpack(">i", _bytes_of(s[to_int(start) - 1:], 4, "LNGB"))[0])


def s_intb(x: Any) -> str:
    n = to_int(x) & 0xFFFF
    return struct.pack(">H", n).decode("latin-1")


def intb(s: str, start: Any = 1) -> float:
    return float(struct.unpack(">h", _bytes_of(s[to_int(start) - 1:], 2, "INTB"))[0])


def s_fltb(x: Any) -> str:
    try:
        return struct.pack(">f", float(x)).decode("latin-1")
    except OverflowError:
        raise VError(ILLEGAL_VALUE, detail=f"$FLTB({x}) beyond single precision") from None


def fltb(s: str, start: Any = 1) -> float:
    return float(struct.unpack(">f", _bytes_of(s[to_int(start) - 1:], 4, "FLTB"))[0])


def s_dblb(x: Any) -> str:
    return struct.pack(">d", float(x)).decode("latin-1")


def dblb(s: str, start: Any = 1) -> float:
    return float(struct.unpack(">d", _bytes_of(s[to_int(start) - 1:], 8, "DBLB"))[0])


def s_transb(t: Location) -> str:
    """``$TRANSB(t)``: X, Y, Z, yaw, pitch, roll as six single-precision floats (24 bytes)."""
    values = (t.X, t.Y, t.Z, t.Yaw, t.Pitch, t.Roll)
    return b"".join(struct.pack(">f", float(v)) for v in values).decode("latin-1")


def transb(s: str, start: Any = 1) -> Location:
    raw = _bytes_of(s[to_int(start) - 1:], 24, "TRANSB")
    return trans(*struct.unpack(">6f", raw))


# -- formats ------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Fmt:
    """One format specifier of TYPE/WRITE/$ENCODE (``/C1``, ``/S``, ``/I0``, ``/F8.2``...)."""

    letter: str
    width: int | None = None
    decimals: int | None = None

    def __repr__(self) -> str:
        w = "" if self.width is None else str(self.width)
        d = "" if self.decimals is None else f".{self.decimals}"
        return f"fmt('/{self.letter}{w}{d}')"


_FMT = re.compile(r"^/([A-Za-z])(\d+)?(?:\.(\d+))?$")


def fmt(text: str) -> Fmt:
    m = _FMT.match(text.strip())
    if not m:
        raise VError(ILLEGAL_VALUE, detail=f"format {text!r}")
    return Fmt(m.group(1).upper(), int(m.group(2)) if m.group(2) else None,
               int(m.group(3)) if m.group(3) else None)


def default_number(x: float) -> str:
    """A number without a format (see the module docstring)."""
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    if abs(x) >= 1e15 or abs(x) < 1e-6:
        return f"{x:.6E}"
    text = f"{x:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _number(x: float, spec: Fmt | None) -> str:
    if spec is None or spec.letter == "D":
        return default_number(x)
    w = spec.width or 0
    if spec.letter == "I":
        return f"{to_int(x):{w}d}"
    if spec.letter == "F":
        return f"{x:{w}.{spec.decimals if spec.decimals is not None else 2}f}"
    if spec.letter == "E":
        return f"{x:{w}.{spec.decimals if spec.decimals is not None else 2}E}"
    if spec.letter == "G":
        d = spec.decimals if spec.decimals is not None else 2
        return f"{x:{w}.{d}f}" if 1e-3 <= abs(x) < 1e6 or x == 0 else f"{x:{w}.{d}E}"
    if spec.letter == "H":
        return f"{to_int(x) & 0xFFFFFFFF:{w}X}"
    return default_number(x)


def render(items: tuple[Any, ...], newline: str = "\n") -> tuple[str, bool]:
    """The text of TYPE/WRITE items and whether a line end should follow (False after /S)."""
    out: list[str] = []
    numeric: Fmt | None = None
    end = True
    for item in items:
        if isinstance(item, Fmt):
            letter, n = item.letter, item.width
            if letter == "C":
                out.append(newline * (1 if n is None else n))
            elif letter == "S":
                end = False
            elif letter == "X":
                out.append(" " * (1 if n is None else n))
            elif letter == "B":
                out.append("\a" * (1 if n is None else n))
            elif letter in ("U", "N"):
                pass  # cursor up / no wait: nothing to show on a plain console [D]
            else:
                numeric = item if letter != "D" else None
        elif isinstance(item, str):
            out.append(item)
        elif isinstance(item, Location):
            out.append(" ".join(default_number(round(v, 3)) for v in (
                (item.X, item.Y, item.Z, item.Yaw, item.Pitch, item.Roll) if item._type == 0
                else item.axis_values())))
        else:
            x = float(item)
            if not math.isfinite(x):
                raise VError(ILLEGAL_VALUE, detail=str(x))
            out.append(_number(x, numeric))
    return "".join(out), end


def s_encode(*items: Any) -> str:
    """``$ENCODE(items)``: the text TYPE would show, without a line end."""
    return _check(render(items)[0])
