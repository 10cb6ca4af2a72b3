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
