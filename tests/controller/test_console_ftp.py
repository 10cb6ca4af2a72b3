"""Deploying to the simulated controller as a lab does: FTP into /flash/projects, then the console.

The deployment test runs ``gpl2py run --console 0 --ftp 0`` as a user would, uploads a small GPL
server project with ftplib, loads and starts it over a plain socket to the console, talks to the
port it serves, shows the threads, stops and unloads it.  The other tests try each way out of the
flash root over FTP (docs/security.md, "Console and FTP") and the console's own limits.
"""

from __future__ import annotations

import ftplib
import io
import os
import re
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from gpltest import FOREGROUND, free_port, write_project

from gplrt.controller import telnet
from gplrt.io import ftp as ftp_module
from gplrt.io.ftp import FtpService
from gplrt.controller.telnet import ConsoleServer
from gplrt.sim import Simulation

ECHO_SERVER = """\
Module Server
    Public Sub Main()
        Dim ep As New IPEndPoint("", {port})
        Dim tl As New TcpListener(ep)
        Dim ts As Socket
        Dim recv As String
        tl.Start()
        While True
            ts = tl.AcceptSocket()
            ts.Receive(recv, 1000)
            ts.Send("echo " & Thread.CurrentThread.Project & ": " & recv)
            ts.Close()
        End While
    End Sub
End Module
"""
ECHO_GPR = 'ProjectBegin\r\nProjectName="Echo"\r\nProjectStart="Server.Main"\r\nProjectSource="Server.gpl"\r\nProjectEnd\r\n'
BOOT = """\
Module Main
    Public Sub Main()
        Console.WriteLine("boot project ran")
        Console.WriteLine(Controller.Command("Show Project"))
    End Sub
End Module
"""


class Console:
    """A plain-socket client of the controller's console: one command, its reply lines."""

    def __init__(self, port: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=60)
        self.banner = self._reply()

    def _reply(self) -> list[str]:
        data = b""
        while not data.endswith(telnet.PROMPT.encode()):
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError(f"console closed the connection after {data!r}")
            data += chunk
        return data.decode("latin-1")[: -len(telnet.PROMPT)].splitlines()

    def __call__(self, command: str) -> list[str]:
        self.sock.sendall(command.encode() + b"\r\n")
        return self._reply()

    def close(self) -> None:
        self.sock.close()


def _ask(port: int, text: bytes) -> bytes:
    with socket.create_connection(("127.0.0.1", port), timeout=30) as s:
        s.sendall(text)
        data = b""
        while chunk := s.recv(4096):
            data += chunk
        return data


def _wait_for(predicate: object, what: str, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while not predicate():  # type: ignore[operator]
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.05)


