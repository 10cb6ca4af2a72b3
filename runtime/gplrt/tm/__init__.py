"""TMscript's runtime layer (docs/design/frontends.md): what generated TMscript code calls as
``tm.<name>`` -- the values and operators (``values``), the built-in library (``library``), the
parameterized objects ``Robot[0]`` and ``IO[...]`` (``objects``) -- on a simulated TM robot
(``motion``, ``robot``); the Listen node (``listen``) and the Ethernet Slave (``slave``).
"""

from __future__ import annotations

from gplrt.tm.library import *  # noqa: F401,F403 (the TMscript names generated code calls)
from gplrt.tm.library import ProjectExit
from gplrt.tm.objects import IO, Robot
from gplrt.tm.values import (  # noqa: F401
    BINARY, Array, TMError, add, bit_and, bit_or, bit_xor, cast, div, eq, format_value, i32, invert, mod,
    mul, neg, shl, shr, store, sub, to_bool, to_byte, to_double, to_float, to_int, to_string, truth,
)


def assign(obj: object, name: str, value: object) -> object:
    """``obj.name = value`` as an expression (an assignment used as a value, L2035)."""
    setattr(obj, name, value)
    return value


def setitem(obj: object, index: object, value: object) -> object:
    obj[index] = value  # type: ignore[index]
    return obj[index]  # type: ignore[index]


def run_project(main: object, closestop: object = None, errorstop: object = None) -> int:
    """Run a script project as TMflow does: ``main``, then ``closestop`` when it ends without error
    or by ``Exit(code >= 0)``, ``errorstop`` after an error (L1045-L1148); 0 or 1."""
    from gplrt.tm import context

    failed = False
    try:
        if callable(main):
            main()
        context.robot().wait_idle()
    except ProjectExit as exc:
        failed = exc.code < 0
    except TMError as exc:
        _report(exc)
        failed = True
    handler = errorstop if failed else closestop
    if callable(handler):
        try:
            handler()
        except TMError as exc:  # an error in closestop/errorstop ends the project (L1070, L1125)
            _report(exc)
            failed = True
        except ProjectExit:
            failed = True
    return 1 if failed else 0


def _report(exc: TMError) -> None:
    """A run-time error as a TM user reads it: the script's file and line, then the message."""
    import sys

    from gplrt.lang.sourcemap import locate

    where = locate(exc)
    print(f"{where + ': ' if where else ''}error: {exc}", file=sys.stderr, flush=True)


def run_module(module: object, sim: object = None) -> int:
    """Run a translated script module (``<package>.main()``)."""
    return int(module.run() or 0)  # type: ignore[attr-defined]


__all__ = ["IO", "Robot", "assign", "run_module", "run_project", "serve", "setitem"]


def serve(robot: str = "TM5-900", host: str = "127.0.0.1", port: int = 5890, svr_port: int = 5891,
          speed: float = float("inf")) -> tuple[object, object]:
    """A simulated TM robot in a Listen node, from a notebook or a script (what ``gpl2py run
    --robot TM5-900 --listen-node`` starts): ``(node, slave)``, serving in the background until
    ``node.close()`` and ``slave.close()``.  Port 0 takes a free port (``node.port``)."""
    from gplrt.tm import context
    from gplrt.tm.listen import ListenNode
    from gplrt.tm.slave import EthernetSlave

    r = context.use_robot(robot, speed)
    node = ListenNode(r, host, port).serve()
    slave = EthernetSlave(r, host, svr_port).serve()
    return node, slave
