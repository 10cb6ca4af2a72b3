"""A straight line that meets a joint limit mid-way, in a transpiled program: Move.Loc queues it
(both ends are fine), the robot stops at the last good cycle, and the program's own Try/Catch
around WaitForEOM gets -1012 with the axis; the program then recovers with a joint move."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gplrt.geometry.location import Location
from gplrt.sim import Simulation
from gpltest import module_src, run_gpl

START = (359.0, 77.02, 269.19, 84.96, 109.06)
#: The goal's joints: J2 stays below +93° at both ends but bulges past it in between.
GOAL_JOINTS = (378.07, 87.16, 269.19, -25.54, 101.24)


def goal_xyz() -> tuple[float, ...]:
    sim = Simulation(capture=True)
    with sim:
        from gplrt.motion import registry

        robot = registry.robot_of(sim, 1)
        loc = Location.from_matrix(robot.forward(np.array(GOAL_JOINTS)))
    return (loc.X, loc.Y, loc.Z, loc.Yaw, loc.Pitch, loc.Roll)


def program(xyz: tuple[float, ...]) -> str:
    x, y, z, yaw, pitch, roll = (repr(float(v)) for v in xyz)
    a = ", ".join(repr(v) for v in START)
    return f"""    Public Sub Main()
        Dim ex As Exception
        Dim line As New Profile
        Dim joint As New Profile
        Dim start As New Location
        Dim goal As New Location
        Dim here As Location
        line.Straight = True
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        start.Angles({a})
        Move.Loc(start, joint)
        Move.WaitForEOM
        goal.XYZ({x}, {y}, {z}, {yaw}, {pitch}, {roll})
        Try
            Move.Loc(goal, line)
            Console.WriteLine("queued")
            Move.WaitForEOM
            Console.WriteLine("arrived")
        Catch ex
            here = Robot.WhereAngles
            Console.WriteLine("stopped: " & CStr(ex.ErrorCode) & " axis " & CStr(ex.Axis))
            If here.Angle(2) <= 93 And here.Angle(2) > 80 Then
                Console.WriteLine("J2 within its limit, past the start")
            End If
        End Try
        Move.Loc(start, joint)
        Move.WaitForEOM
        Console.WriteLine("recovered")
    End Sub"""


def test_a_mid_path_limit_reaches_the_programs_catch_at_waitforeom(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src(program(goal_xyz())))
    assert result.output == ("queued\nstopped: -1012 axis 2\nJ2 within its limit, past the start\n"
                             "recovered\n"), result.output + result.log
    assert result.status == 0
