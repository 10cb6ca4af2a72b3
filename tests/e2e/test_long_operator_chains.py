"""5,000-operand operator chains: transpiled by the ``gpl2py`` command, imported and run.

Generated GPL and long lookup tables continue one expression over thousands of lines.  CPython's
compiler cannot take such a chain as one nested expression (it gave RecursionError or "too many
nested parentheses" at import); the lowering cuts it into steps of at most ``LONG_CHAIN`` operators
(``ExprLowerer.chunked``).  These tests check what a user sees: the project translates without a
diagnostic, the module imports, and each chain gives the value of GPL's left-to-right evaluation
(computed here independently with a Python left fold), raises the controller's error codes where
the nested form would, and keeps short-circuits and evaluation order observable through calls.
"""

from __future__ import annotations

import importlib
import io
import operator
import random
import re
import sys
import tokenize
from collections.abc import Callable
from functools import reduce
from pathlib import Path
from types import ModuleType

import pycodestyle
import pytest

from gpl2py.gpl.lower.expressions import LONG_CHAIN
from gpltest import Transpiled, transpile, write_project
from gplrt.sim import Simulation

N = 5000
_rng = random.Random(20261121)
CONT = " _\n            "  # a GPL line continuation and the indentation of the next operand


def _chain(ops: list[str], operands: list[str]) -> str:
    """``operands[0] ops[0] operands[1] ...`` with one operand per source line."""
    assert len(ops) == len(operands) - 1
    parts = [operands[0]] + [f" {op}{CONT}{x}" for op, x in zip(ops, operands[1:])]
    return "".join(parts)


# --- the chains and what Python says they are ---------------------------------------------------

# Integer +: the variable i (= 3) and literals
INT_OPERANDS = ["i" if k % 4 == 0 else str(_rng.randint(0, 999)) for k in range(N)]
INT_SUM = sum(3 if x == "i" else int(x) for x in INT_OPERANDS)

# Integer + and -: "big" (2147483000) added twice in the middle, so the running value leaves the
# Integer range there; GPL evaluates in Double, so only the stored result must fit
BACK_OPS = ["+"] * (N - 1)
BACK_OPERANDS = ["1"] * N
BACK_OPERANDS[2000] = BACK_OPERANDS[2001] = "big"
BACK_OPERANDS[3000] = BACK_OPERANDS[3001] = "big"
BACK_OPS[2999] = BACK_OPS[3000] = "-"
BACK_VALUE = N - 4  # the four bigs cancel, the four 1s they replaced are gone


def _double_literal() -> str:
    return repr(_rng.uniform(0.5, 9.5) * 10.0 ** _rng.randint(-8, 8))


# Double + and -: magnitudes from 1e-8 to 1e9, so the order of the additions shows in the bits
DSUM_OPS = [_rng.choice("+-") for _ in range(N - 1)]
DSUM_OPERANDS = ["d" if k % 7 == 3 else _double_literal() for k in range(N)]
# Double * and /: factors near 1
DPROD_OPS = [_rng.choice("*/") for _ in range(N - 1)]
DPROD_OPERANDS = [repr(1.0 + _rng.uniform(-1e-3, 1e-3)) for _ in range(N)]

# String +
STR_OPERANDS = ["s" if k % 5 == 0 else f'"{k}."' for k in range(N)]
STR_VALUE = "".join("ab" if x == "s" else x.strip('"') for x in STR_OPERANDS)

# Integer And / Xor: 32-bit values, negative ones included
AND_VALUES = [~(1 << _rng.randint(0, 30)) if k % 50 else -1 for k in range(N)]
XOR_VALUES = [_rng.randint(-(2**31), 2**31 - 1) for _ in range(N)]

