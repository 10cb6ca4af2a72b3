"""Real GPL names, transpiled and run (issue 11 items 5, 6, 7, 9; docs/design/real-code.md): what
the program prints is what a controller prints."""

from __future__ import annotations

from pathlib import Path

from gpltest import run_gpl

CLASSES = """Module Cmd
    Public Sub Main()
        Dim sta As New Station
        Command.AddPlugin("LoadSave 1.0")
        Command.AddPlugin("PARobot 2.1")
        Console.WriteLine(CStr(Command.NumPlugins) & " " & Command.PluginVersion(1))
        sta.flags = STA_FL_PAL Or STA_FL_VERT
        If (sta.flags And STA_FL_PAL) <> 0 Then
            If Station.IsVertical(sta) Then
                Console.WriteLine("vertical pallet")
            End If
        End If
        Console.WriteLine(GpoFile.Names())
    End Sub
End Module
Class Command
    Public Const MAX_PLUGIN As Integer = 8
    Public Shared PluginVersion(MAX_PLUGIN-1) As String
    Public Shared NumPlugins As Integer = 0
    Public Shared Sub AddPlugin(ByVal version As String)
        PluginVersion(NumPlugins) = version
        NumPlugins += 1
    End Sub
End Class
Public Class Station
    Public Const STA_FL_PAL As Integer = &H0001
    Public Const STA_FL_VERT As Integer = &H0010
    Public flags As Integer
    Public Shared Function IsVertical(ByVal sta As Station) As Boolean
        Return (sta.flags And STA_FL_VERT) <> 0
    End Function
End Class
Public Class GpoVar
    Public Const GPV_TY_INTEGER As Integer = 1
    Public Const GPV_TY_STRING As Integer = 4
    Public Const GPV_TY_MAX As Integer = 7
End Class
Public Class GpoFile
    Private Shared TypeName(GPV_TY_MAX) As String
    Public Shared Function Names() As String
        TypeName(GPV_TY_INTEGER) = "Integer"
        TypeName(GPV_TY_STRING) = "String"
        Return CStr(TypeName.Length) & " " & TypeName(1) & " " & TypeName(GPV_TY_STRING)
    End Function
End Class
"""


def test_top_level_classes_and_class_constants_from_everywhere(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, {"Cmd.gpl": CLASSES})
    assert r.status == 0, r.log
    assert r.output.splitlines() == ["2 PARobot 2.1", "vertical pallet", "8 Integer String"]


def test_a_variable_of_a_global_class_is_the_class(tmp_path: Path) -> None:
    src = """Module Main
    Private CTL As Controller
    Public Sub Main()
        CTL.PDbNum(10352, 1, 0, 1) = 42
        Console.WriteLine(CStr(Controller.PDbNum(10352, 1, 0, 1)))
        Console.WriteLine(CStr(CTL.PDbNum(10352, 1, 0, 1) + 1))
    End Sub
End Module
"""
    r = run_gpl(tmp_path, src)
    assert r.status == 0, r.log
    assert r.output.splitlines() == ["42", "43"]


OVERLOADS = """Module Main
    Delegate Function Two(ByVal a As Integer, ByVal b As Integer) As Integer
    Delegate Function One(ByVal a As Integer) As Integer
    Private log_count As Integer
    Public Sub Log(ByVal msg As String)
        Log(msg, 0)
    End Sub
    Public Sub Log(ByVal msg As String, ByVal level As Integer)
        log_count += 1
        Console.WriteLine("[" & CStr(level) & "] " & msg)
    End Sub
    Public Function F(ByVal a As Integer) As Integer
        Return a * 10
    End Function
    Public Function F(ByVal a As Integer, ByVal b As Integer) As Integer
        Return a + b
    End Function
    Public Function Kind(ByVal x As Integer) As String
        Return "Integer " & CStr(x)
    End Function
    Public Function Kind(ByVal x As Double) As String
        Return "Double " & CStr(x)
    End Function
    Public Function Kind(ByVal s As String) As String
        Return "String " & s
    End Function
    Public Sub Worker()
        Log("worker started", 1)
    End Sub
    Public Sub Worker(ByVal n As Integer)
        Log("never the thread's start", n)
    End Sub
    Class Shape
        Public what As String
        Public Sub New(ByVal sides As Integer)
            what = CStr(sides) & " sides"
        End Sub
        Public Sub New(ByVal name As String)
            what = name
        End Sub
        Public Shared Function Make() As Shape
            Return Make(3)
        End Function
        Public Shared Function Make(ByVal sides As Integer) As Shape
            Return New Shape(sides)
        End Function
        Public Function Describe() As String
            Return Describe("a")
        End Function
        Public Function Describe(ByVal article As String) As String
            Return article & " shape with " & what
        End Function
    End Class
    Public Sub Main()
        Dim t As New Thread("Worker")
        Dim d2 As Two
        Dim d1 As One
        Dim dd As Double = 2.5
        Log("hello")
        Log("warning", 2)
        Console.WriteLine(CStr(F(4)) & " " & CStr(F(4, 5)))
        Console.WriteLine(Kind(7) & ", " & Kind(dd) & ", " & Kind("x"))
        Console.WriteLine(New Shape(4).what & ", " & New Shape("circle").what)
        Console.WriteLine(Shape.Make().Describe() & "; " & Shape.Make(5).Describe("one"))
        d2 = New Two("F")
        d1 = New One("Main.F")
        Console.WriteLine(CStr(d2(1, 2)) & " " & CStr(d1(3)))
        d1 = New One(AddressOf F)
        Console.WriteLine(CStr(d1(6)))
        t.Start()
        t.Join(-1)
        Console.WriteLine(CStr(log_count) & " lines")
    End Sub
End Module
"""


