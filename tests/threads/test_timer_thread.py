"""The schedulers' real-time wake-ups run on one reusable thread, and end with the session.

Before: every idle spell of a paced virtual run and every real-clock ``call_at`` started its own
``threading.Timer`` (hundreds of OS threads for a polling loop), superseded ones were never
cancelled, and one still pending after the run kept the whole session (robots, Ruckig
trajectories) reachable at interpreter exit.
"""

from __future__ import annotations

import gc
import threading
import time
import weakref
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from gplrt.sim import Simulation, set_current
from gplrt.threads import Thread
from gplrt.threads.pacer import RealTimer
from gplrt.threads.scheduler import hold_real_time


@pytest.fixture
def thread_starts(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[str]]:
    """Names of every Python thread started while the test runs."""
    started: list[str] = []
    original = threading.Thread.start

    def counting_start(self: threading.Thread) -> None:
        started.append(self.name)
        original(self)

    monkeypatch.setattr(threading.Thread, "start", counting_start)
    yield started


def _gpl_threads(names: list[str]) -> list[str]:
    return [n for n in names if n.startswith("gpl:")]


def _eventually(condition: Callable[[], bool], bound: float = 5.0) -> bool:
    """Poll ``condition`` until it holds or ``bound`` real seconds pass.

    Why not ``time.sleep(x)`` then assert: on a loaded CI machine the timer thread may be late by
    more than any fixed margin; waiting for the event itself keeps the test exact and not flaky.
    """
    end = time.monotonic() + bound
    while not condition():
        if time.monotonic() >= end:
            return False
        time.sleep(0.005)
    return True


def test_a_paced_polling_loop_uses_one_timer_thread(thread_starts: list[str]) -> None:
    """200 paced 1 ms sleeps: each is an idle spell with a real-time wake-up."""
    sim = Simulation(capture=True)  # virtual clock
    woke: list[float] = []

    def poller() -> None:
        release = hold_real_time()  # as an open socket does: virtual time keeps to real time
        try:
            for _ in range(200):
                Thread.Sleep(1)
                woke.append(sim.now())
        finally:
            release()

    assert sim.run_main(poller, timeout=30) == []
    assert len(woke) == 200
    assert woke == sorted(woke) and woke[-1] >= 0.2 - 1e-9  # every sleep took its controller time
    others = [n for n in thread_starts if n not in _gpl_threads(thread_starts)]
    assert len(others) <= 1, f"{len(others)} helper threads started: {others[:5]}"
    sim.close()


def test_close_ends_the_timer_thread_and_frees_the_session() -> None:
    """A paced wait far in the future is still planned when the run is given up on."""
    sim = Simulation(capture=True)

    def sleeper() -> None:
        release = hold_real_time()
        try:
            Thread.Sleep(1_000_000)  # 1000 s: the pacing wake-up would sit in a timer that long
        finally:
            release()

    assert sim.run_main(sleeper, timeout=0.3) != []  # gave up on it while it slept
    sim.close()
    assert not sim.scheduler.timer_thread_alive()
    ref = weakref.ref(sim)
    set_current(None)
    del sim
    gc.collect()
    assert ref() is None, "something still refers to the closed session"


def test_a_run_given_up_on_leaves_no_pacing_wake_up_behind() -> None:
    """Nobody drives the run any more, so time stands still: nothing to wake in 1000 s."""
    sim = Simulation(capture=True)
    slept: list[float] = []

    def sleeper() -> None:
        release = hold_real_time()
        try:
            Thread.Sleep(1_000_000)
            slept.append(sim.now())
        finally:
            release()

    assert sim.run_main(sleeper, timeout=0.3) != []
    assert sim.scheduler.real_time_callbacks_pending() == 0
    t_idle = sim.now()
    time.sleep(0.2)
    assert sim.now() == t_idle  # frozen while nobody drives it
    sim.close()
    assert slept == []


def test_real_clock_call_at_shares_one_thread_and_keeps_order(thread_starts: list[str]) -> None:
    sim = Simulation(clock="real", capture=True)
    fired: list[int] = []
    done = threading.Event()
    t0 = sim.now()
    for i in reversed(range(50)):
        sim.scheduler.call_at(t0 + 0.05 + i * 0.002, lambda i=i: fired.append(i))
    sim.scheduler.call_at(t0 + 0.2, done.set)
    assert done.wait(5)
    assert fired == list(range(50))
    assert len(thread_starts) == 1
    sim.close()


def test_stop_keeps_a_pending_real_clock_action_and_close_drops_it() -> None:
    sim = Simulation(clock="real", capture=True)
    fired: list[str] = []
    sim.scheduler.call_at(sim.now() + 0.15, lambda: fired.append("rule"))
    sim.stop()
    assert _eventually(lambda: fired == ["rule"])  # an I/O rule's delayed action outlives stopping the program
    sim.scheduler.call_at(sim.now() + 0.15, lambda: fired.append("late"))
    sim.close()
    assert not sim.scheduler.timer_thread_alive()
    time.sleep(0.3)
    assert fired == ["rule"]


# -- RealTimer itself -----------------------------------------------------------------------------------


def test_real_timer_cancel_and_reschedule() -> None:
    timer = RealTimer(linger=5.0)
    got: list[str] = []
    h = timer.schedule(0.05, lambda: got.append("cancelled"))
    timer.schedule(0.08, lambda: got.append("kept"))
    timer.cancel(h)
    timer.schedule(0.01, lambda: got.append("first"))
    assert _eventually(lambda: "kept" in got)  # due after the cancelled one: its time has passed
    assert got == ["first", "kept"]
    assert timer.threads_started == 1
    timer.close()
    assert not timer.is_running()


def test_real_timer_thread_ends_when_idle_and_restarts_on_demand() -> None:
    timer = RealTimer(linger=0.05)
    got: list[int] = []
    timer.schedule(0.0, lambda: got.append(1))
    assert _eventually(lambda: not timer.is_running())
    assert got == [1]
    timer.schedule(0.0, lambda: got.append(2))
    assert _eventually(lambda: got == [1, 2])
    assert timer.threads_started == 2
    timer.close()


def test_a_failing_callback_is_reported_and_the_timer_keeps_going(monkeypatch: pytest.MonkeyPatch) -> None:
    reported: list[Any] = []
    monkeypatch.setattr(threading, "excepthook", lambda args: reported.append(args.exc_type))
    timer = RealTimer(linger=5.0)
    got: list[str] = []

    def boom() -> None:
        raise RuntimeError("rule failed")

    timer.schedule(0.0, boom)
    timer.schedule(0.02, lambda: got.append("after"))
    assert _eventually(lambda: got == ["after"])
    assert reported == [RuntimeError]
    timer.close()
