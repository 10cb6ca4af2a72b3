"""Adept's ROS-Industrial server, ``swri-ros/ros.v2``, unchanged through the V+ front end, in two
tasks on a simulated Viper s650 (issue 21).

The client is written from REP-I0006 (``../shared/corpus/docs/rep-I0006-simple-message.rst``),
little-endian as the file builds its messages, and behaves as the ROS client does: it connects and
sends nothing until its first message, and reads each reply by its length prefix.  The file
listens on its own ports, 11000 (joint commands) and 11002 (joint feedback), on loopback, on the
virtual clock.

What it sees is what the Guide makes of the file (docs/design/vplus.md, "A real controller cannot
answer a joint command with this file"): the feedback server streams JOINT_POSITION topics holding
the simulated joints, but the command server stops at its first command with *Undefined value*
(-401) at ros.v2 line 254, ``$msg = $msg+$msg.jts[idx]``, before writing its reply or moving the
arm: ``ros.srv.cmd`` appends elements of its own AUTO ``$msg.jts`` that nothing assigned
(L4129-4143).  A task stopped by an error keeps its devices attached (L7476-7480), so the client's
connection stays open and silent: a client reading the reply by its length prefix waits for ever,
and its STOP is never read.
"""

from __future__ import annotations

import math
import socket
import struct
import time
import warnings
from pathlib import Path

import pytest

from gpl2py.notebook import Cell, GplError
from gpltest import corpus_dir

CMD_PORT, FDB_PORT = 11000, 11002  # (the file's own: cmd.port = 11000, fdb.port = 11002)
GUARD = 60.0  # real seconds before the client gives up (a guard against a hang, not an assertion)
HEADER = struct.Struct("<iiiii")  # length, msg_type, comm_type, reply_code, sequence
JOINTS = struct.Struct("<10f")
JOINT_POSITION, TOPIC, SERVICE_REQUEST = 10, 1, 2


def _recv(conn: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        if not chunk:
            raise ConnectionError(f"server closed after {len(data)} of {n} bytes")
        data += chunk
    return data


def _feedback(conn: socket.socket) -> tuple[tuple[int, ...], list[float]]:
    raw = _recv(conn, 60)
    return HEADER.unpack(raw[:20]), [math.degrees(j) for j in JOINTS.unpack(raw[20:])]


def _command(seq: int, degrees: list[float]) -> bytes:
    rad = [math.radians(d) for d in degrees] + [0.0] * (10 - len(degrees))
    return HEADER.pack(56, JOINT_POSITION, SERVICE_REQUEST, 0, seq) + JOINTS.pack(*rad)


def test_ros_v2_streams_feedback_but_its_command_server_stops_at_the_first_command(
        tmp_path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cell = Cell.load(corpus_dir() / "vplus" / "swri-ros", robot="VIPER-S650", echo=False,
                         cache_dir=tmp_path / "cache")
    target = [10.0, -40.0, 140.0, 5.0, 50.0, 20.0]
    with cell.serve(ports=[CMD_PORT, FDB_PORT], timeout=GUARD):
        fdb = socket.create_connection(("127.0.0.1", FDB_PORT), timeout=GUARD)
        header, joints = _feedback(fdb)
        assert header == (56, JOINT_POSITION, TOPIC, 0, 0)
        assert joints == [0.0] * 10  # the arm at its zero (URDF zero is V+ zero)
        cmd = socket.create_connection(("127.0.0.1", CMD_PORT), timeout=GUARD)
        cmd.sendall(_command(0, target))
        deadline = time.monotonic() + GUARD
        while not cell._failed_threads():  # the command task reads the command, then stops
            assert time.monotonic() < deadline, cell.log
            time.sleep(0.02)
        (task,) = cell._failed_threads()
        error = GplError(task.unhandled_error, task.Name, cell._folder)
        assert (task.Name, error.ErrorCode, error.detail) == ("task 5", -401, "$msg.jts[1]")
        assert error.Message() == "*Undefined value*"
        assert [(f.file, f.line, f.text) for f in error.frames] == [
            ("ros.v2", 254, "$msg = $msg+$msg.jts[idx]")]
        # no reply, and no close: the stopped task keeps its connection (L7476-7480)
        cmd.setblocking(False)
        with pytest.raises(BlockingIOError):
            cmd.recv(HEADER.size)
        cmd.sendall(_command(-2, [0.0] * 6))  # STOP: nothing reads it, run stays TRUE
        # the feedback task goes on streaming the arm, which never moved
        for _ in range(5):
            header, joints = _feedback(fdb)
            assert header == (56, JOINT_POSITION, TOPIC, 0, 0)
            assert joints == [0.0] * 10
        assert list(cell.sim.robot(1).queue.joints_at(cell.sim.now())) == [0.0] * 6
        assert {CMD_PORT, FDB_PORT} <= cell.sim.network.listening_ports()
        with pytest.raises(BlockingIOError):
            cmd.recv(HEADER.size)
        cmd.close()
        fdb.close()
    assert "ROS connected to V+ command server" in cell.sim.console.output
