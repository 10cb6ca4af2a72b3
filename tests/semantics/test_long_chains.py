"""Long continued operator chains (``s = s & "..." & _`` over hundreds of lines).

The parser gives a left-leaning tree as deep as the chain; the type check and lowering walk its
left spine in a loop, and a very long ``&`` run is emitted flat so CPython's own compiler takes it.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.check import Model
from gpl2py.gpl.semantics.info import ChainInfo
from gpl2py.gpl.syntax import ast as A
from gpltest import analyze_text, module_src, run_gpl


def _operand(k: int) -> str:
    """Operand k of the test chains: a String literal, an Integer variable or an Integer literal."""
    return f'"a{k}"' if k % 3 == 0 else ("i" if k % 3 == 1 else str(k))


def _expected_output(n: int) -> str:
    """What the program of :func:`_concat_program` prints, computed independently in Python."""
    s = "".join(f"a{k}" if k % 3 == 0 else "7" if k % 3 == 1 else str(k) for k in range(n))
    return f"{len(s)}\n{s[:12]}|{s[-12:]}\n"


def _concat_program(n: int, operand: Callable[[int], str] = _operand) -> str:
    chain = " & _\n            ".join(operand(k) for k in range(n))
    return module_src(f"""    Public Sub Main()
        Dim s As String
        Dim i As Integer
        i = 7
        s = {chain}
        Console.WriteLine(Len(s))
        Console.WriteLine(Mid(s, 1, 12) & "|" & Mid(s, Len(s) - 11))
    End Sub""")


def _assigned_expr(text: str, tmp_path: Path) -> tuple[A.Expr, Model, list[str]]:
    """The value of the first binary assignment in Sub Main, the model, and every diagnostic."""
    model, sink = analyze_text(tmp_path, text)
    main = next(d for d in model.proc_of_decl if getattr(d, "name", "") == "Main")
    assign = next(s for s in main.body.statements if isinstance(s, A.Assign) and isinstance(s.value, (A.Binary, A.Chain)))
    return assign.value, model, [d.header() for d in sink.sorted()]


def test_type_check_of_a_1500_operand_concatenation_has_no_depth_limit(tmp_path: Path) -> None:
    value, model, diags = _assigned_expr(_concat_program(1500), tmp_path)
    assert diags == []
    assert model.type_of(value) is t.STRING
    # every operator of the chain is typed, down to the first one (a run of CHAIN_MIN operators
    # or more is one Chain node, the type of each of its prefixes a byte of its record)
    assert isinstance(value, A.Chain) and len(value.ops) == 1499
    info = model.info[value]
    assert isinstance(info, ChainInfo)
    assert [info.prefix_type(k) for k in range(1499)] == [t.STRING] * 1499


def test_an_error_deep_in_a_long_chain_is_reported_at_its_line(tmp_path: Path) -> None:
    def operand(k: int) -> str:
        return "undeclared_x" if k == 1000 else _operand(k)

    _, _, diags = _assigned_expr(_concat_program(1500, operand), tmp_path)
    # operand 0 is on line 6 of the module, one operand per line
    assert len(diags) == 1, diags
    assert ":1006:13:" in diags[0] and "GPL3005" not in diags[0] and "undeclared_x" in diags[0], diags


def test_integer_chain_is_typed_integer_all_the_way(tmp_path: Path) -> None:
    chain = " + _\n            ".join("i" if k % 2 else "1" for k in range(1500))
    value, model, diags = _assigned_expr(module_src(f"""    Public Sub Main()
        Dim i, n As Integer
        n = {chain}
    End Sub"""), tmp_path)
    assert diags == []
    assert model.type_of(value) is t.INTEGER


def test_a_1500_operand_concatenation_transpiles_and_runs(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, _concat_program(1500))
    assert result.log == ""
    assert result.output == _expected_output(1500)


def test_a_chain_longer_than_cpython_can_nest_still_compiles(tmp_path: Path) -> None:
    """4,000 nested ``+`` exceed CPython's compiler depth (about 3,000 at the default limit)."""
    result = run_gpl(tmp_path, _concat_program(4000))
    assert result.log == ""
    assert result.output == _expected_output(4000)


def test_short_chains_keep_the_readable_plus_form(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, _concat_program(20))
    code = next(v for k, v in result.files.items() if k.endswith("main_mod.py"))
    assert '"a0" + to_string(i) + to_string(2) + "a3" + to_string(i)' in code
    assert "join" not in code
    assert result.output == _expected_output(20)


def test_long_andalso_and_integer_chains_lower_and_run(tmp_path: Path) -> None:
    conds = " AndAlso _\n            ".join(f"i > {-k}" for k in range(1500))
    total = " + _\n            ".join("i" for _ in range(1500))
    result = run_gpl(tmp_path, module_src(f"""    Public Sub Main()
        Dim i, n As Integer
        i = 1
        If {conds} Then
            Console.WriteLine("all")
        End If
        n = {total}
        Console.WriteLine(n)
        i = 1500000
        n = {total}
        Console.WriteLine(n)
    End Sub"""))
    assert result.output == "all\n1500\n"
    # 1500 * 1500000 overflows Integer: the interval analysis of the chain keeps the range check
    assert "GPL error -710" in result.log and "2250000000" in result.log, result.log


def test_a_call_nested_too_deeply_is_one_diagnostic(tmp_path: Path) -> None:
    """210 calls nested in one another pass the parser's depth limit: GPL1117 is the whole answer.
    (The call whose arguments the parser gave up on was also reported as "takes 1 argument(s),
    0 given", GPL2004.)"""
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.transpile import transpile as transpile_project
    from gpltest import write_project

    nested = "F(" * 210 + "1" + ")" * 210
    src = module_src(f"""    Function F(ByVal x As Integer) As Integer
        Return x + 1
    End Function
    Public Sub Main()
        Console.WriteLine(CStr({nested}))
    End Sub""")
    sink = DiagnosticSink()
    assert transpile_project(write_project(tmp_path, {"Main.gpl": src}), sink) is None
    assert [d.code for d in sink] == ["GPL1117"], [d.header() for d in sink]
