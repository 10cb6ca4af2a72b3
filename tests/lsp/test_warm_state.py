"""The door's ``texts`` and ``memo`` (what the language server keeps warm): the same diagnostics as
a cold check, with only the changed file parsed again."""

from __future__ import annotations

import os
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl import pipeline
from gpl2py.languages import frontend_for
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
                        lambda model, names, mod, sink, **kw: lowered.append(mod.name) or real(model, names, mod, sink, **kw))

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


def counted(monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], list[str], list[int]]:
    """What the semantic pass does, as it goes: the files whose members it checks, the members'
    names, and a 1 each time it collects the declarations."""
    from gpl2py.gpl.semantics.check import Checker
    from gpl2py.gpl.semantics.symbols import ModuleSym

    checked: list[str] = []
    members: list[str] = []
    collected: list[int] = []
    real, real_collect = Checker.check_members, Checker.collect

    def check_members(self: Checker, mod: ModuleSym, items: list[object]) -> None:
        # (a top-level class is checked alone: the file is its own, not its synthetic module's)
        checked.append(Path(mod.path if mod.decl is not None else items[0].span.file).name)  # type: ignore[attr-defined]
        members.extend(str(getattr(m, "name", "?")) for m in items)
        real(self, mod, items)

    monkeypatch.setattr(Checker, "check_members", check_members)
    monkeypatch.setattr(Checker, "collect", lambda self, units: collected.append(1) or real_collect(self, units))
    return checked, members, collected


