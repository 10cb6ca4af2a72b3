"""The stepped form of long operator chains (ExprLowerer.binary_chain / chunked) on the shapes
that make it tricky: signs after ``-``, comparisons (Python would chain ``a == b == c``), a
short-circuit operator after a wrapping one, a long chain inside an operand of another, and the
Double overflow check of a long product.  Each program's output is compared with a Python left
fold of the same operands; the generated module must be PEP 8 clean."""

from __future__ import annotations

import random
import re
from pathlib import Path

import pycodestyle

from gpl2py.gpl.lower.expressions import LONG_CHAIN
from gpl2py.pywriter.wrap import wrap
from gpltest import RunResult, module_src, run_gpl

M = 3 * LONG_CHAIN + 7  # operators per chain: three full steps and a partial one
CONT = " _\n            "


def _run(tmp_path: Path, decls: str, body: str) -> RunResult:
    result = run_gpl(tmp_path, module_src(f"{decls}\n    Public Sub Main()\n{body}\n    End Sub"))
    code = next(k for k in result.files if k.endswith("main_mod.py"))
    path = tmp_path / "main_mod.py"
    path.write_text(result.files[code])
    assert pycodestyle.StyleGuide(max_line_length=99, quiet=True).check_files([str(path)]).total_errors == 0
    return result


def test_subtraction_of_negative_literals(tmp_path: Path) -> None:
    rng = random.Random(1)
    values = [rng.randint(-50, 50) for _ in range(M + 1)]
    chain = f" -{CONT}".join(str(v) if k else "i" for k, v in enumerate(values))
    result = _run(tmp_path, "", f"""        Dim i, n As Integer
        i = {values[0]}
        n = {chain}
        Console.WriteLine(n)""")
    assert result.output == f"{values[0] - sum(values[1:])}\n"
    assert "_chain1 := " in result.files[next(k for k in result.files if k.endswith("main_mod.py"))]


def test_equality_chain_compares_left_to_right(tmp_path: Path) -> None:
    """``a = b = c`` in GPL is ``(a = b) = c``; Python's ``a == b == c`` would mean something else."""
    flags = [k % 3 != 0 for k in range(M + 1)]
    chain = f" ={CONT}".join(str(f) for f in flags)
    result = _run(tmp_path, "", f"""        Dim b As Boolean
        b = {chain}
        If b Then
            Console.WriteLine("true")
        Else
            Console.WriteLine("false")
        End If""")
    acc = flags[0]
    for f in flags[1:]:
        acc = acc == f
    assert result.output == f"{str(acc).lower()}\n"


def test_andalso_after_and_keeps_short_circuit(tmp_path: Path) -> None:
    """``And`` (all operands) and ``AndAlso`` (stops at False) at one precedence level, mixed."""
    ops = ["And" if k % 2 else "AndAlso" for k in range(M)]
    results = [k != 250 for k in range(M + 1)]
    chain = "T(0, True)" + "".join(f" {op}{CONT}T({k + 1}, {results[k + 1]})" for k, op in enumerate(ops))
    result = _run(tmp_path, """    Dim calls As Integer
    Function T(ByVal k As Integer, ByVal r As Boolean) As Boolean
        calls = calls + 1
        Return r
    End Function""", f"""        Dim b As Boolean
        b = {chain}
        Console.WriteLine(calls)""")
    calls, acc = 1, True
    for k, op in enumerate(ops):
        if op == "AndAlso" and not acc:
            continue
        calls += 1
        acc = acc and results[k + 1]
    assert result.output == f"{calls}\n"


def test_a_long_chain_inside_an_operand_of_another(tmp_path: Path) -> None:
    inner = " + ".join(["i"] * (LONG_CHAIN + 5))
    chain = f" +{CONT}".join(f"F({inner})" if k % 100 == 50 else "i" for k in range(M + 1))
    result = _run(tmp_path, """    Function F(ByVal x As Integer) As Integer
        Return x * 2
    End Function""", f"""        Dim i, n As Integer
        i = 1
        n = {chain}
        Console.WriteLine(n)""")
    nested = sum(1 for k in range(M + 1) if k % 100 == 50)
    assert result.output == f"{(M + 1 - nested) + nested * 2 * (LONG_CHAIN + 5)}\n"


def test_integer_division_by_a_literal_steps(tmp_path: Path) -> None:
    chain = f" \\{CONT}".join(["n"] + ["1"] * M)
    result = _run(tmp_path, "", f"""        Dim n, m As Integer
        n = -7
        m = {chain} \\ 2
        Console.WriteLine(m)""")
    assert result.output == "-3\n"  # truncation toward zero, once per operator


def test_a_long_double_product_keeps_its_overflow_check(tmp_path: Path) -> None:
    chain = f" *{CONT}".join(["d"] * (M + 1))
    result = _run(tmp_path, "", f"""        Dim d, x As Double
        d = 1e3
        Try
            x = {chain}
            Console.WriteLine("no error")
        Catch ex As Exception
            Console.WriteLine(ex.ErrorCode)
        End Try""")
    assert result.output == "-710\n"


def test_wrap_never_breaks_a_step_at_a_sign() -> None:
    step = "_chain1 := _chain1" + "".join(f" - -{k} - {k} * -3" for k in range(15))
    text = "x = (" + ", ".join([step] * 4) + ", _chain1 - 1)[-1]"
    lines = wrap(0, text)
    assert len(lines) > 6 and all(4 * ind + len(t) <= 99 for ind, t in lines)
    compile("\n".join("    " * ind + t for ind, t in lines), "wrapped", "exec")
    body = [t for _, t in lines[1:-1]]
    # one step a line, continued before a binary minus; a cut before a sign would start "-3"
    assert sum(t.startswith("_chain1 := ") for t in body) == 4 and body[-1] == "_chain1 - 1"
    assert all(t.startswith(("_chain1", "- ")) for t in body), body
    assert not any(re.match(r"-\d", t) for t in body)
