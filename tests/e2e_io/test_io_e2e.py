"""Must-show (iii) and (iv): a transpiled TCP command server on loopback, files and XML through GPL.

Every client socket operation has a timeout and every loop is bounded, so a broken server makes
these tests fail, never hang.
"""

from __future__ import annotations

import socket
import struct
import threading
import xml.dom.minidom
from collections.abc import Iterator
from pathlib import Path

import pytest

from gpltest import LineClient, Transpiled, copy_project, free_port, transpile
from gplrt.sim import Simulation

#: The GPL projects of these tests (here, not imported from conftest: ``from conftest import``
#: found another folder's conftest when several folders' tests ran in one session).
PROJECTS = Path(__file__).resolve().parent / "projects"

TIMEOUT = 10.0  # seconds, for every client socket operation


@pytest.fixture(scope="module")
def server_port() -> int:
    return free_port()


@pytest.fixture(scope="module")
def seqserver(tmp_path_factory: pytest.TempPathFactory, server_port: int) -> Iterator[tuple[Transpiled, Simulation]]:
    """The server, transpiled with its port changed to a free one, running on the real clock."""
    src = copy_project(PROJECTS / "seqserver", tmp_path_factory.mktemp("src") / "seqserver",
                       {"SERVER_PORT As Integer = 10500": f"SERVER_PORT As Integer = {server_port}"})
    sample = transpile(src, tmp_path_factory.mktemp("seqserver"))
    sim = Simulation(clock="real", capture=True)
    runner = threading.Thread(target=sample.package.main, args=(sim,), daemon=True)
    runner.start()
    for _ in range(200):  # wait until it listens
        if "listening" in sim.console.output:
            break
        runner.join(0.05)
    yield sample, sim
    if runner.is_alive():  # stop it (tests normally do, with "shutdown")
        try:
            c = LineClient(server_port, timeout=TIMEOUT, newline="\n")
            c.ask("0 shutdown")
            c.close()
        except OSError:
            pass
        runner.join(TIMEOUT)


def test_a_thousand_commands_get_one_reply_each_in_order(seqserver: tuple[Transpiled, Simulation],
                                                         server_port: int) -> None:
    clients = [LineClient(server_port, timeout=TIMEOUT, newline="\n") for _ in range(4)]
    try:
        sent: list[tuple[int, int, str]] = []
        for seq in range(1, 1001):
            c = seq % 4
            if seq % 3 == 0:
                sent.append((c, seq, f"{seq} add {seq} 0.5"))
            else:
                sent.append((c, seq, f"{seq} echo hello {seq}"))
        # pipeline: each client sends its requests in bursts of 10 before reading the replies
        by_client: dict[int, list[tuple[int, str]]] = {c: [] for c in range(4)}
        for c, seq, text in sent:
            by_client[c].append((seq, text))
        replies: dict[int, str] = {}
        for burst in range(0, 250, 10):
            for c in range(4):
                chunk = by_client[c][burst:burst + 10]
                clients[c].send("".join(text + ("\r\n" if seq % 2 else "\n") for seq, text in chunk))
            for c in range(4):
                for seq, _ in by_client[c][burst:burst + 10]:
                    reply = clients[c].line()
                    got_seq = int(reply.split(" ", 1)[0])
                    assert got_seq == seq, f"client {c}: expected reply to {seq}, got {reply!r}"
                    assert got_seq not in replies, f"duplicate reply {reply!r}"
                    replies[got_seq] = reply
        assert sorted(replies) == list(range(1, 1001))
        for seq, reply in replies.items():
            expected = f"{seq} {seq + 0.5:g}" if seq % 3 == 0 else f"{seq} hello {seq}"
            assert reply == expected
        for c in clients:  # nothing extra was sent
            c.sock.settimeout(0.2)
            with pytest.raises(TimeoutError):
                c.sock.recv(1)
    finally:
        for c in clients:
            c.close()


