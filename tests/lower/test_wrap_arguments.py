"""A long argument followed by more arguments wraps into valid Python with the same arguments.

The wrapper packs a long call's arguments one per line and breaks an argument line that is still
too long; the separating comma at the end of that line must stay outside the break (it used to be
parenthesised with the argument: ``f((a + b,) c)``, a SyntaxError).
"""

from __future__ import annotations

import ast
from pathlib import Path

from gpl2py.pywriter.wrap import wrap
from gpltest import module_src, run_gpl


def test_long_first_argument_keeps_its_comma_outside() -> None:
    first = " + ".join(f"alpha_{i}" for i in range(12))
    text = f"foo({first}, beta_0 + beta_1)"
    lines = wrap(1, text)
    assert len(lines) > 3 and all(4 * ind + len(t) <= 99 for ind, t in lines)
    call = ast.parse("\n".join("    " * (ind - 1) + t for ind, t in lines)).body[0].value  # type: ignore[attr-defined]
    assert ast.dump(call) == ast.dump(ast.parse(text).body[0].value)  # type: ignore[attr-defined]


def test_call_with_long_string_argument_runs(tmp_path: Path) -> None:
    src = module_src('''
    Sub Show(ByVal text As String, ByVal n As Integer)
        Console.WriteLine(text & n)
    End Sub
    Public Sub Main()
        Dim first_name_of_thing As String = "a"
        Dim second_name_of_thing As String = "b"
        Dim third_name_of_thing As String = "c"
        Show(first_name_of_thing & " and " & second_name_of_thing & " and " & third_name_of_thing & " and more", 5)
    End Sub''')
    assert run_gpl(tmp_path, src).output == "a and b and c and more5\n"


def test_sole_long_argument_breaks_without_extra_parentheses() -> None:
    text = "Console.WriteLine(" + " + ".join(f"alpha_{i}" for i in range(14)) + ")"
    lines = wrap(1, text)
    assert lines[0] == (1, "Console.WriteLine(") and lines[-1] == (1, ")")
    assert [t[:2] for _, t in lines[1:-1]] == ["al", "+ "]
    assert ast.dump(ast.parse("\n".join("    " * (i - 1) + t for i, t in lines))) == ast.dump(ast.parse(text))


def test_the_last_piece_of_a_sole_argument_stays_inside_the_calls_brackets() -> None:
    """A long condition as the sole argument of a call (``to_bool(a or f(x) != y)``), broken before
    ``or``, whose last piece is itself too long: that piece is still inside the call's brackets,
    so it breaks before ``!=`` without brackets of its own.  It was given some, ``(`` then
    ``or f(x)`` then ``!= y`` then ``)``: a SyntaxError in --keep-going output (the pipeline fuzz,
    once ignored errors became longer calls than ``None``)."""
    long_name = "a_function_with_a_name_long_enough_to_need_a_line_of_its_own"
    text = (f'if to_bool(to_bool(lt({long_name}(-729, 12345), 0)) or StringMembers.Substring(sValue, '
            f'bool_num(not_({long_name}(-729, 1234)))) != "\\""):')
    lines = wrap(2, text)
    assert len(lines) > 3 and all(4 * ind + len(t) <= 99 for ind, t in lines)
    wrapped = "\n".join("    " * (ind - 2) + t for ind, t in lines) + "\n    pass"
    assert ast.dump(ast.parse(wrapped).body[0].test) == ast.dump(ast.parse(text + "\n    pass").body[0].test)  # type: ignore[attr-defined]


def test_a_long_one_line_body_written_after_its_header_keeps_its_text(tmp_path: Path) -> None:
    """The lowering writes a one-line body as ``"    x = ..."`` under its header (a Select entered
    by a GoTo: ``if not _enter1:`` then its match value).  Broken, it came out as blank lines:
    Python refused the module (found by the pipeline fuzz)."""
    depth = 9
    subject = "LongSubjectVariableName + LongSubjectVariableName"
    body = ["Dim LongSubjectVariableName As Integer = 1", "Console.WriteLine(\"start\")", "GoTo inside"]
    for _ in range(depth):
        body += [f"Select Case {subject}", "Case 2"]
    body += ["inside:", "Console.WriteLine(\"inside\")"]
    body += ["End Select"] * depth
    src = "Module Main\nPublic Sub Main()\n" + "\n".join(body) + "\nEnd Sub\nEnd Module\n"
    result = run_gpl(tmp_path, {"Main.gpl": src})
    assert result.output.splitlines() == ["start", "inside"] and result.log == ""
    assert wrap(2, "    x = " + "f(" + ", ".join(["argument"] * 12) + ")")[0] == (3, "x = f(")
