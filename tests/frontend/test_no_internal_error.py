"""No input gives an internal error (issue 20, item 2).

* **Every error, ignored or kept.**  For each error code a source (or a project) can carry, a small
  project that has it is translated with every error it has ignored (``--ignore``) and with
  ``--keep-going``: no internal error GPL9000, every generated module compiles and imports, and --
  for an error on a line the program runs -- that line is the call that raises the controller's
  error for the fault (``messages.RUNTIME_CODES``; what the program then does is
  tests/e2e/test_kept_errors.py).  ``test_every_error_code_has_a_case`` keeps the table complete:
  a new error code needs a case here and a decision in ``RUNTIME_CODES``.
* **Deep nesting in module-level initialisers** (a Const of 478 nested parentheses, 500 chained
  calls or members, a parameter's default) is GPL1117 / GPL3005 at its line, as inside a
  procedure, never a RecursionError.
* **A GPL9000 stays in its file**: a bug met while parsing, analysing or lowering one file (planted
  here, as a future bug would be) is reported at that file, and the other files' diagnostics are
  all reported, by ``check`` and ``translate`` alike.
"""

from __future__ import annotations

import contextlib
import importlib
import io
import json
import re
import sys
from pathlib import Path

import pytest

import gpl2py.gpl.semantics.check as check_module
import gpl2py.gpl.pipeline as pipeline_module
from gpl2py import messages as M
from gpl2py.cli import main as cli_main
from gpl2py.diagnostics import DiagnosticSink, Severity
from gpl2py.run import import_package
from gpl2py.selection import Selection
from gpl2py.transpile import transpile, write_package

M_ = "Module Main\n{}\nEnd Module\n"
S = "Module Main\n    Public Sub Main()\n{}\n    End Sub\nEnd Module\n"
MAIN = S.format('        Console.WriteLine("a")')


def gpr(sources: str, start: str = "Main") -> str:
    """A Project.gpr naming ``start`` and the ProjectSource lines ``sources``."""
    return f'ProjectBegin\nProjectName="W"\nProjectStart="{start}"\n{sources}ProjectEnd\n'


