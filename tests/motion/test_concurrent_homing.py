"""Two threads of a multi-robot cell home their robots at the same time (XYZT-GCU: robots 1, 2).

The controller's PowerState is one for all robots; a second Robot.Home that starts while the first
is homing (PowerState 28) used to read 28 as "power not enabled" (-1046).
"""

from __future__ import annotations

from gplrt.controller.services import Controller
from gplrt.lang.errors import POWER_NOT_ENABLED, GplException
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.threads import Thread


def run_two_homings(drop_power: bool) -> tuple[list[tuple[int, object]], int]:
    sim = Simulation(robot="XYZT-GCU", capture=True)
    results: list[tuple[int, object]] = []
    states: list[int] = []

    def homer() -> None:
        n = int(Thread.CurrentThread().Argument)
        Robot.Attached = n
        try:
            Robot.Home()
            results.append((n, "homed"))
        except GplException as exc:
            results.append((n, exc.ErrorCode))

    def main() -> None:
        Controller.PowerEnabled = True
        while Controller.PowerState() < 20:
            Thread.Sleep(50)
        workers = [Thread(homer, k, f"home{k}") for k in (1, 2)]
        for w in workers:
            w.Start()
        Thread.Sleep(10)
        states.append(int(Controller.PowerState()))  # both are homing now
        if drop_power:
            Controller.PowerEnabled = False
        for w in workers:
            w.Join()
        states.append(int(Controller.PowerState()))

    assert sim.run_main(main) == []
    assert states[0] == 28
    return sorted(results), states[-1]


def test_two_robots_home_at_once_and_power_comes_back_to_ready() -> None:
    results, final = run_two_homings(drop_power=False)
    assert results == [(1, "homed"), (2, "homed")]
    assert final == 20  # power on, no robot attached by the main thread


def test_power_off_during_a_shared_homing_fails_both_and_stays_off() -> None:
    results, final = run_two_homings(drop_power=True)
    assert results == [(1, POWER_NOT_ENABLED), (2, POWER_NOT_ENABLED)]
    assert final == 7  # off, waiting for the power request (gpl-dictionary.md PowerState table)
