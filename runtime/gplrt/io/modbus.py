"""GPL ``Modbus`` class: a MODBUS/TCP master (D0 §13) with its own small framing.

Why our own framing rather than pymodbus's client: Modbus/TCP is a 7-byte MBAP header plus a PDU
of a few bytes, and owning the socket lets every wait go through
:func:`gplrt.io._blocking.blocking_call` with GPL's timeout semantics (``Timeout`` in ms, default
infinite), with no hidden retries or reconnect loops, no asyncio, no logging side effects, and no
dependence on pymodbus's API churn (``slave=`` became ``device_id=``).  pymodbus stays a test
dependency: its server is the independent implementation our framing is tested against.

Semantics:

* Creating the object does not connect; the first read/write connects (D0:3489-3511).  A port of
  0 in the endpoint means the standard port 502.  ``Close`` closes the connection; a later call
  reconnects.
* Addresses are sent as given (``mb.ReadCoils(1, 16, b)`` asks for protocol address 1): the
  manual does not say whether GPL subtracts one (gpl-classes.md §23.16), and passing them through
  is the only choice that reaches every address 0..65535.
* Registers read back as Integers 0..65535; a register written may be -32768..65535.
* Errors: exception response -> -1730 *Modbus/RIO exception: n* with ``Qualifier`` = the Modbus
  exception code n; no reply within ``Timeout`` (or no connection within it) -> -1731
  *Modbus/RIO device timeout*; connection refused -> -1702; the slave closed the connection ->
  -1708; a malformed reply -> -1709 *Invalid protocol*; bad count/address/value -> -707.
* Array parameters are annotated ``list[T]`` (a one-dimensional GPL array of T); values are built
  by ``gplrt.io._arrays.make_array``.
* The Modbus/TCP unit identifier is 1 by default (Python-side ``unit_id`` attribute).
* A thread waiting for a reply (``Timeout`` 0 waits forever) ends on ``Thread.Abort``, and
  ``Close`` from another thread does not wait for the reply: it drops the connection and the
  waiting call raises -1707 *Socket not open*.
"""

from __future__ import annotations

import socket as _socket
import struct
import threading
from typing import Any

from gplrt.io._arrays import make_array, to_list
from gplrt.io._blocking import blocking_call, wait_ready
from gplrt.io._codec import from_bytes
from gplrt.io.sockets import IPEndPoint, _ready, _seconds, network_config
from gplrt.lang.errors import (
    CONNECTION_CLOSED,
    CONNECTION_REFUSED,
    INVALID_PROTOCOL,
    SOCKET_NOT_OPEN,
    MODBUS_EXCEPTION,
    MODBUS_TIMEOUT,
    OBJECT_NOT_INSTANTIATED,
    VALUE_OUT_OF_RANGE,
    GplException,
    host_reason,
)
from gplrt.lang.gpltypes import Boolean, Integer, Ref, String

STANDARD_PORT = 502


