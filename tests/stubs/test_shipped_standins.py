"""gpl2py's own stand-ins for protected vendor code (gpl2py/gpl/standins, docs/design/real-code.md).

TCS with the PARobot plug-in reads ``PARobot_auto_center.Version`` in a module ``Init`` and calls
``AC_InitAutoCenter(robot)`` whenever a client connects; both live in a protected ``.gpp`` file.
Without stand-ins the first ends the project before ProjectStart.  These tests use a small project
of our own with the same protected module name (the corpus itself is run by tests/realworld).
"""

from __future__ import annotations

import contextlib
import io
import itertools
from pathlib import Path

from gpl2py.cli import main as cli_main
from gpl2py.run import import_package
from gplrt.sim import Simulation

_serial = itertools.count()

INTF = """Module AutoIntf
    Public Ver As String

    Public Sub Init()
        Ver = PARobot_auto_center.Version
    End Sub

    Public Sub Start()
        Console.WriteLine("plugin: " & Ver)
        AC_InitAutoCenter(1)
        Console.WriteLine("robot set up")
        Try
            AC_HeightDetect(1)
        Catch ex As Exception
            Console.WriteLine("height detect: " & CStr(ex.ErrorCode))
        End Try
    End Sub
End Module
"""


def _project(root: Path) -> Path:
    proj = root / "AcCell"
    proj.mkdir(parents=True)
    (proj / "AutoIntf.gpl").write_text(INTF)
    (proj / "PARobot_auto_center.gpp").write_bytes(b"'#Protected|PARobot_auto_center.gpl;\x1a\x00\x00\xd6\xf2")
    (proj / "Project.gpr").write_text('ProjectBegin\nProjectName="AcCell"\nProjectStart="AutoIntf.Start"\n'
                                      'ProjectSource="AutoIntf.gpl"\nProjectSource="PARobot_auto_center.gpp"\n'
                                      "ProjectEnd\n")
    return proj


def _translate_and_run(root: Path, *options: str) -> tuple[str, int, object]:
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = cli_main([str(_project(root)), "-o", str(root / "out"), *options])
    assert status == 0, err.getvalue()
    pkg = import_package(root / "out" / "ac_cell", f"_standin_test_{next(_serial)}")
    sim = Simulation(capture=True, project="AcCell")
    code = pkg.main(sim)
    return sim.console.output, code, pkg


def test_startup_reads_the_protected_version_through_the_shipped_stand_in(tmp_path: Path) -> None:
    output, code, pkg = _translate_and_run(tmp_path)
    lines = output.splitlines()
    assert code == 0, output
    assert lines[0].startswith("plugin: PARobot_auto_center") and "stand-in" in lines[0]
    assert lines[1:] == ["robot set up", "height detect: -204"]
    standins = {s["name"]: s["standin"] for s in pkg.PROJECT["stubs"]}  # type: ignore[attr-defined]
    assert standins == {"PARobot_auto_center.Version": True, "AC_InitAutoCenter": True,
                        "AC_HeightDetect": False}


def test_a_user_stub_wins_over_the_shipped_stand_in(tmp_path: Path) -> None:
    mine = tmp_path / "mystubs"
    mine.mkdir()
    (mine / "parobot_auto_center.py").write_text('Version = "my auto-centre 1.0"\n')
    output, code, pkg = _translate_and_run(tmp_path, "--stubs", str(mine))
    assert code == 0 and output.splitlines()[:2] == ["plugin: my auto-centre 1.0", "robot set up"], output
    records = {s["name"]: (s["provided"], s["standin"]) for s in pkg.PROJECT["stubs"]}  # type: ignore[attr-defined]
    assert records["PARobot_auto_center.Version"] == (True, False)
    assert records["AC_InitAutoCenter"] == (True, True)


def test_the_warning_names_the_shipped_stand_in(tmp_path: Path) -> None:
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = cli_main(["check", str(_project(tmp_path))])
    assert status == 0, err.getvalue()
    warned = {line.split("warning GPL3501: ")[1].split("'")[1]: line.rsplit(": ", 1)[1]
              for line in err.getvalue().splitlines() if "warning GPL3501" in line}
    assert warned == {
        "PARobot_auto_center.Version": "gpl2py's stand-in parobot_auto_center.py implements it",
        "AC_InitAutoCenter": "gpl2py's stand-in parobot_auto_center.py implements it",
        "AC_HeightDetect": "a stub is generated that raises error -204 if the program uses it",
    }
