"""``--start PROCEDURE`` on a GPL project replaces Project.gpr's ProjectStart (the shared project
option V+ introduced: the program to run), for ``run`` as for ``check``."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from gpltest import write_project

_MAIN = """Module Main
    Public Sub Main()
        Console.WriteLine("main")
    End Sub
    Public Sub Other()
        Console.WriteLine("other")
    End Sub
End Module
"""


def _gpl2py(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "gpl2py", *args], capture_output=True, text=True, timeout=300)


def test_start_replaces_project_start_for_a_gpl_project(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": _MAIN}, start="Main.Main")
    cache = str(tmp_path / "cache")
    assert _gpl2py("run", proj, "--quiet", "--cache-dir", cache).stdout == "main\n"
    assert _gpl2py("run", proj, "--quiet", "--cache-dir", cache, "--start", "Main.Other").stdout == "other\n"


def test_start_naming_no_procedure_is_the_project_start_error(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": _MAIN}, start="Main.Main")
    r = _gpl2py("check", proj, "--start", "Main.Nothing")
    assert r.returncode == 1
    assert "Main.Nothing" in r.stderr


def test_start_for_a_language_without_one_is_refused_not_an_internal_error(tmp_path: Path) -> None:
    src = tmp_path / "x.tms"
    src.write_text("main\n{\n}\n")
    r = _gpl2py("check", str(src), "--start", "foo")
    assert r.returncode == 1
    assert "error GPL9001: --start: a TMscript project has no start to choose" in r.stderr
    assert "GPL9000" not in r.stderr