#: One project per error code: its files (``"start"``: the ProjectStart; a ``Project.gpr`` given
#: is used as it is).
CASES: dict[str, str | dict[str, str | bytes]] = {
    "GPL1001": S.format("        Dim i As Integer\n        i = 1 ¤ 2"),
    "GPL1002": S.format('        Console.WriteLine("abc)'),
    "GPL1004": S.format('        Console.WriteLine("é")'),
    "GPL1006": S.format("        Dim i As Integer\n        i = 725L"),
    "GPL1007": S.format("        Dim d As Double\n        d = " + "9" * 400),
    "GPL1009": S.format("        Dim " + "a" * 130 + " As Integer"),
    "GPL1010": S.format("        Dim i As Integer #Region"),
    "GPL1100": S.format("        Dim i As\n        i = 1"),
    "GPL1101": S.format("        Dim i As Integer\n        i = 1 +"),
    "GPL1102": S.format("        Dim i As Integer\n        i = 1 2"),
    "GPL1103": S.format("        On Error GoTo x"),
    "GPL1104": S.format("        End If"),
    "GPL1105": S.format("        If True Then\n            Console.WriteLine(\"a\")"),
    "GPL1107": S.format("        Dim i"),
    "GPL1108": S.format("        1 + 2"),
    "GPL1109": M_.format("    Console.WriteLine(\"a\")\n    Public Sub Main()\n    End Sub"),
    "GPL1110": "Public Sub Main()\nEnd Sub\n",
    "GPL1111": S.format("        Dim i As Integer\n        i = 1 : i = 2"),
    "GPL1112": S.format("        Dim a, b As Integer = 1"),
    "GPL1113": S.format("        Dim a(3) As Integer = 1"),
    "GPL1114": S.format("        Dim a(1, 2, 3, 4, 5) As Integer"),
    "GPL1115": S.format("        Dim e As Exception\n        Try\n        Catch e\n        Catch e\n        End Try"),
    "GPL1116": S.format("        Try\n        Catch\n        End Try"),
    "GPL1117": S.format("        Dim i As Integer\n        i = " + "(" * 200 + "1" + ")" * 200),
    "GPL1119": S.format("        If True Then For i = 1 To 2"),
    "GPL1120": M_.format("    Public Function F()\n    End Function\n    Public Sub Main()\n    End Sub"),
    "GPL1121": M_.format("    Public Class K\n        Public Property P As Integer\n        End Property\n    End Class\n    Public Sub Main()\n    End Sub"),
    "GPL1122": S.format("        Do While True\n        Loop Until True"),
    "GPL1123": M_.format("    Property P As Integer\n        Get\n        End Get\n    End Property\n    Public Sub Main()\n    End Sub"),
    "GPL1124": S.format("        Select 1\n            Console.WriteLine(\"a\")\n        Case 1\n        End Select"),
    "GPL1125": S.format("        Public Dim i As Integer"),
    "GPL2001": S.format("        x = 1\n        Console.WriteLine(CStr(y))\n        Foo(3)\n        z.Go(1)"),
    "GPL2002": S.format("        Dim i As Integer\n        Dim i As String\n        i = 1"),
    "GPL2003": S.format("        Dim i As Nonsense\n        i = 1"),
    "GPL2004": M_.format("    Sub F(ByVal a As Integer)\n    End Sub\n    Public Sub Main()\n        F(1, 2)\n        F()\n    End Sub"),
    "GPL2005": M_.format("    Public Class K\n    End Class\n    Public Sub Main()\n        Dim k As New K\n        Dim i As Integer\n        i = k\n        k = 5\n    End Sub"),
    "GPL2006": {"A.gpl": "Module A\n    Public x As Integer\nEnd Module\n", "B.gpl": "Module B\n    Public x As Integer\nEnd Module\n",
                "Main.gpl": S.format("        x = 1\n        Console.WriteLine(CStr(x))")},
    "GPL2007": M_.format("    Public Class K\n    End Class\n    Public Sub Main()\n        Dim k As New K\n        k.Nope = 1\n        Console.WriteLine(CStr(k.Nope))\n        k.Nope(2)\n        Main.Nope = 3\n    End Sub"),
    "GPL2008": S.format("        Dim i As Integer\n        CStr(i) = \"a\"\n        1 = i"),
    "GPL2009": M_.format("    Sub F()\n    End Sub\n    Public Sub Main()\n        Dim i As Integer\n        i = F\n        i = F()\n        Console.WriteLine(CStr(F()))\n    End Sub"),
    "GPL2010": {"A.gpl": "Module A\n    Private x As Integer\n    Private Sub P()\n    End Sub\nEnd Module\n", "Main.gpl": S.format("        A.x = 1\n        Console.WriteLine(CStr(A.x))\n        A.P()")},
    "GPL2012": S.format("        Dim i As Integer\n        i(1) = 2\n        Console.WriteLine(CStr(i(1)))"),
    "GPL2013": M_.format("    Public Class K\n        Public Sub New(ByVal a As Integer)\n        End Sub\n    End Class\n    Public Sub Main()\n        Dim k As K\n        k = New K(\"a\", 2)\n    End Sub"),
    "GPL2014": M_.format("    Public Class K\n    End Class\n    Public Sub Main()\n        Dim k As New K\n        Dim i As Integer\n        i = k + 1\n        i = -k\n        Console.WriteLine(CStr(k * 2))\n    End Sub"),
    "GPL2015": M_.format("    Public Function F() As Integer\n        Return\n    End Function\n    Public Sub Main()\n        Return 5\n    End Sub"),
    "GPL2016": S.format("        Exit For\n        Exit While"),
    "GPL2017": S.format("        GoTo nowhere\n        Console.WriteLine(\"a\")"),
    "GPL2018": S.format("here:\n        Console.WriteLine(\"a\")\nhere:\n        GoTo here"),
    "GPL2019": {"Main.gpl": S.format("        Console.WriteLine(\"a\")"), "start": "Nope"},
    "GPL2021": M_.format("    Public Sub Main()\n        Me.x = 1\n        Console.WriteLine(CStr(Me))\n    End Sub"),
    "GPL2022": M_.format("    Public Class K\n        Public ReadOnly Property P As Integer\n            Get\n                Return 1\n            End Get\n        End Property\n        Public WriteOnly Property W As Integer\n            Set (value As Integer)\n            End Set\n        End Property\n    End Class\n    Public Sub Main()\n        Dim k As New K\n        k.P = 2\n        Console.WriteLine(CStr(k.W))\n    End Sub"),
    "GPL2023": {"Other.gpl": "Module Other\nEnd Module\n", "Main.gpl": S.format("        Dim i As Integer\n        i = Integer\n        i = Other\n        Console.WriteLine(CStr(Other))")},
    "GPL2024": S.format("        Dim a(3) As Integer\n        a(1, 2) = 3\n        Console.WriteLine(CStr(a(1, 2)))"),
    "GPL2026": S.format("        Dim i As Integer\n        ReDim i(3)\n        Dim x As Integer\n        For Each x In i\n        Next"),
    "GPL2027": M_.format("    Const C As Integer = 1\n    Public Sub Main()\n        C = 2\n        C += 1\n    End Sub"),
    "GPL2028": S.format("        Dim i As Integer\n        i.Foo = 1\n        Console.WriteLine(CStr(i.Foo))\n        i.Bar(2)"),
    "GPL2029": S.format("        Dim i As Integer\n        Dim t As Thread\n        t = New Thread(AddressOf i)"),
    "GPL2030": M_.format("    Sub _Init()\n    End Sub\n    Public Sub Main()\n    End Sub"),
    "GPL2033": M_.format("    Sub F(Optional ByVal a As Integer = 1, ByVal b As Integer)\n    End Sub\n    Public Sub Main()\n        F(1, 2)\n    End Sub"),
    "GPL2035": S.format("        Dim o As Object\n        o = Nothing"),
    "GPL2036": S.format("        Dim c As Controller\n        c = New Controller"),
    "GPL2040": M_.format("    Sub F(ByVal a As Integer, ByVal b As Double)\n    End Sub\n    Sub F(ByVal a As Double, ByVal b As Integer)\n    End Sub\n    Public Sub Main()\n        F(1, 2)\n    End Sub"),
    "GPL2041": M_.format("    Sub F(ByVal a As Integer)\n    End Sub\n    Sub F(ByVal a As Integer, ByVal b As Integer)\n    End Sub\n    Public Sub Main()\n        F(1, 2, 3)\n    End Sub"),
    "GPL2042": M_.format("    Public Const A As Integer = B + 1\n    Public Const B As Integer = A + 1\n    Public Sub Main()\n        Console.WriteLine(CStr(A))\n    End Sub"),
    "GPL3001": S.format("        Dim i As Integer\n        GoTo inside\n        For i = 1 To 3\ninside:\n            Console.WriteLine(CStr(i))\n        Next"),
    "GPL3002": S.format("        Dim e As Exception\n        GoTo inside\n        Try\ninside:\n            Console.WriteLine(\"a\")\n        Catch e\n        End Try"),
    "GPL3003": S.format("        Try\n        Finally\n            Exit Try\n        End Try"),
    "GPL3005": S.format("        Dim i As Integer\n        i = a" + "(1)" * 600),
    "GPL3007": S.format("        Dim i As Integer\n" + "".join(f"        For i = 1 To {n}\n" for n in range(1, 24)) + "        Console.WriteLine(\"x\")\n" + "        Next\n" * 23),
    # project loading: errors about no line of the program, ignored all the same
    "GPL1400": {"path": "nowhere"},
    "GPL1401": {"Readme.txt": "not GPL", "path": "Readme.txt", "Project.gpr": None},
    "GPL1402": {"Readme.txt": "no sources here", "Project.gpr": None},
    "GPL1404": {"Main.gpl": MAIN, "Bin.gpl": b"Module B\x00\n", "Project.gpr": gpr('ProjectSource="Main.gpl"\nProjectSource="Bin.gpl"\n')},
    "GPL1405": {"Main.gpl": MAIN, "Project.gpr": gpr('ProjectSource="Main.gpl"\nProjectSource="Gone.gpl"\n')},
    "GPL1407": {"Main.gpl": MAIN, "Project.gpr": gpr('ProjectSource="Main.gpl"\nthis is no line\n')},
    "GPL1409": {"Main.gpl": MAIN, "Project.gpr": 'ProjectName="W"\nProjectSource="Main.gpl"\nProjectEnd\n'},
    "GPL1410": {"Main.gpl": MAIN, "Project.gpr": 'ProjectBegin\nProjectStart="Main"\nProjectSource="Main.gpl"\n'},
    "GPL1415": {"Main.gpl": MAIN, "Project.gpr": 'ProjectBegin\nProjectStart="Main"\nProjectEnd\n'},
    "GPL1416": {"Main.gpl": MAIN, "Project.gpr": gpr('ProjectSource="Main.gpl"\nProjectSource="../x.gpl"\n')},
    "GPL1417": {"Main.gpl": MAIN, "Project.gpr": gpr('ProjectSource="Main.gpl"\nProjectSource="x.txt"\n')},
    "GPL1419": {"Main.gpl": MAIN, "Project.gpr": gpr('ProjectSource="Main.gpl"\nProjectName=""\n')},
    "GPL2034": {"Main.gpl": MAIN, "Vendor.gpp": b"'#Protected|\x00\x01", "start": "Hidden"},
}

