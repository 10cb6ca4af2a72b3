"""Declarations inside blocks (issue 11, "Real GPL code", item 1; docs/design/real-code.md).

The manual allows ``Dim`` only at a procedure's outermost level; the vendor's TCS declares inside
If, Select and loop blocks and the controller compiles it.  Such a variable has procedure scope:
one symbol, visible (and at its default) before the block runs.  One name declared in two blocks
that do not contain one another, with one type, is that same variable again; every other repeat
stays a duplicate (GPL2002).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.syntax import ast as A
from gpltest import analyze_text


def _module(body: str, decls: str = "") -> str:
    return f"Module Main\n{decls}\n    Public Sub Main()\n{body}\n    End Sub\nEnd Module\n"


def _declarators(node: A.Node) -> list[A.VarDeclarator]:
    out = [node] if isinstance(node, A.VarDeclarator) else []
    for c in node.children():
        out.extend(_declarators(c))
    return out


def test_dims_in_every_kind_of_block_are_procedure_locals(tmp_path: Path) -> None:
    src = _module("""
        Dim n As Integer
        Console.WriteLine(CStr(t) & CStr(late))   ' before the blocks that declare them
        If n = 0 Then
            Dim t As Integer = n + 1
        End If
        Select n
        Case 1
            Dim sel As String = "one"
        End Select
        For n = 1 To 2
            Dim torques(12) As Double
            torques(0) = t
        Next n
        While n < 5
            Dim loc As New Location
            n += 1
        End While
        Try
            Dim inside As Double = 1.5
        Catch ex As Exception
            Dim code As Integer = ex.ErrorCode
        Finally
            Dim late As Integer = 3
        End Try
        Console.WriteLine(sel & CStr(inside) & CStr(code) & CStr(loc.X))""")
    model, sink = analyze_text(tmp_path, src)
    assert [d.header() for d in sink] == []
    main = model.project.modules["main"].members["main"]
    locals_ = main.locals  # type: ignore[attr-defined]
    assert {"t", "sel", "torques", "loc", "inside", "code", "late"} <= set(locals_)
    assert locals_["torques"].type == t.ArrayType(t.DOUBLE, 1)
    assert locals_["loc"].type.name == "Location"


def test_one_name_in_two_sibling_blocks_with_one_type_is_one_variable(tmp_path: Path) -> None:
    src = _module("""
        Dim n As Integer
        If n = 2 Then
            Dim t As Integer = n * 10
        ElseIf n = 3 Then
            Dim T As Integer
        Else
            Dim t As Integer = 1
        End If
        Select n
        Case 1
            Dim buf(3) As String
        Case Else
            Dim buf(7) As String
        End Select
        Console.WriteLine(CStr(t) & buf(0))""")
    model, sink = analyze_text(tmp_path, src)
    assert [d.header() for d in sink] == []
    proc = model.project.modules["main"].members["main"]
    by_name: dict[str, set[int]] = {}
    for d in _declarators(proc.decl):  # type: ignore[attr-defined]
        v = model.local_of(d, proc)  # type: ignore[arg-type]
        assert v is not None, d.name
        by_name.setdefault(d.name.lower(), set()).add(id(v))
    assert {k: len(v) for k, v in by_name.items()} == {"n": 1, "t": 1, "buf": 1}


@pytest.mark.parametrize("body, line", [
    # the same block twice
    ("        Dim t As Integer\n        Dim t As Integer", 5),
    # an outer declaration and one in a block inside it (either order)
    ("        Dim t As Integer\n        If True Then\n            Dim t As Integer\n        End If", 6),
    ("        If True Then\n            Dim t As Integer\n        End If\n        Dim t As Integer", 7),
    ("        For i = 1 To 2\n            Dim t As Integer\n            If i = 1 Then\n                Dim t As Integer\n"
     "            End If\n        Next i", 7),
    # siblings that disagree on the type, or are not plain Dims
    ("        If True Then\n            Dim t As Integer\n        Else\n            Dim t As String\n        End If", 7),
    ("        If True Then\n            Dim t(2) As Integer\n        Else\n            Dim t(2, 2) As Integer\n"
     "        End If", 7),
    ("        If True Then\n            Static t As Integer\n        Else\n            Dim t As Integer\n        End If", 7),
    ("        If True Then\n            Const t As Integer = 1\n        Else\n            Const t As Integer = 2\n"
     "        End If", 7),
])
def test_other_repeated_declarations_stay_duplicates(tmp_path: Path, body: str, line: int) -> None:
    model, sink = analyze_text(tmp_path, _module(body, "    Dim i As Integer"))
    assert [(d.span.line, d.code) for d in sink] == [(line, "GPL2002")]
    assert "already declared in this procedure" in sink.errors[0].message


def test_a_forward_reference_into_a_block_is_typed_by_its_declaration(tmp_path: Path) -> None:
    model, sink = analyze_text(tmp_path, _module("""
        Dim s As String
        s = word
        If s = "" Then
            Dim word As Integer
        End If"""))
    assert [d.code for d in sink] == ["GPL2031"]  # an Integer stored into a String without CStr
    assert model.project.modules["main"].members["main"].locals["word"].type is t.INTEGER  # type: ignore[attr-defined]
