"""Parsing again only the procedure an edit is in (gpl2py/gpl/syntax/reparse.py, the language
server's keystrokes): the tree and diagnostics are a full parse's, positions and comments included,
and anything it cannot be sure of is parsed whole."""

from __future__ import annotations

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.parser import parse
from gpl2py.gpl.syntax.reparse import reparse_procedure
from gpl2py.source import SourceFile
from gpltest import corpus_dir

TEXT = '''Module Demo
    ' the first one
    Public Sub First(ByVal a As Integer, _
                     ByVal b As Integer)
        Dim x As Integer = a
        x = x + b   ' sum
    End Sub

    Function Second() As Integer
        Return 1
    End Function
End Module

Class Box
    Public Sub Fill()
        Dim n As Integer
        n = 2
    End Sub
End Class
'''


def full(text: str) -> tuple[str, list[str]]:
    sink = DiagnosticSink()
    return A.dump(parse(SourceFile("demo.gpl", text), sink)), [d.header() for d in sink]


def again(old: str, new: str) -> tuple[str, list[str]] | None:
    sink = DiagnosticSink()
    unit = parse(SourceFile("demo.gpl", old), sink)
    got = reparse_procedure(old, unit, list(sink), SourceFile("demo.gpl", new))
    return None if got is None else (A.dump(got[0]), [d.header() for d in got[1]])


@pytest.mark.parametrize("old, new", [
    ("        x = x + b   ' sum", "        x = x * b   ' product"),  # a statement and its comment
    ("        x = x + b   ' sum", "        x = x + "),  # half-typed: a syntax error
    ("        Return 1", "        If True Then"),  # a block left open: closed by End Function
    ("        n = 2", "        n = 3 +"),  # a method of a class
    ("                     ByVal b As Integer)", "                     ByVal b As Double)"),  # a parameter
])
def test_one_procedure_parsed_again_is_a_full_parse(old: str, new: str) -> None:
    before = TEXT.replace("        x = x + b   ' sum", "        x = x - b", 1) if old == "        x = x + " else TEXT
    edited = TEXT.replace(old, new, 1)
    assert again(TEXT, edited) == full(edited)
    assert again(before, TEXT) in (None, full(TEXT))


@pytest.mark.parametrize("old, new", [
    ("        Dim x As Integer = a\n", "        Dim x As Integer = a\n\n"),  # a line added
    ("    Public Sub First(ByVal a As Integer, _", "    Public Sub Firsts(ByVal a As Integer, _"),  # its first line
    ("    End Sub\n\n    Function", "    End Function\n\n    Function"),  # its End line
    ("        x = x + b   ' sum", "    End Sub"),  # a line that closes it early
    ("        x = x + b   ' sum", "    End Module"),  # a line that closes its module
    ("    ' the first one", "    ' the very first one"),  # outside any procedure
])
def test_what_it_cannot_be_sure_of_is_parsed_whole(old: str, new: str) -> None:
    assert again(TEXT, TEXT.replace(old, new, 1)) is None


def test_every_line_of_a_real_procedure(tmp_path: object) -> None:
    """Each line inside a procedure of the corpus's Cmd.gpl, changed: reparsed as a full parse."""
    text = (corpus_dir() / "tcs-3.0C1-pa" / "Cmd.gpl").read_text(errors="replace")
    lines = text.split("\n")
    start = next(i for i, line in enumerate(lines) if "Public Sub Cmd_Version(" in line)
    end = next(i for i in range(start, len(lines)) if lines[i].strip() == "End Sub")
    for i in range(start + 1, end):
        edited = "\n".join(lines[:i] + [lines[i] + " +"] + lines[i + 1:])
        got = again(text, edited)
        assert got is not None and got == full(edited), lines[i]
