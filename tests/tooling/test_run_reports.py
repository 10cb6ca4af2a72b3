"""``gpl2py run`` tells the user what the program does as a server, stops cleanly on SIGTERM, and
keeps its reports in the controller's words (issue 20, item 6)."""

from __future__ import annotations

import json
import os
import queue
import signal
import socket
import subprocess
import sys
import threading
from pathlib import Path
from typing import IO

import pytest

from gpltest import REPO, free_port, gpl2py, in_process, module_src, write_project

# Two joint moves: the first is planned and run (the robot's history holds its Ruckig trajectory),
# the second is refused (a PF400 flange must be horizontal), unhandled.
REFUSED_SECOND_MOVE = module_src("""\
    Public Sub Main()
        Dim prof As New Profile
        Dim a As New Location
        Dim b As New Location
        a.Angles(300, 10, 90, -100, 100)
        b.XYZ(500, 0, 100, 0, 0, 0)
        Controller.PowerEnabled = True
        Robot.Attached = 1
        Robot.Home
        Move.Loc(a, prof)
        Move.Loc(b, prof)
        Move.WaitForEOM
    End Sub""")


def test_an_unhandled_motion_error_leaves_json_stderr_clean(tmp_path: Path) -> None:
    """After an unhandled motion error, the frames of the error held the robot and its planned
    motion until the interpreter's exit, where nanobind printed 22 lines of 'leaked ... ruckig.
    Trajectory' -- on the stderr that --json promises to leave clean."""
    proj = write_project(tmp_path, {"Main.gpl": REFUSED_SECOND_MOVE})
    r = gpl2py("run", proj, "--json")
    assert r.returncode == 3
    assert r.stderr == ""
    [error] = json.loads(r.stdout)["run"]["errors"]
    assert (error["code"], error["line"]) == (-1033, 12)


# A fault of the GPL program that Python noticed first (a list index, an attribute of None, the
# interpreter's recursion limit) is reported as the controller reports it: code, text, GPL line.
PYTHON_NOTICED = {
    "IndexError": (module_src("""\
    Public Sub Main()
        Dim a(3) As Integer
        Dim i As Integer
        i = 5
        a(i) = 1
    End Sub"""), "Main.gpl:6: error -767 in thread Main: *Invalid array index*"),
    # the vendor's shape (TCS TcpComMain): a handler closes a socket that was never accepted
    "AttributeError": (module_src("""\
    Public Sub Main()
        Dim TcpSock As Socket
        Dim ex As Exception
        Try
            ex = New Exception
            ex.ErrorCode = -1705
            Throw ex
        Catch ex
            TcpSock.Close()
        End Try
    End Sub"""), "Main.gpl:10: error -757 in thread Main: *Object not instantiated*"),
    "RecursionError": (module_src("""\
    Function Down(ByVal n As Integer) As Integer
        Return Down(n + 1) + 1
    End Function
    Public Sub Main()
        Console.WriteLine(Down(0))
    End Sub"""), "Main.gpl:3: error -755 in thread Main: *Thread stack too small*"),
}


@pytest.mark.parametrize("python_name", sorted(PYTHON_NOTICED))
def test_a_fault_python_noticed_is_told_in_the_controllers_words(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], python_name: str) -> None:
    """It was '*Invalid array index* - IndexError: list assignment index out of range' (and
    "AttributeError: 'NoneType' object has no attribute 'Close'", 'RecursionError: maximum
    recursion depth exceeded'): words about Python that name nothing in the user's GPL."""
    source, expected = PYTHON_NOTICED[python_name]
    proj = write_project(tmp_path, {"Main.gpl": source})
    r = in_process(capsys, "run", proj)
    assert r.returncode == 3
    report = [line for line in r.stderr.splitlines() if line.startswith(proj)]
    assert report == [f"{proj}/{expected}"], r.stderr
    assert python_name not in r.stderr and "NoneType" not in r.stderr


