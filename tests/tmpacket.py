"""Helpers of the TMscript tests: run a Listen-node packet in-process, talk to a node over TCP.

A module of its own (as gpltest.py): test folders are not packages, tests/ is on the path."""

from __future__ import annotations

import socket
from collections.abc import Callable
from pathlib import Path

from gpl2py.tmscript.pipeline import translate_packet
from gplrt.tm.listen import Vars
from gplrt.tm.values import format_value


def run_packet(script: str) -> Vars:
    """Translate ``script`` as the Listen node does (at run time) and run it on the current robot;
    the variables it leaves."""
    p = translate_packet(script)
    assert not p.errors, [d.header() for d in p.errors]
    import gplrt.tm as tm

    ns: dict[str, object] = {"tm": tm}
    exec(compile(p.python, "<packet>", "exec"), ns)  # noqa: S102 (the front end's own output)
    v = Vars()
    ns["script"](v)  # type: ignore[operator]
    return v


def packet_values(script: str, *names: str) -> list[str]:
    """The text forms (``GetString``'s) of the variables ``names`` a packet leaves."""
    v = run_packet(script)
    return [format_value(getattr(v, n)) for n in names]


class NodeClient:
    """A raw TCP client of a Listen node or Ethernet Slave: send frames, read replies one by one."""

    def __init__(self, port: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=30)
        self.buf = b""

    def send(self, raw: bytes) -> None:
        self.sock.sendall(raw)

    def reply(self) -> bytes:
        while b"\r\n" not in self.buf:
            chunk = self.sock.recv(65536)
            assert chunk, "the robot closed the connection"
            self.buf += chunk
        frame, _, self.buf = self.buf.partition(b"\r\n")
        return frame + b"\r\n"

    def ask(self, raw: bytes) -> bytes:
        self.send(raw)
        return self.reply()

    def close(self) -> None:
        self.sock.close()


def run_project(source: Path, out: Path, robot: str = "TM5-900", speed: float = float("inf"),
                display: Callable[[str], None] | None = None) -> tuple[int, list[str]]:
    """Translate the script project ``source`` into ``out``, import it and ``run()`` it on a new
    simulated ``robot`` (``speed``: a real clock at that speed; default the fast clock):
    (status, the ``Display`` lines; or what ``display`` does with them)."""
    import importlib.util
    import sys

    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.output import write_package
    from gpl2py.transpile import transpile
    from gplrt.tm import context

    sink = DiagnosticSink()
    pkg = transpile(source, sink)
    assert pkg is not None and not sink.has_errors(), [d.header() for d in sink]
    write_package(pkg, out, sink)
    name = f"tm_project_{pkg.package}_{abs(hash(str(out)))}"
    spec = importlib.util.spec_from_file_location(name, out / pkg.package / f"{pkg.package}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    context.use_robot(robot, speed=speed)
    lines: list[str] = []
    context.set_display(display or lines.append)
    try:
        status = module.run()
    finally:
        context.set_display(None)
        sys.modules.pop(spec.name, None)
    return status, lines
