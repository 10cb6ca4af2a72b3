"""The refusals tests/e2e/test_motion_refusals.py does not reach, caught by a transpiled program's
own Try/Catch with the controller's codes: position too close (-1039), a straight line that would
change the arm configuration (-1042), a configuration whose solution is beyond a joint limit
(-1012), and power lost during a motion, reported by the next WaitForEOM (-1046)."""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl

PROGRAM = """    Dim ex As Exception
    Dim prof As New Profile
    Dim line As New Profile
    Dim target As New Location

    Sub Try1(ByVal what As String)
        Try
            Move.Loc(target, prof)
            Move.WaitForEOM
            Console.WriteLine(what & ": moved")
        Catch ex
            Console.WriteLine(what & ": " & CStr(ex.ErrorCode))
        End Try
    End Sub

    Public Sub PowerCut()
        Thread.Sleep(300)
        Controller.PowerEnabled = False
    End Sub

    Public Sub Main()
        Dim cutter As New Thread("PowerCut")
        line.Straight = True
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        target.XYZ(350, 100, 250, 0, 90, 180)
        target.Config = GPL_Righty
        Try1("righty")
        target.XYZ(4, 3, 250, 0, 90, 180)
        Robot.Tool = Location.XYZValue(0, 0, 0, 0, 0, 0)
        Try1("too close")
        target.XYZ(350, 150, 250, 0, 90, 180)
        target.Config = GPL_Lefty
        Try
            Move.Loc(target, line)
            Console.WriteLine("straight lefty: moved")
        Catch ex
            Console.WriteLine("straight lefty: " & CStr(ex.ErrorCode))
        End Try
        target.XYZ(200, 300, 250, 0, 90, 180)
        Try1("lefty beyond J2")
        target.XYZ(300, -300, 250, 0, 90, 180)
        target.Config = GPL_Righty
        prof.Speed = 5
        cutter.Start
        Try
            Move.Loc(target, prof)
            Console.WriteLine("queued")
            Move.WaitForEOM
            Console.WriteLine("arrived")
        Catch ex
            Console.WriteLine("power cut: " & CStr(ex.ErrorCode))
        End Try
        cutter.Join
    End Sub"""


def test_refusals_reach_the_programs_catch_with_their_codes(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src(PROGRAM))
    assert result.output == (
        "righty: moved\n"
        "too close: -1039\n"
        "straight lefty: -1042\n"
        "lefty beyond J2: -1012\n"
        "queued\n"
        "power cut: -1046\n"
    ), result.output + result.log
    assert result.status == 0
