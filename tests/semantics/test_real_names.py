"""Names as real GPL uses them (issue 11; docs/design/real-code.md): top-level classes and their
Public Const/Shared members reached from anywhere, a Const usable in Shared procedures, a variable
of a global class standing for the class, overloaded procedures, and Consts folded across modules.
"""

from __future__ import annotations

from pathlib import Path

from gpl2py.gpl.semantics.info import AddressOfInfo, BuiltinMemberInfo, CallInfo
from gpl2py.gpl.semantics.symbols import OverloadSet, VarSym
from gpltest import analyze_project, analyze_text

CLASSES = """Module Cmd
    Public Sub Main()
        Dim n As Integer
        Command.AddPlugin("v1")
        n = Command.NumPlugins + STA_FL_PAL
        If (n And STA_FL_VERT) <> 0 Then
            n = GpoVar.GPV_TY_MAX
        End If
    End Sub
End Module
Class Command
    Public Shared NumPlugins As Integer
    Public Shared Sub AddPlugin(ByVal version As String)
        NumPlugins += 1
    End Sub
End Class
Public Class Station
    Public Const STA_FL_PAL As Integer = &H0001
    Public Const STA_FL_VERT As Integer = &H0010
    Public flags As Integer
    Public Shared Function IsPallet(ByVal sta As Station) As Boolean
        Return (sta.flags And STA_FL_PAL) <> 0
    End Function
End Class
Public Class GpoVar
    Public Const GPV_TY_MAX As Integer = 7
End Class
Public Class GpoFile
    Private Shared TypeName(GPV_TY_MAX) As String
End Class
"""


def _codes(sink: object) -> list[tuple[str, int]]:
    return [(d.code, d.span.line if d.span else 0) for d in sink]  # type: ignore[attr-defined]


def test_top_level_classes_and_their_public_consts_are_reachable_from_everywhere(tmp_path: Path) -> None:
    # Command.AddPlugin from a module, STA_FL_PAL unqualified in a module and in a Shared function
    # of its own class, GPV_TY_MAX as an array bound in another class (corpus: Load_save.gpl:38,
    # Cmd.gpl:77, Class_station.gpl:120, Class_gpofile.gpl:59)
    model, sink = analyze_text(tmp_path, CLASSES)
    assert _codes(sink) == []
    consts = {v.name: v for v in model.const_values if isinstance(v, VarSym)}
    assert consts["STA_FL_PAL"].shared and model.const_values[consts["STA_FL_PAL"]] == 1


def test_a_class_const_is_shared_and_usable_in_a_shared_procedure(tmp_path: Path) -> None:
    text = """Module M
    Class Box
        Const LIMIT As Integer = 3
        Public size As Integer
        Public Shared Function Cap() As Integer
            Return LIMIT * 2
        End Function
    End Class
    Public Sub Main()
        Dim n As Integer = Box.Cap()
    End Sub
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == []  # was GPL2021 ('Me' in a Shared procedure) for LIMIT


def test_same_public_const_in_two_classes_is_ambiguous_like_module_publics(tmp_path: Path) -> None:
    text = """Module M
    Public Sub Main()
        Dim n As Integer = LIMIT
        n = A.LIMIT + B.LIMIT
    End Sub
End Module
Class A
    Public Const LIMIT As Integer = 1
End Class
Class B
    Public Const LIMIT As Integer = 2
End Class
"""
    _, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == [("GPL2006", 3)]
    assert "A, B" in next(iter(sink)).message


def test_private_and_instance_class_members_stay_qualified(tmp_path: Path) -> None:
    text = """Module M
    Public Sub Main()
        Dim n As Integer = hidden + count
    End Sub
End Module
Class A
    Private Const hidden As Integer = 1
    Public count As Integer
