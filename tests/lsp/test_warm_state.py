"""The door's ``texts`` and ``memo`` (what the language server keeps warm): the same diagnostics as
a cold check, with only the changed file parsed again."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl import pipeline
from gpl2py.transpile import transpile
from gpltest import corpus_dir


def headers(sink: DiagnosticSink) -> list[str]:
    return [d.header() for d in sink.sorted()]


def cold(path: Path) -> list[str]:
    sink = DiagnosticSink()
    transpile(path, sink, keep_modules=False)
    return headers(sink)


def test_warm_checks_equal_cold_ones_and_parse_only_what_changed(tmp_path: Path,
                                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    tcs = shutil.copytree(corpus_dir() / "tcs-3.0C1-pa", tmp_path / "tcs")
    memo: dict[object, object] = {}
    parsed: list[str] = []
    real = pipeline.parse
    monkeypatch.setattr(pipeline, "parse", lambda src, sink: parsed.append(Path(src.path).name) or real(src, sink))

    def warm(texts: dict[str, str] | None = None) -> list[str]:
        sink = DiagnosticSink()
        transpile(tcs, sink, keep_modules=False, texts=texts or {}, memo=memo)
        return headers(sink)

    expected = cold(tcs)
    parsed.clear()
    assert warm() == expected and len(parsed) == 15
    parsed.clear()
    assert warm() == expected and parsed == []  # every tree reused, the analysis run again
    cmd = tcs / "Cmd.gpl"
    edited = cmd.read_text().replace("Public Sub", "Public Sub Broken(\nPublic Sub", 1)
    got = warm({os.path.abspath(cmd): edited})
    assert parsed == ["Cmd.gpl"] and got != expected
    cmd.write_text(edited)  # what a cold check of the edited text says
    assert got == cold(tcs)
    parsed.clear()
    memo_before = len(memo)
    cmd.write_text(edited.replace("Public Sub Broken(\n", "", 1))
    assert warm() == expected and parsed == ["Cmd.gpl"] and len(memo) == memo_before


def test_a_body_edit_lowers_only_its_module_and_reports_what_cold_lowering_does(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    tcs = shutil.copytree(corpus_dir() / "tcs-3.0C1-pa", tmp_path / "tcs")
    memo: dict[object, object] = {}
    lowered: list[str] = []
    real = pipeline.lower_module
    monkeypatch.setattr(pipeline, "lower_module",
                        lambda model, names, mod, sink: lowered.append(mod.name) or real(model, names, mod, sink))

    def warm(texts: dict[str, str]) -> list[str]:
        sink = DiagnosticSink()
        transpile(tcs, sink, keep_modules=False, texts=texts, memo=memo)
        return headers(sink)

    expected = cold(tcs)
    assert warm({}) == expected
    lowered.clear()
    cmd = tcs / "Cmd.gpl"
    # a GoTo into a Try: an error only the lowering reports (GPL3002)
    edited = cmd.read_text().replace(
        "        Dim ii As Integer\n        If bTelnetMode Then\n",
        "        Dim ii As Integer\n        Dim ex As Exception\n        GoTo inside\n        Try\ninside:\n        Catch ex\n        End Try\n"
        "        If bTelnetMode Then\n", 1)
    got = warm({os.path.abspath(cmd): edited})
    assert lowered == ["Cmd"] and any("GPL3002" in h for h in got)
    cmd.write_text(edited)
    assert got == cold(tcs)
    lowered.clear()
    assert warm({}) == got and lowered == []  # nothing changed: every module's diagnostics replayed


def test_a_front_end_without_texts_and_memo_is_called_as_before(tmp_path: Path,
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    """A pipeline whose signature lacks ``texts`` and ``memo`` (V+ and TMscript before they learn
    them) gets the door's other arguments, not a TypeError reported as GPL9000."""
    from gpl2py import languages
    from gpl2py import transpile as door

    calls: list[tuple[object, ...]] = []

    def old_pipeline(path: object, sink: object, keep_going: object, progress: object, stubs_dir: object,
                     strict: object, loaded: object, limits: object, keep_modules: object) -> None:
        calls.append((path, keep_modules))

    front = languages.Frontend("old", "Old", (".old",), "x", "x")
    monkeypatch.setattr(front.__class__, "pipeline", lambda self: old_pipeline)
    monkeypatch.setattr(door, "frontend_for", lambda path, language=None: front)
    sink = DiagnosticSink()
    assert door.transpile(tmp_path, sink, keep_modules=False, texts={"a": "b"}, memo={}) is None
    assert calls == [(tmp_path, False)] and list(sink) == []
