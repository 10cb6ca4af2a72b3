"""The language server's navigation, end to end over stdio: hover, definition, references,
highlight, symbols, completion, signature help, rename and quick fixes on a small project."""

from __future__ import annotations

from pathlib import Path

import pytest
from lsprotocol import types as T

from lspclient import Session, apply_edits, uri

MAIN = """Module Main
    Public Const LIMIT As Integer = 42
    Public Sub Main()
        Dim loc As New Location
        Dim total As Integer
        Dim g As New Gripper
        total = Helper.Twice(LIMIT)
        loc.X = 10
        g.Grip(total)
        If total > 3 Then
            GoTo done
        End If
        Console.WriteLine(CStr(total))
done:
        Console.WriteLine(CStr(loc.X))
    End Sub
End Module
"""
HELPER = """Module Helper
    Public Function Twice(ByVal x As Integer) As Integer
        Return x * 2
    End Function
End Module
"""
TOOLS = """Module Tools
    Public Class Gripper
        Public Force As Integer
        Public Sub Grip(ByVal f As Integer)
            Force = f
        End Sub
    End Class
End Module
"""


def write(root: Path, sources: dict[str, str]) -> Path:
    folder = root / "cell"
    folder.mkdir(exist_ok=True)
    lines = ["ProjectBegin", 'ProjectName="cell"', 'ProjectStart="Main"']
    for name, text in sources.items():
        (folder / name).write_text(text)
        lines.append(f'ProjectSource="{name}"')
    (folder / "Project.gpr").write_text("\n".join(lines + ["ProjectEnd"]) + "\n")
    return folder


@pytest.fixture(scope="module")
def cell(tmp_path_factory: pytest.TempPathFactory) -> tuple[Session, Path]:
    root = tmp_path_factory.mktemp("nav")
    folder = write(root, {"Main.gpl": MAIN, "Helper.gpl": HELPER, "Tools.gpl": TOOLS})
    session = Session(root)
    session.open(folder / "Main.gpl")
    assert session.wait_diagnostics(folder / "Main.gpl") == []
    yield session, folder
    session.close()


def at(text: str, needle: str, nth: int = 0, offset: int = 0) -> tuple[int, int]:
    """The 0-based line and column of the ``nth`` occurrence of ``needle`` (plus ``offset``)."""
    pos = -1
    for _ in range(nth + 1):
        pos = text.index(needle, pos + 1)
    pos += offset
    return text.count("\n", 0, pos), pos - text.rfind("\n", 0, pos) - 1


def test_hover_shows_type_declaration_place_const_value_and_builtin_signature(cell: tuple[Session, Path]) -> None:
    s, folder = cell
    main = folder / "Main.gpl"
    hover = s.hover(main, *at(MAIN, "total", 2))
    assert hover is not None
    assert "Dim total As Integer" in hover.contents.value and "Main.gpl:5:13" in hover.contents.value
    assert "Const LIMIT As Integer = 42" in s.hover(main, *at(MAIN, "LIMIT", 1)).contents.value
    twice = s.hover(main, *at(MAIN, "Twice")).contents.value
    assert "Public Function Helper.Twice(x As Integer) As Integer" in twice and "Helper.gpl:2:21" in twice
    member = s.hover(main, *at(MAIN, "loc.X", 0, 4)).contents.value
    assert "Property Location.X As Double" in member and "built-in member" in member
    assert "Function CStr(" in s.hover(main, *at(MAIN, "CStr")).contents.value


