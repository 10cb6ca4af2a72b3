"""Semantic diagnostics: positions, codes, one run reports every independent error."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gpl2py.cli import main as cli_main
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.semantics.info import CallInfo, IndexInfo, NewInfo
from gpl2py.transpile import transpile
from gpltest import analyze_text, compiled_modules

TEN_ERRORS = """Module Main
    Public Sub Helper(ByVal a As Integer, ByVal b As Integer)
    End Sub
    Sub Report()
    End Sub
    Public Sub Main()
        Dim i As Integer
        Dim loc As Location
        Dim ex As Exception
        Const K As Integer = 3
        i = undeclared_thing
        i = loc
        Helper(1)
        Dim r As NoSuchType
        K = 4
        i = Report()
        loc.Nope = 1
        If i > 0 Then
            Exit For
        End If
        GoTo nowhere
        i = Other.secret
    End Sub
End Module
Module Other
    Private secret As Integer
End Module
"""

EXPECTED = [
    (11, 13, "GPL2001"),  # undeclared name
    (12, 13, "GPL2005"),  # a Location assigned to an Integer
    (13, 9, "GPL2004"),  # wrong argument count
    (14, 18, "GPL2003"),  # unknown type
    (15, 9, "GPL2027"),  # assigning a Const
    (16, 13, "GPL2009"),  # a Sub used as a value
    (17, 9, "GPL3502"),  # no such built-in member: a warning and a stub (tests/stubs/)
    (19, 13, "GPL2016"),  # Exit For outside a For
    (21, 9, "GPL2017"),  # unknown label
    (22, 13, "GPL2010"),  # Private member of another module
]


def test_ten_semantic_errors_ten_diagnostics_with_positions(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, TEN_ERRORS)
    got = [(d.span.line, d.span.col, d.code) for d in sink.sorted() if d.span is not None]
    assert got == EXPECTED, [d.header() for d in sink.sorted()]


def test_messages_name_the_culprit(tmp_path: Path) -> None:
    _, sink = analyze_text(tmp_path, TEN_ERRORS)
    text = "\n".join(d.message for d in sink.sorted())
    assert "'undeclared_thing' is not declared" in text
    assert "a Location value cannot be used as Integer" in text
    assert "'Helper' takes 2 argument(s), 1 given" in text
    assert "'secret' is Private to Other" in text


def test_case_insensitive_names_forward_references_and_qualified_public(tmp_path: Path) -> None:
    text = """Module A
    Public shared_name As Integer
    Public Sub Main()
        LATER(3)
        kk = 2
        Dim kk As Integer
        SHARED_NAME = b.Only_In_B + kk
    End Sub
    Sub Later(ByVal n As Integer)
    End Sub
End Module
Module B
    Public only_in_b As Integer
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    assert [d.header() for d in sink] == []


def test_ambiguous_public_name_needs_module(tmp_path: Path) -> None:
    text = """Module A
    Public Sub Main()
        Dim i As Integer
        i = aa
        i = B.aa + bb
    End Sub
End Module
Module B
    Public aa As Integer
    Public bb As Integer
End Module
Module C
    Public aa As Integer
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    assert [(d.code, d.span.line, d.span.col) for d in sink] == [("GPL2006", 4, 13)]
    assert "B, C" in next(iter(sink)).message


def test_overloads_of_new_and_call_versus_index(tmp_path: Path) -> None:
    text = """Module A
    Class P
        Public Sub New()
        End Sub
        Public Sub New(ByVal x As Integer, ByVal s As String)
        End Sub
    End Class
    Function F(ByVal i As Integer) As Integer
        Return i
    End Function
    Public Sub Main()
        Dim p As P
        Dim arr(3) As Integer
        p = New P
        p = New P(1, "a")
        p = New P(1)
        arr(F(1)) = F(arr(2))
        arr(1, 2) = 0
    End Sub
