"""The real GPL of the shared corpus is syntactically valid GPL to gpl2py (issue 11).

The corpus (``../shared/corpus``, or ``$GPL_CORPUS``; read in place, never copied) is code that
real controllers compile, so neither the lexer nor the parser nor the project loader may report
anything about it: no GPL1xxx diagnostic on any file, except GPL1406 for the protected ``.gpp``
that nobody can read.  Under ``CI=true`` a missing corpus fails these tests.
"""

from __future__ import annotations

from pathlib import Path

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.project import load_project
from gpl2py.gpl.syntax.parser import parse
from gpltest import corpus_dir

_SOURCES = (".gpl", ".gpo")


def _syntax(sink: DiagnosticSink) -> list[str]:
    """Every lexer, parser or loader diagnostic (GPL1xxx), rendered, but the protected file's."""
    return [d.header() for d in sink.sorted() if d.code.startswith("GPL1") and d.code != "GPL1406"]


def test_every_corpus_source_file_lexes_and_parses_without_a_diagnostic() -> None:
    files = sorted(p for p in corpus_dir().rglob("*") if p.suffix.lower() in _SOURCES)
    assert len(files) >= 28, files  # both TCS projects (13 + 15 sources) and the taught .gpo
    found: list[str] = []
    for path in files:
        sink = DiagnosticSink()
        project = load_project(path, sink)  # one file, read as the loader reads every source
        assert project is not None and len(project.sources) == 1, (path, _syntax(sink))
        unit = parse(project.sources[0], sink)
        assert unit.members, path  # something was parsed
        found += _syntax(sink)
    assert found == []


def test_every_corpus_project_loads_with_only_the_protected_file_skipped() -> None:
    projects = sorted(p.parent for p in corpus_dir().rglob("Project.gpr"))
    assert len(projects) >= 2, projects
    for folder in projects:
        sink = DiagnosticSink()
        project = load_project(folder, sink)
        assert project is not None and project.sources, folder
        for src in project.sources:
            parse(src, sink)
        assert _syntax(sink) == [], folder
        protected = sorted(folder.glob("*.gpp"))
        skipped = [d for d in sink if d.code == "GPL1406"]
        assert len(skipped) == len(protected), (folder, [d.header() for d in skipped])
