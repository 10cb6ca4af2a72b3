"""ros.v2 (hand-lowered onto gplrt.vplus: ros_v2_lowered.py) in two tasks on a simulated Adept
Viper s650, served to a simple_message client written from REP-I0006 over loopback on the virtual
clock.

What the client sees is what the file does under the runtime's decisions (docs/design/vplus.md):
the command server reads a four-byte connect notice before the first message, each JOINT_POSITION
command gets a reply whose header says 56 bytes but which carries only the 16 header bytes after
the length field ($msg.jts never assigned), the arm reaches each commanded point, the feedback
server streams JOINT_POSITION topics with the simulated joints, and a STOP (sequence -2) ends both
tasks.
"""

from __future__ import annotations

import math
import socket
import struct
import threading
import time

import numpy as np
import pytest

from gpltest import free_port
from gplrt.sim import Simulation

import ros_v2_lowered as ros

DEADLINE = 60.0  # real seconds before the test gives up waiting (a guard, not an assertion)
HEADER = struct.Struct("<iiiii")  # length, msg_type, comm_type, reply_code, sequence
JOINTS = struct.Struct("<10f")


def _recv(conn: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        if not chunk:
            raise ConnectionError("server closed")
        data += chunk
    return data


def _command(seq: int, degrees: tuple[float, ...]) -> bytes:
    rad = [math.radians(d) for d in degrees] + [0.0] * (10 - len(degrees))
    return HEADER.pack(56, 10, 2, 0, seq) + JOINTS.pack(*rad)


def _feedback(conn: socket.socket) -> tuple[tuple[int, ...], tuple[float, ...]]:
    raw = _recv(conn, 60)
    return HEADER.unpack(raw[:20]), JOINTS.unpack(raw[20:])


@pytest.fixture
def server():  # type: ignore[no-untyped-def]
    sim = Simulation(robot="VIPER-S650", capture=True)
    cmd_port, fdb_port = free_port(), free_port()
    with sim:
        # run_main drives the virtual clock (paced to real time while the servers listen) until
        # every task has ended; the client talks to the servers meanwhile
        runner = threading.Thread(target=sim.run_main, args=(lambda: ros.a_ros(cmd_port, fdb_port),),
                                  daemon=True)
        runner.start()
        deadline = time.monotonic() + DEADLINE
        while not {cmd_port, fdb_port} <= sim.network.listening_ports():
            assert time.monotonic() < deadline, sim.console.output + sim.console.log_text
            time.sleep(0.01)
        yield sim, cmd_port, fdb_port
        sim.stop(grace=10)
        runner.join(10)
    sim.close()


def test_ros_v2_serves_joint_commands_and_feedback(server) -> None:  # type: ignore[no-untyped-def]
    sim, cmd_port, fdb_port = server
    points = [(10.0, -20.0, 40.0, 5.0, 50.0, -10.0), (-15.0, -35.0, 70.0, -5.0, 45.0, 20.0)]
    deadline = time.monotonic() + DEADLINE
    with socket.create_connection(("127.0.0.1", fdb_port), timeout=DEADLINE) as fdb, \
            socket.create_connection(("127.0.0.1", cmd_port), timeout=DEADLINE) as cmd:
        for seq, point in enumerate(points):
            cmd.sendall(_command(seq, point))
            reply = _recv(cmd, 20)
            assert HEADER.unpack(reply) == (56, 10, 3, 1, 0)
            want = [np.float32(math.radians(d)) for d in point]
            while True:  # feedback streams until the arm is there
                header, joints = _feedback(fdb)
                assert header == (56, 10, 1, 0, 0) and joints[6:] == (0.0,) * 4
                if all(abs(j - w) <= 1e-6 for j, w in zip(joints[:6], want)):
                    break
                assert time.monotonic() < deadline, (joints, want)
        assert "ROS connected to V+ command server" in sim.console.output
        cmd.sendall(_command(-2, (0.0,) * 6))  # STOP: sequence -2 (msg.unused == -2)
        while any(t._active for t in sim.threads):
            assert time.monotonic() < deadline, [t.Name for t in sim.threads if t._active]
            time.sleep(0.01)
        assert cmd.recv(1) == b""  # the command server closed its port
    assert sim.console.log_text == ""
