"""TMscript's Modbus TCP client: the ``ModbusTCP`` class and the user-defined ``modbus_*`` reads
and writes (manual §15, L18324-L19693; spec §3.18) on the runtime's Modbus master
(``gplrt.io.modbus.Modbus``, GPL's ``Modbus`` class: its framing, time-outs and error codes).

``ModbusTCP dev = "ip" [, port = 502 [, timeoutMs = 10000]]`` names a device after its variable;
it connects on first use or ``modbus_open`` (L18363).  ``modbus_read(dev, slave, "DO"|"DI"|"RO"|
"RI", addr, n)`` gives the raw bytes (a coil or input one byte 0/1, a register two bytes big
endian, L18871); the ``_int16``/``_int32``/``_float``/``_double`` forms read the same bytes
(zero-padded to whole values) as big-endian values, ``endian`` 0 taking the 16-bit words in
reverse order (CD AB, L19150); ``_string`` is UTF-8 up to the first 0x00.  ``modbus_write(dev,
slave, "DO"|"RO", addr, value [, maxAddr])`` writes coils (FC 05/15: non-zero is 1) or registers
(FC 06 for a bool, else FC 16 with the value's big-endian bytes, int as int32, text as UTF-8,
zero-padded to whole registers; a ``byte`` scalar, FC 06 on the robot, is an int at run time and
goes as an int32), at most ``maxAddr`` addresses when > 0 (L19552).

Not simulated: ``ModbusRTU`` (serial) and the presets a TMflow project defines (``modbus_read(dev,
"preset")``, L18796): there is no project to hold them.  A failed read is a script error naming
the Modbus error; a failed write returns false (L19590).
"""

from __future__ import annotations

import struct

import numpy as np

from gplrt.io.modbus import Modbus
from gplrt.io.sockets import IPEndPoint
from gplrt.lang.byref import Box
from gplrt.lang.errors import GplException
from gplrt.tm import context
from gplrt.tm.values import F32, F64, Array, TMError, to_int, to_string

#: Read type -> (function code, per address: "bit" or "register").
READS = {"DO": 1, "DI": 2, "RO": 3, "RI": 4}


class ModbusTCP:
    """A Modbus TCP device ``name`` at ``ip``:``port`` (L18326)."""

    def __init__(self, name: str, ip: object, port: object = 502, timeout: object = 10000) -> None:
        self.name = name
        self.master = Modbus(IPEndPoint(to_string(ip), to_int(port)))  # type: ignore[arg-type]
        self.master.Timeout = to_int(timeout)  # type: ignore[assignment]
        robot = context.robot()
        devices = getattr(robot, "_modbus_devices", None)
        if devices is None:
            devices = robot._modbus_devices = {}  # type: ignore[attr-defined]
        devices[name.lower()] = self


def _device(name: object, what: str) -> Modbus:
    devices = getattr(context.robot(), "_modbus_devices", {})
    dev = devices.get(to_string(name).strip().lower())
    if dev is None:
        raise TMError(f"{what}: no Modbus device named {to_string(name)!r}")
    return dev.master  # type: ignore[no-any-return]


def modbus_open(name: object) -> bool:
    """Connect now (L18739); false when the device does not answer."""
    try:
        _device(name, "modbus_open")._connect()
    except GplException:
        return False
    return True


def modbus_close(name: object) -> bool:
    """Disconnect (L18767); the next read or write connects again."""
    _device(name, "modbus_close").Close()
    return True


def _raw(name: object, slave: object, kind: object, addr: object, count: object, what: str) -> bytes:
    master = _device(name, what)
    fc = READS.get(to_string(kind).upper())
    if fc is None:
        raise TMError(f"{what}: the read type {to_string(kind)!r} is not DO, DI, RO or RI (L18880)")
    master.unit_id = to_int(slave) & 0xFF
    box = Box()
    try:
        reader = {1: master.ReadCoils, 2: master.ReadDiscreteInputs, 3: master.ReadHoldingRegisters,
                  4: master.ReadInputRegisters}[fc]
        reader(to_int(addr), to_int(count), box)  # type: ignore[arg-type]
    except GplException as exc:
        raise TMError(f"{what}: {exc}") from None
    values = list(box.value)
    if fc in (1, 2):
        return bytes(1 if v else 0 for v in values)
    return b"".join(struct.pack(">H", int(v) & 0xFFFF) for v in values)


def modbus_read(name: object, slave: object, kind: object, addr: object, count: object) -> Array:
    """The raw bytes of ``count`` addresses (L18871)."""
    return Array("byte", _raw(name, slave, kind, addr, count, "modbus_read"))


