"""ros.v2 (hand-lowered onto gplrt.vplus: ros_v2_lowered.py) in two tasks on a simulated Adept
Viper s650, served to a simple_message client written from REP-I0006 over loopback on the virtual
clock.

What the client sees is what the file does under the runtime's decisions (docs/design/vplus.md):
the command server reads a four-byte connect notice before the first message, then stops at its
first command with *Undefined value* ($msg.jts[1], never assigned: L4129-4143) before replying or
moving, keeping its connection open (L7476-7480); the feedback server streams JOINT_POSITION
topics with the simulated joints.
"""

from __future__ import annotations

import math
import socket
import struct
import threading
import time

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


def test_ros_v2_command_server_stops_at_its_first_reply(server) -> None:  # type: ignore[no-untyped-def]
    sim, cmd_port, fdb_port = server
    point = (10.0, -20.0, 40.0, 5.0, 50.0, -10.0)
    deadline = time.monotonic() + DEADLINE
    with socket.create_connection(("127.0.0.1", fdb_port), timeout=DEADLINE) as fdb, \
            socket.create_connection(("127.0.0.1", cmd_port), timeout=DEADLINE) as cmd:
        cmd.sendall(_command(0, point))
        failed: list = []
        while not failed:  # the command task reads the command and stops at $msg.jts[1]
            failed = [t for t in sim.threads if t.unhandled_error is not None]
            assert time.monotonic() < deadline, sim.console.log_text
            time.sleep(0.01)
        (task,) = failed
        assert task.Name == "task 5"
        assert (task.unhandled_error.ErrorCode, task.unhandled_error.Message()) == (-401, "*Undefined value*")
        cmd.setblocking(False)
        with pytest.raises(BlockingIOError):  # no reply, and the connection stays open
            cmd.recv(20)
        for _ in range(3):  # the feedback task streams on; the arm never moved
            header, joints = _feedback(fdb)
            assert header == (56, 10, 1, 0, 0) and joints == (0.0,) * 10
        assert "ROS connected to V+ command server" in sim.console.output