def test_definition_references_and_highlight_across_modules(cell: tuple[Session, Path]) -> None:
    s, folder = cell
    main = folder / "Main.gpl"
    [loc] = s.definition(main, *at(MAIN, "Twice"))
    assert loc.uri == uri(folder / "Helper.gpl") and (loc.range.start.line, loc.range.start.character) == (1, 20)
    [loc] = s.definition(main, *at(MAIN, "g.Grip", 0, 2))
    assert loc.uri == uri(folder / "Tools.gpl") and loc.range.start == T.Position(3, 19)
    [loc] = s.definition(main, *at(MAIN, "GoTo done", 0, 5))
    assert loc.uri == uri(main) and loc.range.start == T.Position(*at(MAIN, "done:"))
    refs = s.references(main, *at(MAIN, "Twice"))
    assert sorted((r.uri, r.range.start.line) for r in refs) == [(uri(folder / "Helper.gpl"), 1), (uri(main), 6)]
    assert len(s.references(main, *at(MAIN, "Twice"), declaration=False)) == 1
    lights = s.highlight(main, *at(MAIN, "total", 1))
    assert [h.range.start.line for h in lights] == [4, 6, 8, 9, 12]
    assert lights[0].kind == T.DocumentHighlightKind.Write


def test_document_and_workspace_symbols(cell: tuple[Session, Path]) -> None:
    s, folder = cell
    [module] = s.document_symbols(folder / "Main.gpl")
    assert module.name == "Main" and module.kind == T.SymbolKind.Module
    assert [(c.name, c.kind) for c in module.children] == [("LIMIT", T.SymbolKind.Constant),
                                                           ("Main", T.SymbolKind.Function)]
    found = {(x.name, x.kind, x.container_name) for x in s.workspace_symbols("gri")}
    assert found == {("Gripper", T.SymbolKind.Class, "Tools"), ("Grip", T.SymbolKind.Method, "Gripper")}


def completion_labels(s: Session, path: Path, text: str, line: int, col: int) -> dict[str, str | None]:
    s.change(path, text)
    return {i.label: i.detail for i in s.completion(path, line, col)}


def test_completion_of_members_names_and_keywords(cell: tuple[Session, Path]) -> None:
    s, folder = cell
    main = folder / "Main.gpl"
    typing = MAIN.replace("        loc.X = 10\n", "        loc.\n        g.\n        Helper.\n        Robot.\n        \n")
    line = at(typing, "        loc.\n")[0]
    members = completion_labels(s, main, typing, line, 12)
    assert {"X", "Y", "Here", "Inverse"} <= set(members) and members["Inverse"] == "Function Inverse() As Location"
    assert set(completion_labels(s, main, typing, line + 1, 10)) == {"Force", "Grip"}
    assert set(completion_labels(s, main, typing, line + 2, 15)) == {"Twice"}
    robot = completion_labels(s, main, typing, line + 3, 14)
    assert "Selected" in robot and "X" not in robot
    names = completion_labels(s, main, typing, line + 4, 8)
    assert {"Dim", "If", "For", "total", "loc", "LIMIT", "Twice", "Helper", "CStr", "Console"} <= set(names)
    s.change(main, MAIN)
    s.wait_diagnostics(main)


def test_signature_help_while_typing_arguments(cell: tuple[Session, Path]) -> None:
    s, folder = cell
    main = folder / "Main.gpl"
    typing = MAIN.replace("        loc.X = 10\n", "        total = Helper.Twice(\n        loc.XYZ(1, 2, \n")
    s.change(main, typing)
    line = at(typing, "Helper.Twice(\n")[0]
    help = s.signature_help(main, line, 29)
    assert help is not None and help.signatures[0].label == "Public Function Twice(x As Integer) As Integer"
    assert help.active_parameter == 0
    help = s.signature_help(main, line + 1, 22)
    assert help is not None and help.signatures[0].label.startswith("Sub Location.XYZ(Optional X As Double")
    assert help.active_parameter == 2
    s.change(main, MAIN)
    s.wait_diagnostics(main)


