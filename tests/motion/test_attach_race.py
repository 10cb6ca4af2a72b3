"""Two threads attaching the same free robot at the same moment (the real clock runs GPL threads
preemptively): exactly one gets it, the other -1006 *Robot already attached*."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

from gplrt.lang.errors import GplException
from gplrt.motion.robot import RobotState
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.threads import Thread


def test_two_threads_attaching_one_robot_at_once_one_wins(monkeypatch: pytest.MonkeyPatch) -> None:
    def read_owner(self: RobotState) -> Any:
        owner = self.__dict__["owner"]
        time.sleep(0.02)  # widen the window between the test of the owner and its setting
        return owner

    def write_owner(self: RobotState, value: Any) -> None:
        self.__dict__["owner"] = value

    sim = Simulation(clock="real", capture=True)
    results: list[object] = []
    go = threading.Event()

    def attacher() -> None:
        go.wait()
        try:
            Robot.Attached = 1
            results.append("attached")
            Thread.Sleep(200)  # hold it while the other thread tries
            Robot.Attached = 0
        except GplException as exc:
            results.append(exc.ErrorCode)

    def main() -> None:
        from gplrt.motion import registry

        registry.robot_of(sim, 1)  # built before the race
        monkeypatch.setattr(RobotState, "owner", property(read_owner, write_owner))
        workers = [Thread(attacher, 0, f"t{i}") for i in range(2)]
        for w in workers:
            w.Start()
        go.set()
        for w in workers:
            w.Join()

    assert sim.run_main(main) == []
    assert sorted(results, key=str) == [-1006, "attached"]
