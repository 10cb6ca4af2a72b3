"""The gpl2py command: exit codes, diagnostic format, --json, --quiet, internal errors, docs in sync."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import gpl2py.cli as cli
import gpl2py.gpl.pipeline as pipeline_module
from gpl2py import messages
from gpl2py.cli import main

REPO = Path(__file__).resolve().parents[2]
SAMPLE = REPO / "samples" / "tcp_command_server"
HEADER = re.compile(r"^(?P<path>.+?):(?P<line>\d+):(?P<col>\d+): (?P<sev>error|warning|note) (?P<code>GPL\d{4}): (?P<msg>.+)$")


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def headers(text: str) -> list[re.Match[str]]:
    return [m for line in text.splitlines() if (m := HEADER.match(line))]


def make_project(folder: Path, gpr_lines: list[str], files: dict[str, bytes]) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "Project.gpr").write_text("\r\n".join(gpr_lines) + "\r\n")
    for name, data in files.items():
        (folder / name).write_bytes(data)
    return folder


GOOD_MODULE = b"Module Main\r\n    Public Sub Main()\r\n        Console.WriteLine(\"hi\")\r\n    End Sub\r\nEnd Module\r\n"


# --- exit codes ---------------------------------------------------------------------------------


def test_clean_sample_project_exits_0(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "check", str(SAMPLE))
    assert err.strip().splitlines()[-1] == "checked 6 files: 0 errors, 0 warnings", err
    assert code == 0
    assert out == ""


def test_load_errors_exit_1_with_caret_excerpt(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = make_project(
        tmp_path / "P",
        ["ProjectBegin", 'ProjectStart="Main"', 'ProjectSource="Missing.gpl"', "ProjectEnd"],
        {},
    )
    code, out, err = run(capsys, "check", str(proj))
    assert code == 1
    lines = err.splitlines()
    gpr = str(proj / "Project.gpr")
    assert lines[0] == f"{gpr}:3:16: error GPL1405: source file Missing.gpl named in Project.gpr not found in {proj}"
    assert lines[1] == '    ProjectSource="Missing.gpl"'
    assert lines[2] == "                   ^^^^^^^^^^^"
    assert lines[-1] == "checked 0 files: 1 error, 0 warnings"


def test_multiple_errors_in_one_run_are_sorted(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = make_project(
        tmp_path / "P",
        [
            "ProjectBegin",
            'ProjectSource="Zed.gpl"',
            "garbage line",
            'ProjectSource="Gone.gpl"',
            'ProjectStart="Main"',
            "ProjectEnd",
        ],
        {"Zed.gpl": b"Module Zed\r\n\x00\x00\r\n"},
    )
    code, _, err = run(capsys, "check", str(proj))
    assert code == 1
    found = [(Path(m["path"]).name, int(m["line"]), m["code"]) for m in headers(err)]
    assert found == [
        ("Project.gpr", 3, "GPL1407"),
        ("Project.gpr", 4, "GPL1405"),
        ("Zed.gpl", 2, "GPL1404"),
    ]
    assert err.splitlines()[-1] == "checked 0 files: 3 errors, 0 warnings"


def test_syntax_errors_in_two_files_are_all_reported(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "Broken"
    folder.mkdir()
    (folder / "A.gpl").write_text("Module A\n    Public Sub Main()\n        x = (1 +\n    End Sub\nEnd Module\n")
    (folder / "B.gpl").write_text("Module B\n    Public Sub F()\n        If x Then\n    End Sub\nEnd Module\n")
    code, _, err = run(capsys, "check", str(folder))
    assert code == 1
    found = headers(err)
    files = {Path(m["path"]).name for m in found if m["sev"] == "error"}
    assert files == {"A.gpl", "B.gpl"}
    # the syntax errors of both files, and (check runs the semantic pass) the undeclared x in each
    assert [(Path(m["path"]).name, int(m["line"]), m["code"]) for m in found] == [
        ("A.gpl", 3, "GPL2001"), ("A.gpl", 3, "GPL1101"), ("B.gpl", 3, "GPL1105"), ("B.gpl", 3, "GPL2001")]
    # Each header is followed by the source line it points into and a caret under the column.
    lines = err.splitlines()
    for i, line in enumerate(lines):
        m = HEADER.match(line)
        if m and m["path"].endswith("A.gpl"):
            src = (folder / "A.gpl").read_text().splitlines()[int(m["line"]) - 1]
            assert lines[i + 1] == "    " + src
            assert lines[i + 2].index("^") == 4 + int(m["col"]) - 1


def test_warnings_only_exit_0(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "OnlyProtected"
    folder.mkdir()
    (folder / "Vendor.gpp").write_bytes(b"'#Protected|\x00\x01\x02")
    code, _, err = run(capsys, "check", str(folder))
    assert code == 0
    # without a Project.gpr line to point at, the warning points at the file itself
    assert [(m["code"], int(m["line"]), int(m["col"])) for m in headers(err)] == [("GPL1406", 1, 1)]
    assert "warning GPL1406" in err and "Vendor.gpp:1:1:" in err
    assert err.splitlines()[-1] == "checked 0 files: 0 errors, 1 warning"


def test_quiet_prints_errors_only(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = make_project(
        tmp_path / "P",
        ["ProjectBegin", 'ProjectStart="Main"', 'Color="blue"', 'ProjectSource="Gone.gpl"', "ProjectEnd"],
        {},
    )
    code, out, err = run(capsys, "check", "--quiet", str(proj))
    assert code == 1 and out == ""
    assert [m["code"] for m in headers(err)] == ["GPL1405"]
    assert "checked" not in err


@pytest.mark.parametrize(
    "argv",
    [
        [],
        ["frobnicate", "x"],
        ["check"],
        ["run", "a", "b"],  # run takes one project (check and translate take several)
        ["check", "--no-such-option", "x"],
        ["--json"],
    ],
)
def test_usage_errors_exit_2(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, *argv)
    assert code == 2
    text = out + err
    assert "GPL9001" in text
    assert "Traceback" not in text


def test_dump_ast_on_a_folder_is_a_usage_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "dump-ast", str(tmp_path))
    assert code == 2 and out == ""
    assert "error GPL9002" in err


def test_missing_path_is_an_input_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "check", str(tmp_path / "nope"))
    assert code == 1
    assert f"error GPL1400: no such file or folder: {tmp_path / 'nope'}" in err


def test_help_explains_commands_and_exit_codes(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "--help")
    assert code == 0
    for text in ("check", "dump-ast", "exit status", "0  no errors", "1  errors", "2  the command line",
                 "internally (GPL9000"):
        assert text in out
    code, out, _ = run(capsys, "check", "--help")
    assert code == 0 and "Project.gpr" in out and "exit status" in out


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    from gpl2py import __version__

    code, out, _ = run(capsys, "--version")
    assert code == 0 and out.strip() == f"gpl2py {__version__}"


# --- --json -------------------------------------------------------------------------------------


def test_json_output_parses_and_carries_positions(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    proj = make_project(
        tmp_path / "P",
        ["ProjectBegin", 'ProjectStart="Main"', 'Color="blue"', 'ProjectSource="Gone.gpl"', "ProjectEnd"],
        {},
    )
    for argv in (["--json", "check", str(proj)], ["check", str(proj), "--json"]):
        code, out, err = run(capsys, *argv)
        assert code == 1 and err == ""
        doc = json.loads(out)
        assert doc["summary"] == {"errors": 1, "warnings": 1}
        assert [(d["code"], d["severity"], d["line"], d["column"]) for d in doc["diagnostics"]] == [
            ("GPL1408", "warning", 3, 1),
            ("GPL1405", "error", 4, 16),
        ]
        assert doc["diagnostics"][1]["file"] == str(proj / "Project.gpr")
        assert "Gone.gpl" in doc["diagnostics"][1]["message"]


def test_json_usage_error_is_json_too(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "--json", "frobnicate")
    assert code == 2 and err == ""
    doc = json.loads(out)
    assert [d["code"] for d in doc["diagnostics"]] == ["GPL9001"]


def test_dump_ast_json_has_ast_and_diagnostics(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "Main.gpl"
    path.write_bytes(GOOD_MODULE)
    code, out, _ = run(capsys, "dump-ast", "--json", str(path))
    assert code == 0
    doc = json.loads(out)
    assert doc["diagnostics"] == []
    assert "Main" in doc["ast"]


def test_dump_ast_prints_the_tree(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.source import SourceFile
    from gpl2py.gpl.syntax.ast import dump
    from gpl2py.gpl.syntax.parser import parse

    path = tmp_path / "Main.gpl"
    path.write_bytes(GOOD_MODULE)
    code, out, err = run(capsys, "dump-ast", str(path))
    assert code == 0
    expected = dump(parse(SourceFile(str(path), GOOD_MODULE.decode()), DiagnosticSink()))
    assert out == expected.rstrip("\n") + "\n"
    assert "WriteLine" in out


# --- internal errors never become tracebacks ----------------------------------------------------


def test_internal_error_becomes_gpl9000(monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    def boom(path: object, sink: object, *limits: object) -> None:
        raise RuntimeError("simulated bug")

    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    monkeypatch.setattr(pipeline_module, "load_project", boom)  # (check runs translate's pipeline)
    code, out, err = run(capsys, "check", str(tmp_path))
    assert code == 2  # gpl2py failed, not the input: ruff's and mypy's status for a crash
    assert "error GPL9000: internal error in gpl2py while processing this input: RuntimeError: simulated bug" in err
    assert "Traceback" not in out + err
    code, out, _ = run(capsys, "check", "--json", str(tmp_path))
    assert code == 2
    assert [d["code"] for d in json.loads(out)["diagnostics"]] == ["GPL9000"]


def test_internal_error_in_the_parser_becomes_gpl9000(monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    def broken_parse(source: object, sink: object) -> None:
        raise IndexError("list index out of range")

    (tmp_path / "Main.gpl").write_bytes(GOOD_MODULE)
    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    monkeypatch.setattr(pipeline_module, "parse", broken_parse)
    code, _, err = run(capsys, "check", str(tmp_path))
    assert code == 2 and "GPL9000" in err and "IndexError" in err and "Traceback" not in err


def test_internal_error_caught_by_the_pipeline_exits_2(monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
                                                       capsys: pytest.CaptureFixture[str]) -> None:
    """transpile() turns a fault of any phase into GPL9000 itself (for library callers): the command
    still exits 2, not 1 as for an error in the GPL input."""
    import gpl2py.gpl.pipeline as transpile

    def broken_lower(*args: object, **kwargs: object) -> None:
        raise KeyError("lowering bug")

    (tmp_path / "Main.gpl").write_bytes(GOOD_MODULE)
    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    monkeypatch.setattr(transpile, "lower", broken_lower)
    code, _, err = run(capsys, str(tmp_path / "Main.gpl"), "-o", str(tmp_path / "out"))
    assert code == 2 and "error GPL9000" in err and "KeyError" in err


_PIECES = st.sampled_from([
    "Module M\n", "End Module\n", "Public Sub Main()\n", "End Sub\n", "If x Then\n", "End If\n",
    "Try\n", "Catch e\n", "End Try\n", "x = (1 + \n", " _\n", "\"unterminated\n", "&HZZ\n",
    "GoTo 100\n", "100: \n", "Select x\n", "Case 1 To\n", "Dim a(,,,,) As\n", "\t\u00e9\n", "\x00",
    "\r\n", "'#Protected|", "#Region\n",
])


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(pieces=st.lists(_PIECES, max_size=25), extra=st.binary(max_size=16))
def test_no_input_produces_a_traceback(pieces: list[str], extra: bytes, tmp_path: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "Fuzz.gpl"
    path.write_bytes("".join(pieces).encode("utf-8") + extra)
    capsys.readouterr()
    code = main(["check", str(path)])
    out, err = capsys.readouterr()
    assert code in (0, 1)
    assert "Traceback" not in out + err and "GPL9000" not in err


# --- the installed command and python -m --------------------------------------------------------


def _script() -> Path:
    return Path(sys.executable).with_name("gpl2py")


def test_installed_command_runs(tmp_path: Path) -> None:
    script = _script()
    assert script.exists(), f"console script not installed next to {sys.executable}"
    proj = make_project(tmp_path / "P", ["ProjectBegin", 'ProjectSource="Gone.gpl"', "ProjectEnd"], {})
    done = subprocess.run([str(script), "check", str(proj)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 1
    assert "error GPL1405" in done.stderr and "Traceback" not in done.stderr
    done = subprocess.run([str(script), "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and "exit status" in done.stdout


def test_python_dash_m_runs(tmp_path: Path) -> None:
    done = subprocess.run([sys.executable, "-m", "gpl2py", "frobnicate"], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 2 and "GPL9001" in done.stderr


# --- docs ---------------------------------------------------------------------------------------


def test_diagnostics_doc_is_in_sync() -> None:
    doc = REPO / "docs" / "diagnostics.md"
    assert doc.read_text() == messages.markdown(), (
        "docs/diagnostics.md is stale: run  python -m gpl2py.messages > docs/diagnostics.md"
    )



# --- room for later commands --------------------------------------------------------------------


def test_a_default_command_would_receive_a_bare_project_path(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`gpl2py PROJECT -o OUT` needs only a Command marked default=True: the parser is not reshaped."""
    seen: dict[str, object] = {}

    def configure(parser: object) -> None:
        parser.add_argument("project")  # type: ignore[attr-defined]
        parser.add_argument("-o", dest="out", required=True)  # type: ignore[attr-defined]

    def run_transpile(args: object) -> cli.Outcome:
        seen.update(project=args.project, out=args.out, json=args.json)  # type: ignore[attr-defined]
        return cli.Outcome()

    extra = cli.Command("transpile", "translate", "Translate a project.", configure, run_transpile, default=True)
    monkeypatch.setattr(cli, "COMMANDS", [*cli.COMMANDS, extra])
    monkeypatch.chdir(tmp_path)
    (tmp_path / "cell").mkdir()  # a bare word that is no path is taken for a mistyped command
    code, _, _ = run(capsys, "--json", "cell", "-o", "out")
    assert code == 0 and seen == {"project": "cell", "out": "out", "json": True}
    code, _, err = run(capsys, "check", str(tmp_path / "missing"))
    assert code == 1 and "GPL1400" in err  # named commands are unaffected


