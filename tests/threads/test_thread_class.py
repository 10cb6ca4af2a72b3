"""The GPL Thread class: events, Join, Abort, Suspend/Resume, ThreadState, unhandled errors."""

from __future__ import annotations

import types

import pytest

from gplrt.controller.services import Controller
from gplrt.lang.console import Console
from gplrt.lang.errors import GplException
from gplrt.lang.procedures import clear_procedures, register_procedure
from gplrt.sim import Simulation
from gplrt.threads import Thread, ThreadStateValue, checkpoint


def now() -> float:
    return Controller.Timer(1)


# ---- WaitEvent / SendEvent -----------------------------------------------------------------------


def test_waitevent_timeout_returns_zero_after_the_timeout(vsim: Simulation) -> None:
    got: list[tuple[int, float]] = []

    def main() -> None:
        t0 = now()
        got.append((Thread.WaitEvent(1, 1500), now() - t0))

    vsim.run_main(main)
    assert got == [(0, 1.5)]


def test_sendevent_wakes_the_waiter_with_the_matching_bits(vsim: Simulation) -> None:
    got: list[tuple[int, float]] = []

    def waiter() -> None:
        got.append((Thread.WaitEvent(0b0110, -1), now()))  # events 2 and 3, no timeout
        got.append((Thread.WaitEvent(0, 0), now()))  # mask 0: what is still pending

    def main() -> None:
        w = Thread(waiter, 0, "Waiter")
        w.Start()
        Thread.Sleep(200)
        w.SendEvent(0b1001)  # events 1 and 4: not waited for
        Thread.Sleep(300)
        w.SendEvent(0b0100)  # event 3
        w.Join()

    vsim.run_main(main)
    assert got == [(0b0100, 0.5), (0b1001, 0.5)]


def test_waitevent_mask_zero_and_timeout_zero_poll_without_waiting(vsim: Simulation) -> None:
    got: list[int] = []

    def main() -> None:
        me = Thread.CurrentThread()
        me.SendEvent(0b10101)
        got.append(Thread.WaitEvent(0, 0))  # all received, nothing cleared
        got.append(Thread.WaitEvent(0b00001, 0))  # clears event 1 only
        got.append(Thread.WaitEvent(0, 5000))  # mask 0 never waits
        got.append(Thread.WaitEvent(0b00010, 0))  # not pending: 0 at once
        got.append(int(now() * 1000))

    vsim.run_main(main)
    assert got == [0b10101, 0b00001, 0b10100, 0, 0]


def test_pending_event_returns_immediately(vsim: Simulation) -> None:
    got: list[tuple[int, float]] = []

    def main() -> None:
        Thread.CurrentThread().SendEvent(1 << 15)  # event 16
        got.append((Thread.WaitEvent(0xFFFF, 10_000), now()))

    vsim.run_main(main)
    assert got == [(0x8000, 0.0)]


@pytest.mark.parametrize("mask", [-1, 0x10000])
def test_bad_event_masks_raise_707(vsim: Simulation, mask: int) -> None:
    with pytest.raises(GplException) as info:
        Thread.CurrentThread().SendEvent(mask)
    assert info.value.ErrorCode == -707


def test_waitevent_timeout_over_2147_seconds_raises_707(vsim: Simulation) -> None:
    with pytest.raises(GplException) as info:
        Thread.WaitEvent(1, 2_147_001)
    assert info.value.ErrorCode == -707


# ---- Join, Start, names ------------------------------------------------------------------------


def test_join_with_timeout_and_states(vsim: Simulation) -> None:
    seen: list[object] = []

    def slow() -> None:
        Thread.Sleep(1000)

    def main() -> None:
        t = Thread(slow, 0, "Slow")
        seen.append(t.ThreadState)  # not started: idle
        seen.append(t.Join(100))  # never started: returns at once
        t.Start()
        seen.append(t.ThreadState)
        seen.append(t.Join(300))  # times out
        seen.append(now())
        seen.append(t.Join(0))  # poll
        seen.append(t.Join())  # forever
        seen.append(now())
        seen.append(t.ThreadState)

    vsim.run_main(main)
    assert seen == [0, True, 1, False, 0.3, False, True, 1.0, 0]


