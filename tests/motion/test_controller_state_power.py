"""Concurrent ``Controller.PowerEnabled = True`` requests share one power-up sequence.

Before: a second request restarted the sequence (PowerState back to 8) and, when it woke, found
the first request's 10 instead of its own 8 and raised -1046 although power came on.  Now the
second joins the power-up in progress and both return when it reaches 20; a power-off request
during a power-up wins (power ends off, every requester raises -1600 *Power off requested*).
The power-up is the controller's, not a thread's: suspending or aborting the thread that asked
first does not stop it.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

import pytest

from gplrt.controller.services import Controller
from gplrt.lang.errors import GplException
from gplrt.sim import Simulation
from gplrt.threads import Thread


def requester(results: list[tuple[str, object, float]]) -> Callable[[], None]:
    """A GPL thread body: after ``Argument`` ms, PowerEnabled = True; records how and when it
    returned in ``results``."""

    def body() -> None:
        me = Thread.CurrentThread()
        Thread.Sleep(int(me.Argument))
        try:
            Controller.PowerEnabled = True
            results.append((me.Name, "on", round(Controller.Timer(1), 6)))
        except GplException as exc:
            results.append((me.Name, exc.ErrorCode, round(Controller.Timer(1), 6)))

    return body


def run_requests(starts_ms: list[int], off_at_ms: int | None = None,
                 late_on_ms: int | None = None) -> tuple[list[tuple[str, object, float]], list[int], int]:
    """Threads asking for power at ``starts_ms``; optionally a power-off request at ``off_at_ms``
    and one more power request at ``late_on_ms``.  Returns (results, PowerState trace, final state)."""
    sim = Simulation(capture=True)
    results: list[tuple[str, object, float]] = []
    trace: list[int] = []  # PowerState, sampled every 10 ms, repeats dropped

    def watcher() -> None:
        for _ in range(80):
            state = int(Controller.PowerState())
            if not trace or trace[-1] != state:
                trace.append(state)
            Thread.Sleep(10)

    def main() -> None:
        w = Thread(watcher, 0, "watcher")
        w.Start()
        workers = [Thread(requester(results), t, f"req{i}") for i, t in enumerate(starts_ms)]
        if late_on_ms is not None:
            workers.append(Thread(requester(results), late_on_ms, "late"))
        for t in workers:
            t.Start()
        if off_at_ms is not None:
            Thread.Sleep(off_at_ms)
            Controller.PowerEnabled = False
        for t in workers:
            t.Join()
        w.Join()

    assert sim.run_main(main) == []
    return sorted(results), trace, int(sim.controller.power_state)


def test_two_requests_at_the_same_instant_share_one_power_up() -> None:
    results, trace, final = run_requests([0, 0])
    assert results == [("req0", "on", 0.3), ("req1", "on", 0.3)]
    assert trace == [7, 8, 10, 20]
    assert final == 20


def test_a_request_during_a_power_up_joins_it_instead_of_restarting_it() -> None:
    results, trace, final = run_requests([0, 100, 200])
    # everyone returns when the one sequence (started at 0) reaches 20, not 0.3 s after its own request
    assert results == [("req0", "on", 0.3), ("req1", "on", 0.3), ("req2", "on", 0.3)]
    assert trace == [7, 8, 10, 20]
    assert final == 20


def test_a_request_once_power_is_on_returns_at_once() -> None:
    results, _, final = run_requests([0, 400])
    assert results == [("req0", "on", 0.3), ("req1", "on", 0.4)]
    assert final == 20


def test_power_off_during_a_shared_power_up_wins() -> None:
    results, trace, final = run_requests([0, 50], off_at_ms=100)
    # both are told at the moment of the power-off request
    assert results == [("req0", -1600, 0.1), ("req1", -1600, 0.1)]
    assert trace == [7, 8, 7]  # never 10 or 20 afterwards
    assert final == 7


def test_a_request_after_the_power_off_starts_a_fresh_power_up() -> None:
    results, trace, final = run_requests([0], off_at_ms=100, late_on_ms=120)
    # "late" asked after the power-off ended the running power-up: a fresh one starts at its
    # request (0.12) and takes the whole power-up time
    assert results == [("late", "on", 0.42), ("req0", -1600, 0.1)]
    assert trace == [7, 8, 7, 8, 10, 20]
    assert final == 20


def test_soft_estop_during_a_power_up_fails_it_with_1046() -> None:
    sim = Simulation(capture=True)
    codes: list[int] = []

    def asker() -> None:
        try:
            Controller.PowerEnabled = True
        except GplException as exc:
            codes.append(exc.ErrorCode)

    def main() -> None:
        t = Thread(asker)
        t.Start()
        Thread.Sleep(200)
        Controller.SoftEStop = True
        t.Join()

    assert sim.run_main(main) == []
    assert codes == [-1046]
    assert sim.controller.power_state == 7


@pytest.mark.parametrize("threads", [2, 4])
def test_concurrent_requests_on_the_real_clock(threads: int) -> None:
    sim = Simulation(clock="real", speed=10.0, capture=True)  # power-up: 0.03 s of wall time
    results: list[object] = []
    go = threading.Event()

    def asker() -> None:
        go.wait()
        try:
            Controller.PowerEnabled = True
            results.append(int(Controller.PowerState()))
        except GplException as exc:
            results.append(exc.ErrorCode)

    def main() -> None:
        workers = [Thread(asker, 0, f"a{i}") for i in range(threads)]
        for w in workers:
            w.Start()
        go.set()  # all at once: preemptive threads really race
        for w in workers:
            w.Join()

    assert sim.run_main(main) == []
    assert results == [20] * threads
    assert sim.controller.power_state == 20


@pytest.mark.parametrize("interrupt", ["Suspend", "Abort"])
def test_interrupting_the_first_requester_does_not_hold_up_the_power_up(interrupt: str) -> None:
    """The power-up is the controller's, not the thread's that asked first: suspending or
    aborting that thread only stops it waiting, and the power-up runs to time for the others."""
    sim = Simulation(capture=True)
    results: list[tuple[str, object, float]] = []

    def main() -> None:
        first = Thread(requester(results), 0, "first")
        joiner = Thread(requester(results), 50, "joiner")
        first.Start()
        joiner.Start()
        Thread.Sleep(100)
        getattr(first, interrupt)()
        Thread.Sleep(900)
        results.append(("main", int(Controller.PowerState()), round(Controller.Timer(1), 6)))
        if interrupt == "Suspend":
            first.Resume()  # it returns now: power is on
        first.Join()
        joiner.Join()

    assert sim.run_main(main) == []
    first_result = [("first", "on", 1.0)] if interrupt == "Suspend" else []
    assert sorted(results) == [*first_result, ("joiner", "on", 0.3), ("main", 20, 1.0)]
