"""Tasks by number, events, TAS, timers, REACTE/RETURNE and REACT, run on the virtual clock."""

from __future__ import annotations

import pytest

from gplrt import vplus as vp
from gplrt.sim import Simulation


def test_execute_two_tasks_and_a_shared_global(sim: Simulation) -> None:
    """ros.v2's a.ros: globals set, two tasks started, each runs until run = FALSE."""
    @vp.program("t.worker")
    def worker(n: vp.Ref) -> None:
        while vp.truth(vp.G["run"].v):
            vp.G["count"].v = vp.add(vp.G["count"].v, 1)
            vp.wait_event(None, 0.1)
        vp.type_("worker ", n.v, " done")

    @vp.program("t.stopper")
    def stopper() -> None:
        vp.wait_for(lambda: vp.ge(vp.G["count"].v, 10))
        vp.G["run"].v = vp.FALSE

    @vp.program("t.main")
    def main() -> None:
        vp.G["run"].v = vp.TRUE
        vp.G["count"].v = 0
        vp.execute(5, "t.worker", vp.byval(5))
        vp.execute(6, stopper)
        vp.type_("main returns")

    assert sim.run_main(lambda: main()) == []
    lines = sim.console.output.splitlines()
    assert lines == ["main returns", "worker 5 done"]
    assert vp.G["count"].v == 10.0
    assert sim.now() >= 0.9  # ten waits of 0.1 s of virtual time


def test_task_in_use_and_abort(sim: Simulation) -> None:
    @vp.program("t.forever")
    def forever() -> None:
        while True:
            vp.wait()

    def main() -> None:
        vp.execute(3, forever)
        try:
            vp.execute(3, forever)
        except vp.VError as e:
            vp.type_(e.Message())
        vp.wait()
        vp.type_(vp.task_status(3))
        vp.abort(3)
        vp.type_(vp.task_status(3))

    assert sim.run_main(main) == []
    assert sim.console.output.splitlines() == ["*Task already in use*", "-1", "0"]


def test_set_event_wakes_wait_event(sim: Simulation) -> None:
    @vp.program("t.waiter")
    def waiter() -> None:
        got = vp.wait_event()
        vp.type_("woke ", got, " at ", vp.fmt("/F4.2"), vp.timer(1))

    def main() -> None:
        vp.timer_set(1, 0)
        vp.execute(2, waiter)
        vp.wait_event(None, 0.5)  # a pure delay: nobody sets task 0's flag
        vp.set_event(2)

    assert sim.run_main(main) == []
    assert sim.console.output == "woke 1 at 0.50\n"


def test_tas_returns_old_value(sim: Simulation) -> None:
    lock = vp.G["lock"]
    lock.v = 0
    assert vp.tas(lock, 1) == 0.0 and vp.tas(lock, 1) == 1.0 and lock.v == 1.0


def test_reacte_runs_handler_and_returne_continues_after_the_failing_statement(sim: Simulation) -> None:
    @vp.program("trouble")
    def trouble() -> None:
        vp.type_("trapped ", vp.error(-1), " ", vp.s_error(vp.error(-1)))
        return  # RETURNE

    def main() -> None:
        x = vp.Cell("x")
        vp.reacte("trouble")
        with vp.step(3):
            vp.type_("before")
        with vp.step(4):
            x.v = vp.div(1, 0)
            vp.type_("not reached")
        with vp.step(5):
            vp.type_("after, x defined: ", vp.defined(x))

    assert sim.run_main(main) == []
    assert sim.console.output.splitlines() == [
        "before", "trapped -406 *Divide by zero*", "after, x defined: 0"]


def test_without_reacte_the_error_stops_the_task(sim: Simulation) -> None:
    def main() -> None:
        with vp.step(1):
            vp.type_(vp.Cell("y").v)
        vp.type_("not reached")

    sim.run_main(main)
    assert sim.console.output == ""
    assert "*Undefined value* (-401)" in sim.console.log_text


def test_halt_is_not_trapped(sim: Simulation) -> None:
    @vp.program("h.trap")
    def trap() -> None:
        vp.type_("trapped")

    @vp.program("h.task")
    def task() -> None:
        vp.reacte(trap)
        with vp.step(1):
            vp.halt()
        vp.type_("not reached")

    def main() -> None:
        vp.execute(1, task)

    sim.run_main(main)
    assert sim.console.output == "" and sim.console.log_text == ""


def test_react_calls_program_on_signal_edge_and_lock_defers(sim: Simulation) -> None:
    @vp.program("alarm")
    def alarm() -> None:
        vp.type_("alarm at ", vp.fmt("/F4.2"), sim.now())

    def main() -> None:
        vp.react(1001, "alarm", priority=10)
        vp.lock(20)  # deferred while the program priority is 20
        vp.wait_for(lambda: vp.sig(1001))
        vp.wait_event(None, 0.2)
        vp.type_("unlocking")
        vp.lock(0)
        vp.type_("done")

    sim.io.when(10001)  # noqa: keep the io map bound
    sim.io.schedule_input(10001, True, 0.5)
    assert sim.run_main(main) == []
    lines = sim.console.output.splitlines()
    assert lines[0] == "unlocking" and lines[1].startswith("alarm at 0.7") and lines[2] == "done"


def test_stop_restarts_the_program_while_cycles_remain(sim: Simulation) -> None:
    @vp.program("t.cycle")
    def cycle() -> None:
        vp.G["k"].v = vp.add(vp.G["k"].v, 1)
        vp.type_("cycle ", vp.G["k"].v)
        sub()
        vp.type_("not reached")

    @vp.program("t.sub")
    def sub() -> None:
        vp.stop()  # STOP ends the cycle even from a subroutine (L1082-1085)

    def main() -> None:
        vp.G["k"].v = 0
        vp.execute(1, cycle, cycles=3)

    assert sim.run_main(main) == []
    assert sim.console.output.splitlines() == ["cycle 1", "cycle 2", "cycle 3"]


def test_prompt_reads_a_string_or_a_number(sim: Simulation) -> None:
    vp.set_prompt_input(["Ada", "42"])
    name, n = vp.Cell("$ans"), vp.Cell("n")
    vp.prompt("May I have your name please? ", name)
    vp.prompt("How many? ", n)
    assert (name.v, n.v) == ("Ada", 42.0)
    with pytest.raises(vp.VError) as info:
        vp.prompt("More? ", n)
    assert info.value.ErrorCode == -504
    assert sim.console.output == "May I have your name please? Ada\nHow many? 42\nMore? "


def test_prompt_reads_standard_input_by_default(sim: Simulation, monkeypatch: pytest.MonkeyPatch) -> None:
    import io
    monkeypatch.setattr("sys.stdin", io.StringIO("3\n"))

    def main() -> None:
        choice = vp.Cell("choice")
        vp.prompt("Enter selection and press RETURN: ", choice)
        vp.type_("choice ", choice.v)
        try:
            vp.prompt("again: ", choice)
        except vp.VError as e:
            vp.type_(e.Message())

    assert sim.run_main(main) == []
    assert sim.console.output == "Enter selection and press RETURN: choice 3\nagain: *Unexpected end of file*\n"