# --- check runs the semantic pass; summaries count the files ------------------------------------

SEMANTIC_ERROR = b"Module Main\n    Public Sub Main()\n        Dim n As Integer\n        n = Undeclared + 1\n    End Sub\nEnd Module\n"


def test_check_reports_semantic_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "Main.gpl").write_bytes(SEMANTIC_ERROR)
    code, out, err = run(capsys, "check", str(tmp_path / "Main.gpl"))
    assert code == 1 and out == ""
    assert [(int(m["line"]), int(m["col"]), m["code"]) for m in headers(err)] == [(4, 13, "GPL2001")]
    assert err.splitlines()[-1] == "checked 1 file: 1 error, 0 warnings"


def test_check_reports_stub_warnings_and_strict_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "Main.gpl").write_bytes(SEMANTIC_ERROR)
    (tmp_path / "Vendor.gpp").write_bytes(b"'#Protected|\x00\x01")
    code, _, err = run(capsys, "check", str(tmp_path))
    assert code == 0
    # GPL1406 at Vendor.gpp:1:1; GPL2032 (Sub Main assumed as the start) is what translate says too
    assert sorted(m["code"] for m in headers(err)) == ["GPL1406", "GPL2032", "GPL3501"]
    assert err.splitlines()[-1] == "checked 1 file: 0 errors, 3 warnings"
    code, _, err = run(capsys, "check", str(tmp_path), "--strict")
    assert code == 1 and err.splitlines()[-1] == "checked 1 file: 1 error, 1 warning"


