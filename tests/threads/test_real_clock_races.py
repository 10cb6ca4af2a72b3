"""Under the real clock Python may switch GPL threads between any two bytecodes.

(Under the virtual clock only one GPL thread runs at a time, but an outside caller —
``Simulation.stop`` on Ctrl-C — may still request an Abort between a thread's look and its wait.)

Each test here forces the unlucky interleaving that once broke a real-clock run, so the fault shows
every time instead of once in a few hundred runs:

* a ``TestAndSet`` that found the lock taken wrote its stale 1 over the holder's release;
* a ``Join`` (or ``WaitEvent``, or a suspended thread's wait for ``Resume``, or an ``Abort``) whose
  wakeup arrived between the caller's own test and its registration on the wait queue slept
  forever.
"""

from __future__ import annotations

import sys
import threading
import time
import types
from typing import Any, Iterator

import pytest

from gplrt.lang.byref import Box
from gplrt.lang.errors import GplException
from gplrt.sim import Simulation
from gplrt.threads import Thread, checkpoint
from gplrt.threads.scheduler import Phase, RealScheduler, Scheduler, VirtualScheduler

GUARD = 10.0  # seconds a forced-race call may take before the test calls it hung


class ReleasedDuringTheRead(Box):
    """A lock cell whose holder releases it right after a TestAndSet has read the old value 1."""

    __slots__ = ()

    def get(self) -> Any:
        old = self.value
        self.value = 0  # the holder's ``lock = 0``, between the read and the write
        return old


def test_testandset_that_finds_the_lock_taken_keeps_the_holders_release() -> None:
    lock = ReleasedDuringTheRead(1)
    assert Thread.TestAndSet(lock, 1) == 1  # the caller saw the lock taken...
    assert lock.value == 0  # ...and the release it raced with is not lost


def test_testandset_still_stores_a_new_value() -> None:
    lock = Box(0)
    assert Thread.TestAndSet(lock, 1) == 0
    assert lock.value == 1
    counter = Box(5)
    assert Thread.TestAndSet(counter, 7) == 5
    assert counter.value == 7


@pytest.fixture
def race_window(monkeypatch: pytest.MonkeyPatch) -> Iterator[list[Any]]:
    """Run each action queued in the returned list just before a GPL thread's next wait registers.

    That is exactly the window between a caller's ``while not condition`` and its wait.
    """
    actions: list[Any] = []

    def in_the_window(cls: type[Scheduler]) -> None:
        original = cls._block

        def block(self: Scheduler, ctx: Any, queue: Any, deadline: Any, until: Any = None) -> bool:
            while actions:
                actions.pop(0)()
            return original(self, ctx, queue, deadline, until)

        monkeypatch.setattr(cls, "_block", block)

    in_the_window(RealScheduler)
    in_the_window(VirtualScheduler)
    yield actions


def run_guarded(sim: Simulation, main: Any) -> list[str]:
    """``sim.run_main`` that gives up after GUARD seconds and names the threads still waiting."""
    return sim.run_main(main, timeout=GUARD)


def test_join_of_a_thread_that_ends_just_before_the_wait_returns(race_window: list[Any]) -> None:
    sim = Simulation(clock="real", capture=True)
    gate = threading.Event()
    ended = threading.Event()
    result: list[bool] = []

    def worker() -> None:
        gate.wait(GUARD)

    def main() -> None:
        w = Thread(worker, 0, "worker")
        w.Start()

        def let_it_end() -> None:
            gate.set()
            deadline = time.monotonic() + GUARD
            # until the worker has ended *and* sent its notification to the (still empty) queue
            while w._ctx.phase != Phase.DONE and time.monotonic() < deadline:  # type: ignore[union-attr]
                time.sleep(0.001)
            ended.set()

        race_window.append(let_it_end)
        result.append(bool(w.Join()))

    assert run_guarded(sim, main) == []
    assert ended.is_set() and result == [True]


