"""Every refusal of the simulated controller reaches a transpiled program's own Try/Catch.

Issue "Simulated controller": Move refuses with the controller's code when the robot is not
attached, power is off or the robot is not homed; a joint beyond its limit and a Cartesian target
out of reach raise their codes; a robot attached by another thread cannot be attached again. The
second program adds the refusals that need a homed robot at a chosen posture: position too close
(-1039), a straight line that would change the arm configuration (-1042), a configuration whose
solution is beyond a joint limit (-1012), and power lost during a motion, reported by the next
WaitForEOM (-1046).
"""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl

#: The module variables and the Try/Catch around one joint move that both programs use.
TRY_MOVE = """    Dim prof As New Profile
    Dim ex As Exception
    Dim target As New Location

    Sub TryMove(ByVal what As String)
        Try
            Move.Loc(target, prof)
            Move.WaitForEOM
            Console.WriteLine(what & ": moved")
        Catch ex
            Console.WriteLine(what & ": " & CStr(ex.ErrorCode))
        End Try
    End Sub
"""

REFUSALS = TRY_MOVE + """
    Dim flag As Integer

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


POSTURE_REFUSALS = TRY_MOVE + """
    Dim line As New Profile

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
        TryMove("righty")
        target.XYZ(4, 3, 250, 0, 90, 180)
        Robot.Tool = Location.XYZValue(0, 0, 0, 0, 0, 0)
        TryMove("too close")
        target.XYZ(350, 150, 250, 0, 90, 180)
        target.Config = GPL_Lefty
        Try
            Move.Loc(target, line)
            Console.WriteLine("straight lefty: moved")
        Catch ex
            Console.WriteLine("straight lefty: " & CStr(ex.ErrorCode))
        End Try
        target.XYZ(200, 300, 250, 0, 90, 180)
        TryMove("lefty beyond J2")
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


def test_each_refusal_is_caught_with_its_code(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src(REFUSALS))
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


def test_posture_refusals_reach_the_programs_catch_with_their_codes(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src(POSTURE_REFUSALS))
    assert result.output == (
        "righty: moved\n"
        "too close: -1039\n"
        "straight lefty: -1042\n"
        "lefty beyond J2: -1012\n"
        "queued\n"
        "power cut: -1046\n"
    ), result.output + result.log
    assert result.status == 0
