"""Modbus master against a real pymodbus server on 127.0.0.1 (EX-22/EX-23 shapes), and errors."""

from __future__ import annotations

import asyncio
import socket
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from gpltest import free_port
from gplrt.lang.byref import Box
from pymodbus.client import ModbusTcpClient
from pymodbus.datastore import ModbusDeviceContext, ModbusSequentialDataBlock, ModbusServerContext
from pymodbus.pdu.device import ModbusDeviceIdentification
from pymodbus.server import ModbusTcpServer

from gplrt.io.modbus import Modbus
from gplrt.io.sockets import IPEndPoint
from gplrt.lang.errors import GplException

SIZE = 100  # data points per table; reads beyond it get an exception response


@dataclass
class Slave:
    port: int

    def get(self, fc: int, address: int, count: int) -> list[int]:
        """Read back through pymodbus's own client: an independent view of the slave's data."""
        client = ModbusTcpClient("127.0.0.1", port=self.port, timeout=2)
        assert client.connect()
        try:
            if fc in (1, 2):
                read = client.read_coils if fc == 1 else client.read_discrete_inputs
                return list(read(address, count=count).bits[:count])
            read = client.read_holding_registers if fc == 3 else client.read_input_registers
            return list(read(address, count=count).registers)
        finally:
            client.close()


@pytest.fixture
def slave() -> Iterator[Slave]:
    """A pymodbus TCP server in a background thread, stopped at teardown."""
    device = ModbusDeviceContext(
        co=ModbusSequentialDataBlock(1, [False] * SIZE),
        di=ModbusSequentialDataBlock(1, [i % 3 == 0 for i in range(SIZE)]),
        hr=ModbusSequentialDataBlock(1, [0] * SIZE),
        ir=ModbusSequentialDataBlock(1, [1000 + i for i in range(SIZE)]),
    )
    identity = ModbusDeviceIdentification(info_name={"VendorName": "GplSim", "ProductCode": "PF-1"})
    port = free_port()
    loop = asyncio.new_event_loop()
    servers: list[ModbusTcpServer] = []

    async def serve() -> None:  # the server must be built inside its running loop
        server = ModbusTcpServer(
            ModbusServerContext(devices=device, single=True), identity=identity, address=("127.0.0.1", port)
        )
        servers.append(server)
        await server.serve_forever()

    thread = threading.Thread(target=loop.run_until_complete, args=(serve(),), daemon=True)
    thread.start()
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline:  # bounded wait until the port accepts
        try:
            socket.create_connection(("127.0.0.1", port), 0.2).close()
            break
        except OSError:
            time.sleep(0.02)
    yield Slave(port)
    asyncio.run_coroutine_threadsafe(servers[0].shutdown(), loop).result(5)
    thread.join(5)
    loop.close()


def test_ex23_writes_then_ex22_reads(slave: Slave) -> None:
    mb = Modbus(IPEndPoint("127.0.0.1", slave.port))
    mb.Timeout = 2000
    for ii in range(1, 17):  # EX-23
        mb.WriteSingleCoil(ii, ii & 1)
    mb.WriteSingleRegister(1, 600)
    bools = [bool(ii & 2) for ii in range(16)]
    coils = Box(None)
    mb.ReadCoils(1, 16, coils)  # EX-22
    assert list(coils.get()) == [bool(ii & 1) for ii in range(1, 17)]
    assert slave.get(1, 1, 16) == [bool(ii & 1) for ii in range(1, 17)]
    mb.WriteMultipleCoils(1, bools)
    mb.ReadCoils(1, 16, coils)
    assert list(coils.get()) == bools
    output = [ii * ii for ii in range(16)]
    mb.WriteMultipleRegisters(1, output)
    regs = Box(None)
    mb.ReadHoldingRegisters(1, 16, regs)
    assert list(regs.get()) == output
    assert slave.get(3, 1, 16) == output
    mb.ReadHoldingRegisters(0, 2, regs)
    assert list(regs.get()) == [0, 0]
    inputs = Box(None)
    mb.ReadDiscreteInputs(1, 16, inputs)
    assert list(inputs.get()) == slave.get(2, 1, 16)
    mb.ReadInputRegisters(1, 2, regs)
    assert list(regs.get()) == slave.get(4, 1, 2)
    mb.Close()


