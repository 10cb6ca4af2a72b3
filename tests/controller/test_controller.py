"""Controller's non-motion members: time, power, speed, messages, error log, dialogs, PDb hook."""

from __future__ import annotations

import pytest

from gplrt.controller.services import Controller
from gplrt.lang.byref import Box
from gplrt.lang.conversions import to_string
from gplrt.lang.errors import GplException
from gplrt.sim import Simulation
from gplrt.threads import Thread


def test_timer_tick_and_sleeptick_on_the_virtual_clock(vsim: Simulation) -> None:
    got: list[float] = []

    def main() -> None:
        t0 = Controller.Timer(1)
        Controller.SleepTick()  # one trajectory period
        got.append(Controller.Timer(1) - t0)
        Controller.SleepTick(round(2 / Controller.Tick))  # ≈ 2 s (sleeptick.htm)
        got.append(Controller.Timer(1) - t0)
        got.append(Controller.Timer() - Controller.Timer(1))

    vsim.run_main(main)
    assert Controller.Tick == 0.001
    assert got[0] == 0.001 and got[1] == 2.001
    assert got[2] == vsim.controller.time_of_day_origin  # Timer(0): seconds since 1 Jan 1988


def test_timer_is_quantised_to_125_microseconds(vsim: Simulation) -> None:
    def main() -> None:
        Thread.Sleep(1)
        Controller.SleepTick(0)

    vsim.run_main(main)
    vsim.scheduler.clock.advance_by(0.0001)  # 1.1 ms
    assert Controller.Timer(1) == 0.001  # floor to the 125 µs grid
    vsim.scheduler.clock.advance_by(0.00003)  # 1.13 ms
    assert Controller.Timer(1) == 0.001125


def test_ex16_power_on_sequence_is_visible_in_powerstate(vsim: Simulation) -> None:
    states: list[tuple[float, int]] = []

    def watcher() -> None:
        for _ in range(5):
            states.append((round(Controller.Timer(1), 3), Controller.PowerState()))
            Thread.Sleep(100)

    def main() -> None:
        w = Thread(watcher, 0, "Watcher")
        w.Start()
        Thread.Sleep(50)
        Controller.PowerEnabled = True  # EX-16
        if Controller.PowerEnabled:
            states.append((round(Controller.Timer(1), 3), -1))
        w.Join()

    vsim.run_main(main)
    # 8 from 0.05, 10 from 0.2 (main's wait began before the watcher's: it wins the 0.2 tie),
    # 20 from 0.35 when the assignment returns
    assert states == [(0.0, 7), (0.1, 8), (0.2, 10), (0.3, 10), (0.35, -1), (0.4, 20)]
    Controller.PowerEnabled = False
    assert Controller.PowerState() == 7 and not Controller.PowerEnabled


def test_soft_estop_blocks_power(vsim: Simulation) -> None:
    Controller.SoftEStop = True
    with pytest.raises(GplException) as info:
        Controller.PowerEnabled = True
    assert info.value.ErrorCode == -1046
    Controller.SoftEStop = False
    Controller.PowerEnabled = True
    assert Controller.PowerEnabled and Controller.PowerState() == 20


def test_system_speed_range(vsim: Simulation) -> None:
    # boots at the parameter database's DataID 601 "System wide test speed" (robot-models.md §2.4:
    # a real PF400 reports 50), not at 100
    assert Controller.SystemSpeed == 50.0 == vsim.pdb.get_num(601)
    Controller.SystemSpeed = 25
    assert Controller.SystemSpeed == 25.0
    for bad in (0, 100.5, -3):
        with pytest.raises(GplException) as info:
            Controller.SystemSpeed = bad
        assert info.value.ErrorCode == -707
    assert Controller.SystemSpeed == 25.0


