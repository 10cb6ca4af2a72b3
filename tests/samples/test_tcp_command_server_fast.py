"""samples/tcp_command_server on the FAST clock, served from a notebook Cell to a socket client.

``Cell.serve`` runs ProjectStart in the background and returns once the server listens; the
client then powers, homes and moves the robot at 2 % speed, where each move is tens of seconds
of controller time.  On the fast clock a client waiting for a motion does not wait for it in
wall time, so every reply comes within the client's socket time-out (15 s, the hang guard) —
on the paced virtual clock the first move alone would exceed it.  Poses are read off the
simulated robot itself (``cell.where()``) and compared with the taught positions of
Globals.gpo and with the server's own "where" reply.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gpltest import SAMPLES, LineClient, copy_project, free_port, hand_rotation, module_src, write_project
from gpl2py.notebook import Cell

PICK = (300.0, 150.0, 120.0, 90.0)  # x, y, z, yaw (Globals.gpo)
PLACE = (350.0, -150.0, 125.5, -60.0)
MOVES = 6


def where_fields(reply: str) -> dict[str, float]:
    words = reply.split()
    assert words[0] == "0" and words[-1] == "ok", reply
    return {k: float(v) for k, v in zip(words[1:-1:2], words[2:-1:2])}


def assert_at(cell: Cell, pose: tuple[float, float, float, float]) -> None:
    matrix = cell.where().matrix
    assert matrix is not None
    assert np.max(np.abs(matrix[:3, 3] - np.array(pose[:3]))) < 1e-6, (matrix[:3, 3], pose)
    assert np.max(np.abs(matrix[:3, :3] - hand_rotation(pose[3]))) < 1e-9


@pytest.fixture
def cell(tmp_path: Path) -> tuple[Cell, int]:
    port = free_port()
    src = copy_project(SAMPLES / "tcp_command_server", tmp_path / "src" / "tcp_command_server",
                       {"SERVER_PORT As Integer = 10100": f"SERVER_PORT As Integer = {port}"})
    return Cell.load(src, clock="fast", echo=False, cache_dir=tmp_path / "cache"), port


def test_slow_moves_are_served_faster_than_the_robot_moves(cell: tuple[Cell, int]) -> None:
    cell_, port = cell
    with cell_.serve(ports=[port], timeout=30.0) as serving:
        with LineClient(port, newline="\n") as client:
            assert client.ask("power on") == "0 power on"
            assert client.ask("home") == "0 homed"
            assert client.ask("speed 2") == "0 warning: very slow, speed 2"
            start = cell_.time
            for i in range(MOVES):
                target, pose = ("pick", PICK) if i % 2 == 0 else ("place", PLACE)
                assert client.ask(f"move {target}") == f"0 at {target}"
                assert_at(cell_, pose)
                here = where_fields(client.ask("where"))
                joints = cell_.where().joints
                assert [here[f"j{k}"] for k in range(1, 6)] == pytest.approx(joints, abs=1e-6)
                assert (here["x"], here["y"], here["z"]) == pytest.approx(pose[:3], abs=1e-6)
            assert client.ask("shutdown") == "0 shutting down"
        segments = [s for s in cell_.sim.robots[1].queue.history if s.t0 >= start]
        motion = sum(s.end - s.t0 for s in segments)
        assert len(segments) >= MOVES and motion > MOVES * 15.0  # each move is slow
        assert cell_.time - start >= motion
        assert serving.stop().still_alive == []
    assert serving.status == 0 and cell_.log == ""


def test_serve_reports_a_program_that_ends_or_never_listens(tmp_path: Path) -> None:
    """``Cell.serve`` fails clearly instead of leaving a client to connect to nothing."""
    ends = Cell.load(write_project(tmp_path, {"Main.gpl": module_src(
        'Public Sub Main()\n    Console.WriteLine("bye")\nEnd Sub')}), echo=False, cache_dir=tmp_path / "cache")
    with pytest.raises(RuntimeError, match=r"ended \(status 0\) before listening on \[1\]"):
        ends.serve(ports=[1], timeout=30.0)
    elsewhere = Cell.load(write_project(tmp_path, {"Main.gpl": module_src(
        "Public Sub Main()\n"
        "    Dim ep As New IPEndPoint(\"\", 0)\n"  # some free port, never port 1
        "    Dim tl As New TcpListener(ep)\n"
        "    tl.Start()\n"
        "    While Not tl.Pending()\n"
        "        Thread.Sleep(100)\n"
        "    End While\n"
        "End Sub")}), clock="fast", echo=False, cache_dir=tmp_path / "cache")
    with pytest.raises(TimeoutError, match=r"ports \[1\] not listening after 0.2 s"):
        elsewhere.serve(ports=[1], timeout=0.2)
    assert elsewhere.sim.scheduler.live == []  # stopped, not left running


def test_serve_tells_where_the_program_listens(tmp_path: Path) -> None:
    """A server whose port the test cannot know (it asked for port 0) or that listens elsewhere
    than asked: ``Serving.listening`` and the time-out's message say where it really listens."""
    port = free_port()
    cell_ = Cell.load(write_project(tmp_path, {"Main.gpl": module_src(
        "Public Sub Serve()\n"
        "    Dim chosen As New TcpListener(New IPEndPoint(\"0.0.0.0\", 0))\n"
        f"    Dim known As New TcpListener(New IPEndPoint(\"\", {port}))\n"
        "    chosen.Start()\n"
        "    known.Start()\n"
        "    While Not known.Pending()\n"
        "        Thread.Sleep(100)\n"
        "    End While\n"
        "End Sub\n"
        "Public Sub Main()\n"
        "    Dim t As New Thread(\"Serve\", 0, \"Server\")\n"
        "    t.Start()\n"
        "End Sub")}), clock="fast", echo=False, cache_dir=tmp_path / "cache")
    with cell_.serve(ports=[port], timeout=30.0) as serving:
        where = serving.listening
        assert [(w.protocol, w.thread) for w in where] == [("TCP", "Server")] * 2
        assert f"127.0.0.1:{port}" in [str(w) for w in where]
        [chosen] = [w for w in where if w.port != port]
        assert chosen.address == "127.0.0.1" and chosen.port != 0  # the port it was given
    assert serving.listening == []  # stopped: its listeners are closed
    with pytest.raises(TimeoutError) as info:
        cell_.serve(ports=[1], timeout=0.2)
    said = str(info.value).splitlines()[0]
    assert said.startswith("ports [1] not listening after 0.2 s; it listens on ") and said.endswith(":")
    places = said.removeprefix("ports [1] not listening after 0.2 s; it listens on ")[:-1].split(", ")
    assert f"127.0.0.1:{port} (thread Server)" in places and len(places) == 2
