"""TMscript's serial ports: the ``SerialPort`` class and the ``com_*`` functions (manual §8,
L12367-L13395; spec §3.11), on **virtual** ports.

A script's ``"COM2"`` never opens a host device by itself: the script is untrusted input
(docs/security.md), and a PC has no robot's COM ports anyway.  The user attaches the other end of
a virtual port, by name, with a pyserial URL::

    from gplrt.tm.serial import attach_serial
    attach_serial("COM2", "loop://")                 # what the script writes comes back to it
    attach_serial("COM2", "socket://127.0.0.1:7000") # a device simulator on a TCP port
    attach_serial("COM2", "/dev/ttyUSB0")            # a real adapter, named by the user

(``gpl2py run script.tms --serial COM2=URL`` does the same.)  pyserial opens the URL with the
declaration's settings (baud rate, parity, data and stop bits, flow control: a URL handler that
has no line ignores them).  A port nobody attached cannot be opened: ``com_open`` is false and
the project reports the error (L12447), so it is a script error naming the port.

Semantics (L12369-L13395):

* ``SerialPort spd = "COM2", 115200 [, "none", 8, 1 [, 10000 [, false, false, false]]]`` (2, 5, 6
  or 9 values; parity none/odd/even/mark/space, data bits 5-8, stop bits 1, 1.5, 2, time-out
  0-10000 ms); a bad value is a script error at the declaration.  A script project does not
  connect at the declaration (L12431): ``com_open`` does; a read or write of a device not yet
  open opens it first ("it will ask for confirmation of connecting", L12433).
* Once open, a reader (a thread of the robot's scheduler) fills the Received Buffer; reads take
  from it (``gplrt.tm.devices.take``, shared with the Socket class).  ``com_close``, the end of
  the block that declared the device, and the end of the project close the port and clear the
  buffer (L12494-L12498).
* ``com_write``/``com_writeline`` send a value's bytes as ``socket_send`` does (little-endian
  numbers, UTF-8 text, start and length for strings and arrays) and return false for nothing to
  send or a port that fails (L13220).
"""

from __future__ import annotations

import threading
from typing import Any

from gplrt.io._blocking import POLL_SLICE, blocking_call
from gplrt.threads.scheduler import abort_point
from gplrt.tm.conversions import GetBytes, write_span
from gplrt.tm.devices import Device, find, take, text
from gplrt.tm.motion import start_thread
from gplrt.tm.values import Array, TMError, to_bool, to_float, to_int, to_string

#: TMscript parity words -> pyserial's parity letters.
PARITY = {"none": "N", "odd": "O", "even": "E", "mark": "M", "space": "S"}

_attached: dict[str, str] = {}
_attached_lock = threading.Lock()


def attach_serial(port: str, url: str | None) -> None:
    """Attach the other end of the virtual port ``port`` (``"COM2"``, any case) to ``url``, a
    pyserial URL or device path the *user* names (``None`` detaches it).  Ports opened after this
    use it; one already open keeps its link until closed."""
    key = port.strip().upper()
    with _attached_lock:
        if url is None:
            _attached.pop(key, None)
        else:
            _attached[key] = url


def attached(port: str) -> str | None:
    """What the virtual port ``port`` is attached to, or None."""
    with _attached_lock:
        return _attached.get(port.strip().upper())


class SerialSettings:
    """A ``SerialPort``/``ModbusRTU`` parameter list (L12376-L12404), checked at the
    declaration; :meth:`open` opens the port the user attached with these settings."""

    def __init__(self, what: str, port: object, baud: object, parity: object = "none", data_bits: object = 8,
                 stop_bits: object = 1, timeout: object = 10000, dtr_dsr: object = False, rts_cts: object = False,
                 xon_xoff: object = False) -> None:
        self.what = what
        self.port, self.baud = to_string(port), to_int(baud)
        self.parity = to_string(parity).strip().lower()
        self.data_bits, self.stop_bits = to_int(data_bits), float(to_float(stop_bits))
        self.timeout = to_int(timeout)
        self.dtr_dsr, self.rts_cts, self.xon_xoff = to_bool(dtr_dsr), to_bool(rts_cts), to_bool(xon_xoff)
        if self.baud <= 0:
            self._bad(f"the baud rate {self.baud}")
        if self.parity not in PARITY:
            self._bad(f"the parity {to_string(parity)!r} (none, odd, even, mark, space)")
        if self.data_bits not in (5, 6, 7, 8):
            self._bad(f"the data bits {self.data_bits} (5, 6, 7, 8)")
        if self.stop_bits not in (1.0, 1.5, 2.0):
            self._bad(f"the stop bits {to_string(stop_bits)} (1, 1.5, 2)")
        if not 0 <= self.timeout <= 10000:
            self._bad(f"the timeout {self.timeout} ms (0-10000)")

    def _bad(self, what: str) -> None:
        raise TMError(f"{self.what}: {what} is not valid (L12390)")

    def open(self, what: str) -> Any:
        """An open pyserial port on what the user attached to ``self.port``; TMError (``what``
        failed) when nothing is attached or it cannot be opened."""
        url = attached(self.port)
        if url is None:
            raise TMError(f"{what}: the serial port {self.port} cannot be opened: nothing is attached to it "
                          "(the simulated robot's ports connect only to what the user attaches: "
                          "gpl2py run --serial PORT=URL, or gplrt.tm.serial.attach_serial)")
        try:
            import serial
        except ImportError:  # pragma: no cover (pyserial is a dependency of gpl2py)
            raise TMError(f"{what}: serial ports need pyserial (pip install pyserial)") from None
        write_timeout = self.timeout / 1000.0 if self.timeout > 0 else None
        try:
            port = serial.serial_for_url(
                url, baudrate=self.baud, parity=PARITY[self.parity], bytesize=self.data_bits,
                stopbits=self.stop_bits, timeout=POLL_SLICE, write_timeout=write_timeout, xonxoff=self.xon_xoff,
                rtscts=self.rts_cts, dsrdtr=self.dtr_dsr, do_not_open=True)
            blocking_call(port.open, write_timeout)
        except (serial.SerialException, OSError, ValueError) as exc:
            raise TMError(f"{what}: the serial port {self.port} cannot be opened ({url}: {exc})") from None
        return port


