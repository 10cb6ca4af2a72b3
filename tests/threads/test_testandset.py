"""Thread.TestAndSet spin locks (EX-31/EX-32): no increment lost, on either clock."""

from __future__ import annotations

import time
import types

import pytest

from gplrt.lang.arrays import GplArray
from gplrt.lang.byref import AttrRef, Box, ItemRef
from gplrt.lang.gpltypes import Integer
from gplrt.sim import Simulation
from gplrt.threads import Thread, checkpoint

THREADS = 8
INCREMENTS = 10_000


def counter_program(locked: bool) -> tuple[types.SimpleNamespace, object]:
    """Eight workers add 1 to a module variable 10,000 times each; the read and the write are
    separated by a back-edge checkpoint, so preemption inside the critical section happens."""
    m = types.SimpleNamespace(lock=0, counter=0, spins=0)

    def worker() -> None:
        lock = AttrRef(m, "lock")
        for _ in range(INCREMENTS):
            if locked:
                while Thread.TestAndSet(lock, 1) != 0:
                    m.spins += 1
                    checkpoint()
            v = m.counter
            checkpoint()
            m.counter = v + 1
            if locked:
                lock.set(0)
            checkpoint()

    def main() -> None:
        workers = [Thread(worker, 0, f"Inc{k}") for k in range(THREADS)]
        for w in workers:
            w.Start()
        for w in workers:
            w.Join()

    return m, main


@pytest.mark.parametrize("clock", ["virtual", "real"])
def test_spin_lock_loses_no_increment(clock: str) -> None:
    # An odd slice makes slice ends fall inside the critical section too (two checkpoints per
    # iteration), so the lock is really contended.
    sim = Simulation(clock=clock, capture=True, slice_checkpoints=997)  # type: ignore[arg-type]
    m, main = counter_program(locked=True)
    wall = time.perf_counter()
    assert sim.run_main(main, timeout=120) == []
    print(f"{clock}: {THREADS}x{INCREMENTS} locked increments in {time.perf_counter() - wall:.2f} s wall")
    assert m.counter == THREADS * INCREMENTS
    assert m.lock == 0
    assert sim.controller.error_log == []
    if clock == "virtual":
        assert m.spins > 0  # threads did find the lock taken


def test_without_the_lock_increments_are_lost_in_virtual_time() -> None:
    """The control experiment: the preemption the lock guards against really happens."""
    sim = Simulation(capture=True, slice_checkpoints=997)
    m, main = counter_program(locked=False)
    sim.run_main(main)
    assert m.counter < THREADS * INCREMENTS


def test_testandset_returns_old_value_and_writes_through_cells() -> None:
    box = Box(0)
    assert Thread.TestAndSet(box, 1) == 0
    assert Thread.TestAndSet(box, 1) == 1
    assert box.get() == 1


def test_ex32_interlocked_add_on_an_array_element(vsim: Simulation) -> None:
    """EX-32: AddArray under acquire_sem/release_sem, the lock being an array element (ByRef)."""
    m = types.SimpleNamespace(locks=GplArray(Integer, 1), my_array=GplArray(Integer, 1))

    def acquire_sem(sem_var: ItemRef) -> None:
        while Thread.TestAndSet(sem_var, 1) != 0:
            Thread.Sleep(0)
            checkpoint()

    def add_array(inc: int) -> None:
        acquire_sem(ItemRef(m.locks, 0))
        v = m.my_array[0]
        Thread.Sleep(1)  # hold the lock across a scheduling point
        m.my_array[0] = v + inc
        ItemRef(m.locks, 0).set(0)

    def worker() -> None:
        for _ in range(50):
            add_array(int(Thread.CurrentThread().Argument))
            checkpoint()

    def main() -> None:
        ts = [Thread(worker, k, f"A{k}") for k in (1, 10, 100)]
        for t in ts:
            t.Start()
        for t in ts:
            t.Join()

    vsim.run_main(main)
    assert m.my_array[0] == 50 * 111
