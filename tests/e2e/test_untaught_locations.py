"""Moves to Locations a program never taught fail as on a controller.

* An Angles Location that holds no values (``l.Type = 1`` and nothing else) holds 12 zeros, as a
  controller's does (a real TCS writes an untaught station as ``Angles(0, 0, ...)``): moving there
  is refused where zero is beyond a joint's limit (-1012 on a PF400SX),
  instead of going nowhere.
* ``Move.Approach`` of a Location whose ZClearance was never set is -794 *ZClearance property not
  set*, the controller's code for it (it was -1033 *Invalid Cartesian value*).
"""

from __future__ import annotations

from pathlib import Path

from gpltest import module_src, run_gpl

PROGRAM = """    Public Sub Main()
        Dim p As New Profile
        Dim l As New Location
        Dim c As New Location
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        l.Type = 1
        Console.WriteLine("axis 3 reads " & CStr(l.Angle(3)))
        Try
            Move.Loc(l, p)
            Move.WaitForEOM
            Console.WriteLine("moved")
        Catch ex As Exception
            Console.WriteLine("untaught: " & CStr(ex.ErrorCode))
        End Try
        c = Robot.Where
        Try
            Move.Approach(c, p)
            Move.WaitForEOM
            Console.WriteLine("approached")
        Catch ex As Exception
            Console.WriteLine("approach: " & CStr(ex.ErrorCode))
        End Try
    End Sub"""


def test_untaught_locations_are_refused_with_the_controllers_codes(tmp_path: Path) -> None:
    res = run_gpl(tmp_path, module_src(PROGRAM))
    assert res.status == 0, res.output + res.log
    assert res.output.splitlines() == ["axis 3 reads 0", "untaught: -1012", "approach: -794"]
