"""TMscript's SerialPort class and com_* functions (manual §8, L12367-L13395) on the simulated
robot's virtual serial ports: the test attaches the other end (pyserial's ``loop://``, or
``socket://`` to a TCP peer of the test's) and checks what the script sends and reads."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from tmpacket import Peer, run_packet, run_project

from gpl2py.tmscript.pipeline import translate_packet
from gplrt.tm import context, devices
from gplrt.tm.serial import attach_serial
from gplrt.tm.values import TMError, format_value

HELLO = b"Hello, World\r\n"


@pytest.fixture
def robot() -> Iterator[object]:
    yield context.use_robot("TM5-900")
    for port in ("COM2", "COM3"):
        attach_serial(port, None)


def hexes(data: bytes) -> str:
    return "{" + ",".join(str(b) for b in data) + "}"


def test_declarations_with_2_5_6_and_9_values_e69(robot) -> None:  # type: ignore[no-untyped-def]
    v = run_packet('SerialPort spd_c1 = "COM2",115200\nSerialPort spd_c2 = "COM2",115200,"none",8,1\n'
                   'SerialPort spd_c3 = "COM2",115200,"none",8,1,10000\n'
                   'SerialPort spd_c4 = "COM2",9600,"even",7,2,500,true,false,true')
    settings = v.spd_c4.settings
    assert (settings.baud, settings.parity, settings.data_bits, settings.stop_bits, settings.timeout) == \
        (9600, "even", 7, 2.0, 500)
    assert (settings.dtr_dsr, settings.rts_cts, settings.xon_xoff) == (True, False, True)
    assert v.spd_c3.settings.timeout == 10000 and v.spd_c1.settings.parity == "none"


def test_a_declaration_with_another_count_is_a_compile_error() -> None:
    p = translate_packet('SerialPort spd = "COM2",115200,"none"')
    assert [d.header() for d in p.errors] == ["packet:1:1: error GPL5303: SerialPort() takes 2, 5, 6 or 9 arguments, not 3"]


@pytest.mark.parametrize("values, wrong", [('"COM2",115200,"weird",8,1', "the parity 'weird'"),
                                           ('"COM2",115200,"none",9,1', "the data bits 9"),
                                           ('"COM2",115200,"none",8,3', "the stop bits 3"),
                                           ('"COM2",115200,"none",8,1,20000', "the timeout 20000 ms")])
def test_a_bad_setting_is_a_script_error(robot, values: str, wrong: str) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(TMError, match=f"SerialPort spd: {wrong}"):
        run_packet(f"SerialPort spd = {values}")


def test_a_port_nobody_attached_cannot_be_opened(robot) -> None:  # type: ignore[no-untyped-def]
    """A script's COM port never opens a host device by itself (docs/security.md): com_open of
    a port the user attached nothing to is the project's error (L12447), naming the port."""
    with pytest.raises(TMError, match=r'com_open\("spd"\): the serial port COM3 cannot be opened: nothing is attached'):
        run_packet('SerialPort spd = "COM3",115200\ncom_open("spd")')
    assert run_packet('SerialPort spd2 = "COM3",115200\nbool f = com_write("spd2", 1)').f is False


def test_write_l13270_as_the_peer_receives_it(robot) -> None:  # type: ignore[no-untyped-def]
    peer = Peer()
    attach_serial("COM2", peer.url)
    writes = ['1000', '(float)1.234', '(double)123.456', '"Hello, World"+newline', '1000, 1, 2', "bb",
              "bb, 1, 1", "bb, -1, 1", '"達明機器人", 2', "ss", "Byte_Concat(GetBytes(ss), GetBytes(newline))",
              "ss, 2, 100"]
    script = ('SerialPort spd = "COM2",115200\nbool o = com_open("spd")\nbyte[] bb = {100, 200}\n'
              'string[] ss = {"TM", "", "達明機器人"}\n'
              + "\n".join(f'bool f{i} = com_write("spd", {w})' for i, w in enumerate(writes))
              + '\nbool l = com_writeline("spd", "Hello, World")\nbool e = com_write("spd", "")')
    v = run_packet(script)
    tm_robot = "達明機器人".encode()
    want = (bytes([0xE8, 3, 0, 0]) + bytes([0xB6, 0xF3, 0x9D, 0x3F]) + bytes([0x77, 0xBE, 0x9F, 0x1A, 0x2F, 0xDD, 0x5E, 0x40])
            + HELLO + bytes([0xE8, 3, 0, 0]) + bytes([100, 200]) + bytes([200]) + bytes([100]) + "機器人".encode()
            + b"TM" + tm_robot + b"TM" + tm_robot + b"\r\n" + tm_robot + HELLO)
    assert peer.wait_for(len(want)) == want
    assert v.o is True and [getattr(v, f"f{i}") for i in range(len(writes))] == [True] * len(writes)
    assert (v.l, v.e) == (True, False)  # (an empty value writes nothing: false, L13220)


def test_reads_wait_for_what_the_line_brings(robot) -> None:  # type: ignore[no-untyped-def]
    """The reader fills the Received Buffer in the background after com_open (L12494); a read
    with a read time waits for it, in controller time."""
    peer = Peer(HELLO + b"$TM\r\n", asked=True)
    attach_serial("COM2", peer.url)
    v = run_packet('SerialPort spd = "COM2",115200\ncom_open("spd")\ncom_write("spd", "?")\n'
                   'byte[] a = com_read("spd", 14, 5000)\n'
                   'string b = com_read_string("spd", newline, 1, 5000)\nbyte[] c = com_read("spd")\n'
                   'bool d = com_close("spd")')
    assert bytes(v.a) == HELLO and v.b == "$TM" and v.c == [] and v.d is True


