"""A reader that closes gpl2py's output (``gpl2py run X | head``) ends it quietly: status 141, as a
program that SIGPIPE stops, no message, no traceback -- and never a GPL error of the program that
was writing (it was error -201 "BrokenPipeError" at the user's WriteLine line, status 3)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from gpltest import REPO, module_src, write_project

CHATTY = module_src("""\
    Public Sub Main()
        Dim i As Integer
        While True
            i = i + 1
            Console.WriteLine("line " & CStr(i))
        End While
    End Sub""")


def _gpl2py(*args: str, stdout: int = subprocess.PIPE, stderr: int = subprocess.PIPE) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-m", "gpl2py", *args], stdout=stdout, stderr=stderr,
                            text=True, cwd=REPO, env=os.environ.copy())


def test_run_piped_to_head_ends_quietly(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Main.gpl": CHATTY}, name="Chatty")
    proc = _gpl2py("run", str(proj), "--quiet")
    assert proc.stdout is not None and proc.stderr is not None
    assert [proc.stdout.readline() for _ in range(2)] == ["line 1\n", "line 2\n"]
    proc.stdout.close()  # what head does after its lines
    err = proc.stderr.read()
    assert proc.wait(timeout=120) == 141, err
    assert err == "", err  # no -201, no "Exception ignored ... BrokenPipeError", no traceback


def test_dump_ast_piped_to_head_ends_quietly(tmp_path: Path) -> None:
    src = tmp_path / "Main.gpl"
    src.write_text(CHATTY)
    proc = _gpl2py("dump-ast", str(src))
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()  # the reader is gone before gpl2py writes the tree
    err = proc.stderr.read()
    assert proc.wait(timeout=120) == 141, err
    assert err == "", err


def test_check_with_its_diagnostics_piped_to_head_ends_quietly(tmp_path: Path) -> None:
    src = tmp_path / "Bad.gpl"
    src.write_text("Module Bad\n    Public Sub Main()\n        x = 1\n    End Sub\nEnd Module\n")
    proc = _gpl2py("check", str(src), stdout=subprocess.DEVNULL)
    assert proc.stderr is not None
    proc.stderr.close()  # gpl2py check X 2>&1 | head, after head's lines
    assert proc.wait(timeout=120) == 141
