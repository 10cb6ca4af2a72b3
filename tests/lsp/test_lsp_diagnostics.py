"""The language server's diagnostics, end to end over stdio: ``gpl2py check``'s, as you type."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gpltest import corpus_dir, gpl2py
from lspclient import Session, uri

MAIN = """Module Main
    Public Sub Main()
        Dim n As Integer
        n = Helper.Twice(3)
        Console.WriteLine(CStr(n))
    End Sub
End Module
"""
HELPER = """Module Helper
    Public Function Twice(ByVal x As Integer) As Integer
        Return x * 2
    End Function
End Module
"""


def project(root: Path, sources: dict[str, str]) -> Path:
    folder = root / "cell"
    folder.mkdir()
    lines = ["ProjectBegin", 'ProjectName="cell"', 'ProjectStart="Main"']
    for name, text in sources.items():
        (folder / name).write_text(text)
        lines.append(f'ProjectSource="{name}"')
    (folder / "Project.gpr").write_text("\n".join(lines + ["ProjectEnd"]) + "\n")
    return folder


def check_json(path: Path, cwd: Path) -> set[tuple[str, int, int, str, str]]:
    """What ``gpl2py check --json`` reports: (uri, line, column, code, message), 0-based lines."""
    done = gpl2py("check", str(path), "--json", cwd=cwd)
    return {(uri(d["file"]), d["line"] - 1, d["column"] - 1, d["code"], d["message"])
            for d in json.loads(done.stdout)["diagnostics"] if d["file"]}


def published(session: Session) -> set[tuple[str, int, int, str, str]]:
    return {(u, d.range.start.line, d.range.start.character, str(d.code), d.message)
            for u, diags in session.diagnostics.items() for d in diags}


def test_open_publishes_what_check_reports(tmp_path: Path) -> None:
    folder = project(tmp_path, {"Main.gpl": MAIN.replace("Dim n As Integer", "Dim n As Integr"),
                                "Helper.gpl": HELPER.replace("Return x * 2", "Return y * 2")})
    expected = check_json(folder, tmp_path)
    assert {e[3] for e in expected} == {"GPL2001", "GPL2003"} and len({e[0] for e in expected}) == 2, expected
    with Session(tmp_path) as s:
        s.open(folder / "Main.gpl")
        s.wait_diagnostics(folder / "Helper.gpl")  # the whole project's, the unopened file's too
        s.wait_diagnostics(folder / "Main.gpl")  # (published after Helper.gpl: the files go in sorted order)
        assert published(s) == expected
        d = s.diagnostics[uri(folder / "Main.gpl")][0]
        assert d.source == "gpl2py" and d.code_description is not None
        assert d.code_description.href.endswith("diagnostics.md#" + str(d.code).lower())


def test_edits_recheck_and_a_broken_file_does_not_stop_the_others(tmp_path: Path) -> None:
    folder = project(tmp_path, {"Main.gpl": MAIN, "Helper.gpl": HELPER})
    main, helper = folder / "Main.gpl", folder / "Helper.gpl"
    with Session(tmp_path) as s:
        s.open(main)
        assert s.wait_diagnostics(main) == []
        s.open(helper)
        s.wait_diagnostics(helper)
        # half-typed: the Function's header cut in the middle of its parameter list
        s.change(helper, HELPER.replace("(ByVal x As Integer) As Integer", "(ByVal x As"))
        s.wait_diagnostics(helper)
        assert any(d.severity == 1 for d in s.diagnostics[uri(helper)])
        # an undeclared name in Main is still reported while Helper is broken
        s.change(main, MAIN.replace("Console.WriteLine(CStr(n))", "Console.WriteLine(CStr(m))"))
        diags = s.wait_diagnostics(main)
        assert [(d.code, d.message) for d in diags] == [("GPL2001", "'m' is not declared")]
        # incremental keystrokes: complete the header again, the good edit clears Helper
        s.change(helper, HELPER)
        assert s.wait_diagnostics(helper) == []
        s.edit(main, 4, 31, 4, 32, "n")  # 'm' -> 'n'
        assert s.wait_diagnostics(main) == []
        assert "internal error" not in " ".join(s.logs)


def test_tool_gpl2py_settings_apply_as_in_check(tmp_path: Path) -> None:
    folder = project(tmp_path, {"Main.gpl": MAIN.replace("CStr(n)", "CStr(q)")})
    with Session(tmp_path) as s:
        s.open(folder / "Main.gpl")
        assert "'q' is not declared" in [d.message for d in s.wait_diagnostics(folder / "Main.gpl")]
    (tmp_path / "pyproject.toml").write_text('[tool.gpl2py]\nignore = ["GPL2001"]\n')
    assert check_json(folder, tmp_path) == set()
    with Session(tmp_path) as s:
        s.open(folder / "Main.gpl")
        assert s.wait_diagnostics(folder / "Main.gpl") == []


def test_a_file_its_project_does_not_list_is_checked_alone(tmp_path: Path) -> None:
    folder = project(tmp_path, {"Main.gpl": MAIN, "Helper.gpl": HELPER})
    (folder / "Scratch.gpl").write_text("Module Scratch\n    Sub Try1()\n        x = 1\n    End Sub\nEnd Module\n")
    with Session(tmp_path) as s:
        s.open(folder / "Scratch.gpl")
        assert [d.code for d in s.wait_diagnostics(folder / "Scratch.gpl")] == ["GPL2001"]


def test_tcs_file_gets_checks_diagnostics(tmp_path: Path) -> None:
    tcs = corpus_dir() / "tcs-3.0C1-pa"
    expected = check_json(tcs, tmp_path)
    target = tcs / "PARobot_auto_center_intf.gpl"
    with Session(tmp_path) as s:
        s.open(target)
        s.wait_diagnostics(target)
        s.wait_diagnostics(tcs / "Project.gpr", after=0)  # (published after the target: sorted order)
        got = published(s)
    assert got == expected and any(e[0] == uri(target) for e in expected)


def test_an_internal_error_is_logged_and_the_server_goes_on(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from gpl2py.lsp import server as S
    from gpl2py.lsp.projects import ProjectState

    folder = project(tmp_path, {"Main.gpl": MAIN})
    srv = S.build()
    logs: list[str] = []
    sent: list[object] = []
    monkeypatch.setattr(srv, "log", lambda kind, text: logs.append(text))
    monkeypatch.setattr(srv, "text_document_publish_diagnostics", sent.append)
    monkeypatch.setattr(S.GplServer, "workspace", property(lambda self: _Codec()))
    state = srv.gpl.project_of(str(folder / "Main.gpl"))
    real = ProjectState.check

    def broken(self: ProjectState, texts: object, config: object) -> None:
        raise RuntimeError("planted")

    monkeypatch.setattr(ProjectState, "check", broken)
    srv.check_now(state)
    assert sent == [] and "internal error while checking" in logs[0] and "RuntimeError: planted" in logs[0]
    monkeypatch.setattr(ProjectState, "check", real)
    srv.check_now(state)  # the next check works
    assert len(sent) == 2


class _Codec:
    from pygls.workspace.position_codec import PositionCodec

    position_codec = PositionCodec()
    text_documents: dict[str, object] = {}


def test_a_source_changed_on_disk_is_checked_again(tmp_path: Path) -> None:
    """A file not open in the editor changes on disk (a git checkout): the editor's
    didChangeWatchedFiles makes the server check its project again."""
    from lsprotocol import types as T

    folder = project(tmp_path, {"Main.gpl": MAIN, "Helper.gpl": HELPER})
    helper = folder / "Helper.gpl"
    watching = T.ClientCapabilities(workspace=T.WorkspaceClientCapabilities(
        did_change_watched_files=T.DidChangeWatchedFilesClientCapabilities(dynamic_registration=True)))
    with Session(tmp_path, capabilities=watching) as s:
        s.open(folder / "Main.gpl")
        assert s.wait_diagnostics(helper) == []
        [watch] = s.registrations  # the server asked to be told about the sources on disk
        assert watch.method == "workspace/didChangeWatchedFiles"
        assert {"globPattern": "**/*.gpl"} in watch.register_options["watchers"]
        mark = len(s.published)
        helper.write_text(HELPER.replace("Return x * 2", "Return y * 2"))
        s.client.workspace_did_change_watched_files(T.DidChangeWatchedFilesParams(
            changes=[T.FileEvent(uri=uri(helper), type=T.FileChangeType.Changed)]))
        assert [d.message for d in s.wait_diagnostics(helper, after=mark)] == ["'y' is not declared"]


def test_a_tmscript_file_gets_checks_diagnostics_through_the_same_door(tmp_path: Path) -> None:
    """The place left for the other front ends: a TMscript project (whose pipeline has not learnt
    the editor's unsaved texts yet) gets what check reports for its files as saved."""
    folder = tmp_path / "tm"
    folder.mkdir()
    script = folder / "Main.tms"
    script.write_text("main\n{\n}\nint F()\n{\n  return\n}\n")
    expected = check_json(folder, tmp_path)
    assert {e[3] for e in expected} == {"GPL5306"}
    with Session(tmp_path) as s:
        s.open(script)
        s.wait_diagnostics(script)
        assert published(s) == expected
        assert "internal error" not in " ".join(s.logs)


def test_a_check_publishes_the_files_whose_diagnostics_changed(tmp_path: Path) -> None:
    """After an edit, the edited document's diagnostics are published (its new version) and those
    of a file the edit changed, not those of the files whose diagnostics are what they were."""
    folder = project(tmp_path, {"Main.gpl": MAIN, "Helper.gpl": HELPER.replace("Return x * 2", "Return y * 2"),
                                "Tools.gpl": "Module Tools\n    Sub Nop()\n    End Sub\nEnd Module\n"})
    main, helper = folder / "Main.gpl", folder / "Helper.gpl"
    with Session(tmp_path) as s:
        s.open(main)
        s.wait_diagnostics(folder / "Tools.gpl", after=0)  # (the last in sorted order)
        assert s.wait_diagnostics(main) == [] and len(s.diagnostics[uri(helper)]) == 1
        mark = len(s.published)
        s.change(main, MAIN.replace("CStr(n)", "CStr(n + 1)"))  # nothing else changes
        assert s.wait_diagnostics(main) == []
        s.settle()
        assert [p for _, p, _ in s.published[mark:]] == [uri(main)]
        mark = len(s.published)
        s.change(main, MAIN.replace("Helper.Twice(3)", "Helper.Twice(3, 4)"))  # Main's diagnostics change
        assert [d.code for d in s.wait_diagnostics(main)] != []
        s.open(helper)  # (an open document: its version is published)
        s.change(helper, HELPER)  # Helper's error fixed: Helper's diagnostics change, Tools's do not
        assert s.wait_diagnostics(helper) == []
        s.settle()
        assert uri(folder / "Tools.gpl") not in [p for _, p, _ in s.published[mark:]]
        assert s.diagnostics[uri(helper)] == []