def test_start_an_active_thread_raises_750_and_duplicate_names_749(vsim: Simulation) -> None:
    codes: list[int] = []

    def idle() -> None:
        Thread.Sleep(100)

    def main() -> None:
        t = Thread(idle, 0, "Worker")
        t.Start()
        for action in (t.Start, Thread(idle, 0, "worker").Start):
            try:
                action()
            except GplException as exc:
                codes.append(exc.ErrorCode)
        t.Join()
        t.Start()  # restartable once idle
        t.Join()

    vsim.run_main(main)
    assert codes == [-750, -749]


def test_join_on_itself_raises_750_and_negative_sleep_yields(vsim: Simulation) -> None:
    codes: list[int] = []

    def main() -> None:
        Thread.Sleep(-5)
        try:
            Thread.CurrentThread().Join(100)
        except GplException as exc:
            codes.append(exc.ErrorCode)

    vsim.run_main(main)
    assert codes == [-750] and vsim.now() == 0.0


def test_thread_limit_raises_207() -> None:
    sim = Simulation(capture=True, max_threads=3)
    codes: list[int] = []

    def idle() -> None:
        Thread.Sleep(100)

    def main() -> None:
        Thread(idle, 0, "A").Start()
        Thread(idle, 0, "B").Start()
        try:
            Thread(idle, 0, "C").Start()  # main + A + B = 3 active
        except GplException as exc:
            codes.append(exc.ErrorCode)

    sim.run_main(main)
    assert codes == [-207]


def test_new_thread_by_procedure_name_and_properties() -> None:
    sim = Simulation(capture=True, project="Cell")
    got: list[object] = []
    clear_procedures()

    def scanner() -> None:
        me = Thread.CurrentThread()
        got.extend([me.Name, me.StartProcedure, me.Argument, me.Project])

    register_procedure("IoTask", "Scanner", scanner, public=True)
    try:

        def main() -> None:
            t1 = Thread("iotask.scanner", 42)
            t1.Start()
            t1.Join()
            t2 = Thread("Scanner", 7, "Second")
            t2.Start()
            t2.Join()

        sim.run_main(main)
        with pytest.raises(GplException) as info:
            Thread("NoSuchProc")
        assert info.value.ErrorCode == -729
    finally:
        clear_procedures()
    assert got == ["scanner", "iotask.scanner", 42, "Cell", "Second", "Scanner", 7, "Cell"]


# ---- Abort, Suspend, Resume ----------------------------------------------------------------------


def test_abort_a_sleeping_thread_runs_finally_but_not_catch(vsim: Simulation) -> None:
    log: list[str] = []

    def victim() -> None:
        try:
            try:
                Thread.Sleep(10_000)
            except GplException:
                log.append("caught")
            log.append("after sleep")
        finally:
            log.append(f"finally at {now()}")

    def main() -> None:
        t = Thread(victim, 0, "Victim")
        t.Start()
        Thread.Sleep(250)
        t.Abort()
        log.append(f"state {t.ThreadState} at {now()}")

    vsim.run_main(main)
    assert log == ["finally at 0.25", "state 0 at 0.25"]
    assert vsim.controller.error_log == []


def test_abort_a_busy_thread_at_its_next_checkpoint(vsim: Simulation) -> None:
    m = types.SimpleNamespace(n=0)

    def spinner() -> None:
        while True:
            m.n += 1
            checkpoint()

    def main() -> None:
        t = Thread(spinner, 0, "Spinner")
        t.Start()
        Thread.Sleep(10)
        t.Abort()
        m.after_abort = m.n
        Thread.Sleep(10)

    vsim.run_main(main)
    assert m.n > 0 and m.n == m.after_abort


def test_suspend_and_resume(vsim: Simulation) -> None:
    m = types.SimpleNamespace(ticks=[], states=[])

    def ticker() -> None:
        for _ in range(10):
            m.ticks.append(round(now(), 3))
            Thread.Sleep(100)

    def main() -> None:
        t = Thread(ticker, 0, "Ticker")
        t.Start()
        Thread.Sleep(250)
        t.Suspend()
        m.states.append(t.ThreadState)
        Thread.Sleep(1000)
        t.Resume()
        m.states.append(t.ThreadState)
        t.Join()

    vsim.run_main(main)
    assert m.states == [ThreadStateValue.STOPPED, ThreadStateValue.RUNNING]
    # ticks at 0, .1, .2; parks after the sleep ending at .3; resumes at 1.25
    assert m.ticks[:3] == [0.0, 0.1, 0.2]
    assert m.ticks[3] == 1.25
    assert len(m.ticks) == 10


