"""End-to-end: the real-code constructs of issue 11 items 1-4 (docs/design/real-code.md), as small
GPL programs transpiled and run on the simulated controller, with their Console output asserted.

1. ``Dim`` inside If/Select/For/While/Try blocks: procedure scope; the initializer or array
   allocation runs each time the statement does; the variable resets on each procedure entry.
2. ``ReDim Preserve`` on locals, fields and arrays inside objects.
3. A ``_`` continuation glued to a comma.
4. Strings and Nothing: Nothing is the empty String wherever the two meet.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

from gpltest import gpl2py, module_src, run_gpl, write_project


def run_main(tmp_path: Path, body: str, decls: str = "") -> str:
    src = module_src(f"{decls}\n    Public Sub Main()\n{body}\n    End Sub")
    result = run_gpl(tmp_path, src)
    assert result.log == "", result.log
    return result.output


# -- 1. Dim inside blocks -----------------------------------------------------------------------------


def test_a_dim_initializer_in_a_loop_runs_each_time_and_a_bare_dim_keeps_its_value(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim n As Integer
        For n = 1 To 3
            Dim fresh As Integer = 100
            Dim kept As Integer
            fresh += n
            kept += n
            Console.WriteLine(CStr(fresh) & " " & CStr(kept))
        Next n""")
    assert out == "101 1\n102 3\n103 6\n"


def test_a_dim_array_in_a_block_is_allocated_each_time_the_statement_runs(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim n As Integer
        Dim keep() As Integer
        While n < 3
            n += 1
            Dim buf(n) As Integer
            buf(0) += n
            If n = 2 Then keep = buf
            Console.WriteLine(CStr(buf.Length) & " " & CStr(buf(0)))
        End While
        Console.WriteLine("kept " & CStr(keep.Length) & " " & CStr(keep(0)))""")
    assert out == "2 1\n3 2\n4 3\nkept 3 2\n"


def test_a_block_variable_resets_on_each_procedure_entry(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Tally(True)
        Tally(False)
        Tally(True)""", decls="""    Sub Tally(ByVal declare As Boolean)
        Console.WriteLine("entry " & CStr(count) & " " & CStr(loc Is Nothing))
        If declare Then
            Dim count As Integer
            Dim loc As New Location
            Static calls As Integer = 100
            count += 5
            calls += 1
        End If
        count += 1
        Console.WriteLine("exit " & CStr(count) & " " & CStr(loc Is Nothing) & " " & CStr(calls))
    End Sub""")
    # read before its Dim ran: the default; each call starts again from the defaults (a Static in a
    # block is initialised once, on the first execution of its statement, and keeps its value)
    assert out == "entry 0 -1\nexit 6 0 101\nentry 0 -1\nexit 1 -1 101\nentry 0 -1\nexit 6 0 102\n"


def test_dims_in_select_try_and_catch_blocks_run_where_they_stand(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim n As Integer
        For n = 1 To 2
            Select n
            Case 1
                Dim label As String = "one"
                Console.WriteLine(label)
            Case Else
                Dim label As String = "other"
                Console.WriteLine(label & " after " & CStr(n))
            End Select
        Next n
        Try
            Dim d As Double = 1 / 0
        Catch ex As Exception
            Dim code As Integer = ex.ErrorCode
            Console.WriteLine("caught " & CStr(code) & " d=" & CStr(d))
        End Try
        GoTo skip
        If True Then
            Dim skipped As Integer = 9
        End If
skip:
        Console.WriteLine("skipped " & CStr(skipped))""")
    assert out == "one\nother after 2\ncaught -709 d=0\nskipped 0\n"


# -- 2. ReDim Preserve ------------------------------------------------------------------------------------


def test_redim_preserve_grows_and_shrinks_a_local_keeping_what_fits(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim header() As String
        Dim ln As Integer
        For ln = 1 To 3
            ReDim Preserve header(ln - 1)
            header(ln - 1) = "line" & CStr(ln)
        Next ln
        Console.WriteLine(CStr(header.Length) & " " & header(0) & " " & header(2))
        ReDim Preserve header(4)
        Console.WriteLine(CStr(header.Length) & " [" & header(3) & "] " & header(1))
        ReDim Preserve header(0)
        Console.WriteLine(CStr(header.Length) & " " & header(0))
        ReDim header(1)
        Console.WriteLine("[" & header(0) & "]")""")
    assert out == "3 line1 line3\n5 [] line2\n1 line1\n[]\n"