def test_waitevent_sent_just_before_the_wait_is_received(race_window: list[Any]) -> None:
    sim = Simulation(clock="real", capture=True)
    got: list[int] = []

    def main() -> None:
        me = Thread.CurrentThread()
        race_window.append(lambda: me.SendEvent(4))
        got.append(int(Thread.WaitEvent(4, -1)))

    assert run_guarded(sim, main) == []
    assert got == [4]


def test_resume_just_before_the_suspended_thread_waits_lets_it_run(race_window: list[Any]) -> None:
    sim = Simulation(clock="real", capture=True)
    m = types.SimpleNamespace(after=False)

    def main() -> None:
        me = Thread.CurrentThread()
        race_window.append(me.Resume)
        me.Suspend()  # parks until Resume: the Resume lands in the race window
        m.after = True

    assert run_guarded(sim, main) == []
    assert m.after


@pytest.mark.parametrize("clock", ["real", "virtual"])
def test_abort_just_before_the_wait_ends_the_thread(race_window: list[Any], clock: str) -> None:
    sim = Simulation(clock=clock, capture=True)  # type: ignore[arg-type]
    m = types.SimpleNamespace(after=False)

    def main() -> None:
        me = Thread.CurrentThread()
        race_window.append(lambda: sim.scheduler.request_abort(me._ctx))
        Thread.WaitEvent(1, -1)  # forever, unless the Abort is noticed
        m.after = True

    assert run_guarded(sim, main) == []
    assert not m.after


@pytest.fixture
def frequent_switches() -> Iterator[None]:
    """Make CPython switch threads every 10 µs instead of every 5 ms: races show up at once."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-5)
    try:
        yield
    finally:
        sys.setswitchinterval(old)


def test_spin_lock_and_join_under_frequent_preemption(frequent_switches: None) -> None:
    """EX-31's pattern, 8 threads x 2,000 locked increments, switching threads every 10 µs.

    Before the fixes this lost the lock (all threads spinning forever) or the final Join within a
    few runs.
    """
    for _ in range(3):
        sim = Simulation(clock="real", capture=True, slice_checkpoints=997)
        m = types.SimpleNamespace(lock=0, counter=0)
        lock = Box(0)

        def worker() -> None:
            for _ in range(2000):
                while Thread.TestAndSet(lock, 1) != 0:
                    checkpoint()
                v = m.counter
                checkpoint()
                m.counter = v + 1
                lock.set(0)
                checkpoint()

        def main() -> None:
            workers = [Thread(worker, 0, f"Inc{k}") for k in range(8)]
            for w in workers:
                w.Start()
            for w in workers:
                w.Join()

        assert run_guarded(sim, main) == []
        assert m.counter == 8 * 2000 and lock.value == 0


class _SlowLimit:
    """A thread limit whose comparison pauses: it holds one Start between its duplicate-name check
    and marking its thread active, where a second Start of the same name used to slip through."""

    def __init__(self, limit: int, pause: float) -> None:
        self.limit, self.pause = limit, pause

    def __le__(self, active: int) -> bool:  # ``len(active) >= limit`` asks ``limit <= len(active)``
        time.sleep(self.pause)
        return self.limit <= active


def test_two_simultaneous_starts_of_one_thread_name_start_one_thread() -> None:
    sim = Simulation(clock="real", capture=True)
    sim.max_threads = _SlowLimit(32, 0.2)  # type: ignore[assignment]
    gate = threading.Event()
    outcomes: list[str] = []
    barrier = threading.Barrier(2)

    def worker() -> None:
        gate.wait(GUARD)

    def start_one() -> None:
        t = Thread(worker, 0, "station", _session=sim)
        barrier.wait(GUARD)
        try:
            t.Start()
            outcomes.append("started")
        except GplException as exc:
            outcomes.append(str(exc.ErrorCode))

    starters = [threading.Thread(target=start_one) for _ in range(2)]
    for s in starters:
        s.start()
    for s in starters:
        s.join(GUARD)
    gate.set()
    assert sim.scheduler.wait_until_quiet(None, GUARD)
    assert sorted(outcomes) == ["-749", "started"]