End Class
"""
    _, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == [("GPL2001", 3), ("GPL2001", 3)]


def _protected_project(root: Path, text: str) -> Path:
    proj = root / "Prot"
    proj.mkdir()
    (proj / "Main.gpl").write_text(text)
    (proj / "Lib.gpp").write_bytes(b"'#Protected|\x00\x93\xfa\x01binary vendor code\xff")
    (proj / "Project.gpr").write_text('ProjectBegin\nProjectName="Prot"\nProjectStart="Main"\n'
                                      'ProjectSource="Main.gpl"\nProjectSource="Lib.gpp"\nProjectEnd\n')
    return proj


def test_no_protected_code_stub_for_names_the_project_declares(tmp_path: Path) -> None:
    text = CLASSES.replace("        n = Command.NumPlugins + STA_FL_PAL\n",
                           "        n = Command.NumPlugins + STA_FL_PAL + VendorThing(2)\n")
    _, sink = analyze_project(_protected_project(tmp_path, text))
    stubs = [d.message for d in sink if d.code == "GPL3501"]
    assert len(stubs) == 1 and "'VendorThing'" in stubs[0], stubs  # the one name it does not declare


def test_a_variable_of_a_global_class_stands_for_the_class(tmp_path: Path) -> None:
    # corpus PARobot.gpl:2614 "Private CTL As Controller", then CTL.PDbNum(...) = v
    text = """Module M
    Private CTL As Controller
    Public Sub Main()
        Dim v As Double
        CTL.PDbNum(16050, 1, 0, 1) = 2.5
        v = CTL.PDbNum(16050, 1, 0, 1) + CTL.Timer
    End Sub
End Module
"""
    model, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == []
    members = [i for i in model.info.values() if isinstance(i, BuiltinMemberInfo) and i.owner.name == "Controller"]
    assert members and all(i.static and i.receiver is None for i in members)


def test_new_of_a_global_class_is_an_error(tmp_path: Path) -> None:
    text = "Module M\n    Public Sub Main()\n        Dim c As Controller = New Controller\n    End Sub\nEnd Module\n"
    _, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == [("GPL2036", 3)]


OVERLOADS = """Module M
    Public Sub Log(ByVal msg As String)
        Log(msg, 0)
    End Sub
    Public Sub Log(ByVal msg As String, ByVal level As Integer)
    End Sub
    Function Scale(ByVal x As Integer) As String
        Return "i"
    End Function
    Function Scale(ByVal x As Double) As String
        Return "d"
    End Function
    Function Scale(ByVal s As String) As String
        Return "s"
    End Function
    Public Sub Main()
        Dim d As Double
        Dim sh As Short
        Dim s As String
        Log("a")
        Log("a", 2)
        s = Scale(1) & Scale(d) & Scale("x") & Scale(sh) & Scale(True)
    End Sub
End Module
"""


def _calls(model: object, name: str) -> list[int]:
    """The overload index of each call of ``name``, in source order."""
    infos = [(e.span.line, e.span.col, i.sym.overload_index) for e, i in model.info.items()  # type: ignore[attr-defined]
             if isinstance(i, CallInfo) and getattr(i.sym, "name", "") == name]
    return [k for _, _, k in sorted(infos)]


def test_overloads_are_chosen_by_count_then_by_type(tmp_path: Path) -> None:
    model, sink = analyze_text(tmp_path, OVERLOADS)
    assert _codes(sink) == []
    assert isinstance(model.project.modules["m"].members["log"], OverloadSet)
    assert _calls(model, "Log") == [1, 0, 1]  # Log(msg, 0) inside the first one, then Main's two
    # Integer -> Scale(Integer); Double -> Double; String -> String; Short widens to Integer
    # before Double; a Boolean narrows to a number (cheaper than to a String): Integer
    assert _calls(model, "Scale") == [0, 1, 2, 0, 0]


def test_overload_diagnostics(tmp_path: Path) -> None:
    text = """Module M
    Sub P(ByVal a As Integer)
    End Sub
    Sub P(ByVal b As Integer)
    End Sub
    Sub Q(ByVal a As Single)
    End Sub
    Sub Q(ByVal a As Short)
    End Sub
    Sub R(ByVal a As Location)
    End Sub
    Sub R(ByVal a As Profile)
    End Sub
    Public Sub Main()
        Dim loc As Location
        P(1)
        Q(2.5)
        R(Nothing)
        R(loc, 2)
        R("text")
    End Sub
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    got = _codes(sink)
    assert got == [("GPL2002", 4),  # same parameter types as line 2
                   ("GPL2040", 18),  # Nothing fits both objects equally
                   ("GPL2041", 19),  # no R takes two arguments
                   ("GPL2041", 20)], [d.header() for d in sink]  # a String is no object
    texts = "\n".join(d.message for d in sink)
    assert "R(Location), R(Profile)" in texts
    # Q(2.5): a Double narrows to Single at a smaller cost than to Short: not ambiguous


