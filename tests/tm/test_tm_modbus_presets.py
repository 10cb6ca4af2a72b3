"""TMscript's Modbus presets (``dev.Preset``, ``modbus_read(dev, preset)``, ``modbus_write(dev,
preset, value [, maxAddr])``: manual L18372-L18404, L18796, L19446) and the ``ModbusRTU`` class
(L18527-L18582), against pymodbus slaves: a Modbus TCP one, and an RTU one (pymodbus's RTU
framer, CRC included) that the robot's virtual serial port reaches with pyserial's ``socket://``."""

from __future__ import annotations

import struct
from collections.abc import Iterator

import pytest
from tmpacket import modbus_slave, run_packet

from gplrt.io.modbus_rtu import crc16_modbus, frame
from gplrt.tm import context
from gplrt.tm.serial import attach_serial
from gplrt.tm.values import TMError

pymodbus = pytest.importorskip("pymodbus")
from pymodbus import FramerType  # noqa: E402
from pymodbus.datastore import ModbusDeviceContext, ModbusSequentialDataBlock  # noqa: E402


def registers(data: bytes) -> list[int]:
    return list(struct.unpack(f">{len(data) // 2}H", data))


def slave(framer: FramerType) -> Iterator[int]:
    """A pymodbus slave on loopback speaking ``framer``, holding the manual's preset table data
    (L18830): coil 800 on, input 7202 on, holding registers 9000-9003 ``ab1234cd``, input
    registers 7001-7002 the float -314.1593 (big endian); its port."""
    coils = [False] * 8000
    coils[800] = True
    inputs = [False] * 8000
    inputs[7202] = True
    holding = [0] * 9100
    holding[9000:9004] = registers(b"ab1234cd")
    inputs_r = [0] * 7100
    inputs_r[7001:7003] = registers(struct.pack(">f", -314.1593))
    device = ModbusDeviceContext(co=ModbusSequentialDataBlock(1, coils), di=ModbusSequentialDataBlock(1, inputs),
                                 hr=ModbusSequentialDataBlock(1, holding), ir=ModbusSequentialDataBlock(1, inputs_r))
    with modbus_slave(device, framer) as free:
        context.use_robot("TM5-900")
        try:
            yield free
        finally:
            attach_serial("COM2", None)


@pytest.fixture(params=["tcp", "rtu"])
def device(request) -> Iterator[str]:  # type: ignore[no-untyped-def]
    """The declaration of a device ``mbus1`` on a fresh slave: Modbus TCP, or Modbus RTU on
    the virtual port COM2 attached to an RTU slave."""
    rtu = request.param == "rtu"
    for port in slave(FramerType.RTU if rtu else FramerType.SOCKET):
        if rtu:
            attach_serial("COM2", f"socket://127.0.0.1:{port}")
            yield 'ModbusRTU mbus1 = "COM2",115200'
        else:
            yield f'ModbusTCP mbus1 = "127.0.0.1", {port}'


def test_the_crc_of_an_rtu_frame() -> None:
    """The classic read of one holding register of slave 1: ``01 03 00 00 00 01 84 0A``."""
    assert frame(1, bytes([3, 0, 0, 0, 1])) == bytes.fromhex("010300000001840A")
    assert crc16_modbus(b"123456789") == 0x4B37  # (CRC-16/MODBUS's check value)


def test_the_manuals_preset_example_e100(device: str) -> None:
    v = run_packet(
        f"{device}\n"
        'bool p1 = mbus1.Preset("light", 1, "DO", 7206, "bool")\n'
        'bool p2 = mbus1.Preset("preset_9000", 1, "RO", 9000, "int", 0)\n'
        'bool p3 = mbus1.Preset("preset_9000", 1, "RO", 9000, "string", 5)\n'
        'bool flag = modbus_read("mbus1", "light")\n'
        'modbus_write("mbus1", "light", true)\n'
        'bool flag2 = modbus_read("mbus1", "light")\n'
        'bool w0 = modbus_write("mbus1 ", "preset_9000", Ctrl("\\0\\0\\0\\0\\0\\0\\0\\0\\0\\0"))\n'
        'bool w1 = modbus_write("mbus1", "preset_9000", 1234)\n'
        'int var_i = modbus_read("mbus1", "preset_9000")\n'
        'modbus_write("mbus1", "preset_9000", "HelloWorld")\n'
        'string var_s = modbus_read("mbus1", "preset_9000")\n'
        'modbus_write("mbus1", "preset_9000", 1234)\n'
        'string var_t = modbus_read("mbus1", "preset_9000")')
    assert (v.p1, v.p2, v.p3, v.flag, v.flag2, v.w0, v.w1) == (True, True, True, False, True, True, True)
    assert (v.var_i, v.var_s, v.var_t) == (1234, "HelloWorld", "1234oWorld")
    # "Return error, unable to convert 1234oWorld to integer" (L18474)
    with pytest.raises(TMError):
        run_packet('int var_j = modbus_read("mbus1", "preset_9000")')
    # "Return error, naming must be in alphanumeric combination" (L18434)
    with pytest.raises(TMError, match="preset name '9000'"):
        run_packet(f'{device}\nmbus1.Preset("9000", 1, "RO", 9000, "string")')


