"""Parsing again only the procedure an edit is in (gpl2py/gpl/syntax/reparse.py, the language
server's keystrokes): the tree and diagnostics are a full parse's, positions and comments included,
and anything it cannot be sure of is parsed whole."""

from __future__ import annotations

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.parser import parse
from gpl2py.gpl.syntax.reparse import reparse_procedure
from gpl2py.gpl.syntax.shift import Moves
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


def positions(unit: A.SourceUnit) -> list[tuple[object, ...]]:
    """Where every node starts and ends, and every comment, in tree order (``dump`` shows where
    nodes start only)."""
    out: list[tuple[object, ...]] = []
    stack: list[A.Node] = [unit]
    while stack:
        node = stack.pop()
        out.append((type(node).__name__, node._line, node._col, node._end_line, node._end_col))
        for name in ("leading_comments", "trailing_comment", "header_comment", "end_comments", "end_comment"):
            value = getattr(node, name, None)
            for c in (value if isinstance(value, tuple) else (value,) if value is not None else ()):
                out.append((name, *c.span[1:]))
        if isinstance(node, A.Chain):
            out.append(tuple(node.lines))
        stack.extend(reversed(list(node.children())))
    return out


def full(text: str) -> tuple[str, list[str], list[tuple[object, ...]], list[object]]:
    sink = DiagnosticSink()
    unit = parse(SourceFile("demo.gpl", text), sink)
    return A.dump(unit), [d.header() for d in sink], positions(unit), [tuple(d.span) for d in sink]


def again(old: str, new: str) -> tuple[str, list[str], list[tuple[object, ...]], list[object]] | None:
    sink = DiagnosticSink()
    unit = parse(SourceFile("demo.gpl", old), sink)
    got = reparse_procedure(old, unit, list(sink), SourceFile("demo.gpl", new))
    return None if got is None else (A.dump(got[0]), [d.header() for d in got[1]], positions(got[0]),
                                     [tuple(d.span) for d in got[1]])


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
    ("        Dim x As Integer = a\n", "        Dim x As Integer = a\n\n"),  # Enter
    ("        Dim x As Integer = a\n", "        Dim x As Integer = a\n        x = (1 +\n\n"),  # Enter, typing
    # a pasted block
    ("        Dim x As Integer = a\n", "        Dim x As Integer = a\n        If x > 1 Then ' big\n"
                                      "            x = 1\n        Else\n            x = 2\n        End If\n"),
    ("        Dim x As Integer = a\n", ""),  # a line deleted
    ("        Dim x As Integer = a\n        x = x + b   ' sum\n", ""),  # every line of its body deleted
    ("        Return 1\n", "        Return 1\n\n"),  # in the module's last procedure: its End line moves
    ("        n = 2\n", "\n        n = 2 +\n"),  # a method of the class at the end of the file
])
def test_lines_added_or_removed_in_one_procedure_move_what_is_below(old: str, new: str) -> None:
    """The procedure parsed again, what is below it moved (syntax/shift.py): a full parse's tree,
    every position and comment included, and its diagnostics, the syntax errors below included."""
    text = TEXT.replace("        Return 1\n", "        Return (1 ' unclosed\n", 1) if "Return 1" not in old else TEXT
    text = text.replace("        n = 2\n", "        n = 2 * (\n", 1) if "n = 2" not in old else text
    edited = text.replace(old, new, 1)
    assert old in text and again(text, edited) == full(edited)
    assert again(edited, text) == full(text)  # (and back)


def test_edits_in_a_row_moving_what_earlier_edits_moved_are_full_parses() -> None:
    """Lines added and removed again and again, in one procedure then in others, each edit made
    on the last one's tree with the walks the earlier moves kept (``shift.Moves``, as the
    pipeline keeps them): every tree is a full parse's, positions and comments included.  The
    walks kept must follow the edits: a procedure parsed again and the containers copied on the
    way are not the file's any more, and a member moved whole once (the class, below the module)
    is moved again after an edit inside it made it a new node."""
    first, fill, second = "        Dim x As Integer = a\n", "        n = 2\n", "        Return 1\n"
    edits = [(first, first + "\n"), (first, first + "\n\n"), (fill, fill + "        ' more\n"),
             ("        x = x + b   ' sum\n", ""), (second, second + "\n"), (fill, ""), (first, first + "        x = 1 ' one\n"),
             (second, "")]
    moves = Moves()
    text = TEXT
    sink = DiagnosticSink()
    unit = parse(SourceFile("demo.gpl", text), sink)
    diags = list(sink)
    for old, new in edits:
        assert old in text
        edited = text.replace(old, new, 1)
        got = reparse_procedure(text, unit, diags, SourceFile("demo.gpl", edited), moves)
        assert got is not None and got[2] is not None, (old, new)  # (one procedure, lines moved)
        unit, diags, _ = got
        assert (A.dump(unit), [d.header() for d in diags], positions(unit)) == full(edited)[:3], (old, new)
        text = edited