def test_register_range_and_reconnect_after_close(slave: Slave) -> None:
    mb = Modbus(IPEndPoint("127.0.0.1", slave.port))
    mb.WriteSingleRegister(5, -1)
    mb.WriteSingleRegister(6, 65535)
    regs = Box(None)
    mb.ReadHoldingRegisters(5, 2, regs)
    assert list(regs.get()) == [65535, 65535]
    with pytest.raises(GplException) as exc:
        mb.WriteSingleRegister(5, 65536)
    assert exc.value.ErrorCode == -707
    with pytest.raises(GplException) as exc:
        mb.ReadCoils(0, 0, regs)
    assert exc.value.ErrorCode == -707
    mb.Close()
    mb.WriteSingleRegister(7, 42)  # reconnects on demand
    assert slave.get(3, 7, 1) == [42]
    mb.Close()


def test_exception_response_maps_to_1730_with_code(slave: Slave) -> None:
    mb = Modbus(IPEndPoint("127.0.0.1", slave.port))
    mb.Timeout = 2000
    with pytest.raises(GplException) as exc:
        mb.ReadHoldingRegisters(SIZE + 10, 5, Box(None))  # illegal data address
    assert exc.value.ErrorCode == -1730
    assert exc.value.Qualifier == 2
    assert exc.value.Message() == "*Modbus/RIO exception: n*: 2"
    regs = Box(None)
    mb.ReadHoldingRegisters(0, 1, regs)  # the connection is still usable afterwards
    assert list(regs.get()) == [0]
    mb.Close()


def test_read_device_id(slave: Slave) -> None:
    mb = Modbus(IPEndPoint("127.0.0.1", slave.port))
    mb.Timeout = 2000
    assert mb.ReadDeviceID(0) == "GplSim"
    assert mb.ReadDeviceID(1) == "PF-1"
    mb.Close()


def test_timeout_when_slave_never_answers() -> None:
    silent = socket.socket()
    silent.bind(("127.0.0.1", 0))
    silent.listen(1)
    mb = Modbus(IPEndPoint("127.0.0.1", silent.getsockname()[1]))
    mb.Timeout = 100
    start = time.monotonic()
    with pytest.raises(GplException) as exc:
        mb.ReadCoils(1, 1, Box(None))
    assert exc.value.ErrorCode == -1731
    assert 0.09 <= time.monotonic() - start < 2
    mb.Close()
    silent.close()


def test_refused_and_default_port() -> None:
    port = free_port()
    mb = Modbus(IPEndPoint("127.0.0.1", port))
    with pytest.raises(GplException) as exc:
        mb.WriteSingleCoil(1, True)
    assert exc.value.ErrorCode == -1702
    assert Modbus(IPEndPoint("192.168.0.150"))._address == ("192.168.0.150", 502)


def test_reads_return_gpl_arrays(slave: Slave) -> None:
    from gplrt.lang.arrays import GplArray

    mb = Modbus(IPEndPoint("127.0.0.1", slave.port))
    mb.Timeout = 2000
    bools, regs = Box(None), Box(None)
    mb.ReadCoils(1, 16, bools)
    mb.ReadHoldingRegisters(1, 3, regs)
    assert isinstance(bools.get(), GplArray) and bools.get().GetUpperBound(0) == 15
    assert isinstance(regs.get(), GplArray) and regs.get().Length == 3
    ReDim = GplArray.from_list([True, False, True])
    mb.WriteMultipleCoils(20, ReDim)  # a GPL array argument is read element by element
    mb.ReadCoils(20, 3, bools)
    assert list(bools.get()) == [True, False, True]
    mb.Close()


def test_manual_examples_transpiled_write_then_read_back(slave: Slave, tmp_path: Path) -> None:
    """EX-23 and EX-22 as GPL source, through gpl2py, against the pymodbus slave."""
    from gpltest import run_gpl

    src = (Path(__file__).parent / "projects" / "modbus_ex22_ex23.gpl").read_text()
    src = src.replace("SLAVE_PORT As Integer = 5020", f"SLAVE_PORT As Integer = {slave.port}")
    result = run_gpl(tmp_path, src)
    assert result.status == 0, result.log

    coils = [bool(ii & 2) for ii in range(16)]  # EX-23's WriteMultipleCoils overwrote the singles
    assert slave.get(1, 1, 16) == coils
    assert slave.get(3, 1, 16) == [ii * ii for ii in range(16)]
    inputs = slave.get(2, 1, 16)
    iregs = slave.get(4, 1, 2)

    def gpl_bool(value: bool) -> str:
        from gplrt.builtins import CStr

        return str(CStr(value))  # Boolean text is the runtime's decision (spec AMB-22), not ours

    expected = [f"Coil {i + 1}: {gpl_bool(v)}" for i, v in enumerate(coils)]
    expected += [f"Input {i + 1}: {gpl_bool(v)}" for i, v in enumerate(inputs)]
    expected += ["HReg 1: 0", "HReg 2: 1"]
    expected += [f"IReg {i + 1}: {v:X}" for i, v in enumerate(iregs)]
    assert result.output.splitlines() == expected
