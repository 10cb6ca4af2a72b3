"""Outside-world waits under the virtual scheduler, the real clock, and the scheduler's waits."""

from __future__ import annotations

import threading
import time
import types

from gplrt.controller.services import Controller
from gplrt.session import current_session
from gplrt.sim import Simulation
from gplrt.threads import Thread, WaitQueue, checkpoint, external_wait


def test_external_wait_lets_others_run_and_time_does_not_race_ahead(vsim: Simulation) -> None:
    outside = threading.Event()
    m = types.SimpleNamespace(ticks=[], returned_at=None)

    def receiver() -> None:
        with external_wait():  # e.g. a socket receive
            outside.wait(10)
        m.returned_at = Controller.Timer(1)

    def ticker() -> None:
        for _ in range(3):
            Thread.Sleep(100)
            m.ticks.append(Controller.Timer(1))

    def main() -> None:
        Thread(receiver, 0, "Receiver").Start()
        Thread(ticker, 0, "Ticker").Start()

    wall0 = time.monotonic()
    threading.Timer(0.2, outside.set).start()
    assert vsim.run_main(main, timeout=30) == []
    wall = time.monotonic() - wall0
    print(f"virtual {m.returned_at} s when the outside answered after {wall:.3f} s of wall time")
    assert m.ticks == [0.1, 0.2, 0.3]  # the ticker ran while the receiver was blocked outside
    assert m.returned_at is not None
    assert m.returned_at <= wall  # no faster than real time while someone waits outside


def test_external_wait_outside_gpl_threads_is_harmless() -> None:
    with external_wait():
        pass


def test_real_clock_speed_factor() -> None:
    sim = Simulation(clock="real", speed=20.0, capture=True)
    got: list[float] = []

    def main() -> None:
        t0 = Controller.Timer(1)
        Thread.Sleep(2000)  # 0.1 s of wall time at speed 20
        got.append(Controller.Timer(1) - t0)

    wall0 = time.monotonic()
    sim.run_main(main, timeout=30)
    print(f"2 s at speed 20 took {time.monotonic() - wall0:.3f} s wall")
    assert got[0] >= 2.0 - 0.000125


def test_real_mode_events_join_abort_and_errors() -> None:
    sim = Simulation(clock="real", speed=10.0, capture=True)
    m = types.SimpleNamespace(events=[], spins=0)

    def waiter() -> None:
        m.events.append(Thread.WaitEvent(0b100, -1))
        m.events.append(Thread.WaitEvent(0b1, 100))  # times out: 0

    def spinner() -> None:
        while True:
            m.spins += 1
            checkpoint()

    def faulty() -> None:
        raise ZeroDivisionError

    def main() -> None:
        w = Thread(waiter, 0, "Waiter")
        s = Thread(spinner, 0, "Spinner")
        f = Thread(faulty, 0, "Faulty")
        for t in (w, s, f):
            t.Start()
        Thread.Sleep(50)
        w.SendEvent(0b110)
        m.joined = w.Join(60_000)  # generous: the machine may be busy; returns as soon as done
        s.Abort()
        s.Join(60_000)
        m.spinner_state = s.ThreadState
        m.faulty_joined = f.Join(60_000)

    assert sim.run_main(main, timeout=30) == []
    assert m.events == [0b100, 0]
    assert m.joined is True and m.faulty_joined is True
    assert m.spinner_state == 0 and m.spins > 0
    assert [e.code for e in sim.controller.error_log] == [-201]


def test_scheduler_waits_for_the_motion_work(vsim: Simulation) -> None:
    """sleep_until, wait/notify_all with a deadline, call_at — what WaitForEOM builds on, on the
    calling thread's session (``current_session()``)."""
    q = WaitQueue("eom")
    m = types.SimpleNamespace(log=[], done=False)

    def now() -> float:
        return current_session().now()

    def mover() -> None:
        sched = current_session().scheduler
        sched.call_at(1.5, lambda: m.log.append(("callback", now())))
        sched.sleep_until(2.0)  # the planned end of a motion
        m.done = True
        sched.notify_all(q)
        m.log.append(("moved", now()))

    def waiter() -> None:
        sched = current_session().scheduler
        deadline = now() + 0.5
        while not m.done:
            if not sched.wait(q, deadline):
                m.log.append(("timeout", now()))
                deadline = now() + 5.0
        m.log.append(("woken", now()))

    def main() -> None:
        a = Thread(mover, 0, "Mover")
        b = Thread(waiter, 0, "Waiter")
        a.Start()
        b.Start()
        a.Join()
        b.Join()
        current_session().scheduler.sleep(0.25)
        m.log.append(("end", now()))

    vsim.run_main(main)
    assert m.log == [("timeout", 0.5), ("callback", 1.5), ("moved", 2.0), ("woken", 2.0), ("end", 2.25)]


def test_thread_exit_hooks_run_on_the_ending_thread(vsim: Simulation) -> None:
    ended: list[tuple[str, float]] = []
    vsim.thread_exit_hooks.append(lambda t: ended.append((t.Name, current_session().now())))

    def child() -> None:
        Thread.Sleep(300)

    def main() -> None:
        Thread(child, 0, "Child").Start()

    vsim.run_main(main)
    assert ended == [("main", 0.0), ("Child", 0.3)]


def test_notebook_helpers_start_run_for_and_as_gpl_thread(vsim: Simulation) -> None:
    beats: list[float] = []

    def heartbeat() -> None:
        while True:
            beats.append(current_session().now())
            Thread.Sleep(1000)

    t = vsim.start(heartbeat, name="Heartbeat")
    vsim.run_for(3.5)
    assert beats == [0.0, 1.0, 2.0, 3.0]
    with vsim.as_gpl_thread():
        me = Thread.CurrentThread()
        Thread.Sleep(1000)
        assert current_session().now() == 4.5 and beats[-1] == 4.0
        assert me.Name != "Heartbeat"
    t.Abort()
    assert t.ThreadState == 0
