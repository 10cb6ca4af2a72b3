"""The language server on the real 12,000-line TCS project (../shared/corpus/tcs-3.0C1-pa):
hover, definition across modules, references, completion after ``Cmd.``, rename, and a broken
edit followed by a good one, over stdio (its diagnostics against check's: test_lsp_diagnostics)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from lsprotocol import types as T

from gpltest import corpus_dir, gpl2py
from lspclient import Session, apply_edits, uri


@pytest.fixture(scope="module")
def tcs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Session, Path]:
    root = tmp_path_factory.mktemp("tcs")
    folder = Path(shutil.copytree(corpus_dir() / "tcs-3.0C1-pa", root / "tcs"))
    session = Session(root)
    session.open(folder / "Main.gpl")
    session.wait_diagnostics(folder / "Main.gpl")
    yield session, folder
    session.close()


def line_of(path: Path, needle: str) -> tuple[int, int]:
    for i, text in enumerate(path.read_text(errors="replace").splitlines()):
        if needle in text:
            return i, text.index(needle)
    raise AssertionError(needle)


def test_hover_definition_and_references_across_modules(tcs: tuple[Session, Path]) -> None:
    s, folder = tcs
    main = folder / "Main.gpl"
    line, col = line_of(main, "Cmd.NewRobNum = robNumArg")
    hover = s.hover(main, line, col + 4).contents.value
    assert "Public NewRobNum As Integer" in hover and "Class_command.gpl:140" in hover
    assert "Dim Cmd As Command" in s.hover(main, line, col).contents.value
    [loc] = s.definition(main, line, col + 4)
    assert loc.uri == uri(folder / "Class_command.gpl") and loc.range.start.line == 139
    refs = s.references(main, line, col + 4)
    assert {"Main.gpl", "Class_command.gpl"} <= {r.uri.rsplit("/", 1)[-1] for r in refs}
    assert sum(r.uri.endswith("/Main.gpl") for r in refs) == main.read_text(errors="replace").count("Cmd.NewRobNum")


def test_completion_after_cmd_dot_lists_the_command_class(tcs: tuple[Session, Path]) -> None:
    s, folder = tcs
    main = folder / "Main.gpl"
    text = main.read_text(errors="replace")
    line, col = line_of(main, "Cmd.NewRobNum = robNumArg")
    typing = text.replace("Cmd.NewRobNum = robNumArg", "Cmd.", 1)
    s.change(main, typing)
    items = {i.label: i for i in s.completion(main, line, col + 4)}
    assert {"NewRobNum", "IsStatus", "Rob", "InMsg", "Reply"} <= set(items)
    assert items["NewRobNum"].kind == T.CompletionItemKind.Field
    # broken (half-typed) then good: the diagnostics follow the text
    diags = s.wait_diagnostics(main)
    assert any(d.severity == T.DiagnosticSeverity.Error for d in diags)
    s.change(main, text)
    assert [d for d in s.wait_diagnostics(main) if d.severity == T.DiagnosticSeverity.Error] == []


def test_rename_a_public_field_project_wide(tcs: tuple[Session, Path], tmp_path: Path) -> None:
    s, folder = tcs
    main = folder / "Main.gpl"
    line, col = line_of(main, "Cmd.NewRobNum = robNumArg")
    edit = s.rename(main, line, col + 4, "RequestedRobot")
    assert edit is not None and len(edit.changes) >= 2
    copy = Path(shutil.copytree(folder, tmp_path / "renamed"))
    for u, edits in edit.changes.items():
        target = copy / u.rsplit("/", 1)[-1]
        target.write_text(apply_edits(target.read_text(errors="replace"), edits))
    before = json.loads(gpl2py("check", str(folder), "--json", cwd=tmp_path).stdout)["summary"]
    after = json.loads(gpl2py("check", str(copy), "--json", cwd=tmp_path).stdout)["summary"]
    assert after == before and before["errors"] == 0
    assert "NewRobNum" not in "".join(p.read_text(errors="replace") for p in copy.glob("*.gpl"))
