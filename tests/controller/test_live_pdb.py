"""Live DataIDs of the parameter database (gplrt/controller/live_pdb.py), read and written by
transpiled GPL as TCS does it: version, robot count, date, power state and request, homing."""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl


def test_version_robots_date_and_power_state(tmp_path: Path) -> None:
    res = run_gpl(tmp_path, module_src("""
    Public Sub Main()
        Dim v As Integer
        v = Controller.PDbNum(104) * 1000000 + Controller.PDbNum(105) * 10000 + Controller.PDbNum(106)
        Console.WriteLine(CStr(v) & " " & CStr(v >= 4020109))
        Console.WriteLine(CStr(Controller.PDbNum(111)) & " " & CStr(Controller.PDbNum(113)))
        Console.WriteLine(Controller.PDb(121).Length & " " & Controller.PDb(121).Substring(2, 1))
        Console.WriteLine(CStr(Controller.PDbNum(234)))
        Controller.PDb(121) = "04-20-2022 15:59:43"
        Console.WriteLine(Controller.PDb(121))
        Try
            Controller.PDbNum(234) = 20
        Catch ex As Exception
            Console.WriteLine("234: " & CStr(ex.ErrorCode))
        End Try
    End Sub
    """))
    assert res.output.splitlines() == ["4021002 -1", "1 1", "19 -", "7", "04-20-2022 15:59:43", "234: -209"], \
        res.output + res.log


def test_241_starts_power_without_waiting_and_213_homes_all(tmp_path: Path) -> None:
    res = run_gpl(tmp_path, module_src("""
    Public Sub Main()
        Dim p As New Profile
        Dim l As New Location
        Try
            Controller.PDbNum(213) = 1
        Catch ex As Exception
            Console.WriteLine("home with power off: " & CStr(ex.ErrorCode))
        End Try
        Controller.PDbNum(241, 0, 0, 0) = 1
        Console.WriteLine("after 241: " & CStr(Controller.PDbNum(234)) & " " & CStr(Controller.PowerEnabled))
        Thread.Sleep(1000)
        Console.WriteLine("later: " & CStr(Controller.PDbNum(234)) & " " & CStr(Controller.PowerEnabled))
        Controller.PDbNum(213) = 1
        Console.WriteLine("homing: " & CStr(Controller.PDbNum(234)) & " " & CStr(Robot.TrajState(1)))
        Thread.Sleep(2000)
        Robot.Attached = 1
        l.Angles(300, 0, 90, 0, 100)
        Move.Loc(l, p)
        Move.WaitForEOM
        Console.WriteLine("moved: " & CStr(Robot.WhereAngles.Angle(1)) & " " & CStr(Controller.PDbNum(3520, 1)))
    End Sub
    """))
    assert res.output.splitlines() == ["home with power off: -1046", "after 241: 8 0", "later: 20 -1",
                                       "homing: 28 9", "moved: 300 1"], res.output + res.log


def test_dataid_601_is_the_system_speed() -> None:
    """TCS's ``mspeed`` writes and reads DataID 601; a controller's 601 is the speed every motion
    is scaled by, the same value as Controller.SystemSpeed (the stored value only boots it)."""
    from gplrt.controller.services import Controller
    from gplrt.lang.errors import GplException
    from gplrt.sim import Simulation

    sim = Simulation(robot="PF400SX", capture=True)

    def body() -> None:
        assert Controller.PDbNum(601) == Controller.SystemSpeed == 50.0  # the PF400SX boots at 50
        Controller.set_PDbNum(601, 30)
        assert Controller.SystemSpeed == 30.0 and sim.controller.system_speed == 30.0
        Controller.SystemSpeed = 70
        assert Controller.PDbNum(601) == 70.0
        try:
            Controller.set_PDbNum(601, 0)
        except GplException as exc:
            assert exc.ErrorCode == -707
        else:
            raise AssertionError("601 = 0 was accepted")

    sim.call(body)


