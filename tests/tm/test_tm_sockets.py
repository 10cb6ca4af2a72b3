"""TMscript's Socket class and socket_* functions (manual §9, L13396-L14356) against the manual's
own examples, with a TCP server of the test's on loopback as the remote device."""

from __future__ import annotations

import socket

import pytest
from tmpacket import Peer, run_packet, run_project

from gplrt.tm import context
from gplrt.tm.values import format_value

HELLO = b"Hello, World\r\n"


@pytest.fixture
def robot():  # type: ignore[no-untyped-def]
    return context.use_robot("TM5-900")




def hexes(data: bytes) -> str:
    return "{" + ",".join(str(b) for b in data) + "}"


def test_open_read_with_a_read_time_and_close(robot) -> None:  # type: ignore[no-untyped-def]
    peer = Peer(HELLO)
    v = run_packet(f'Socket ntd_a = "127.0.0.1", {peer.port}\nbool o = socket_open("ntd_a")\n'
            'byte[] a = socket_read("ntd_a", 14, 5000)\nbyte[] b = socket_read("ntd_a")\nbool c = socket_close("ntd_a")')
    assert v.o is True and bytes(v.a) == HELLO and v.b == [] and v.c is True


def test_read_from_the_received_buffer_l13505_l13856(robot) -> None:  # type: ignore[no-untyped-def]
    peer = Peer()
    run_packet(f'Socket ntd_a = "127.0.0.1", {peer.port}\nsocket_open("ntd_a")')
    buffer = robot._socket_devices["ntd_a"].buffer

    def read(call: str) -> tuple[str, bytes]:
        value = run_packet(f"byte[] x = {call}").x
        return format_value(value), bytes(buffer)

    buffer[:] = HELLO
    assert read('socket_read("ntd_a", 6)') == (hexes(b"Hello,"), b" World\r\n")
    assert read('socket_read("ntd_a", 100)') == ("{}", b" World\r\n")
    assert read('socket_read("ntd_a", 0)') == (hexes(b" World\r\n"), b"")
    buffer[:] = b"Hello,\r\nWorld\r\n"
    assert read('socket_read("ntd_a", "", "")') == (hexes(b"Hello,\r\nWorld\r\n"), b"")
    buffer[:] = b"Hello,\r\nWorld\r\n"
    assert read('socket_read("ntd_a", "He", newline)') == (hexes(b"Hello,\r\n"), b"World\r\n")
    assert read('socket_read("ntd_a", "", newline, 1)') == (hexes(b"World"), b"")
    buffer[:] = b"Hello,\r\nWorld\r\n"
    assert read('socket_read("ntd_a", "lo", newline)') == (hexes(b"lo,\r\n"), b"World\r\n")
    buffer[:] = b"$Hello\r\n#Hi\r\n$TM\r\n#Robot\r\n"
    assert read('socket_read("ntd_a", "#", newline, 2)') == ("{}", b"$Hello\r\n#Hi\r\n$TM\r\n#Robot\r\n")
    assert read('socket_read("ntd_a", "$", newline, 2)') == (hexes(b"$Hello\r\n"), b"#Hi\r\n$TM\r\n#Robot\r\n")
    assert read('socket_read("ntd_a", "#", newline, 2)') == (hexes(b"#Hi\r\n"), b"$TM\r\n#Robot\r\n")
    assert read('socket_read("ntd_a", "$", newline, 3)') == (hexes(b"TM"), b"#Robot\r\n")
    assert read('socket_read("ntd_a", "#", newline, 3)') == (hexes(b"Robot"), b"")
    buffer[:] = "達明\r\n".encode()
    assert run_packet('string s = socket_read_string("ntd_a", "", newline, 1)').s == "達明"