#: Error codes no case walks: what makes them (a file the OS will not let gpl2py read, a FIFO, a
#: link out of the folder, a size limit, an output folder that cannot be written, a bad --stubs
#: folder) is no GPL text; each stops a file from loading as GPL1405 does, or concerns the output
#: (tests/frontend/test_hostile_inputs.py, test_cli.py and tests/stubs have them).
NOT_WALKED = {"GPL1403", "GPL1420", "GPL1421", "GPL1422", "GPL1423", "GPL3004", "GPL3503"}
#: Errors of a declaration or a block's closing line, not of a line the program runs: their code is
#: translated as well as it can be (a reserved name kept, a second Catch dropped ...) and raises nothing.
NOT_ON_A_RUN_LINE = {"GPL1104", "GPL1109", "GPL1110", "GPL1115", "GPL1116", "GPL1120", "GPL1121", "GPL1122",
                     "GPL1123", "GPL1124", "GPL2018", "GPL2030", "GPL2033", "GPL2042"}


def write_case(root: Path, code: str) -> Path:
    """The project of ``CASES[code]`` below ``root``; the path to translate."""
    case = CASES[code]
    files = dict(case) if isinstance(case, dict) else {"Main.gpl": case}
    folder = root / code
    folder.mkdir(parents=True)
    path = files.pop("path", None)
    start = files.pop("start", "Main")
    if "Project.gpr" not in files:
        files["Project.gpr"] = gpr("".join(f'ProjectSource="{n}"\n' for n in files), str(start))
    for name, data in files.items():
        if data is not None:
            (folder / name).write_bytes(data if isinstance(data, bytes) else str(data).encode("utf-8"))
    return folder / str(path) if path is not None else folder


