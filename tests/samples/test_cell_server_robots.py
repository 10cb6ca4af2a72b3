"""samples/cell_server on controllers with two robots: one robot thread and one job queue per robot.

Two cells, both in virtual time (open sockets hold the clock to real time, as in test_cell_server):

* the shipped XYZT-GCU parameter set, whose robot 1 is a 4-axis XYZT motion device and robot 2 an
  *Encoder Only Module* (no kinematic module, no amplifier: it reads an encoder and cannot move).
  The sample must find both robots, run a thread for each, move robot 1 while robot 2 is read, and
  report the controller's own refusal (-1036 *Kinematics not installed*) for a Cartesian move of
  robot 2.
* a cell of two PF400SX arms on one controller: the shipped PF400SX set, with its robot01/calib01
  files loaded a second time as robot02/calib02 and DataID 116 (robot types) naming the PF400
  module for robot 2 — how a second arm is configured on a real controller.  Here two clients move
  the two robots at the same time, and the motions must overlap in controller time.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
import pytest

from gpltest import (SAMPLES, LineClient, Transpiled, ask_all, copy_project, free_port, shutdown_server, start_server,
                     transpile)
from gplrt.controller.pdb import DATA_DIR, ParameterDatabase, default_database
from gplrt.motion.registry import robot_of
from gplrt.sim import Simulation

TIMEOUT = 15.0


@dataclass
class Cell:
    sim: Simulation
    port: int
    runner: threading.Thread


def build(tmp_path_factory: pytest.TempPathFactory) -> tuple[Transpiled, int]:
    """A fresh transpiled package (module state is per package) listening on a free port."""
    port = free_port()
    src = copy_project(SAMPLES / "cell_server", tmp_path_factory.mktemp("src") / "cell_server",
                       {"SERVER_PORT As Integer = 10200": f"SERVER_PORT As Integer = {port}"})
    return transpile(src, tmp_path_factory.mktemp("cell_server")), port


def two_pf400_database() -> ParameterDatabase:
    """The PF400SX set with a second, identical arm as robot 2."""
    db = default_database("PF400SX")
    for name in ("robot01.pac", "calib01.pac"):
        db.load_text((DATA_DIR / "pf400sx" / name).read_text(encoding="ascii"), name.replace("01", "02"))
    db.entry(116).values[1] = db.entry(116).values[0]  # robot 2's kinematic module: the PF400's
    return db


def serve(sample: tuple[Transpiled, int], sim: Simulation) -> Iterator[Cell]:
    package, port = sample[0].package, sample[1]
    runner = start_server(lambda: package.main(sim), sim)
    cell = Cell(sim, port, runner)
    yield cell
    shutdown_server(port, runner, TIMEOUT)
    assert not runner.is_alive()
    assert sim.console.output.splitlines()[-1].startswith("cell server stopped after ")


def tool_xyz(sim: Simulation, robot: int) -> np.ndarray:
    state = sim.robots[robot]
    return np.asarray(state.forward(state.joints_at(sim.now()))[:3, 3])


def thread_names(sim: Simulation) -> list[str]:
    return [str(t.Name) for t in sim.threads]


# -- the shipped XYZT-GCU set ---------------------------------------------------------------------

@pytest.fixture(scope="module")
def gcu(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Cell]:
    yield from serve(build(tmp_path_factory), Simulation(robot="XYZT-GCU", capture=True))


def test_gcu_cell_finds_both_robots_and_runs_a_thread_for_each(gcu: Cell) -> None:
    with LineClient(gcu.port) as c:
        assert c.ask("robots") == "OK robots 2"
        assert c.ask("where 3") == "ERR no robot 3"
    names = thread_names(gcu.sim)
    assert names.count("robot1") == 1 and names.count("robot2") == 1
    assert "robot3" not in names
    assert gcu.sim.robots[1].owner is not None and gcu.sim.robots[2].owner is not None, gcu.sim.console.output + gcu.sim.console.log_text


def test_gcu_robot1_moves_while_robot2_is_read_and_refuses_a_cartesian_move(gcu: Cell) -> None:
    replies = ask_all(gcu.port, {
        1: ["move 120 -45.5 30", "where"],
        2: ["where 2", "move 2 10 0 0", "where 2"],
    })
    assert replies[1] == ["OK moved to 120.000 -45.500 30.000", "OK 120.000 -45.500 30.000"]
    assert replies[2] == ["OK joints 0.000", "ERR error -1036 after 0 tries", "OK joints 0.000"]
    assert np.max(np.abs(tool_xyz(gcu.sim, 1) - [120.0, -45.5, 30.0])) < 1e-6
    assert gcu.sim.robots[2].joints_at(gcu.sim.now())[0] == 0.0


# -- two PF400SX arms ----------------------------------------------------------------------------

@pytest.fixture(scope="module")
def twin(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Cell]:
    sim = Simulation(capture=True)
    sim.pdb = two_pf400_database()
    yield from serve(build(tmp_path_factory), sim)


def test_two_clients_move_two_robots_at_the_same_time(twin: Cell) -> None:
    targets = {1: (400.0, 150.0, 220.0), 2: (420.0, -60.0, 180.0)}
    replies = ask_all(twin.port, {k: [f"move {k} {x:g} {y:g} {z:g}", f"where {k}"]
                                  for k, (x, y, z) in targets.items()})
    for k, (x, y, z) in targets.items():
        assert replies[k] == [f"OK moved to {x:.3f} {y:.3f} {z:.3f}", f"OK {x:.3f} {y:.3f} {z:.3f}"]
        assert np.max(np.abs(tool_xyz(twin.sim, k) - np.array(targets[k]))) < 1e-6
    names = thread_names(twin.sim)
    assert names.count("robot1") == 1 and names.count("robot2") == 1
    # each robot ran on its own thread: the two motions overlapped in controller time
    last = {k: robot_of(twin.sim, k).queue.history[-1] for k in targets}
    assert max(seg.t0 for seg in last.values()) < min(seg.end for seg in last.values())


def test_unnumbered_commands_still_address_robot_1(twin: Cell) -> None:
    with LineClient(twin.port) as c:
        assert c.ask("robots") == "OK robots 2"
        before2 = tool_xyz(twin.sim, 2)
        assert c.ask("move 380 40 200") == "OK moved to 380.000 40.000 200.000"
        assert np.max(np.abs(tool_xyz(twin.sim, 1) - [380.0, 40.0, 200.0])) < 1e-6
        assert np.max(np.abs(tool_xyz(twin.sim, 2) - before2)) < 1e-9
        assert c.ask("where") == "OK 380.000 40.000 200.000"
        assert c.ask("move x 1 2 3") == "ERR -717 *Invalid number format*"  # CInt("x"), caught by Dispatch
        assert c.ask("move 0 1 2 3") == "ERR no robot 0"
