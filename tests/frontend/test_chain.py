"""Issue 20, item 3: a long run of binary operators of one precedence level is one compact
:class:`~gpl2py.gpl.syntax.ast.Chain` node, which means exactly the nested Binary nodes it stands
for: the same types, diagnostics at the same places, the same Python, the same ``dump-ast``.

The reference is the nested form itself: the same sources parsed with ``CHAIN_MIN`` set beyond
every chain in them (so the parser builds Binary nodes as before the Chain existed).
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.parser import parse
from gpl2py.source import SourceFile
from gpltest import module_src, run_gpl, translation_of

_OPS = ["+", "-", "*", "/", "\\", "Mod", "^", "<<", ">>", "And", "Or", "Xor", "&", "=", "<>", "<", ">",
        "<=", ">=", "AndAlso", "OrElse"]
_ATOMS = ["1", "2", "7", "&H1F", "007", "3.5", "i", "s", "b", "x", "sh", "(i + 1)", "f(i)", '"ab"', "True",
          "0", "100000", "2147483647", "2147483648", "1e3", "-3", "l", "Console"]


def _program(seed: int) -> str:
    """Statements whose values are runs of 60 to 400 operators: one operator repeated, ``+``/``-``
    mixed, or any operators (several precedence levels, so runs inside runs), over operands of
    every kind (literals kept as values and not, variables, calls, errors: a Location, a Sub)."""
    rnd = random.Random(seed)
    stmts = []
    for _ in range(12):
        n = rnd.choice([63, 64, 65, 130, 400])
        mode = rnd.random()
        if mode < 0.3:
            ops = [rnd.choice(_OPS)] * n
        elif mode < 0.6:
            ops = [rnd.choice(["+", "-"]) for _ in range(n)]
        else:
            ops = [rnd.choice(_OPS) for _ in range(n)]
        terms = [rnd.choice(_ATOMS if rnd.random() < 0.3 else ["1", "2", "3"]) for _ in range(n + 1)]
        expr = terms[0] + "".join(f" {o} {x}" for o, x in zip(ops, terms[1:]))
        expr = expr.replace(" + ", " + _\n            ", 5)
        stmts.append(f"        {rnd.choice(['d', 'sh', 'x', 's', 'b'])} = {expr}")
    return module_src("""    Function f(ByVal v As Integer) As Integer
        Return v
    End Function
    Public Sub Main()
        Dim i As Integer = 3
        Dim d As Integer
        Dim sh As Short
        Dim x As Double
        Dim s As String = "q"
        Dim b As Boolean
        Dim l As New Location
""" + "\n".join(stmts) + "\n    End Sub")


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_chain_translates_as_the_nested_binary_nodes_do(seed: int, tmp_path: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    text = _program(seed)
    files, diags = translation_of(tmp_path / "chain", text)
    monkeypatch.setattr(A, "CHAIN_MIN", 10**9)
    nested_files, nested_diags = translation_of(tmp_path / "nested", text)
    assert diags == nested_diags
    assert files == nested_files


def test_a_run_of_chain_min_operators_is_one_chain_with_its_literals_kept_as_values() -> None:
    terms = ["1", "x", "&H10", "2"] * 20
    text = "Module M\nSub A()\n    y = " + " + ".join(terms) + " * 3 + 4\nEnd Sub\nEnd Module\n"
    unit = parse(SourceFile("t.gpl", text), DiagnosticSink())
    assign = unit.members[0].members[0].body.statements[0]  # type: ignore[attr-defined]
    chain = assign.value
    assert isinstance(chain, A.Chain) and len(chain.ops) == 80 and {chain.op(k) for k in range(80)} == {"+"}
    assert isinstance(chain.first, A.IntegerLiteral)
    # a decimal literal is a value, the others nodes (a name, a hex literal, the product 2 * 3)
    assert chain.literal(3) == 1 and chain.literal(2) == 2 and chain.literal(0) is None
    assert isinstance(chain.operands[0], A.Name) and isinstance(chain.operands[1], A.IntegerLiteral)
    assert isinstance(chain.operands[78], A.Binary) and chain.operands[78].op == "*"
    one = chain.operand(3)  # the fifth term, "1" at column 9 + 4 * len("1 + x + &H10 + 2 + ")
    assert isinstance(one, A.IntegerLiteral) and one.value == 1 and one.text == "1"
    assert (one.span.line, one.span.col, one.span.end_col) == (3, 9 + 19, 10 + 19)
    assert chain.prefix_span(3)[1:] == (3, 9, 3, 10 + 19)
    assert chain.span[1:] == (3, 9, 3, len(text.splitlines()[2]) + 1)  # to the end of "+ 4"


def test_a_short_run_stays_nested_binary_nodes() -> None:
    text = "Module M\nSub A()\n    y = " + " + ".join(["1"] * A.CHAIN_MIN) + "\nEnd Sub\nEnd Module\n"
    unit = parse(SourceFile("t.gpl", text), DiagnosticSink())
    value = unit.members[0].members[0].body.statements[0].value  # type: ignore[attr-defined]
    assert isinstance(value, A.Binary)  # CHAIN_MIN - 1 operators


def test_dump_ast_shows_a_chain_as_the_nested_binary_nodes(monkeypatch: pytest.MonkeyPatch) -> None:
    text = "Module M\nSub A()\n    y = " + " - _\n    ".join(["1", "x", "2"] * 40) + "\nEnd Sub\nEnd Module\n"
    chained = A.dump(parse(SourceFile("t.gpl", text), DiagnosticSink()))
    monkeypatch.setattr(A, "CHAIN_MIN", 10**9)
    assert chained == A.dump(parse(SourceFile("t.gpl", text), DiagnosticSink()))


def test_a_long_mixed_chain_computes_what_python_computes(tmp_path: Path) -> None:
    """The value, run: ``1 + 2 - 3 + ...`` over continued lines, the Integer range checked at the
    end (the bounds of the chain are folded through the Chain)."""
    terms = [str(k % 97) for k in range(500)]
    ops = ["+" if k % 3 else "-" for k in range(499)]
    expr = terms[0] + "".join(f" {o} _\n            {x}" if k % 7 == 0 else f" {o} {x}"
                              for k, (o, x) in enumerate(zip(ops, terms[1:])))
    expected = int(terms[0])
    for o, x in zip(ops, terms[1:]):
        expected = expected + int(x) if o == "+" else expected - int(x)
    result = run_gpl(tmp_path, module_src(f"""    Public Sub Main()
        Dim sh As Short
        sh = {expr}
        Console.WriteLine(sh)
    End Sub"""))
    assert result.output == f"{expected}\n"