def test_redim_preserve_on_fields_and_arrays_inside_objects(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim item As New GpoVar
        Dim i As Integer
        For i = 0 To 3
            If item.numeric_value Is Nothing Then
                ReDim item.numeric_value(i)
            Else
                ReDim Preserve item.numeric_value(i)
            End If
            item.numeric_value(i) = i * 1.5
        Next i
        ReDim Preserve item.locs(1)
        item.locs(1) = New Location
        ReDim Preserve item.locs(2)
        Console.WriteLine(CStr(item.numeric_value.Length) & " " & CStr(item.numeric_value(3)) & " " _
            & CStr(item.numeric_value(1)))
        Console.WriteLine(CStr(item.locs(0) Is Nothing) & " " & CStr(item.locs(1) Is Nothing) & " " _
            & CStr(item.locs.Length))
        ReDim Preserve counts(2)
        counts(2) = 7
        ReDim Preserve counts(3)
        Console.WriteLine(CStr(counts(2)) & " " & CStr(counts.Length))""",
        decls="""    Dim counts() As Integer
    Class GpoVar
        Public numeric_value() As Double
        Public locs() As Location
    End Class""")
    assert out == "4 4.5 1.5\n-1 0 3\n7 4\n"


def test_redim_preserve_of_a_matrix_keeps_elements_at_their_subscripts(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim m(1, 1) As Integer
        Dim i, j As Integer
        Dim s As String = ""
        m(0, 0) = 1
        m(0, 1) = 2
        m(1, 0) = 3
        m(1, 1) = 4
        ReDim Preserve m(1, 2)
        ReDim Preserve m(2, 2)
        For i = 0 To 2
            For j = 0 To 2
                s &= CStr(m(i, j))
            Next j
            s &= " "
        Next i
        Console.WriteLine(s)""")
    assert out == "120 340 000 \n"


def test_redim_preserve_in_a_procedure_does_not_rebind_a_byval_array(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim a(1) As Integer
        a(1) = 5
        Grow(a)
        Console.WriteLine(CStr(a.Length))
        GrowRef(a)
        Console.WriteLine(CStr(a.Length) & " " & CStr(a(1)))""", decls="""    Sub Grow(ByVal x() As Integer)
        ReDim Preserve x(9)
    End Sub
    Sub GrowRef(ByRef x() As Integer)
        ReDim Preserve x(9)
    End Sub""")
    assert out == "2\n10 5\n"


# -- 3. continuation glued to a comma -------------------------------------------------------------


def test_a_call_continued_after_a_comma_glued_underscore_gets_every_argument(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim lcc As New Location
        lcc.XYZ(1, 2, 3,_
           4, 5,_
           6)
        Console.WriteLine(CStr(lcc.X) & "," & CStr(lcc.Z) & "," & CStr(lcc.Roll) & Join("a",_
            "b"))""", decls="""    Function Join(ByVal a As String, ByVal b As String) As String
        Return "/" & a & b
    End Function""")
    assert out == "1,3,6/ab\n"


# -- 4. Strings and Nothing ---------------------------------------------------------------------------------


