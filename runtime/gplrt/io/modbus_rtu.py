"""A Modbus RTU master: GPL's ``Modbus`` class (``gplrt.io.modbus``) with RTU framing on a serial
line instead of MBAP on TCP.

Why a subclass: the requests (function codes 1-6, 15, 16, 43), their checks and the errors a
program sees (-1730 exception with its code, -1731 time-out, -1709 malformed reply, -707 bad
count/address/value) are Modbus's, whatever carries them; only the frame differs.  An RTU frame
is ``unit, function, data..., CRC`` with the CRC-16/MODBUS (init 0xFFFF, reflected polynomial
0xA001) low byte first; the reply's length follows from its function code (an exception reply is
5 bytes, a read ``5 + byte count``, a write echo 8).  ``opener()`` gives an open pyserial-like
port (``read``, ``write``, ``flush``, ``reset_input_buffer``, ``close``) whose read time-out is a
short slice: the master waits in slices through :func:`gplrt.io._blocking.wait_ready`, so a
waiting thread still ends on ``Thread.Abort``.  A CRC that does not match is -1709 *Invalid
protocol*; a reply from another unit is skipped, as the TCP master skips another transaction's.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from gplrt.io._blocking import blocking_call, wait_ready
from gplrt.io.modbus import Modbus, _reply_data
from gplrt.lang.errors import CONNECTION_CLOSED, INVALID_PROTOCOL, MODBUS_TIMEOUT, GplException


def crc16_modbus(data: bytes) -> int:
    """CRC-16/MODBUS of ``data``."""
    crc = 0xFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return crc


def frame(unit: int, pdu: bytes) -> bytes:
    """An RTU frame: the unit, the PDU, the CRC low byte first."""
    body = bytes([unit & 0xFF]) + pdu
    crc = crc16_modbus(body)
    return body + bytes([crc & 0xFF, crc >> 8])


class ModbusRtu(Modbus):
    """A Modbus master on a serial line; ``opener()`` opens the line on first use."""

    def __init__(self, opener: Callable[[], Any]) -> None:
        self._opener = opener
        self._address = ("serial", 0)
        self._timeout_ms = 0
        self._sock: Any = None
        self._tid = 0
        self._lock = threading.Lock()
        self.unit_id = 1

    def _connect(self) -> Any:
        if self._sock is None:
            self._sock = self._opener()
        return self._sock

    def _disconnect(self) -> None:
        port, self._sock = self._sock, None
        if port is not None:
            try:
                port.close()
            except Exception:
                pass

    def _transact(self, function: int, payload: bytes) -> bytes:
        """Send one request PDU to ``unit_id`` and return the reply's data (after the function
        code)."""
        with self._lock:
            port = self._connect()
            try:
                port.reset_input_buffer()  # (bytes of an earlier, timed-out reply)
                port.write(frame(self.unit_id, bytes([function]) + payload))
                port.flush()
                while True:
                    head = self._receive(port, 2)
                    if head[1] == function | 0x80:
                        rest = self._receive(port, 3)
                    elif head[1] in (1, 2, 3, 4):
                        count = self._receive(port, 1)
                        rest = count + self._receive(port, count[0] + 2)
                    elif head[1] in (5, 6, 15, 16):
                        rest = self._receive(port, 6)
                    else:
                        rest = self._receive_until_quiet(port)
                    reply = head + rest
                    crc = crc16_modbus(reply[:-2])
                    if reply[-2:] != bytes([crc & 0xFF, crc >> 8]):
                        raise GplException(INVALID_PROTOCOL, detail="Modbus RTU reply with a bad CRC")
                    if head[0] == self.unit_id & 0xFF:
                        break
                body = reply[1:-2]
            except GplException:
                self._disconnect()
                raise
            except BaseException as exc:  # the line failed, or Thread.Abort while waiting
                self._disconnect()
                if isinstance(exc, Exception):
                    raise GplException(CONNECTION_CLOSED, detail=f"Modbus RTU line: {exc}") from None
                raise
        return _reply_data(function, body)

    def _receive(self, port: Any, size: int) -> bytes:
        timeout = self._timeout()
        data = bytearray()

        def ready(step: float) -> bool:
            data.extend(port.read(size - len(data)))
            return len(data) >= size

        if not blocking_call(lambda: wait_ready(ready, timeout), timeout):
            raise GplException(MODBUS_TIMEOUT, detail=f"no reply within {self._timeout_ms} ms")
        return bytes(data)

    def _receive_until_quiet(self, port: Any) -> bytes:
        """The rest of a reply of no fixed length (FC 43): what comes until the line is quiet
        for one read slice."""
        data = bytearray(self._receive(port, 1))
        while chunk := blocking_call(lambda: port.read(256), None):
            data += chunk
        return bytes(data)


__all__ = ["ModbusRtu", "crc16_modbus", "frame"]