def test_keeps_serving_after_a_hundred_abrupt_disconnects(seqserver: tuple[Transpiled, Simulation],
                                                          server_port: int) -> None:
    for n in range(100):
        s = socket.create_connection(("127.0.0.1", server_port), timeout=TIMEOUT)
        s.settimeout(TIMEOUT)
        if n % 4 == 1:
            s.sendall(b"7 echo half a li")  # half a line, then gone
        elif n % 4 == 2:
            s.sendall(b"8 echo whole\n")  # a whole line, gone before the reply is read
        if n % 2:  # reset instead of an orderly close
            s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        s.close()
        # A few ms between clients: the listen backlog is 8 (TcpListener.BACKLOG), and a burst
        # beyond it makes the kernel drop SYNs that are retried only a second later.
        threading.Event().wait(0.005)
        if n % 10 == 9:  # meanwhile, a well-behaved client is still served
            probe = LineClient(server_port, timeout=TIMEOUT, newline="\n")
            try:
                assert probe.ask(f"{n} echo probe") == f"{n} probe"
            finally:
                probe.close()
    c = LineClient(server_port, timeout=TIMEOUT, newline="\n")
    try:
        assert c.ask("5001 echo still here") == "5001 still here"
        # every dropped connection ended its thread (more than 32 would have hit the thread limit)
        served = 0
        for _ in range(100):
            served = int(c.ask("5002 served").split()[1])
            if served >= 110:
                break
            threading.Event().wait(0.05)
        assert served >= 110  # 100 dropped + 10 probes, each counted once its thread ended
        assert c.ask("5003 frobnicate") == "5003 error frobnicate"
    finally:
        c.close()


def test_shutdown_stops_the_server(seqserver: tuple[Transpiled, Simulation], server_port: int) -> None:
    sample, sim = seqserver
    c = LineClient(server_port, timeout=TIMEOUT, newline="\n")
    assert c.ask("9999 shutdown") == "9999 bye"
    c.close()
    for _ in range(200):
        if "stopped after" in sim.console.output:
            break
        threading.Event().wait(0.05)
    assert sim.console.output.splitlines()[0] == "listening"
    assert sim.console.output.splitlines()[-1].startswith("stopped after ")
    assert sim.controller.error_log == []


# -- (iv) files and XML ------------------------------------------------------------------------------

CONFIG = """<?xml version="1.0"?>
<procedureControl cellId="TestCell">
  <command>start</command>
</procedureControl>
"""


@pytest.fixture(scope="module")
def fileio(tmp_path_factory: pytest.TempPathFactory) -> Transpiled:
    return transpile(PROJECTS / "fileio", tmp_path_factory.mktemp("fileio"))


def test_files_refusals_and_xml_through_gpl(fileio: Transpiled, tmp_path: Path) -> None:
    folder = tmp_path / "flash" / "e2e"
    folder.mkdir(parents=True)
    (folder / "config.xml").write_text(CONFIG)
    sim = Simulation(capture=True, flash_root=tmp_path)
    assert fileio.package.main(sim) == 0

    data = (folder / "data.txt").read_bytes()
    assert data == (b"line 1, value 1.5\r\nline 2, value 3\r\nline 3, value 4.5\r\n\r\n"
                    b"caf\xe9\r\nappended\r\n")
    assert (folder / "copy.txt").read_bytes() == data
    assert not (tmp_path / "escape.txt").exists() and not (tmp_path.parent / "escape.txt").exists()
    assert sim.console.output.splitlines() == [
        f"length {len(data)}",
        "1: [line 1, value 1.5]",
        "2: [line 2, value 3]",
        "3: [line 3, value 4.5]",
        "4: []",
        "5: [caf\xe9]",
        "6: [appended]",
        "/etc/passwd refused -301",
        "/flash/.. refused -516",
        "missing file -508",
        "cell TestCell",
        "command start",
        "saved",
        "broken xml -799",
    ]
    out = xml.dom.minidom.parse(str(folder / "config_out.xml")).documentElement
    assert out.tagName == "procedureControl" and out.getAttribute("cellId") == "TestCell-2"
    assert out.getElementsByTagName("command")[0].firstChild.data == "stop"
    run = out.getElementsByTagName("run")[0]
    assert run.getAttribute("count") == "3"
    assert run.getElementsByTagName("result")[0].firstChild.data == "ok & done"
