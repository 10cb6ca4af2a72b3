"""TMscript's runtime layer (docs/design/frontends.md): what generated TMscript code calls as
``tm.<name>`` -- the values and operators (``values``), the built-in library (``library``), the
parameterized objects ``Robot[0]`` and ``IO[...]`` (``objects``) -- on a simulated TM robot
(``motion``, ``robot``); the Listen node (``listen``) and the Ethernet Slave (``slave``).
The Listen node is not imported here: it runs the packets it receives in this package's namespace.
"""

from __future__ import annotations

import sys

from gplrt.lang.sourcemap import locate
from gplrt.tm import context
from gplrt.tm.library import *  # noqa: F401,F403 (the TMscript names generated code calls)
from gplrt.tm.library import ProjectExit
from gplrt.tm.objects import IO, Robot
from gplrt.tm.values import (  # noqa: F401
    BINARY, Array, TMError, Unset, add, bit_and, bit_or, bit_xor, cast, div, eq, format_value, i32, invert, mod,
    mul, neg, shl, shr, store, sub, to_bool, to_byte, to_double, to_float, to_int, to_string, truth,
)


def assign(obj: object, name: str, value: object) -> object:
    """``obj.name = value`` as an expression (an assignment used as a value, L2035)."""
    setattr(obj, name, value)
    return value


def setitem(obj: object, index: object, value: object) -> object:
    obj[index] = value  # type: ignore[index]
    return obj[index]  # type: ignore[index]


def run_project(main: object, closestop: object = None, errorstop: object = None, define: object = None) -> int:
    """Run a script project as TMflow does: ``define`` (the globals' initial values, L996) and
    ``main`` (L1015), then ``closestop`` when they end without error or by ``Exit(code >= 0)``,
    ``errorstop`` after an error (L1045-L1148); 0 or 1.  ``define`` runs here, at each run on the
    current robot, not when the project's module is imported."""
    failed = False
    try:
        if callable(define):
            define()
        if callable(main):
            main()
        context.robot().wait_idle()
        context.robot().check_fault()  # (a motion queued last may have stopped the project)
    except ProjectExit as exc:
        failed = exc.code < 0
    except TMError as exc:
        _report(exc)
        failed = True
        context.robot().acknowledge_fault()
    handler = errorstop if failed else closestop
    if callable(handler):
        try:
            handler()
        except TMError as exc:  # an error in closestop/errorstop ends the project (L1070, L1125)
            _report(exc)
            failed = True
        except ProjectExit:
            failed = True
    context.robot().close_devices()  # the project stops: its devices close (L12494)
    return 1 if failed else 0


def _report(exc: TMError) -> None:
    """A run-time error as a TM user reads it: the script's file and line, then the message."""
    where = getattr(exc, "where", None) or locate(exc)
    print(f"{where + ': ' if where else ''}error: {exc}", file=sys.stderr, flush=True)


def run_module(module: object, sim: object = None) -> int:
    """Run a translated script module (``<package>.main()``)."""
    return int(module.run() or 0)  # type: ignore[attr-defined]


__all__ = ["IO", "Robot", "assign", "run_module", "run_project", "setitem"]