def test_edits_check_again_only_the_edited_file_and_report_what_a_cold_check_does(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The guard of the warm semantic pass (gpl2py/gpl/semantics/warm.py): after a series of edits
    -- bodies, with and without errors (syntax errors typed inside a line too), one shifting every
    later line of its file, a Public Const's
    value, a parameter's type, a Public declaration other files use renamed, a protected name used
    for the first time -- each check's diagnostics equal a cold check of the same texts; an edit
    that leaves every declaration as it was checks only the edited file (only the edited procedure
    when the edit is inside one), and one that changes a declaration's type only the files that
    name it."""
    tcs = shutil.copytree(corpus_dir() / "tcs-3.0C1-pa", tmp_path / "tcs")
    memo: dict[object, object] = {}
    checked, members, collected = counted(monkeypatch)
    texts = {name: (tcs / name).read_text()
             for name in ("Cmd.gpl", "Main.gpl", "Globals.gpl", "Functions.gpl", "Class_command.gpl")}

    declared = [True]

    def step(name: str, old: str, new: str) -> tuple[list[str], set[str]]:
        assert old in texts[name], old
        texts[name] = texts[name].replace(old, new, 1)
        checked.clear()
        members.clear()
        collected.clear()
        sink = DiagnosticSink()
        transpile(tcs, sink, keep_modules=False, memo=memo,
                  texts={os.path.abspath(tcs / n): t for n, t in texts.items()})
        got, files, rechecked = headers(sink), set(checked), list(members)
        declared[0] = bool(collected)  # (the declarations were collected again)
        for n, t in texts.items():  # what a cold check of the same texts says
            (tcs / n).write_text(t)
        assert got == cold(tcs), name
        members[:] = rechecked  # (those of the warm check, not the cold one's)
        return got, files

    everything = {Path(s).name for s in os.listdir(tcs) if s.endswith(".gpl") or s.endswith(".gpo")}
    step("Cmd.gpl", "", "")  # the first check: every file
    anchor = "        Dim ii As Integer\n        If bTelnetMode Then\n"
    got, files = step("Cmd.gpl", anchor, anchor + "        ii = 7\n")
    assert files == {"Cmd.gpl"} and not any(" error GPL" in h for h in got)
    got, files = step("Main.gpl", "        Dim cCount As Integer = 0\n",
                      "        Dim cCount As Integer = 0\n        cCount = \"text\" & Nothing.Foo\n")
    assert files == {"Main.gpl"} and any("Main.gpl" in h and " error GPL" in h for h in got)
    # lines added near the top of Cmd.gpl: every later declaration moves, an error far below
    got, files = step("Cmd.gpl", anchor, anchor + "        ii = 8\n\n\n")
    got, files = step("Cmd.gpl", "    Public Sub Cmd_Nop(ByVal Cmd As Command, ByRef Reply As String)\n",
                      "    Public Sub Cmd_Nop(ByVal Cmd As Command, ByRef Reply As String)\n        Reply = 1 +\n")
    assert files == {"Cmd.gpl"} and any("Cmd.gpl" in h and " error GPL" in h for h in got)
    # edits that keep the number of lines: only the procedure around them is parsed and checked again
    got, files = step("Cmd.gpl", "        ii = 7\n", "        ii = 70\n")
    assert members == ["Cmd_Version"] and not declared[0]  # (nor the declarations collected again)
    got, files = step("Cmd.gpl", "        Reply = 1 +\n", "        Reply = 1 + 2\n")
    assert members == ["Cmd_Nop"] and not any("Cmd.gpl" in h and " error GPL" in h for h in got)
    got, files = step("Cmd.gpl", "        Reply = 1 + 2\n", "        Reply = (1 + 2 Then\n")
    assert members == ["Cmd_Nop"] and any("Cmd.gpl" in h and " error GPL" in h for h in got)
    got, files = step("Cmd.gpl", "        Reply = (1 + 2 Then\n", "        If True Then\n")  # (no End If)
    assert any("Cmd.gpl" in h and " error GPL" in h for h in got)
    got, files = step("Cmd.gpl", "        If True Then\n", "        Reply = 1\n")
    got, files = step("Class_command.gpl", "                ss = \"\"\n", "                ss = \"?\"\n")
    assert files == {"Class_command.gpl"}  # (a top-level class: checked as one)
    const = '    Public Const EcUnknown As String = "-2805 *Unknown command*"'
    got, files = step("Globals.gpl", const, const.replace("command*", "command 2*"))
    assert files == {"Globals.gpl"} and declared[0]  # (not inside a procedure: collected again)
    # a parameter's type changed: the files that name the procedure are checked again, and only they
    sub = "    Public Sub Backspace(ByVal index As Integer, ByRef msg As String)"
    got, files = step("Functions.gpl", sub, sub.replace("index As Integer", "index As Double"))
    assert files == {"Functions.gpl", "Main.gpl"}
    got, files = step("Functions.gpl", "index As Double", "index As Integer")
    assert files == {"Functions.gpl", "Main.gpl"}
    # a declaration other files use, renamed: they are checked again (and now take it for a name of
    # the protected code)
    got, files = step("Globals.gpl", "Public Const EcUnknown As", "Public Const EcUnknown2 As")
    assert files == everything and any("Class_command.gpl" in h and "EcUnknown" in h for h in got)
    got, files = step("Globals.gpl", "Public Const EcUnknown2 As", "Public Const EcUnknown As")
    assert files == everything and not any("Class_command.gpl" in h for h in got)
    # a name of the protected code used for the first time: which file reports it depends on the order
    got, files = step("Cmd.gpl", anchor, anchor + "        AC_ErrorMessage()\n")
    assert files == everything
    got, files = step("Cmd.gpl", "        AC_ErrorMessage()\n", "")
    assert files == everything  # Cmd.gpl's last check met a stub: the order matters again
    got, files = step("Cmd.gpl", "        ii = 70\n", "        ii = 10\n")
    assert members == ["Cmd_Version"]
    # the same, typed inside a line (the procedure parsed again alone)
    got, files = step("Cmd.gpl", "        ii = 10\n", "        AC_ErrorMessage()\n")
    assert files == everything
    got, files = step("Cmd.gpl", "        AC_ErrorMessage()\n", "        ii = 10\n")
    assert files == everything


def navigation(state: object, paths: list[str]) -> list[object]:
    """What hover, definition and references answer at every name of ``paths`` (the language
    server's index of ``state``'s last check), and the procedures' extents; symbols are shown by
    their hover text, so two servers' answers compare."""
    from gpl2py.lsp.gpl.describe import describe
    from gpl2py.lsp.gpl.index import index_of, in_order

    index = index_of(state)  # type: ignore[arg-type]
    assert index is not None
    out: list[object] = []
    for path in paths:
        for o in index.occs(path):
            decl = index.declaration(o.sym)
            hover = describe(o, index, state)  # type: ignore[arg-type]
            out.append((Path(o.path).name, o.line, o.col, o.end, o.decl, hover,
                        None if decl is None else (Path(decl.path).name, decl.line, decl.col, decl.end)))
            if o.decl:
                out.append([(Path(r.path).name, r.line, r.col) for r in in_order(index.occurrences(o.sym))])
        out.append([(first, last, proc.name) for first, last, proc, _cls, _mod in index.procs.get(path, ())])
    return out


def test_edits_that_add_or_remove_lines_check_one_procedure_and_move_what_is_below(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Enter, a pasted block, a deleted line inside the first procedure of the project's largest
    file (44 procedures below it): the file is not parsed whole (syntax/reparse.py parses the
    procedure and moves what is below it), only that procedure is checked again, and the
    diagnostics are a cold check's: those below the edit, kept from the last check (a lowering
    error, a syntax error, a duplicate declaration whose message names the line of the first),
    are where a cold check puts them; hover, definition and references below the edit answer what
    a cold server does."""
    from gpl2py.config import Config
    from gpl2py.lsp.projects import ProjectState

    tcs = shutil.copytree(corpus_dir() / "tcs-3.0C1-pa", tmp_path / "tcs")
    parsed: list[str] = []
    real_parse = pipeline.parse
    monkeypatch.setattr(pipeline, "parse",
                        lambda src, sink: parsed.append(Path(src.path).name) or real_parse(src, sink))
    _files, members, collected = counted(monkeypatch)

    robot = os.path.abspath(tcs / "PARobot.gpl")
    main = os.path.abspath(tcs / "Main.gpl")
    text = [Path(robot).read_text(errors="replace")]
    warm = ProjectState(str(tcs), frontend_for(str(tcs)))

    def step(*edits: tuple[str, str], oracle: bool = True, nav: bool = False) -> tuple[list[str], list[str], bool]:
        """Edit PARobot.gpl (each ``(old, new)`` in turn) and check it; what the warm check parsed
        whole and checked, and whether it collected the declarations again, once its diagnostics
        (and with ``nav`` its navigation) equal a cold check's."""
        for old, new in edits:
            assert old in text[0], old
            text[0] = text[0].replace(old, new, 1)
        parsed.clear()
        members.clear()
        collected.clear()
        got = warm.check({robot: text[0]}, Config())
        whole, checked, declared = list(parsed), list(members), bool(collected)
        if oracle:
            cold = ProjectState(str(tcs), frontend_for(str(tcs)))
            expected = cold.check({robot: text[0]}, Config())
            assert [d.header() for ds in got.by_file.values() for d in ds] == \
                [d.header() for ds in expected.by_file.values() for d in ds]
            # (the ranges too, which an editor shows: where each diagnostic ends)
            assert [tuple(d.span) for d in got.by_file[robot]] == [tuple(d.span) for d in expected.by_file[robot]]
            if nav:
                answers = navigation(warm, [robot, main])
                assert answers == navigation(cold, [robot, main]) and len(answers) > 3000
        return whole, checked, declared

    # a GoTo into a Try below the edits, in the same module and in the file's other module: an
    # error only the lowering reports (GPL3002), which the next checks replay from the lowering's
    # memo (of the procedure; of the module, whose tree is the same)
    safe = "        Dim ex As Exception\n\n        CurConfig = Robot.Where.config\n"
    grasp = "        Dim btmp As Boolean\n\n        If Cmd.Rob.GripAxis = 0 Then\n"
    goto = "\n        GoTo inside\n        Try\ninside:\n        Catch ex\n        End Try\n"
    step((safe, safe.replace("\n\n", goto, 1)),
         (grasp, grasp.replace("\n\n", "\n        Dim ex As Exception" + goto, 1)), oracle=False)
    init = "       Dim inti As Integer\n"
    assert step((init, init + "\n"), nav=True) == ([], ["Init"], False)  # Enter
    assert sum("GPL3002" in d.header() for d in warm.last.by_file[robot]) == 2  # type: ignore[union-attr]
    block = "       inti = 1\n       inti = inti + 2\n       If inti > 2 Then\n           inti = 0\n       End If\n"
    assert step((init + "\n", init + "\n" + block)) == ([], ["Init"], False)  # a pasted block
    assert step(("       inti = inti + 2\n", "")) == ([], ["Init"], False)  # a line deleted
    # below the edit: a duplicate Dim (its message names the line of the first), a syntax error,
    # two module variables of one name (the collection's diagnostic, naming a line too)
    step(("        ' No parameters\n        ' Returns the current active gripper (1 or 2)\n",
          "        Dim k As Integer\n        Dim k As Integer\n"),
         ("CStr(Cmd.Rob.ActiveGripper+1)\n", "CStr(Cmd.Rob.ActiveGripper+1\n"),
         ("    #End Region\n          \n\nEnd Module",
          "    #End Region\n    Private Zzz As Integer\n    Private Zzz As Integer\n\nEnd Module"),
         oracle=False)
    # Enter twice: the members whose diagnostics name a moved line are checked again, and the
    # declarations collected again
    whole, checked, declared = step((init, init + "\n\n"), nav=True)
    assert (whole, sorted(checked), declared) == ([], ["Cmd_GetActiveGripper", "Init"], True)
    assert step((init + "\n\n", init))[:2] == ([], ["Init", "Cmd_GetActiveGripper"])


Checked = Callable[[str], list[tuple[str, tuple[object, ...]]]]


def one_file_cell(tmp_path: Path, text: str) -> tuple[Path, dict[object, object], Checked, Checked]:
    """A project of one module, Main.gpl holding ``text``: its path, the memo of its warm checks,
    and two checks of a text giving each diagnostic's header and range: ``warm`` (the text
    given as the editor's, the memo kept) and ``cold`` (the text written, checked afresh)."""
    folder = tmp_path / "cell"
    folder.mkdir()
    (folder / "Project.gpr").write_text('ProjectBegin\nProjectName="cell"\nProjectStart="Main"\n'
                                        'ProjectSource="Main.gpl"\nProjectEnd\n')
    main = folder / "Main.gpl"
    main.write_text(text)
    memo: dict[object, object] = {}

    def warm(text: str) -> list[tuple[str, tuple[object, ...]]]:
        sink = DiagnosticSink()
        transpile(folder, sink, keep_modules=False, texts={os.path.abspath(main): text}, memo=memo)
        return [(d.header(), tuple(d.span)) for d in sink.sorted()]

    def cold(text: str) -> list[tuple[str, tuple[object, ...]]]:
        main.write_text(text)
        sink = DiagnosticSink()
        transpile(folder, sink, keep_modules=False)
        return [(d.header(), tuple(d.span)) for d in sink.sorted()]

    return main, memo, warm, cold


def test_what_the_symbols_hold_of_a_position_moves_with_the_lines(tmp_path: Path) -> None:
    """After Enter in a procedure, a diagnostic reported at a symbol's span, not at a node's (the
    start procedure should be Public: reported at its procedure's symbol on every check), is where
    a cold check reports it, and its range ends on the moved End line."""
    text = ("Module Main\n    Public Sub First()\n        Dim i As Integer\n        i = 1\n    End Sub\n\n"
            "    Sub Main()\n        First()\n    End Sub\nEnd Module\n")
    main, memo, warm, cold = one_file_cell(tmp_path, text)
    first = warm(text)
    assert first == cold(text) and any("GPL2025" in h for h, _ in first)
    for edited in (text.replace("        i = 1\n", "        i = 1\n\n\n", 1),  # Enter twice
                   text.replace("        i = 1\n", "", 1)):  # a line deleted
        before = memo[("gpl-parse", str(main))][1]  # type: ignore[index]
        assert warm(edited) == cold(edited)
        after = memo[("gpl-parse", str(main))][1]  # type: ignore[index]
        # (the procedure below the edit is the node it was: moved, not parsed again)
        assert after is not before and after.members[0].members[1] is before.members[0].members[1]
        assert warm(text) == cold(text)


def test_lines_added_above_a_long_dim_report_what_a_cold_check_does(tmp_path: Path) -> None:
    """Enter above a procedure whose Dim of 70 names is held compactly (issue 20): its variables'
    uses and a misuse below the edit are where a cold check reports them (the moved positions
    were a crash of the language server's re-check)."""
    names = ", ".join(f"v{k}" for k in range(70))
    text = ("Module Main\n    Public Sub First()\n        Dim i As Integer\n        i = 1\n    End Sub\n\n"
            f"    Public Sub Main()\n        Dim {names} As Integer\n        v7.X = 1\n        First()\n"
            "        v8 = v7 + w\n    End Sub\nEnd Module\n")
    _, _, warm, cold = one_file_cell(tmp_path, text)
    first = warm(text)
    assert first == cold(text) and len(first) >= 2  # (v7 has no member X, w is not declared)
    for edited in (text.replace("        i = 1\n", "        i = 1\n\n\n", 1), text.replace("        i = 1\n", "", 1)):
        assert warm(edited) == cold(edited)
        assert warm(text) == cold(text)

