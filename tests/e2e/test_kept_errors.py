"""Code translated despite an error raises the controller's error when the program reaches it
(issue 20, item 2; docs/design/lowering.md, "Code that keeps an error").

``--ignore GPL2001`` on ``x = 1`` with ``x`` undeclared once ended in internal error GPL9000 ("no
lowering for a store into ErrorInfo"); with ``--keep-going`` the line became ``pass``, and a Sub
used as a value was called.  Now each such line raises, when reached, the error the controller's
compiler names for the fault (``gpl2py.messages.RUNTIME_CODES``, from the controller's error
table, spec/gpl-dictionary.md §8): -729 *Undefined symbol* for an undeclared name (the manual:
"Using an undeclared name is a compile error ("Undefined symbol")", spec/gpl-language.md §6.1).
The program's own Try/Catch receives it like any GPL error; the rest of the program runs.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py.cli import main as cli_main
from gpltest import run_gpl

PROGRAM = """Module Main
    Const LIMIT As Integer = 3
    Sub Work()
    End Sub
    Public Sub Main()
        Dim ex As Exception
        Dim i As Integer
        Console.WriteLine("start")
        Try
            x = 1
            Console.WriteLine("not reached 1")
        Catch ex
            Console.WriteLine("x = 1: " & CStr(ex.ErrorCode) & " " & ex.Message)
        End Try
        Try
            Console.WriteLine(CStr(y + 1))
        Catch ex
            Console.WriteLine("read y: " & CStr(ex.ErrorCode))
        End Try
        Try
            i = Work()
        Catch ex
            Console.WriteLine("a Sub as a value: " & CStr(ex.ErrorCode))
        End Try
        Try
            LIMIT = 4
        Catch ex
            Console.WriteLine("a Const assigned: " & CStr(ex.ErrorCode))
        End Try
        Try
            GoTo nowhere
        Catch ex
            Console.WriteLine("GoTo no label: " & CStr(ex.ErrorCode))
        End Try
        Try
            On Error GoTo handler
        Catch ex
            Console.WriteLine("a line that does not parse: " & CStr(ex.ErrorCode))
        End Try
        Console.WriteLine("limit " & CStr(LIMIT))
        i = undeclared_too
        Console.WriteLine("not reached 2")
    End Sub
End Module
"""

CAUGHT = """start
x = 1: -729 *Undefined symbol*: GPL2001: 'x' is not declared
read y: -729
a Sub as a value: -730
a Const assigned: -760
GoTo no label: -723
a line that does not parse: -712
limit 3
"""


def test_ignored_errors_raise_the_controllers_errors_where_the_program_reaches_them(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, PROGRAM, ignore=("GPL",))
    assert r.output == CAUGHT
    # the last one is not caught: the thread ends with it, at its line
    assert r.status == 1
    line = PROGRAM.splitlines().index("        i = undeclared_too") + 1
    assert ("unhandled error: GPL error -729: *Undefined symbol*: GPL2001: 'undeclared_too' is not "
            f"declared (at Main.gpl:{line})") in r.log


def test_keep_going_translates_the_same_errors_the_same_way(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, PROGRAM, keep_going=True)
    assert r.output == CAUGHT and r.status == 1


def test_an_ignore_comment_on_the_line_and_the_command_line(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    """The issue's own example, through ``gpl2py run``: ``x = 1`` with ``x`` undeclared and its
    GPL2001 ignored by a comment runs, and raises -729 at its line; a Catch handles it."""
    source = tmp_path / "Main.gpl"
    source.write_text("Module Main\n    Public Sub Main()\n        Dim ex As Exception\n        Try\n"
                      "            x = 1 ' gpl2py: ignore[GPL2001] (the controller says -729)\n"
                      "        Catch ex\n            Console.WriteLine(\"caught \" & CStr(ex.ErrorCode))\n"
                      "        End Try\n        Console.WriteLine(\"after\")\n    End Sub\nEnd Module\n")
    status = cli_main(["run", str(source), "--cache-dir", str(tmp_path / "cache")])
    out, err = capsys.readouterr()
    assert status == 0 and out == "caught -729\nafter\n", err
    assert "GPL9000" not in err and "0 errors" in err
    status = cli_main(["translate", "--ignore", "GPL2001", str(source).replace("Main.gpl", ""), "-o",
                       str(tmp_path / "out")])
    assert status == 0