def test_preset_reads_l18830(device: str) -> None:
    v = run_packet(
        f"{device}\n"
        'mbus1.Preset("preset_800", 1, "DO", 800, "byte")\nmbus1.Preset("preset_7202", 1, "DI", 7202, "bool")\n'
        'mbus1.Preset("preset_9000", 1, "RO", 9000, "string", 4)\nmbus1.Preset("preset_7001", 1, "RI", 7001, "float")\n'
        'byte a = modbus_read("TCP_1", "preset_800")' .replace("TCP_1", "mbus1") + "\n"
        'bool b = modbus_read("mbus1", "preset_7202")\nstring c = modbus_read("mbus1", "preset_9000")\n'
        'float d = modbus_read("mbus1", "preset_7001")\n'
        'bool bad = mbus1.Preset("p", 1, "DI", 7202, "float")')
    assert (v.a, v.b, v.c, float(v.d)) == (1, True, "ab1234cd", pytest.approx(-314.1593, rel=1e-7))
    assert v.bad is False  # (a bit signal holds no float: the preset is refused)


def test_preset_writes_l19510(device: str) -> None:
    """A string preset of 4 addresses writes at most 8 bytes, padded with 0x00 to whole registers;
    ``maxAddr`` 0 writes all, 5 at most 5 registers; int32 in the preset's word order."""
    def raw(call: str) -> bytes:
        return bytes(run_packet(f"{call}\nbyte[] r = modbus_read(\"mbus1\", 1, \"RO\", 9000, 5)").r)

    run_packet(f"{device}\n"
               'mbus1.Preset("preset_800", 1, "DO", 800, "bool")\nmbus1.Preset("preset_9000", 1, "RO", 9000, "string", 4)\n'
               'mbus1.Preset("little", 1, "RO", 9000, "int32", 0)\nmbus1.Preset("big", 1, "RO", 9000, "int32")\n'
               'mbus1.Preset("d", 1, "RO", 9000, "double", 0)')
    v = run_packet('modbus_write("mbus1", "preset_800", 0)\nbyte a = modbus_read("mbus1", 1, "DO", 800, 1)[0]\n'
                   'modbus_write("mbus1", "preset_800", 1)\nbyte b = modbus_read("mbus1", 1, "DO", 800, 1)[0]')
    assert (v.a, v.b) == (0, 1)
    assert raw('modbus_write("mbus1", "preset_9000", "ABCDEFGHJKLMNOPQRST")') == b"ABCDEFGH\x00\x00"
    assert raw('modbus_write("mbus1", "preset_9000", "1234567")') == b"1234567\x00\x00\x00"
    assert raw('modbus_write("mbus1", "preset_9000", "09AB123", 0)') == b"09AB123\x00\x00\x00"
    assert raw('modbus_write("mbus1", "preset_9000", "09AB1234XY", 5)') == b"09AB1234XY"
    assert raw('modbus_write("mbus1", "little", 305419896)')[:4] == bytes.fromhex("56781234")
    assert raw('modbus_write("mbus1", "big", 305419896)')[:4] == bytes.fromhex("12345678")
    assert run_packet('modbus_write("mbus1", "d", (double)-1.5)\ndouble x = modbus_read("mbus1", "d")').x == -1.5
    v = run_packet('bool e = modbus_write("mbus1", "preset_9000", "")')
    assert v.e is False  # (nothing to write, L19500)


def test_an_rtu_slave_exception_and_an_unattached_port() -> None:
    for port in slave(FramerType.RTU):
        attach_serial("COM2", f"socket://127.0.0.1:{port}")
        with pytest.raises(TMError, match="exception"):  # (address 9500: past the slave's registers)
            run_packet('ModbusRTU r1 = "COM2",115200,"none",8,1,2000\nbyte[] x = modbus_read("r1", 1, "RO", 9500, 2)')
        v = run_packet('ModbusRTU r2 = "COM3",115200\nbool o = modbus_open("r2")\n'
                       'bool w = modbus_write("r2", 1, "RO", 1, 5)')
        assert (v.o, v.w) == (False, False)
        with pytest.raises(TMError, match="COM3 cannot be opened"):
            run_packet('byte[] y = modbus_read("r2", 1, "RO", 1, 1)')
