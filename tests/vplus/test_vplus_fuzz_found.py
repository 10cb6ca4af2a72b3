"""What the V+ pipeline fuzz (tests/vplus/test_vplus_fuzz.py) found, one focused case each: bad or
extreme input that gave a traceback, an internal error, a hang or a package that does not import,
and now gets a clear answer."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.run import import_package
from gpl2py.transpile import transpile, write_package


def _translate(tmp_path: Path, body: str, name: str = "m.v2") -> tuple[object, list[str]]:
    src = tmp_path / name
    src.write_text(body)
    sink = DiagnosticSink()
    out = transpile(src, sink)
    assert not any(d.code == "GPL9000" for d in sink), [d.header() for d in sink]
    return out, [d.header() for d in sink]


def _program(line: str) -> str:
    return f".PROGRAM m()\n  x = 0\n  {line}\n  TYPE x\n.END\n"


def test_a_long_sum_is_checked_in_time_proportional_to_its_length(tmp_path: Path) -> None:
    """The checker walked each operand of a binary operator twice, so a chain of n operators cost
    2**n: a 40-term sum took minutes (the fuzz's hang).  CPU time bounded generously (seconds
    where it was 2**40 steps), not a timing of the machine."""
    started = time.process_time()
    out, diags = _translate(tmp_path, _program("x = " + " + ".join(["x"] * 60)))
    assert out is not None and diags == []
    assert time.process_time() - started < 30


@pytest.mark.parametrize("expr", [
    " + ".join(["1"] * 1000),  # a chain: RecursionError in the checks and the lowering
    "ABS(" * 100 + "1" + ")" * 100,  # nested calls: RecursionError in the parser
    "a[" * 100 + "1" + "]" * 100,  # nested indices
])
def test_expressions_past_the_limits_are_gpl4111_not_a_traceback(tmp_path: Path, expr: str) -> None:
    out, diags = _translate(tmp_path, _program(f"x = {expr}"))
    assert out is None
    assert len(diags) == 1 and ":3:" in diags[0] and "error GPL4111: expression nested too deeply" in diags[0], diags


def test_expressions_just_inside_the_limits_translate_at_the_deepest_block(tmp_path: Path) -> None:
    body = ".PROGRAM m()\n  x = 1\n" + "IF x THEN\n" * 50 + "x = " + "ABS(1+" * 39 + "+".join(["1"] * 80) \
        + ")" * 39 + "\n" + "END\n" * 50 + "TYPE x\n.END\n"
    out, diags = _translate(tmp_path, body)
    assert out is not None and diags == []
    for name, text in out.files.items():  # type: ignore[attr-defined]
        if name.endswith(".py"):
            compile(text, name, "exec")


@pytest.mark.parametrize("head, tail", [("IF x THEN", "END"), ("DO", "UNTIL TRUE"), ("WHILE x DO", "END"),
                                        ("FOR i = 1 TO 2", "END"), ("CASE x OF\nVALUE 1:", "END")])
def test_blocks_nested_past_fifty_are_one_error_and_the_next_program_is_read(tmp_path: Path, head: str,
                                                                           tail: str) -> None:
    """200 nested blocks were a RecursionError in the parser: now one GPL4113 at the 51st block's
    line, the rest of the program skipped to its .END, and the next program still checked."""
    lines = [".PROGRAM m()", "  x = 0"] + [head] * 200 + ["TYPE 1"] + [tail] * 200 + [".END",
                                                                                   ".PROGRAM q()", "  FROB 3", ".END"]
    text = "\n".join(lines) + "\n"
    out, diags = _translate(tmp_path, text)
    assert out is None
    deep = [d for d in diags if "GPL4113" in d]
    assert len(deep) == 1 and "blocks nested more than 50 deep" in deep[0], diags
    heads_before = 2 + 51 * (head.count("\n") + 1)
    assert f":{heads_before - head.count(chr(10))}:" in deep[0], deep
    assert any("error GPL4101" in d and f":{text.splitlines().index('  FROB 3') + 1}:3:" in d for d in diags), diags  # q's FROB 3
    assert len(diags) == 2, diags


@pytest.mark.parametrize("stem", ["__main__", "__init__", "current", "1st"])
def test_a_file_named_like_the_package_s_own_names_gets_a_module_of_its_own(tmp_path: Path, stem: str) -> None:
    """``__main__.pg`` became the module ``__main__`` and overwrote the package's ``__main__.py``
    (and ``__init__.v2`` its ``__init__.py``; ``current.v2`` hid the function ``init()`` calls;
    ``1st.v2`` was ``from . import 1st``): each file now has a module of its own and the package
    imports and runs."""
    src = tmp_path / "p"
    src.mkdir()
    (src / f"{stem}.v2").write_text('.PROGRAM hello()\n  TYPE "hi"\n.END\n')
    sink = DiagnosticSink()
    out = transpile(src, sink)
    assert out is not None, [d.header() for d in sink]
    assert write_package(out, tmp_path / "out", sink)
    pkg = import_package(tmp_path / "out" / out.package, f"_fuzz_found_{stem.strip('_')}")
    assert pkg.PROJECT["start"] == "hello"
    assert len(pkg.PROJECT["modules"]) == 1 and pkg.PROJECT["modules"][0] not in ("__main__", "__init__", "current")
    assert (tmp_path / "out" / out.package / "__main__.py").read_text().startswith('"""``python -m')


def test_a_dot_and_a_letter_of_another_alphabet_starting_a_line_is_an_error_not_an_assertion(tmp_path: Path) -> None:
    """``.é`` at the start of a line: the lexer took it for a directive (``isalpha`` is true of
    ``é``) and failed its own assertion that a V+ name follows."""
    out, diags = _translate(tmp_path, ".PROGRAM m()\n.\u00e9t\u00e9\n.END\n")
    assert out is None and diags and all(":2:" in d for d in diags), diags


def test_a_digit_of_another_script_is_an_error_not_an_assertion(tmp_path: Path) -> None:
    """``x = ²`` (or an Arabic-Indic digit): ``isdigit`` is true of it, and the lexer failed its
    own assertion that a V+ number follows."""
    out, diags = _translate(tmp_path, ".PROGRAM m()\n  x = \u00b2\n  y = \u0663\n.END\n")
    assert out is None and diags and all(":2:" in d or ":3:" in d for d in diags), diags
