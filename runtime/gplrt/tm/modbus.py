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

``ModbusRTU dev = "COM2", 115200 [, ...]`` (L18527) is the same device on a virtual serial port
(``gplrt.tm.serial``: the user attaches the port's other end), framed by ``gplrt.io.modbus_rtu``
(the same requests and error codes, RTU frames with CRC-16/MODBUS); the slave id is the RTU
address.  ``dev.Preset(name, slave, "DO"|"DI"|"RO"|"RI", addr, type [, endian|count])`` (L18372)
names an item; ``modbus_read(dev, preset)`` gives its value in its type and ``modbus_write(dev,
preset, value [, maxAddr])`` writes one (L18796, L19446).  ``IODDPreset`` is not simulated.  A
failed read is a script error naming the Modbus error; a failed write returns false (L19590).
"""

from __future__ import annotations

import re
import struct

import numpy as np

from gplrt.io.modbus import Modbus
from gplrt.io.modbus_rtu import ModbusRtu
from gplrt.io.sockets import IPEndPoint
from gplrt.lang.byref import Box
from gplrt.lang.errors import NO_DEVICE_MAPPED, GplException
from gplrt.tm.devices import Device, find
from gplrt.tm.serial import SerialSettings
from gplrt.tm.values import F32, F64, Array, TMError, to_bool, to_byte, to_double, to_float, to_int, to_string

#: Read type -> (function code, per address: "bit" or "register").
READS = {"DO": 1, "DI": 2, "RO": 3, "RI": 4}
#: A preset's value type -> registers per value (L18372; ``int`` is the manual's own example's
#: spelling of ``int32``, L18437).
PRESET_TYPES = {"bool": 1, "byte": 1, "int16": 1, "int32": 2, "int": 2, "float": 2, "double": 4, "string": 0}
_PRESET_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


class Preset:
    """A named Modbus item of a device (L18372): slave, signal type, address, value type and the
    endian (int32/float/double) or address count (string)."""

    def __init__(self, slave: int, signal: str, addr: int, kind: str, suffix: int) -> None:
        self.slave, self.signal, self.addr, self.kind, self.suffix = slave, signal, addr, kind, suffix


class ModbusDevice(Device):
    """What ``ModbusTCP`` and ``ModbusRTU`` share: the master, the presets."""

    kind = "modbus"

    def __init__(self, name: str, master: Modbus, timeout: int) -> None:
        self.master = master
        self.master.Timeout = timeout  # type: ignore[assignment]
        self.presets: dict[str, Preset] = {}
        super().__init__(name)

    def close(self) -> bool:
        self.master.Close()
        return True

    def Preset(self, name: object, slave: object, signal: object, addr: object, kind: object,
               suffix: object = None) -> bool:
        """Define (or redefine) the preset ``name`` (L18372-L18404).  A name that is not a word of
        letters, digits and ``_`` (not starting with a digit) is an error (the manual's
        ``Preset("9000", ...)``, L18434); a signal or value type the table does not have, or a
        bit signal (DO/DI) with a register type, is false."""
        key = to_string(name)
        if not _PRESET_NAME.match(key):
            raise TMError(f"{self.name}.Preset: the preset name {key!r} must be letters, digits and '_' (L18434)")
        signal_text, kind_text = to_string(signal).strip().upper(), to_string(kind).strip().lower()
        if signal_text not in READS or kind_text not in PRESET_TYPES:
            return False
        if signal_text in ("DO", "DI") and kind_text not in ("bool", "byte"):
            return False
        if kind_text == "int":
            kind_text = "int32"
        default = 0 if kind_text == "string" else 1
        number = default if suffix is None else to_int(suffix)
        if kind_text in ("int32", "float", "double") and number not in (0, 1):
            return False
        self.presets[key.lower()] = Preset(to_int(slave) & 0xFF, signal_text, to_int(addr), kind_text, number)
        return True

    def IODDPreset(self, *args: object) -> bool:
        """Presets from an IODD file (L18480): not simulated (no IODD files on the robot)."""
        raise TMError(f"{self.name}.IODDPreset: IODD files are not simulated")


class ModbusTCP(ModbusDevice):
    """A Modbus TCP device ``name`` at ``ip``:``port`` (L18326)."""

    def __init__(self, name: str, ip: object, port: object = 502, timeout: object = 10000) -> None:
        super().__init__(name, Modbus(IPEndPoint(to_string(ip), to_int(port))), to_int(timeout))  # type: ignore[arg-type]


class ModbusRTU(ModbusDevice):
    """A Modbus RTU device ``name`` on a virtual serial port, with a SerialPort's parameter list
    (L18527-L18582): the line opens on first use or ``modbus_open``."""

    def __init__(self, name: str, *args: object) -> None:
        if len(args) not in (2, 5, 6, 9):
            raise TMError(f"ModbusRTU {name}: {len(args)} values; the class takes 2, 5, 6 or 9 (L18531)")
        settings = SerialSettings(f"ModbusRTU {name}", *args)

        def opener() -> object:
            try:
                return settings.open(f'ModbusRTU "{name}"')
            except TMError as exc:  # (a read reports it, a write is false, as for any Modbus failure)
                raise GplException(NO_DEVICE_MAPPED, detail=str(exc)) from None
        super().__init__(name, ModbusRtu(opener), settings.timeout)


def _device(name: object, what: str) -> Modbus:
    return _known(name, what).master


def _known(name: object, what: str) -> ModbusDevice:
    dev = find("modbus", name)
    if dev is None:
        raise TMError(f"{what}: no Modbus device named {to_string(name)!r}")
    return dev  # type: ignore[no-any-return]


def modbus_open(name: object) -> bool:
    """Connect now (L18739); false when the device does not answer."""
    master = _device(name, "modbus_open")
    try:
        master._connect()
    except (GplException, TMError):
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


def modbus_read(name: object, *args: object) -> object:
    """``(dev, preset)``: the preset's value in its type (L18796); ``(dev, slave, type, addr,
    count)``: the raw bytes of ``count`` addresses (L18871)."""
    if len(args) == 1:
        return _preset_read(name, args[0])
    if len(args) != 4:
        raise TMError(f"modbus_read: {len(args) + 1} arguments; it takes 2 (a preset) or 5 (L18796, L18871)")
    return Array("byte", _raw(name, *args, "modbus_read"))


def _preset(name: object, preset: object, what: str) -> tuple[ModbusDevice, Preset]:
    dev = _known(name, what)
    found = dev.presets.get(to_string(preset).strip().lower())
    if found is None:
        raise TMError(f"{what}: the Modbus device {dev.name} has no preset {to_string(preset)!r}")
    return dev, found


def _preset_read(name: object, preset: object) -> object:
    """A preset's value (the table at L18810): a bit as bool or byte, a register as bool (not 0),
    byte (its low byte), int16, int32/float/double (two or four registers in the preset's word
    order) or UTF-8 text up to 0x00 over its address count."""
    dev, p = _preset(name, preset, "modbus_read")
    count = p.suffix if p.kind == "string" else PRESET_TYPES[p.kind]
    if count <= 0:
        raise TMError(f"modbus_read: the string preset {to_string(preset)!r} has no address count (L18390)")
    data = _raw(name, p.slave, p.signal, p.addr, count, "modbus_read")
    if p.signal in ("DO", "DI") or p.kind in ("bool", "byte"):
        bit = data[-1] if p.signal in ("RO", "RI") else data[0]
        return bool(any(data)) if p.kind == "bool" else bit
    if p.kind == "int16":
        return struct.unpack(">h", data)[0]
    if p.kind == "string":
        return _text(data)
    size, fmt = {"int32": (4, ">i"), "float": (4, ">f"), "double": (8, ">d")}[p.kind]
    value = struct.unpack(fmt, _words(data, size, p.suffix)[0])[0]
    return F32(value) if p.kind == "float" else F64(value) if p.kind == "double" else value


def _text(data: bytes) -> str:
    """Register bytes as UTF-8 up to the first 0x00; a character cut at the end is dropped."""
    return data.split(b"\x00", 1)[0].decode("utf-8", errors="ignore")


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
    return _text(_raw(name, slave, kind, addr, count, "modbus_read_string"))  # ("1234", L19425)


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


def modbus_write(name: object, *args: object) -> bool:
    """``(dev, preset, value [, maxAddr])`` writes a preset (L19446); ``(dev, slave, type, addr,
    value [, maxAddr])`` coils or registers from ``addr`` (L19552).  False when there is nothing
    to write or the device fails."""
    if len(args) in (2, 3):
        return _preset_write(name, *args)
    if len(args) not in (4, 5):
        raise TMError(f"modbus_write: {len(args) + 1} arguments; it takes 3 or 4 (a preset), 5 or 6 (L19446, L19552)")
    return _write(name, *args)


def _preset_write(name: object, preset: object, value: object, max_addr: object = None) -> bool:
    """A preset's write (the table at L19466): a coil (FC 05); a bool, byte or int16 register
    (FC 06); int32/float/double in the preset's word order and text (FC 16).  Text goes as its
    UTF-8 bytes padded with 0x00 to whole registers, at most ``maxAddr`` registers when > 0, else
    the preset's address count when > 0 (L19500: the rest of the registers keep what they had,
    the manual's ``1234oWorld``, L18471)."""
    dev, p = _preset(name, preset, "modbus_write")
    if isinstance(value, (list, tuple)):
        raise TMError("modbus_write: a preset takes one value, not an array (L19490)")
    if p.signal not in ("DO", "RO"):
        raise TMError(f"modbus_write: the preset {to_string(preset)!r} is an input ({p.signal}): it cannot be written")
    master = dev.master
    master.unit_id = p.slave
    try:
        if p.signal == "DO":
            on = bool(value) if isinstance(value, (bool, np.bool_)) else to_int(value) != 0
            master.WriteSingleCoil(p.addr, on)  # type: ignore[arg-type]
            return True
        if p.kind in ("bool", "byte", "int16"):
            word = (1 if to_bool(value) else 0) if p.kind == "bool" else to_byte(value) if p.kind == "byte" \
                else to_int(value) & 0xFFFF
            master.WriteSingleRegister(p.addr, word)  # type: ignore[arg-type]
            return True
        if p.kind == "string":
            data = to_string(value).encode("utf-8")
            limit = p.suffix if max_addr is None else to_int(max_addr)
        else:
            size, fmt, convert = {"int32": (4, ">i", to_int), "float": (4, ">f", to_float),
                                  "double": (8, ">d", to_double)}[p.kind]
            data = _words(struct.pack(fmt, convert(value)), size, p.suffix)[0]  # type: ignore[operator]
            limit = 0
        return _write_registers(master, p.addr, data, limit)
    except GplException:
        return False


def _write_registers(master: Modbus, start: int, data: bytes, limit: int) -> bool:
    """FC 16: ``data`` zero-padded to whole registers, at most ``limit`` of them when > 0; false
    when there is nothing to write."""
    data = data.ljust(-(-len(data) // 2) * 2, b"\x00")
    registers = [int.from_bytes(data[i:i + 2], "big") for i in range(0, len(data), 2)]
    registers = registers[:limit if limit > 0 else None]
    if not registers:
        return False
    master.WriteMultipleRegisters(start, registers)  # type: ignore[arg-type]
    return True


def _write(name: object, slave: object, kind: object, addr: object, value: object, max_addr: object = 0) -> bool:
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
        return _write_registers(master, start, _register_bytes(value), limit)
    except GplException:
        return False


__all__ = ["ModbusRTU", "ModbusTCP", "modbus_close", "modbus_open", "modbus_read", "modbus_read_double",
           "modbus_read_float", "modbus_read_int16", "modbus_read_int32", "modbus_read_string", "modbus_write"]