def test_translate_counts_files_when_a_semantic_error_stops_it(tmp_path: Path,
                                                              capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "Main.gpl").write_bytes(SEMANTIC_ERROR)
    (tmp_path / "Other.gpl").write_bytes(b"Module Other\nEnd Module\n")
    code, _, err = run(capsys, str(tmp_path), "-o", str(tmp_path / "out"))
    assert code == 1
    assert err.splitlines()[-1] == "checked 2 files: 1 error, 0 warnings"
    assert "    n = Undeclared + 1" in err  # the excerpt: the files are known to the printer
    assert not (tmp_path / "out").exists()


# --- did you mean -------------------------------------------------------------------------------


def test_a_mistyped_command_is_not_taken_for_a_project(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "chek", str(SAMPLE))
    assert code == 2 and out == ""
    assert "error GPL9001: gpl2py: 'chek' is neither a command nor a project path; did you mean 'check'?" in err
    code, _, err = run(capsys, "frobnicate")
    assert code == 2 and "(the commands: check, " in err and "did you mean" not in err


def test_an_existing_folder_with_a_command_like_name_is_a_project(
        monkeypatch: pytest.MonkeyPatch, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "chek").mkdir()
    (tmp_path / "chek" / "Main.gpl").write_bytes(GOOD_MODULE)
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, "chek", "-o", "out")
    assert code == 0, err
    assert (tmp_path / "out" / "chek" / "__init__.py").is_file()