# the module that runs them; a Boolean-returning Tick(k, result) records calls and their order
PROJECT = f"""Module Chains
    Public dsum As Double
    Public dprod As Double
    Dim calls As Integer
    Dim nextk As Integer
    Dim inorder As Boolean

    Function Tick(ByVal k As Integer, ByVal result As Boolean) As Boolean
        If k <> nextk Then
            inorder = False
        End If
        nextk = k + 1
        calls = calls + 1
        Return result
    End Function

    Function Num(ByVal k As Integer, ByVal v As Integer) As Integer
        Tick(k, True)
        Return v
    End Function

    Function One(ByVal k As Integer) As Double
        Tick(k, True)
        Return 1.5
    End Function

    Sub Reset()
        calls = 0
        nextk = 0
        inorder = True
    End Sub

    Function Word(ByVal b As Boolean) As String
        If b Then
            Return "true"
        End If
        Return "false"
    End Function

    Sub Report(ByVal what As String)
        Console.WriteLine(what & " calls " & CStr(calls) & " in order " & Word(inorder))
    End Sub

    Function Readable(ByVal i As Integer) As Integer
        Return {_chain(["+"] * LONG_CHAIN, ["i"] * (LONG_CHAIN + 1))}
    End Function

    Function Stepped(ByVal i As Integer) As Integer
        Return {_chain(["+"] * (LONG_CHAIN + 1), ["i"] * (LONG_CHAIN + 2))}
    End Function

    Public Sub Main()
        Dim i, n, big, m As Integer
        Dim d, z As Double
        Dim s, t As String
        Dim b As Boolean
        i = 3
        d = 0.1
        s = "ab"
        big = 2147483000
        n = {_chain(["+"] * (N - 1), INT_OPERANDS)}
        Console.WriteLine("int " & CStr(n))
        n = {_chain(BACK_OPS, BACK_OPERANDS)}
        Console.WriteLine("back in range " & CStr(n))
        n = 7
        Try
            n = {_chain(["+"] * (N - 1), ["big" if k in (2500, 2501) else "1" for k in range(N)])}
            Console.WriteLine("no overflow " & CStr(n))
        Catch ex As Exception
            Console.WriteLine("overflow " & CStr(ex.ErrorCode) & " n still " & CStr(n))
        End Try
        dsum = {_chain(DSUM_OPS, DSUM_OPERANDS)}
        dprod = {_chain(DPROD_OPS, DPROD_OPERANDS)}
        t = {_chain(["+"] * (N - 1), STR_OPERANDS)}
        Console.WriteLine("string " & t)
        Reset()
        m = {_chain(["And"] * (N - 1), [f"Num({k}, {v})" for k, v in enumerate(AND_VALUES)])}
        Console.WriteLine("and = " & CStr(m))
        Report("and")
        m = {_chain(["Xor"] * (N - 1), [str(v) for v in XOR_VALUES])}
        Console.WriteLine("xor = " & CStr(m))
        Reset()
        b = {_chain(["Or"] * (N - 1), [f"Tick({k}, {k == 1234})" for k in range(N)])}
        Console.WriteLine("or = " & Word(b))
        Report("or")
        Reset()
        b = {_chain(["AndAlso"] * (N - 1), [f"Tick({k}, {k != 2999})" for k in range(N)])}
        Console.WriteLine("andalso = " & Word(b))
        Report("andalso")
        Reset()
        b = {_chain(["OrElse"] * (N - 1), [f"Tick({k}, {k == 3210})" for k in range(N)])}
        Console.WriteLine("orelse = " & Word(b))
        Report("orelse")
        Reset()
        z = 0
        Try
            d = {_chain(["/"] * (N - 1), ["z" if k == 2500 else f"One({k})" for k in range(N)])}
            Console.WriteLine("no division error")
        Catch ex As Exception
            Console.WriteLine("division = " & CStr(ex.ErrorCode))
        End Try
        Report("division")
        Console.WriteLine(Readable(1) + Stepped(1))
    End Sub
End Module
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Transpiled:
    root = tmp_path_factory.mktemp("chains")
    project = write_project(root, {"Chains.gpl": PROJECT})
    return transpile(Path(project), root / "out")


@pytest.fixture(scope="module")
def ran(built: Transpiled) -> tuple[list[str], ModuleType]:
    """The console lines of one run of Main, and the generated module (its globals hold the
    Double results, read back bit for bit)."""
    sim = Simulation(capture=True)
    built.package.main(sim)
    assert sim.console.log_text == ""
    module = importlib.import_module(f"{built.package.__name__}.chains")
    return sim.console.output.splitlines(), module


def _line(ran: tuple[list[str], ModuleType], head: str) -> str:
    lines = [ln for ln in ran[0] if ln.startswith(head + " ")]
    assert len(lines) == 1, ran[0]
    return lines[0][len(head) + 1:]


def _generated(built: Transpiled) -> str:
    return (built.folder / "chains.py").read_text()


def test_the_project_transpiles_without_a_diagnostic(built: Transpiled) -> None:
    built.assert_clean()


def test_integer_sum(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "int") == str(INT_SUM)


def test_a_sum_may_leave_the_integer_range_on_the_way(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "back in range") == str(BACK_VALUE)


def test_integer_overflow_in_the_middle_is_caught_with_the_controllers_code(
        ran: tuple[list[str], ModuleType]) -> None:
    # two bigs exceed 2**31 - 1: -710 Arithmetic overflow, and the target keeps its old value
    assert _line(ran, "overflow") == "-710 n still 7"


def _left_fold(ops: list[str], values: list[float]) -> float:
    step: dict[str, Callable[[float, float], float]] = {
        "+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv}
    acc = values[0]
    for op, x in zip(ops, values[1:]):
        acc = step[op](acc, x)
    return acc


def test_double_sum_is_bit_for_bit_the_left_fold(ran: tuple[list[str], ModuleType]) -> None:
    values = [0.1 if x == "d" else float(x) for x in DSUM_OPERANDS]
    expected = _left_fold(DSUM_OPS, values)
    assert ran[1].dsum.hex() == expected.hex()
    # the check has teeth: summing in another order gives other bits
    assert sum(sorted(v if op == "+" else -v for op, v in zip(["+", *DSUM_OPS], values))) != expected


def test_double_product_and_quotient_is_bit_for_bit_the_left_fold(ran: tuple[list[str], ModuleType]) -> None:
    expected = _left_fold(DPROD_OPS, [float(x) for x in DPROD_OPERANDS])
    assert ran[1].dprod.hex() == expected.hex()


def test_string_plus_concatenates(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "string") == STR_VALUE


def test_integer_and_evaluates_every_operand_in_order(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "and =") == str(reduce(operator.and_, AND_VALUES))
    assert _line(ran, "and calls") == f"{N} in order true"


def test_integer_xor(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "xor =") == str(reduce(operator.xor, XOR_VALUES))


def test_boolean_or_does_not_short_circuit(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "or =") == "true"
    assert _line(ran, "or calls") == f"{N} in order true"


def test_andalso_stops_at_the_first_false(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "andalso =") == "false"
    assert _line(ran, "andalso calls") == "3000 in order true"


def test_orelse_stops_at_the_first_true(ran: tuple[list[str], ModuleType]) -> None:
    assert _line(ran, "orelse =") == "true"
    assert _line(ran, "orelse calls") == "3211 in order true"


def test_a_failing_operator_stops_the_chain_before_later_operands(ran: tuple[list[str], ModuleType]) -> None:
    """``... / z / One(2501) ...`` with z = 0: -709 is raised at the division, before the next
    operand's function runs (as in the nested form: operands and operators interleave)."""
    assert _line(ran, "division =") == "-709"
    assert _line(ran, "division calls") == "2500 in order true"


