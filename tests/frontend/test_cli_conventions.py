"""The command line's conventions, next to ruff and mypy (issue 15): --select/--ignore and
``' gpl2py: ignore`` comments, ``[tool.gpl2py]``, several paths, --output-format
text|json|sarif|github, colour with NO_COLOR/FORCE_COLOR."""

from __future__ import annotations

import json
import os
import pty
import re
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest

import gpl2py.cli as cli
from gpl2py.cli import main

REPO = Path(__file__).resolve().parents[2]
SARIF_SCHEMA = Path(__file__).with_name("data") / "sarif-2.1.0-rtm.5.json"
ANSI = re.compile(r"\x1b\[[0-9;]*m")

# Line 6: GPL2014 (Is on a number); line 7: GPL2014 (Is on Strings); line 8: GPL2005 (String -> Location)
SOURCE = """Module Main
    Public Sub Main()
        Dim s As String
        Dim b As Boolean
        Dim n As Integer
        b = (n Is Nothing){c6}
        b = (s Is s){c7}
        Dim l As Location = s{c8}
    End Sub
End Module
"""


def write(folder: Path, c6: str = "", c7: str = "", c8: str = "", name: str = "Main.gpl") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text(SOURCE.format(c6=c6, c7=c7, c8=c8))
    return path


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    capsys.readouterr()
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def found(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, list[tuple[str, int]]]:
    """The status and (code, line) of every diagnostic, from the JSON output."""
    code, out, _ = run(capsys, *argv, "--output-format", "json")
    return code, [(d["code"], d["line"]) for d in json.loads(out)["diagnostics"]]


ALL = [("GPL2014", 6), ("GPL2014", 7), ("GPL2005", 8)]