@pytest.mark.parametrize("argv, hint", [
    (["check", "--stricct", str(SAMPLE)], "; did you mean --strict?"),
    (["run", "--clock", "fats", str(SAMPLE)], "; did you mean fast?"),
    (["run", "--robot", "pf40", str(SAMPLE)], "; did you mean PF400?"),
])
def test_a_mistyped_option_or_choice_gets_a_suggestion(argv: list[str], hint: str,
                                                       capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, *argv)
    assert code == 2 and "error GPL9001" in err
    assert err.rstrip().endswith(hint), err


# --- explain ------------------------------------------------------------------------------------


def test_explain_prints_a_codes_documentation_from_the_installed_package(tmp_path: Path) -> None:
    # from a folder without docs/: the text comes from gpl2py.messages, docs/diagnostics.md's source
    done = subprocess.run([str(_script()), "explain", "GPL2014"], capture_output=True, text=True,
                          timeout=60, cwd=tmp_path)
    assert done.returncode == 0 and done.stderr == ""
    m = messages.PARSE_EXPECTED_EXPRESSION.__class__  # the registry's Message type
    [entry] = [x for x in messages.all_messages() if x.code == "GPL2014"]
    assert isinstance(entry, m)
    first, blank, *notes = done.stdout.splitlines()
    assert first == f"GPL2014 (error): {entry.template}" and blank == ""
    assert " ".join(notes) == entry.notes
    assert entry.notes.startswith(entry.doc) and "raises error -738 *Invalid data type*" in entry.notes


def test_explain_lists_a_range_and_suggests_a_code(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "explain", "gpl35")
    assert code == 0
    assert [line.split(" ")[0] for line in out.splitlines()] == ["GPL3501", "GPL3502", "GPL3503"]
    code, out, _ = run(capsys, "explain", "--json", "1101")
    assert code == 0
    assert json.loads(out)["explain"] == {
        "code": "GPL1101", "severity": "error", "message": "expected an expression, found {found}",
        "notes": "Translated anyway (--keep-going, or the error ignored), the code it affects raises error "
                 "-712 *Invalid syntax* when the program reaches it."}
    code, _, err = run(capsys, "explain", "GPL9O01")
    assert code == 2 and "error GPL9001: gpl2py explain: no diagnostic code 'GPL9O01'; did you mean GPL9001?" in err