def test_system_speed_boots_at_each_robots_database_value() -> None:
    gcu = Simulation(robot="XYZT-GCU", capture=True)
    with gcu:
        assert Controller.SystemSpeed == 10.0  # its DataID 601
    set_first = Simulation(capture=True)
    with set_first:
        Controller.SystemSpeed = 80  # set before the database loads: the program's value wins
        assert Controller.SystemSpeed == 80.0


def test_ex17_system_message_and_scripted_dialog(vsim: Simulation) -> None:
    vsim.controller.dialog_answers.append(2)

    def main() -> None:
        button = Box(0)
        Controller.SystemMessage("Sample output to Operator Control Panel")
        Controller.ShowDialog("Yes,No", "Do you like this pop-up?", button)
        Controller.SystemMessage("Operator pressed button " + to_string(button.get()))

    vsim.run_main(main)
    assert [m.text for m in vsim.controller.system_messages] == [
        "Sample output to Operator Control Panel",
        "Operator pressed button 2",
    ]
    assert "SystemMessage: Operator pressed button 2" in vsim.console.log_text
    assert vsim.console.output == ""  # not mixed into the program's own output


def test_dialog_handler_and_no_operator(vsim: Simulation) -> None:
    asked: list[tuple[list[str], str]] = []
    button = Box(0)
    with pytest.raises(GplException) as info:
        Controller.ShowDialog("OK", "Anyone there?", button)
    assert info.value.ErrorCode == -204
    vsim.controller.dialog_handler = lambda labels, prompt: asked.append((labels, prompt)) or 3
    Controller.ShowDialog("A, B, C", "Pick", button)
    assert button.get() == 3 and asked == [(["A", "B", "C"], "Pick")]


def test_error_log_entries_and_clear(vsim: Simulation) -> None:
    def bad(code: int):  # type: ignore[no-untyped-def]
        def proc() -> None:
            raise GplException(code)

        return proc

    vsim.run_main(bad(-709))
    vsim.run_main(bad(-1046))
    assert Controller.ErrorLog(1) == "-1046 Power not enabled (proc)"
    assert Controller.ErrorLog(2) == "-709 Division by 0 (proc)"
    assert Controller.ErrorLog(3) == ""
    Controller.set_ErrorLog(0, "")
    assert Controller.ErrorLog(1) == ""


def test_pdb_before_any_motion_and_with_a_custom_database(vsim: Simulation) -> None:
    # a fresh session reads its robot model's shipped database before any motion (TCS does this
    # at start-up): PF400SX has 5 axes (DataID 2000), model 400 (2007), J3 max 348 (16077)
    assert Controller.PDbNum(2000) == 5.0
    assert Controller.PDbNum(2007, 1) == 400.0
    assert Controller.PDbNum(16077, 1, 1, 3) == 348.0
    from gplrt.controller.pdb import ParameterDatabase

    db = ParameterDatabase()
    db.define(601, [50.0])
    vsim.pdb = db
    assert Controller.PDbNum(601) == 50.0
    Controller.set_PDbNum(601, 75.0)
    assert Controller.PDbNum(601) == 75.0
    assert Controller.PDb(601) == "75"


def test_unemulated_members_raise_204(vsim: Simulation) -> None:
    """Controller.Command is the console (tests/controller/test_console_commands.py); Controller.Load
    compiles with the compiler ``gpl2py run`` gives the session, and a session without one (this
    one) cannot: -204, as before.  The pendant's dialog has no hardware here."""
    folder = vsim.files.resolve("/flash/projects/x/Project.gpr").file
    assert folder is not None
    folder.box.path(*folder.parts[:-1]).mkdir()
    folder.replace(b'ProjectBegin\nProjectName="x"\nProjectEnd\n')
    button = Box(0)
    for call in (lambda: Controller.Load("/flash/projects/x"),
                 lambda: Controller.ShowDialogMCP(1, "ready?", button)):
        with pytest.raises(GplException) as info:
            call()
        assert info.value.ErrorCode == -204