def _words(data: bytes, size: int, endian: int) -> list[bytes]:
    """``data`` zero-padded to whole ``size``-byte values, each with its 16-bit words reversed
    when ``endian`` is 0 (little endian, CD AB)."""
    data = data.ljust(-(-len(data) // size) * size, b"\x00")
    out = []
    for i in range(0, len(data), size):
        chunk = data[i:i + size]
        if endian == 0 and size > 2:
            chunk = b"".join(chunk[j:j + 2] for j in range(size - 2, -1, -2))
        out.append(chunk)
    return out


def modbus_read_int16(name: object, slave: object, kind: object, addr: object, count: object,
                      endian: object = 1) -> Array:
    """Big-endian int16s (``endian`` has no effect on 16 bits, L18960)."""
    data = _raw(name, slave, kind, addr, count, "modbus_read_int16")
    return Array("int", [struct.unpack(">h", w)[0] for w in _words(data, 2, 1)])


def modbus_read_int32(name: object, slave: object, kind: object, addr: object, count: object,
                      endian: object = 1) -> Array:
    data = _raw(name, slave, kind, addr, count, "modbus_read_int32")
    return Array("int", [struct.unpack(">i", w)[0] for w in _words(data, 4, to_int(endian))])


def modbus_read_float(name: object, slave: object, kind: object, addr: object, count: object,
                      endian: object = 1) -> Array:
    data = _raw(name, slave, kind, addr, count, "modbus_read_float")
    return Array("float", [F32(struct.unpack(">f", w)[0]) for w in _words(data, 4, to_int(endian))])


def modbus_read_double(name: object, slave: object, kind: object, addr: object, count: object,
                       endian: object = 1) -> Array:
    data = _raw(name, slave, kind, addr, count, "modbus_read_double")
    return Array("double", [F64(struct.unpack(">d", w)[0]) for w in _words(data, 8, to_int(endian))])


def modbus_read_string(name: object, slave: object, kind: object, addr: object, count: object,
                       endian: object = 1) -> str:
    """UTF-8 text up to the first 0x00 (L19346)."""
    data = _raw(name, slave, kind, addr, count, "modbus_read_string")
    return data.split(b"\x00", 1)[0].decode("utf-8", errors="ignore")  # (a character cut at the end is dropped: "1234", L19425)


def _register_bytes(value: object) -> bytes:
    """A value's big-endian bytes for FC 16 (int as int32, L19580)."""
    if isinstance(value, (list, tuple)):
        kind = getattr(value, "type", None)
        if kind in ("byte", "bool"):
            return bytes(int(v) & 0xFF for v in value)
        return b"".join(_register_bytes(v) for v in value)
    if isinstance(value, str):
        return value.encode("utf-8")
    if isinstance(value, (bool, np.bool_)):
        return bytes([1 if value else 0])
    if isinstance(value, (int, np.integer)):
        return struct.pack(">i", to_int(value))
    if isinstance(value, np.float64):
        return struct.pack(">d", float(value))
    return struct.pack(">f", float(F32(value)))


def modbus_write(name: object, slave: object, kind: object, addr: object, value: object,
                 max_addr: object = 0) -> bool:
    """Write coils (``DO``) or registers (``RO``) from ``addr`` (L19552); false when there is
    nothing to write or the device fails."""
    master = _device(name, "modbus_write")
    master.unit_id = to_int(slave) & 0xFF
    kind_text, start, limit = to_string(kind).upper(), to_int(addr), to_int(max_addr)
    try:
        if kind_text == "DO":
            if isinstance(value, (list, tuple)):
                bits = [bool(int(v)) for v in value][:limit if limit > 0 else None]
                if not bits:
                    return False
                master.WriteMultipleCoils(start, bits)  # type: ignore[arg-type]
            else:
                on = bool(value) if isinstance(value, (bool, np.bool_)) else to_int(value) != 0
                master.WriteSingleCoil(start, on)  # type: ignore[arg-type]
            return True
        if kind_text != "RO":
            raise TMError(f"modbus_write: the write type {to_string(kind)!r} is not DO or RO (L19560)")
        if isinstance(value, (bool, np.bool_)):  # (FC 06; an int scalar is an int32: FC 16)
            master.WriteSingleRegister(start, int(value) & 0xFF)  # type: ignore[arg-type]
            return True
        data = _register_bytes(value)
        data = data.ljust(-(-len(data) // 2) * 2, b"\x00")
        registers = [int.from_bytes(data[i:i + 2], "big") for i in range(0, len(data), 2)]
        registers = registers[:limit if limit > 0 else None]
        if not registers:
            return False
        master.WriteMultipleRegisters(start, registers)  # type: ignore[arg-type]
    except GplException:
        return False
    return True


__all__ = ["ModbusTCP", "modbus_close", "modbus_open", "modbus_read", "modbus_read_double", "modbus_read_float",
           "modbus_read_int16", "modbus_read_int32", "modbus_read_string", "modbus_write"]