# ---- unhandled exceptions ------------------------------------------------------------------------


def test_unhandled_exception_ends_only_its_thread_and_is_reported(vsim: Simulation) -> None:
    m = types.SimpleNamespace(done=[])

    def faulty() -> None:
        Thread.Sleep(100)
        raise GplException(-709)

    def steady() -> None:
        for i in range(3):
            Thread.Sleep(100)
        m.done.append(now())

    def main() -> None:
        f = Thread(faulty, 0, "Faulty")
        s = Thread(steady, 0, "Steady")
        f.Start()
        s.Start()
        m.joined = f.Join()
        m.state = f.ThreadState
        s.Join()
        Console.WriteLine(f"main saw {Controller.ErrorLog(1)}")

    assert vsim.run_main(main) == []
    assert m.joined is True and m.state == ThreadStateValue.ERROR
    assert m.done == [0.3]
    assert "thread Faulty: unhandled error: GPL error -709" in vsim.console.log_text
    assert vsim.console.output == "main saw -709 Division by 0 (Faulty)\n"
    assert [e.code for e in vsim.controller.error_log] == [-709]


def test_python_bug_in_a_thread_is_reported_too(vsim: Simulation) -> None:
    def broken() -> None:
        raise KeyError("oops")

    vsim.run_main(broken)
    assert "Python error KeyError" in vsim.console.log_text
    assert vsim.controller.error_log[0].code == -201


# ---- sessions and outside callers ---------------------------------------------------------------


def test_call_from_outside_returns_the_result_and_raises_errors(vsim: Simulation) -> None:
    def add_later(a: int, b: int) -> int:
        Thread.Sleep(500)
        return a + b

    def fail() -> None:
        raise GplException(-786, 8)

    assert vsim.call(add_later, 2, 3) == 5
    assert vsim.now() == 0.5
    with pytest.raises(GplException) as info:
        vsim.call(fail)
    assert info.value.Message() == "*Project generated error*: 8"
    assert vsim.controller.error_log == []  # the caller got it: not an unhandled thread error


def test_sleep_from_an_unregistered_thread_does_not_deadlock(vsim: Simulation) -> None:
    Thread.Sleep(2000)  # pytest's thread is no GPL thread: adopted for the call
    assert vsim.now() == 2.0


def test_stalled_program_returns_with_the_waiting_threads(vsim: Simulation) -> None:
    def forever() -> None:
        Thread.WaitEvent(1, -1)

    def main() -> None:
        Thread(forever, 0, "Forever").Start()

    assert vsim.run_main(main) == ["Forever"]
    assert "stalled" in vsim.console.log_text


# ---- Integer arguments convert by GPL's rules --------------------------------------------------------


@pytest.mark.parametrize(
    ("value", "code"),
    [(float("nan"), -710), (1e300, -710), ("soon", -717), (None, -782)],
)
def test_bad_millisecond_and_mask_arguments_are_gpl_errors(vsim: Simulation, value: object, code: int) -> None:
    """Hand-written Python (a notebook) may pass anything; before, int() and comparisons leaked
    ValueError/TypeError, and Sleep(1e300) slept forever instead of overflowing."""
    from gpltest import code_of

    t = Thread(lambda: Thread.Sleep(100), 0, "sleeper")
    got: list[int] = []

    def main() -> None:
        t.Start()
        got.append(code_of(t.Join, value))
        got.append(code_of(Thread.Sleep, value))
        got.append(code_of(Thread.WaitEvent, 1, value))
        got.append(code_of(Thread.WaitEvent, value, 0))
        got.append(code_of(t.SendEvent, value))
        t.Join()

    assert vsim.run_main(main, timeout=10) == []
    assert got == [code] * 5


def test_millisecond_arguments_round_like_cint(vsim: Simulation) -> None:
    got: list[float] = []

    def main() -> None:
        t0 = now()
        Thread.Sleep(2.5)  # CInt(2.5) = 3 ms; int() truncated it to 2
        got.append(round((now() - t0) * 1000, 6))
        t0 = now()
        Thread.WaitEvent(1, "4")  # numeric text converts
        got.append(round((now() - t0) * 1000, 6))

    vsim.run_main(main)
    assert got == [3.0, 4.0]
