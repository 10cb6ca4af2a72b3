"""samples/tcp_command_server in virtual time, driven by a Python client over loopback, to completion.

A client powers and homes the robot, runs the pick-and-place command and shuts the server down.
Expected poses come from the taught positions documented in Globals.gpo (safe (250, 0, 300) yaw 0,
pick_1 (300, 150, 120) yaw 90, place_1 (350, -150, 125.5) yaw -60; the PF400SX hand horizontal:
pitch 90, roll 180), never from a previous run.  The gripper output must switch exactly where the
robot is at pick_1 and at place_1, and the program must end by itself after ``shutdown``.
"""

from __future__ import annotations

import numpy as np
import pytest

from gpltest import SAMPLES, LineClient, Transpiled, copy_project, free_port, hand_rotation, start_server, transpile
from gplrt.sim import Simulation

TIMEOUT = 30.0
GRIPPER_OUT = 1
SAFE = (250.0, 0.0, 300.0, 0.0)  # x, y, z, yaw
PICK = (300.0, 150.0, 120.0, 90.0)
PLACE = (350.0, -150.0, 125.5, -60.0)


def assert_at(sim: Simulation, t: float, pose: tuple[float, float, float, float]) -> None:
    robot = sim.robots[1]
    T = robot.forward(robot.joints_at(t))
    assert np.max(np.abs(T[:3, 3] - np.array(pose[:3]))) < 1e-6, (t, T[:3, 3], pose)
    assert np.max(np.abs(T[:3, :3] - hand_rotation(pose[3]))) < 1e-9


def where_fields(reply: str) -> dict[str, float]:
    """The "where" reply "0 x 250 y ... ok" as numbers by name."""
    words = reply.split()
    assert words[0] == "0" and words[-1] == "ok", reply
    return {k: float(v) for k, v in zip(words[1:-1:2], words[2:-1:2])}


@pytest.fixture(scope="module")
def session(tmp_path_factory: pytest.TempPathFactory) -> tuple[Simulation, list[str]]:
    """The whole conversation, run once: the replies in order, and the finished simulation."""
    port = free_port()
    src = copy_project(SAMPLES / "tcp_command_server", tmp_path_factory.mktemp("src") / "tcp_command_server",
                       {"SERVER_PORT As Integer = 10100": f"SERVER_PORT As Integer = {port}"})
    sample: Transpiled = transpile(src, tmp_path_factory.mktemp("out"))
    sample.assert_clean()
    sim = Simulation(capture=True)  # virtual clock; open sockets keep it to real time
    status: list[int] = []
    runner = start_server(lambda: status.append(sample.package.main(sim)), sim)
    client = LineClient(port, timeout=TIMEOUT, newline="\n")
    try:
        replies = [client.ask(cmd) for cmd in
                   ("power on", "home", "move pick", "where", "pick", "where", "move nowhere", "shutdown")]
        assert client.sock.recv(16) == b""  # the server closed the connection after shutdown
    finally:
        client.close()
    runner.join(TIMEOUT)
    if runner.is_alive():
        sim.stop(5.0)
        pytest.fail("the server did not end after shutdown: " + sim.console.output + sim.console.log_text)
    assert status == [0], sim.console.log_text
    return sim, replies


def test_replies_to_each_command(session: tuple[Simulation, list[str]]) -> None:
    _, replies = session
    assert replies[:3] == ["0 power on", "0 homed", "0 at pick"]
    assert replies[4] == "0 done"
    assert replies[6:] == ["-1 unknown location nowhere", "0 shutting down"]
    at_pick, at_safe = where_fields(replies[3]), where_fields(replies[5])
    for fields, (x, y, z, yaw) in ((at_pick, PICK), (at_safe, SAFE)):
        got = [fields[k] for k in ("x", "y", "z", "yaw", "pitch", "roll")]
        assert np.allclose(got, [x, y, z, yaw, 90.0, 180.0], atol=1e-6), fields
    assert at_safe["power"] == -1 and at_safe["homed"] == -1 and at_safe["attached"] == 1


def test_gripper_closes_at_pick_and_opens_at_place(session: tuple[Simulation, list[str]]) -> None:
    sim, _ = session
    changes = [c for c in sim.io.trace if c.kind == "DIO" and c.signal == GRIPPER_OUT and c.source == "gpl"]
    assert [c.value for c in changes] == [True, False]
    assert_at(sim, changes[0].time, PICK)
    assert_at(sim, changes[1].time, PLACE)
    assert changes[1].time - changes[0].time > 0.25  # it held the part while moving it


def test_program_ends_with_the_robot_at_safe(session: tuple[Simulation, list[str]]) -> None:
    sim, _ = session
    assert_at(sim, sim.now(), SAFE)
    assert sim.io.read_dio(GRIPPER_OUT) is False
    port_line, *rest = sim.console.output.splitlines()
    assert port_line.startswith("TCP command server listening on port ")
    assert rest == ["TCP command server stopped"]
    assert sim.console.log_text == "" and sim.controller.error_log == []
