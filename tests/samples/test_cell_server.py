"""samples/cell_server: the transpiled cell served to Python socket clients over loopback.

The server runs in virtual time, like every sample: while its sockets are open the virtual clock
keeps to real time (gplrt.threads.scheduler, hold_real_time), so the clients' timeouts are real and
motions still take controller time.  Poses are checked against
the commanded targets, read off the simulated robot itself to 1e-6 mm.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator

import numpy as np
import pytest

from gpltest import (SAMPLES, LineClient, Transpiled, ask_all, copy_project, free_port, hand_rotation, shutdown_server,
                     start_server, transpile)
from gplrt.sim import Simulation

TIMEOUT = 15.0


@pytest.fixture(scope="module")
def cell(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Simulation, int, threading.Thread]]:
    port = free_port()
    src = copy_project(SAMPLES / "cell_server", tmp_path_factory.mktemp("src") / "cell_server",
                       {"SERVER_PORT As Integer = 10200": f"SERVER_PORT As Integer = {port}"})
    sample: Transpiled = transpile(src, tmp_path_factory.mktemp("cell_server"))
    sim = Simulation(capture=True)  # virtual clock: open sockets keep it to real time
    runner = start_server(lambda: sample.package.main(sim), sim)
    yield sim, port, runner
    shutdown_server(port, runner, TIMEOUT)


def tool_pose(sim: Simulation) -> np.ndarray:
    robot = sim.robots[1]
    return robot.forward(robot.joints_at(sim.now()))


def test_hello_speed_and_unknown_commands(cell: tuple[Simulation, int, threading.Thread]) -> None:
    sim, port, _ = cell
    with LineClient(port) as c:
        assert c.ask("hello") == "OK hello from cell_server"
        assert c.ask("HELLO") == "OK hello from cell_server"  # names are case-insensitive
        assert c.ask("speed 80") == "OK speed 80"
        assert c.ask("speed") == "OK speed 80"
        assert c.ask("speed 0") == "ERR speed must be 1..100"
        assert c.ask("frobnicate now") == "ERR unknown command frobnicate"


def test_move_and_where_report_and_reach_the_target(cell: tuple[Simulation, int, threading.Thread]) -> None:
    sim, port, _ = cell
    with LineClient(port) as c:
        assert c.ask("move 400 50 200") == "OK moved to 400.000 50.000 200.000"
        T = tool_pose(sim)
        assert np.max(np.abs(T[:3, 3] - [400.0, 50.0, 200.0])) < 1e-6
        assert np.max(np.abs(T[:3, :3] - hand_rotation(0.0))) < 1e-9
        assert c.ask("where") == "OK 400.000 50.000 200.000"
        assert c.ask("move 450.25 -30.5 310") == "OK moved to 450.250 -30.500 310.000"
        assert np.max(np.abs(tool_pose(sim)[:3, 3] - [450.25, -30.5, 310.0])) < 1e-6


def test_unreachable_move_is_retried_then_reported(cell: tuple[Simulation, int, threading.Thread]) -> None:
    sim, port, _ = cell
    with LineClient(port) as c:
        assert c.ask("move 350 0 250") == "OK moved to 350.000 0.000 250.000"
        assert c.ask("move 2000 0 250") == "ERR error -1040 after 3 tries"  # -1040 *Position too far*
        assert np.max(np.abs(tool_pose(sim)[:3, 3] - [350.0, 0.0, 250.0])) < 1e-6
        assert c.ask("move 1 2") == "ERR usage: move x y z"
        assert c.ask("move a b c").startswith("ERR -")  # the CDbl error, caught by Dispatch


def test_io_reads_inputs_and_sets_outputs(cell: tuple[Simulation, int, threading.Thread]) -> None:
    sim, port, _ = cell
    with LineClient(port) as c:
        assert c.ask("io 10003") == "OK io 10003 off"
        sim.io.set_input(10003, True)
        assert c.ask("io 10003") == "OK io 10003 on"
        assert c.ask("io 5 1") == "OK io 5 on"
        assert sim.io.read_dio(5) is True
        assert c.ask("io 5 0") == "OK io 5 off"
        assert sim.io.read_dio(5) is False


def test_two_clients_move_through_the_one_robot_thread(cell: tuple[Simulation, int, threading.Thread]) -> None:
    sim, port, _ = cell
    targets = {0: (380.0, 80.0, 150.0), 1: (420.0, -60.0, 180.0)}
    replies = ask_all(port, {k: [f"move {x:g} {y:g} {z:g}"] * 3 for k, (x, y, z) in targets.items()}, TIMEOUT)
    for k, (x, y, z) in targets.items():
        assert replies[k] == [f"OK moved to {x:.3f} {y:.3f} {z:.3f}"] * 3
    final = tool_pose(sim)[:3, 3]
    assert min(np.max(np.abs(final - np.array(t))) for t in targets.values()) < 1e-6


def test_quit_closes_only_that_connection_and_shutdown_stops_the_cell(
        cell: tuple[Simulation, int, threading.Thread]) -> None:
    sim, port, runner = cell
    a, b = LineClient(port), LineClient(port)
    try:
        assert a.ask("quit") == "OK bye"
        assert a.sock.recv(16) == b""  # the server closed it
        assert b.ask("hello") == "OK hello from cell_server"
        assert b.ask("shutdown") == "OK shutting down"
    finally:
        a.close()
        b.close()
    runner.join(TIMEOUT)
    assert not runner.is_alive()
    lines = sim.console.output.splitlines()
    assert lines[0].startswith("cell server listening on port ")
    assert lines[-1].startswith("cell server stopped after ")
    assert sim.controller.error_log == []