def test_rename_project_wide_and_refused_on_collision(tmp_path: Path) -> None:
    from gpltest import gpl2py

    folder = write(tmp_path, {"Main.gpl": MAIN, "Helper.gpl": HELPER, "Tools.gpl": TOOLS})
    main, helper = folder / "Main.gpl", folder / "Helper.gpl"
    with Session(tmp_path) as s:
        s.open(main)
        s.wait_diagnostics(main)
        edit = s.rename(main, *at(MAIN, "Twice"), "Doubled")
        assert edit is not None and set(edit.changes) == {uri(main), uri(helper)}
        renamed_main = apply_edits(MAIN, edit.changes[uri(main)])
        main.write_text(renamed_main)
        helper.write_text(apply_edits(HELPER, edit.changes[uri(helper)]))
        assert "Helper.Doubled(LIMIT)" in renamed_main and "Function Doubled(" in helper.read_text()
        assert gpl2py("check", str(folder), cwd=tmp_path).returncode == 0
        s.change(main, renamed_main)
        s.wait_diagnostics(main)
        # a class: its declaration, New, and every As of a variable, parameter or result
        tools = folder / "Tools.gpl"
        helper.write_text(helper.read_text().replace(
            "End Module", "    Public Function Make(ByVal g As Gripper) As Tools.Gripper\n        Return g\n"
                          "    End Function\nEnd Module"))
        s.change(main, renamed_main + " ")  # (a check, which reads Helper from disk)
        s.wait_diagnostics(main)
        edit = s.rename(main, *at(renamed_main, "New Gripper", 0, 4), "Holder")
        assert {u.rsplit("/", 1)[-1]: len(e) for u, e in edit.changes.items()} == \
            {"Main.gpl": 1, "Helper.gpl": 2, "Tools.gpl": 1}
        for u, edits in edit.changes.items():
            target = folder / u.rsplit("/", 1)[-1]
            text = renamed_main if target == main else target.read_text()
            target.write_text(apply_edits(text, edits))
        renamed_main = main.read_text()
        assert "Dim g As New Holder" in renamed_main and "As Tools.Holder" in helper.read_text()
        assert "Public Class Holder" in tools.read_text()
        assert gpl2py("check", str(folder), cwd=tmp_path).returncode == 0
        s.change(main, renamed_main)
        s.wait_diagnostics(main)
        edit = s.rename(main, *at(renamed_main, "total", 1), "count")
        assert len(edit.changes[uri(main)]) == 5
        for new, reason in [("loc", "'loc' is already declared in Main"),
                            ("Integer", "not a GPL name"),
                            ("LIMIT", "would hide 'LIMIT'")]:
            with pytest.raises(Exception, match=reason):
                s.rename(main, *at(renamed_main, "total", 1), new)
        helper.write_text(helper.read_text().replace("End Module", "    Public Sub Other()\n    End Sub\nEnd Module"))
        s.change(main, renamed_main + "\n")  # (a check, which reads Helper from disk)
        s.wait_diagnostics(main)
        with pytest.raises(Exception, match="Helper already has a member 'Other'"):
            s.rename(main, *at(renamed_main, "Doubled"), "Other")


def test_quick_fixes_for_an_undeclared_name(tmp_path: Path) -> None:
    broken = MAIN.replace("        loc.X = 10\n", "        totl = 5\n        ratio = 2.5 * total\n")
    folder = write(tmp_path, {"Main.gpl": broken, "Helper.gpl": HELPER, "Tools.gpl": TOOLS})
    main = folder / "Main.gpl"
    with Session(tmp_path) as s:
        s.open(main)
        diags = s.wait_diagnostics(main)
        assert [d.message for d in diags] == ["'totl' is not declared", "'ratio' is not declared"]
        explained = s.hover(main, diags[0].range.start.line, diags[0].range.start.character).contents.value
        assert "**GPL2001** (error): '{name}' is not declared" in explained  # gpl2py explain's text
        [fix, dim] = s.code_actions(main, diags[0].range.start.line, [diags[0]])
        assert fix.title == "Change 'totl' to 'total'"
        assert dim.title == "Declare 'Dim totl As Integer'"
        [dim] = s.code_actions(main, diags[1].range.start.line, [diags[1]])
        assert dim.title == "Declare 'Dim ratio As Double'"
        fixed = apply_edits(broken, fix.edit.changes[uri(main)] + dim.edit.changes[uri(main)])
        assert "        Dim ratio As Double\n        Dim loc As New Location\n" in fixed
        s.change(main, fixed)
        assert s.wait_diagnostics(main) == []


