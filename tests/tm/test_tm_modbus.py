"""TMscript's ModbusTCP class and user-defined modbus_* reads and writes (manual §15,
L18324-L19693) against a pymodbus TCP server holding the manual's example data."""

from __future__ import annotations

import math
import socket
import struct
from collections.abc import Iterator

import pytest
from tmpacket import modbus_slave, run_packet

from gplrt.tm import context

pymodbus = pytest.importorskip("pymodbus")
from pymodbus.client import ModbusTcpClient  # noqa: E402
from pymodbus.datastore import ModbusDeviceContext, ModbusSequentialDataBlock  # noqa: E402

RO_BYTES = bytes.fromhex("54656368 6D616EE9 8194E698")
RI_BYTES = bytes.fromhex("29309F4C C37C999A 445EECCD 42B40000 80000000 00000000")
RI_DATE = bytes.fromhex("07E20005 0012000F 00310023")


def registers(data: bytes) -> list[int]:
    return list(struct.unpack(f">{len(data) // 2}H", data))


@pytest.fixture
def port() -> Iterator[int]:
    """A pymodbus slave: coils 0-3 off, inputs 0-2 = 1,0,0, holding registers 0-5 the manual's
    RO 9000 bytes, input registers 0-11 its RI 7001 bytes and 20-25 its RI 7301 bytes."""
    device = ModbusDeviceContext(
        co=ModbusSequentialDataBlock(1, [False] * 16), di=ModbusSequentialDataBlock(1, [True, False, False]),
        hr=ModbusSequentialDataBlock(1, registers(RO_BYTES) + [0] * 20),
        ir=ModbusSequentialDataBlock(1, registers(RI_BYTES) + [0] * 8 + registers(RI_DATE)))
    with modbus_slave(device) as free:
        context.use_robot("TM5-900")
        yield free


def close(a: list[float], b: list[float]) -> bool:
    return len(a) == len(b) and all(math.isclose(x, y, rel_tol=1e-6, abs_tol=1e-45) for x, y in zip(a, b))


def test_reads_l18871_l19445(port: int) -> None:
    v = run_packet(f'ModbusTCP TCP_1 = "127.0.0.1", {port}\nbool o = modbus_open("TCP_1")\n'
            'byte[] do4 = modbus_read("TCP_1", 0, "DO", 0, 4)\nbyte[] di3 = modbus_read("TCP_1", 0, "DI", 0, 3)\n'
            'byte[] ro = modbus_read("TCP_1", 0, "RO", 0, 6)\nbyte[] ri = modbus_read("TCP_1", 0, "RI", 0, 12)\n'
            'int[] a = modbus_read_int16("TCP_1", 0, "DI", 0, 3)\nint[] b = modbus_read_int16("TCP_1", 0, "RO", 0, 6)\n'
            'int[] c = modbus_read_int16("TCP_1", 0, "RI", 0, 12)\nint[] d = modbus_read_int16("TCP_1", 0, "RI", 20, 6)\n'
            'int[] e = modbus_read_int32("TCP_1", 0, "DI", 0, 3)\nint[] f = modbus_read_int32("TCP_1", 0, "RO", 0, 6)\n'
            'int[] g = modbus_read_int32("TCP_1", 0, "RI", 0, 12)\nint[] h = modbus_read_int32("TCP_1", 0, "RI", 20, 6)\n'
            'int[] i = modbus_read_int32("TCP_1", 0, "RI", 20, 6, 0)\nfloat[] j = modbus_read_float("TCP_1", 0, "DI", 0, 3)\n'
            'float[] k = modbus_read_float("TCP_1", 0, "RO", 0, 6)\nfloat[] l = modbus_read_float("TCP_1", 0, "RI", 0, 12)\n'
            'double[] m = modbus_read_double("TCP_1", 0, "RO", 0, 6)\ndouble[] n = modbus_read_double("TCP_1", 0, "RI", 0, 12)\n'
            'bool x = modbus_close("TCP_1")')
    assert v.o is True and v.x is True
    assert (bytes(v.do4), bytes(v.di3), bytes(v.ro), bytes(v.ri)) == (b"\0\0\0\0", b"\1\0\0", RO_BYTES, RI_BYTES)
    assert v.a == [256, 0] and v.b == [21605, 25448, 28001, 28393, -32364, -6504]
    assert v.c == [10544, -24756, -15492, -26214, 17502, -4915, 17076, 0, -32768, 0, 0, 0]
    assert v.d == [2018, 5, 18, 15, 49, 35]
    assert v.e == [16777216] and v.f == [1415930728, 1835101929, -2120948072]
    assert v.g == [691052364, -1015244390, 1147071693, 1119092736, -2147483648, 0]
    assert v.h == [132251653, 1179663, 3211299] and v.i == [329698, 983058, 2293809]
    assert close(v.j, [2.350989e-38]) and close(v.k, [3.940861e12, 4.360513e27, -5.46975e-38])
    assert close(v.l, [3.921802e-14, -252.6, 891.7, 90, 0, 0])
    assert close(v.m, [3.65481260356117e98, -4.87647898854073e-301])
    assert close(v.n, [2.76472410615396e-110, 2.2818627604613e21, 0])


def test_writes_and_string_l19346_l19552(port: int) -> None:
    v = run_packet(f'ModbusTCP TCP_1 = "127.0.0.1", {port}\nbyte[] bb = {{10, 20, 0, 30}}\n'
            'bool w1 = modbus_write("TCP_1", 0, "DO", 0, bb)\nbool w2 = modbus_write("TCP_1", 0, "DO", 8, bb, 2)\n'
            'bool w3 = modbus_write("TCP_1", 0, "DO", 12, true)\nint i = 10000\n'
            'bool w4 = modbus_write("TCP_1", 0, "RO", 10, i)\nstring[] n = {"ABC", "12", "34"}\n'
            'bool w5 = modbus_write("TCP_1", 0, "RO", 14, n, 2)\nbool w6 = modbus_write("TCP_1", 0, "RO", 16, "1234達明")\n'
            'string s3 = modbus_read_string("TCP_1", 0, "RO", 16, 3)\nstring s6 = modbus_read_string("TCP_1", 0, "RO", 16, 6)\n'
            'byte[] empty = {}\nbool w7 = modbus_write("TCP_1", 0, "RO", 20, empty)')
    assert (v.w1, v.w2, v.w3, v.w4, v.w5, v.w6, v.w7) == (True, True, True, True, True, True, False)
    assert (v.s3, v.s6) == ("1234", "1234達明")
    client = ModbusTcpClient("127.0.0.1", port=port, timeout=5)
    assert client.connect()
    try:
        assert list(client.read_coils(0, count=13).bits[:13]) == [True, True, False, True] + [False] * 4 + [True, True, False, False, True]
        assert client.read_holding_registers(10, count=2).registers == [0x0000, 0x2710]
        assert client.read_holding_registers(14, count=2).registers == [0x4142, 0x4331]  # "AB", "C1"
    finally:
        client.close()


def test_a_device_that_does_not_answer(port: int) -> None:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        dead = s.getsockname()[1]
    v = run_packet(f'ModbusTCP m = "127.0.0.1", {dead}, 500\nbool o = modbus_open("m")\nbool w = modbus_write("m", 0, "DO", 0, true)')
    assert (v.o, v.w) == (False, False)
