"""Realistic GPL sources parse cleanly, and the trees have the shapes the constructs imply.

The files live in tests/frontend/sources/ (one per construct family) and samples/ (whole projects);
they are loaded through gpl2py.project so that this also exercises the real loading path.
"""

from __future__ import annotations

from collections.abc import Iterator
from functools import cache
from pathlib import Path

import pytest

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.project import load_project
from gpl2py.gpl.syntax import ast
from gpl2py.gpl.syntax.parser import parse

REPO = Path(__file__).resolve().parents[2]
SOURCES = REPO / "tests" / "frontend" / "sources"
SAMPLE = REPO / "samples" / "tcp_command_server"
ALL_FILES = sorted(SOURCES.glob("*.gpl")) + sorted(SAMPLE.glob("*.gp[lo]"))


@cache
def parsed(path: Path) -> tuple[ast.SourceUnit, tuple[str, ...]]:
    sink = DiagnosticSink()
    project = load_project(path, sink)
    assert project is not None and len(project.sources) == 1
    unit = parse(project.sources[0], sink)
    rendered = tuple(d.render(project.sources[0]) for d in sink.sorted())
    return unit, rendered


def unit_of(name: str) -> ast.SourceUnit:
    path = SOURCES / name if (SOURCES / name).exists() else SAMPLE / name
    return parsed(path)[0]


def walk(node: ast.Node) -> Iterator[ast.Node]:
    yield node
    for child in node.children():
        yield from walk(child)


def nodes(unit: ast.Node, kind: type[ast.Node]) -> list:  # type: ignore[type-arg]
    return [n for n in walk(unit) if isinstance(n, kind)]


def proc(unit: ast.Node, name: str) -> ast.ProcDecl:
    found = [p for p in nodes(unit, ast.ProcDecl) if p.name.lower() == name.lower()]
    assert len(found) == 1, f"{name}: {len(found)} procedures"
    return found[0]


