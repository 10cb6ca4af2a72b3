"""``Robot.RapidDecel(robot)`` alone on a line stops the robot (docs/design/real-code.md).

The vendor's TCS implements its ``halt`` command as that one statement (Cmd.gpl:1841).  Read in an
expression, the member stays the in-progress flag and stops nothing.
"""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl

PROGRAM = """    Public Sub Main()
        Dim prof As New Profile
        Dim far As New Location
        Dim busy As Boolean
        prof.Speed = 10
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        far.Angles(250, 0, 180, 0, 80)
        Move.Loc(far, prof)
        Move.WaitForEOM
        far.Angles(250, 60, 120, 0, 80)
        Move.Loc(far, prof)
        Thread.Sleep(200)
        busy = Robot.RapidDecel(1)
        Console.WriteLine("reading stops nothing: " & CStr(Robot.TrajState(1) <> 1) & " " & CStr(busy))
        Robot.RapidDecel(1)
        Console.WriteLine("decelerating: " & CStr(Robot.RapidDecel(1)))
        Move.WaitForEOM
        Console.WriteLine("J2 " & Format(Robot.WhereAngles(1).Angle(2), "0.000"))
        Console.WriteLine("J3 " & Format(Robot.WhereAngles(1).Angle(3), "0.000"))
    End Sub"""


def test_rapid_decel_as_a_statement_stops_the_robot(tmp_path: Path) -> None:
    res = run_gpl(tmp_path, module_src(PROGRAM))
    lines = res.output.splitlines()
    assert res.status == 0, res.output + res.log
    assert lines[0] == "reading stops nothing: -1 0"  # still moving, no deceleration asked
    assert lines[1] == "decelerating: -1"
    j2 = float(lines[2].split()[1])
    j3 = float(lines[3].split()[1])
    # stopped on the way: short of the target (60, 120), well past the start (0, 180)
    assert 1.0 < j2 < 50.0 and 130.0 < j3 < 179.0, res.output
