"""A project without ProjectStart (a folder without Project.gpr, or one file): its only Public
Sub Main starts it, with warning GPL2032; with none or several, ``main()`` and ``gpl2py run`` say so."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from gpl2py.cli import main as cli_main

MAIN = "Module {m}\n    Public Sub {p}()\n        Console.WriteLine(\"{m}.{p} ran\")\n    End Sub\nEnd Module\n"


def _folder(root: Path, *modules: tuple[str, str]) -> Path:
    root.mkdir()
    for m, p in modules:
        (root / f"{m}.gpl").write_text(MAIN.format(m=m, p=p))
    return root


def test_folder_without_gpr_runs_its_only_public_sub_main(tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    proj = _folder(tmp_path / "Cell", ("Station", "Main"), ("Helpers", "Report"))
    status = cli_main(["run", str(proj), "--cache-dir", str(tmp_path / "cache")])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert captured.out == "Station.Main ran\n"
    assert "warning GPL2032" in captured.err and "starting Station.Main" in captured.err


def test_two_mains_leave_the_project_without_a_start(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = _folder(tmp_path / "Cell", ("Station", "Main"), ("Other", "Main"))
    status = cli_main(["run", str(proj), "--cache-dir", str(tmp_path / "cache")])
    captured = capsys.readouterr()
    assert status == 2
    assert "has no start procedure" in captured.err and "single Public Sub Main" in captured.err
    assert captured.out == ""
    assert cli_main([str(proj), "-o", str(tmp_path / "out")]) == 0
    capsys.readouterr()
    r = subprocess.run([sys.executable, "-m", "cell"], cwd=tmp_path / "out", capture_output=True, text=True,
                       timeout=60)
    assert r.returncode == 1
    assert r.stderr.strip() == ("GPL project Cell has no start procedure: Project.gpr names no ProjectStart "
                                "and the project has no single Public Sub Main; call its procedures from "
                                "Python instead")