def test_overloaded_procedures_run_the_overload_the_arguments_choose(tmp_path: Path) -> None:
    r = run_gpl(tmp_path, OVERLOADS)
    assert r.status == 0, r.log
    assert r.output.splitlines() == [
        "[0] hello",
        "[2] warning",
        "40 9",
        "Integer 7, Double 2.5, String x",
        "4 sides, circle",
        "a shape with 3 sides; one shape with 5 sides",
        "3 30",
        "60",
        "[1] worker started",
        "3 lines",
    ]


def test_a_name_no_overload_fits_at_run_time_is_a_gpl_error(tmp_path: Path) -> None:
    src = """Module Main
    Delegate Function Three(ByVal a As Integer, ByVal b As Integer, ByVal c As Integer) As Integer
    Delegate Function OneS(ByVal s As String) As String
    Public Function F(ByVal a As Integer) As Integer
        Return a
    End Function
    Public Function F(ByVal a As String) As String
        Return a
    End Function
    Public Function F(ByVal a As Integer, ByVal b As Integer) As Integer
        Return a + b
    End Function
    Public Sub Main()
        Dim d3 As Three
        Dim d1 As OneS
        Try
            d3 = New Three("F")
        Catch ex As Exception
            Console.WriteLine("three " & CStr(ex.ErrorCode))
        End Try
        Try
            d1 = New OneS("F")
        Catch ex As Exception
            Console.WriteLine("one " & CStr(ex.ErrorCode))
        End Try
    End Sub
End Module
"""
    r = run_gpl(tmp_path, src)
    assert r.status == 0, r.log
    # no F takes 3 arguments: -741 Argument mismatch; two take 1: -772 Ambiguous
    assert r.output.splitlines() == ["three -741", "one -772"]


def test_constants_across_modules_size_arrays_whatever_the_module_order(tmp_path: Path) -> None:
    # corpus Globals.gpl / Startup.gpl: Globals initialises first
    globals_ = """Module Globals
    Public Const N_ROB As Integer = Startup.NumRobots
    Public Const N_ALL As Integer = N_ROB * Startup.PerRobot + 1
    Public CmdObject(N_ROB) As String
    Public Table(N_ALL) As Integer
    Public Sub Main()
        Console.WriteLine(CStr(CmdObject.Length) & " " & CStr(Table.Length) & " " & CStr(Startup.Early))
    End Sub
End Module
"""
    startup = """Module Startup
    Public Const NumRobots As Integer = 4
    Public Const PerRobot As Integer = 3
    Public Early As Integer = Globals.N_ALL
End Module
"""
    r = run_gpl(tmp_path, {"Globals.gpl": globals_, "Startup.gpl": startup})
    assert r.status == 0, r.log
    assert r.output.splitlines() == ["5 14 13"]


def test_a_notebook_calls_the_overload_its_arguments_fit(tmp_path: Path) -> None:
    from gpl2py.notebook import Cell
    from gpltest import code_of, write_project

    proj = write_project(tmp_path, {"Main.gpl": """Module Main
    Public Function Twice(ByVal x As Integer) As Integer
        Return 2 * x
    End Function
    Public Function Twice(ByVal x As Integer, ByVal y As Integer) As Integer
        Return 2 * x + y
    End Function
    Public Sub Main()
    End Sub
End Module
"""})
    cell = Cell.load(proj, cache_dir=tmp_path / "cache", echo=False)
    assert cell.call("Twice", 3) == 6
    assert cell.call("Main.Twice", 3, 4) == 10
    assert code_of(cell.call, "Twice") == -741  # neither takes no argument
    assert code_of(cell.procedure, "Twice") == -772  # which one, without a count?
