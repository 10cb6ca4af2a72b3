"""The lowering is a visitor that raises on what it has no rule for (issue 13, item 4).

A statement kind or a kind of meaning (``semantics/info.py``) that the lowering does not handle is
a gap in gpl2py: it must come out as internal error GPL9000 *at the node's position*, with a
non-zero exit, never as ``None`` in the generated Python or a statement silently left out.  The
tests plant such a node in a correctly analysed program, as a future pass or a bug would.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest

import gpl2py.gpl.pipeline as pipeline_module
import gpl2py.transpile as transpile_module
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.semantics.info import Info, VarInfo
from gpl2py.gpl.syntax import ast as A
from gpltest import write_project

SRC = """Module Main
    Public Sub Main()
        Dim x As Integer
        x = 1
        Console.WriteLine(CStr(x + 2))
    End Sub
End Module
"""


@dataclass(slots=True, eq=False)
class Unheard(A.Stmt):
    """A statement kind the lowering has never heard of."""


@dataclass(eq=False, slots=True)
class UnheardInfo(Info):
    """A kind of meaning the lowering has never heard of."""


def _main_body(units: list[A.SourceUnit]) -> A.Block:
    for unit in units:
        for member in unit.members:
            if isinstance(member, A.ModuleDecl):
                for proc in member.members:
                    if isinstance(proc, A.ProcDecl) and proc.name == "Main":
                        return proc.body
    raise AssertionError("no Sub Main")


def _transpile_planted(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, plant) -> tuple[object, DiagnosticSink]:  # type: ignore[no-untyped-def]
    """Transpile SRC with ``plant(units, model)`` run between analysis and lowering."""
    real = pipeline_module.analyze

    def analyze(units, *args, **kwargs):  # type: ignore[no-untyped-def]
        model = real(units, *args, **kwargs)
        plant(units, model)
        return model

    monkeypatch.setattr(pipeline_module, "analyze", analyze)
    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    project = write_project(tmp_path, {"Main.gpl": SRC})
    sink = DiagnosticSink()
    return transpile_module.transpile(project, sink), sink


def _internal(sink: DiagnosticSink) -> list[str]:
    return [d.header() for d in sink if d.code == "GPL9000"]


def test_the_program_translates_without_the_plant(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out, sink = _transpile_planted(tmp_path, monkeypatch, lambda units, model: None)
    assert out is not None and not sink.has_errors()


def test_an_unknown_statement_kind_is_gpl9000_at_the_statement(tmp_path: Path,
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    def plant(units: list[A.SourceUnit], model: object) -> None:
        body = _main_body(units)
        assign = body.statements[1]  # x = 1, line 4
        body.statements.insert(2, Unheard(assign.span))

    out, sink = _transpile_planted(tmp_path, monkeypatch, plant)
    assert out is None
    (header,) = _internal(sink)
    assert "Main.gpl:4:9: error GPL9000:" in header and "Unheard" in header


def test_an_unknown_kind_of_meaning_is_gpl9000_at_the_expression(tmp_path: Path,
                                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    def plant(units: list[A.SourceUnit], model: object) -> None:
        call = _main_body(units).statements[2]  # Console.WriteLine(CStr(x + 2)), line 5
        assert isinstance(call, A.CallStmt) and isinstance(call.expr, A.Invoke)
        cstr = call.expr.args[0]
        assert isinstance(cstr, A.Invoke)
        plus = cstr.args[0]  # x + 2, column 32
        model.info[plus] = UnheardInfo(model.info[plus].type)  # type: ignore[attr-defined]

    out, sink = _transpile_planted(tmp_path, monkeypatch, plant)
    assert out is None
    (header,) = _internal(sink)
    assert "Main.gpl:5:32: error GPL9000:" in header and "UnheardInfo" in header


def test_a_store_into_a_meaning_without_a_rule_is_gpl9000_not_a_dropped_line(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    def plant(units: list[A.SourceUnit], model: object) -> None:
        assign = _main_body(units).statements[1]  # x = 1
        assert isinstance(assign, A.Assign)
        info = model.info[assign.target]  # type: ignore[attr-defined]
        assert isinstance(info, VarInfo)
        model.info[assign.target] = UnheardInfo(info.type)  # type: ignore[attr-defined]

    out, sink = _transpile_planted(tmp_path, monkeypatch, plant)
    assert out is None
    (header,) = _internal(sink)
    assert "Main.gpl:4:9: error GPL9000:" in header


def test_gpl9000_from_the_command_line_names_the_position_and_exits_2(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    from gpl2py.cli import main as cli_main

    real = pipeline_module.analyze

    def analyze(units, *args, **kwargs):  # type: ignore[no-untyped-def]
        model = real(units, *args, **kwargs)
        body = _main_body(units)
        body.statements.insert(2, Unheard(body.statements[1].span))
        return model

    monkeypatch.setattr(pipeline_module, "analyze", analyze)
    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    project = write_project(tmp_path, {"Main.gpl": SRC})
    status = cli_main(["translate", project, "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert status == 2
    assert "Main.gpl:4:9: error GPL9000:" in err and "Traceback" not in err