# The example: one Exception object thrown and caught at line 7, then given a new code and
# thrown again, unhandled, at line 13 (TCS reuses its `ex` so: Main.gpl:215-216).
THROWN_TWICE = module_src("""\
    Public Sub Main()
        Dim e2 As New Exception
        Dim ex As Exception
        e2.ErrorCode = -31000
        Try
            Throw e2
        Catch ex
            Console.WriteLine("caught " & CStr(ex.ErrorCode))
        End Try
        Console.WriteLine("thrown again")
        e2.ErrorCode = -31001
        Throw e2
    End Sub""")

# A fault in a procedure called through a delegate (its runtime wrapper records the GPL line) is
# caught by the caller and thrown on from there.
THROWN_ON_FROM_A_DELEGATES_FAULT = """\
Module Main
    Delegate Sub Action()
    Public Sub Faulty()
        Dim a(1) As Integer
        a(2) = 1
    End Sub
    Public Sub Main()
        Dim d As Action
        Dim ex As Exception
        d = New Action("Faulty")
        Try
            d()
        Catch ex
            Console.WriteLine("caught " & CStr(ex.ErrorCode))
            Throw ex
        End Try
    End Sub
End Module
"""


@pytest.mark.parametrize(("source", "expected"), [
    (THROWN_TWICE, "Main.gpl:13: error -31001 in thread Main: *Error -31001*"),
    (THROWN_ON_FROM_A_DELEGATES_FAULT, "Main.gpl:15: error -767 in thread Main: *Invalid array index*"),
], ids=["thrown-twice", "thrown-on-from-a-delegate"])
def test_an_exception_thrown_again_is_reported_where_it_was_thrown_this_time(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], source: str, expected: str) -> None:
    """An Exception object has no location member, so its last Throw is where the thread stopped;
    the report named the first Throw's line (Python kept that raise's frames in the traceback)."""
    proj = write_project(tmp_path, {"Main.gpl": source})
    r = in_process(capsys, "run", proj)
    assert r.returncode == 3
    report = [line for line in r.stderr.splitlines() if line.startswith(proj)]
    assert report == [f"{proj}/{expected}"], r.stderr


