"""Input text never becomes code (issue 12, items 1 and 2; docs/security.md, "Generated code").

Project names, folder names, source file names, string literals and comments are untrusted.  Each
reaches the generated package through ``gpl2py.pywriter.text.escape`` only; these tests feed it
hostile text directly, then through whole projects that are translated, imported and run, and
check that a planted command never runs and the text comes back unchanged where it is shown.
"""

from __future__ import annotations

import ast
import io
import tokenize
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gpl2py.cli import main as cli_main
from gpl2py.pywriter.text import escape, py_string
from gpl2py.run import import_package
from gplrt.sim import Simulation

HOSTILE = [
    'x""";__import__("os").system("touch PWNED");"""',
    "ab\\N",
    "ab\\N{",
    "tail\\",
    "\\x00\\u12",
    '"',
    "'''",
    "line\nimport os",
    "cr\rimport os",
    "nel\x85import os",
    "ls\u2028import os",
    "ff\x0cvt\x0b",
    "fs\x1cgs\x1drs\x1e",
    "nul\x00",
    "caf\xe9 \u00fc \U0001f600",
]

text_st = st.text(st.characters(min_codepoint=0, max_codepoint=0x10FFFF, exclude_categories=("Cs",)))


@pytest.mark.parametrize("text", HOSTILE)
def test_string_and_docstring_round_trip(text: str) -> None:
    assert ast.literal_eval(py_string(text)) == text
    assert ast.literal_eval('"""' + escape(text, "docstring") + '"""') == text
    assert py_string(text).isascii() and escape(text, "docstring").isascii()


@settings(max_examples=300, deadline=None)
@given(text_st)
def test_any_text_round_trips_through_a_literal(text: str) -> None:
    assert ast.literal_eval(py_string(text)) == text
    assert ast.literal_eval('"""' + escape(text, "docstring") + '"""') == text


def _comment_tokens(comment: str) -> list[tokenize.TokenInfo]:
    source = f"x = 1  # {comment}\ny = 2\n"
    return [tok for tok in tokenize.generate_tokens(io.StringIO(source).readline)
            if tok.type not in (tokenize.NL, tokenize.NEWLINE, tokenize.ENDMARKER)]


@pytest.mark.parametrize("text", HOSTILE)
def test_a_comment_stays_on_its_line(text: str) -> None:
    comment = escape(text, "comment")
    tree = ast.parse(f"x = 1  # {comment}\ny = 2\n")
    assert [type(s).__name__ for s in tree.body] == ["Assign", "Assign"]
    assert len((f"# {comment}").splitlines()) == 1
    assert [t.type for t in _comment_tokens(comment)].count(tokenize.COMMENT) == 1


@settings(max_examples=300, deadline=None)
@given(text_st)
def test_any_comment_stays_on_its_line(text: str) -> None:
    comment = escape(text, "comment")
    assert len((f"# {comment}").splitlines()) == 1
    tree = ast.parse(f"x = 1  # {comment}\ny = 2\n")
    assert len(tree.body) == 2


def test_readable_comment_text_is_kept() -> None:
    assert escape("caf\xe9 \\ \"quoted\" \ttab", "comment") == "caf\xe9 \\ \"quoted\" \ttab"


# -- whole projects ---------------------------------------------------------------------------------

MAIN = """Module Main
    Public Sub Main()
        Console.WriteLine("ran")
    End Sub
End Module
"""


def _translate(proj: Path, out: Path) -> tuple[int, str]:
    import contextlib

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = cli_main([str(proj), "-o", str(out)])
    return status, err.getvalue()


def _run(folder: Path, tag: str) -> str:
    pkg = import_package(folder, f"_gate_{tag}")
    sim = Simulation(capture=True, project="gate")
    assert pkg.main(sim) == 0
    return pkg, sim.console.output


def _only_package(out: Path) -> Path:
    (folder,) = [p for p in out.iterdir() if p.is_dir()]
    return folder


def _compiles(folder: Path) -> None:
    for path in folder.glob("*.py"):
        compile(path.read_text(), str(path), "exec")


# Project.gpr takes ProjectName=value unquoted to the end of the line (the value may not start with
# a quote or a blank): the forms a hostile file can carry.
PROJECT_NAMES = [HOSTILE[0], "ab\\N", "ab\\N{", "tail\\", "a'''b", "x\x0bimport os", "caf\xe9"]


@pytest.mark.parametrize("name", PROJECT_NAMES)
def test_hostile_project_name_is_only_a_name(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    monkeypatch.chdir(tmp_path)
    proj = tmp_path / "proj"
    proj.mkdir()
    (proj / "Main.gpl").write_text(MAIN)
    value = name
    (proj / "Project.gpr").write_bytes(
        f'ProjectBegin\nProjectName={value}\nProjectStart="Main"\nProjectSource="Main.gpl"\nProjectEnd\n'
        .encode("latin-1"))
    status, err = _translate(proj, tmp_path / "out")
    assert status == 0, err
    folder = _only_package(tmp_path / "out")
    _compiles(folder)
    pkg, output = _run(folder, f"name{PROJECT_NAMES.index(name)}")
    assert output == "ran\n"
    assert not (tmp_path / "PWNED").exists()
    assert pkg.__doc__.startswith(f"GPL project {value}, ")
    assert pkg.PROJECT["name"] == value


def test_hostile_folder_and_file_names(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    hostile = 'x""";__import__("os").system("touch PWNED");x="""'
    proj = tmp_path / hostile
    proj.mkdir()
    (proj / f"{hostile}.gpl").write_text(MAIN)
    (proj / "Other\\N.gpl").write_text("Module Other\n    Public n As Integer\nEnd Module\n")
    status, err = _translate(proj, tmp_path / "out")
    assert status == 0, err
    folder = _only_package(tmp_path / "out")
    _compiles(folder)
    pkg, output = _run(folder, "files")
    assert output == "ran\n"
    assert not (tmp_path / "PWNED").exists()
    assert pkg.main_mod.__doc__ == f"Module Main, transpiled by gpl2py from {hostile}.gpl."
    assert pkg.other.__doc__ == "Module Other, transpiled by gpl2py from Other\\N.gpl."


def test_hostile_comment_and_string_text(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    proj = tmp_path / "proj"
    proj.mkdir()
    source = ("Module Main\n    Public Sub Main()\n"
              "        ' note\x0b__import__('os').system('touch PWNED')\x85still a comment \\N\n"
              "        Console.WriteLine(\"a\\N\"\"b\")  ' \x1c__import__('os').system('touch PWNED')\n"
              "    End Sub\nEnd Module\n")
    (proj / "Main.gpl").write_bytes(source.encode("latin-1"))
    status, err = _translate(proj, tmp_path / "out")
    assert status == 0, err
    folder = _only_package(tmp_path / "out")
    _compiles(folder)
    _, output = _run(folder, "comments")
    assert output == 'a\\N"b\n'
    assert not (tmp_path / "PWNED").exists()
    text = (folder / "main_mod.py").read_text()
    assert "# note\\x0b__import__('os')" in text
