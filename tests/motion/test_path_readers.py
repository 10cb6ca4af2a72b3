"""Reading a robot runs its path motions' cycles (path_run): two threads reading at once — under
the real clock any two GPL threads can — must leave one record of those cycles, not two."""

from __future__ import annotations

import threading

import numpy as np

from gplrt.motion.path_run import PathRun
from gplrt.motion.robot import RobotState


def test_two_threads_reading_a_line_at_once_solve_its_cycles_once(
        slow_line: tuple[RobotState, PathRun, float]) -> None:
    robot, run, t_end = slow_line
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
    assert np.array_equal(results[0], robot.queue.last.q_end)