def test_send_l14149(robot) -> None:  # type: ignore[no-untyped-def]
    peer = Peer()
    sends = ['100', '1000', '(float)1.234', '(double)123.456', '"Hello, World"+newline', "var_ii", "var_ss",
             '1000, 1, 2', '"Hello, World"+newline, 0, 7', "var_bb", "var_bb, 1, 1", "var_bb, -1, 1",
             '"達明機器人", 2']
    script = (f'Socket ntd_a = "127.0.0.1", {peer.port}\nint[] var_ii = {{100, 200, 300, 400}}\n'
              'string[] var_ss = {"TM", "", "Robot"}\nbyte[] var_bb = {100, 200}\n'
              + "\n".join(f'int r{i} = socket_send("ntd_a", {s})' for i, s in enumerate(sends))
              + '\nint l = socket_sendline("ntd_a", "TM")\nint e = socket_send("ntd_a", "")'
              + '\nint missing = socket_send("nope", 1)')
    v = run_packet(script)  # (socket_send connects an unopened device itself, L13424)
    want = (bytes([0x64]) + bytes([0xE8, 3, 0, 0]) + bytes([0xB6, 0xF3, 0x9D, 0x3F]) + bytes([0x77, 0xBE, 0x9F, 0x1A, 0x2F, 0xDD, 0x5E, 0x40])
            + HELLO + bytes([100, 0, 0, 0, 200, 0, 0, 0, 0x2C, 1, 0, 0, 0x90, 1, 0, 0]) + b"TMRobot"
            + bytes([0xE8, 3, 0, 0]) + b"Hello, " + bytes([100, 200]) + bytes([200]) + bytes([100])
            + "機器人".encode() + b"TM\r\n")
    assert peer.wait_for(len(want)) == want
    assert [getattr(v, f"r{i}") for i in range(len(sends))] == [1] * len(sends)
    assert (v.l, v.e, v.missing) == (1, 0, -3)


def test_a_device_that_cannot_connect(robot) -> None:  # type: ignore[no-untyped-def]
    closed = socket.create_server(("127.0.0.1", 0))
    port = closed.getsockname()[1]
    closed.close()
    v = run_packet(f'Socket ntd_b = "127.0.0.1", {port}, 500\nbool o = socket_open("ntd_b")\nint s = socket_send("ntd_b", 1)')
    assert (v.o, v.s) == (False, -2)


def test_suffix_only_reads_and_string_counts_of_characters_l13994_l14060(robot) -> None:  # type: ignore[no-untyped-def]
    """``socket_read(dev, suffix [, option [, ms]])`` (syntax 7-9) and a ``_string`` read's count
    of characters, not bytes (the manual's ``機器人`` examples)."""
    peer = Peer()
    run_packet(f'Socket ntd_a = "127.0.0.1", {peer.port}\nsocket_open("ntd_a")')
    buffer = robot._socket_devices["ntd_a"].buffer
    buffer[:] = b"Hello,\r\nWorld"
    v = run_packet('string a = socket_read_string("ntd_a", newline)\nstring b = socket_read_string("ntd_a", newline, 0)')
    assert (v.a, v.b, bytes(buffer)) == ("Hello,\r\n", "", b"World")
    buffer[:] = b"World\r\n123\r\n"
    v = run_packet('string a = socket_read_string("ntd_a", newline, 1)\nbyte[] b = socket_read("ntd_a", newline, 2)')
    assert (v.a, bytes(v.b), bytes(buffer)) == ("World", b"123\r\n", b"")
    buffer[:] = "TM達明機器人".encode()
    v = run_packet('string a = socket_read_string("ntd_a", 4)\nstring b = socket_read_string("ntd_a", 5)')
    assert (v.a, v.b, bytes(buffer)) == ("TM達明", "", "機器人".encode())


def test_a_socket_declared_in_a_block_is_closed_when_the_block_is_left_e22(robot, tmp_path) -> None:  # type: ignore[no-untyped-def]
    """L1320, L1335-L1345: leaving the block (its end, or an error in it) closes the device, so
    the peer sees the close before the next statement runs; the name is forgotten."""
    peers = [Peer(), Peer()]
    src = tmp_path / "scoped.tms"
    src.write_text(
        "main\n{\n"
        "    if (true)\n    {\n"
        f'        Socket bbb = "127.0.0.1", {peers[0].port}\n        socket_open("bbb")\n'
        '        socket_send("bbb", "hi")\n    }\n'
        '    Display("after the block")\n'
        '    Display(socket_send("bbb", "again"))\n'
        "    Fail()\n}\n"
        "void Fail()\n{\n"
        f'    Socket ccc = "127.0.0.1", {peers[1].port}\n    socket_open("ccc")\n'
        "    int zero = 0\n    int x = 1 / zero\n}\n"
        'errorstop\n{\n    Display("errorstop")\n}\n')
    seen: list[tuple[str, bool]] = []

    def display(line: str) -> None:  # (runs in the script: what the peers saw at that moment)
        if line in ("after the block", "errorstop"):
            peer = peers[0] if line == "after the block" else peers[1]
            seen.append((line, peer.closed.wait(30)))  # (30 s only ends a hang)
        else:
            seen.append((line, False))

    assert run_project(src, tmp_path / "out", robot=None, display=display)[0] == 1
    assert seen == [("after the block", True), ("-3", False), ("errorstop", True)]
    assert peers[0].wait_for(2) == b"hi"
