"""Issue 20, item 3: a long ``Dim`` of simple names in a procedure holds its declarators as one
:class:`~gpl2py.gpl.syntax.ast.CompactDeclarators` (names and positions in arrays) and its locals
as a :class:`~gpl2py.gpl.semantics.symbols.LocalRun` (a symbol only for a name looked up); it
means the list of declarators exactly: the same diagnostics at the same places, the same Python,
the same ``dump-ast``.

The reference is the list itself: the same sources parsed with ``DIM_MIN`` set beyond every Dim in
them (so the parser builds a VarDeclarator per name, as before the compact form existed).
"""

from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.parser import parse
from gpl2py.source import SourceFile
from gpltest import module_src, run_gpl, translation_of

_TYPES = ["Integer", "Integer", "String", "Double", "Boolean", "Location", "Box", "Foo", "Short"]
#: names a long Dim declares: plain ones (some twice, some differing in case only), Python and
#: runtime names, a parameter's, a module variable's, the procedure's own
_SPECIAL = ["list", "print", "str", "self", "gplrt", "None", "lambda", "mv", "p1", "Work", "Console", "result"]
#: statements that use names of the Dim: read, assigned, compound, passed ByRef, counted, printed
_USES = ["{a} = {b} + 1", "{a} += 2", "Bump({a})", "For {a} = 1 To 3\n            Next", "Console.WriteLine({a})",
         "If {a} > 0 Then {b} = 0", "{a} = {a} + 1", "Main.mv = {a}"]
#: how a long Dim may end: simple, or with a declarator that turns it back into a list
_ENDS = ["", "", "", ", arr(3) As Integer", ", bx As New Box", ", z As Integer = 3", ", w", ", q(2), r As String",
         " As Integer = 4"]


def _dim(rnd: random.Random, keyword: str = "Dim", simple: bool = False,
         pool: list[str] | None = None) -> tuple[str, list[str]]:
    """A Dim of 60 to 200 names in groups of types, maybe ending in a declarator that is not simple
    (``simple``: of 64 names or more, all simple); also its names.  ``pool``: names to take, each
    once, and types that exist (a Dim without errors)."""
    n = rnd.choice([64, 65, 130, 200] if simple else [60, 63, 64, 65, 130, 200])
    names: list[str] = []
    for _ in range(n):
        r = rnd.random()
        if pool is not None:
            names.append(pool.pop())
        elif r < 0.08:
            names.append(rnd.choice(_SPECIAL))
        elif r < 0.12 and names:
            names.append(rnd.choice(names).upper())  # declared again, maybe in another case
        else:
            names.append(f"v{rnd.randrange(400)}")
    types = [t for t in _TYPES if t != "Foo"] if pool is not None else _TYPES
    parts, k = [], 0
    while k < n:
        size = rnd.choice([1, 5, 40, n])
        group = names[k:k + size]
        k += size
        sep = rnd.choice([", ", ", ", ",", ", _\n            "])
        parts.append(sep.join(group) + f" As {rnd.choice(types)}")
    text = f"{keyword} " + ", ".join(parts)
    end = "" if simple else rnd.choice(_ENDS)
    if end.startswith(" As"):  # a value for the last name only (an error if the group has several)
        text = text.rsplit(" As ", 1)[0] + end
    else:
        text += end
    return text, names


def _program(seed: int, clean: bool = False) -> str:
    """A Function whose body holds long Dims (its own block, an If's, a Static) and uses some of
    their names; ``clean``: every name declared once and every type known (no error: the output
    is the one a program without error gets)."""
    rnd = random.Random(seed)
    pool = None
    if clean:
        pool = [f"v{k}" for k in range(1000)] + ["list", "print", "str", "self", "gplrt", "lambda", "mv"]
        rnd.shuffle(pool)
    body = []
    dim, names = _dim(rnd, simple=True, pool=pool)
    body.append(dim)
    used = [n for n in names if n.lower().startswith("v")] or ["v1"]
    if clean:
        used = [n for n in used if _type_of(dim, n) == "Integer"]
    for _ in range(rnd.randrange(4, 10) if used else 0):
        body.append(rnd.choice(_USES).format(a=rnd.choice(used), b=rnd.choice(used)))
    if rnd.random() < 0.7 and not clean:  # a short Dim of a name the long one declared: a duplicate
        body.append(f"Dim {rnd.choice(names)} As Integer")
    nested, nested_names = _dim(rnd, simple=clean, pool=pool)
    branch = rnd.choice(["", f"Dim {rnd.choice(used)} As Integer"]) if not clean else ""
    body.append(f"If p1 > 0 Then\n            {nested}\n            Console.WriteLine({rnd.choice(nested_names)})\n"
                f"        Else\n            {branch}\n        End If")
    if rnd.random() < 0.5:
        static, _ = _dim(rnd, "Static", simple=clean, pool=pool)
        body.append(static)
    if rnd.random() < 0.5:
        body.append(_dim(rnd, simple=clean, pool=pool)[0])  # a second long Dim, in the procedure's own block
    text = "\n        ".join(body)
    return module_src(f"""    Dim mv As Integer
    Class Box
        Public n As Integer
    End Class
    Sub Bump(ByRef x As Integer)
        x = x + 1
    End Sub
    Function Work(ByVal p1 As Integer) As Integer
        {text}
        Return 0
    End Function
    Public Sub Main()
        Console.WriteLine(Work(1))
    End Sub""")


