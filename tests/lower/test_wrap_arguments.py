"""A long argument followed by more arguments wraps into valid Python with the same arguments.

The wrapper packs a long call's arguments one per line and breaks an argument line that is still
too long; the separating comma at the end of that line must stay outside the break (it used to be
parenthesised with the argument: ``f((a + b,) c)``, a SyntaxError).
"""

from __future__ import annotations

import ast
from pathlib import Path

from gpl2py.lower.wrap import wrap
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
