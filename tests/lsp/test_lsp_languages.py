"""V+ and TMscript files in the language server: diagnostics from their front ends (through the one
door, the editor's unsaved text checked), and the outline (document and workspace symbols)."""

from __future__ import annotations

from pathlib import Path

from lsprotocol import types as T

from gpltest import gpl2py
from lspclient import Session, uri

VPLUS = """.PROGRAM main()
  CALL helper(2)
.END
.PROGRAM helper(n)
  TYPE n
.END
"""
TMSCRIPT = """define
{
    int count = 1
}
main
{
    Display(Twice(count))
}
int Twice(int x)
{
    return x * 2
}
"""


def check_json(path: Path, cwd: Path) -> set[tuple[str, int, int, str]]:
    """What ``gpl2py check --json`` reports: (uri, line, column, code), 0-based lines."""
    import json

    done = gpl2py("check", str(path), "--json", cwd=cwd)
    return {(uri(d["file"]), d["line"] - 1, d["column"] - 1, d["code"])
            for d in json.loads(done.stdout)["diagnostics"] if d["file"]}


def published(session: Session, path: Path) -> set[tuple[str, int, int, str]]:
    u = uri(path)
    return {(u, d.range.start.line, d.range.start.character, str(d.code)) for d in session.diagnostics.get(u, [])}


def names(symbols: list[T.DocumentSymbol]) -> list[tuple[str, int]]:
    return [(s.name, s.selection_range.start.line) for s in symbols]


def test_a_vplus_file_gets_its_front_ends_diagnostics_and_outline(tmp_path: Path) -> None:
    folder = tmp_path / "cell"
    folder.mkdir()
    path = folder / "cell.v2"
    path.write_text(VPLUS)
    typed = VPLUS.replace("CALL helper(2)", "CALL helper(2, 3)")  # one argument too many: GPL4303
    with Session(tmp_path) as s:
        s.open(path, typed)
        got = published(s, path) if s.wait_diagnostics(path) is not None else set()
        assert {(e[0], e[1], e[3]) for e in got} == {(uri(path), 1, "GPL4303")}
        assert names(s.document_symbols(path)) == [("main", 0), ("helper", 3)]
        assert [w.name for w in s.workspace_symbols("help")] == ["helper"]
        s.change(path, VPLUS)
        assert s.wait_diagnostics(path) == []
    path.write_text(typed)
    assert got == check_json(path, tmp_path)  # the editor's text, checked as check checks the file


def test_a_tmscript_file_gets_its_front_ends_diagnostics_and_outline(tmp_path: Path) -> None:
    folder = tmp_path / "tm"
    folder.mkdir()
    path = folder / "job.tms"
    path.write_text(TMSCRIPT)
    typed = TMSCRIPT.replace("return x * 2", "return y * 2")  # an undeclared variable
    with Session(tmp_path) as s:
        s.open(path, typed)
        s.wait_diagnostics(path)
        got = published(s, path)
        assert got and all(line == 10 for _, line, _, _ in got), got  # (0-based: "return y * 2")
        assert names(s.document_symbols(path)) == [("define", 1), ("main", 5), ("Twice", 8)]  # (a section: its braces)
        s.change(path, TMSCRIPT)
        assert s.wait_diagnostics(path) == []
    path.write_text(typed)
    assert got == check_json(path, tmp_path)
