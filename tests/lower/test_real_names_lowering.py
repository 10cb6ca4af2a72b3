"""Generated code for real GPL names (docs/design/real-code.md, lowering.md "Names"): overloads
get Python names of their own, Consts folded at translation time hold their value from import,
a variable of a global class is the class."""

from __future__ import annotations

from pathlib import Path

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.lower.names import overload_names
from gpl2py.transpile import transpile
from gpltest import generated_main_module as gen
from gpltest import main_body, write_project


def test_overload_names_say_which_overload() -> None:
    assert overload_names("Log", [["String"], ["String", "Integer"]]) == ["Log_1", "Log_2"]
    assert overload_names("Scale", [["Integer"], ["String"], []]) == ["Scale_Integer", "Scale_String", "Scale_0"]
    assert overload_names("Put", [["Double()"], ["Mod.Station"]]) == ["Put_DoubleArray", "Put_Station"]
    assert overload_names("print", [[], ["Integer"]]) == ["print_0", "print_1"]
    assert overload_names("_x", [[], ["Integer"]]) == ["_u_x_0", "_u_x_1"]


def test_overloaded_procedures_are_separate_functions_called_by_their_own_names(tmp_path: Path) -> None:
    text = gen(tmp_path, """        Log("a")
        Log("b", 2)
        Console.WriteLine(Scale(1) & Scale("x"))""", decls="""    Public Sub Log(ByVal msg As String)
        Log(msg, 0)
    End Sub
    Public Sub Log(ByVal msg As String, ByVal level As Integer)
        Console.WriteLine(msg)
    End Sub
    Function Scale(ByVal x As Integer) As String
        Return "i"
    End Function
    Function Scale(ByVal s As String) As String
        Return s
    End Function
    Sub Log_1()
    End Sub""")
    # the user's own Log_1 keeps its name; the overload moves aside
    assert "def Log_1_(msg: str) -> None:\n    Log_2(msg, 0)\n" in text
    assert "def Log_2(msg: str, level: int) -> None:" in text
    assert "def Log_1() -> None:" in text
    assert main_body(text).splitlines() == [
        '    Log_1_("a")', '    Log_2("b", 2)', '    Console.WriteLine(Scale_Integer(1) + Scale_String("x"))']
    # every overload is registered under the GPL name, with its index
    assert ('register_procedure("Main", "Log", gpl_entry(Log_1_), public=True, overload=0, '
            'package=__package__)') in text
    assert ('register_procedure("Main", "Log", gpl_entry(Log_2), public=True, overload=1, '
            'package=__package__)') in text
    assert 'register_procedure("Main", "Log_1", gpl_entry(Log_1), public=False, package=__package__)' in text


def test_static_locals_of_two_overloads_are_two_variables(tmp_path: Path) -> None:
    text = gen(tmp_path, "        Count()\n        Count(2)", decls="""    Sub Count()
        Static n As Integer
        n += 1
    End Sub
    Sub Count(ByVal k As Integer)
        Static n As Integer
        n += k
    End Sub""")
    assert "_s_Count_0_n = 0" in text and "_s_Count_1_n = 0" in text


def test_constructors_with_one_argument_each_dispatch_on_type_for_python_callers(tmp_path: Path) -> None:
    text = gen(tmp_path, '        Dim a As New C(1)\n        Dim b As New C("s")', decls="""    Class C
        Public v As String
        Public Sub New(ByVal x As Integer)
            v = "int"
        End Sub
        Public Sub New(ByVal s As String)
            v = "str"
        End Sub
        Public Sub New(ByVal s As String, ByVal n As Integer)
            v = "two"
        End Sub
    End Class""")
    assert ("        if len(args) == 1 and isinstance(args[0], int):\n"
            "            self._new_0(*args)\n"
            "        elif len(args) == 1:\n"
            "            self._new_1(*args)\n"
            "        elif len(args) == 2:\n"
            "            self._new_2(*args)\n") in text
    body = main_body(text)
    assert "C._create_0(1)" in body and 'C._create_1("s")' in body


def test_folded_constants_hold_their_value_from_import_and_reset(tmp_path: Path) -> None:
    proj = write_project(tmp_path, {"Globals.gpl": """Module Globals
    Public Const N_ROB As Integer = Startup.NumRobots ' Max number of robots
    Public Const LIVE As Integer = Controller.PDbNum(104) * 1000000
    Public CmdObject(N_ROB) As Integer
    Public Sub Main()
    End Sub
End Module
""", "Startup.gpl": "Module Startup\n    Public Const NumRobots As Integer = 4\nEnd Module\n"})
    sink = DiagnosticSink()
    out = transpile(proj, sink)
    assert out is not None, [d.header() for d in sink]
    text = next(v for k, v in out.files.items() if k.endswith("/globals_.py"))
    assert "\nN_ROB: int = 4  # Max number of robots\n" in text
    reset = text.split("def _reset() -> None:", 1)[1].split("\n\n\n", 1)[0]
    init = text.split("def _init() -> None:", 1)[1].split("\n\n\n", 1)[0]
    assert "    N_ROB = 4\n" in reset and "    LIVE = 0\n" in reset
    assert "N_ROB =" not in init  # nothing left to compute when the program starts
    assert "    LIVE = to_int32(Controller.PDbNum(104) * 1000000)\n" in init
    assert init.endswith("    CmdObject = GplArray(\"Integer\", N_ROB)")


def test_class_consts_are_class_attributes_with_their_values(tmp_path: Path) -> None:
    text = gen(tmp_path, "        Console.WriteLine(C.K2)", decls="""    Class C
        Const K As Integer = 3
        Public Const K2 As Integer = K * 2
        Public v As Integer
    End Class""")
    assert '    __slots__ = ("v",)\n    K = 3\n    K2 = 6\n' in text
    assert "    C.K = 3\n    C.K2 = 6\n" in text  # _reset


def test_a_variable_of_a_global_class_lowers_to_the_class(tmp_path: Path) -> None:
    text = gen(tmp_path, """        CTL.PDbNum(16050, 1, 0, 1) = 2.5
        Console.WriteLine(CTL.PDbNum(16050, 1, 0, 1))""", decls="    Private CTL As Controller")
    body = main_body(text)
    assert "Controller.set_PDbNum(16050, 1, 0, 1, 2.5)" in body
    assert "Console.WriteLine(Controller.PDbNum(16050, 1, 0, 1))" in body
    assert "CTL." not in body
