"""Names, scopes and the checks the TMscript manual states, over one script or packet.

Scopes are the manual's (L1226-L1349): ``define`` globals are seen everywhere; a local lives from
its declaration to the end of its block; no name may be declared twice in one function or repeat a
global (L1286-L1301); a word that names no variable in scope is the string of that word, with a
warning (L602-L605, L1320-L1333).  A Listen node's packets share their variables: ``known`` holds
those of earlier packets, and declaring one again is an error (L17838-L17851).

The result, :class:`Info`, is what the lowering reads: each name's variable (or ``None``: a bare
word), each call's kind, each function's assigned globals.
"""

from __future__ import annotations

import keyword
import re
from dataclasses import dataclass, field

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import Span, make_span
from gpl2py.tmscript import messages as M
from gpl2py.tmscript.semantics.library import (
    BUILTINS, BY_NAME, CLASS_ARGUMENTS, CLASSES, DOCUMENTED_MEMBERS, DOCUMENTED_METHODS, OBJECTS, RETURNS,
)
from gpl2py.tmscript.semantics.members_data import MEMBERS
from gpl2py.tmscript.syntax import ast as A

INTEGER = frozenset({"byte", "int"})
_QUOTED_NAME = re.compile(r"'([A-Za-z_][A-Za-z0-9_]*)'")
#: The Listen node's priority commands take a literal only (L18185-L18190).
PRIORITY = {"ScriptExit": "0 or 1", "StopAndClearBuffer": "0, 1 or 2"}


@dataclass
class Var:
    """A declared variable: ``storage`` is ``global`` (define), ``local`` (a function's, a
    parameter), or ``node`` (a Listen-node variable, kept between packets)."""

    name: str
    type: str
    array: bool
    storage: str
    pyname: str
    cls: str | None = None  # a class variable (Socket, TPoint, ...)


@dataclass
class Info:
    names: dict[int, Var | None] = field(default_factory=dict)
    calls: dict[int, str] = field(default_factory=dict)  # "user" | "builtin" | "method"
    globals_assigned: dict[str, set[str]] = field(default_factory=dict)
    declared: dict[str, Var] = field(default_factory=dict)  # a packet's new node variables
    functions: dict[str, A.Function] = field(default_factory=dict)
    types: dict[int, str] = field(default_factory=dict)  # static types known (decls, literals)
    #: a string literal's single-quoted variable names: (start, end, variable) in its text (L628)
    interpolations: dict[int, list[tuple[int, int, Var]]] = field(default_factory=dict)
    #: a by-name built-in's call (``GetVarValue``, ``VarSync``): the variables visible there
    scopes: dict[int, dict[str, Var]] = field(default_factory=dict)


#: Python names a TMscript name must not become (the generated code's own names and Python's).
RESERVED = frozenset(keyword.kwlist) | frozenset(keyword.softkwlist) | {
    "tm", "v", "run", "print", "len", "list", "str", "int", "float", "bool", "range", "object", "type"}


def pyname(name: str) -> str:
    """The Python name of a TMscript name (``name_`` when it would clash).  One to one: ``v_``
    becomes ``v__`` because ``v`` becomes ``v_`` (two parameters ``v`` and ``v_`` were one Python
    name, a function Python refused)."""
    return name + "_" if name.rstrip("_") in RESERVED or name.startswith("_") else name


