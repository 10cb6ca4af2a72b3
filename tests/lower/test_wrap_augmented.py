"""Long augmented assignments (``s &= a & b & ...`` written over `` _`` lines) wrap into valid Python.

Found by tests/realworld/tcs_like: vendor code builds replies with long ``&=`` continuation lines;
the wrapper used to parenthesise the whole statement (``(txt += ...)``), a SyntaxError.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from gpl2py.pywriter.wrap import wrap
from gpltest import module_src, run_gpl


@pytest.mark.parametrize("op", ["+=", "-=", "*=", "/=", "//=", "%=", "|=", "&=", "^=", "<<=", ">>="])
def test_augmented_assignment_wraps_only_its_value(op: str) -> None:
    text = f"self.total {op} " + " + ".join(f"value_number_{i}" for i in range(12))
    lines = wrap(2, text)
    assert len(lines) > 2 and all(4 * ind + len(t) <= 99 for ind, t in lines)
    assert lines[0] == (2, f"self.total {op} (")
    wrapped = ast.parse("\n".join("    " * (ind - 2) + t for ind, t in lines))
    # valid Python is not enough: the wrapped statement must mean the original one
    assert ast.dump(wrapped) == ast.dump(ast.parse(text))


def test_long_string_building_line_runs(tmp_path: Path) -> None:
    src = module_src('''
    Public Sub Main()
        Dim txt As String = "C"
        Dim x As Double = 1.5
        txt &= " " & Format(x, "0.000") & " " & Format(x * 2, "0.000") & " " & Format(x * 3, "0.000") _
            & " " & Format(x * 4, "0.000") & " " & Format(x * 5, "0.000") & " " & Format(x * 6, "0.000")
        Console.WriteLine(txt)
    End Sub''')
    assert run_gpl(tmp_path, src).output == "C 1.500 3.000 4.500 6.000 7.500 9.000\n"
