"""Adept's ROS-Industrial server, ``swri-ros/ros.v2``, unchanged through the V+ front end, in two
tasks on a simulated Viper s650 (issue 21).

The client is written from REP-I0006 (``../shared/corpus/docs/rep-I0006-simple-message.rst``),
little-endian as the file builds its messages, and behaves as the ROS client does: it connects and
sends nothing until its first message.  The file listens on its own ports, 11000 (joint commands)
and 11002 (joint feedback), on loopback, on the virtual clock.

What it sees is what the file does under the runtime's decisions (docs/design/vplus.md): each
JOINT_POSITION command is answered by a SERVICE_REPLY whose header says 56 bytes but which carries
only the 16 header bytes after the length field (the file appends ``$msg.jts`` elements it never
assigned), the arm reaches each commanded point, the feedback server streams JOINT_POSITION topics
holding the simulated joints, and a STOP (sequence -2) ends both tasks.
"""

from __future__ import annotations

import math
import socket
import struct
import time
import warnings
from pathlib import Path

import numpy as np

from gpl2py.notebook import Cell
from gpltest import corpus_dir

CMD_PORT, FDB_PORT = 11000, 11002  # (the file's own: cmd.port = 11000, fdb.port = 11002)
GUARD = 60.0  # real seconds before the client gives up (a guard against a hang, not an assertion)
HEADER = struct.Struct("<iiiii")  # length, msg_type, comm_type, reply_code, sequence
JOINTS = struct.Struct("<10f")
JOINT_POSITION, TOPIC, SERVICE_REQUEST, SERVICE_REPLY, SUCCESS = 10, 1, 2, 3, 1


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


def test_ros_v2_serves_joint_commands_and_streams_feedback_until_stop(tmp_path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cell = Cell.load(corpus_dir() / "vplus" / "swri-ros", robot="VIPER-S650", echo=False,
                         cache_dir=tmp_path / "cache")
    points = [[10.0, -40.0, 140.0, 5.0, 50.0, 20.0], [-25.0, -20.0, 120.0, -10.0, 70.0, -30.0]]
    with cell.serve(ports=[CMD_PORT, FDB_PORT], timeout=GUARD):
        fdb = socket.create_connection(("127.0.0.1", FDB_PORT), timeout=GUARD)
        header, joints = _feedback(fdb)
        assert header == (56, JOINT_POSITION, TOPIC, 0, 0)
        assert joints == [0.0] * 10  # the arm at its zero (URDF zero is V+ zero)
        cmd = socket.create_connection(("127.0.0.1", CMD_PORT), timeout=GUARD)
        for seq, target in enumerate(points):
            cmd.sendall(_command(seq, target))
            reply = HEADER.unpack(_recv(cmd, 20))
            assert reply == (56, JOINT_POSITION, SERVICE_REPLY, SUCCESS, 0)
            # the file reads each joint as a single-precision float in radians: (jts*180)/PI
            goal = [float(np.float32(math.radians(d))) * 180 / math.pi for d in target]
            deadline = time.monotonic() + GUARD
            while True:  # the feedback stream shows the arm arriving
                header, joints = _feedback(fdb)
                assert header == (56, JOINT_POSITION, TOPIC, 0, 0)
                if max(abs(a - b) for a, b in zip(joints[:6], goal, strict=True)) < 1e-4:
                    break
                assert time.monotonic() < deadline, (target, joints)
            simulated = cell.sim.robot(1).queue.joints_at(cell.sim.now())
            assert max(abs(a - b) for a, b in zip(simulated, goal, strict=True)) < 1e-9
        cmd.sendall(_command(-2, [0.0] * 6))  # STOP: the command task calls ros.stop, run = FALSE
        deadline = time.monotonic() + GUARD
        while cell.sim.network.listening_ports() & {CMD_PORT, FDB_PORT}:
            assert time.monotonic() < deadline, cell.log
            time.sleep(0.05)
    assert "ROS connected to V+ command server" in cell.sim.console.output