def udp_port() -> int:
    """A UDP port on loopback that nothing is bound to right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def listeners(tcp: int, udp: int) -> str:
    """A thread named Listener opens a TCP server twice (Start, Stop, Start, Stop) and a UDP one."""
    return module_src(f"""\
    Public Sub Serve()
        Dim tl As New TcpListener(New IPEndPoint("", {tcp}))
        Dim u As UdpClient
        tl.Start()
        tl.Stop()
        tl.Start()
        u = New UdpClient(New IPEndPoint("0.0.0.0", {udp}))
        u.Close()
        tl.Stop()
    End Sub
    Public Sub Main()
        Dim t As New Thread("Serve", 0, "Listener")
        t.Start()
        t.Join()
        Console.WriteLine("done")
    End Sub""")


def test_a_server_says_where_it_listens_each_time_it_starts(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    """Without it a user cannot tell when to connect, and probing costs TCS's one client its turn.
    The address is where a client must connect: loopback, though the program bound 0.0.0.0."""
    tcp, udp = free_port(), udp_port()
    proj = write_project(tmp_path, {"Main.gpl": listeners(tcp, udp)})
    r = in_process(capsys, "run", proj)
    assert r.returncode == 0 and r.stdout == "done\n"
    notes = [line for line in r.stderr.splitlines() if line.startswith("note: listening")]
    assert notes == [f"note: listening on 127.0.0.1:{tcp} (thread Listener)"] * 2 + [
        f"note: listening on 127.0.0.1:{udp}/udp (thread Listener)"]


@pytest.mark.parametrize("option", ["--quiet", "--json"])
def test_quiet_and_json_runs_print_no_listening_note(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                     option: str) -> None:
    proj = write_project(tmp_path, {"Main.gpl": listeners(free_port(), udp_port())})
    r = in_process(capsys, "run", proj, option)
    assert r.returncode == 0
    assert r.stderr == ""


class Lines:
    """The lines a subprocess writes to one of its pipes, read on a helper thread so that a test can
    wait for one without blocking forever on a program that never writes it."""

    def __init__(self, stream: IO[str]) -> None:
        self.seen: list[str] = []
        self._queue: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=self._read, args=(stream,), daemon=True).start()

    def _read(self, stream: IO[str]) -> None:
        for line in stream:
            self._queue.put(line.rstrip("\n"))
        self._queue.put(None)

    def wait_for(self, wanted: str, timeout: float = 120.0) -> None:
        """Return once the line ``wanted`` was written; fail, with every line seen, if the stream
        ends (or ``timeout`` real seconds pass) first."""
        while wanted not in self.seen:
            try:
                line = self._queue.get(timeout=timeout)
            except queue.Empty:
                line = None
            if line is None:
                pytest.fail(f"never wrote {wanted!r}; wrote:\n" + "\n".join(self.seen))
            self.seen.append(line)

    def rest(self) -> list[str]:
        """Every line, once the stream has ended."""
        while (line := self._queue.get(timeout=60)) is not None:
            self.seen.append(line)
        return self.seen


def test_sigterm_stops_the_run_as_ctrl_c_does_and_exits_143(tmp_path: Path) -> None:
    """docker stop, systemd and CI time-outs send SIGTERM: the run died at once, leaving its
    temporary flash folder behind (and skipping the GPL threads' stop).  Now every GPL thread is
    stopped, the servers close, the folder is removed, and the status is 143 (128 + SIGTERM)."""
    port = free_port()
    proj = write_project(tmp_path, {"Main.gpl": module_src(f"""\
    Public Sub Serve()
        Dim tl As New TcpListener(New IPEndPoint("", {port}))
        Dim sock As Socket
        tl.Start()
        While True
            sock = tl.AcceptSocket()
            sock.Send("hello" & Chr(10))
        End While
    End Sub
    Public Sub Main()
        Dim t As New Thread("Serve", 0, "Server")
        t.Start()
        t.Join()
    End Sub""")})
    temp = tmp_path / "tmp"  # the run's temporary flash folder is made here (tempfile's TMPDIR)
    temp.mkdir()
    proc = subprocess.Popen([sys.executable, "-X", "faulthandler", "-m", "gpl2py", "run", proj,
                             "--cache-dir", str(tmp_path / "cache")],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, cwd=REPO,
                            env={**os.environ, "TMPDIR": str(temp)})
    try:
        assert proc.stderr is not None
        err = Lines(proc.stderr)
        err.wait_for(f"note: listening on 127.0.0.1:{port} (thread Server)")
        with socket.create_connection(("127.0.0.1", port), timeout=30) as client:
            assert client.makefile().readline() == "hello\n"  # the server serves
        [flash] = temp.glob("gplrt-flash-*")
        assert (flash / "flash" / "projects").is_dir()
        proc.send_signal(signal.SIGTERM)
        try:
            proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            proc.send_signal(signal.SIGABRT)  # -X faulthandler: the stacks say where it was stuck
            pytest.fail("still running 60 s after SIGTERM:\n" + "\n".join(err.rest()))
        lines = err.rest()
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 143, lines
    assert lines[-1] == "gpl2py: terminated; stopped 2 GPL threads"
    assert not any("Traceback" in line or "KeyboardInterrupt" in line for line in lines), lines
    assert list(temp.iterdir()) == []  # the flash folder is gone
    with pytest.raises(ConnectionRefusedError):
        socket.create_connection(("127.0.0.1", port), timeout=30)


def test_a_port_in_use_is_reported_with_its_address_and_port(tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        proj = write_project(tmp_path, {"Main.gpl": module_src(f"""\
    Public Sub Main()
        Dim tl As New TcpListener(New IPEndPoint("", {port}))
        tl.Start()
    End Sub""")})
        r = in_process(capsys, "run", proj)
    assert r.returncode == 3
    assert f"{proj}/Main.gpl:4: error -304 in thread Main: *Device already in use* - listen on " \
           f"127.0.0.1:{port}: address already in use" in r.stderr.splitlines()
    assert "note: listening" not in r.stderr
