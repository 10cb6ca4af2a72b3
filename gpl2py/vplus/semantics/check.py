"""What a V+ project means: its programs, its variables' scopes and types, and what is wrong.

* **Programs** form one flat namespace across the project's files (spec §1.1); a name defined
  again is kept from the first file loaded (User's Guide L3190-3192: LOAD does not replace a
  resident program), with a warning when the two differ.
* **Scopes** (spec §1.6, §3.7): a name is a parameter or an AUTO of the program, else one of its
  LOCALs, else GLOBAL -- and an undeclared name is GLOBAL, wherever it is first used.  A scalar and
  an array of the same name are two variables (``AUTO a`` and ``AUTO a[5]`` in the corpus's
  self-test; docs/design/vplus.md).
* **Types** (spec §3.1): the sigil fixes strings, precision points and belts; an unprefixed name is
  a real or a transformation, inferred from every use in every program, through CALL arguments
  (which bind by reference) to parameters and back, to a fixed point.  A name used as both is
  GPL4302, reported at each use that disagrees with the first.
* **Control**: step labels unique per program, GOTO targets exist, EXIT/NEXT inside a loop,
  CALL/EXECUTE/REACT name a program, functions are V+ functions.

The result, :class:`Model`, is what the lowering reads: every :class:`~ast.Var`'s symbol and
every expression's type, so that lowering decides nothing about meaning.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import Span
from gpl2py.vplus import messages as M
from gpl2py.vplus.semantics.types import FUNCTIONS, LOCATION_FIRST, REAL_VALUES, T, of_sigil
from gpl2py.vplus.syntax import ast as A
from gpl2py.vplus.syntax.keywords import UNSIMULATED


@dataclass(eq=False)
class Symbol:
    """One variable: ``scope`` is GLOBAL, LOCAL, AUTO or PARAM; ``array`` for ``name[]``."""

    name: str  # as first written, with its sigil
    key: str  # V+'s name (ast.key) plus "[]" for an array
    scope: str
    program: str | None  # the program of a LOCAL, AUTO or PARAM
    type: T
    span: Span
    array: bool = False
    double: bool = False
    dims: list[A.Expr] | None = None
    typed_at: Span | None = None  # where the type was fixed


@dataclass(eq=False)
class ProgramInfo:
    program: A.Program
    path: str
    params: list[Symbol] = field(default_factory=list)
    names: dict[str, Symbol] = field(default_factory=dict)  # AUTO, LOCAL and parameters by key
    labels: dict[int, A.Stmt] = field(default_factory=dict)


@dataclass
class Model:
    """The analysed project."""

    programs: dict[str, ProgramInfo] = field(default_factory=dict)  # by V+ name, in load order
    globals: dict[str, Symbol] = field(default_factory=dict)
    symbol_of: dict[int, Symbol] = field(default_factory=dict)  # id(Var) -> Symbol
    type_of: dict[int, T] = field(default_factory=dict)  # id(Expr) -> T
    data: list[tuple[A.DataSection, str]] = field(default_factory=list)
    start: ProgramInfo | None = None


def analyze(modules: list[A.Module], sink: DiagnosticSink, start: str | None = None,
            start_span: Span | None = None) -> Model:
    """The model of ``modules`` (in load order); ``start`` names the program to run (default: the
    first program of the first file, as V+'s EXECUTE of the main program)."""
    model = Model()
    for mod in modules:
        for prog in mod.programs:
            first = model.programs.get(prog.key)
            if first is not None:
                if _text(first.program) != _text(prog):
                    sink.report(M.DUPLICATE_PROGRAM, prog.name_span, name=prog.name,
                                first=str(first.program.name_span))
                continue
            model.programs[prog.key] = ProgramInfo(prog, mod.path)
        for section in mod.data:
            model.data.append((section, mod.path))
    a = _Analysis(model, sink)
    for info in model.programs.values():
        a.declare(info)
    for section, _path in model.data:
        for datum in section.data:
            a.datum(datum)
    for _ in range(20):  # types flow between programs, to a fixed point: the pass that changes
        a.changed = False  # nothing saw the final types, and its diagnostics are the ones to keep
        a.sink = sink.child()
        for info in model.programs.values():
            a.program(info, report=True)
        if not a.changed:
            break
    sink.extend(a.sink)
    sink.ignored_errors.extend(a.sink.ignored_errors)  # (their lines raise: gpl2py.kept)
    a.sink = sink
    for sym in a.all_symbols():
        if sym.type is T.UNKNOWN:
            sym.type = T.REAL
    if start is not None:
        model.start = model.programs.get(A.key("", start))
        if model.start is None:
            sink.report(M.START_NOT_FOUND, start_span, name=start)
    elif model.programs:
        model.start = next(iter(model.programs.values()))
    return model


def _text(prog: A.Program) -> str:
    """A program's identity for duplicate detection: its statements' source positions differ, so
    compare the dump of the tree without spans."""
    import dataclasses

    def norm(x: object) -> object:
        if isinstance(x, list):
            return [norm(i) for i in x]
        if dataclasses.is_dataclass(x) and not isinstance(x, type):
            return (type(x).__name__,) + tuple(
                norm(getattr(x, f.name)) for f in dataclasses.fields(x) if f.name not in ("span", "comments", "name_span",
                                                                                            "target_span", "program_span",
                                                                                            "end_span", "trailing"))
        return x.lower() if isinstance(x, str) else x

    return repr(norm(prog.body)) + repr(norm(prog.params)) + repr(norm(prog.decls))


class _Analysis:
    def __init__(self, model: Model, sink: DiagnosticSink) -> None:
        self.model = model
        self.sink = sink
        self.changed = False
        self.report = False
        self.info: ProgramInfo | None = None
        self.loops = 0

    def all_symbols(self) -> list[Symbol]:
        out = list(self.model.globals.values())
        for info in self.model.programs.values():
            out.extend(info.names.values())
        return out

    # --- declarations ---------------------------------------------------------------------------

    def declare(self, info: ProgramInfo) -> None:
        prog = info.program
        for p in prog.params:
            sym = self._new(p.var, "PARAM", prog.name, array=p.var.whole)
            info.params.append(sym)
            info.names.setdefault(sym.key, sym)
            self.model.symbol_of[id(p.var)] = sym
        for decl in prog.decls:
            for item in decl.items:
                array = item.dims is not None or item.var.whole
                k = item.var.key + ("[]" if array else "")
                if decl.kind == "GLOBAL":
                    sym = self.model.globals.get(k)
                    if sym is None:
                        sym = self.model.globals[k] = self._new(item.var, "GLOBAL", None, array=array)
                    info.names.pop(k, None)
                else:
                    sym = info.names.get(k)
                    if sym is not None and sym.scope != "PARAM":
                        detail = f" (first at {sym.span})"
                        self.sink.report(M.REDECLARED, item.span, name=item.var.shown, detail=detail)
                    if sym is None or sym.scope != "PARAM":
                        sym = self._new(item.var, decl.kind, prog.name, array=array)
                        info.names[k] = sym
                sym.dims = item.dims or sym.dims
                if decl.qualifier == "DOUBLE":
                    sym.double = True
                if decl.qualifier == "LOC" and not item.var.sigil:
                    sym.type, sym.typed_at = T.TRANS, item.span
                self.model.symbol_of[id(item.var)] = sym

    def _new(self, var: A.Var, scope: str, program: str | None, array: bool) -> Symbol:
        fixed = of_sigil(var.sigil)
        return Symbol(var.shown, var.key + ("[]" if array else ""), scope, program, fixed or T.UNKNOWN,
                      var.span, array=array, typed_at=var.span if fixed else None)

    def datum(self, datum: A.Datum) -> None:
        sym = self.resolve(datum.var, None)
        if not datum.var.sigil and len(datum.values) == 6:
            self.expect_sym(sym, T.TRANS, datum.span)
        elif not datum.var.sigil:
            self.expect_sym(sym, T.REAL, datum.span)

    # --- names ---------------------------------------------------------------------------------

    def resolve(self, var: A.Var, info: ProgramInfo | None) -> Symbol:
        array = var.index is not None or var.whole
        k = var.key + ("[]" if array else "")
        sym = None
        if info is not None:
            sym = info.names.get(k)
        if sym is None:
            sym = self.model.globals.get(k)
            if sym is None:
                sym = self.model.globals[k] = self._new(var, "GLOBAL", None, array=array)
        self.model.symbol_of[id(var)] = sym
        if len(var.name) > A.SIGNIFICANT and self.report:
            self.sink.report(M.NAME_TRUNCATED, var.span, name=var.shown, short=var.sigil + var.name[:A.SIGNIFICANT])
        return sym

    def expect_sym(self, sym: Symbol, t: T, span: Span) -> None:
        if t is T.UNKNOWN:
            return
        if sym.type is T.UNKNOWN:
            if of_sigil(sym.name[:1]) is None and t in (T.REAL, T.TRANS):
                sym.type, sym.typed_at = t, span
                self.changed = True
            return
        if sym.type is not t and self.report and not (sym.type is T.TRANS and t is T.PPOINT):
            self.sink.report(M.TYPE_CONFLICT, span, name=sym.name, new=t.value, old=sym.type.value,
                             where=str(sym.typed_at or sym.span))

    # --- programs ------------------------------------------------------------------------------

    def program(self, info: ProgramInfo, report: bool) -> None:
        self.report = report
        self.info = info
        self.loops = 0
        if report:
            info.labels = {}
            self._labels(info, info.program.body)
        self.block(info.program.body)

    def _labels(self, info: ProgramInfo, body: list[A.Stmt]) -> None:
        for s in body:
            if s.label is not None:
                first = info.labels.get(s.label)
                if first is not None:
                    self.sink.report(M.DUPLICATE_LABEL, s.span, label=s.label, program=info.program.name,
                                     line=first.span.line)
                else:
                    info.labels[s.label] = s
            for sub in blocks(s):
                self._labels(info, sub)

    def block(self, body: list[A.Stmt]) -> None:
        for s in body:
            self.stmt(s)

    def stmt(self, s: A.Stmt) -> None:  # noqa: C901 (one dispatch over the statement kinds)
        info = self.info
        assert info is not None
        if isinstance(s, A.Assign):
            sym = self.resolve(s.target, info)
            self.indices(s.target)
            t = self.expr(s.value)
            if sym.type.is_location and self.report:
                self.sink.report(M.LOCATION_ASSIGNED, s.target.span, name=s.target.shown)
            elif not sym.type.is_location:
                want = T.STRING if s.target.sigil == "$" else T.REAL
                self.expect_sym(sym, want, s.target.span)
                self.expect(s.value, want)
            del t
        elif isinstance(s, A.SetLoc):
            sym = self.resolve(s.target, info)
            self.indices(s.target)
            self.expr(s.value)
            want = T.PPOINT if s.target.sigil == "#" else T.TRANS
            self.expect_sym(sym, want, s.target.span)
            self.expect(s.value, want)
        elif isinstance(s, A.Here):
            for f in s.frames:
                self.expect(f, T.TRANS)
            sym = self.resolve(s.target, info)
            self.indices(s.target)
            self.expect_sym(sym, T.PPOINT if s.target.sigil == "#" else T.TRANS, s.target.span)
        elif isinstance(s, A.If):
            self.expect(s.cond, T.REAL)
            self.block(s.then)
            if s.orelse is not None:
                self.block(s.orelse)
        elif isinstance(s, A.IfGoto | A.Goto):
            if isinstance(s, A.IfGoto):
                self.expect(s.cond, T.REAL)
            if self.report and s.target not in info.labels:
                self.sink.report(M.UNKNOWN_LABEL, s.target_span, label=s.target, program=info.program.name)
        elif isinstance(s, A.Case):
            self.expect(s.subject, T.REAL)
            for arm in s.arms:
                for v in arm.values or ():
                    self.expect(v, T.REAL)
                self.block(arm.body)
        elif isinstance(s, A.DoUntil | A.While | A.For):
            if isinstance(s, A.For):
                sym = self.resolve(s.var, info)
                self.indices(s.var)
                self.expect_sym(sym, T.REAL, s.var.span)
                for e in (s.start, s.stop, s.step):
                    if e is not None:
                        self.expect(e, T.REAL)
            if isinstance(s, A.While):
                self.expect(s.cond, T.REAL)
            self.loops += 1
            self.block(s.body)
            self.loops -= 1
            if isinstance(s, A.DoUntil):
                self.expect(s.cond, T.REAL)
        elif isinstance(s, A.Exit):
            if s.count is not None:
                self.expect(s.count, T.REAL)
            if self.loops == 0 and self.report:
                self.sink.report(M.EXIT_OUTSIDE_LOOP, s.span, word=s.word)
        elif isinstance(s, A.CallStmt):
            if s.dynamic is not None:
                self.expect(s.dynamic, T.STRING)
                for arg in s.args:
                    if arg is not None:
                        self.expr(arg)
            else:
                self.call(s.name, s.name_span, s.args)
        elif isinstance(s, A.Execute):
            if s.task is not None:
                self.expect(s.task, T.REAL)
            for e in s.rest:
                if e is not None:
                    self.expect(e, T.REAL)
            self.call(s.program, s.program_span, s.args)
        elif isinstance(s, A.React):
            if s.signal is not None:
                self.expect(s.signal, T.REAL)
            if s.priority is not None:
                self.expect(s.priority, T.REAL)
            if s.program:
                self.call(s.program, s.program_span, s.args)
        elif isinstance(s, A.Instr):
            self.instr(s)

    def instr(self, s: A.Instr) -> None:
        word = s.word
        if word in UNSIMULATED and self.report:
            self.sink.report(M.UNSIMULATED, s.span, name=word)
        for e in s.unit or ():
            if e is not None:
                if word == "ATTACH" and isinstance(e, A.Var):  # ATTACH (lun, 4) returns the LUN in lun
                    self.expect_sym(self.resolve(e, self.info), T.REAL, e.span)
                    self.indices(e)
                else:
                    self.expect(e, T.REAL)
        if word in ("PARAMETER", "SWITCH", "SELECT", "ENABLE", "DISABLE"):
            for e in s.target or (s.args if word in ("ENABLE", "DISABLE") else []):
                if isinstance(e, A.Var) and e.index:
                    for i in e.index:
                        self.expect(i, T.REAL)
            for e in s.args if word not in ("ENABLE", "DISABLE") else []:
                if e is not None:
                    self.expect(e, T.REAL)
            return
        if word == "DECOMPOSE":
            for e in s.target or ():
                if isinstance(e, A.Var):
                    self.expect_sym(self.resolve(e, self.info), T.REAL, e.span)
                    self.indices(e)
            for e in s.args:
                if e is not None:
                    self.expr(e)
            return
        if word == "READ" or word == "PROMPT":
            for e in s.args:
                if isinstance(e, A.Var):
                    sym = self.resolve(e, self.info)
                    self.indices(e)
                    self.expect_sym(sym, T.REAL if not e.sigil else of_sigil(e.sigil) or T.REAL, e.span)
                elif e is not None:
                    self.expr(e)
            return
        if word == "SPEED" and len(s.args) > 1 and isinstance(s.args[1], A.Str) and self.report:
            self.sink.report(M.DIALECT_SPEED_STRING, s.args[1].span)
        for e in s.target or ():
            if e is not None:
                self.expect(e, T.REAL)
        for i, e in enumerate(s.args):
            if e is None:
                continue
            if word in LOCATION_FIRST and i == 0:
                self.expect(e, T.PPOINT if _is_ppoint(e) else T.TRANS)
            elif word in REAL_VALUES or (word in LOCATION_FIRST and i > 0):
                if not (word == "SPEED" and isinstance(e, A.Str)):
                    self.expect(e, T.REAL)
            else:
                self.expr(e)

    def call(self, name: str, span: Span, args: list[A.Expr | None]) -> None:
        callee = self.model.programs.get(A.key("", name))
        if callee is None:
            if self.report:
                self.sink.report(M.UNDEFINED_PROGRAM, span, name=name)
            for arg in args:
                if arg is not None:
                    self.expr(arg)
            return
        if len(args) > len(callee.params) and self.report:
            self.sink.report(M.ARGUMENT_COUNT, span, name=name, expected=len(callee.params), given=len(args))
        for arg in args[len(callee.params):]:
            if arg is not None:
                self.expr(arg)
        for arg, param in zip(args, callee.params, strict=False):
            if arg is None:
                continue
            t = self.expr(arg)
            if isinstance(arg, A.Var):
                sym = self.model.symbol_of[id(arg)]
                if sym.type is T.UNKNOWN and param.type is not T.UNKNOWN:
                    self.expect_sym(sym, param.type, arg.span)
                elif param.type is T.UNKNOWN and sym.type is not T.UNKNOWN:
                    self.expect_sym(param, sym.type, param.span)
                elif param.type is not T.UNKNOWN:
                    self.expect_sym(sym, param.type, arg.span)
            elif t is not T.UNKNOWN:
                if param.type is T.UNKNOWN:
                    self.expect_sym(param, t, param.span)

    def indices(self, var: A.Var) -> None:
        for i in var.index or ():
            self.expect(i, T.REAL)

    # --- expressions ---------------------------------------------------------------------------

    def expect(self, e: A.Expr, t: T) -> T:
        """The type of ``e``, which the context wants to be ``t`` (a variable takes it)."""
        if isinstance(e, A.Paren):
            got = self.expect(e.inner, t)
            self.model.type_of[id(e)] = got
            return got
        if isinstance(e, A.Var):
            sym = self.resolve(e, self.info)
            self.indices(e)
            self.expect_sym(sym, t, e.span)
            got = sym.type if sym.type is not T.UNKNOWN else t
            self.model.type_of[id(e)] = got
            return got
        return self.expr(e)

    def operand(self, e: A.Expr, t: T) -> None:
        """An operand already typed by :meth:`expr` that its operator wants to be ``t``: a variable
        (in parentheses or not) takes the type.  Anything else is not walked again -- walking each
        operand twice made a chain of n operators cost 2**n (a 100-term sum never finished)."""
        inner = e
        while isinstance(inner, A.Paren):
            inner = inner.inner
        if isinstance(inner, A.Var):
            self.expect(e, t)

    def expr(self, e: A.Expr) -> T:
        t = self._expr(e)
        self.model.type_of[id(e)] = t
        return t

    def _expr(self, e: A.Expr) -> T:  # noqa: C901
        if isinstance(e, A.Num):
            return T.REAL
        if isinstance(e, A.Str):
            return T.STRING
        if isinstance(e, A.Format):
            return T.UNKNOWN
        if isinstance(e, A.Paren):
            return self.expr(e.inner)
        if isinstance(e, A.Var):
            sym = self.resolve(e, self.info)
            self.indices(e)
            return sym.type
        if isinstance(e, A.Unary):
            self.expect(e.operand, T.REAL)
            return T.REAL
        if isinstance(e, A.Binary):
            if e.op == ":":
                left = self.expr(e.left) if _is_belt(e.left) else self.expect(e.left, T.TRANS)
                del left
                self.expect(e.right, T.TRANS)
                return T.TRANS
            lt = self.expr(e.left)
            rt = self.expr(e.right)
            want = T.STRING if e.op in ("+", "==", "<>", "<", ">", "<=", ">=", "=<", "=>") and T.STRING in (lt, rt) \
                else T.REAL
            self.operand(e.left, want)
            self.operand(e.right, want)
            return T.STRING if want is T.STRING and e.op == "+" else T.REAL
        if isinstance(e, A.Call):
            return self.function(e)
        return T.UNKNOWN

    def function(self, e: A.Call) -> T:
        name = e.upper
        if name in UNSIMULATED and self.report:
            self.sink.report(M.UNSIMULATED, e.span, name=e.sigil + e.name)
        sig = FUNCTIONS.get(name)
        if sig is None:
            if self.report:
                self.sink.report(M.UNKNOWN_FUNCTION, e.span, name=e.sigil + e.name)
            for a in e.args:
                if a is not None:
                    self.expr(a)
            return of_sigil(e.sigil) or T.UNKNOWN
        result, params = sig
        for i, a in enumerate(e.args):
            if a is None:
                continue
            want = params[min(i, len(params) - 1)] if params else T.UNKNOWN
            if name in ("DEFINED", "LAST", "PARAMETER", "SWITCH", "SELECT") and isinstance(a, A.Var):
                if name in ("DEFINED", "LAST"):
                    self.resolve(a, self.info)
                    self.indices(a)
                continue
            if want is T.UNKNOWN:
                self.expr(a)
            elif name in ("DISTANCE", "DX", "DY", "DZ", "INRANGE", "IDENTICAL") and _is_ppoint(a):
                self.expr(a)
            else:
                self.expect(a, want)
        for a in e.by or ():
            if a is not None:
                self.expect(a, T.REAL)
        return result


def _is_ppoint(e: A.Expr) -> bool:
    return (isinstance(e, A.Var) and e.sigil == "#") or (isinstance(e, A.Call) and e.sigil == "#")


def _is_belt(e: A.Expr) -> bool:
    return isinstance(e, A.Var) and e.sigil == "%"


def blocks(s: A.Stmt) -> list[list[A.Stmt]]:
    """The statement lists nested in ``s``."""
    if isinstance(s, A.If):
        return [s.then] + ([s.orelse] if s.orelse is not None else [])
    if isinstance(s, A.Case):
        return [arm.body for arm in s.arms]
    if isinstance(s, A.DoUntil | A.While | A.For):
        return [s.body]
    return []