def test_deploy_by_ftp_then_load_start_show_stop_unload_from_the_console(tmp_path: Path) -> None:
    boot = write_project(tmp_path / "boot", {"Main.gpl": BOOT})
    echo_port = free_port()
    env = {**os.environ, "GPL2PY_CACHE_DIR": str(tmp_path / "cache")}
    proc = subprocess.Popen([sys.executable, "-c", FOREGROUND, "run", boot, "--console", "0", "--ftp", "0"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        notes: dict[str, int] = {}
        assert proc.stderr is not None
        while len(notes) < 2:
            line = proc.stderr.readline()
            assert line, f"gpl2py run ended: {proc.wait()}"
            print(line, end="")
            found = re.match(r"note: (console|FTP)\b.* listening on 127\.0\.0\.1:(\d+)", line)
            if found:
                notes[found.group(1)] = int(found.group(2))

        # 1. Upload the project with the standard library's FTP client, as a lab does.
        with ftplib.FTP() as client:
            client.connect("127.0.0.1", notes["FTP"], timeout=30)
            print(client.login())
            assert client.nlst("/") == ["NVRAM", "ROMDISK", "flash"]
            client.mkd("/flash/projects/Echo")
            client.storbinary("STOR /flash/projects/Echo/Project.gpr", io.BytesIO(ECHO_GPR.encode()))
            client.storbinary("STOR /flash/projects/Echo/Server.gpl",
                              io.BytesIO(ECHO_SERVER.format(port=echo_port).encode()))
            listing: list[str] = []
            client.retrlines("LIST /flash/projects/Echo", listing.append)
            print("\n".join(listing))
            assert [line.split()[-1] for line in listing] == ["Project.gpr", "Server.gpl"]

        # 2. Load, compile and start it from the console, over a plain socket.
        console = Console(notes["console"])
        for command in ["Load /flash/projects/Echo", "Compile Echo", "Start Echo"]:
            reply = console(command)
            print(f"GPL: {command}\n" + "\n".join(reply))
            assert reply == []  # the controller answers success with its prompt alone

        # 3. The uploaded project serves its port.
        answer = b""

        def served() -> bool:
            nonlocal answer
            try:
                answer = _ask(echo_port, b"hello")
            except OSError:
                return False
            return True

        _wait_for(served, "the uploaded server")
        print(answer)
        assert answer == b"echo Echo: hello"

        # 4. Show the threads, stop the project, unload it.
        threads = console("Show Thread")
        print("GPL: Show Thread\n" + "\n".join(threads))
        rows = [line.split() for line in threads[1:]]
        assert ["Echo", "Main", "Running"] in rows
        assert [rows_ for rows_ in rows if rows_[0] != "Echo"] == [[rows[0][0], "Main", "Idle"]]  # the boot project
        assert console("Stop Echo") == []
        stopped = console("Show Thread")
        print("GPL: Show Thread\n" + "\n".join(stopped))
        assert ["Echo", "Main", "Idle"] in [line.split() for line in stopped[1:]]
        with pytest.raises(OSError):
            _ask(echo_port, b"again")  # nothing listens any more
        assert console("Unload Echo") == []
        assert console("Start Echo") == ["-729 *Undefined symbol*", "no project 'Echo' in memory"]
        console.close()
    finally:
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    print(out, err)
    assert "boot project ran" in out
    shown = out.splitlines()[out.splitlines().index("boot project ran") + 1:]
    assert shown[0].split() == ["Project", "State", "Folder"]  # Controller.Command: the same console
    assert shown[1].split()[1:] == ["Running", f"/flash/projects/{shown[1].split()[0]}"]
    assert proc.returncode == 130  # a controller stays on until interrupted


# -- FTP: no way out of the disks ---------------------------------------------------------------------


@pytest.fixture
def served(tmp_path: Path) -> Iterator[tuple[ftplib.FTP, Path, Path]]:
    """An FTP client logged in to a session's disks; the flash root; a folder outside it."""
    root, outside = tmp_path / "root", tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.txt").write_text("outside data")
    sim = Simulation(capture=True, flash_root=root)
    sim.files.root()  # the device folders exist from here on
    service = FtpService(sim.files, 0, "127.0.0.1").start()
    client = ftplib.FTP()
    client.connect(*service.address, timeout=30)
    client.login("anyone", "anything")
    try:
        yield client, root, outside
    finally:
        client.close()
        service.close()
        sim.close(0.5)


def _refused(call: object, *args: object) -> str:
    with pytest.raises(ftplib.error_perm) as info:
        call(*args)  # type: ignore[operator]
    return str(info.value)


def test_ftp_paths_cannot_leave_the_disks(served: tuple[ftplib.FTP, Path, Path]) -> None:
    client, root, outside = served
    for path in ["/flash/../../outside/secret.txt", "../outside/secret.txt", "/etc/passwd", str(outside / "secret.txt")]:
        assert _refused(client.retrbinary, f"RETR {path}", print).startswith("550")
    client.cwd("/flash")
    client.cwd("..")
    client.cwd("..")  # .. stops at the FTP root, which lists the devices only
    assert client.pwd() == "/"
    assert client.nlst() == ["NVRAM", "ROMDISK", "flash"]
    assert _refused(client.storbinary, "STOR /outside.txt", io.BytesIO(b"x")).startswith("550")
    assert _refused(client.mkd, "/etc") .startswith("550")
    assert not (root / "outside.txt").exists()
    # a name the controller refuses: too long, a leading dot, a control character
    assert "-516" in _refused(client.storbinary, f"STOR /flash/{'n' * 44}", io.BytesIO(b"x"))
    assert "-516" in _refused(client.storbinary, "STOR /flash/.hidden", io.BytesIO(b"x"))
    assert "-517" in _refused(client.storbinary, "STOR /flash/" + "/".join(["d" * 40] * 7), io.BytesIO(b"x"))
    assert sorted(p.name for p in (root / "flash").iterdir()) == []


def test_ftp_never_follows_a_link_planted_in_the_flash_folder(served: tuple[ftplib.FTP, Path, Path]) -> None:
    client, root, outside = served
    flash = root / "flash"
    (flash / "to_file").symlink_to(outside / "secret.txt")
    (flash / "to_folder").symlink_to(outside)
    os.link(outside / "secret.txt", flash / "hard")
    assert client.nlst("/flash") == []  # links and hard-linked files are not shown
    for name in ["to_file", "to_folder/secret.txt", "hard"]:
        assert _refused(client.retrbinary, f"RETR /flash/{name}", print).startswith("550")
    assert _refused(client.cwd, "/flash/to_folder").startswith("550")
    assert _refused(client.nlst, "/flash/to_folder").startswith("550")
    # uploading over a link or a hard link replaces nothing outside; writing into a linked folder fails
    assert "-208" in _refused(client.storbinary, "STOR /flash/to_file", io.BytesIO(b"overwritten"))
    assert "-208" in _refused(client.storbinary, "STOR /flash/hard", io.BytesIO(b"overwritten"))
    assert "-208" in _refused(client.storbinary, "STOR /flash/to_folder/new.txt", io.BytesIO(b"x"))
    assert _refused(client.delete, "/flash/to_file").startswith("550")
    assert _refused(client.rename, "/flash/to_folder", "/flash/moved").startswith("550")
    assert _refused(client.rename, "/flash/hard", "/flash/moved").startswith("550")
    assert (outside / "secret.txt").read_text() == "outside data"
    assert sorted(p.name for p in outside.iterdir()) == ["secret.txt"]
    assert (flash / "to_file").is_symlink() and (flash / "to_folder").is_symlink()
    # the flash folder itself a link: every use is refused
    (flash / "to_folder").unlink()
    (flash / "to_file").unlink()
    (flash / "hard").unlink()
    flash.rmdir()
    flash.symlink_to(outside)
    assert _refused(client.nlst, "/flash").startswith("550")
    assert "-208" in _refused(client.storbinary, "STOR /flash/x.txt", io.BytesIO(b"x"))
    assert sorted(p.name for p in outside.iterdir()) == ["secret.txt"]


def test_ftp_uploads_stay_within_the_sandbox_limits(served: tuple[ftplib.FTP, Path, Path],
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    client, root, _ = served
    monkeypatch.setattr(ftp_module, "MAX_FILE_BYTES", 1000)
    monkeypatch.setattr(ftp_module, "FLASH_BYTES", 2500)
    monkeypatch.setattr(ftp_module, "MAX_ENTRIES", 6)
    client.storbinary("STOR /flash/a.bin", io.BytesIO(b"a" * 1000))  # at the limit: stored
    assert (root / "flash" / "a.bin").stat().st_size == 1000
    with pytest.raises(ftplib.Error):
        client.storbinary("STOR /flash/big.bin", io.BytesIO(b"b" * 1001))  # one byte over a file's limit
    assert not (root / "flash" / "big.bin").exists()  # what it wrote is removed
    client.storbinary("STOR /flash/b.bin", io.BytesIO(b"b" * 1000))
    with pytest.raises(ftplib.Error):
        client.storbinary("STOR /flash/c.bin", io.BytesIO(b"c" * 600))  # the disk holds 2500 bytes
    assert not (root / "flash" / "c.bin").exists()
    client.storbinary("STOR /flash/a.bin", io.BytesIO(b"A" * 1000))  # replacing a file frees its room
    assert (root / "flash" / "a.bin").read_bytes() == b"A" * 1000
    for n in range(4):
        client.mkd(f"/flash/d{n}")
    assert "-207" in _refused(client.mkd, "/flash/one-too-many")  # 6 entries at most: a, b, d0-d3
    assert "-207" in _refused(client.storbinary, "STOR /flash/d0/x", io.BytesIO(b"x"))
    assert "-209" in _refused(client.storbinary, "STOR /NVRAM/file1", io.BytesIO(b"x"))  # read-only here
    assert _refused(client.sendcmd, "SITE CHMOD 777 /flash/a.bin").startswith("5")
    with pytest.raises(ftplib.Error, match="STOU is not supported"):
        client.sendcmd("STOU")


def test_ftp_serves_only_so_many_clients_at_once(tmp_path: Path) -> None:
    sim = Simulation(capture=True, flash_root=tmp_path / "root")
    service = FtpService(sim.files, 0, "127.0.0.1").start()
    clients = []
    try:
        for _ in range(ftp_module.MAX_CLIENTS):
            client = ftplib.FTP()
            client.connect(*service.address, timeout=30)
            clients.append(client)
        extra = ftplib.FTP()
        with pytest.raises(ftplib.error_temp) as info:
            extra.connect(*service.address, timeout=30)
        assert str(info.value).startswith("421")
    finally:
        for client in clients:
            client.close()
        service.close()
        sim.close(0.5)


# -- the Telnet console's own limits --------------------------------------------------------------------


def test_console_drops_telnet_negotiation_refuses_long_lines_and_too_many_clients(tmp_path: Path) -> None:
    sim = Simulation(capture=True, flash_root=tmp_path / "root")
    server = ConsoleServer(sim.projects, 0, "127.0.0.1").start()
    port = server.address[1]
    try:
        console = Console(port)
        # IAC DO ECHO, IAC WILL SUPPRESS-GO-AHEAD, a subnegotiation: read and dropped
        console.sock.sendall(bytes([255, 253, 1, 255, 251, 3, 255, 250, 24, 0, 1, 255, 240]))
        assert console("dir /flash") == ["Directory of /flash"]
        assert console("x" * (telnet.MAX_LINE + 1)) == ["-712 *Invalid syntax*", f"a command line is at most {telnet.MAX_LINE} bytes"]
        assert console("help")[0] == "Load path"  # the connection goes on
        others = [Console(port) for _ in range(telnet.MAX_CLIENTS - 1)]
        with socket.create_connection(("127.0.0.1", port), timeout=30) as extra:
            refused = b""
            while chunk := extra.recv(4096):
                refused += chunk
        assert refused.startswith(b"-207 *Too many*")
        console.sock.sendall(b"exit\r\n")
        assert console.sock.recv(100) == b""  # exit closes the connection
        for other in others:
            other.close()
    finally:
        server.close()
        sim.close(0.5)


def test_console_listens_on_loopback_unless_the_network_is_opened(tmp_path: Path) -> None:
    sim = Simulation(capture=True, flash_root=tmp_path / "root")
    server = ConsoleServer(sim.projects, 0, sim.listen).start()
    try:
        assert server.address[0] == "127.0.0.1"
    finally:
        server.close()
        sim.close(0.5)


# -- gpl2py run's options -------------------------------------------------------------------------------


def test_ftp_without_pyftpdlib_names_the_extra(tmp_path: Path) -> None:
    """--ftp needs the optional pyftpdlib: without it, one line naming the extra, status 2, before
    the program runs (as --plot without matplotlib)."""
    from gpltest import gpl2py

    fake = tmp_path / "no_pyftpdlib" / "pyftpdlib"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'pyftpdlib'\", name='pyftpdlib')\n")
    proj = write_project(tmp_path / "p", {"Main.gpl": BOOT})
    r = gpl2py("run", proj, "--ftp", "--quiet", env={"PYTHONPATH": str(fake.parent)})
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr == "error GPL9001: --ftp needs pyftpdlib, which is not installed: pip install 'gpl2py[ftp]'\n"


def test_a_console_port_in_use_is_a_command_line_error(tmp_path: Path) -> None:
    from gpltest import gpl2py

    proj = write_project(tmp_path / "p", {"Main.gpl": BOOT})
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        r = gpl2py("run", proj, "--console", str(taken.getsockname()[1]), "--quiet")
    assert r.returncode == 2
    assert r.stderr.startswith("error GPL9001: cannot serve the console or FTP: "), r.stderr
    assert "boot project ran" not in r.stdout  # nothing ran
    bad = gpl2py("run", proj, "--console", "70000")
    assert bad.returncode == 2 and "a port is 0 to 65535" in bad.stderr
