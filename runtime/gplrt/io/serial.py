"""Serial ports ``/dev/comN`` for StreamReader/StreamWriter, and their simulated back ends.

A PC running the simulator has no controller serial ports, so a port exists only when the
simulator (or a test) maps one:

    from gplrt.io.serial import configure_serial, LoopbackPort, PtyPort
    configure_serial("com1", LoopbackPort())   # bytes written come back as input
    pty = configure_serial("com2", PtyPort())  # another program opens pty.device_path

Opening an unmapped port raises -309 *No physical device mapped*, naming the port.

Semantics (D0:3872-3924): a port can be open for input and output at the same time; ``AutoFlush``
defaults to True; ``Peek`` never blocks (< 0 = no data yet, as EX-25 polls); ``Read`` blocks until
a byte arrives (through :func:`gplrt.io._blocking.blocking_call`, waiting in slices so that
``Thread.Abort`` ends a reader blocked on a silent line); a serial link cannot detect that the
other end went away.
"""

from __future__ import annotations

import os
import select
import threading
import tty
from typing import Protocol

from gplrt.io._blocking import blocking_call, wait_ready
from gplrt.lang.errors import DEVICE_IO_ERROR, NO_DEVICE_MAPPED, GplException, host_reason


class SerialPort(Protocol):
    """What a simulated serial port offers the stream classes."""

    def write(self, data: bytes) -> None: ...

    def peek(self) -> int:
        """Next byte without removing it, or -1 if none is available now."""
        ...

    def read(self, timeout: float | None = None) -> int:
        """Next byte, waiting up to ``timeout`` s (None = forever); -1 on timeout."""
        ...

    def available(self) -> int: ...


class LoopbackPort:
    """A port whose transmit line is wired to its receive line (a loop-back plug)."""

    def __init__(self) -> None:
        self._buffer = bytearray()
        self._ready = threading.Condition()

    def write(self, data: bytes) -> None:
        with self._ready:
            self._buffer += data
            self._ready.notify_all()

    def peek(self) -> int:
        with self._ready:
            return self._buffer[0] if self._buffer else -1

    def available(self) -> int:
        with self._ready:
            return len(self._buffer)

    def read(self, timeout: float | None = None) -> int:
        got: list[int] = []

        def take(step: float) -> bool:
            with self._ready:
                if not self._ready.wait_for(lambda: bool(self._buffer), step):
                    return False
                got.append(self._buffer.pop(0))
                return True

        return got[0] if blocking_call(lambda: wait_ready(take, timeout), timeout) else -1


class PtyPort:
    """A port backed by a pseudo-terminal: the controller side is the master end, and an outside
    program (a terminal emulator, a test, a device simulator) opens :attr:`device_path`."""

    def __init__(self) -> None:
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)  # bytes pass unchanged, no echo, no line editing
        self.device_path: str = os.ttyname(self._slave)
        self._pending = bytearray()
        self._lock = threading.Lock()

    def _fill(self, timeout: float | None) -> None:
        ready, _, _ = select.select([self._master], [], [], timeout)
        if ready:
            try:
                self._pending += os.read(self._master, 4096)
            except OSError as exc:
                detail = f"{self.device_path}: {host_reason(exc)}"
                raise GplException(DEVICE_IO_ERROR, detail=detail) from None

    def write(self, data: bytes) -> None:
        os.write(self._master, data)

    def peek(self) -> int:
        with self._lock:
            if not self._pending:
                self._fill(0)
            return self._pending[0] if self._pending else -1

    def available(self) -> int:
        with self._lock:
            self._fill(0)
            return len(self._pending)

    def read(self, timeout: float | None = None) -> int:
        got: list[int] = []

        def take(step: float) -> bool:
            with self._lock:
                if not self._pending:
                    self._fill(step)
                if not self._pending:
                    return False
                got.append(self._pending.pop(0))
                return True

        return got[0] if blocking_call(lambda: wait_ready(take, timeout), timeout) else -1

    def close(self) -> None:
        """Release both ends of the pseudo-terminal (the simulator calls this at shutdown)."""
        for fd in (self._master, self._slave):
            try:
                os.close(fd)
            except OSError:
                pass


_ports: dict[str, SerialPort] = {}
_ports_lock = threading.Lock()


def configure_serial(name: str, port: SerialPort | None) -> SerialPort | None:
    """Map ``/dev/<name>`` (``"com1"``) to ``port``; ``None`` removes the mapping."""
    key = name.lower().removeprefix("/dev/")
    with _ports_lock:
        if port is None:
            _ports.pop(key, None)
        else:
            _ports[key] = port
    return port


def open_port(name: str) -> SerialPort:
    """The port mapped to ``/dev/<name>``, or -309 naming what is missing."""
    with _ports_lock:
        port = _ports.get(name.lower())
    if port is None:
        raise GplException(
            NO_DEVICE_MAPPED,
            detail=f"no serial port /dev/{name} configured in the simulator "
            "(gplrt.io.serial.configure_serial)",
        )
    return port
