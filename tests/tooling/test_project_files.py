"""A project's own files are where the controller has them: /flash/projects/<project>/, and a
relative file name resolves there (gplrt/io/project_files.py) — with gpl2py run, python -m and
Cell.load; links and non-regular files in the project folder are never followed or copied."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from gpltest import gpl2py

MAIN = """Module Main
    Public Sub Main()
        Dim r As New StreamReader("data.txt")
        Console.WriteLine("read: " & r.ReadLine)
        r.Close
        Dim w As New StreamWriter("out.txt")
        w.WriteLine("written")
        w.Close
        Console.WriteLine("flash copy: " & CStr(File.Length("/flash/projects/RelProj/out.txt")))
        Try
            r = New StreamReader("secret.txt")
            Console.WriteLine("secret: " & r.ReadLine)
        Catch ex As Exception
            Console.WriteLine("secret: " & CStr(ex.ErrorCode))
        End Try
    End Sub
End Module
"""


def _project(root: Path) -> Path:
    proj = root / "relproj"
    proj.mkdir()
    (proj / "Main.gpl").write_text(MAIN)
    (proj / "data.txt").write_bytes(b"hello from the project\r\n")
    (root / "secret.txt").write_text("host secret\n")
    os.symlink(root / "secret.txt", proj / "secret.txt")  # a link out of the project: never copied
    (proj / "Project.gpr").write_text('ProjectBegin\nProjectName="RelProj"\nProjectStart="Main"\n'
                                      'ProjectSource="Main.gpl"\nProjectEnd\n')
    return proj


EXPECTED = ["read: hello from the project", "flash copy: 9", "secret: -508"]


def test_gpl2py_run_installs_the_project_files(tmp_path: Path) -> None:
    r = gpl2py("run", str(_project(tmp_path)), "--quiet", "--cache-dir", str(tmp_path / "cache"),
               "--flash", str(tmp_path / "disk"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.splitlines() == EXPECTED
    assert (tmp_path / "disk" / "flash" / "projects" / "RelProj" / "data.txt").is_file()
    assert not (tmp_path / "disk" / "flash" / "projects" / "RelProj" / "secret.txt").exists()


def test_python_m_installs_the_files_written_with_the_package(tmp_path: Path) -> None:
    r = gpl2py(str(_project(tmp_path)), "-o", str(tmp_path / "out"))
    assert r.returncode == 0, r.stderr
    assert sorted(p.name for p in (tmp_path / "out" / "rel_proj" / "_project_files").iterdir()) == \
        ["Main.gpl", "Project.gpr", "data.txt"]
    run = subprocess.run([sys.executable, "-m", "rel_proj"], cwd=tmp_path / "out", capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.splitlines() == EXPECTED


def test_notebook_cell_load_installs_the_files(tmp_path: Path) -> None:
    from gpl2py.notebook import Cell

    cell = Cell.load(_project(tmp_path), cache_dir=tmp_path / "cache")
    cell.run_main()
    assert cell.console.splitlines() == EXPECTED