class Modbus:
    """``New Modbus(ep)``: the connection object for one MODBUS/TCP slave."""

    def __init__(self, ep: IPEndPoint) -> None:
        if ep is None:
            raise GplException(OBJECT_NOT_INSTANTIATED, detail="Modbus needs an IPEndPoint")
        host, port = ep._remote()
        self._address = (host, port or STANDARD_PORT)
        self._timeout_ms = 0
        self._sock: _socket.socket | None = None
        self._tid = 0
        self._lock = threading.Lock()
        self.unit_id = 1

    # -- GPL members ---------------------------------------------------------------------------

    @property
    def Timeout(self) -> Integer:
        """Milliseconds to wait for a reply before -1731; 0 = wait forever (the default)."""
        return Integer(self._timeout_ms)

    @Timeout.setter
    def Timeout(self, value: Integer) -> None:
        self._timeout_ms = max(0, int(value))

    def Close(self) -> None:
        """Drop the connection now, even while another thread waits for a reply (no lock)."""
        self._disconnect()

    def ReadCoils(self, start: Integer, number: Integer, value_array: Ref[list[Boolean]]) -> None:
        """FC1: ``number`` coils from ``start`` into a Boolean array (element 0 = ``start``)."""
        value_array.set(make_array(self._read_bits(1, start, number), Boolean))

    def ReadDiscreteInputs(self, start: Integer, number: Integer, value_array: Ref[list[Boolean]]) -> None:
        """FC2: discrete inputs into a Boolean array."""
        value_array.set(make_array(self._read_bits(2, start, number), Boolean))

    def ReadHoldingRegisters(self, start: Integer, number: Integer, value_array: Ref[list[Integer]]) -> None:
        """FC3: holding registers into an Integer array (0..65535)."""
        value_array.set(make_array(self._read_registers(3, start, number), Integer))

    def ReadInputRegisters(self, start: Integer, number: Integer, value_array: Ref[list[Integer]]) -> None:
        """FC4: input registers into an Integer array (0..65535)."""
        value_array.set(make_array(self._read_registers(4, start, number), Integer))

    def WriteSingleCoil(self, coil: Integer, value: Boolean) -> None:
        """FC5: one coil (any non-zero value is on; EX-23 passes ``ii And 1``)."""
        payload = struct.pack(">HH", _address(coil), 0xFF00 if value else 0x0000)
        self._expect_echo(5, payload)

    def WriteSingleRegister(self, register: Integer, value: Integer) -> None:
        """FC6: one holding register."""
        payload = struct.pack(">HH", _address(register), _register(value))
        self._expect_echo(6, payload)

    def WriteMultipleCoils(self, start: Integer, value_array: list[Boolean]) -> None:
        """FC15: all elements of a Boolean array, element 0 to coil ``start``."""
        bits = [bool(v) for v in to_list(value_array)]
        _count(len(bits), 1968)
        packed = bytearray((len(bits) + 7) // 8)
        for i, bit in enumerate(bits):
            if bit:
                packed[i // 8] |= 1 << (i % 8)
        payload = struct.pack(">HHB", _address(start), len(bits), len(packed)) + bytes(packed)
        self._expect_header(15, start, len(bits), payload)

    def WriteMultipleRegisters(self, start: Integer, value_array: list[Integer]) -> None:
        """FC16: all elements of an Integer array, element 0 to register ``start``."""
        values = [_register(v) for v in to_list(value_array)]
        _count(len(values), 123)
        payload = struct.pack(f">HHB{len(values)}H", _address(start), len(values), 2 * len(values), *values)
        self._expect_header(16, start, len(values), payload)

    def ReadDeviceID(self, object_id: Integer = Integer(0)) -> String:
        """FC43 / MEI 14: one device-identification object (0 VendorName, 1 ProductCode,
        2 MajorMinorRevision, ...) as a String."""
        if not 0 <= int(object_id) <= 255:
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"object id {object_id}")
        reply = self._transact(43, bytes([0x0E, 0x04, int(object_id)]))
        try:
            count = reply[5]
            pos = 6
            for _ in range(count):
                oid, length = reply[pos], reply[pos + 1]
                value = reply[pos + 2 : pos + 2 + length]
                if len(value) != length:
                    break
                if oid == int(object_id):
                    return String(from_bytes(value))
                pos += 2 + length
        except IndexError:
            pass
        raise GplException(INVALID_PROTOCOL, detail="device identification reply without the object")

    ReadDeviceId = ReadDeviceID  # spelling used by gpl-classes.md; GPL names are case-insensitive

    # -- requests ------------------------------------------------------------------------------

    def _read_bits(self, function: int, start: int, number: int) -> list[bool]:
        _count(int(number), 2000)
        reply = self._transact(function, struct.pack(">HH", _address(start), int(number)))
        data = reply[1:]
        if not reply or reply[0] != len(data) or len(data) < (int(number) + 7) // 8:
            raise GplException(INVALID_PROTOCOL, detail=f"FC{function}: bad byte count")
        return [bool(data[i // 8] >> (i % 8) & 1) for i in range(int(number))]

    def _read_registers(self, function: int, start: int, number: int) -> list[int]:
        _count(int(number), 125)
        reply = self._transact(function, struct.pack(">HH", _address(start), int(number)))
        if not reply or reply[0] != 2 * int(number) or len(reply) != 1 + 2 * int(number):
            raise GplException(INVALID_PROTOCOL, detail=f"FC{function}: bad byte count")
        return list(struct.unpack(f">{int(number)}H", reply[1:]))

    def _expect_echo(self, function: int, payload: bytes) -> None:
        if self._transact(function, payload) != payload:
            raise GplException(INVALID_PROTOCOL, detail=f"FC{function}: reply does not echo the request")

    def _expect_header(self, function: int, start: int, count: int, payload: bytes) -> None:
        if self._transact(function, payload) != struct.pack(">HH", _address(start), count):
            raise GplException(INVALID_PROTOCOL, detail=f"FC{function}: unexpected reply")

    # -- transport -----------------------------------------------------------------------------

    def _timeout(self) -> float | None:
        return _seconds(self._timeout_ms)  # GPL's 0 = forever, as for socket timeouts

    def _disconnect(self) -> None:
        sock, self._sock = self._sock, None
        if sock is not None:
            sock.close()

    def _connect(self) -> _socket.socket:
        if self._sock is not None:
            return self._sock
        timeout = self._timeout() or network_config().connect_timeout
        where = f"{self._address[0]}:{self._address[1]}"
        try:
            sock = blocking_call(lambda: _socket.create_connection(self._address, timeout), timeout)
        except TimeoutError:
            raise GplException(MODBUS_TIMEOUT, detail=f"no connection to {where}") from None
        except ConnectionRefusedError:
            raise GplException(CONNECTION_REFUSED, detail=f"Modbus slave {where}") from None
        except OSError as exc:
            raise GplException(MODBUS_TIMEOUT, detail=f"{where}: {host_reason(exc)}") from None
        sock.settimeout(None)
        sock.setsockopt(_socket.IPPROTO_TCP, _socket.TCP_NODELAY, 1)
        self._sock = sock
        return sock

    def _transact(self, function: int, payload: bytes) -> bytes:
        """Send one request PDU and return the reply's data (after the function code)."""
        with self._lock:
            sock = self._connect()
            self._tid = (self._tid + 1) & 0xFFFF
            pdu = bytes([function]) + payload
            frame = struct.pack(">HHHB", self._tid, 0, len(pdu) + 1, self.unit_id) + pdu
            try:
                sock.sendall(frame)
                while True:
                    header = self._receive(sock, 7)
                    tid, protocol, length, _unit = struct.unpack(">HHHB", header)
                    if protocol != 0 or length < 2:
                        raise GplException(INVALID_PROTOCOL, detail="bad MBAP header")
                    body = self._receive(sock, length - 1)
                    if tid == self._tid:
                        break  # replies to earlier (timed-out) requests are skipped
            except GplException:
                self._disconnect()  # the stream position is unknown: start afresh next time
                raise
            except OSError as exc:
                self._disconnect()
                raise GplException(CONNECTION_CLOSED, detail=f"Modbus slave: {host_reason(exc)}") from None
            except BaseException:  # Thread.Abort while waiting: the reply may still come
                self._disconnect()
                raise
        return _reply_data(function, body)

    def _receive(self, sock: _socket.socket, size: int) -> bytes:
        timeout = self._timeout()

        def check() -> None:
            if self._sock is not sock:
                raise GplException(SOCKET_NOT_OPEN, detail="the Modbus connection was closed while waiting")

        def wait() -> bytes:
            data = bytearray()
            while len(data) < size:
                if not wait_ready(lambda step: _ready(sock, step), timeout, check):
                    raise GplException(MODBUS_TIMEOUT, detail=f"no reply within {self._timeout_ms} ms")
                check()
                chunk = sock.recv(size - len(data))
                if not chunk:
                    raise GplException(CONNECTION_CLOSED, detail="the Modbus slave closed the connection")
                data += chunk
            return bytes(data)

        return blocking_call(wait, timeout)


def _reply_data(function: int, pdu: bytes) -> bytes:
    """A reply PDU's data after its function code; an exception reply is -1730 with its code
    (the same for every transport: TCP here, RTU in ``gplrt.io.modbus_rtu``)."""
    if pdu[0] == function | 0x80:
        code = pdu[1] if len(pdu) > 1 else 0
        raise GplException(MODBUS_EXCEPTION, code, detail=f"FC{function}: exception code {code}")
    if pdu[0] != function:
        raise GplException(INVALID_PROTOCOL, detail=f"reply to FC{pdu[0]} for FC{function}")
    return pdu[1:]


def _address(value: int) -> int:
    if not 0 <= int(value) <= 0xFFFF:
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"Modbus address {value}")
    return int(value)


def _register(value: Any) -> int:
    number = int(value)
    if not -0x8000 <= number <= 0xFFFF:
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"register value {number}")
    return number & 0xFFFF


def _count(number: int, limit: int) -> None:
    if not 1 <= number <= limit:
        raise GplException(VALUE_OUT_OF_RANGE, detail=f"count {number}: must be 1..{limit}")


__all__ = ["Modbus"]