def _type_of(dim: str, name: str) -> str:
    """The type ``dim`` declares ``name`` of."""
    after = re.split(rf"(?<![\w]){re.escape(name)}(?![\w])", dim, maxsplit=1)[1]
    return after.split(" As ", 1)[1].split(",", 1)[0].split()[0]


def _compact_dims(text: str) -> int:
    unit = parse(SourceFile("t.gpl", text), DiagnosticSink())
    stack: list[A.Node] = [unit]
    count = 0
    while stack:
        node = stack.pop()
        count += isinstance(node, A.VarDecl) and node.compact
        stack.extend(node.children())
    return count


@pytest.mark.parametrize("seed", [*range(8), *(f"clean{k}" for k in range(4))])
def test_a_compact_dim_translates_as_its_list_of_declarators_does(seed: int | str, tmp_path: Path,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    """Programs with duplicate names (GPL2002 at each), unknown types, Dims turned back into lists
    by a declarator with bounds, New or a value (translated with ``--keep-going``), and programs
    without error."""
    clean = isinstance(seed, str)
    text = _program(int(str(seed).removeprefix("clean")), clean)
    assert _compact_dims(text) >= 1  # (else the test compares the list with itself)
    files, diags = translation_of(tmp_path / "compact", text)
    assert not clean or not diags, diags
    monkeypatch.setattr(A, "DIM_MIN", 10**9)
    assert _compact_dims(text) == 0
    listed_files, listed_diags = translation_of(tmp_path / "listed", text)
    assert diags == listed_diags
    assert files == listed_files


def _declarators(unit: A.SourceUnit) -> list[tuple[object, ...]]:
    """Every declarator of ``unit``: its span, name, bounds, type (name and span), New, value."""
    out: list[tuple[object, ...]] = []
    stack: list[A.Node] = [unit]
    while stack:
        node = stack.pop()
        if isinstance(node, A.VarDecl):
            for d in node.declarators:
                out.append((tuple(d.span), d.name, d.bounds and [b and A.dump(b) for b in d.bounds],
                             d.type and (d.type.name, tuple(d.type.span)), d.new,
                             d.new_args and [A.dump(a) for a in d.new_args], d.initializer and A.dump(d.initializer)))
        else:
            stack.extend(node.children())
    return out


@pytest.mark.parametrize("seed", range(8))
def test_a_compact_dim_parses_into_the_declarators_and_dump_of_the_list(
        seed: int, monkeypatch: pytest.MonkeyPatch) -> None:
    text = _program(seed)
    sink = DiagnosticSink()
    compact = parse(SourceFile("t.gpl", text), sink)
    monkeypatch.setattr(A, "DIM_MIN", 10**9)
    listed_sink = DiagnosticSink()
    listed = parse(SourceFile("t.gpl", text), listed_sink)
    assert _declarators(compact) == _declarators(listed)
    assert A.dump(compact) == A.dump(listed)
    assert [d.header() for d in sink.sorted()] == [d.header() for d in listed_sink.sorted()]


def test_a_dim_of_dim_min_simple_names_is_compact_and_a_shorter_one_a_list() -> None:
    names = [f"v{k}" for k in range(A.DIM_MIN)]
    text = ("Module M\nSub A()\n    Dim " + ", ".join(names[:40]) + " As Integer, _\n        "
            + ", ".join(names[40:]) + " As String\n    Dim " + ", ".join(names[1:]) + " As Integer\n"
            "End Sub\nEnd Module\n")
    unit = parse(SourceFile("t.gpl", text), DiagnosticSink())
    long, short = unit.members[0].members[0].body.statements  # type: ignore[attr-defined]
    assert long.compact and not short.compact
    decls = long.declarators
    assert isinstance(decls, A.CompactDeclarators) and len(decls) == A.DIM_MIN
    first, last = decls[0], decls[A.DIM_MIN - 1]
    line3, line4 = text.splitlines()[2:4]
    assert (first.name, first.type.name, tuple(first.span)[1:]) == (
        "v0", "Integer", (3, 9, 3, line3.index(", _") + 1))  # (to the end of its group's type)
    assert (last.name, last.type.name, tuple(last.span)[1:]) == (
        f"v{A.DIM_MIN - 1}", "String", (4, line4.index(f"v{A.DIM_MIN - 1}") + 1, 4, len(line4) + 1))
    # made anew each time, one declarator all the same (a key of the analysis's tables)
    assert decls[5] is not decls[5] and decls[5] == decls[5] and hash(decls[5]) == hash(decls[5])
    assert decls[5] != decls[6]
    assert list(long.children()) == [first.type, last.type]  # (the names are not child nodes)


def test_the_names_of_a_long_dim_have_their_values_when_run(tmp_path: Path) -> None:
    """Run: names read, assigned, counted and passed ByRef, others never named."""
    names = [f"n{k}" for k in range(300)]
    result = run_gpl(tmp_path, module_src(f"""    Sub Bump(ByRef x As Integer)
        x = x + 10
    End Sub
    Public Sub Main()
        Dim {", ".join(names[:150])} As Integer, {", ".join(names[150:])} As String, s As String
        n7 = 5
        Bump(n7)
        For n8 = 1 To 4
            n9 += n8
        Next
        n200 = "x" & n7
        s = n201 & "|" & n3
        Console.WriteLine(n7 & " " & n8 & " " & n9 & " " & n200 & " " & s & " " & n149)
    End Sub"""))
    assert result.output == "15 5 10 x15 |0 0\n"