@pytest.fixture(autouse=True)
def _no_config_around(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every test works in its own folder, where no pyproject.toml is found unless it writes one."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.delenv("FORCE_COLOR", raising=False)


# --- --select / --ignore ------------------------------------------------------------------------


@pytest.mark.parametrize("options, expected", [
    ([], ALL),
    (["--ignore", "GPL2014"], [("GPL2005", 8)]),
    (["--ignore", "GPL20"], []),
    (["--select", "GPL2014"], [("GPL2014", 6), ("GPL2014", 7)]),
    (["--select", "gpl2", "--ignore", "GPL2005"], [("GPL2014", 6), ("GPL2014", 7)]),
    (["--ignore", "GPL2", "--select", "GPL2005"], [("GPL2005", 8)]),  # the more specific wins
    (["--ignore", "GPL2014,GPL2005"], []),
    (["--ignore", "GPL2014", "--ignore", "GPL2005"], []),
])
def test_select_and_ignore_by_code_or_prefix(options: list[str], expected: list[tuple[str, int]],
                                             tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(tmp_path / "p")
    status, diags = found(capsys, "check", str(path), *options)
    assert [d for d in diags if d[0] != "GPL2032"] == expected
    assert status == (1 if expected else 0)


def test_an_ignored_error_no_longer_stops_the_translation(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(tmp_path / "p")
    status, _, err = run(capsys, str(path), "-o", str(tmp_path / "out"))
    assert status == 1 and not (tmp_path / "out").exists()
    status, _, err = run(capsys, str(path), "-o", str(tmp_path / "out"), "--ignore", "GPL20")
    assert status == 0, err
    assert (tmp_path / "out" / "main" / "main_mod.py").is_file()
    assert err.splitlines()[-1].endswith(": 0 errors, 0 warnings")  # (GPL2032 is a GPL20 too)


@pytest.mark.parametrize("value, hint", [("GLP2014", "did you mean GPL2014?"), ("GPL2999", "no diagnostic has this code"),
                                         ("E501", "not a diagnostic code or prefix")])
def test_a_bad_code_is_a_usage_error(value: str, hint: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = run(capsys, "check", str(write(tmp_path / "p")), "--ignore", value)
    assert status == 2 and f"error GPL9001: gpl2py check: --ignore '{value}': " in err and hint in err


def test_an_internal_error_cannot_be_ignored(monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    import gpl2py.gpl.pipeline as transpile

    def broken_lower(*args: object, **kwargs: object) -> None:
        raise KeyError("lowering bug")

    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    monkeypatch.setattr(transpile, "lower", broken_lower)
    status, diags = found(capsys, str(write(tmp_path / "p")), "-o", "out", "--ignore", "GPL")
    assert status == 2 and [c for c, _ in diags] == ["GPL9000"]


# --- ' gpl2py: ignore comments ------------------------------------------------------------------


def test_an_inline_comment_suppresses_its_codes_on_its_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(tmp_path / "p", c6=" ' gpl2py: ignore[GPL2014] the vendor compares this way",
                 c7=" ' gpl2py: ignore[GPL2005]", c8=" ' GPL2PY: Ignore")
    status, diags = found(capsys, "check", str(path))
    # line 6: its code; line 7: another code, so GPL2014 stays; line 8: every code, any case
    assert [d for d in diags if d[0] != "GPL2032"] == [("GPL2014", 7)] and status == 1


def test_inline_codes_may_be_several_or_prefixes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(tmp_path / "p", c6=" ' gpl2py: ignore[GPL2005, GPL20]", c7=" ' gpl2py: ignore[GPL1, GPL2014]")
    _, diags = found(capsys, "check", str(path))
    assert [d for d in diags if d[0] != "GPL2032"] == [("GPL2005", 8)]


def test_a_quote_in_a_string_literal_is_no_suppression(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "p"
    folder.mkdir()
    (folder / "Main.gpl").write_text(
        'Module Main\n    Public Sub Main()\n        Dim s As String\n'
        '        s = "a \' gpl2py: ignore" & 5 Is s\n    End Sub\nEnd Module\n')
    _, diags = found(capsys, "check", str(folder / "Main.gpl"))
    assert ("GPL2014", 4) in diags


def test_a_bad_code_in_a_comment_is_a_warning_at_the_comment(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(tmp_path / "p", c6=" ' gpl2py: ignore[GLP2014]")
    status, _, err = run(capsys, "check", str(path))
    assert status == 1
    assert (f"{path}:6:28: warning GPL9004: 'GLP2014' in a gpl2py: ignore comment suppresses nothing: not a "
            "diagnostic code or prefix") in err and "did you mean GPL2014?" in err
    assert f"{path}:6:14: error GPL2014" in err  # and it suppressed nothing


def test_run_applies_the_selection_and_does_not_reuse_another_selections_cache(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(tmp_path / "p")
    cache = str(tmp_path / "cache")
    status, _, err = run(capsys, "run", str(path), "--cache-dir", cache)
    assert status == 1 and "GPL2014" in err
    status, _, err = run(capsys, "run", str(path), "--cache-dir", cache, "--ignore", "GPL20")
    # translated without a diagnostic; the line of an ignored error raises it when the program
    # reaches it (line 6: -738 *Invalid data type* for GPL2014), an unhandled error (status 3)
    assert "0 errors, 0 warnings" in err and "error GPL20" not in err, err
    assert status == 3 and "Main.gpl:6: error -738 in thread Main" in err, err
    status, _, err = run(capsys, "run", str(path), "--cache-dir", cache)  # the first entry, unchanged
    assert status == 1 and "GPL2014" in err


# --- [tool.gpl2py] ------------------------------------------------------------------------------


def config(folder: Path, text: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "pyproject.toml").write_text(f"[project]\nname = \"cells\"\n\n[tool.gpl2py]\n{text}")
    return folder / "pyproject.toml"


def test_config_from_the_current_folder_or_above(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    write(tmp_path / "cells" / "a")
    config(tmp_path, 'paths = ["cells/a"]\nignore = ["GPL2014"]\n')
    (tmp_path / "sub").mkdir()
    monkeypatch.chdir(tmp_path / "sub")  # found in a parent folder; paths relative to the file
    status, diags = found(capsys, "check")
    assert status == 1 and [d for d in diags if d[0] != "GPL2032"] == [("GPL2005", 8)]
    status, diags = found(capsys, "check", "--ignore", "GPL2005")  # the command line wins
    assert [d for d in diags if d[0] != "GPL2032"] == [("GPL2014", 6), ("GPL2014", 7)]
    status, diags = found(capsys, "check", "--no-config", str(tmp_path / "cells" / "a"))
    assert [d for d in diags if d[0] != "GPL2032"] == ALL


def test_config_paths_show_relative_to_the_current_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    write(tmp_path / "cells" / "a")
    config(tmp_path, 'paths = ["cells/a"]\n')
    _, out, _ = run(capsys, "check", "--output-format", "json")
    assert {d["file"] for d in json.loads(out)["diagnostics"]} == {str(Path("cells/a/Main.gpl"))}


def test_a_project_folders_own_pyproject_is_not_read(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    """A project is untrusted input (docs/security.md): its folder never configures gpl2py, whose
    table can name --stubs, Python that run executes."""
    path = write(tmp_path / "vendor")
    config(tmp_path / "vendor", 'ignore = ["GPL2"]\n')
    (tmp_path / "work").mkdir()
    monkeypatch.chdir(tmp_path / "work")
    _, diags = found(capsys, "check", str(path))
    assert [d for d in diags if d[0] != "GPL2032"] == ALL


def test_config_strict_stubs_and_no_strict(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cell = tmp_path / "cell"
    cell.mkdir()
    (cell / "Main.gpl").write_text("Module Main\n    Public Sub Main()\n        VendorLib.Grip(3)\n    End Sub\nEnd Module\n")
    (cell / "VendorLib.gpp").write_bytes(b"'#Protected|\x00\x01")
    (tmp_path / "sim").mkdir()
    (tmp_path / "sim" / "vendorlib.py").write_text("def Grip(w):\n    return w\n")
    config(tmp_path, 'paths = ["cell"]\nstrict = true\nstubs = "sim"\n')
    status, _, err = run(capsys, "check")
    assert status == 1 and "error GPL3501" in err and "the --stubs file vendorlib.py implements it" in err
    status, _, err = run(capsys, "check", "--no-strict")
    assert status == 0 and "warning GPL3501" in err


def test_config_robot_and_clock_for_run(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cell = tmp_path / "cell"
    cell.mkdir()
    (cell / "Main.gpl").write_text('Module Main\n    Public Sub Main()\n        Console.WriteLine(CStr(Robot.Selected))\n'
                                   '    End Sub\nEnd Module\n')
    config(tmp_path, 'robot = "pf3400"\nclock = "fast"\n')
    status, out, err = run(capsys, "run", str(cell), "--cache-dir", str(tmp_path / "cache"))
    assert status == 0, err
    assert "(fast clock," in err.splitlines()[-1]
    config(tmp_path, 'robot = "PF9999"\n')
    status, _, err = run(capsys, "run", str(cell), "--cache-dir", str(tmp_path / "cache"))
    assert status == 2 and "error GPL9003: " in err and "robot = 'PF9999': not a robot model" in err


@pytest.mark.parametrize("text, problem", [
    ("ignore = [\"GPL2014\"\n", "not valid TOML"),
    ("path = [\"a\"]\n", "[tool.gpl2py] has no key 'path'; did you mean 'paths'?"),
    ("strict = \"yes\"\n", "[tool.gpl2py] strict = 'yes': must be true or false"),
    ("clock = \"slow\"\n", "[tool.gpl2py] clock = 'slow': must be one of virtual, fast, real"),
    ("ignore = [\"GLP2014\"]\n", "[tool.gpl2py] ignore 'GLP2014': not a diagnostic code or prefix"),
    ("max-source-mb = -1\n", "max-source-mb = -1: must be a positive number"),
])
def test_a_bad_config_is_gpl9003_status_2(text: str, problem: str, tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    conf = config(tmp_path, text)
    status, out, err = run(capsys, "check", str(write(tmp_path / "p")))
    assert status == 2 and out == ""
    assert f"error GPL9003: {conf}: " in err and problem in err, err
    assert "Traceback" not in err


def test_config_file_named_on_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    conf = config(tmp_path / "elsewhere", 'ignore = ["GPL2"]\n')
    status, diags = found(capsys, "check", str(write(tmp_path / "p")), "--config", str(conf))
    assert status == 0 and diags == []
    status, _, err = run(capsys, "check", str(write(tmp_path / "p")), "--config", str(tmp_path / "nope.toml"))
    assert status == 2 and "nope.toml: no such file" in err


def test_no_path_and_no_config_paths_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = run(capsys, "check")
    assert status == 2 and "PATH (or paths in [tool.gpl2py] of pyproject.toml)" in err


# --- several paths ------------------------------------------------------------------------------

GOOD = "Module Main\n    Public Sub Main()\n        Console.WriteLine(\"hi\")\n    End Sub\nEnd Module\n"


def test_check_several_projects(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = write(tmp_path / "bad")
    (tmp_path / "good").mkdir()
    (tmp_path / "good" / "Main.gpl").write_text(GOOD)
    status, out, err = run(capsys, "check", str(tmp_path / "good"), str(bad))
    assert status == 1
    # GPL2032 (the Sub Main start) of the good one; the bad one stops before the lowering says it
    assert err.count("error GPL2014") == 2 and err.splitlines()[-1] == "checked 2 files: 3 errors, 1 warning"


def test_translate_several_projects_writes_those_without_errors(tmp_path: Path,
                                                                capsys: pytest.CaptureFixture[str]) -> None:
    for name in ("one", "two"):
        (tmp_path / name).mkdir()
        (tmp_path / name / f"{name.title()}.gpl").write_text(GOOD.replace("Main", name.title()))
    bad = write(tmp_path / "bad", name="Bad.gpl")
    status, _, err = run(capsys, str(tmp_path / "one"), str(bad), str(tmp_path / "two"), "-o", str(tmp_path / "out"))
    assert status == 1
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["one", "two"]
    assert err.splitlines()[-1].startswith("transpiled 2 of 3 projects, 3 files (")
    # the same package twice: the second is an output error, the first stays
    status, _, err = run(capsys, str(tmp_path / "one"), str(tmp_path / "one" / "One.gpl"), "-o", str(tmp_path / "o2"))
    assert status == 1 and "error GPL3004: cannot write" in err and "is translated to this package already" in err


# --- output formats -----------------------------------------------------------------------------


def test_json_has_a_schema_version(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from gpl2py import __version__

    _, out, _ = run(capsys, "check", str(write(tmp_path / "p")), "--json")
    doc = json.loads(out)
    assert doc["schema_version"] == 1 and doc["gpl2py_version"] == __version__
    assert doc["summary"] == {"errors": 3, "warnings": 0}


def test_sarif_validates_against_the_schema(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = write(tmp_path / "p", c6=" ' gpl2py: ignore[GPL9999]")
    (tmp_path / "p" / "Vendor.gpp").write_bytes(b"'#Protected|\x00")
    status, out, err = run(capsys, "check", str(tmp_path / "p"), str(tmp_path / "missing"), "--output-format", "sarif")
    assert status == 1 and err == ""
    log = json.loads(out)
    jsonschema.validate(log, json.loads(SARIF_SCHEMA.read_text()))
    [run_] = log["runs"]
    results = run_["results"]
    by_rule = {(r["ruleId"], r["level"]) for r in results}
    assert {("GPL2014", "error"), ("GPL2005", "error"), ("GPL1406", "warning"), ("GPL9004", "warning"),
            ("GPL1400", "error")} <= by_rule
    first = next(r for r in results if r["ruleId"] == "GPL2014")
    assert first["locations"][0]["physicalLocation"] == {
        "artifactLocation": {"uri": "p/Main.gpl", "uriBaseId": "%SRCROOT%"},
        "region": {"startLine": 6, "startColumn": 14, "endLine": 6, "endColumn": 15}}
    assert run_["originalUriBaseIds"]["%SRCROOT%"]["uri"] == tmp_path.absolute().as_uri() + "/"
    assert "locations" not in next(r for r in results if r["ruleId"] == "GPL1400")  # no position
    rules = run_["tool"]["driver"]["rules"]
    assert [r["id"] for r in rules] == sorted(r["id"] for r in rules)
    assert all(rules[r["ruleIndex"]]["id"] == r["ruleId"] for r in results)
    # a rule's description is gpl2py explain's: what a line that keeps the error raises included
    rule = next(r for r in rules if r["id"] == "GPL2014")
    assert rule["fullDescription"]["text"].endswith("raises error -738 *Invalid data type* when the program reaches it.")
    assert run_["invocations"] == [{"executionSuccessful": True}]


def test_github_annotations(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "a,b:c"
    write(folder)
    status, out, err = run(capsys, "check", str(Path("a,b:c")), "--output-format", "github")
    assert status == 1
    lines = out.splitlines()
    assert lines[0] == ("::error file=a%2Cb%3Ac/Main.gpl,line=6,col=14,endLine=6,endColumn=15,title=GPL2014::"
                        "GPL2014: operator Is cannot be applied to Integer and Nothing")
    assert [line.split(" ", 1)[0] for line in lines] == ["::error", "::error", "::error"]
    assert err.splitlines() == ["checked 1 file: 3 errors, 0 warnings"]  # the summary, for the log
    write(folder, c6=" ' gpl2py: ignore[GPL2014%]")
    _, out, _ = run(capsys, "check", str(Path("a,b:c")), "--output-format", "github")
    assert ("::warning file=a%2Cb%3Ac/Main.gpl,line=6,col=28,endLine=6,endColumn=54,title=GPL9004::GPL9004: "
            "'GPL2014%25' in a gpl2py: ignore comment") in out


def test_run_annotates_an_unhandled_gpl_error_for_github(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cell = tmp_path / "cell"
    cell.mkdir()
    (cell / "Main.gpl").write_text("Module Main\n    Public Sub Main()\n        Dim z As Integer\n"
                                   "        Console.WriteLine(CStr(1 \\ z))\n    End Sub\nEnd Module\n")
    status, out, _ = run(capsys, "run", "cell", "--output-format", "github", "--cache-dir", str(tmp_path / "c"))
    assert status == 3
    assert "::error file=cell/Main.gpl,line=4,title=GPL error -709::error -709 in thread Main: *Division by 0*" in out
    status, _, err = run(capsys, "run", "cell", "--output-format", "sarif")
    assert status == 2 and "--output-format sarif describes diagnostics" in err


# --- colour -------------------------------------------------------------------------------------


def test_colour_when_asked_and_never_by_default_in_a_pipe(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    path = str(write(tmp_path / "p"))
    _, _, err = run(capsys, "check", path)
    assert not ANSI.search(err)
    _, _, err = run(capsys, "check", path, "--color", "always")
    assert f"\x1b[1m{path}:6:14:\x1b[0m \x1b[1;31merror GPL2014\x1b[0m: operator Is" in err
    assert ANSI.sub("", err) == run(capsys, "check", path)[2]  # the same text, only coloured
    monkeypatch.setenv("FORCE_COLOR", "1")
    assert ANSI.search(run(capsys, "check", path)[2])
    monkeypatch.setenv("NO_COLOR", "1")  # NO_COLOR wins over FORCE_COLOR
    assert not ANSI.search(run(capsys, "check", path)[2])
    assert ANSI.search(run(capsys, "check", path, "--color", "always")[2])  # the command line wins
    _, out, _ = run(capsys, "check", path, "--color", "always", "--json")
    assert not ANSI.search(out)


@pytest.mark.parametrize("env, coloured", [({}, True), ({"NO_COLOR": "1"}, False), ({"TERM": "dumb"}, False),
                                           ({"NO_COLOR": ""}, True)])
def test_colour_on_a_terminal(env: dict[str, str], coloured: bool, tmp_path: Path) -> None:
    path = write(tmp_path / "p")
    primary, secondary = pty.openpty()
    base = {k: v for k, v in os.environ.items() if k not in ("NO_COLOR", "FORCE_COLOR")}
    try:
        done = subprocess.run([sys.executable, "-m", "gpl2py", "check", str(path)], stdout=subprocess.DEVNULL,
                              stderr=secondary, cwd=tmp_path, env={**base, "TERM": "xterm", **env}, timeout=120)
        os.close(secondary)
        chunks = []
        while True:
            try:
                data = os.read(primary, 65536)
            except OSError:  # the terminal's other end is closed: everything was read
                break
            if not data:
                break
            chunks.append(data)
    finally:
        os.close(primary)
    text = b"".join(chunks).decode()
    assert done.returncode == 1 and "error GPL2014" in text
    assert bool(ANSI.search(text)) is coloured


def test_every_new_option_is_in_the_parser() -> None:
    parser = cli.build_parser()
    check = next(a for a in parser._actions if a.dest == "command").choices["check"]  # type: ignore[attr-defined]
    options = {s for a in check._actions for s in a.option_strings}
    assert {"--select", "--ignore", "--config", "--no-config", "--output-format", "--color", "--no-strict"} <= options


# --- pre-commit ---------------------------------------------------------------------------------


def test_pre_commit_hook_checks_the_configured_projects(tmp_path: Path) -> None:
    """What pre-commit does with the hook: match the changed files against ``files``, then run
    ``entry`` once, without file names, in the repository's root (``pass_filenames: false``)."""
    import shlex

    yaml = pytest.importorskip("yaml")
    [hook] = yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())
    assert hook["id"] == "gpl2py-check" and hook["language"] == "python" and hook["pass_filenames"] is False
    files = re.compile(hook["files"])
    assert all(files.search(p) for p in ("cells/a/Main.gpl", "Tcs.GPO", "x/Vendor.gpp", "cells/a/Project.gpr"))
    assert not any(files.search(p) for p in ("README.md", "setup.py", "cells/a/Project.gpr.bak", "notproject.gpr"))
    write(tmp_path / "cells" / "a")
    config(tmp_path, 'paths = ["cells/a"]\n')
    entry = shlex.split(hook["entry"])
    assert entry[0] == "gpl2py"
    script = Path(sys.executable).with_name("gpl2py")
    done = subprocess.run([str(script), *entry[1:]], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert done.returncode == 1 and "cells/a/Main.gpl:6:14: error GPL2014" in done.stderr
    config(tmp_path, 'paths = ["cells/a"]\nignore = ["GPL20"]\n')
    done = subprocess.run([str(script), *entry[1:]], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr


def test_options_with_values_before_the_project_of_the_bare_form(tmp_path: Path,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    """`gpl2py --ignore GPL20 -o out cell`: the values are not taken for a mistyped command."""
    write(tmp_path / "cell")
    status, _, err = run(capsys, "--ignore", "GPL20", "-o", "out", "cell")
    assert status == 0, err
    assert (tmp_path / "out" / "cell" / "__init__.py").is_file()
