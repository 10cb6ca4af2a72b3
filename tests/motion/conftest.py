"""Fixtures shared by the motion tests."""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.motion.move import Move
from gplrt.motion.path_run import PathRun
from gplrt.motion.profile import Profile
from gplrt.motion.robot import RobotState
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation


@pytest.fixture
def sim(request: pytest.FixtureRequest) -> Iterator[Simulation]:
    """A captured simulation whose robot 1 is attached, powered and homed, ready for Move.*.

    The robot model is the PF400SX unless a test names another through indirect
    parametrisation: ``@pytest.mark.parametrize("sim", ["XYZT-GCU"], indirect=True)``.
    Test modules that need the robot *not* ready (e.g. to check the errors before Attach/Home)
    define their own ``sim`` fixture, which takes precedence over this one.
    """
    s = Simulation(robot=getattr(request, "param", "PF400SX"), capture=True)
    with s:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        yield s


@pytest.fixture
def slow_line(sim: Simulation, monkeypatch: pytest.MonkeyPatch) -> tuple[RobotState, PathRun, float]:
    """A straight line queued on ``sim``'s robot 1 whose cycles are not solved yet, with each
    solve slowed down (``PathRun._solve`` sleeps 50 ms first) to widen the window in which two
    threads could run the same cycles: for tests of what holds the robot's lock.  Returns the
    robot, the line's PathRun and its end time (a read there runs all of its cycles)."""
    Move.Loc(Location.from_angles((300.0, 10.0, 90.0, -100.0, 100.0)), Profile())
    Move.WaitForEOM()
    goal = Robot.Where()
    goal.XYZ(goal.X + 150.0, goal.Y - 100.0, goal.Z - 50.0, goal.Yaw, 90.0, 180.0)
    line = Profile()
    line.Straight = True
    Move.Loc(goal, line)
    robot = sim.robots[1]
    seg = robot.queue.last
    run = seg.path_joints
    assert isinstance(run, PathRun) and len(run.ts) == 1  # nothing solved yet
    solve = PathRun._solve

    def slow_solve(self: PathRun, times: list[float]) -> object:
        time.sleep(0.05)
        return solve(self, times)

    monkeypatch.setattr(PathRun, "_solve", slow_solve)
    return robot, run, seg.t0 + seg.duration