def test_overloads_in_classes_shared_and_instance(tmp_path: Path) -> None:
    text = """Module M
    Class C
        Public Shared Function Make() As C
            Return Make(1)
        End Function
        Public Shared Function Make(ByVal n As Integer) As C
            Dim c As New C
            Return c
        End Function
        Public Function Area() As Integer
            Return Area(2)
        End Function
        Public Function Area(ByVal k As Integer) As Integer
            Return k
        End Function
    End Class
    Public Sub Main()
        Dim c As C = C.Make()
        Dim n As Integer = c.Area() + c.Area(3) + C.Make(2).Area
    End Sub
End Module
"""
    model, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == []
    assert _calls(model, "Make") == [1, 0, 1]
    assert _calls(model, "Area") == [1, 0, 1, 0]


def test_instance_overloads_are_not_reached_through_the_class(tmp_path: Path) -> None:
    text = """Module M
    Class C
        Public Function Area() As Integer
            Return 1
        End Function
        Public Shared Function Area(ByVal k As Integer) As Integer
            Return k
        End Function
    End Class
    Public Sub Main()
        Dim n As Integer = C.Area(2)
        n = C.Area()
    End Sub
End Module
"""
    _, sink = analyze_text(tmp_path, text)
    assert [c for c, _ in _codes(sink)] == ["GPL2041"]  # C.Area() would need an object
    assert _codes(sink)[0][1] == 12


def test_start_procedure_and_init_among_overloads(tmp_path: Path) -> None:
    text = """Module M
    Public Sub Init(ByVal n As Integer)
    End Sub
    Public Sub Init()
    End Sub
    Public Sub Main(ByVal n As Integer)
    End Sub
    Public Sub Main()
    End Sub
End Module
"""
    model, sink = analyze_text(tmp_path, text, start="Main")
    assert _codes(sink) == []
    assert model.start is not None and not model.start.params and model.start.overload_index == 1
    init = model.project.modules["m"].init_proc
    assert init is not None and not init.params and init.overload_index == 1


def test_addressof_binds_the_overload_that_fits_the_delegate(tmp_path: Path) -> None:
    text = """Module M
    Delegate Function One(ByVal a As Integer) As Integer
    Delegate Function Two(ByVal a As Integer, ByVal b As Integer) As Integer
    Function F(ByVal a As Integer) As Integer
        Return a
    End Function
    Function F(ByVal a As Integer, ByVal b As Integer) As Integer
        Return a + b
    End Function
    Public Sub Main()
        Dim d1 As New One(AddressOf F)
        Dim d2 As Two = New Two(AddressOf F)
    End Sub
End Module
"""
    model, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == []
    bound = sorted((e.span.line, i.sym.overload_index) for e, i in model.info.items() if isinstance(i, AddressOfInfo))
    assert bound == [(11, 0), (12, 1)]


def test_constants_fold_across_modules_in_any_order(tmp_path: Path) -> None:
    # corpus Globals.gpl: Public Const N_ROB As Integer = Startup.NumRobots, Globals first
    text = """Module Globals
    Public Const N_ROB As Integer = Startup.NumRobots
    Public Const HALF As Double = N_ROB / 8 + Limits.K
    Public Const TXT As String = "rob" & CStr(N_ROB) & Chr(33)
    Public Const ROUNDED As Integer = 7 / 2
    Public Const BIG As Integer = N_ROB * 1000000000
    Public Const LIVE As Double = Controller.Timer
    Public Const FROM_LIVE As Double = LIVE + 1
End Module
Class Limits
    Public Const K As Integer = N_ROB \\ 3
End Class
Module Startup
    Public Const NumRobots As Integer = 4
End Module
"""
    model, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == []
    values = {v.name: value for v, value in model.const_values.items()}
    assert values == {"N_ROB": 4, "HALF": 1.5, "TXT": "rob4!", "ROUNDED": 4, "K": 1, "NumRobots": 4}
    # BIG overflows an Integer (-710 when the program initialises it); LIVE needs the controller


def test_a_cycle_of_constants_is_a_diagnostic_not_a_hang(tmp_path: Path) -> None:
    text = """Module A
    Public Const X As Integer = B.Y + 1
    Public Const SELF As Integer = SELF
End Module
Module B
    Public Const Y As Integer = Z * 2
    Public Const Z As Integer = A.X
    Public Const OK As Integer = 3
End Module
"""
    model, sink = analyze_text(tmp_path, text)
    assert _codes(sink) == [("GPL2042", 2), ("GPL2042", 3)]
    texts = [d.message for d in sink]
    assert "A.X -> B.Y -> B.Z -> A.X" in texts[0]
    assert {v.name: value for v, value in model.const_values.items()} == {"OK": 3}
