"""Public session control: ``Simulation.stop()`` and ``Thread.unhandled_error``."""

from __future__ import annotations

import types

from gplrt.lang.errors import GplException
from gplrt.sim import Simulation
from gplrt.threads import Thread, ThreadStateValue, checkpoint


def test_unhandled_error_is_the_exception_that_ended_the_thread(vsim: Simulation) -> None:
    m = types.SimpleNamespace()

    def faulty() -> None:
        Thread.Sleep(100)
        raise GplException(-709, detail="x / 0")

    def fine() -> None:
        Thread.Sleep(50)

    def main() -> None:
        m.f, m.g = Thread(faulty, 0, "Faulty"), Thread(fine, 0, "Fine")
        m.f.Start()
        m.g.Start()
        m.while_running = m.f.unhandled_error
        m.f.Join()
        m.g.Join()

    vsim.run_main(main)
    assert m.while_running is None
    assert isinstance(m.f.unhandled_error, GplException) and m.f.unhandled_error.ErrorCode == -709
    assert m.g.unhandled_error is None


def test_an_aborted_thread_has_no_unhandled_error(vsim: Simulation) -> None:
    m = types.SimpleNamespace()

    def sleeper() -> None:
        Thread.Sleep(10_000)

    def main() -> None:
        m.t = Thread(sleeper, 0, "Sleeper")
        m.t.Start()
        Thread.Sleep(10)
        m.t.Abort()
        m.t.Join()

    vsim.run_main(main)
    assert m.t.ThreadState == ThreadStateValue.IDLE
    assert m.t.unhandled_error is None


def test_stop_aborts_every_live_thread_and_runs_their_finally_blocks(vsim: Simulation) -> None:
    cleaned: list[str] = []

    def waiter() -> None:
        try:
            Thread.WaitEvent(1, -1)  # waits for ever
        finally:
            cleaned.append("waiter")

    def spinner() -> None:
        try:
            while True:
                checkpoint()
        finally:
            cleaned.append("spinner")

    threads = [vsim.start(waiter, name="Waiter"), vsim.start(spinner, name="Spinner")]
    vsim.run_for(0.5)
    assert [t.ThreadState for t in threads] != [ThreadStateValue.IDLE] * 2
    report = vsim.stop(grace=5.0)
    assert sorted(report.aborted) == ["Spinner", "Waiter"]
    assert report.still_alive == []
    assert sorted(cleaned) == ["spinner", "waiter"]
    assert all(t.unhandled_error is None for t in threads)
    assert [c for c in vsim.scheduler.live if c.phase != "done"] == []


def test_stop_with_nothing_running_reports_nothing(vsim: Simulation) -> None:
    vsim.run_main(lambda: Thread.Sleep(10))
    report = vsim.stop()
    assert report.aborted == [] and report.still_alive == []


def test_thread_schedule_is_accepted_and_changes_nothing_observable(vsim: Simulation) -> None:
    """No real-time priorities on a PC (gpl-classes §22.5): accepted, timing unchanged."""
    times: list[float] = []

    def main() -> None:
        Thread.Schedule(1, 0.01, 0.002, 0.0)
        Thread.Sleep(250)
        times.append(vsim.now())

    vsim.run_main(main)
    assert times == [0.25] and vsim.console.log_text == ""