@pytest.mark.parametrize("path", ALL_FILES, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_parses_without_diagnostics(path: Path) -> None:
    unit, diagnostics = parsed(path)
    assert diagnostics == (), "\n".join(diagnostics)
    assert unit.members, "the file has at least one module"


def test_sample_project_loads_in_gpr_order() -> None:
    sink = DiagnosticSink()
    project = load_project(SAMPLE, sink)
    assert project is not None and list(sink) == []
    assert project.start == "Startup.Main"
    assert [Path(s.path).name for s in project.sources] == [
        "Globals.gpo", "CmdParse.gpl", "Motion.gpl", "Commands.gpl", "Dispatch.gpl", "Startup.gpl",
    ]


# --- loops and exits ----------------------------------------------------------------------------


def test_all_do_loop_forms() -> None:
    loops = nodes(proc(unit_of("loops.gpl"), "DoForms"), ast.DoLoop)
    shapes = [(d.condition is None, d.test_at_top if d.condition else None, d.until if d.condition else None)
              for d in loops]
    assert shapes == [
        (False, True, False),   # Do While c ... Loop
        (False, True, True),    # Do Until c ... Loop
        (False, False, False),  # Do ... Loop While c
        (False, False, True),   # Do ... Loop Until c
        (True, None, None),     # Do ... Loop
    ]


def test_for_steps_and_loop_variables() -> None:
    fors = nodes(proc(unit_of("loops.gpl"), "ForForms"), ast.For)
    assert len(fors) == 6
    no_step, minus_one, quarter, outer, inner, element = fors
    assert no_step.step is None and isinstance(no_step.next_var, ast.Name)
    assert minus_one.next_var is None
    step = minus_one.step
    assert (isinstance(step, ast.Unary) and step.op == "-" and isinstance(step.operand, ast.IntegerLiteral)
            and step.operand.value == 1) or (isinstance(step, ast.IntegerLiteral) and step.value == -1)
    assert isinstance(quarter.step, ast.RealLiteral) and quarter.step.value == 0.25
    assert inner in list(walk(outer.body))
    assert isinstance(element.var, ast.Invoke)  # For counters(2) = 1 To 5


def test_every_exit_kind() -> None:
    kinds = {e.kind.lower() for e in nodes(unit_of("loops.gpl"), ast.Exit)}
    assert kinds == {"do", "for", "while", "select", "sub", "function", "try"}


# --- operators and literals ---------------------------------------------------------------------


def test_every_binary_operator_and_compound_assignment() -> None:
    unit = unit_of("operators.gpl")
    binary = {b.op.lower() for b in nodes(unit, ast.Binary)}
    assert binary >= {"^", "*", "/", "\\", "mod", "+", "-", "&", "<<", ">>", "=", "<>", "<", ">", "<=", ">=",
                      "is", "and", "andalso", "or", "orelse", "xor"}
    unary = {u.op.lower() for u in nodes(unit, ast.Unary)}
    assert unary >= {"-", "+", "not"}
    assigns = {a.op for a in nodes(proc(unit, "Compound"), ast.Assign)}
    assert assigns == {"=", "^=", "*=", "/=", "\\=", "+=", "-=", "<<=", ">>=", "&="}


def test_literals_decode() -> None:
    unit = unit_of("operators.gpl")
    ints = {i.text.lower(): i.value for i in nodes(unit, ast.IntegerLiteral)}
    assert ints["&hff00"] == 0xFF00
    assert ints["&h00ff"] == 0xFF
    assert ints["&o777"] == 0o777
    assert ints["&o17"] == 15
    assert ints["&h7fffffff"] == 0x7FFFFFFF
    reals = {r.text.lower(): r.value for r in nodes(unit, ast.RealLiteral)}
    assert reals["1e+32"] == 1e32 and reals["2.5e-3"] == 0.0025 and reals[".9"] == 0.9
    strings = {s.value for s in nodes(unit, ast.StringLiteral)}
    assert {'Tom said, "Hello world"', '"', "Joe's", "&H20 is text, not hex"} <= strings


def _assignment_values(unit: ast.Node, proc_name: str) -> list[ast.Expr]:
    return [a.value for a in nodes(proc(unit, proc_name), ast.Assign) if a.op == "="]


def test_precedence_shapes() -> None:
    unit = unit_of("operators.gpl")
    arith = _assignment_values(unit, "Arithmetic")
    pow_chain = arith[1]  # a ^ 2 ^ 3 is (a ^ 2) ^ 3
    assert isinstance(pow_chain, ast.Binary) and pow_chain.op == "^"
    assert isinstance(pow_chain.left, ast.Binary) and pow_chain.left.op == "^"
    neg_pow = arith[2]  # -a ^ 2 is -(a ^ 2)
    assert isinstance(neg_pow, ast.Unary) and isinstance(neg_pow.operand, ast.Binary)
    assert neg_pow.operand.op == "^"
    logic = _assignment_values(unit, "Logic")
    assert isinstance(logic[0], ast.Binary) and logic[0].op == "="  # t = a = b: comparison
    not_eq = logic[6]  # Not a = b is Not (a = b)
    assert isinstance(not_eq, ast.Unary) and not_eq.op.lower() == "not"
    assert isinstance(not_eq.operand, ast.Binary) and not_eq.operand.op == "="
    mixed = logic[10]  # a < b And b < 10 Or a = 0 Xor t is ((.. And ..) Or ..) Xor t
    assert isinstance(mixed, ast.Binary) and mixed.op.lower() == "xor"
    assert isinstance(mixed.left, ast.Binary) and mixed.left.op.lower() == "or"
    assert isinstance(mixed.left.left, ast.Binary) and mixed.left.left.op.lower() == "and"


# --- classes, Me, delegates ---------------------------------------------------------------------


def test_nested_classes_properties_and_constructors() -> None:
    unit = unit_of("classes.gpl")
    classes = {c.name: c for c in nodes(unit, ast.ClassDecl)}
    assert set(classes) == {"Counter", "Snapshot", "Note", "Scaler"}
    counter = classes["Counter"]
    assert classes["Snapshot"] in counter.members
    assert classes["Note"] in classes["Snapshot"].members
    ctors = [m for m in counter.members if isinstance(m, ast.ProcDecl) and m.name.lower() == "new"]
    assert [len(c.params) for c in ctors] == [0, 1]
    props = {p.name: p for p in counter.members if isinstance(p, ast.PropertyDecl)}
    assert props["Count"].getter is not None and props["Count"].setter is not None
    assert props["Limit"].getter is None and props["Limit"].setter is not None
    assert nodes(counter, ast.MeExpr)
    shared = [m for m in counter.members if isinstance(m, ast.VarDecl) and "Shared" in m.modifiers]
    assert {d.name for s in shared for d in s.declarators} == {"Created", "MaxSize"}


def test_delegates_from_names_addresses_and_bound_methods() -> None:
    unit = unit_of("classes.gpl")
    assert {d.name: d.kind.lower() for d in nodes(unit, ast.DelegateDecl)} == {"Scale": "function",
                                                                             "Notify": "sub"}
    targets = []
    for a in nodes(unit, ast.AddressOf):
        t = a.target
        targets.append(t.name if isinstance(t, ast.Name) else f"{t.target.name}.{t.name}")
    assert targets == ["Half", "sc.Apply", "Say"]
    by_string = [n for n in nodes(unit, ast.New) if n.type.name == "Scale" and n.args
                 and isinstance(n.args[0], ast.StringLiteral)]
    assert [n.args[0].value for n in by_string] == ["Half", "Shapes.Half"]
    # table(1)(2.5): index, then invoke the delegate
    double = [i for i in nodes(unit, ast.Invoke) if isinstance(i.target, ast.Invoke)]
    assert len(double) == 1 and isinstance(double[0].target.target, ast.Name)


# --- control flow -------------------------------------------------------------------------------


def test_labels_goto_and_single_line_if_else() -> None:
    unit = unit_of("control.gpl")
    assert {lab.name.lower() for lab in nodes(unit, ast.Label)} == {"100", "again", "done", "retry"}
    assert {g.label.lower() for g in nodes(unit, ast.GoTo)} == {"100", "done", "again", "retry"}
    single = [i for i in nodes(proc(unit, "Classify"), ast.If) if i.single_line]
    assert len(single) == 2
    assert single[0].else_body is None and single[1].else_body is not None
    block_if = [i for i in nodes(proc(unit, "Classify"), ast.If) if not i.single_line][0]
    assert len(block_if.elseifs) == 2 and block_if.else_body is not None


def test_select_forms() -> None:
    selects = nodes(proc(unit_of("control.gpl"), "Classify"), ast.Select)
    assert len(selects) == 2
    primes = selects[0].cases[0]
    assert [c.value.value for c in primes.items] == [1, 3, 5, 7, 11]  # type: ignore[union-attr]
    assert selects[1].cases[-1].is_else and not selects[0].cases[-1].is_else


def test_retry_goto_from_catch_into_try() -> None:
    retry = proc(unit_of("control.gpl"), "Retry")
    tries = nodes(retry, ast.Try)
    assert len(tries) == 1
    assert any(isinstance(s, ast.Label) and s.name.lower() == "retry" for s in walk(tries[0].body))
    assert tries[0].catch is not None and tries[0].catch.variable == "exc1"
    assert [g.label for g in nodes(tries[0].catch, ast.GoTo)] == ["retry"]


def test_continued_call_arguments() -> None:
    calls = proc(unit_of("control.gpl"), "Calls")
    kinds = [type(s).__name__ for s in calls.body.statements]
    assert kinds == ["CallStmt"] * 6
    assert calls.body.statements[0].call_keyword  # type: ignore[attr-defined]


# --- declarations -------------------------------------------------------------------------------


def test_declaration_shapes() -> None:
    unit = unit_of("declarations.gpl")
    decls = {d.name: (v, d) for v in nodes(unit, ast.VarDecl) for d in v.declarators}
    assert len(decls["hyper"][1].bounds or []) == 4
    assert decls["later"][1].bounds == [None] and decls["later2"][1].bounds == [None, None]
    assert decls["origin"][1].new and decls["tool_off"][1].initializer is not None
    secret, hidden = decls["secret"][1], decls["hidden"][1]
    # ``Private secret, hidden As String``: both share the one String type node (spec §3.4).
    assert secret.type is not None and secret.type is hidden.type and secret.type.name == "String"
    assert decls["a"][1].type.name == "Single" and decls["k"][1].type.name == "Integer"  # type: ignore[union-attr]
    assert decls["calls"][0].keyword == "Static" and decls["STEP_SIZE"][0].is_const
    locals_proc = proc(unit, "Locals")
    assert [p.array_rank for p in locals_proc.params] == [0, 0, 1]
    assert [p.by_ref for p in locals_proc.params] == [False, True, False]
    redims = nodes(locals_proc, ast.ReDim)
    assert [len(r.bounds) for r in redims] == [2, 1]
    assert proc(unit, "NoParens").params == []


# --- the sample project -------------------------------------------------------------------------


def test_sample_dispatch_table_and_statics() -> None:
    unit = unit_of("Dispatch.gpl")
    [delegate] = nodes(unit, ast.DelegateDecl)
    assert delegate.name == "CommandProc" and [p.by_ref for p in delegate.params] == [False, True]
    statics = [d.name for v in nodes(unit, ast.VarDecl) if v.keyword == "Static" for d in v.declarators]
    assert statics == ["calls", "failures"]
    assert [len(r.bounds) for r in nodes(unit, ast.ReDim)] == [1, 1]


def test_sample_twenty_line_continued_expression() -> None:
    where = proc(unit_of("Motion.gpl"), "WhereText")
    [assign] = [a for a in nodes(where, ast.Assign)
                if isinstance(a.target, ast.Name) and a.target.name == "text"]
    assert assign.span.end_line - assign.span.line == 19
    concat = [b for b in walk(assign.value) if isinstance(b, ast.Binary) and b.op == "&"]
    assert len(concat) == 38


def test_sample_overloaded_constructors_and_exit_try() -> None:
    unit = unit_of("CmdParse.gpl")
    ctors = [p for p in nodes(unit, ast.ProcDecl) if p.name.lower() == "new"]
    assert [len(c.params) for c in ctors] == [0, 1, 2]
    motion = unit_of("Motion.gpl")
    pick = proc(motion, "PickAndPlace")
    assert [e.kind.lower() for e in nodes(pick, ast.Exit)] == ["try", "try", "try"]
    [t] = nodes(pick, ast.Try)
    assert t.catch is not None and t.finally_ is not None
    assert nodes(proc(motion, "Prepare"), ast.Throw)


def test_extensions_file_uses_vb_forms() -> None:
    unit = unit_of("extensions.gpl")
    clamp = proc(unit, "Clamp")
    assert [p.optional for p in clamp.params] == [False, True, True]
    assert all(p.default is not None for p in clamp.params[1:])
    items = [type(i).__name__ for c in nodes(unit, ast.CaseClause) for i in c.items]
    assert items == ["CaseIs", "CaseRange", "CaseRange", "CaseValue", "CaseValue", "CaseIs"]
    assert len(nodes(unit, ast.ForEach)) == 1
    [t] = nodes(proc(unit, "SafeRatio"), ast.Try)
    assert t.catch is not None and t.catch.variable == "ex" and t.catch.type is not None
    assert t.catch.type.name == "Exception" and t.finally_ is None
    [gauge] = [c for c in nodes(unit, ast.ClassDecl) if c.name == "Gauge"]
    [level] = [p for p in gauge.members if isinstance(p, ast.PropertyDecl)]
    assert level.setter is not None and [e.kind for e in nodes(level.setter, ast.Exit)] == ["Property"]


def test_vendor_style_crlf_tabs_and_keyword_case() -> None:
    raw = (SOURCES / "vendor_style.gpl").read_bytes()
    assert b"\r\n" in raw and b"\t" in raw  # the point of the file: keep it CR-LF with tabs
    unit = unit_of("vendor_style.gpl")
    assert [m.name for m in unit.members if isinstance(m, ast.ModuleDecl)] == ["GModule", "Cell"]
    main_proc = proc(unit, "Main")
    [loop] = nodes(main_proc, ast.For)
    assert isinstance(loop.next_var, ast.Name) and loop.next_var.name == "ii"
    assert [g.label for g in nodes(main_proc, ast.GoTo)] == ["done"]
    [msg] = [a for a in nodes(main_proc, ast.Assign) if isinstance(a.target, ast.Name) and a.target.name == "msg"]
    assert msg.span.end_line == msg.span.line + 1  # joined across the " _" continuation
    reals = [r.value for r in nodes(unit, ast.RealLiteral)]
    assert 1e32 in reals and 412.5 in reals
    wait = [m for m in nodes(main_proc, ast.MemberAccess) if m.name.lower() == "waitforeom"]
    assert len(wait) == 1 and isinstance(wait[0].target, ast.Name) and wait[0].target.name == "move"


# --- the TCP-command-server-like module -------------------------------------------------------


def _comments(unit: ast.Node) -> list[ast.Comment]:
    """Every comment and '#' line the parser kept, wherever it was attached."""
    out: list[ast.Comment] = []
    for n in walk(unit):
        out.extend(getattr(n, "leading_comments", []))
        out.extend(getattr(n, "end_comments", []))
        for attr in ("trailing_comment", "end_comment", "header_comment"):
            c = getattr(n, attr, None)
            if c is not None:
                out.append(c)
    return out


def test_tcs_server_keeps_every_region_line() -> None:
    unit = unit_of("tcs_server.gpl")
    directives = [c.text.split('"')[0].strip().lower() for c in _comments(unit) if c.directive]
    assert directives.count("#region") == 6 and directives.count("#end region") == 6


def test_tcs_server_retries_by_goto_from_catch_into_its_try() -> None:
    listen = proc(unit_of("tcs_server.gpl"), "Listen")
    [t] = nodes(listen, ast.Try)
    first = t.body.statements[0]
    assert isinstance(first, ast.Label) and first.name == "retry"
    assert t.catch is not None and t.catch.variable == "exc"
    assert [g.label for g in nodes(t.catch, ast.GoTo)] == ["retry"]
    # and a forward GoTo inside the Try's own loop
    loop = [s for s in t.body.statements if isinstance(s, ast.While)][0]
    assert [g.label for g in nodes(loop, ast.GoTo)] == ["closed"]
    assert [s.name for s in loop.body.statements if isinstance(s, ast.Label)] == ["closed"]


def test_tcs_server_select_with_and_without_case() -> None:
    unit = unit_of("tcs_server.gpl")
    text = (SOURCES / "tcs_server.gpl").read_text().splitlines()
    heads = {p.name: [text[s.span.line - 1].split()[1] for s in nodes(p, ast.Select)]
             for p in nodes(unit, ast.ProcDecl) if nodes(p, ast.Select)}
    assert heads == {"Cmd_Hp": ["args.GetUpperBound(0)"], "Cmd_Mode": ["Case"]}
    [bare] = nodes(proc(unit, "Cmd_Hp"), ast.Select)
    subject = bare.subject
    assert isinstance(subject, ast.Invoke) and isinstance(subject.target, ast.MemberAccess)
    assert subject.target.name == "GetUpperBound"
    assert [c.is_else for c in bare.cases] == [False, False, True]
    [with_case] = nodes(proc(unit, "Cmd_Mode"), ast.Select)
    assert [[i.value.value for i in c.items] for c in with_case.cases[:2]] == [["verbose", "v"], ["quiet", "q"]]


def test_tcs_server_optional_parameters_with_defaults() -> None:
    unit = unit_of("tcs_server.gpl")
    register = proc(unit, "Register")
    assert [(p.name, p.optional) for p in register.params] == [("name", False), ("proc", True)]
    assert isinstance(register.params[1].default, ast.StringLiteral) and register.params[1].default.value == ""
    make = proc(unit, "MakeReply")  # its parameter list is continued over two lines
    assert [p.optional for p in make.params] == [False, True, True]
    assert isinstance(make.params[2].default, ast.BooleanLiteral) and make.params[2].default.value is False
    assert make.params[2].span.line == make.span.line + 1
    calls = [i for i in nodes(unit, ast.Invoke) if isinstance(i.target, ast.Name) and i.target.name == "Register"]
    assert sorted(len(c.args) for c in calls) == [1, 1, 2, 2]


def test_tcs_server_delegates_and_threads_from_strings() -> None:
    unit = unit_of("tcs_server.gpl")
    [delegate] = nodes(unit, ast.DelegateDecl)
    assert delegate.kind == "Function" and [p.array_rank for p in delegate.params] == [1, 0]
    register = proc(unit, "Register")
    [made] = [n for n in nodes(register, ast.New) if n.type.name == "CmdHandler"]
    [arg] = made.args or []
    assert isinstance(arg, ast.Name) and arg.name == "proc"  # a procedure name held in a String
    [default_name] = [a.value for a in nodes(register, ast.Assign)
                      if isinstance(a.target, ast.Name) and a.target.name == "proc"]
    assert isinstance(default_name, ast.Binary) and default_name.op == "&"
    assert isinstance(default_name.left, ast.StringLiteral) and default_name.left.value == "TcsServer.Cmd_"
    [thread] = [n for n in nodes(proc(unit, "Main"), ast.New) if n.type.name == "Thread"]
    assert isinstance(thread.args[0], ast.StringLiteral) and thread.args[0].value == "TcsServer.Listen"
    # g_handlers(ii)(args, reply): index the table, then invoke the delegate
    [invoke] = [i for i in nodes(proc(unit, "Execute"), ast.Invoke) if isinstance(i.target, ast.Invoke)]
    table = invoke.target.target
    assert isinstance(table, ast.Name) and table.name == "g_handlers"
    assert [type(a).__name__ for a in invoke.args] == ["Name", "Name"]


def test_tcs_server_twenty_line_continued_help_text() -> None:
    help_proc = proc(unit_of("tcs_server.gpl"), "Cmd_Help")
    [assign] = [a for a in nodes(help_proc, ast.Assign) if isinstance(a.target, ast.Name)]
    assert assign.span.end_line - assign.span.line + 1 == 20
    pieces = [s.value for s in walk(assign.value) if isinstance(s, ast.StringLiteral)]
    assert pieces[0] == "TcsServer commands:" and pieces[-1] == "; commands: " and len(pieces) == 18
    assert nodes(assign.value, ast.Invoke)[-1].span.line == assign.span.end_line  # CStr(g_count)