def test_2800_says_whether_the_robot_is_homed(tmp_path: Path) -> None:
    """DataID 2800, robot homed (issue 20: real TCS clients read ``pd 2800`` on connect and after
    ``home``): 0 before ``Robot.Home``, 1 after, per robot and read-only."""
    res = run_gpl(tmp_path, module_src("""
    Public Sub Main()
        Console.WriteLine("before " & CStr(Controller.PDbNum(2800)) & " " & Controller.PDb(2800, 1, 0, 0))
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        Console.WriteLine("after " & CStr(Controller.PDbNum(2800, 1)) & " " & Controller.PDb(2800))
        Try
            Controller.PDbNum(2800) = 0
        Catch ex As Exception
            Console.WriteLine("write: " & CStr(ex.ErrorCode))
        End Try
        Try
            Console.WriteLine(Controller.PDb(2800, 2))
        Catch ex As Exception
            Console.WriteLine("robot 2: " & CStr(ex.ErrorCode))
        End Try
    End Sub
    """))
    assert res.output.splitlines() == ["before 0 0", "after 1 1", "write: -209", "robot 2: -1509"], \
        res.output + res.log


def test_identity_text_and_power_on_hours(tmp_path: Path) -> None:
    """100-102, 107, 108 and 110 are the controller's identity, read-only text; 136 counts the
    hours the controller has run, so it grows with the controller clock."""
    res = run_gpl(tmp_path, module_src("""
    Public Sub Main()
        Dim id As Integer
        For id = 100 To 110
            Console.WriteLine(CStr(id) & ": " & Controller.PDb(id))
        Next
        Try
            Controller.PDb(110) = "x"
        Catch ex As Exception
            Console.WriteLine("110 write: " & CStr(ex.ErrorCode))
        End Try
        Console.WriteLine("hours " & CStr(Controller.PDbNum(136)))
        Thread.Sleep(9000000)
        Console.WriteLine("hours " & CStr(Controller.PDbNum(136)))
    End Sub
    """))
    assert res.output.splitlines() == [
        "100: Precise Automation", "101: gplrt simulated controller", "102: simulated (gplrt)",
        "103: GPL 4.2J2, Mar  6 2020, Release", "104: 4", "105: 2", "106: 1002", "107: Mar  6 2020",
        "108: Release", "109: PreciseFlex 400SX Handler Prod_B44B", "110: 0014FF-00000000",
        "110 write: -209", "hours 0", "hours 2"], res.output + res.log


def test_230_is_1_while_a_gpl_project_runs() -> None:
    """Auto-execution state: 0 on a controller that runs no GPL, 1 while a project's thread runs."""
    from gplrt.controller.services import Controller
    from gplrt.sim import Simulation

    sim = Simulation(capture=True)
    with sim:
        assert sim.database().get_num(230) == 0.0
    assert sim.call(lambda: Controller.PDbNum(230)) == 1.0
    with sim:
        assert sim.database().get_num(230) == 0.0


def test_420_is_the_address_the_controller_listens_on() -> None:
    from gplrt.sim import Simulation

    for listen, address in (("127.0.0.1", "127.0.0.1"), ("0.0.0.0", "127.0.0.1")):
        sim = Simulation(capture=True, listen=listen)
        with sim:
            assert sim.database().pdb_text(420) == address


def test_247_resets_no_fatal_error_and_901_saves_the_database_to_flash(tmp_path: Path) -> None:
    """A ``pc`` change is kept in flash once 901 is written (TCS guide, ``pc``): the files in
    ``/flash/config`` load back into the database as changed."""
    from gplrt.controller.pdb import ParameterDatabase

    res = run_gpl(tmp_path, module_src("""
    Public Sub Main()
        Controller.PDbNum(247) = 1
        Console.WriteLine("247 " & Controller.PDb(247) & " 901 " & Controller.PDb(901))
        Controller.PDb(2002) = "Arm A"
        Controller.PDbNum(2704, 1, 0, 1) = 120
        Controller.PDbNum(901) = 1
    End Sub
    """))
    assert res.output.splitlines() == ["247 0 901 0"], res.output + res.log
    config = res.sim.files.root().root / "flash" / "config"
    assert sorted(p.name for p in config.iterdir()) == [
        "calib01.pac", "controller.pac", "diomotion01.pac", "gpl_vars.pac", "robot01.pac"]
    saved = ParameterDatabase.load(config)
    assert saved.get(2002) == ["Arm A"] and saved.get_num(2704) == 120.0
    assert saved.get_nums(16077) == [1161.5, 93.0, 348.0, 960.0, 134.0]  # the PF400SX's, unchanged
    assert {k: e.values for k, e in saved.entries.items()} == \
        {k: e.values for k, e in res.sim.database().entries.items()}