def errors_of(sink: DiagnosticSink) -> list[str]:
    return sorted({d.code for d in sink if d.severity is Severity.ERROR})


_packages = iter(range(10**6))


def compiled_and_imported(files: dict[str, str], folder: Path) -> str:
    """Write the package, compile every module and import them all (their code runs: definitions,
    registrations); the generated GPL modules' text."""
    sink = DiagnosticSink()
    from gpl2py.transpile import Output

    out = Output("kept", dict(files))
    assert write_package(out, folder, sink), [d.header() for d in sink]
    texts = []
    for name, text in files.items():
        if name.endswith(".py"):
            compile(text, name, "exec", dont_inherit=True)
            texts.append(text)
    name = f"_kept_pkg_{next(_packages)}"
    try:
        import_package(folder / "kept", name)
        for sub in sorted((folder / "kept").glob("*.py")):
            if sub.stem not in ("__init__", "__main__"):
                importlib.import_module(f"{name}.{sub.stem}")
    finally:
        for mod in [m for m in sys.modules if m == name or m.startswith(name + ".")]:
            del sys.modules[mod]
    return "\n".join(texts)


def package_files(out: object) -> dict[str, str]:
    files = getattr(out, "files")
    package = getattr(out, "package")
    return {name.replace(f"{package}/", "kept/", 1): text for name, text in files.items()}


