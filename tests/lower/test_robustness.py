"""Bad input never crashes the transpiler, and --keep-going output is still valid Python.

Mutated copies of the conformance programs (lines deleted, duplicated, cut short, words replaced
by tokens that break grammar or meaning) go through the whole pipeline: every run must end with
diagnostics (a mutation that happens to stay valid GPL may have none), never an exception or an
internal error (GPL9000), and whatever is written with ``keep_going`` must compile.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

import gpl2py.gpl.pipeline as pipeline_module
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.transpile import transpile
from gpltest import compiled_modules, main_body

REPO = Path(__file__).resolve().parents[2]
WORDS = ["x", "1", "(", ")", "As", "Integer", "Me", "Nothing", "New", "GoTo L", "L:", ".", "&",
         "Exit For", "Return", "s", "Location", '"a"', "Next", "End If", "Then", "", "ByRef", "Sub"]


def mutate(lines: list[str], rnd: random.Random) -> list[str]:
    src = list(lines)
    for _ in range(rnd.randint(1, 4)):
        i = rnd.randrange(len(src))
        op = rnd.random()
        if op < 0.3 and len(src) > 3:
            del src[i]
        elif op < 0.5:
            src.insert(i, src[rnd.randrange(len(src))])
        elif op < 0.8:
            words = src[i].split(" ")
            words[rnd.randrange(len(words))] = rnd.choice(WORDS)
            src[i] = " ".join(words)
        else:
            src[i] = src[i][: rnd.randrange(len(src[i]) + 1)]
    return src


def test_mutated_programs_give_diagnostics_not_crashes(tmp_path: Path) -> None:
    sources = sorted((REPO / "tests/conformance/differential").glob("*.gpl"))
    assert sources
    rnd = random.Random(20261121)
    rejected = compiled = 0
    for n in range(150):
        text = rnd.choice(sources).read_text(encoding="latin-1").split("\n")
        path = tmp_path / f"m{n}.gpl"
        path.write_text("\n".join(mutate(text, rnd)), encoding="latin-1")
        sink = DiagnosticSink()
        out = transpile(str(path), sink, keep_going=True)
        assert not [d for d in sink if d.code == "GPL9000"], (path.read_text(), [d.header() for d in sink])
        rejected += sink.has_errors()
        if out is not None:
            for name, code in out.files.items():
                if name.endswith(".py"):
                    compile(code, name, "exec")
                    compiled += 1
    # the loop proves something only if the mutations really are bad input (most of them are
    # rejected with diagnostics) and keep_going really wrote code that was compiled
    assert rejected >= 100 and compiled >= 300, (rejected, compiled)


def _project(tmp_path: Path) -> Path:
    path = tmp_path / "Ok.gpl"
    path.write_text("Module Ok\n    Public Sub Main()\n        Console.WriteLine(1)\n    End Sub\nEnd Module\n",
                    encoding="latin-1")
    return path


@pytest.mark.parametrize("phase", ["load_project", "parse", "analyze", "lower_module"])
def test_library_transpile_turns_a_bug_in_any_phase_into_gpl9000(
        phase: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """``transpile()`` is the library API (notebooks, the test harness): like the CLI it must never
    leak a traceback, whichever phase fails -- the semantic pass was once outside the guard."""
    def boom(*args: object, **kwargs: object) -> None:
        raise KeyError("simulated bug")

    monkeypatch.delenv("GPL2PY_TRACEBACK", raising=False)
    monkeypatch.setattr(pipeline_module, phase, boom)
    sink = DiagnosticSink()
    assert transpile(str(_project(tmp_path)), sink) is None
    assert [d.code for d in sink.errors] == ["GPL9000"]
    assert "KeyError: 'simulated bug'" in sink.errors[0].message


def test_library_transpile_reraises_with_gpl2py_traceback(tmp_path: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    def boom(*args: object, **kwargs: object) -> None:
        raise KeyError("simulated bug")

    monkeypatch.setenv("GPL2PY_TRACEBACK", "1")
    monkeypatch.setattr(pipeline_module, "analyze", boom)
    with pytest.raises(KeyError):
        transpile(str(_project(tmp_path)), DiagnosticSink())


def test_keep_going_output_with_a_case_after_case_else_compiles(tmp_path: Path) -> None:
    """Found by mutation: the parser reports a Case after Case Else and keeps it; the lowering
    must not emit an ``elif`` after ``else``."""
    path = tmp_path / "Sel.gpl"
    path.write_text("""Module Sel
    Public Sub Main()
        Dim s As String = "x"
        Select Case s
            Case "a"
                Console.WriteLine(1)
            Case Else
                Console.WriteLine(2)
            Case "b"
                Console.WriteLine(3)
        End Select
    End Sub
End Module
""")
    sink = DiagnosticSink()
    out = transpile(str(path), sink, keep_going=True)
    assert "GPL1100" in [d.code for d in sink.errors]
    assert out is not None
    body = main_body(compiled_modules(out.files)["sel/sel.py"])
    # the Case before Case Else and the Case Else itself are kept, the unreachable one is not
    assert 'Console.WriteLine(1)' in body and "else:\n        Console.WriteLine(2)" in body
    assert "Console.WriteLine(3)" not in body