def test_loopback_reads_back_what_was_written(robot) -> None:  # type: ignore[no-untyped-def]
    attach_serial("COM2", "loop://")
    v = run_packet('SerialPort spd = "COM2",115200\ncom_writeline("spd", "ping")\n'
                   'string s = com_read_string("spd", newline, 0, 5000)')
    assert v.s == "ping\r\n"  # (com_writeline opened the device first: L12433)


def test_reads_from_the_received_buffer_l12500_l13192(robot) -> None:  # type: ignore[no-untyped-def]
    attach_serial("COM2", "loop://")
    run_packet('SerialPort spd = "COM2",115200\ncom_open("spd")')
    buffer = robot._serial_devices["spd"].buffer

    def read(call: str) -> tuple[str, bytes]:
        kind = "string" if "_string" in call else "byte[]"
        value = run_packet(f"{kind} x = {call}").x
        return (value if kind == "string" else format_value(value)), bytes(buffer)

    buffer[:] = HELLO
    assert read('com_read("spd", 6)') == (hexes(b"Hello,"), b" World\r\n")
    assert read('com_read("spd", 100)') == ("{}", b" World\r\n")
    assert read('com_read("spd", 0)') == (hexes(b" World\r\n"), b"")
    buffer[:] = b"Hello,\r\nWorld\r\n"
    assert read('com_read("spd", "He", newline)') == (hexes(b"Hello,\r\n"), b"World\r\n")
    assert read('com_read("spd", "", newline, 1)') == (hexes(b"World"), b"")
    buffer[:] = b"Hello,\r\nWorld\r\n"
    assert read('com_read("spd", "lo", newline)') == (hexes(b"lo,\r\n"), b"World\r\n")
    buffer[:] = b"$Hello\r\n#Hi\r\n$TM\r\n#Robot\r\n"
    assert read('com_read("spd", "#", newline, 2)') == ("{}", b"$Hello\r\n#Hi\r\n$TM\r\n#Robot\r\n")
    assert read('com_read("spd", "$", newline, 2)') == (hexes(b"$Hello\r\n"), b"#Hi\r\n$TM\r\n#Robot\r\n")
    assert read('com_read("spd", "#", newline, 3)') == (hexes(b"Hi"), b"$TM\r\n#Robot\r\n")
    # the suffix-only forms (syntax 7-9, L12751)
    buffer[:] = b"Hello,\r\nWorld\r\n"
    assert read('com_read("spd", newline)') == (hexes(b"Hello,\r\n"), b"World\r\n")
    assert read('com_read("spd", newline, 1)') == (hexes(b"World"), b"")
    buffer[:] = b"Hello,\r\nWorld"
    assert read('com_read_string("spd", newline)') == ("Hello,\r\n", b"World")
    assert read('com_read_string("spd", newline, 0)') == ("", b"World")
    buffer[:] = b"World\r\n123\r\n"
    assert read('com_read_string("spd", newline, 1)') == ("World", b"123\r\n")
    assert read('com_read_string("spd", newline, 2)') == ("123\r\n", b"")
    # a string read's count is of characters (L13067)
    buffer[:] = "TM達明機器人".encode()
    assert read('com_read_string("spd", 4)') == ("TM達明", "機器人".encode())
    assert read('com_read_string("spd", 5)') == ("", "機器人".encode())


def test_the_buffer_drops_the_oldest_bytes_when_full(robot, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.setattr(devices, "BUFFER_SIZE", 8)
    peer = Peer(b"0123456789ABCDEF", asked=True)
    attach_serial("COM2", peer.url)
    v = run_packet('SerialPort spd = "COM2",115200\ncom_writeline("spd", "?")\nbyte[] a = com_read("spd", "F", 0, 5000)\n'
                   'string s = com_read_string("spd")')
    assert bytes(v.a) == b"89ABCDEF" and v.s == ""


def test_the_end_of_the_project_closes_the_port(robot, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    """When the project stops the port closes and its buffer is cleared (L12494-L12498)."""
    peer = Peer()
    attach_serial("COM2", peer.url)
    src = tmp_path / "serial_project.tms"
    src.write_text('define\n{\n    SerialPort spd = "COM2",115200\n}\nmain\n{\n    com_open("spd")\n'
                   '    com_writeline("spd", "bye")\n}\n')
    lines: list[str] = []
    assert run_project(src, tmp_path / "out", robot=None, display=lines.append)[0] == 0
    assert peer.closed.wait(30) and peer.wait_for(5) == b"bye\r\n"
    assert robot._serial_devices == {}


def test_gpl2py_run_attaches_ports_with_serial(tmp_path: Path) -> None:
    """``gpl2py run script.tms --serial COM2=loop://``; without it the port cannot be opened and
    the run ends with the script's error on its line, not a traceback."""
    import subprocess
    import sys

    src = tmp_path / "echo.tms"
    src.write_text('main\n{\n    SerialPort spd = "COM2", 9600\n    com_open("spd")\n    com_writeline("spd", "echo")\n'
                   '    Display(com_read_string("spd", newline, 1, 5000))\n}\n')
    command = [sys.executable, "-m", "gpl2py", "run", str(src), "--robot", "TM5-900"]
    r = subprocess.run(command + ["--serial", "COM2=loop://"], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert (r.returncode, r.stdout) == (0, "echo\n"), r.stderr
    r = subprocess.run(command, capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert 'echo.tms:4: error: com_open("spd"): the serial port COM2 cannot be opened' in r.stderr