@pytest.mark.parametrize("code", sorted(CASES))
def test_an_error_ignored_or_kept_translates_to_code_that_raises_it(
        code: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("GPL2PY_TRACEBACK", "1")  # a bug is an exception here, never a GPL9000
    path = write_case(tmp_path, code)
    sink = DiagnosticSink()
    assert transpile(path, sink) is None
    found = errors_of(sink)
    assert code in found, [d.header() for d in sink]  # the case has the error it stands for
    # every error it has, ignored (--ignore): they stop nothing, and the translation raises them
    ignored = DiagnosticSink(Selection(None, tuple(found)))
    out = transpile(path, ignored)
    assert not ignored.has_errors() and errors_of(DiagnosticSink()) == []
    assert {d.code for d in ignored.ignored_errors} == set(found)
    if code in ("GPL1400", "GPL1401"):  # no project at all: nothing to translate
        assert out is None
    else:
        assert out is not None
        text = compiled_and_imported(package_files(out), tmp_path / "ignored")
        if code in M.RUNTIME_CODES and code not in NOT_ON_A_RUN_LINE:
            assert re.search(rf"compile_error\(\s*{M.RUNTIME_CODES[code]},", text), text
    # the same errors kept (--keep-going): the same diagnostics, code that compiles
    kept = DiagnosticSink()
    out = transpile(path, kept, keep_going=True)
    assert errors_of(kept) == found
    if out is not None:
        compiled_and_imported(package_files(out), tmp_path / "kept")


def test_every_error_code_has_a_case_and_a_run_time_decision() -> None:
    """A new error code needs a case above and a decision: the controller's error a line that
    keeps it raises (messages.RUNTIME_CODES), or why it is about no line of the program."""
    from gplrt.lang.error_codes import ERROR_MESSAGES

    # (the GPL front end's codes, GPL1000-GPL3999: the other front ends' are walked by their own
    # tests, tests/tm/test_diagnostics.py for TMscript's, tests/vplus/test_error_cases.py for V+'s;
    # docs/design/frontends.md, "Diagnostics")
    errors = {m.code for m in M.all_messages() if m.severity is Severity.ERROR and m.code < "GPL4000"}
    assert errors - set(CASES) == NOT_WALKED
    assert set(CASES) - errors == set()
    about_no_line = {c for c in errors if c.startswith("GPL14")} | {"GPL2019", "GPL2034", "GPL3004", "GPL3503"}
    assert errors - set(M.RUNTIME_CODES) == about_no_line
    assert set(M.RUNTIME_CODES) <= errors
    for runtime in {*M.RUNTIME_CODES.values(), M.COMPILATION_ERRORS}:  # the controller's own codes and texts
        assert ERROR_MESSAGES[runtime] == M.RUNTIME_TEXTS[runtime], runtime


# --------------------------------------------------------------------------------------------------
# Deep nesting in module-level initialisers


def report(tmp_path: Path, command: str, folder: Path) -> tuple[int, list[tuple[str, str, int]]]:
    """``gpl2py check --json`` or ``translate --json``: the exit status and (code, file, line) of
    every diagnostic."""
    argv = [command, "--json", str(folder)] + (["-o", str(tmp_path / "out")] if command == "translate" else [])
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        status = cli_main(argv)
    diags = json.loads(out.getvalue())["diagnostics"]
    return status, [(d["code"], Path(d["file"]).name if d["file"] else "", d["line"] or 0) for d in diags]


OTHER = "Module Other\n    Public Sub Work()\n        Dim s As String\n        s = undeclared\n    End Sub\nEnd Module\n"
DEEP = {
    "parentheses": "(" * 478 + "1" + ")" * 478,
    "calls": "a" + "(1)" * 500,
    "members": "a" + ".b" * 500,
}


@pytest.mark.parametrize("shape", sorted(DEEP))
@pytest.mark.parametrize("where", ["Public Const X As Integer = {}", "Public X As Integer = {}",
                                   "Public Class K\n        Public Shared Y As Integer = {}\n    End Class",
                                   "Sub P(Optional ByVal q As Integer = {})\n    End Sub"])
def test_deep_nesting_in_a_module_level_initialiser_is_reported_at_its_line(
        shape: str, where: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Once a RecursionError in the semantic pass: GPL9000 with no position, and "checked 0
    files" -- every other diagnostic of the project gone.  Inside a procedure the same was
    already GPL1117 / GPL3005."""
    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    folder = tmp_path / "P"
    folder.mkdir()
    main = f"Module Main\n    {where.format(DEEP[shape])}\n    Public Sub Main()\n    End Sub\nEnd Module\n"
    (folder / "Main.gpl").write_text(main)
    (folder / "Other.gpl").write_text(OTHER)
    checked = report(tmp_path, "check", folder)
    assert checked == report(tmp_path, "translate", folder)
    status, diags = checked
    assert status == 1 and "GPL9000" not in {c for c, _, _ in diags}, diags
    assert ("GPL2001", "Other.gpl", 4) in diags  # the other file's error is still reported
    deep = [(c, f, line) for c, f, line in diags if f == "Main.gpl"]
    assert deep and {c for c, _, _ in deep} <= {"GPL1117", "GPL3005", "GPL2001"}, diags
    line = next(i for i, text in enumerate(main.splitlines(), 1) if DEEP[shape] in text)
    assert {line for _, _, line in deep} == {line}  # at the initialiser's line
    assert {"GPL1117", "GPL3005"} & {c for c, _, _ in deep}


# --------------------------------------------------------------------------------------------------
# A GPL9000 stays in its file


BUG = "Module Bug\n    Public Sub Main()\n        Console.WriteLine(\"bug\")\n    End Sub\nEnd Module\n"
CLEAN = "Module Other\n    Public Sub Work()\n        Dim s As String\n        s = 5\n    End Sub\nEnd Module\n"


def _project(tmp_path: Path, other: str) -> Path:
    folder = tmp_path / "P"
    folder.mkdir()
    (folder / "Bug.gpl").write_text(BUG)
    (folder / "Other.gpl").write_text(other)
    (folder / "Project.gpr").write_text(gpr('ProjectSource="Bug.gpl"\nProjectSource="Other.gpl"\n', "Bug.Main"))
    return folder


def _planted(kind: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """A bug in gpl2py that only file Bug.gpl meets, in ``kind`` (parse, analysis, lowering)."""
    if kind == "parse":
        real_parse = pipeline_module.parse

        def parse(src, sink):  # type: ignore[no-untyped-def]
            if src.path.endswith("Bug.gpl"):
                raise ValueError("planted parser bug")
            return real_parse(src, sink)

        monkeypatch.setattr(pipeline_module, "parse", parse)
    elif kind == "analysis":
        real_module = check_module.Checker._module

        def _module(self, mod):  # type: ignore[no-untyped-def]
            if mod.name == "Bug":
                raise KeyError("planted analysis bug")
            return real_module(self, mod)

        monkeypatch.setattr(check_module.Checker, "_module", _module)
    else:
        real_lower = pipeline_module.lower_module

        def lower_module(model, names, mod, sink, **options):  # type: ignore[no-untyped-def]
            if mod.name == "Bug":
                raise IndexError("planted lowering bug")
            return real_lower(model, names, mod, sink, **options)

        monkeypatch.setattr(pipeline_module, "lower_module", lower_module)


@pytest.mark.parametrize("kind", ["parse", "analysis", "lowering"])
def test_an_internal_error_in_one_file_keeps_the_other_files_diagnostics(
        kind: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Once a GPL9000 anywhere ended the whole run: no position, the files after it never
    parsed, and ``check`` said "checked 0 files" with nothing else."""
    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    # the lowering runs only on a project without errors: the other file has a warning only
    other = CLEAN if kind == "lowering" else CLEAN + "x = \"\x93\"\n"  # (GPL2031 at s = 5)
    folder = _project(tmp_path, other)
    _planted(kind, monkeypatch)
    checked = report(tmp_path, "check", folder)
    assert checked == report(tmp_path, "translate", folder)
    status, diags = checked
    assert status == 2  # an internal error: gpl2py could not do its job
    found = [(c, f) for c, f, _ in diags]
    assert found.count(("GPL9000", "Bug.gpl")) == 1 and ("GPL9000", "Bug.gpl", 1) in diags  # at the file
    # every diagnostic of the other file, and no knock-on error (the start is in Bug.gpl)
    if kind == "lowering":
        assert found == [("GPL9000", "Bug.gpl"), ("GPL2031", "Other.gpl")]
    else:
        assert found == [("GPL9000", "Bug.gpl"), ("GPL2031", "Other.gpl"), ("GPL1109", "Other.gpl"),
                         ("GPL1004", "Other.gpl")]
    out = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(out):
        cli_main(["check", str(folder)])
    assert "checked 2 files" in out.getvalue()


# --------------------------------------------------------------------------------------------------
# The caller's stack depth


NEAR_THE_LIMIT = {
    "calls": "CInt(" * 149 + "1" + ")" * 149,
    "negations": "-" * 149 + "1",
    "members": "Console" + ".X" * 200,
    "subscripts": "a" + "(1)" * 200,
}


def _at_depth(frames: int, path: Path) -> list[tuple[str, int]]:
    if frames > 0:
        return _at_depth(frames - 1, path)
    sink = DiagnosticSink()
    transpile(path, sink)
    return sorted((d.code, d.span.line if d.span else 0) for d in sink)


@pytest.mark.parametrize("shape", sorted(NEAR_THE_LIMIT))
def test_a_translation_does_not_depend_on_how_deep_it_is_called(
        shape: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The analysis and the lowering recurse on expressions, under Python's recursion limit, which
    counts from the bottom of the stack: the same project gave nothing from ``translate``, GPL3005
    from ``check`` (one frame deeper: the pipeline fuzz found it) and an internal error GPL9000
    from a caller a few hundred frames deep.  The pipeline now has a budget of its own."""
    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    main = f"Module Main\n    Public Sub Main()\n        Dim i As Integer\n        i = {NEAR_THE_LIMIT[shape]}\n    End Sub\nEnd Module\n"
    (tmp_path / "Main.gpl").write_text(main)
    found = {frames: _at_depth(frames, tmp_path) for frames in (0, 150, 300, 600)}  # (under the limit of 1,000)
    assert all(codes == found[0] for codes in found.values()), found
    assert "GPL9000" not in {c for c, _ in found[0]}