class Checker:
    def __init__(self, sink: DiagnosticSink, known: dict[str, Var] | None = None) -> None:
        self.sink = sink
        self.info = Info()
        self.globals: dict[str, Var] = dict(known or {})
        self.blocks: list[dict[str, Var]] = []
        self.function_names: set[str] = set()  # every local of the current function
        self.function: A.Function | None = None
        self.loops = 0
        self.switches = 0
        self.packet = False
        self.written: set[int] = set()  # the members assigned (``Robot[0].Joint = ...``)

    # --- entry points ---------------------------------------------------------------------------
    def script(self, tree: A.Script) -> Info:
        for fn in tree.functions:
            if fn.name in self.info.functions:
                self.sink.report(M.TM_REDECLARED, fn.span, name=fn.name, where=" as a function")
            self.info.functions[fn.name] = fn
        self.blocks = [self.globals]
        self.current = "define"  # (an initialiser may assign a global: ``int w = (n = 5) + 1``)
        for st in tree.define:
            if isinstance(st, (A.Decl, A.ClassDecl)):
                self.declare_stmt(st, "global")
            else:
                self.sink.report(M.TM_NOT_HERE, st.span, what="a statement", where="in 'define' (declarations only)")
        if "main" not in tree.sections:
            self.sink.report(M.TM_MAIN_MISSING, tree.span)
        for name in ("main", "closestop", "errorstop"):
            if name in tree.sections:
                self.in_function(name, [], tree.sections[name])
        for fn in tree.functions:
            self.function = fn
            self.in_function(fn.name, fn.params, fn.body)
            self.function = None
        return self.info

    def packet_script(self, tree: A.Script) -> Info:
        self.packet = True
        self.blocks = [self.globals]
        self.function_names = set(self.globals)
        self.blocks.append({})
        for st in tree.statements:
            self.statement(st)
        for name, var in self.blocks[-1].items():
            self.info.declared[name] = var
        return self.info

    def in_function(self, name: str, params: list[A.Param], body: A.Block) -> None:
        self.function_names = set()
        self.current = name
        self.info.globals_assigned[name] = set()
        scope: dict[str, Var] = {}
        for p in params:
            scope[p.name] = Var(p.name, p.type, p.array, "local", pyname(p.name))
            self.function_names.add(p.name)
        self.blocks = [self.globals, scope]
        for st in body.body:
            self.statement(st)

    # --- declarations ---------------------------------------------------------------------------
    def declare(self, name: str, type_: str, array: bool, span: object, storage: str, cls: str | None = None) -> Var:
        if name in self.function_names or (name in self.globals and (storage != "global" or self.packet)):
            where = " in an earlier packet" if self.packet and name in self.globals else ""
            self.sink.report(M.TM_REDECLARED, span, name=name, where=where)
        var = Var(name, type_, array, storage, pyname(name), cls)
        self.blocks[-1][name] = var
        if storage != "global":
            self.function_names.add(name)
        return var

    def declare_stmt(self, st: A.Node, storage: str | None = None) -> None:
        storage = storage or ("node" if self.packet else "local")
        if isinstance(st, A.Decl):
            for d in st.declarators:
                if d.init is not None:
                    self.expr(d.init)
                    self.check_store(st.type, st.array, d.init)
                var = self.declare(d.name, st.type, st.array, d.span, storage)
                self.info.names[id(d)] = var
        elif isinstance(st, A.ClassDecl):
            if st.cls not in CLASSES:
                self.sink.report(M.TM_UNSUPPORTED, st.span, what=f"the class {st.cls}")
            counts = CLASS_ARGUMENTS.get(st.cls)
            if counts is not None and len(st.args) not in counts:
                expected = ", ".join(map(str, counts[:-1])) + f" or {counts[-1]}"
                self.sink.report(M.TM_ARGUMENT_COUNT, st.span, name=st.cls, expected=expected, s="s",
                                 given=len(st.args))
            for a in st.args:
                self.expr(a)
            self.info.names[id(st)] = self.declare(st.name, st.cls, False, st.span, storage, st.cls)

    def check_store(self, type_: str, array: bool, value: A.Node) -> None:
        if type_ == "byte" and not array and isinstance(value, A.Num) and isinstance(value.value, int) \
                and not 0 <= value.value <= 255 and value.text.startswith("-"):
            self.sink.report(M.TM_BYTE_LITERAL, value.span, value=value.text)

    def lookup(self, name: str) -> Var | None:
        for scope in reversed(self.blocks):
            if name in scope:
                return scope[name]
        return None

    # --- statements -----------------------------------------------------------------------------
    def statement(self, st: A.Node) -> None:
        if isinstance(st, (A.Decl, A.ClassDecl)):
            self.declare_stmt(st)
        elif isinstance(st, A.ExprStmt):
            self.expr(st.expr)
        elif isinstance(st, A.Block):
            self.block(st.body)
        elif isinstance(st, A.If):
            self.expr(st.cond)
            self.block([st.then])
            if st.other is not None:
                self.block([st.other])
        elif isinstance(st, A.While):
            self.expr(st.cond)
            self.loop([st.body])
        elif isinstance(st, A.DoWhile):
            self.loop([st.body])
            self.expr(st.cond)
        elif isinstance(st, A.For):
            self.blocks.append({})
            for s in st.init:
                self.statement(s) if isinstance(s, A.Decl) else self.expr(s)
            if st.cond is not None:
                self.expr(st.cond)
            for s in st.step:
                self.expr(s)
            self.loop([st.body])
            self.blocks.pop()
        elif isinstance(st, A.Switch):
            self.expr(st.subject)
            self.switches += 1
            for c in st.cases:
                if c.label is not None:
                    self.expr(c.label)
                self.block(c.body)
            self.switches -= 1
        elif isinstance(st, A.Jump):
            if self.loops == 0 and not (st.word == "break" and self.switches):
                self.sink.report(M.TM_BREAK_OUTSIDE, st.span, word=st.word,
                                 switch=" or a switch" if st.word == "break" else "")
        elif isinstance(st, A.Return):
            if st.value is not None:
                self.expr(st.value)
            fn = self.function
            if fn is not None and fn.ret == "void" and st.value is not None:
                self.sink.report(M.TM_RETURN_VALUE, st.span, what=f"the void function {fn.name}() returns no value")
            elif fn is not None and fn.ret != "void" and st.value is None:
                self.sink.report(M.TM_RETURN_VALUE, st.span, what=f"{fn.name}() must return a {fn.ret} value")

    def block(self, body: list[A.Node]) -> None:
        self.blocks.append({})
        for s in body:
            self.statement(s)
        self.blocks.pop()

    def loop(self, body: list[A.Node]) -> None:
        self.loops += 1
        saved, self.switches = self.switches, 0
        self.block(body)
        self.switches = saved
        self.loops -= 1

    # --- expressions ----------------------------------------------------------------------------
    def expr(self, e: A.Node) -> None:
        if isinstance(e, A.Str):
            found = []
            for m in _QUOTED_NAME.finditer(e.value):
                var = self.lookup(m.group(1))
                if var is not None and not var.array and var.cls is None:
                    found.append((m.start(), m.end(), var))
                    self.sink.report(M.TM_INTERPOLATION, e.span, name=var.name)
            if found:
                self.info.interpolations[id(e)] = found
        elif isinstance(e, A.Name):
            var = self.lookup(e.name)
            self.info.names[id(e)] = var
            if var is None and e.name not in OBJECTS:
                self.sink.report(M.TM_BARE_WORD, e.span, name=e.name)
        elif isinstance(e, A.ArrayLit):
            for x in e.items:
                self.expr(x)
        elif isinstance(e, A.Call):
            self.call(e)
        elif isinstance(e, A.Index):
            self.expr(e.obj)
            if isinstance(e.obj, (A.Str, A.Num, A.Bool)) or (
                    isinstance(e.obj, A.Name) and self.info.names.get(id(e.obj)) is None and e.obj.name not in OBJECTS):
                what = f"'{e.obj.name}'" if isinstance(e.obj, A.Name) else "a literal"
                self.sink.report(M.TM_NOT_INDEXABLE, e.obj.span, what=what)
            self.expr(e.index)
            if e.index2 is not None:
                self.expr(e.index2)
        elif isinstance(e, A.Member):
            self.expr(e.obj)
            self.member(e)
        elif isinstance(e, (A.Unary, A.Postfix)):
            self.expr(e.operand)
            if e.op in ("++", "--"):
                self.assignable(e.operand, e.op)
                var = self.info.names.get(id(e.operand)) if isinstance(e.operand, A.Name) else None
                if var is not None and (var.type not in INTEGER or var.array):
                    self.sink.report(M.TM_INCREMENT, e.span, op=e.op)
        elif isinstance(e, A.Binary):
            self.expr(e.left)
            self.expr(e.right)
            if e.op in ("/", "%") and isinstance(e.right, A.Num) and e.right.value == 0:
                self.sink.report(M.TM_DIVISION_BY_ZERO, e.right.span)
        elif isinstance(e, A.Cond):
            self.expr(e.cond)
            self.expr(e.then)
            self.expr(e.other)
        elif isinstance(e, A.Assign):
            self.expr(e.value)
            if isinstance(e.target, A.Member):
                self.written.add(id(e.target))
            self.expr(e.target)
            self.assignable(e.target, e.op)
            if isinstance(e.target, A.Name):
                var = self.info.names.get(id(e.target))
                if var is not None:
                    self.check_store(var.type, var.array, e.value)
            if e.op in ("/=", "%=") and isinstance(e.value, A.Num) and e.value.value == 0:
                self.sink.report(M.TM_DIVISION_BY_ZERO, e.value.span)
        elif isinstance(e, A.Cast):
            self.expr(e.operand)
            if isinstance(e.operand, A.Bool) and e.type not in ("bool", "string"):
                self.sink.report(M.TM_BAD_CAST, e.span, src="bool", dst=e.type)

    def assignable(self, target: A.Node, op: str) -> None:
        if isinstance(target, A.Name):
            var = self.info.names.get(id(target))
            if var is None:
                self.sink.report(M.TM_NOT_ASSIGNABLE, target.span, op=op)
            elif var.storage == "global" and not self.packet:
                self.info.globals_assigned.setdefault(self.current, set()).add(var.pyname)

    def call(self, e: A.Call) -> None:
        for a in e.args:
            self.expr(a)
        callee = e.callee
        if isinstance(callee, A.Member):
            self.expr(callee.obj)
            self.info.calls[id(e)] = "method"
            self.method(callee)
            return
        if not isinstance(callee, A.Name):
            self.sink.report(M.TM_UNKNOWN_FUNCTION, callee.span, name="(expression)")
            return
        fn = self.info.functions.get(callee.name)
        if fn is not None:
            self.info.calls[id(e)] = "user"
            if len(e.args) != len(fn.params):
                n = len(fn.params)
                self.sink.report(M.TM_ARGUMENT_COUNT, e.span, name=fn.name, expected=n,
                                 s="" if n == 1 else "s", given=len(e.args))
            if fn.ret != "void":
                self.info.types[id(e)] = fn.ret + ("[]" if fn.ret_array else "")
            return
        arity = BUILTINS.get(callee.name)
        if arity is None:
            self.sink.report(M.TM_UNKNOWN_FUNCTION, callee.span, name=callee.name)
            return
        self.info.calls[id(e)] = "builtin"
        if callee.name in BY_NAME:
            visible: dict[str, Var] = {}
            for scope in self.blocks:
                visible.update(scope)
            self.info.scopes[id(e)] = {n: v for n, v in visible.items() if v.cls is None}
        if self.packet and callee.name in PRIORITY and e.args and not isinstance(e.args[0], A.Num):
            self.sink.report(M.TM_PRIORITY_ARGUMENT, e.args[0].span, name=callee.name, allowed=PRIORITY[callee.name])
        lo, hi = arity
        if len(e.args) < lo or (hi is not None and len(e.args) > hi):
            expected = str(lo) if lo == hi else (f"{lo} or more" if hi is None else f"{lo} to {hi}")
            self.sink.report(M.TM_ARGUMENT_COUNT, e.span, name=callee.name, expected=expected,
                             s="" if expected == "1" else "s", given=len(e.args))
        if callee.name in RETURNS:
            self.info.types[id(e)] = RETURNS[callee.name]


    def method(self, callee: A.Member) -> None:
        """``var.Method(...)``: a method the variable's class has in the runtime (L18366:
        ``mbus1.Preset``).  On anything else (a bare word, a class without that method) it is
        reported here, where a TM user reads it, rather than failing in Python at run time: a
        method the manual documents and the runtime lacks (``TBase.GetValue``) is not supported
        yet."""
        obj = callee.obj
        var = self.info.names.get(id(obj)) if isinstance(obj, A.Name) else None
        if var is None or var.cls is None:
            if isinstance(obj, A.Name):
                self.sink.report(M.TM_UNKNOWN_FUNCTION, callee.span, name=f"{obj.name}.{callee.name}")
            return
        if var.cls not in CLASSES:
            return  # (the declaration's class is reported, GPL5314)
        if MEMBERS.get(var.cls, {}).get(callee.name) == "method":
            return
        if callee.name in DOCUMENTED_METHODS.get(var.cls, ()):
            self.sink.report(M.TM_UNSUPPORTED, callee.span, what=f"{var.cls}.{callee.name}()")
        else:
            self.sink.report(M.TM_UNKNOWN_FUNCTION, callee.span, name=f"{var.cls}.{callee.name}")

    def member(self, e: A.Member) -> None:
        """``obj.Name`` read or assigned: a member the runtime implements (its classes, through
        ``members_data``); one the manual documents and the runtime lacks (``tcp1.MCF``, E82) is
        not supported yet; anything else is not a member.  Reported at the member's name, so no
        member reaches Python that the runtime does not have."""
        owner, label = self.owner(e.obj)
        if label is None:
            return
        name, span = e.name, self.name_span(e)
        if owner is not None:
            mode = MEMBERS.get(owner, {}).get(name)
            if mode == "R" and id(e) in self.written:
                self.sink.report(M.TM_READ_ONLY_MEMBER, span, owner=label, name=name)
            if mode in ("R", "RW"):
                return
            if name in DOCUMENTED_MEMBERS.get(owner, {}):
                self.sink.report(M.TM_UNSUPPORTED, span, what=f"the member {label}.{name}")
                return
        self.sink.report(M.TM_UNKNOWN_MEMBER, span, name=name, owner=label)

    def owner(self, obj: A.Node) -> tuple[str | None, str | None]:
        """Whose members ``obj`` has: (the class or parameterized object, how messages name it),
        (None, a description) for a value without members, (None, None) when it was reported
        already (a class not supported)."""
        if isinstance(obj, A.Name):
            var = self.info.names.get(id(obj))
            if var is None:
                return None, f"{obj.name} without an index" if obj.name in OBJECTS else f'the string "{obj.name}"'
            if var.cls is None:
                return None, f"the {var.type}{'[]' if var.array else ''} variable {var.name}"
            return (var.cls, var.cls) if var.cls in CLASSES else (None, None)
        if isinstance(obj, A.Index) and isinstance(obj.obj, A.Name) and self.info.names.get(id(obj.obj)) is None:
            if obj.obj.name in OBJECTS:
                return obj.obj.name, f"{obj.obj.name}[...]"
            return None, None  # (a bare word indexed: GPL5316)
        if isinstance(obj, A.Index) and isinstance(obj.obj, (A.Str, A.Num, A.Bool)):
            return None, None  # (GPL5316)
        return None, "this value"

    @staticmethod
    def name_span(e: A.Member) -> Span:
        """The span of the member's name (``e``'s ends with it)."""
        s = e.span
        return make_span(s.file, s.end_line, max(1, s.end_col - len(e.name)), s.end_line, s.end_col)


def check_script(tree: A.Script, sink: DiagnosticSink) -> Info:
    """A script project's names and checks."""
    return Checker(sink).script(tree)


def check_packet(tree: A.Script, sink: DiagnosticSink, known: dict[str, Var] | None = None) -> Info:
    """A packet's names and checks; ``known``: the Listen node's variables so far."""
    return Checker(sink, known).packet_script(tree)
