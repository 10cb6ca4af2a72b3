"""Two projects in one process (two notebook Cells) with the same module and procedure names:
threads and delegates started by name find their own project's procedure, not the one loaded last."""

from __future__ import annotations

from pathlib import Path

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.run import build, import_built
from gpltest import write_project
from gplrt.sim import Simulation

SRC = """Module Main
    Delegate Sub Action()
    Public Sub Worker()
        Console.WriteLine("{who} worker")
    End Sub
    Public Sub Main()
        Dim t As New Thread("Worker")
        Dim d As Action
        t.Start()
        t.Join()
        d = New Action("Main.Worker")
        d()
    End Sub
End Module
"""


def _load(root: Path, who: str, cache: Path):  # type: ignore[no-untyped-def]
    proj = write_project(root / who, {"Main.gpl": SRC.format(who=who)}, start="Main.Main", name="Twin")
    sink = DiagnosticSink()
    built = build(proj, sink, cache_dir=cache)
    assert built is not None, [d.header() for d in sink]
    return import_built(built)


def test_each_project_starts_its_own_procedures_by_name(tmp_path: Path) -> None:
    first = _load(tmp_path, "first", tmp_path / "cache")
    second = _load(tmp_path, "second", tmp_path / "cache")  # loaded last
    for pkg, who in ((first, "first"), (second, "second"), (first, "first")):
        sim = Simulation(capture=True, project="Twin")
        assert pkg.main(sim) == 0, sim.console.log_text
        assert sim.console.output == f"{who} worker\n{who} worker\n"
