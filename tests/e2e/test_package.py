"""End-to-end behaviour of the command and of the generated package (issue part 1 and 4)."""

from __future__ import annotations

import importlib
import subprocess
import sys
from pathlib import Path

import libcst
import pytest
from pyflakes.api import check as pyflakes_check
from pyflakes.reporter import Reporter

from gpl2py.cli import main as cli_main
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.transpile import transpile
from gpltest import module_src, run_gpl, write_project
from gplrt.lang.sourcemap import format_gpl_traceback
from gplrt.sim import Simulation

REPO = Path(__file__).resolve().parents[2]
PY = sys.executable

TWO_MODULES = {
    "Globals.gpo": """Module Globals
    Public greeting As String = "hello"
    Public order As String
    Public Sub Init()
        order = order & "G"
    End Sub
End Module
""",
    "App.gpl": """' The application module
Module App
    Public total As Integer = 40
    Public Sub Init()
        order = order & "A"
    End Sub
    Public Function AddTo(ByVal n As Integer) As Integer
        total = total + n   ' module variable of this module
        Return total
    End Function
    Public Sub Main()
        Console.WriteLine(greeting & " " & Globals.order & " " & AddTo(2))
    End Sub
End Module
""",
}


def _cli(args: list[str], cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([PY, "-m", "gpl2py", *args], capture_output=True, text=True, cwd=cwd, timeout=120)



def two_frames(module: str) -> str:
    """A module whose Public ``Outer(0)`` fails two calls down (``10 \\ 0`` in ``Inner``, line 3,
    called from line 6): the traceback tests check that both GPL lines are named."""
    return f"""Module {module}
    Function Inner(ByVal d As Integer) As Integer
        Return 10 \\ d
    End Function
    Public Function Outer(ByVal d As Integer) As Integer
        Return Inner(d) + 1
    End Function
    Public Sub Main()
    End Sub
End Module
"""

def test_cli_writes_package_and_python_m_runs_it(tmp_path: Path) -> None:
    proj = write_project(tmp_path, TWO_MODULES, start="App.Main", name="My Cell")
    out = tmp_path / "out"
    r = _cli([proj, "-o", str(out)])
    assert r.returncode == 0, r.stderr
    pkg = out / "my_cell"
    assert sorted(p.name for p in pkg.iterdir()) == [
        "__init__.py", "__main__.py", "_project_files", "_sourcemap.json", "app.py", "globals_.py"]
    # the project folder's own files, which python -m installs in /flash/projects/<project>/
    assert sorted(p.name for p in (pkg / "_project_files").iterdir()) == \
        sorted(p.name for p in Path(proj).iterdir())
    run = subprocess.run([PY, "-m", "my_cell"], capture_output=True, text=True, cwd=out, timeout=120)
    assert run.returncode == 0, run.stderr
    # module variables initialised in ProjectSource order, then each module's Init, then ProjectStart
    assert run.stdout == "hello GA 42\n"
    # the form: python -m out.<package> from the folder above the output folder
    run = subprocess.run([PY, "-m", "out.my_cell"], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert run.returncode == 0 and run.stdout == "hello GA 42\n", run.stderr


def test_output_is_deterministic(tmp_path: Path) -> None:
    proj = write_project(tmp_path, TWO_MODULES, start="App.Main", name="Det")
    first = transpile(proj, DiagnosticSink())
    second = transpile(proj, DiagnosticSink())
    assert first is not None and second is not None
    assert first.files == second.files
    assert str(tmp_path) not in "".join(first.files.values())


def test_import_starts_nothing_and_notebook_calls_public_procedures(tmp_path: Path) -> None:
    proj = write_project(tmp_path, TWO_MODULES, start="App.Main", name="Notebook")
    out = tmp_path / "out"
    assert cli_main([proj, "-o", str(out), "--quiet"]) == 0
    sys.path.insert(0, str(out))
    try:
        pkg = importlib.import_module("notebook")
        assert pkg.globals_.order == ""  # imported: nothing ran (no Init)
        sim = Simulation(capture=True)
        sim.call(pkg.init)
        sim.call(pkg.init)  # idempotent per session
        assert pkg.globals_.order == "GA"
        assert sim.call(pkg.app.AddTo, 5) == 45
        assert sim.console.output == ""
    finally:
        sys.path.remove(str(out))


def test_errors_write_nothing_unless_keep_going(tmp_path: Path) -> None:
    src = module_src("    Public Sub Main()\n        x = 1\n    End Sub")
    proj = write_project(tmp_path, {"Main.gpl": src})
    out = tmp_path / "out"
    r = _cli([proj, "-o", str(out)])
    assert r.returncode == 1
    assert "GPL2001" in r.stderr and "'x' is not declared" in r.stderr
    assert not out.exists()
    r = _cli([proj, "-o", str(out), "--keep-going"])
    assert r.returncode == 1
    assert (out / Path(proj).name.lower()).is_dir()


def test_unhandled_error_reports_code_message_and_gpl_line(tmp_path: Path) -> None:
    src = """Module Main
    Function Inner(ByVal d As Integer) As Integer
        Return 10 \\ d
    End Function
    Public Sub Main()
        Console.WriteLine("before")
        Console.WriteLine(Inner(0))
    End Sub
End Module
"""
    result = run_gpl(tmp_path, src)
    assert result.output == "before\n"
    assert result.status == 1
    assert "-709" in result.log and "*Division by 0*" in result.log and "(at Main.gpl:3)" in result.log


def test_unhandled_python_fault_reports_controller_code_and_gpl_line(tmp_path: Path) -> None:
    src = """Module Main
    Class K
        Public v As Integer
    End Class
    Public Sub Worker()
        Dim k As K
        k.v = 1
    End Sub
    Public Sub Main()
        Dim t As New Thread("Worker")
        t.Start()
        t.Join(-1)
        Console.WriteLine("main goes on")
    End Sub
End Module
"""
    result = run_gpl(tmp_path, src)
    assert result.output == "main goes on\n"
    assert "-757" in result.log and "*Object not instantiated*" in result.log
    assert "(at Main.gpl:7)" in result.log


def test_traceback_names_gpl_file_and_line_of_each_frame(tmp_path: Path) -> None:
    src = two_frames("Main")
    result = run_gpl(tmp_path, src)
    mod = result.package.main_mod
    with pytest.raises(Exception) as info:
        result.sim.call(mod.Outer, 0)
    text = format_gpl_traceback(info.value)
    assert "[GPL Main.gpl:6]" in text and "[GPL Main.gpl:3]" in text


def test_comments_are_carried_and_names_kept(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, dict(TWO_MODULES), start="App.Main")
    app = result.files[[k for k in result.files if k.endswith("/app.py")][0]]
    assert "# The application module" in app
    # (the statement is long: its comment moves to the line above it)
    assert "    # module variable of this module\n" \
        "    total = chk_int32(_v1) if ((_v1 := total + n) > 1073741823 or _v1 < -1073741823) else _v1\n" in app
    assert "def AddTo(n: int) -> int:" in app


def _flakes(text: str, name: str) -> list[str]:
    import io

    out, err = io.StringIO(), io.StringIO()
    pyflakes_check(text, name, Reporter(out, err))
    # The requirement: no undefined names, no unused imports (and no syntax errors).  A local the
    # GPL program assigns but never reads is the program's own business.
    return [line for line in (out.getvalue() + err.getvalue()).splitlines()
            if line and "is assigned to but never used" not in line]


@pytest.mark.parametrize("source", sorted(p.name for p in (REPO / "tests/frontend/sources").glob("*.gpl")))
def test_frontend_sources_compile_and_pass_pyflakes(source: str) -> None:
    path = REPO / "tests/frontend/sources" / source
    sink = DiagnosticSink()
    out = transpile(str(path), sink)
    assert out is not None and not sink.errors, [d.header() for d in sink.sorted()]
    for name, text in out.files.items():
        if name.endswith(".py"):
            compile(text, name, "exec")
            libcst.parse_module(text)
            assert _flakes(text, name) == []


def test_sample_tcp_command_server_compiles_and_passes_pyflakes() -> None:
    sink = DiagnosticSink()
    out = transpile(str(REPO / "samples/tcp_command_server"), sink)
    assert out is not None and not sink.errors, [d.header() for d in sink.sorted()]
    for name, text in out.files.items():
        if name.endswith(".py"):
            compile(text, name, "exec")
            assert _flakes(text, name) == []


def test_a_new_session_starts_from_defaults(tmp_path: Path) -> None:
    src = """Module Main
    Public runs As Integer
    Function Counted() As Integer
        Static calls As Integer = 10
        calls += 1
        Return calls
    End Function
    Public Sub Main()
        runs += 1
        Console.WriteLine(runs & " " & Counted() & " " & Counted())
    End Sub
End Module
"""
    first = run_gpl(tmp_path, src)
    second = Simulation(capture=True)
    assert first.package.main(second) == 0
    assert first.output == second.console.output == "1 11 12\n"


def test_uncaught_error_in_a_script_prints_the_gpl_line_of_every_frame(tmp_path: Path) -> None:
    """A script (or ``python -c``) that imports the package and calls a Public procedure which
    fails two calls down: the uncaught exception's traceback names each frame's GPL file and line
    (gplrt.lang.sourcemap.install_excepthook), not only generated Python lines."""
    src = two_frames("Calc")
    proj = write_project(tmp_path, {"Calc.gpl": src}, start="Calc.Main", name="Tb")
    out = tmp_path / "out"
    assert cli_main([proj, "-o", str(out), "--quiet"]) == 0
    script = ("import tb\nfrom gplrt.sim import Simulation\n"
              "sim = Simulation(capture=True)\nsim.call(tb.init)\nsim.call(tb.calc.Outer, 0)\n")
    r = subprocess.run([PY, "-c", script], capture_output=True, text=True, cwd=out, timeout=120)
    assert r.returncode == 1
    frames = [line for line in r.stderr.splitlines() if "[GPL " in line]
    assert [f.split("[GPL ")[1] for f in frames] == ["Calc.gpl:6]", "Calc.gpl:3]"], r.stderr
    assert "in Outer" in frames[0] and "in Inner" in frames[1]
    last = r.stderr.rstrip().splitlines()[-1]
    assert "GPL error -709: *Division by 0*" in last and last.endswith("(at Calc.gpl:3)"), r.stderr
    ok = subprocess.run([PY, "-c", "import tb\nraise ValueError('plain')\n"], capture_output=True, text=True,
                        cwd=out, timeout=120)
    assert "ValueError: plain" in ok.stderr and "[GPL " not in ok.stderr  # other errors unchanged
