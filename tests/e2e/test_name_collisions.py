"""Issue 12, items 4 and 5: two GPL names never become one Python name, and no GPL name hides a
name the generated code needs (a runtime helper, ``sys``, the package's own ``init``/``main``).

Every test runs the translated program and checks what it prints: a collision shows up as the
wrong variable printed, a module that is not callable (-201), or a package that cannot start.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.run import import_package
from gpl2py.transpile import transpile, write_package
from gpltest import module_src, run_gpl, write_project
from gplrt.sim import Simulation


def output_of(tmp_path: Path, sources: dict[str, str] | str) -> str:
    result = run_gpl(tmp_path, sources)
    assert result.log == "", result.log
    assert result.status == 0
    return result.output


def test_a_name_and_the_same_name_with_an_underscore_stay_two_variables(tmp_path: Path) -> None:
    # list -> list_ (a builtin) and list_ -> list_ printed "2 2"
    src = module_src("""
    Dim list As Integer = 1
    Dim list_ As Integer = 2
    Dim print__ As String = "c"
    Public Sub Main()
        Dim str As String = "a"
        Dim str_ As String = "b"
        Dim print_ As String = "d"
        Dim print As String = "e"
        Console.WriteLine(CStr(list) & " " & CStr(list_) & " " & str & str_ & print__ & print_ & print)
    End Sub""")
    assert output_of(tmp_path, src) == "1 2 abcde\n"


def test_class_fields_that_differ_by_a_trailing_underscore(tmp_path: Path) -> None:
    # two fields in __slots__ with one name: the class could not even be created
    src = module_src("""
    Public Class Pair
        Public type As Integer
        Public type_ As Integer
        Public Shared id As Integer
        Public Shared id_ As Integer
    End Class
    Public Sub Main()
        Dim p As New Pair
        p.type = 1
        p.type_ = 2
        Pair.id = 3
        Pair.id_ = 4
        Console.WriteLine(CStr(p.type) & CStr(p.type_) & CStr(Pair.id) & CStr(Pair.id_))
    End Sub""")
    assert output_of(tmp_path, src) == "1234\n"


def test_static_locals_whose_joined_names_coincide(tmp_path: Path) -> None:
    # Static C of Sub A_B and Static B_C of Sub A were both _s_A_B_C; Static X_done of Sub P was
    # the "initialised" flag of Static X
    src = module_src("""
    Public Sub A_B()
        Static C As Integer = 10
        C += 1
        Console.Write(CStr(C) & " ")
    End Sub
    Public Sub A()
        Static B_C As Integer = 100
        B_C += 1
        Console.Write(CStr(B_C) & " ")
    End Sub
    Public Sub P()
        Static X As Integer = 5
        Static X_done As Integer = 7
        X += 1
        X_done += 1
        Console.Write(CStr(X) & "/" & CStr(X_done) & " ")
    End Sub
    Public Sub Main()
        A_B()
        A()
        A_B()
        A()
        P()
        P()
        Console.WriteLine("")
    End Sub""")
    assert output_of(tmp_path, src) == "11 101 12 102 6/8 7/9 \n"


def test_a_local_spelled_like_a_class_of_its_module(tmp_path: Path) -> None:
    # Dim Station As New Station: the local hid the class (UnboundLocalError, -201)
    src = module_src("""
    Public Class Station
        Public n As Integer
        Public Shared count As Integer
    End Class
    Public Sub Main()
        Dim Station As New Station
        Station.n = 3
        Dim other As Station
        other = New Station
        other.n = 4
        Console.WriteLine(CStr(Station.n) & CStr(other.n))
    End Sub""")
    assert output_of(tmp_path, src) == "34\n"


# module names that were also names the generated code imports or defines
HELPER_MODULES = ["ChkInt32", "Current", "Checkpoint", "RegisterPackage", "UseProcedures", "GplEntry",
                  "Init", "Sys", "ToString", "AsGplException", "Con", "Nul"]


@pytest.mark.parametrize("module", HELPER_MODULES)
def test_a_module_named_like_a_runtime_helper(tmp_path: Path, module: str) -> None:
    # every run failed with -201 (the package's 'current' was the module) or the helper a module
    # needed was the sibling module of the same name
    main = module_src(f"""
    Public Sub Main()
        Dim i As Integer = 2
        Dim k, z As Integer
        Dim d As Double = 0.5
        Dim e As Exception
        While k < 3
            i = i * 2
            k += 1
        End While
        Try
            k = k \\ z
        Catch e
            Console.Write(CStr(e.ErrorCode) & " ")
        End Try
        Console.WriteLine(CStr(i) & " " & CStr({module}.Twice(i)) & " " & CStr(d))
    End Sub""")
    other = module_src("""
    Public Function Twice(ByVal n As Integer) As Integer
        Dim k As Integer = n
        k = k * 2
        Return k
    End Function""", name=module)
    assert output_of(tmp_path, {"Main.gpl": main, f"{module}.gpl": other}) == "-709 16 32 0.5\n"


def test_a_protected_name_spelled_like_a_stub_module_helper(tmp_path: Path) -> None:
    # a protected name 'not_available' became a stub 'def not_available' that replaced the helper
    # every stub calls: using it recursed until the stack ran out instead of raising -204
    main = module_src("""
    Public Sub Main()
        Dim e As Exception
        Try
            not_available(1)
        Catch e
            Console.WriteLine(CStr(e.ErrorCode))
        End Try
        Try
            Other(1)
        Catch e
            Console.WriteLine(CStr(e.ErrorCode))
        End Try
    End Sub""")
    proj = Path(write_project(tmp_path, {"Main.gpl": main}))
    (proj / "Vendor.gpp").write_bytes(b"'#Protected|\x00\x93binary")
    gpr = proj / "Project.gpr"
    gpr.write_text(gpr.read_text().replace("ProjectEnd", 'ProjectSource="Vendor.gpp"\nProjectEnd'))
    sink = DiagnosticSink()
    out = transpile(proj, sink)
    assert out is not None, [d.header() for d in sink]
    write_package(out, tmp_path / "out", sink)
    pkg = import_package(tmp_path / "out" / out.package, f"_collide_{out.package}")
    sim = Simulation(capture=True, project=out.package)
    pkg.main(sim)
    assert sim.console.output == "-204\n-204\n", sim.console.log_text


@pytest.mark.parametrize("project", ["Numpy", "Json", "Gplrt", "Threading"])
def test_a_project_named_like_a_module_the_runtime_imports(tmp_path: Path, project: str) -> None:
    # the package was out/numpy/: 'python -m numpy' from the output folder imported the project
    # as numpy, and the runtime with it
    proj = Path(write_project(tmp_path, {"Main.gpl": module_src("""
    Public Sub Main()
        Console.WriteLine("ran")
    End Sub""")}, name=project))
    sink = DiagnosticSink()
    out = transpile(proj, sink)
    assert out is not None
    assert out.package.lower() != project.lower()
    write_package(out, tmp_path / "built", sink)
    proc = subprocess.run([sys.executable, "-m", out.package], cwd=tmp_path / "built", capture_output=True,
                          text=True, timeout=120)
    assert (proc.returncode, proc.stdout) == (0, "ran\n"), proc.stderr[-2000:]


def test_a_top_level_class_named_like_a_runtime_helper(tmp_path: Path) -> None:
    # found by the corpus fuzz: a class outside any Module called gpl_entry replaced the helper its
    # own module's registrations call (TypeError at import); top-level classes were not counted
    # among the names GPL code uses
    src = """Public Class gpl_entry
    Public v As Integer
    Public Shared Function Make(ByVal k As Integer) As gpl_entry
        Dim g As New gpl_entry
        g.v = k
        Return g
    End Function
    Public Function Twice() As gpl_entry
        Return Make(2 * v)
    End Function
End Class
Module Main
    Public Sub Main()
        Dim g As New gpl_entry
        g.v = 7
        Console.WriteLine(CStr(g.Twice().v))
    End Sub
End Module
"""
    assert output_of(tmp_path, src) == "14\n"
