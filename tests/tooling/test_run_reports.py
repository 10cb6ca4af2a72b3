"""``gpl2py run`` tells the user what the program does as a server, stops cleanly on SIGTERM, and
keeps its reports in the controller's words (issue 20, item 6)."""

from __future__ import annotations

import json
from pathlib import Path

from gpltest import gpl2py, module_src, write_project

# Two joint moves: the first is planned and run (the robot's history holds its Ruckig trajectory),
# the second is refused (a PF400 flange must be horizontal), unhandled.
REFUSED_SECOND_MOVE = module_src("""\
    Public Sub Main()
        Dim prof As New Profile
        Dim a As New Location
        Dim b As New Location
        a.Angles(300, 10, 90, -100, 100)
        b.XYZ(500, 0, 100, 0, 0, 0)
        Controller.PowerEnabled = True
        Robot.Attached = 1
        Robot.Home
        Move.Loc(a, prof)
        Move.Loc(b, prof)
        Move.WaitForEOM
    End Sub""")


def test_an_unhandled_motion_error_leaves_json_stderr_clean(tmp_path: Path) -> None:
    """After an unhandled motion error, the frames of the error held the robot and its planned
    motion until the interpreter's exit, where nanobind printed 22 lines of 'leaked ... ruckig.
    Trajectory' -- on the stderr that --json promises to leave clean."""
    proj = write_project(tmp_path, {"Main.gpl": REFUSED_SECOND_MOVE})
    r = gpl2py("run", proj, "--json")
    assert r.returncode == 3
    assert r.stderr == ""
    [error] = json.loads(r.stdout)["run"]["errors"]
    assert (error["code"], error["line"]) == (-1033, 12)