def test_strings_meet_nothing_as_the_empty_string(tmp_path: Path) -> None:
    out = run_main(tmp_path, """        Dim sValue As String = Nothing
        Dim labels(2) As String
        Dim it As New Holder
        labels(1) = "busy"
        Console.WriteLine(CStr(sValue Is Nothing) & " " & CStr(sValue.Length) & " [" & sValue & "]")
        Console.WriteLine(CStr(labels(0) Is Nothing) & " " & CStr(Not labels(1) Is Nothing))
        labels(1) = Nothing
        Console.WriteLine(CStr(labels(1) Is Nothing) & " " & CStr(labels(1) = "") & " " & CStr(labels(1) = Nothing))
        sValue = "x"
        Console.WriteLine(CStr(sValue Is Nothing) & " " & CStr(sValue = Nothing) & " " & CStr(sValue <> Nothing))
        sValue = Nothing
        Console.WriteLine(CStr(Nothing Is sValue) & " [" & sValue & Nothing & "]")
        Console.WriteLine(CStr(it.name Is Nothing) & " " & CStr(it.text.Length))
        it.name = "n"
        it.name = Nothing
        Console.WriteLine(CStr(it.name Is Nothing) & " " & Show(Nothing) & Show("y") & "|" & NoText() & "|")
        Fill(Nothing)
        Dim loc As New Location
        Console.WriteLine(CStr(loc.Text Is Nothing))
        loc.Text = "taught"
        Console.WriteLine(CStr(Not loc.Text Is Nothing))""", decls="""    Class Holder
        Public name As String
        Public text As String = Nothing
    End Class
    Function Show(Optional ByVal s As String = Nothing) As String
        If s Is Nothing Then Return "<none>"
        Return s
    End Function
    Function NoText() As String
        Return Nothing
    End Function
    Sub Fill(ByRef s As String)
        Console.WriteLine("fill [" & s & "] " & CStr(s Is Nothing))
        s = "x"
    End Sub""")
    assert out == ("-1 0 []\n"
                   "-1 -1\n"
                   "-1 -1 -1\n"
                   "0 0 -1\n"
                   "-1 []\n"
                   "-1 0\n"
                   "-1 <none>y||\n"
                   "fill [] -1\n"
                   "-1\n"
                   "-1\n")


def test_is_nothing_on_a_stub_result_tests_the_value_it_returns(tmp_path: Path) -> None:
    """A built-in member the simulator lacks is a stub of unknown type; with a Python stub that
    returns None, "" or an object, ``Is Nothing`` answers as for an object or a String."""
    proj = Path(write_project(tmp_path, {"Main.gpl": textwrap.dedent("""\
        Module Main
            Public Sub Main()
                Dim i As Integer
                For i = 0 To 2
                    If Controller.VendorLookup(i) Is Nothing Then
                        Console.WriteLine(CStr(i) & " nothing")
                    ElseIf Not Controller.VendorLookup(i) Is Nothing Then
                        Console.WriteLine(CStr(i) & " something")
                    End If
                Next i
            End Sub
        End Module
        """)}))
    stubs = tmp_path / "stubs"
    stubs.mkdir()
    (stubs / "controller.py").write_text("def VendorLookup(i):\n    return [None, '', object()][i]\n")
    proc = gpl2py("run", str(proj), "--stubs", str(stubs), "--quiet")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == "0 nothing\n1 nothing\n2 something\n"


# -- A class's Shared Sub Init runs at start-up ------------------------------------------------------


def test_a_shared_init_of_a_class_runs_at_start_up_before_its_modules_init(tmp_path: Path) -> None:
    """``Private Shared Sub Init()`` of a top-level class fills its tables ("Init routine called
    automatically at startup", Class_gpofile.gpl:72-74; TCS reads every .gpo through them), and so
    does one of a class nested in a module, before that module's Init, which may use the class.
    An instance ``Sub Init`` is an ordinary method: nothing calls it without an object."""
    files = {
        "Main.gpl": """Module Main
    Public Sub Init()
        Console.WriteLine("module Init sees " & Inner.seen)
    End Sub
    Class Inner
        Public Shared seen As String = "declared"
        Private Shared Sub Init()
            seen = "inner Init"
        End Sub
    End Class
    Public Sub Main()
        Dim t As New Table
        Console.WriteLine(Table.Name(2) & " " & CStr(Table.Count) & " " & Inner.seen & " " & CStr(t.own))
    End Sub
End Module
""",
        "Table.gpl": """Public Class Table
    Public Shared Count As Integer = 1
    Public Shared Name(3) As String
    Public own As Integer
    Private Shared Sub Init()
        Name(2) = "Double"
        Count += 10
    End Sub
End Class
Class Other
    Public Sub Init()
        Console.WriteLine("never")
    End Sub
End Class
""",
    }
    result = run_gpl(tmp_path, files)
    assert result.log == "", result.log
    assert result.output == "module Init sees inner Init\nDouble 11 inner Init 0\n"