@pytest.mark.parametrize("old, new", [
    ("    Public Sub First(ByVal a As Integer, _", "    Public Sub Firsts(ByVal a As Integer, _"),  # its first line
    ("    End Sub\n\n    Function", "    End Function\n\n    Function"),  # its End line
    ("        x = x + b   ' sum", "    End Sub"),  # a line that closes it early
    ("        x = x + b   ' sum", "    End Module"),  # a line that closes its module
    ("    ' the first one", "    ' the very first one"),  # outside any procedure
    ("    ' the first one\n", ""),  # a line removed outside any procedure
    ("        x = x + b   ' sum\n", "        x = x + b   ' sum\n    End Sub\n    Sub Third()\n"),  # a procedure added
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


def test_enter_after_every_line_of_a_real_procedure() -> None:
    """Enter after each line inside a procedure of the corpus's Cmd.gpl (2,102 lines, the
    procedure near the top; every third line, a full parse of the file each): the procedure parsed
    again, everything below it moved, a full parse."""
    text = (corpus_dir() / "tcs-3.0C1-pa" / "Cmd.gpl").read_text(errors="replace")
    lines = text.split("\n")
    start = next(i for i, line in enumerate(lines) if "Public Sub Cmd_Version(" in line)
    end = next(i for i in range(start, len(lines)) if lines[i].strip() == "End Sub")
    for i in range(start, end, 3):
        edited = "\n".join(lines[:i + 1] + ["        "] + lines[i + 1:])
        got = again(text, edited)
        assert got is not None and got == full(edited), lines[i]


def test_a_long_chain_of_operators_below_the_edit_moves_too() -> None:
    """A run of 64 operators or more is one Chain node keeping its literal operands' lines in an
    array (ast.py): moved with the rest."""
    chain = "        Return " + " + ".join(["1"] * 70) + " + _\n            " + " + ".join(["2"] * 70) + "\n"
    text = TEXT.replace("        Return 1\n", chain, 1)
    edited = text.replace("        Dim x As Integer = a\n", "        Dim x As Integer = a\n\n\n", 1)
    assert again(text, edited) == full(edited)
    assert again(edited, text) == full(text)


def test_lines_added_in_a_file_with_a_long_dim_parse_it_whole_and_other_edits_do_not() -> None:
    """A Dim of 64 simple names or more keeps its names' positions in arrays and makes its
    declarators when asked (ast.CompactDeclarators), which the analysis keeps as its variables'
    nodes: they are not moved in place, so lines added or removed in a file with one parse the
    file whole.  An edit that adds no line still parses one procedure again, the Dim's too."""
    dim = "        Dim " + ", ".join(f"v{k}" for k in range(70)) + " As Integer\n        v3 = 4\n"
    text = TEXT.replace("        Return 1\n", dim + "        Return v3\n", 1)
    above = text.replace("        x = x + b   ' sum\n", "        x = x + b   ' sum\n\n", 1)
    assert again(text, above) is None and again(above, text) is None
    beside = text.replace("        x = x + b   ' sum\n", "        x = x - b\n", 1)
    assert again(text, beside) == full(beside)
    inside = text.replace("        v3 = 4\n", "        v3 = 5\n", 1)
    assert again(text, inside) == full(inside)
    # (a Dim made long by an edit marks the file too)
    short = TEXT.replace("        Return 1\n", "        Dim v0 As Integer\n        Return v0\n", 1)
    sink = DiagnosticSink()
    got = reparse_procedure(short, parse(SourceFile("demo.gpl", short), sink), list(sink),
                            SourceFile("demo.gpl", text.replace("        v3 = 4\n", "        v3 = 5\n", 1)))
    assert got is not None and got[0].compact_dims
