"""Cosmetics of the generated code (it is a product): folded constants, compound assignments kept,
no unreachable ``return`` and no dead defaults -- with the behaviour unchanged."""

from __future__ import annotations

from pathlib import Path

from gpltest import run_gpl
from gpltest import generated_main_module as gen
from gpltest import main_body

SCALE = """Module Main
    Public total As Double
    Public Const LIMIT As Integer = -3100
    Public Function Scale(ByVal n As Integer) As Double
        Dim x As Double
        Dim s As String
        Dim k As Integer
        x = 10.0
        x *= 0.9
        x += n * 2.5
        x -= 1.0 - 0.5
        s = "a"
        s &= "b" & CStr(n)
        total += x
        k = -153
        k += 1
        Console.WriteLine(s & " " & CStr(k) & " " & CStr(LIMIT))
        If n > 0 Then
            Return x
        Else
            Throw New Exception
        End If
    End Function
    Public Sub Main()
        Console.WriteLine(CStr(Scale(2)) & " " & CStr(total))
        Try
            Scale(0)
        Catch ex As Exception
            Console.WriteLine("thrown")
        End Try
    End Sub
End Module
"""


def test_folded_constants_compound_assignments_and_no_unreachable_return(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, SCALE)
    assert result.output == "ab2 -152 -3100\n13.5 13.5\nab0 -152 -3100\nthrown\n", result.log
    code = next(v for k, v in result.files.items() if k.endswith("/main_mod.py"))
    scale = code.split("def Scale", 1)[1].split("\n\n\n", 1)[0]
    assert "LIMIT: int = -3100" in code
    for line in ("x *= 0.9", "x += n * 2.5", "x -= 1.0 - 0.5", 's += "b" + str(n)', "total += x",
                 "k = -153", "k = chk_int32(_v1) if (_v1 := k + 1) > 2147483647 else _v1"):
        assert f"    {line}\n" in scale, (line, scale)
    assert "chk_int32(-" not in code and "chk_double" not in scale
    assert scale.rstrip().endswith("raise GplException()")  # no unreachable return after it


def test_no_default_for_a_local_assigned_after_unrelated_statements(tmp_path: Path) -> None:
    body = main_body(gen(tmp_path, """        Dim waited As Integer
        Dim other As Integer
        Console.WriteLine("start")
        waited = 0
        If other > 0 Then
            Console.WriteLine("x")
        End If
        other = 2
        While waited < 3
            waited += 1
        End While
        Console.WriteLine(CStr(waited + other))"""))
    assert body.count("waited = 0") == 1, body  # no dead default before the store
    assert body.index('Console.WriteLine("start")') < body.index("waited = 0")
    assert body.count("other = 0") == 1, body  # read by the If before its store: keeps its default


def test_goto_before_the_store_keeps_the_default(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, """Module Main
    Public Sub Main()
        Dim n As Integer
        GoTo skip
        n = 5
skip:
        Console.WriteLine(CStr(n))
    End Sub
End Module
""")
    assert result.output == "0\n", result.log


def test_overloaded_constructors_pass_arguments_only_to_those_that_take_them(tmp_path: Path) -> None:
    src = """Module Main
    Public Class Box
        Public size As Integer
        Public Sub New()
            size = 1
        End Sub
        Public Sub New(ByVal n As Integer)
            size = n
        End Sub
    End Class
    Public Sub Main()
        Dim a As New Box
        Dim b As New Box(7)
        Console.WriteLine(CStr(a.size) & " " & CStr(b.size))
    End Sub
End Module
"""
    result = run_gpl(tmp_path, src)
    text = next(v for k, v in result.files.items() if k.endswith("main_mod.py") or k.endswith("/main.py"))
    assert "        if len(args) == 0:\n            self._new_0()\n" in text
    assert "        elif len(args) == 1:\n            self._new_1(*args)\n" in text
    assert result.output == "1 7\n"