End Module
"""
    model, sink = analyze_text(tmp_path, text)
    codes = [(d.code, d.span.line) for d in sink]
    assert codes == [("GPL2013", 16), ("GPL2024", 18)]
    kinds = {type(i) for i in model.info.values()}
    assert {IndexInfo, CallInfo, NewInfo} <= kinds


def test_start_procedure_is_resolved(tmp_path: Path) -> None:
    text = "Module A\n    Sub Main()\n    End Sub\nEnd Module\n"
    model, sink = analyze_text(tmp_path, text, start="a.MAIN")
    assert model.start is not None and model.start.name == "Main"
    assert [d.code for d in sink] == ["GPL2025"]  # not Public: warned, started anyway (AMB-20)
    _, sink = analyze_text(tmp_path, text, start="Nope")
    assert [d.code for d in sink] == ["GPL2019"]


def test_zero_argument_members_with_or_without_parentheses(tmp_path: Path) -> None:
    text = """Module A
    Function Five() As Integer
        Return 5
    End Function
    Public Sub Main()
        Dim ex As New Exception
        Dim s As String
        Dim i As Integer
        s = ex.Message
        s = ex.Message()
        i = Five + Five()
        Console.WriteLine(s)
    End Sub
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    assert [d.header() for d in sink] == []


def test_goto_into_for_body_or_out_of_finally_is_reported(tmp_path: Path) -> None:
    f = tmp_path / "Main.gpl"
    f.write_text("""Module Main
    Public Sub Main()
        Dim i As Integer
        GoTo inside
        For i = 1 To 3
inside:
            Console.WriteLine(i)
        Next
        Try
            GoTo after
        Finally
            GoTo after
        End Try
after:
    End Sub
End Module
""")
    sink = DiagnosticSink()
    assert transpile(str(f), sink) is None
    got = [(d.code, d.severity.value, d.span.line) for d in sink.sorted()]
    # GPL2032: a single file runs its only Public Sub Main (no ProjectStart)
    # (line 10, a GoTo out of a Try, is accepted: real code does it, docs/design/real-code.md)
    assert got == [("GPL2032", "warning", 2), ("GPL3001", "error", 4), ("GPL3002", "error", 12)]
    # the message names the For loop: jumps into If, While, Do and Case bodies are accepted
    into_for = next(d for d in sink.sorted() if d.code == "GPL3001")
    assert "into a For loop" in into_for.message, into_for.message
    # and GPL3002 does not call the jump out of the Try (line 10, accepted) illegal
    out_of_finally = next(d for d in sink.sorted() if d.code == "GPL3002")
    assert "leaves a Finally block" in out_of_finally.message, out_of_finally.message


def test_implicit_number_to_string_is_a_warning(tmp_path: Path) -> None:
    text = """Module A
    Public Sub Main()
        Dim s As String
        s = 5
        s = "n=" & 5
        s = CStr(5)
    End Sub
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    assert [(d.code, d.severity.value, d.span.line) for d in sink] == [("GPL2031", "warning", 4)]
    assert list(sink)[0].message.startswith("an Integer value is stored into a String")  # not "a Integer"


# A two-file project with eleven different semantic errors (eleven codes), every one an error (no
# warnings among them), through the command a porting engineer types: eleven diagnostics with
# file:line:col, exit status 1 and no output written.
TEN_ERRORS_CELL = """Module Cell
    Public count As Integer
    Private hidden As Double
    Public Sub Place(ByVal slot As Integer, ByVal speed As Double)
    End Sub
    Public Function Total() As Integer
        Return count
    End Function
    Public Sub Main()
        Dim loc As Location
        Dim n As Integer
        Dim s As String
        Const LIMIT As Integer = 4
        n = loc
        Place(1)
        n = Station.secret
        LIMIT = 5
        n = missing_var + 1
        Dim r As Gripperz
        GoTo nowhere
        Me.count = 1
        n = Station.Ping()
    End Sub
End Module
"""
TEN_ERRORS_STATION = """Module Station
    Private secret As Integer
    Public Sub Ping()
    End Sub
    Public Sub Run()
        Dim a(3) As Integer
        a(1, 2) = 0
        Exit Do
    End Sub
