"""Helpers of the TMscript tests: run a Listen-node packet in-process, talk to a node over TCP.

A module of its own (as gpltest.py): test folders are not packages, tests/ is on the path."""

from __future__ import annotations

import asyncio
import contextlib
import importlib.util
import socket
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from types import ModuleType

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.output import write_package
from gpl2py.tmscript.pipeline import translate_packet
from gpl2py.transpile import transpile
from gplrt.tm import context
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


def load_project(source: Path, out: Path) -> ModuleType:
    """Translate the script project ``source`` into ``out`` and import its module (not run)."""
    sink = DiagnosticSink()
    pkg = transpile(source, sink)
    assert pkg is not None and not sink.has_errors(), [d.header() for d in sink]
    write_package(pkg, out, sink)
    name = f"tm_project_{pkg.package}_{abs(hash(str(out)))}"
    spec = importlib.util.spec_from_file_location(name, out / pkg.package / f"{pkg.package}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_loaded(module: ModuleType, display: Callable[[str], object] | None = None) -> tuple[int, list[str]]:
    """``run()`` an imported project on the current robot: (status, the ``Display`` lines; or what
    ``display`` does with them)."""
    lines: list[str] = []
    context.set_display(display or lines.append)
    try:
        status = int(module.run())
    finally:
        context.set_display(None)
    return status, lines


def run_project(source: Path, out: Path, robot: str | None = "TM5-900", speed: float = float("inf"),
                display: Callable[[str], object] | None = None) -> tuple[int, list[str]]:
    """Translate the script project ``source`` into ``out``, import it and ``run()`` it on a new
    simulated ``robot`` (``speed``: a real clock at that speed; default the fast clock), or on the
    current one when ``robot`` is None (a test that attached devices to it first): (status, the
    ``Display`` lines; or what ``display`` does with them)."""
    module = load_project(source, out)
    if robot is not None:
        context.use_robot(robot, speed=speed)
    return run_loaded(module, display)


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


class Peer:
    """A remote device on loopback for the Socket and SerialPort tests (``port``; ``url`` for a
    serial port attached with pyserial's ``socket://``): accepts one client, sends ``greeting``
    (``asked``: only once the client sent something, as a serial device answers; opening a
    serial port drops what came before, pyserial's ``open`` resets the input), keeps what it
    receives and notes when the client closes."""

    def __init__(self, greeting: bytes = b"", asked: bool = False) -> None:
        self.asked = asked
        self.server = socket.create_server(("127.0.0.1", 0))
        self.port = self.server.getsockname()[1]
        self.url = f"socket://127.0.0.1:{self.port}"
        self.received = bytearray()
        self.greeting = greeting
        self.closed = threading.Event()
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self) -> None:
        conn, _ = self.server.accept()
        if not self.asked:
            conn.sendall(self.greeting)
        while chunk := conn.recv(65536):
            if self.asked and not self.received:
                conn.sendall(self.greeting)
            self.received += chunk
        self.closed.set()

    def wait_for(self, n: int) -> bytes:
        end = time.monotonic() + 30  # (only ends a hang; not a timing assertion)
        while len(self.received) < n and time.monotonic() < end:
            time.sleep(0.005)
        return bytes(self.received)


@contextlib.contextmanager
def modbus_slave(device: object, framer: object = None) -> Iterator[int]:
    """A pymodbus slave serving ``device`` (a ``ModbusDeviceContext``) on a free loopback port,
    framed by ``framer`` (Modbus TCP by default; pymodbus's RTU framer for an RTU slave that a
    virtual serial port reaches with ``socket://``); its port, once it accepts."""
    from pymodbus import FramerType
    from pymodbus.datastore import ModbusServerContext
    from pymodbus.server import ModbusTcpServer

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        free = s.getsockname()[1]
    loop = asyncio.new_event_loop()
    servers: list[ModbusTcpServer] = []

    async def serve() -> None:
        server = ModbusTcpServer(ModbusServerContext(devices=device, single=True), address=("127.0.0.1", free),
                                 framer=framer or FramerType.SOCKET)
        servers.append(server)
        await server.serve_forever()
    thread = threading.Thread(target=loop.run_until_complete, args=(serve(),), daemon=True)
    thread.start()
    end = time.monotonic() + 10
    while time.monotonic() < end:  # (until the port accepts; not a timing assertion)
        try:
            socket.create_connection(("127.0.0.1", free), 0.2).close()
            break
        except OSError:
            time.sleep(0.02)
    try:
        yield free
    finally:
        asyncio.run_coroutine_threadsafe(servers[0].shutdown(), loop).result(5)
        thread.join(5)
        loop.close()