class SerialPort(Device):
    """A serial device ``name`` on the virtual port its declaration names (L12369)."""

    kind = "serial"

    def __init__(self, name: str, *args: object) -> None:
        if len(args) not in (2, 5, 6, 9):
            raise TMError(f"SerialPort {name}: {len(args)} values; the class takes 2, 5, 6 or 9 (L12376)")
        self.settings = SerialSettings(f"SerialPort {name}", *args)
        self.port: Any = None
        super().__init__(name)

    def open(self, what: str = "com_open") -> bool:
        """Open the port (or keep it open) and start the reader; TMError when it cannot."""
        if self.port is not None:
            return True
        self.port = port = self.settings.open(f'{what}("{self.name}")')
        # an open line paces the robot's virtual time to real time, as an open socket does: what
        # the peer sends takes real time to come (whichever thread opened it: a script project's
        # main runs on the caller's thread, not one of the scheduler's)
        self._release = self.robot.sched.hold_real_time()
        start_thread(self.robot.sched, f"tm-serial-{self.name}", lambda: self._receive(port))
        return True

    def _receive(self, port: Any) -> None:
        """The reader: what arrives on the port goes to the Received Buffer until it closes."""
        try:
            while self.port is port:
                abort_point()
                try:
                    data = blocking_call(lambda: _read_some(port), POLL_SLICE)
                except Exception:  # (closed meanwhile, or the link failed: the reader ends)
                    break
                if data and self.port is port:
                    self.received(bytes(data))
        finally:
            self.robot._notify()

    def close(self) -> bool:
        port, self.port = self.port, None
        if port is not None:
            self._release()
            try:
                port.close()
            except Exception:
                pass
        self.buffer.clear()
        return True

    def send(self, data: bytes) -> bool:
        if not data:
            return False
        try:
            self.open("com_write")
        except TMError:
            return False
        port = self.port
        try:
            blocking_call(lambda: (port.write(data), port.flush()), port.write_timeout)
        except Exception:
            return False
        return True


def _read_some(port: Any) -> bytes:
    """What the line has: waits up to the port's read slice for a first byte, then takes what
    else is there (``in_waiting`` is only 0/1 for some URL handlers: ``socket://``)."""
    data = bytes(port.read(port.in_waiting or 1))
    while data and port.in_waiting:
        data += port.read(port.in_waiting)
    return data


def _known(name: object, what: str) -> SerialPort:
    dev = find("serial", name)
    if dev is None:
        raise TMError(f"{what}: no SerialPort device named {to_string(name)!r}")
    return dev  # type: ignore[no-any-return]


def com_open(name: object) -> bool:
    """Open the device (L12435); a port that cannot be opened is a script error (L12447)."""
    return _known(name, "com_open").open()


def com_close(name: object) -> bool:
    """Close it; its Received Buffer is cleared (L12463)."""
    return _known(name, "com_close").close()


def _reading(name: object, what: str) -> SerialPort:
    dev = _known(name, what)
    dev.open(what)
    return dev


def com_read(name: object, *args: object) -> Array:
    """Bytes from the Received Buffer (L12500): ``(dev)``, ``(dev, n [, ms])``, ``(dev, prefix,
    suffix [, option [, ms]])``, ``(dev, suffix [, option [, ms]])``; ``byte[0]`` when nothing
    matches."""
    return Array("byte", take(_reading(name, "com_read"), args, "com_read"))


def com_read_string(name: object, *args: object) -> str:
    """As ``com_read``, as UTF-8 text; a count is of characters (L12850, L13067)."""
    return text(take(_reading(name, "com_read_string"), args, "com_read_string", chars=True))


def _write(name: object, value: object, start: object, length: object, line: bool) -> bool:
    dev = _known(name, "com_writeline" if line else "com_write")
    part = write_span(value, start, length)
    data = bytes(GetBytes(part))
    if not data:
        return False
    return dev.send(data + (b"\r\n" if line else b""))


def com_write(name: object, value: object, start: object = 0, length: object = 0) -> bool:
    """Send ``value``'s bytes (L13193): false for nothing to send or a port that fails."""
    return _write(name, value, start, length, False)


def com_writeline(name: object, value: object, start: object = 0, length: object = 0) -> bool:
    """``com_write`` and CR LF (L13299)."""
    return _write(name, value, start, length, True)


__all__ = ["SerialPort", "attach_serial", "com_close", "com_open", "com_read", "com_read_string", "com_write",
           "com_writeline"]