End Module
"""
EXPECTED_CELL = [
    ("Cell.gpl", 14, 13, "GPL2005"),  # a Location assigned to an Integer
    ("Cell.gpl", 15, 9, "GPL2004"),  # wrong argument count
    ("Cell.gpl", 16, 13, "GPL2010"),  # Private member of another module
    ("Cell.gpl", 17, 9, "GPL2027"),  # assigning a Const
    ("Cell.gpl", 18, 13, "GPL2001"),  # undeclared name
    ("Cell.gpl", 19, 18, "GPL2003"),  # unknown type
    ("Cell.gpl", 20, 9, "GPL2017"),  # unknown label
    ("Cell.gpl", 21, 9, "GPL2021"),  # Me outside a class
    ("Cell.gpl", 22, 13, "GPL2009"),  # a Sub used as a value
    ("Station.gpl", 7, 9, "GPL2024"),  # wrong number of subscripts
    ("Station.gpl", 8, 9, "GPL2016"),  # Exit Do outside a Do
]


def test_eleven_errors_in_a_project_through_the_command(tmp_path: Path,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    proj = tmp_path / "cell"
    proj.mkdir()
    (proj / "Cell.gpl").write_text(TEN_ERRORS_CELL)
    (proj / "Station.gpl").write_text(TEN_ERRORS_STATION)
    (proj / "Project.gpr").write_text('ProjectBegin\nProjectName="Cell"\nProjectStart="Main"\n'
                                      'ProjectSource="Cell.gpl"\nProjectSource="Station.gpl"\nProjectEnd\n')
    out = tmp_path / "out"
    status = cli_main(["--json", str(proj), "-o", str(out)])
    report = json.loads(capsys.readouterr().out)
    got = [(Path(d["file"]).name, d["line"], d["column"], d["code"]) for d in report["diagnostics"]]
    assert status == 1
    assert got == EXPECTED_CELL, report["diagnostics"]
    assert all(d["severity"] == "error" for d in report["diagnostics"])
    assert not out.exists()


def test_required_parameter_after_optional_and_duplicate_parameter(tmp_path: Path) -> None:
    """Both are errors with positions; with --keep-going the package still compiles (a required
    Python parameter after a default one, or a duplicate one, would be a SyntaxError)."""
    text = """Module A
    Sub F(Optional ByVal a As Integer = 1, ByVal b As Integer)
    End Sub
    Sub G(ByVal y As Integer, ByVal Y As Double)
    End Sub
    Public Sub Main()
        F()
    End Sub
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    got = [(d.code, d.span.line, d.span.col) for d in sink.sorted() if d.span is not None]
    assert got == [("GPL2033", 2, 44), ("GPL2002", 4, 31)]
    assert "parameter 'b' follows an Optional parameter" in sink.errors[0].message
    out = transpile(str(tmp_path / "Main.gpl"), DiagnosticSink(), keep_going=True)
    assert out is not None
    module = compiled_modules(out.files)["main/a_mod.py"]
    # both procedures are in the compiled module, each with its parameters named once
    assert "def F(a: int = 1, b: int" in module and "def G(y: int) -> None:" in module


def test_member_access_through_a_class_and_an_instance_reports_missing_and_private(tmp_path: Path) -> None:
    """Module, class and instance member access share one lookup rule (check._visible_member):
    a Private member seen from outside is GPL2010, a missing one -- or a nested class reached
    through an instance, or an instance member through the class name -- is GPL2007."""
    text = """Module Main
    Public Class Box
        Private secret As Integer
        Public size As Integer
        Public Shared made As Integer
        Public Class Lid
        End Class
    End Class
    Public Sub Main()
        Dim b As New Box
        Dim i As Integer
        i = b.secret
        i = b.nothere
        i = Box.size
        i = Box.made
        i = b.size
        i = b.Lid
    End Sub
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    got = [(d.code, d.span.line, d.span.col) for d in sink.sorted()]
    assert got == [("GPL2010", 12, 13), ("GPL2007", 13, 13), ("GPL2007", 14, 13), ("GPL2007", 17, 13)]
    assert "Box" in sink.errors[0].message and "secret" in sink.errors[0].message
