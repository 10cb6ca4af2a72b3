"""A GPL thread that nobody else can overtake waits without a thread switch (issue 14, item 2).

When a wait's end comes before any other thread can run (one GPL thread, as a rule), the virtual
scheduler moves time on and hands the token straight back: ``WaitForEOM``, ``Thread.Sleep`` and
a full motion queue then cost no Event set/wait.  What the program sees is unchanged: the same
times, the same interleaving when another thread does wake first.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.lang.console import Console
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.threads import Thread
from gplrt.threads.scheduler import VirtualScheduler


@pytest.fixture
def token_waits(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The names of the threads that waited for the token (``_await_token``), in order."""
    waits: list[str] = []
    await_token = VirtualScheduler._await_token

    def counted(self: VirtualScheduler, ctx: object) -> None:
        waits.append(getattr(ctx, "name", "?"))
        await_token(self, ctx)

    monkeypatch.setattr(VirtualScheduler, "_await_token", counted)
    return waits


def _moves_and_sleeps(log: list[tuple[str, float]], ready: Callable[[], None] = lambda: None) -> None:
    Robot.Attached = 1
    Controller.PowerEnabled = True
    Robot.Home()
    ready()
    prof = Profile()
    for k in range(10):
        Move.Loc(Location.from_angles((300.0 + 20.0 * k, 10.0, 90.0, -100.0, 100.0)), prof)
        Move.WaitForEOM()
        log.append(("eom", Controller.Timer(1)))
        Thread.Sleep(10)
        log.append(("sleep", Controller.Timer(1)))
    for k in range(12):  # more than the queue holds: Move waits for room
        Move.Loc(Location.from_angles((300.0 + 20.0 * (k % 2), 10.0, 90.0, -100.0, 100.0)), prof)
    Move.WaitForEOM()
    log.append(("queue", Controller.Timer(1)))


def test_a_lone_thread_waits_without_waiting_for_the_token(token_waits: list[str]) -> None:
    sim = Simulation(capture=True)
    log: list[tuple[str, float]] = []
    # Counted once the robot is ready: until ``run_main``'s caller starts driving the run (it
    # starts the thread first), a wait may find time frozen and wait for it; homing has moved
    # time on, so the driver is there from then on.
    sim.run_main(lambda: _moves_and_sleeps(log, token_waits.clear))
    assert sim.console.log_text == ""
    assert len(log) == 21
    # time moved on at every wait, and no wait waited for the token
    times = [t for _, t in log]
    assert all(b > a for a, b in zip(times, times[1:]))
    assert [t for _, t in log if _ == "sleep"][0] == pytest.approx(log[0][1] + 0.010, abs=1.25e-4)
    assert token_waits == []


def test_another_thread_that_wakes_first_still_runs_first(token_waits: list[str]) -> None:
    """The fast path must not overtake a thread whose wait ends earlier."""
    sim = Simulation(capture=True)

    def ticker() -> None:
        for _ in range(3):
            Thread.Sleep(30)
            Console.WriteLine(f"tick {Controller.Timer(1):.3f}")

    def main() -> None:
        Thread(ticker, 0, "Ticker").Start()
        for _ in range(4):
            Thread.Sleep(20)
            Console.WriteLine(f"main {Controller.Timer(1):.3f}")

    sim.run_main(main)
    assert sim.console.output.split("\n")[:7] == [
        "main 0.020", "tick 0.030", "main 0.040", "tick 0.060", "main 0.060", "main 0.080", "tick 0.090"]
    assert "Ticker" in token_waits  # the two threads did hand the token over


def test_lone_waits_skip_the_wait_machinery(monkeypatch: pytest.MonkeyPatch) -> None:
    """With nothing else to happen first, WaitForEOM and Sleep just move time on: they never
    park the thread (``_block``), register a timer or touch a wait queue."""
    blocks: list[str] = []
    block = VirtualScheduler._block

    def counted(self: VirtualScheduler, ctx: object, *args: object, **kwargs: object) -> bool:
        blocks.append(getattr(ctx, "waiting_on", ""))
        return block(self, ctx, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(VirtualScheduler, "_block", counted)
    sim = Simulation(capture=True)
    log: list[tuple[str, float]] = []
    sim.run_main(lambda: _moves_and_sleeps(log, blocks.clear))  # (the power-up waits for its timers)
    assert sim.console.log_text == ""
    assert len(log) == 21
    assert blocks == []


def test_a_timer_due_during_a_lone_wait_fires_at_its_time() -> None:
    """An I/O rule's delayed action (a scheduler timer) that falls inside a WaitForEOM or a
    Sleep fires at its own time, not when the wait ends."""
    sim = Simulation(capture=True)
    fired: list[float] = []
    ends: list[float] = []

    def main() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        sched = sim.scheduler
        t0 = sched.clock.now()
        sched.call_at(t0 + 0.25, lambda: fired.append(sched.clock.now() - t0))
        Move.Loc(Location.from_angles((900.0, 60.0, 150.0, 30.0, 100.0)), Profile())
        end = sim.robots[1].queue.end_time
        Move.WaitForEOM()
        ends.append(sched.clock.now() - end)
        sched.call_at(sched.clock.now() + 0.004, lambda: fired.append(sched.clock.now() - t0))
        Thread.Sleep(10)

    sim.run_main(main)
    assert sim.console.log_text == ""
    assert fired[0] == pytest.approx(0.25, abs=1e-9)
    assert len(fired) == 2 and fired[1] < fired[0] + 10.0
    assert ends[0] == pytest.approx(0.0, abs=1e-9)
