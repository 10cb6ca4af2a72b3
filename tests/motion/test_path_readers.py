"""Reading a robot runs its path motions' cycles (path_run): two threads reading at once — under
the real clock any two GPL threads can — must leave one record of those cycles, not two."""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest

from gplrt.geometry.location import Location
from gplrt.motion.move import Move
from gplrt.motion.path_run import PathRun
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation


def test_two_threads_reading_a_line_at_once_solve_its_cycles_once(sim: Simulation,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
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
        time.sleep(0.05)  # widen the window in which a second reader could start the same cycles
        return solve(self, times)

    monkeypatch.setattr(PathRun, "_solve", slow_solve)
    t_end = seg.t0 + seg.duration
    results: list[np.ndarray] = []
    errors: list[BaseException] = []

    def read() -> None:
        try:
            results.append(robot.joints_at(t_end))
        except BaseException as exc:  # noqa: BLE001 - reported below
            errors.append(exc)

    readers = [threading.Thread(target=read) for _ in range(2)]
    for r in readers:
        r.start()
    for r in readers:
        r.join(10.0)
    assert not errors, errors
    assert len(results) == 2 and np.array_equal(results[0], results[1])
    assert np.all(np.diff(run.ts) > 0.0), run.ts  # each cycle once, in order
    assert len(run.ts) == len(run.us) == len(run.qs)
    assert np.array_equal(results[0], seg.q_end)
