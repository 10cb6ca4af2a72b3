"""V+ LUN I/O: a disk file written and read back with IOSTAT, and a TCP server LUN serving a plain
Python socket client (simple_message framing as ros.v2 builds it) on the virtual clock."""

from __future__ import annotations

import socket
import struct
import time
from pathlib import Path

from gpltest import free_port
from gplrt import vplus as vp
from gplrt.sim import Simulation


def test_disk_io_example_of_the_guide(tmp_path: Path) -> None:
    """Appendix B.2 (L7755-7798) as generated code runs it."""
    sim = Simulation(capture=True, flash_root=tmp_path)

    def main() -> None:
        dlun, txt = vp.Cell("dlun"), vp.G["$txt"]
        vp.attach(dlun, 4, "DISK")
        assert vp.iostat(dlun) == 1
        vp.fopenw(dlun, "data.tst")
        for i in range(1, 4):
            vp.write(dlun, vp.add("Line ", vp.s_encode(i)))
        vp.fclose(dlun)
        vp.fopenw(dlun, "data.tst")
        vp.type_("again: ", vp.s_error(vp.iostat(dlun)))
        vp.fopenr(dlun, "data.tst")
        vp.read(dlun, txt)
        while vp.iostat(dlun) > 0:
            vp.type_(txt.v)
            vp.read(dlun, txt)
        vp.type_(vp.iostat(dlun), " ", vp.s_error(vp.iostat(dlun)))
        vp.fclose(dlun)
        vp.detach(dlun)
        vp.type_(vp.iostat(dlun))

    with sim:
        assert sim.run_main(main) == []
    assert sim.console.output.splitlines() == [
        "again: *File already exists*", "Line 1", "Line 2", "Line 3", "-504 *Unexpected end of file*", "-516"]
    sim.close()


def _recv_exactly(conn: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        assert chunk, "server closed"
        data += chunk
    return data


def test_tcp_server_lun_serves_a_socket_client() -> None:
    port = free_port()
    sim = Simulation(capture=True)

    @vp.program("srv.test")
    def server() -> None:
        lun, c = vp.Cell("lun"), vp.Cell("c")
        tmp = vp.Cell("$tmp")
        vp.attach(lun, 4, "TCP")
        vp.fopen(lun, vp.add("/LOCAL_PORT", vp.add(vp.s_encode(port), " /CLIENTS 1 /BUFFER_SIZE 1024")), 16)
        vp.type_("fopen ", vp.iostat(lun))
        notice = []
        for _ in range(4):  # ros.v2: "Read 4 bytes from connection"
            notice.append(vp.getc(lun, 2))
        vp.type_("connected ", vp.iostat(lun), " notice ", vp.s_encode(*[int(b) for b in notice]))
        while True:
            tmp.v = ""
            for _ in range(4):
                c.v = vp.getc(lun, 2)
                if vp.truth(vp.lt(c.v, 0)):
                    vp.type_("closed ", c.v, " ", vp.iostat(lun))
                    return
                tmp.v = vp.add(tmp.v, vp.s_chr(c.v))
            length = vp.lngb(tmp.v[::-1])  # little-endian on the wire, as ros.v2 reverses
            body = ""
            for _ in range(int(length)):
                body += vp.s_chr(vp.getc(lun, 2))
            reply = vp.s_lngb(len(body))[::-1] + body.upper()
            vp.write(lun, reply, vp.fmt("/S"))

    with sim:
        sim.start(lambda: server(), name="task 5")
        deadline = time.monotonic() + 10
        while port not in sim.network.listening_ports() and time.monotonic() < deadline:
            time.sleep(0.01)
        with socket.create_connection(("127.0.0.1", port), timeout=10) as conn:
            for word in (b"hello", b"simple message"):
                conn.sendall(struct.pack("<i", len(word)) + word)
                (n,) = struct.unpack("<i", _recv_exactly(conn, 4))
                assert _recv_exactly(conn, n) == word.upper()
        while "closed" not in sim.console.output and time.monotonic() < deadline:
            time.sleep(0.01)
        sim.stop(grace=10)
    lines = sim.console.output.splitlines()
    assert lines == ["fopen 1", "connected 100 notice 0001", "closed -504 101"]
    sim.close()


def test_getc_no_wait_reports_no_data() -> None:
    port = free_port()
    sim = Simulation(capture=True)

    def main() -> None:
        lun = vp.Cell("lun")
        vp.attach(lun, 4, "TCP")
        vp.fopen(lun, f"/LOCAL_PORT {port}", 16)
        vp.type_(vp.getc(lun, 1), " ", vp.iostat(lun), " ", vp.s_error(vp.iostat(lun)))
        vp.detach(lun)

    with sim:
        assert sim.run_main(main) == []
    assert sim.console.output == "-526 -526 *No data received*\n"
    sim.close()


def test_read_numbers_from_a_text_file(tmp_path: Path) -> None:
    """robot-sandbox desen.v2: ATTACH (lun, 4) "NFS"; FOPENR (lun) "desen.txt"; READ (lun) x, y."""
    (tmp_path / "flash").mkdir()
    (tmp_path / "flash" / "desen.txt").write_bytes(b"2\r\n10.5, -3\r\n4 5\r\n")
    sim = Simulation(capture=True, flash_root=tmp_path)

    def main() -> None:
        lun, n, x, y = vp.Cell("lun"), vp.Cell("n"), vp.Cell("x"), vp.Cell("y")
        vp.attach(lun, 4, "NFS")
        vp.fopenr(lun, "desen.txt")
        vp.read(lun, n)
        for _ in range(int(n.v)):
            vp.read(lun, x, y)
            vp.type_(x.v, " ", y.v)
        vp.fclose(lun)

    with sim:
        assert sim.run_main(main) == []
    assert sim.console.output == "10.5 -3\n4 5\n", sim.console.log_text
    sim.close()


def test_tcp_client_lun_writes_and_reads_records() -> None:
    """FOPEN (lun) "/REMOTE_IP a /REMOTE_PORT p" connects out; WRITE sends a record with CR/LF,
    READ returns the next one without it; the peer's close is -504 on the next READ."""
    import threading

    listener = socket.create_server(("127.0.0.1", 0))
    port = listener.getsockname()[1]
    received: list[bytes] = []

    def peer() -> None:
        conn, _ = listener.accept()
        with conn:
            data = b""
            while not data.endswith(b"\r\n"):
                data += conn.recv(100)
            received.append(data)
            conn.sendall(b"pong 7\r\n")

    t = threading.Thread(target=peer, daemon=True)
    t.start()
    sim = Simulation(capture=True)

    def main() -> None:
        lun, reply = vp.Cell("lun"), vp.Cell("$reply")
        vp.attach(lun, 4, "TCP")
        vp.fopen(lun, vp.add("/REMOTE_IP 127.0.0.1 /REMOTE_PORT ", vp.s_encode(port)))
        vp.type_("open ", vp.iostat(lun))
        vp.write(lun, "ping ", 7)
        vp.read(lun, reply)
        vp.type_(reply.v, " ", vp.iostat(lun), " ", vp.iostat(lun, 2))
        vp.read(lun, reply)
        vp.type_(vp.iostat(lun))

    with sim:
        assert sim.run_main(main) == []
    t.join(10)
    listener.close()
    assert received == [b"ping 7\r\n"], sim.console.output + sim.console.log_text
    assert sim.console.output.splitlines() == ["open 1", "pong 7 1 6", "-504"]
    sim.close()
