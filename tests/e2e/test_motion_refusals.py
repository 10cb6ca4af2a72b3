"""Every refusal of the simulated controller reaches a transpiled program's own Try/Catch.

Issue "Simulated controller": Move refuses with the controller's code when the robot is not
attached, power is off or the robot is not homed; a joint beyond its limit and a Cartesian target
out of reach raise their codes; a robot attached by another thread cannot be attached again.
"""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl

PROGRAM = """    Dim prof As New Profile
    Dim ex As Exception
    Dim target As New Location
    Dim flag As Integer

    Sub TryMove(ByVal what As String)
        Try
            Move.Loc(target, prof)
            Move.WaitForEOM
            Console.WriteLine(what & ": moved")
        Catch ex
            Console.WriteLine(what & ": " & CStr(ex.ErrorCode))
        End Try
    End Sub

    Public Sub Holder()
        Robot.Attached = 1
        flag = 1
        While flag = 1
            Thread.Sleep(10)
        End While
        Robot.Attached = 0
    End Sub

    Public Sub Main()
        Dim other As New Thread("Holder")
        target.Angles(250, 0, 180, 0, 80)
        TryMove("not attached")
        Robot.Attached = 1
        TryMove("power off")
        Controller.PowerEnabled = True
        TryMove("not homed")
        Robot.Home
        TryMove("ready")
        target.Angles(250, 0, 180, 0, 80000)
        TryMove("joint limit")
        target = Robot.Where
        target.X = 5000
        TryMove("too far")
        target.Pitch = target.Pitch + 45
        target.X = 300
        TryMove("tilted tool")
        Robot.Attached = 0
        other.Start
        Thread.Sleep(50)
        Try
            Robot.Attached = 1
            Console.WriteLine("attached twice")
        Catch ex
            Console.WriteLine("held by another thread: " & CStr(ex.ErrorCode))
        End Try
        flag = 0
        other.Join
    End Sub"""


def test_each_refusal_is_caught_with_its_code(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src(PROGRAM))
    assert result.output == (
        "not attached: -1009\n"
        "power off: -1046\n"
        "not homed: -1021\n"
        "ready: moved\n"
        "joint limit: -1012\n"
        "too far: -1040\n"
        "tilted tool: -1033\n"
        "held by another thread: -1006\n"
    ), result.output + result.log
    assert result.status == 0