def test_short_chains_stay_nested_and_long_ones_are_stepped(built: Transpiled,
                                                            ran: tuple[list[str], ModuleType]) -> None:
    code = _generated(built)
    readable = code.split("def Readable(", 1)[1].split("\ndef ", 1)[0]
    stepped = code.split("def Stepped(", 1)[1].split("\ndef ", 1)[0]
    # (the Integer store's inline range check names its value with ':=', a step would be _chainN)
    assert "_chain" not in readable and readable.count("i + i") >= 1
    assert stepped.count("_chain1 :=") == 1 and "_chain1 + i" in stepped
    assert ran[0][-1] == str(2 * LONG_CHAIN + 3)
    # each of Main's ten long non-short-circuit chains takes at least 49 steps
    main = code.split("def Main(", 1)[1].split("\ndef ", 1)[0]
    steps = re.findall(r"^ *_chain\d+ := ", main, re.MULTILINE)
    assert len(steps) >= 10 * ((N - 2) // LONG_CHAIN)
    # a helper call is a step of its own
    assert re.search(r"^ *(_chain\d+) := div\(\1, One\(2501\)\),$", main, re.MULTILINE)


def test_no_expression_nests_deeply(built: Transpiled) -> None:
    """The bracket depth of the generated module stays small (the tokenizer's limit is 200): the
    helper calls of a long ``/`` chain are steps, not ``div(div(div(...)))``."""
    depth = deepest = 0
    for tok in tokenize.generate_tokens(io.StringIO(_generated(built)).readline):
        if tok.type == tokenize.OP and tok.string in "([{":
            depth += 1
            deepest = max(deepest, depth)
        elif tok.type == tokenize.OP and tok.string in ")]}":
            depth -= 1
    assert deepest <= 6


def test_generated_module_is_pep8(built: Transpiled) -> None:
    style = pycodestyle.StyleGuide(max_line_length=99, quiet=True)
    assert style.check_files([str(built.folder / "chains.py")]).total_errors == 0


def test_generated_module_compiles_deep_in_a_call_stack(built: Transpiled) -> None:
    """CPython's compiler depth budget shrinks with the caller's stack (about 3 per frame left):
    the stepped chains still compile with only 150 frames to spare."""
    code = _generated(built)

    def frames() -> int:
        f, n = sys._getframe(), 0
        while f is not None:
            f, n = f.f_back, n + 1
        return n

    def compile_at(depth: int) -> object:
        return compile_at(depth - 1) if depth > 0 else compile(code, "chains.py", "exec")

    assert compile_at(sys.getrecursionlimit() - 150 - frames()) is not None
