"""Issue 12, item 6: GPL nests deeper than CPython compiles (20 loop/try blocks in a function, 99
levels of indentation).  Whatever the nesting, ``translate`` never exits 0 with a module that does
not compile, ``--keep-going`` output compiles, and ``check`` reports what translate would
(GPL3007 at the statement that goes too deep).

For each construct the test finds the deepest nesting gpl2py accepts, compiles that translation,
and checks that one level more is GPL3007; the depths are the ones docs/security.md lists.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gpl2py.cli import main as cli_main
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.pywriter.emit import BLOCKS, MAX_BLOCKS, MAX_INDENT
from gpl2py.transpile import transpile

HEAD = ["Module Main", "Public Sub Main()", "Dim x As Integer", "Dim n As Integer = 3", "Dim e As Exception"]
TAIL = ["Console.WriteLine(CStr(x))", "End Sub", "End Module"]


def nest(kind: str, depth: int) -> str:
    """A module whose Main nests ``depth`` constructs of ``kind`` around ``x = x + 1``."""
    inner = ["x = x + 1"]
    if kind == "If":
        body = ["If x = 0 Then"] * depth + inner + ["End If"] * depth
    elif kind == "While":
        body = ["While x < 1"] * depth + inner + ["End While"] * depth
    elif kind == "Do":
        body = ["Do"] * depth + inner + ["Loop Until x > 0"] * depth
    elif kind in ("For literal", "For variable"):
        bound = "1" if kind == "For literal" else "n"
        body = ([f"Dim i{k} As Integer" for k in range(depth)] + [f"For i{k} = 1 To {bound}" for k in range(depth)]
                + inner + ["Next"] * depth)
    elif kind == "Select":
        body = ["Select Case x", "Case 0"] * depth + inner + ["End Select"] * depth
    elif kind == "Select with Exit":
        body = ["Select Case x", "Case 0", "If n = 0 Then Exit Select"] * depth + inner + ["End Select"] * depth
    elif kind == "Try in Try":
        body = ["Try"] * depth + inner + ["Catch e", "End Try"] * depth
    elif kind == "Try in Catch":
        body = ["Try", "x = 1", "Catch e"] * depth + inner + ["End Try"] * depth
    elif kind == "Try/Finally in Catch":
        body = ["Try", "x = 1", "Catch e"] * depth + inner + ["Finally", "x = 2", "End Try"] * depth
    elif kind == "Try with Exit Try":
        body = ["Try", "If n = 0 Then Exit Try"] * depth + inner + ["Catch e", "End Try"] * depth
    elif kind == "Class":
        return "\n".join(["Module Main"] + [f"Public Class C{k}" for k in range(depth)]
                         + ["Public v As Integer", "Public Sub M()", "v = 1", "End Sub"]
                         + ["End Class"] * depth + ["Public Sub Main()", "End Sub", "End Module"]) + "\n"
    elif kind == "If in a method of 50 classes":
        return "\n".join(["Module Main"] + [f"Public Class C{k}" for k in range(50)]
                         + ["Public v As Integer", "Public Sub M()"]
                         + ["If v = 0 Then"] * depth + ["v = 1"] + ["End If"] * depth + ["End Sub"]
                         + ["End Class"] * 50 + ["Public Sub Main()", "End Sub", "End Module"]) + "\n"
    else:
        raise ValueError(kind)
    return "\n".join(HEAD + body + TAIL) + "\n"


# the deepest nesting that translates (docs/security.md, "Nesting")
DEEPEST = {
    "If": 98, "While": 20, "Do": 20, "For literal": 20, "For variable": 20, "Select": 98,
    "Select with Exit": 20, "Try in Try": 19, "Try in Catch": 10, "Try/Finally in Catch": 6,
    "Try with Exit Try": 19, "Class": 98, "If in a method of 50 classes": 48,
}


def translate(tmp_path: Path, text: str, keep_going: bool = False) -> tuple[dict[str, str] | None, DiagnosticSink]:
    src = tmp_path / "Main.gpl"
    src.write_text(text)
    sink = DiagnosticSink()
    out = transpile(src, sink, keep_going=keep_going)
    return (out.files if out is not None else None), sink


def compiles(files: dict[str, str]) -> None:
    for name, text in files.items():
        if name.endswith(".py"):
            compile(text, name, "exec")  # raises SyntaxError for "too many statically nested blocks"


def accepted(tmp_path: Path, kind: str, depth: int) -> bool:
    files, sink = translate(tmp_path, nest(kind, depth))
    if files is None:
        # Python's limit (GPL3007, at each statement that does not fit), or beyond 100 blocks
        # the parser's (GPL1117)
        codes = {d.code for d in sink.errors}
        assert codes in ({"GPL3007"}, {"GPL1117"}), [d.header() for d in sink]
        return False
    compiles(files)
    return True


@pytest.mark.parametrize("kind", sorted(DEEPEST))
def test_the_deepest_nesting_that_translates_compiles_and_one_more_is_gpl3007(tmp_path: Path, kind: str) -> None:
    lo, hi = 1, 101  # accepted(lo); not accepted(hi)
    assert accepted(tmp_path, kind, lo)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if accepted(tmp_path, kind, mid):
            lo = mid
        else:
            hi = mid
    assert lo == DEEPEST[kind]
    files, sink = translate(tmp_path, nest(kind, lo + 1), keep_going=True)
    assert files is not None
    compiles(files)  # --keep-going output is Python too
    assert sink.errors and {d.code for d in sink.errors} == {"GPL3007"}, [d.header() for d in sink]
    assert all(d.span is not None and d.span.file.endswith("Main.gpl") for d in sink.errors)


def test_the_innermost_statement_that_does_not_fit_is_reported(tmp_path: Path) -> None:
    # 21 Whiles: the 21st is the one whose body Python cannot hold
    _, sink = translate(tmp_path, nest("While", 21))
    assert [(d.code, d.span.line, d.span.col) for d in sink.errors] == [("GPL3007", len(HEAD) + 21, 1)]
    assert "inside 21 loop and Try blocks" in sink.errors[0].message
    _, sink = translate(tmp_path, nest("If", 99))
    assert [(d.code, d.span.line) for d in sink.errors] == [("GPL3007", len(HEAD) + 99)]
    assert "indented 100 levels" in sink.errors[0].message


def test_check_reports_what_translate_would(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # 20 nested Try, 21 nested For or 99 nested If passed check, then translate wrote a broken module
    for kind, depth in (("Try in Try", 20), ("For literal", 21), ("If", 99)):
        (tmp_path / "Main.gpl").write_text(nest(kind, depth))
        assert cli_main(["check", str(tmp_path / "Main.gpl")]) == 1
        err = capsys.readouterr().err
        assert "Main.gpl:" in err and "error GPL3007" in err
        assert cli_main(["translate", str(tmp_path / "Main.gpl"), "-o", str(tmp_path / "out")]) == 1
        capsys.readouterr()
        assert not list((tmp_path / "out").rglob("*.py"))


def _nested_source(headers: list[str], depth: int) -> str:
    lines = []
    for k in range(depth):
        lines.append("    " * k + headers[k % len(headers)])
    return "\n".join(lines) + "\n" + "    " * depth + "pass\n"


def test_the_limits_are_cpythons() -> None:
    # emit.MAX_INDENT / MAX_BLOCKS / BLOCKS are what the running interpreter compiles
    compile(_nested_source(["if x:"], MAX_INDENT), "x", "exec")
    with pytest.raises(SyntaxError, match="indentation"):
        compile(_nested_source(["if x:"], MAX_INDENT + 1), "x", "exec")
    compile("def f():\n" + "".join("    " * (k + 1) + "while x:\n" for k in range(MAX_BLOCKS))
            + "    " * (MAX_BLOCKS + 1) + "pass\n", "x", "exec")
    with pytest.raises(SyntaxError, match="statically nested blocks"):
        compile(_nested_source(["while x:"], MAX_BLOCKS + 1), "x", "exec")

    def handlers(n: int, finally_: bool) -> str:
        text = ""
        for k in range(n):
            pad = "    " * k
            text += f"{pad}try:\n{pad}    pass\n{pad}except BaseException as _e:\n"
        text += "    " * n + "pass\n"
        if finally_:  # the innermost try also has a finally: its handler counts one more
            text = text.replace("except BaseException as _e:\n" + "    " * n + "pass\n",
                                "except BaseException as _e:\n" + "    " * n + "pass\n"
                                + "    " * (n - 1) + "finally:\n" + "    " * n + "pass\n")
        return text

    deepest = MAX_BLOCKS // BLOCKS["except"]
    compile(handlers(deepest, False), "x", "exec")
    with pytest.raises(SyntaxError, match="statically nested blocks"):
        compile(handlers(deepest + 1, False), "x", "exec")
    # n handlers, the innermost inside a finally: 2 (n - 1) + 3 blocks
    n = (MAX_BLOCKS - BLOCKS["except+finally"]) // BLOCKS["except"] + 1
    compile(handlers(n, True), "x", "exec")
    with pytest.raises(SyntaxError, match="statically nested blocks"):
        compile(handlers(n + 1, True), "x", "exec")