def test_typing_a_file_character_by_character_never_breaks_the_server(tmp_path: Path) -> None:
    """Every prefix of a file, as typed (every 5th character), checked and asked everything at
    the cursor: no internal error is logged, every request is answered, and the finished text is
    clean again."""
    folder = write(tmp_path, {"Main.gpl": MAIN, "Helper.gpl": HELPER, "Tools.gpl": TOOLS})
    main = folder / "Main.gpl"
    with Session(tmp_path) as s:
        s.open(main, "")
        for end in list(range(0, len(MAIN), 5)) + [len(MAIN)]:
            text = MAIN[:end]
            s.change(main, text)
            diags = s.wait_diagnostics(main)
            line = text.count("\n")
            col = len(text) - (text.rfind("\n") + 1)
            s.completion(main, line, col)
            s.signature_help(main, line, col)
            s.hover(main, line, max(col - 1, 0))
            s.definition(main, line, max(col - 1, 0))
            s.highlight(main, line, max(col - 1, 0))
            s.document_symbols(main)
            s.code_actions(main, line, diags)
        assert s.wait_diagnostics(main) == []
        assert not [log for log in s.logs if "internal error" in log], s.logs


def test_a_request_right_after_an_edit_sees_the_edited_text(tmp_path: Path) -> None:
    """With the check still waiting for typing to pause, hover and rename answer for the text the
    editor shows: the waiting check is made first."""
    folder = write(tmp_path, {"Main.gpl": MAIN, "Helper.gpl": HELPER, "Tools.gpl": TOOLS})
    main = folder / "Main.gpl"
    with Session(tmp_path, debounce_ms=10_000) as s:
        s.open(main)
        s.wait_diagnostics(main)
        shifted = "' a comment line typed above everything\n" + MAIN
        s.change(main, shifted)
        hover = s.hover(main, *at(shifted, "total", 2))
        assert hover is not None and "Dim total As Integer" in hover.contents.value
        edit = s.rename(main, *at(shifted, "total", 1), "count")
        assert apply_edits(shifted, edit.changes[uri(main)]).count("count") == 5


def test_navigation_in_a_long_dim(tmp_path: Path) -> None:
    """A Dim of 300 names (held compactly, a symbol made only for a name used: issue 20): hover,
    definition, highlight, completion and rename find its names as they find a short Dim's, used
    or not."""
    names = [f"n{k}" for k in range(300)]
    text = MAIN.replace("        Dim total As Integer\n",
                        "        Dim " + ", ".join(names[:150]) + " As Integer, " + ", ".join(names[150:])
                        + " As String, total As Integer\n        n7 = 5\n        n200 = CStr(n7)\n")
    folder = write(tmp_path, {"Main.gpl": text, "Helper.gpl": HELPER, "Tools.gpl": TOOLS})
    main = folder / "Main.gpl"
    with Session(tmp_path) as s:
        s.open(main)
        assert s.wait_diagnostics(main) == []
        dim = at(text, "Dim n0")[0]
        hover = s.hover(main, *at(text, "n7 = 5")).contents.value
        assert "Dim n7 As Integer" in hover and f"Main.gpl:{dim + 1}:{at(text, 'n7,')[1] + 1}" in hover
        assert "Dim n200 As String" in s.hover(main, *at(text, "n200 =")).contents.value
        [loc] = s.definition(main, *at(text, "CStr(n7)", 0, 5))
        assert loc.range.start == T.Position(*at(text, "n7,"))
        assert [h.range.start.line for h in s.highlight(main, *at(text, "n7 = 5"))] == [dim, dim + 1, dim + 2]
        assert [h.range.start.line for h in s.highlight(main, *at(text, "n9,"))] == [dim]  # (never used)
        assert {"n0", "n299", "total"} <= set(completion_labels(s, main, text.replace("n7 = 5", "n"), dim + 1, 9))
        s.change(main, text)
        s.wait_diagnostics(main)
        for needle, count in (("n7,", 3), ("n9,", 1)):
            edit = s.rename(main, *at(text, needle), "renamed")
            assert edit is not None and len(edit.changes[uri(main)]) == count, needle
        renamed = apply_edits(text, edit.changes[uri(main)])
        assert "n8, renamed, n10" in renamed
