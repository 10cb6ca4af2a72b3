"""V+ digital signals on the core's ``IoMap`` (L7254-7316, spec §3.13).

V+ numbers outputs 1..512, inputs 1001..1512 and soft signals 2001..2512; the core (GPL) numbers
outputs 1..64, inputs 10001..10064 and soft signals 20001..22048.  The layer translates: a V+
input ``1000 + k`` is the core's ``10000 + k``, a soft signal ``2000 + k`` the core's ``20000 + k``,
an output stays as it is.  Why translate rather than give V+ its own map: the simulation's input
rules, traces and notebooks all speak the core's numbers, and a V+ run then shows in them.
[D] Outputs above the core's 64 are not simulated (*Illegal value*).
"""

from __future__ import annotations

from typing import Any

from gplrt.lang.errors import GplException
from gplrt.session import current_session
from gplrt.vplus.errors import ILLEGAL_VALUE, VError, from_core
from gplrt.vplus.operators import to_int


def core_number(signal: Any) -> int:
    """The core's number for a V+ signal number (sign kept: negative means "off")."""
    n = to_int(signal)
    k = abs(n)
    if 1 <= k <= 512:
        core = k
    elif 1001 <= k <= 1512:
        core = 10000 + (k - 1000)
    elif 2001 <= k <= 2512:
        core = 20000 + (k - 2000)
    else:
        raise VError(ILLEGAL_VALUE, detail=f"signal {n}")
    return -core if n < 0 else core


def vplus_number(core: int) -> int:
    k = abs(core)
    if 10001 <= k <= 10512:
        return 1000 + (k - 10000)
    if 20001 <= k <= 20512:
        return 2000 + (k - 20000)
    return k


def signal(*signals: Any) -> None:
    """``SIGNAL n, -m, ...``: outputs or soft signals on (positive) or off (negative)."""
    io = current_session().io
    for s in signals:
        core = core_number(s)
        try:
            io.write_dio(abs(core), core > 0)
        except GplException as exc:
            raise from_core(exc) from None


def sig(*signals: Any) -> float:
    """``SIG(a, b, ...)``: -1 when every signal is in the state asked (negative = off)."""
    io = current_session().io
    for s in signals:
        core = core_number(s)
        try:
            if io.read_dio(abs(core)) != (core > 0):
                return 0.0
        except GplException as exc:
            raise from_core(exc) from None
    return -1.0


def sig_ins(n: Any) -> float:
    try:
        core_number(n)
        current_session().io.read_dio(abs(core_number(n)))
    except (VError, GplException):
        return 0.0
    return -1.0


def reset() -> None:
    """``RESET``: every output off."""
    io = current_session().io
    for n in io.map.digital_outputs:
        if io.read_dio(n):
            io.write_dio(n, False)


def bits(first: Any, count: Any = 1) -> float:
    """``BITS(first, n)``: signals first..first+n-1 read as a binary number (first = bit 0)."""
    f, c = to_int(first), to_int(count)
    value = 0
    for i in range(c):
        if sig(f + i):
            value |= 1 << i
    return float(value)


def bits_set(first: Any, count: Any, value: Any) -> None:
    """``BITS first, n = value``."""
    f, c, v = to_int(first), to_int(count), to_int(value)
    signal(*[(f + i) if v >> i & 1 else -(f + i) for i in range(c)])
