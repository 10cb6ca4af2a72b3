"""Statements and procedures -> Python (docs/design/lowering.md, "Statements", "Procedures").

:class:`ProcLowerer` emits one procedure.  Loops that Python can express directly stay plain
(``while``, ``for ... in range``); ``Exit`` and ``GoTo`` that must leave several Python loops set a
flag and break level by level; a statement list holding a GoTo target becomes a dispatch loop
(``lower/goto.py``).  Every Python loop the lowering opens is a :class:`Frame` on a stack, which is
how a jump knows how many loops it must leave.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink, InternalError
from gpl2py.gpl.lower.context import ModuleContext
from gpl2py.pywriter.emit import BLOCKS, Writer
from gpl2py.gpl.lower.expressions import (
    BYREF,
    CONV,
    EXC,
    MEMBERS,
    P_AND,
    P_ADD,
    P_ATOM,
    P_OR,
    Code,
    ExprLowerer,
    negation,
    annotation,
    default_code,
    elem_type_code,
    paren,
)
from gpl2py.gpl.lower.goto import GotoPlan, plan_gotos
from gpl2py.gpl.lower.names import py_ident
from gpl2py.pywriter.text import py_string
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.check import child_blocks
from gpl2py.gpl.semantics.info import (
    BuiltinMemberInfo,
    DynamicMemberInfo,
    IndexInfo,
    PropInfo,
    Reached,
    ResultInfo,
    StubNameInfo,
    VarInfo,
)
from gpl2py.gpl.semantics.symbols import ClassSym, ProcSym, VarSym
from gpl2py.gpl.syntax import ast as A

THREADS = "gplrt.threads"
# A range For of fewer literal steps than this is a plain ``range``: ``paced_range`` would return
# the range itself (its checkpoint every PACE iterations, gplrt.threads.scheduler.PACE, which a
# test keeps equal; the transpiler does not import the runtime).
PACE = 1024
ARRAYS = "gplrt.lang.arrays"


@dataclass(eq=False)
class Frame:
    """One Python loop the lowering opened."""

    kind: str  # For | While | Do | Select | Try | dispatch
    after: list[tuple[str, str]] = field(default_factory=list)  # (flag, action) checks after the loop
    block: A.Block | None = None


def lower_procedure(ctx: ModuleContext, p: ProcSym, cls: ClassSym | None, sink: DiagnosticSink,
                    method: bool) -> Writer:
    """The ``def`` of procedure ``p`` (:meth:`ProcLowerer.procedure`)."""
    return ProcLowerer(ctx, p, cls, sink).procedure(p, method=method)


class ProcLowerer(ExprLowerer):
    def __init__(self, ctx: ModuleContext, proc: ProcSym | None, cls: ClassSym | None,
                 sink: DiagnosticSink) -> None:
        super().__init__(ctx, proc, cls)
        self.sink = sink
        self.w = Writer()
        self.frames: list[Frame] = []
        self.flags: list[str] = []
        self.flag_of: dict[tuple[int, str], str] = {}
        self.counter = 0
        # Integer locals that can never be negative (_counters); set when a procedure is lowered
        self.counters: set[VarSym] = set()
        # the first statement of a loop body that adds 1 to a variable the loop's test has just
        # found below an Integer: it cannot overflow (guarded_increment)
        self.guarded: set[A.Stmt] = set()
        self.current: A.Stmt | None = None  # the statement being lowered
        self.plan: GotoPlan | None = None
        self.state_var: dict[A.Block, str] = {}
        self.entry_flag: dict[A.Stmt, str] = {}
        # per Try being lowered (innermost last): None when its Exit Try raises ExitTry, else the
        # loop a retried Try runs in (framed_try), which Exit Try breaks
        self.exit_try: list[Frame | None] = []
        self.too_deep_seen = False  # a statement was nested too deeply for Python (too_deep)
        self._read_past_loops: set[str] | None = None

    def read_past_loops(self, v: VarSym) -> bool:
        """Whether the procedure may read ``v`` where a range For over it has left its final value:
        anywhere but inside the bodies of the For loops over ``v`` (each stores ``v`` before its
        body runs).  A For over ``v`` nested in another is read in the outer body: always True."""
        if self._read_past_loops is None:
            body = getattr(getattr(self.proc, "decl", None), "body", None)
            self._read_past_loops = _reads_outside_own_loops(body) if body is not None else None
        return self._read_past_loops is None or v.name.lower() in self._read_past_loops

    def fresh(self, stem: str) -> str:
        self.counter += 1
        return f"_{stem}{self.counter}"

    # -- stores -------------------------------------------------------------------------------------------

    def target_type(self, e: A.Expr) -> t.GplType:
        return self.info(e).type  # a built-in member's: the value type of its assignment form

    def store(self, target: A.Expr, value: str, source: A.Expr | None = None) -> None:
        """Emit ``target = value`` (``value`` already converted to the target's type; ``source``:
        the GPL expression it came from, when there is one).  Dispatched on the target's meaning;
        a target with no rule is a gap in gpl2py (GPL9000), never a line left out."""
        i = self.info(target)
        if isinstance(i, VarInfo):
            self.store_var(i, value, source)
        elif isinstance(i, ResultInfo):
            self.w.line(f"_result = {value}")
        elif isinstance(i, IndexInfo):
            assert isinstance(target, A.Invoke)
            self.w.line(f"{self.index_code(target)} = {value}")
        elif isinstance(i, PropInfo):
            prop = i.sym
            if prop.shared:
                self.w.line(f"{self.class_ref(prop.owner)}._set_{py_ident(prop.name)}({value})")  # type: ignore[arg-type]
            else:
                self.w.line(f"{self.prop_ref(prop, i.receiver)} = {value}")
        elif isinstance(i, BuiltinMemberInfo):
            m = i.sym
            head = self.ctx.builtin(i.owner.python_name) if i.static else self.sub(i.receiver, P_ATOM)  # type: ignore[arg-type]
            if m.kind == "property" and not isinstance(target, A.Invoke):
                self.w.line(f"{head}.{m.name} = {value}")
            else:  # ``X.M(args) = v``, or a member whose getter takes arguments: its set_ companion
                args = self.args_code(target.args if isinstance(target, A.Invoke) else [], i.params or [])
                self.w.line(f"{head}.set_{m.name}({', '.join([*args, value])})")
        elif isinstance(i, DynamicMemberInfo):
            # a member of a value of unknown type: the runtime admits GPL members only
            assert i.receiver is not None
            setter = self.rt(MEMBERS, "set_member")
            self.w.line(f"{setter}({self.val(i.receiver)}, {py_string(i.name)}, {value})")
        elif isinstance(i, StubNameInfo):
            stub = i.stub
            if stub.builtin is None:
                self.w.line(f"{self.ctx.stub_ref(stub)} = {value}")  # a variable of the protected code
                return
            module, attr = self.ctx.stub_parts(stub)
            args = [self.val(i.receiver)] if not stub.shared and i.receiver is not None else []
            self.w.line(f"{module}.set_{attr}({', '.join([*args, value])})")
        elif self.model.errors_reported:  # not a target: the error reported at it, when reached
            self.w.line(self.fault(target))
        else:
            raise InternalError(target.span, f"no lowering for a store into {type(i).__name__}")

    def store_var(self, i: VarInfo, value: str, source: A.Expr | None) -> None:
        """``v = value`` for each storage of a variable (docs/design/lowering.md, "Declarations")."""
        v = i.sym
        if v.storage == "temp":
            self.w.line(f"{v.name} = {value}")
            return
        if v.storage == "local" and not v.read and not v.boxed:
            # never read: keep the value's side effects only (no unused local for pyflakes)
            if source is None or not self.effect_free(source, v.type):
                self.w.line(value)
            return
        if v.storage in ("local", "param"):
            n = self.local_name(v)
            if (v.storage == "param" and v.byref) or v.boxed:
                self.w.line(f"{n}.value = {value}")
            else:
                self.w.line(f"{n} = {value}")
            return
        if v.storage == "static":
            name = self.static_name(v)
            self.globals.add(name)
            self.w.line(f"{name} = {value}")
            return
        if v.storage == "module" and not self.ctx.module_prefix(self.ctx.owner_module(v)) \
                and not self.shadowed(v):
            self.globals.add(py_ident(v.name))
        self.w.line(f"{self.var_code(v, i.receiver)[0]} = {value}")

    def effect_free(self, e: A.Expr, dst: t.GplType) -> bool:
        """Whether storing ``e`` into a ``dst`` variable can neither fail nor act: a literal of
        ``dst``'s own type, Nothing, or a plain variable of that type (no conversion to raise)."""
        if isinstance(e, A.NothingLiteral):
            return True
        i = self.model.info.get(e)
        if isinstance(e, (A.IntegerLiteral, A.RealLiteral, A.StringLiteral, A.BooleanLiteral)):
            return i is not None and i.type is dst
        return isinstance(e, A.Name) and isinstance(i, VarInfo) and i.type is dst and i.receiver is None

    # -- procedures -----------------------------------------------------------------------------------------

    def procedure(self, p: ProcSym, method: bool) -> Writer:
        """The ``def`` of a module procedure or class method."""
        decl = p.decl
        assert decl is not None
        self.plan = plan_gotos(decl.body, self.sink)
        for info in self.plan.blocks.values():
            if self.plan.dispatch(info.block) is not None:
                self.state_var[info.block] = self.fresh("g")
        for stmt in self.plan.entered:
            flag = self.fresh("enter")
            self.entry_flag[stmt] = flag
            self.flags.append(flag)
        for v in p.locals.made():  # (a name of a long Dim nothing names has no symbol: a Dim's, not static)
            if v.storage == "static":
                self.ctx.statics.append((self.static_name(v), default_code(v.type)))
        body = self.w
        body.level = 1
        body.base = len(self.cls.path) if method and self.cls is not None else 0  # inside its classes
        start = body.mark()
        self.counters = _counters(p, self.model.info)
        self.nonneg |= self.counters
        self.block(decl.body)
        if p.kind == "Function" and _falls_through(decl.body):
            # the value of a Function that ends without Return (§9.1); no unreachable line
            body.line("return _result" if p.uses_result else f"return {default_code(p.result)}")
        out = Writer()
        out.gpl_line = decl.span.line
        params = ["self"] if method and not p.shared else []
        for v in p.params:
            text = py_ident(v.name)
            ann = annotation(v.type)
            if ann and v.byref:  # the callee gets a cell over the caller's variable (gplrt.lang.byref)
                ann = f"{self.ctx.helper('gplrt.lang.gpltypes', 'Ref')}[{ann}]"
            if ann:
                text += f": {ann}"
            if v.optional:
                dflt = self.conv(v.default, v.type)[0] if v.default is not None else default_code(v.type)
                text += f" = {dflt}" if ann else f"={dflt}"
            params.append(text)
        ret = ""
        if p.kind == "Function":
            ann = annotation(p.result)
            ret = f" -> {ann}" if ann else ""
        elif p.kind in ("Sub", "New", "Set"):
            ret = " -> None"
        elif p.kind == "Get" and p.prop is not None:
            ann = annotation(p.prop.type)
            ret = f" -> {ann}" if ann else ""
        name = self.ctx.names.proc_name(p)
        out.comments(decl.leading_comments)  # above any decorator: they describe the whole def
        if p.kind == "New":
            name = "__init__" if len(p.owner.ctors) <= 1 else f"_new_{p.overload_index}"  # type: ignore[union-attr]
        if p.kind in ("Get", "Set") and p.prop is not None and p.prop.shared:
            # a Shared property: static accessors, reached as Cls._get_P() / Cls._set_P(v)
            out.line("@staticmethod")
            name = f"_{p.kind.lower()}_{name}"
            params = params[1:] if params and params[0] == "self" else params
        elif p.kind == "Get":
            out.line("@property")
        elif p.kind == "Set" and p.prop is not None and p.prop.getter is None:
            name = f"_set_{name}"  # write-only property: property(fset=...) follows the def
        elif p.kind == "Set":
            out.line(f"@{name}.setter")
        elif method and p.shared:
            out.line("@staticmethod")
        header = out.def_at = out.mark()
        out.line(f"def {name}({', '.join(params)}){ret}:")
        out.trailing(decl.trailing_comment, header)
        out.indent()
        prologue = self.prologue(p)
        for line in prologue:
            out.line(line)
        out.extend(body, extra_indent=0)
        if not prologue and body.only_comments(start):
            out.line("pass")
        if decl.end_comment is not None:
            out.comments([decl.end_comment])
        return out

    def prologue(self, p: ProcSym) -> list[str]:
        lines: list[str] = []
        if self.globals:
            lines.append("global " + ", ".join(sorted(self.globals)))
        box = None
        for v in p.params:
            if v.boxed:
                box = box or self.rt(BYREF, "Box")
                lines.append(f"{py_ident(v.name)} = {box}({py_ident(v.name)})")
        assigned_first = _assigned_before_use(p)
        for v in p.locals.made():  # (one nothing looked up is neither read nor boxed)
            if v.storage != "local" or not (v.read or v.boxed):
                continue
            if v in assigned_first:
                continue  # the procedure's first statements store it before any read
            d = default_code(v.type)
            if v.boxed:
                box = box or self.rt(BYREF, "Box")
                d = f"{box}({d})"
            lines.append(f"{py_ident(v.name)} = {d}")
        if p.uses_result:
            lines.append(f"_result = {default_code(p.result)}")
        for f in self.flags:
            lines.append(f"{f} = False")
        return lines

    # -- blocks ----------------------------------------------------------------------------------------------

    def block(self, block: A.Block) -> None:
        start = self.w.mark()
        dispatch = self.plan.dispatch(block) if self.plan is not None else None
        if dispatch is None:
            for s in block.statements:
                self.stmt(s)
        else:
            self.dispatch_block(block, dispatch.targets)
        self.w.comments(block.end_comments)
        self.w.ensure_body(start)

    def dispatch_block(self, block: A.Block, targets: list[A.Stmt]) -> None:
        assert self.plan is not None
        state = self.state_var[block]
        info = self.plan.blocks[block]
        owner = info.owner
        if owner is not None and owner in self.entry_flag and self.plan.entered.get(owner) is block:
            # entered by a GoTo from outside: keep the segment it chose, once
            flag = self.entry_flag[owner]
            self.w.line(f"if {flag}:")
            self.w.line(f"    {flag} = False")
            self.w.line("else:")
            self.w.line(f"    {state} = 0")
        elif not (isinstance(owner, A.Try) and owner in self.plan.retry_tries and block is owner.body):
            self.w.line(f"{state} = 0")
        segments: list[list[A.Stmt]] = [[]]
        for s in block.statements:
            if any(s is x for x in targets):
                segments.append([])
            segments[-1].append(s)
        self.paced_loop()
        self.w.indent(BLOCKS["loop"])
        frame = Frame("dispatch", block=block)
        self.frames.append(frame)
        for k, seg in enumerate(segments):
            if k == 0 and not seg:
                continue
            self.w.line(f"if {state} <= {k}:")
            self.w.indent()
            start = self.w.mark()
            for s in seg:
                self.stmt(s)
            self.w.ensure_body(start)
            self.w.dedent()
        self.w.line("break")
        self.frames.pop()
        self.w.dedent()
        self.after(frame)

    def after(self, frame: Frame) -> None:
        for flag, action in frame.after:
            self.w.line(f"if {flag}:")
            self.w.indent()
            if action != "break-on":
                self.w.line(f"{flag} = False")
                self.w.line(action)
            else:
                self.w.line("break")
            self.w.dedent()

    def jump(self, target: Frame, action: str, pre: list[str]) -> None:
        """Leave loops up to ``target`` and ``break``/``continue`` it."""
        for line in pre:
            self.w.line(line)
        idx = self.frames.index(target)
        inner = self.frames[idx + 1:]
        if not inner:
            self.w.line(action)
            return
        key = (id(target), action)
        flag = self.flag_of.get(key)
        if flag is None:
            flag = self.fresh("jump")
            self.flag_of[key] = flag
            self.flags.append(flag)
        self.w.line(f"{flag} = True")
        self.w.line("break")
        for j, f in enumerate(inner):
            entry = (flag, action if j == 0 else "break-on")
            if entry not in f.after:
                f.after.append(entry)

    def innermost(self, kind: str) -> Frame | None:
        for f in reversed(self.frames):
            if f.kind == kind:
                return f
        return None

    # -- statements -----------------------------------------------------------------------------------------

    def stmt(self, s: A.Stmt) -> None:
        w = self.w
        w.gpl_line = s.span.line
        w.comments(s.leading_comments)
        start = w.mark()
        begun = w.begin_statement()
        visit = _STMT_VISIT.get(type(s))
        if visit is None:  # a gap in gpl2py: GPL9000 at the statement, never a statement dropped
            raise InternalError(s.span, f"no lowering for the statement {type(s).__name__}")
        outer_stmt, self.current = self.current, s
        if not self.kept_error(s):
            visit(self, s)
        self.current = outer_stmt
        detail = w.too_deep(begun, "loop and Try blocks of one procedure")
        if detail is not None:
            self.too_deep(s, start, detail)
        w.end_statement(begun)
        w.trailing(s.trailing_comment, start)

    def kept_error(self, s: A.Stmt) -> bool:
        """Code that keeps an error raises it when the program reaches its line (gpl2py/kept.py):
        a statement without blocks of its own with an error on one of its lines is the raising
        call alone (returns True); a statement with blocks raises before it runs when its first
        line has an error, and its blocks are lowered as usual (a GoTo may enter them).  A label
        stays what it is, the target of a GoTo."""
        if isinstance(s, A.Label) or not self.ctx.kept.any():
            return False
        simple = not child_blocks(s)
        if not self.ctx.kept.on_lines(s.span, whole=simple):
            return False
        self.w.line(self.fault(s))
        return simple

    def too_deep(self, s: A.Stmt, start: int, detail: str) -> None:
        """``s`` is the innermost statement whose Python would nest deeper than CPython compiles
        (emit.MAX_INDENT, emit.MAX_BLOCKS): an error at it, and in its place the call that raises
        the error when reached (gpl2py/kept.py), so that code which keeps the error compiles."""
        self.sink.report(M.NESTED_TOO_DEEPLY, s.span, detail=detail)
        self.too_deep_seen = True
        self.w.discard_since(start)
        self.w.line(self.fault(s))

    def s_misplaced(self, s: A.Stmt) -> None:
        """A line of a procedure body the parser reported -- a declaration that cannot be there, or
        a line it could not read (an ErrorStmt) --: it raises the controller's error for it when
        reached (gpl2py/kept.py)."""
        if not self.model.errors_reported:
            raise InternalError(s.span, f"a {type(s).__name__} inside a procedure body was not reported")
        self.w.line(self.fault(s))

    def s_Label(self, s: A.Label) -> None:
        self.w.line(f"# {s.name}:")

    def s_VarDecl(self, s: A.VarDecl) -> None:
        p = self.proc
        assert p is not None
        if s.compact:
            return  # (simple names: no value to store, and a local's default is the prologue's)
        for d in s.declarators:
            v = self.model.local_of(d, p)
            if v is None:
                continue
            value = self.declarator_value(d, v)
            if value is None:
                continue
            if v.storage == "static":
                name, done = self.static_name(v), self.static_flag(v)
                self.ctx.statics.append((done, "False"))
                self.globals.update({name, done})
                self.w.line(f"if not {done}:")
                self.w.indent()
                self.w.line(f"{name} = {value}")
                self.w.line(f"{done} = True")
                self.w.dedent()
            else:
                target = A.Name(d.span, d.name)
                self.model.info[target] = self.model.info.get(target) or VarInfo(v.type, v)
                self.store(target, value, d.initializer if not d.bounds and d not in self.model.decl_new else None)

    def declarator_value(self, d: A.VarDeclarator, v: VarSym) -> str | None:
        """The value a declaration statement stores (array, New, initializer), or None."""
        if d.bounds and all(b is not None for b in d.bounds):
            elem = v.type.element if isinstance(v.type, t.ArrayType) else t.ERROR
            bounds = [self.val(b) for b in d.bounds if b is not None]
            return f"{self.rt(ARRAYS, 'GplArray')}({', '.join([elem_type_code(elem), *bounds])})"
        new = self.model.decl_new.get(d)
        if new is not None:
            return self.val(new)
        if d.initializer is not None and not d.bounds:
            return self.conv(d.initializer, v.type)[0]
        return None

    def s_Assign(self, s: A.Assign) -> None:
        tt = self.target_type(s.target)
        if s.op == "=":
            value = self.conv(s.value, tt)[0]
            if tt is t.DOUBLE and _may_overflow_double(s.value, self):
                value = self.double_checked(value)
            self.store(s.target, self.checked(s.target, value, s.value), s.value)
            return
        op = s.op[:-1]
        vt = self.type_of(s.value)
        checked = tt is t.DOUBLE and op == "*" and _bound(s.target, self) * _bound(s.value, self) > _SAFE \
            and not _shrinks(s.value)
        if not checked and self.augmented(s.target, op, tt, s.value):
            return
        target = s.target
        if isinstance(target, A.Invoke) and isinstance(self.info(target), IndexInfo):
            target = self.hoist_index(target)
        ti = self.info(target)
        if isinstance(ti, Reached) and ti.receiver is not None and not isinstance(ti.receiver, (A.Name, A.MeExpr)):
            # the object expression is evaluated once (§10.1): GetObj().f += 1
            tmp = self.fresh("t")
            self.w.line(f"{tmp} = {self.val(ti.receiver)}")
            recv = A.Name(ti.receiver.span, tmp)
            self.model.info[recv] = VarInfo(self.type_of(ti.receiver), VarSym(tmp, None, self.type_of(ti.receiver), "temp"))
            target = A.MemberAccess(target.span, recv, getattr(target, "name", ""))
            self.model.info[target] = replace(ti, receiver=recv)
        value = self.binop(op, (*self.expr(target), tt), (*self.expr(s.value), vt), target, s.value)
        code = self.coerce(value, _binary_result(op, tt, vt), tt)[0]
        if checked:
            code = self.double_checked(code)
        self.store(target, self.checked(target, code, A.Binary(s.span, op, target, s.value)))

    def augmented(self, target: A.Expr, op: str, tt: t.GplType, value: A.Expr) -> bool:
        """Emit ``x += v`` / ``x -= v`` / ``x *= v`` for a compound assignment whose plain Python
        operation is exactly GPL's, with no conversion or range check around it: Doubles with
        numbers, Strings joined (``&=``, or ``+=`` of two Strings)."""
        i = self.info(target)
        if not isinstance(i, VarInfo):
            return False
        v = i.sym
        if v.storage not in ("local", "param", "module") or v.boxed or v.byref or not v.read:
            return False
        if v.storage == "module" and (self.ctx.module_prefix(self.ctx.owner_module(v)) or self.shadowed(v)):
            return False
        vt = self.type_of(value)
        if tt is t.DOUBLE and op in ("+", "-", "*") and vt in (t.BYTE, t.SHORT, t.INTEGER, t.SINGLE, t.DOUBLE):
            right = self.val(value)
        elif tt is t.STRING and op == "+" and vt is t.STRING:
            right = self.val(value)
        elif tt is t.STRING and op == "&" and vt not in (t.NOTHING, t.ERROR):
            right, op = self.concat_part(self.expr(value), vt), "+"
        else:
            return False
        if v.storage == "module":
            self.globals.add(py_ident(v.name))
        self.w.line(f"{self.var_code(v, i.receiver)[0]} {op}= {right}")
        return True

    def double_checked(self, value: str) -> str:
        """A Double product that may leave the Double range: checked before the store (-710
        instead of Infinity, §4.4) with an inline test, so the usual path makes no call."""
        tmp = self.fresh("v")
        self.w.line(f"{tmp} = {value}")
        self.w.line(f"if {tmp} - {tmp} != 0.0:  # Infinity or NaN")
        self.w.line(f"    {self.rt(CONV, 'chk_double')}({tmp})")
        return tmp

    def checked(self, target: A.Expr, value: str, source: A.Expr | None = None) -> str:
        """For an Integer stored into a variable or field, check the range inline before the store:
        no call on the usual path (a call costs about three times the store, runtime_speed).
        ``source`` is the GPL expression stored: a sum or difference of two Integer variables or
        literals one of which cannot be negative can leave the range on one side only, and is
        tested on that side."""
        inner = self.int_checks.get(value)
        if inner is None or not isinstance(self.info(target), VarInfo):
            return value
        if self.guarded and self.current in self.guarded:
            return inner  # i = i + 1 right after the loop's test found i below an Integer
        return self.int_checked(inner, source)

    def int_checked(self, inner: str, source: A.Expr | None) -> str:
        """``inner`` (an int expression) range-checked inline for an Integer store, one line:
        ``chk_int32(_v1) if (_v1 := inner) > 2147483647 else _v1`` (the value is stored only
        after the test, as chk_int32(inner) would; see checked).

        A test of one end compares with that end.  A test of both ends compares with
        ±(2**30 - 1) and calls ``chk_int32`` (the exact test) only beyond: CPython 3.11 compares
        two ints below 2**30 in its fast path, larger ones in the general one, which costs as much
        as the rest of a ``total = total + i`` (benchmarks/runtime_speed.py)."""
        chk = self.ctx.alias("chk_int32")
        tmp = self.fresh("v")
        upper, lower = self.overflow_sides(source)
        if upper and lower:
            test = f"(({tmp} := {inner}) > 1073741823 or {tmp} < -1073741823)"
        else:
            test = f"({tmp} := {inner}) {'> 2147483647' if upper else '< -2147483648'}"
        return f"{chk}({tmp}) if {test} else {tmp}"

    def overflow_sides(self, e: A.Expr | None) -> tuple[bool, bool]:
        """Whether the Integer value of ``e`` can pass the upper and the lower end of the range:
        ``a + b`` of two Integers of which one is not negative cannot pass the lower end, and
        ``a - b`` with ``b`` not negative cannot pass the upper one.  Only for variables and
        literals, whose values are in the range (every store is checked); an operation inside
        the expression is not (``v * 2 + 1``: ``v * 2`` may be far below it)."""
        if not (isinstance(e, A.Binary) and e.op in ("+", "-")
                and all(isinstance(x, (A.Name, A.IntegerLiteral)) and self.type_of(x) in _INT_TYPES
                        for x in (e.left, e.right))):
            return True, True
        if e.op == "+" and (self.nonnegative(e.left) or self.nonnegative(e.right)):
            return True, False
        if e.op == "-" and self.nonnegative(e.right):
            return False, True
        return True, True

    def nonnegative(self, e: A.Expr) -> bool:
        """``e`` cannot be negative: a literal, a Byte, or a For counter counting up from zero or
        more (``nonneg``)."""
        if isinstance(e, A.IntegerLiteral):
            return e.value >= 0
        if self.type_of(e) is t.BYTE:
            return True
        i = self.model.info.get(e)
        return isinstance(i, VarInfo) and i.sym in self.nonneg

    def hoist_index(self, e: A.Invoke) -> A.Invoke:
        """Evaluate an element's array and subscripts once for ``a(i) += x`` (§10.1)."""
        simple = all(isinstance(a, (A.Name, A.IntegerLiteral)) for a in e.args) and isinstance(e.target, A.Name)
        if simple:
            return e
        names: list[A.Expr] = []
        for sub in [e.target, *e.args]:
            tmp = self.fresh("t")
            self.w.line(f"{tmp} = {self.val(sub)}")
            n = A.Name(sub.span, tmp)
            self.model.info[n] = VarInfo(self.type_of(sub), VarSym(tmp, None, self.type_of(sub), "temp"))
            names.append(n)
        new = A.Invoke(e.span, names[0], names[1:])
        self.model.info[new] = self.info(e)
        return new

    def s_CallStmt(self, s: A.CallStmt) -> None:
        i = self.model.info.get(s.expr)
        if isinstance(i, BuiltinMemberInfo) and i.sym.action:
            # a built-in member whose statement form acts (Robot.RapidDecel(1) stops robot 1)
            args = s.expr.args if isinstance(s.expr, A.Invoke) else []
            self.w.line(self.builtin_member(i, s.expr, args, statement=True)[0])
            return
        self.w.line(self.val(s.expr))

    def entered_cond(self, s: A.Stmt, body: A.Block | None, c: Code) -> str:
        """A branch condition of a statement a GoTo may enter: the entered branch is taken without
        testing, the others are skipped while entering."""
        flag = self.entry_flag.get(s)
        if flag is None:
            return c[0]
        if self.plan is not None and self.plan.entered.get(s) is body:
            return f"{flag} or {paren(c, P_OR + 1)}"
        return f"not {flag} and {paren(c, P_AND + 1)}"

    def s_If(self, s: A.If) -> None:
        self.w.line(f"if {self.entered_cond(s, s.then_body, self.cond(s.condition))}:")
        self.branch(s.then_body)
        for ei in s.elseifs:
            self.w.gpl_line = ei.span.line
            self.w.comments(ei.leading_comments)
            start = self.w.mark()
            self.w.line(f"elif {self.entered_cond(s, ei.body, self.cond(ei.condition))}:")
            self.w.trailing(ei.trailing_comment, start)
            self.branch(ei.body)
        if s.else_body is not None:
            self.w.line("else:")
            self.branch(s.else_body)
        if s.end_comment is not None:
            self.w.comments([s.end_comment])

    def branch(self, body: A.Block) -> None:
        if body.header_comment is not None:
            self.w.lines[-1].attach(_ctext(body.header_comment))
        self.w.indent()
        self.block(body)
        self.w.dedent()

    def loop_body(self, body: A.Block, frame: Frame, head: list[str] | None = None,
                  tail: list[str] | None = None) -> None:
        self.w.indent(BLOCKS["loop"])
        self.frames.append(frame)
        for line in head or []:
            self.w.line(line)
        start = self.w.mark()
        self.block(body)
        for line in tail or []:
            self.w.line(line)
        self.w.ensure_body(start)
        self.frames.pop()
        self.w.dedent()
        self.after(frame)

    def paced_loop(self) -> None:
        """The header of a While or Do loop: ``for _ in paced():``, endless, each turn one
        checkpoint of the thread's slice taken in C by the ``for`` itself (gplrt.threads.paced;
        docs/design/lowering.md, "Loops and other threads"); the loop's test is an ``if ...:
        break`` in its body."""
        self.w.line(f"for _ in {self.rt(THREADS, 'paced')}():")

    def loop_exit(self, s: A.While | A.DoLoop, condition: A.Expr, until: bool, body: A.Block | None) -> list[str]:
        """``if <exit>: break``, the test of a While or Do loop: the loop ends when ``condition``
        is true (``until``) or false; ``body`` is given for a test at the top of the body.  A
        literal test that never ends the loop (``While True``, ``Loop Until False``) is none."""
        if isinstance(condition, A.BooleanLiteral) and condition.value != until:
            return []
        if body is not None and s not in self.entry_flag and self.plan is not None and self.plan.dispatch(body) is None:
            first = guarded_increment(condition, until, body, self.model.info)
            if first is not None:
                self.guarded.add(first)
        if body is not None and s in self.entry_flag:  # entered by a GoTo: the first turn does not test
            c = self.cond(condition)
            stay: Code = negation(c) if until else c
            entering = self.plan is not None and self.plan.entered.get(s) is body
            exit_test = negation((self.entered_cond(s, body, stay), P_OR if entering else P_AND))
        else:
            exit_test = self.cond(condition) if until else self.negated_cond(condition)
        return [f"if {exit_test[0]}:", "    break"]

    def s_While(self, s: A.While) -> None:
        self.paced_loop()
        self.loop_body(s.body, Frame("While", block=s.body), self.loop_exit(s, s.condition, False, s.body))

    def s_DoLoop(self, s: A.DoLoop) -> None:
        self.paced_loop()
        if s.condition is None:
            self.loop_body(s.body, Frame("Do", block=s.body))
        elif s.test_at_top:
            self.loop_body(s.body, Frame("Do", block=s.body), self.loop_exit(s, s.condition, s.until, s.body))
        else:
            self.loop_body(s.body, Frame("Do"), tail=self.loop_exit(s, s.condition, s.until, None))

    def s_For(self, s: A.For) -> None:
        vt = self.type_of(s.var)
        vi = self.info(s.var)
        v = vi.sym if isinstance(vi, VarInfo) else None
        step_lit = _int_literal(s.step) if s.step is not None else 1
        fast = (isinstance(v, VarSym) and v.storage in ("local", "param") and not v.boxed and not v.byref
                and vt is t.INTEGER and step_lit in (1, -1)
                and self.type_of(s.start) in (t.INTEGER, t.SHORT, t.BYTE)
                and self.type_of(s.end) in (t.INTEGER, t.SHORT, t.BYTE)
                and not _writes_or_leaves(s.body, v.name.lower()))
        if fast:
            assert isinstance(v, VarSym)
            self.range_for(s, v, step_lit)  # type: ignore[arg-type]
            return
        self.store(s.var, self.conv(s.start, vt)[0])
        end = self.once(s.end, s.body, force=True)
        step = "1" if s.step is None else self.once(s.step, s.body, force=True)
        cur = self.val(s.var)
        if step_lit is not None and step_lit >= 0 or _pos_real(s.step):
            test = f"{cur} <= {end}"
        elif step_lit is not None or _neg_real(s.step):
            test = f"{cur} >= {end}"
        else:
            test = f"({cur} <= {end} if {step} >= 0 else {cur} >= {end})"
        self.w.line(f"while {test}:")
        frame = Frame("For")
        self.w.indent(BLOCKS["loop"])
        self.frames.append(frame)
        mark = self.w.mark()
        self.block(s.body)
        inc = self.binop("+", (*self.expr(s.var), vt), (step, P_ATOM, self.type_of(s.step) if s.step else t.INTEGER))
        res = _binary_result("+", vt, self.type_of(s.step) if s.step else t.INTEGER)
        self.store(s.var, self.coerce(inc, res, vt)[0])
        self.w.line(f"{self.rt(THREADS, 'checkpoint')}()")  # as While loops: a scheduling point
        self.w.ensure_body(mark)
        self.frames.pop()
        self.w.dedent()
        self.after(frame)

    def range_for(self, s: A.For, v: VarSym, step: int) -> None:
        """A For over an Integer local with Step 1 or -1 whose body neither writes the counter nor
        leaves early: ``for i in paced_range(a, b + 1):``.  ``paced_range`` (gplrt.threads) is a
        ``range`` that gives the other GPL threads their turn every 1024 iterations, without a
        call per iteration; a loop of fewer literal steps is a plain ``range``.  The counter holds
        the first value past the end afterwards (§10.3) only where something reads it there."""
        name = self.local_name(v)
        final = self.read_past_loops(v)
        lo, hi = _int_literal(s.start), _int_literal(s.end)
        if final:  # the bounds are used again after the loop: evaluated once, into temporaries
            start, end = self.once(s.start, s.body), self.once(s.end, s.body)
            stop = str(hi + step) if hi is not None else f"{end} {'+' if step > 0 else '-'} 1"
        else:  # range() evaluates each once, in order, as For does (§10.3)
            start = self.val(s.start)
            stop = str(hi + step) if hi is not None else self.range_stop(s.end, step)
        tail = ", -1" if step == -1 else ""
        few = lo is not None and hi is not None and abs(hi - lo) < PACE
        loop = "range" if few else self.rt(THREADS, "paced_range")
        self.w.line(f"for {name} in {loop}({start}, {stop}{tail}):")
        if step == 1 and lo is not None and lo >= 0:
            self.nonneg.add(v)  # a subscript that cannot be negative (lower/expressions.py)
        self.loop_body(s.body, Frame("For"))
        if v not in self.counters:
            self.nonneg.discard(v)
        if final:
            if lo is not None and hi is not None:  # For ii = 1 To 80: ii = 81
                past = str(max(lo, hi + step) if step == 1 else min(lo, hi + step))
            else:
                past = f"{'max' if step == 1 else 'min'}({start}, {stop})"
            self.w.line(f"{name} = {past}  # the first value past the end (§10.3)")

    def range_stop(self, e: A.Expr, step: int) -> str:
        """The stop of ``range`` for a For ending at ``e``: ``n`` for ``To n - 1`` (``For i = 0 To
        count - 1`` is ``range(0, count)``), else ``end + 1`` (``end - 1`` stepping down)."""
        back = "-" if step > 0 else "+"
        if isinstance(e, A.Binary) and e.op == back and isinstance(e.right, A.IntegerLiteral) \
                and 1 <= e.right.value < 2**31 and self.type_of(e.left) in (t.INTEGER, t.SHORT, t.BYTE):
            k = e.right.value - 1
            left = self.expr(e.left)
            return left[0] if k == 0 else f"{paren(left, P_ADD)} {back} {k}"
        return f"{paren(self.expr(e), P_ADD)} {'+' if step > 0 else '-'} 1"

    def once(self, e: A.Expr, body: A.Block, force: bool = False) -> str:
        """A For bound: evaluated once (§10.3) -- a temporary unless it is a literal or a local the
        body never writes."""
        if isinstance(e, (A.IntegerLiteral, A.RealLiteral)):
            return self.val(e)
        i = self.info(e)
        if isinstance(e, A.Name) and isinstance(i, VarInfo) and i.sym.storage in ("local", "param") \
                and not i.sym.boxed and not i.sym.byref and not _writes_or_leaves(body, e.name.lower(), exits=False):
            return self.val(e)
        tmp = self.fresh("end" if not force else "v")
        self.w.line(f"{tmp} = {self.val(e)}")
        return tmp

    def s_ForEach(self, s: A.ForEach) -> None:
        vi = self.info(s.var)
        v = vi.sym if isinstance(vi, VarInfo) else None
        if isinstance(v, VarSym) and v.storage in ("local", "param") and not v.boxed and not v.byref:
            self.w.line(f"for {self.local_name(v)} in {self.val(s.collection)}:")
            self.loop_body(s.body, Frame("For", block=s.body))
            return
        tmp = self.fresh("item")
        self.w.line(f"for {tmp} in {self.val(s.collection)}:")
        self.w.indent(BLOCKS["loop"])
        self.store(s.var, tmp)
        self.w.dedent()
        self.loop_body(s.body, Frame("For", block=s.body))

    def s_Select(self, s: A.Select) -> None:
        st = self.type_of(s.subject)
        sel = self.fresh("sel")
        if s in self.entry_flag:  # entered by a GoTo: the match value is not evaluated
            self.w.line(f"if not {self.entry_flag[s]}:")
            self.w.line(f"    {sel} = {self.val(s.subject)}")
        else:
            self.w.line(f"{sel} = {self.val(s.subject)}")
        frame: Frame | None = None
        if _has_exit(s, "Select"):
            frame = Frame("Select")
            self.w.line("while True:")
            self.w.indent(BLOCKS["loop"])
            self.frames.append(frame)
        first = True
        for c in s.cases:
            self.w.gpl_line = c.span.line
            self.w.comments(c.leading_comments)
            mark = self.w.mark()
            if c.is_else:
                if first:
                    self.w.line("if True:")
                else:
                    self.w.line("else:")
            else:
                tests = [paren(self.case_test(sel, st, item), P_OR + 1) for item in c.items]
                test = self.entered_cond(s, c.body, (" or ".join(tests), P_OR))
                self.w.line(f"{'if' if first else 'elif'} {test}:")
            self.w.trailing(c.trailing_comment, mark)
            first = False
            self.w.indent()
            self.block(c.body)
            self.w.dedent()
            if c.is_else:
                # nothing after Case Else is reachable; the parser has already reported a Case
                # that follows it, and --keep-going output must still be Python
                break
        self.w.comments(s.end_comments)
        if frame is not None:
            self.w.line("break")
            self.frames.pop()
            self.w.dedent()
            self.after(frame)

    def case_test(self, sel: str, st: t.GplType, item: A.Node) -> Code:
        subject = (sel, P_ATOM, st)
        if isinstance(item, A.CaseValue):
            v = self.conv(item.value, st)
            return self.binop("=", subject, (*v, st if st is not t.ERROR else self.type_of(item.value)))
        if isinstance(item, A.CaseRange):
            lo = self.conv(item.low, st)
            hi = self.conv(item.high, st)
            a = self.binop(">=", subject, (*lo, st))
            b = self.binop("<=", subject, (*hi, st))
            return f"{paren(a, P_AND + 1)} and {paren(b, P_AND + 1)}", P_AND
        assert isinstance(item, A.CaseIs)
        v = self.conv(item.value, st)
        return self.binop(item.op, subject, (*v, st))

    def s_Try(self, s: A.Try) -> None:
        assert self.plan is not None
        retry = s in self.plan.retry_tries
        if retry and s.body in self.state_var:
            self.w.line(f"{self.state_var[s.body]} = 0")
        if s.catch is None and s.finally_ is None:  # the parser reported it: keep the body
            self.block(s.body)
            return
        if retry:
            self.framed_try(s)
            return
        # One try statement: except and finally share it.  ``Exit Try`` raises ExitTry, which the
        # statement's own first ``except`` clause ends (Finally runs as on any way out), so leaving
        # loops nested in the body needs no flags.  From the Catch body, the handler's own ``try``
        # ends it (a raise there would bypass the sibling clause).
        both = s.catch is not None and s.finally_ is not None
        self.w.line("try:")
        self.w.indent(BLOCKS["try+finally" if both else "try"])
        self.exit_try.append(None)
        self.block(s.body)
        self.exit_try.pop()
        self.w.dedent()
        if _exits(s.body, "Try"):
            self.w.line(f"except {self.rt(EXC, 'ExitTry')}:")
            self.w.line("    pass")
        self.catch(s, BLOCKS["except+finally" if both else "except"])
        self.finally_(s)

    def framed_try(self, s: A.Try) -> None:
        """A Try re-entered by a retry GoTo from its Catch: ``try: while True: try/except ...
        break finally: ...``; the GoTo ``continue``s the loop (Finally does not run between
        attempts) and an ``Exit Try`` ``break``s it."""
        if s.finally_ is not None:
            self.w.line("try:")
            self.w.indent(BLOCKS["try"])
        self.w.line("while True:")
        self.w.indent(BLOCKS["loop"])
        frame = Frame("Try")
        self.frames.append(frame)
        self.exit_try.append(frame)
        if s.catch is None:
            self.block(s.body)
        else:
            self.w.line("try:")
            self.w.indent(BLOCKS["try"])
            self.block(s.body)
            self.w.dedent()
            self.catch(s, BLOCKS["except"], framed=True)
        self.exit_try.pop()
        self.w.line("break")
        self.frames.pop()
        self.w.dedent()
        self.after(frame)
        if s.finally_ is not None:
            self.w.dedent()
            self.finally_(s)

    def clause_header(self, clause: A.CatchClause | A.FinallyClause, header: str) -> None:
        """The header line of a Try clause, mapped to the clause's GPL line with its comments."""
        self.w.gpl_line = clause.span.line
        self.w.comments(clause.leading_comments)
        mark = self.w.mark()
        self.w.line(header)
        self.w.trailing(clause.trailing_comment, mark)

    def catch(self, s: A.Try, blocks: int, framed: bool = False) -> None:
        c = s.catch
        if c is None:
            return
        self.clause_header(c, "except BaseException as _e:")
        self.w.indent(blocks)
        exc = f"{self.rt(EXC, 'as_gpl_exception')}(_e)"
        ref = self.model.catch_var.get(c)
        if ref is not None and ref in self.model.info:
            self.store(ref, exc)
        else:
            self.w.line(exc)
        if framed or not _exits(c.body, "Try"):
            self.block(c.body)  # (a framed Try's Exit Try breaks its loop from here too)
        else:
            self.w.line("try:")
            self.w.indent(BLOCKS["try"])
            self.exit_try.append(None)
            self.block(c.body)
            self.exit_try.pop()
            self.w.dedent()
            self.w.line(f"except {self.rt(EXC, 'ExitTry')}:")
            self.w.line("    pass")
        self.w.dedent()

    def finally_(self, s: A.Try) -> None:
        f = s.finally_
        if f is None:
            return
        self.clause_header(f, "finally:")
        self.w.indent(BLOCKS["finally"])
        self.block(f.body)
        self.w.dedent()
        if s.end_comment is not None:
            self.w.comments([s.end_comment])

    def s_GoTo(self, s: A.GoTo) -> None:
        assert self.plan is not None
        j = self.plan.jumps.get(s)
        if j is None:  # a jump to no label, or one that is not permitted (reported)
            self.w.line(self.fault(s))
            return
        label = j.states[-1][1]
        if isinstance(label, A.Label) and label in self.plan.exits:
            self.exit_tail(self.plan.exits[label])  # GoTo _exit: the statement the label leads to
            return
        pre = [f"{self.state_var[b.block]} = {self.plan.segment(b, st)}" for b, st in j.states
               if b.block in self.state_var]
        if j.retry_try is not None and j.retry_try.body not in self.state_var:
            # the attempt starts at the top of the Try body, which has no dispatch loop (and so no
            # checkpoint of its own): the retry loop's back-edge is a scheduling point
            pre.append(f"{self.rt(THREADS, 'checkpoint')}()")
        pre += [f"{self.entry_flag[st]} = True" for st in j.entries]
        if j.restart.block in self.plan.tails:
            # to the labels that end a loop body: the next iteration (a While or Do loop's next
            # turn is its scheduling point, as for its own back-edge)
            frame = next(f for f in reversed(self.frames) if f.block is j.restart.block)
        elif j.retry_try is not None:
            frame = next(f for f in reversed(self.frames) if f.kind == "Try")
        else:
            frame = next(f for f in reversed(self.frames) if f.kind == "dispatch" and f.block is j.restart.block)
        self.jump(frame, "continue", pre)

    def exit_tail(self, end: A.Stmt | None) -> None:
        """What a jump to the procedure's exit labels does: their Return or Exit, else what the
        end of the procedure does (``gpl2py.gpl.lower.goto``, ``GotoPlan.exits``)."""
        p = self.proc
        assert p is not None
        if isinstance(end, A.Return):
            self.s_Return(end)
        elif isinstance(end, A.Exit):
            self.s_Exit(end)
        elif p.kind == "Function":
            self.w.line("return _result" if p.uses_result else f"return {default_code(p.result)}")
        else:
            self.w.line("return")

    def s_Exit(self, s: A.Exit) -> None:
        p = self.proc
        assert p is not None
        if s.kind in ("Sub", "Property"):
            if p.kind == "Get" and p.prop is not None:
                self.w.line(f"return {default_code(p.prop.type)}")
            else:
                self.w.line("return")
            return
        if s.kind == "Function":
            self.w.line("return _result" if p.uses_result else f"return {default_code(p.result)}")
            return
        if s.kind == "Try" and self.exit_try and self.exit_try[-1] is None:
            self.w.line(f"raise {self.rt(EXC, 'ExitTry')}")  # ends the Try statement (s_Try)
            return
        frame = self.innermost(s.kind)
        if frame is None:
            self.w.line("pass")
            return
        self.jump(frame, "break", [])

    def s_Return(self, s: A.Return) -> None:
        p = self.proc
        assert p is not None
        if s.value is None:
            self.w.line("return")
            return
        if p.kind == "Function":
            value = self.conv(s.value, p.result)[0]
            inner = self.int_checks.get(value)
            if inner is not None:  # (inline, as for a store: checked)
                value = self.int_checked(inner, s.value)
            self.w.line(f"return {value}")
        elif p.kind == "Get" and p.prop is not None:
            self.w.line(f"return {self.conv(s.value, p.prop.type)[0]}")
        else:
            self.w.line(f"return {self.val(s.value)}")

    def s_Throw(self, s: A.Throw) -> None:
        self.w.line("raise" if s.value is None else f"raise {self.val(s.value)}")

    def s_ReDim(self, s: A.ReDim) -> None:
        tt = self.type_of(s.target)
        elem = tt.element if isinstance(tt, t.ArrayType) else t.ERROR
        bounds = [self.val(b) for b in s.bounds]
        helper = self.rt(ARRAYS, "redim_preserve" if s.preserve else "redim")
        self.store(s.target, f"{helper}({', '.join([self.val(s.target), elem_type_code(elem), *bounds])})")


# -- helpers ---------------------------------------------------------------------------------------


_SAFE = 1e300  # a magnitude bound below this cannot overflow in one more + or -
_INT_BOUND = 2.0**31


def _bound(e: A.Expr, low: ExprLowerer, memo: dict[int, float] | None = None) -> float:
    """An upper bound of ``abs(e)`` from its static types (``inf`` when unknown): Integer values
    are below 2**31, Sin/Cos below 1, a square root of any Double below 1.4e154.

    Operators are bounded bottom-up with an explicit stack, not by recursion: a product over
    thousands of continued lines is a left-leaning tree as deep as it is long.  ``memo`` (by node
    id) keeps the bounds of every operator visited, so a caller asking about each node of a chain
    in turn does linear work, not quadratic."""
    memo = {} if memo is None else memo
    stack: list[tuple[A.Expr, bool]] = [(e, False)]
    while stack:
        node, children_done = stack.pop()
        if id(node) in memo:
            continue
        if not _is_operator(node, low):
            memo[id(node)] = _leaf_bound(node, low)
        elif not children_done:
            stack.append((node, True))
            kids = [node.operand] if isinstance(node, A.Unary) else [node.left, node.right]  # type: ignore
            stack.extend((k, False) for k in kids if id(k) not in memo)
        elif isinstance(node, A.Unary):
            memo[id(node)] = memo[id(node.operand)]
        else:
            assert isinstance(node, A.Binary)
            memo[id(node)] = _fold_bound(node, memo[id(node.left)], memo[id(node.right)])
    return memo[id(e)]


def _is_operator(e: A.Expr, low: ExprLowerer) -> bool:
    """Whether :func:`_bound` derives ``e``'s bound from its operands (an Integer-typed operator
    is bounded by its type alone)."""
    return isinstance(e, (A.Unary, A.Binary)) and low.type_of(e) not in (t.BYTE, t.SHORT, t.INTEGER, t.BOOLEAN)


def _fold_bound(e: A.Binary, a: float, b: float) -> float:
    """The bound of ``e`` from the bounds ``a`` and ``b`` of its operands."""
    import math

    if e.op in ("+", "-"):
        return a + b
    if e.op == "*":
        return a * b if a and b else 0.0
    if e.op == "/" and isinstance(e.right, (A.IntegerLiteral, A.RealLiteral)) and e.right.value:
        return a / abs(float(e.right.value))
    return math.inf


def _leaf_bound(e: A.Expr, low: ExprLowerer) -> float:
    """The bound of an operand that is not an operator: a literal, an integer value, a Math call."""
    import math

    if isinstance(e, (A.IntegerLiteral, A.RealLiteral)):
        return abs(float(e.value))
    if low.type_of(e) in (t.BYTE, t.SHORT, t.INTEGER, t.BOOLEAN):
        return _INT_BOUND
    i = low.model.info.get(e)
    if isinstance(i, BuiltinMemberInfo) and i.owner.name == "Math":
        if i.sym.name in ("Sin", "Cos"):
            return 1.0
        if i.sym.name in ("Atan", "Atan2"):
            return 4.0
        if i.sym.name == "Sqrt":
            return 1.4e154
    return math.inf


def _shrinks(e: A.Expr) -> bool:
    """A literal factor of magnitude at most 1 (``x * 0.9``): the product is no larger than the
    other factor, which is a finite Double already, so it cannot overflow."""
    if isinstance(e, A.Unary) and e.op == "-":
        e = e.operand
    return isinstance(e, (A.IntegerLiteral, A.RealLiteral)) and abs(float(e.value)) <= 1.0


def _may_overflow_double(e: A.Expr, low: ExprLowerer) -> bool:
    """Whether a Double value stored from ``e`` needs the overflow check: it contains a product
    whose bound is unknown (sums and differences overflow only from operands that are already
    beyond half the range -- values that a checked product or the runtime produced first)."""
    memo: dict[int, float] = {}
    stack: list[A.Node] = [e]
    while stack:
        n = stack.pop()
        if isinstance(n, A.Binary) and n.op == "*" and _bound(n, low, memo) > _SAFE \
                and not (_shrinks(n.left) or _shrinks(n.right)):
            return True
        if isinstance(n, A.Chain) and A.CHAIN_CODES["*"] in n.ops:
            return True  # (a product in a chain of CHAIN_MIN operators: not worth bounding)
        if isinstance(n, (A.Binary, A.Unary, A.Chain)):
            stack.extend(n.children())
    return False


def _names_in(node: A.Node) -> set[str]:
    out: set[str] = set()
    stack: list[A.Node] = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, A.Name):
            out.add(n.name.lower())
        stack.extend(n.children())
    return out


def _reads_outside_own_loops(body: A.Node) -> set[str]:
    """The names ``body`` mentions outside the bodies of the For loops counting with them (and
    outside those loops' own ``For v =`` / ``Next v``): where a range loop's final value could be
    seen.  A For nested in a For over the same name counts as seen (the outer body reads it)."""
    out: set[str] = set()
    stack: list[tuple[A.Node, frozenset[str]]] = [(body, frozenset())]
    while stack:
        n, inside = stack.pop()
        if isinstance(n, A.For):
            counter = n.var.name.lower() if isinstance(n.var, A.Name) else None
            if counter in inside:
                out.add(counter)  # type: ignore[arg-type]
            stack.extend((c, inside) for c in (n.start, n.end, n.step) if c is not None)
            if counter is None:
                stack.append((n.var, inside))  # an element or field counter: its parts are read
            stack.append((n.body, inside | {counter} if counter is not None else inside))
            continue
        if isinstance(n, A.Name) and n.name.lower() not in inside:
            out.add(n.name.lower())
        stack.extend((c, inside) for c in n.children())
    return out


def _falls_through(block: A.Block) -> bool:
    """Whether control can reach the end of ``block`` (conservative: True when unsure).

    A Function whose body ends in Return/Throw, or in an If/Select whose every branch does, needs
    no ``return <default>`` after it: that line would be unreachable.
    """
    if not block.statements:
        return True
    last = block.statements[-1]
    if isinstance(last, (A.Return, A.Throw)):
        return False
    if isinstance(last, A.Exit) and last.kind in ("Function", "Sub", "Property"):
        return False
    if isinstance(last, A.If) and last.else_body is not None:
        bodies = [last.then_body, *(ei.body for ei in last.elseifs), last.else_body]
        return any(_falls_through(b) for b in bodies)
    if isinstance(last, A.Select) and any(c.is_else for c in last.cases) and not _has_exit(last, "Select"):
        return any(_falls_through(c.body) for c in last.cases)
    if isinstance(last, A.Try) and not _has_exit(last, "Try"):
        # a Try whose body and Catch both return (or whose Finally does) ends the procedure
        if last.finally_ is not None and not _falls_through(last.finally_.body):
            return False
        return _falls_through(last.body) or (last.catch is not None and _falls_through(last.catch.body))
    return True


def _jumps(node: A.Node) -> bool:
    """Whether ``node`` is or contains a GoTo or a label (control that is not straight-line)."""
    stack: list[A.Node] = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, (A.GoTo, A.Label)):
            return True
        stack.extend(n.children())
    return False


def _assigned_before_use(p: ProcSym) -> set[VarSym]:
    """Unboxed locals that the procedure's leading straight-line statements assign with ``=``
    before anything reads them: they need no default at entry (the default would be dead)."""
    decl = p.decl
    if decl is None:
        return set()
    read: set[str] = set()
    out: set[VarSym] = set()
    for s in decl.body.statements:
        targets: list[tuple[str, A.Expr | None]] = []
        if isinstance(s, A.Assign) and s.op == "=" and isinstance(s.target, A.Name):
            targets.append((s.target.name.lower(), s.value))
        elif isinstance(s, A.VarDecl) and s.keyword != "Static":
            for d in s.declarators if not s.compact else ():  # (simple names store nothing)
                if d.initializer is not None and not d.bounds and not d.new:
                    targets.append((d.name.lower(), d.initializer))
                elif (d.bounds and all(b is not None for b in d.bounds)) or d.new:
                    targets.append((d.name.lower(), None))  # allocates: Dim a(3), As New T
                    for b in d.bounds or []:
                        if b is not None:
                            read |= _names_in(b)
                    for a in d.new_args or []:
                        read |= _names_in(a)
        elif isinstance(s, A.For) and isinstance(s.var, A.Name):
            # the loop stores its start value first; its bounds are read before that
            for e in (s.start, s.end, s.step):
                if e is not None:
                    read |= _names_in(e)
            v = p.locals.get(s.var.name.lower())
            if v is not None and v.storage == "local" and not v.boxed and s.var.name.lower() not in read:
                out.add(v)
            break  # the body may read anything
        elif _jumps(s):
            break  # a GoTo could skip a later assignment
        else:
            # any other statement (a call, an If ...): locals are not visible to callees, so only
            # the names it mentions can be read before their first assignment
            read |= _names_in(s)
            continue
        for name, value in targets:
            if value is not None:
                read |= _names_in(value)
            v = p.locals.get(name)
            if v is not None and v.storage == "local" and not v.boxed and name not in read:
                out.add(v)
        if isinstance(s, A.Assign):
            for sub in s.target.children():
                read |= _names_in(sub)
    return out


def guarded_increment(condition: A.Expr, until: bool, body: A.Block, info: Mapping[A.Node, object]) -> A.Assign | None:
    """The first statement of a loop body tested at the top, when it adds 1 to an Integer local
    that the loop's test has just found below an Integer variable or literal (``While i < n``
    then ``i += 1``): the sum is at most ``n``, so it needs no range check.  Locals only (no other
    thread or callee can change them between the test and the store), neither boxed nor ByRef."""
    if not (isinstance(condition, A.Binary) and condition.op in (("<", ">") if not until else (">=", "<="))):
        return None
    below_first = condition.op in ("<", ">=")  # i < n, Until i >= n; else n > i, Until n <= i
    v_side, bound = (condition.left, condition.right) if below_first else (condition.right, condition.left)

    def local(e: A.Expr) -> VarSym | None:
        i = info.get(e)
        if isinstance(i, VarInfo) and i.receiver is None:
            v = i.sym
            if v.storage in ("local", "param") and not v.boxed and not v.byref and v.type is t.INTEGER:
                return v
        return None

    v = local(v_side)
    bi = info.get(bound)
    in_range = (isinstance(bound, A.IntegerLiteral) and bound.value <= 2147483647) or (
        isinstance(bound, A.Name) and isinstance(bi, VarInfo) and bi.sym.type in _INT_TYPES)
    if v is None or not in_range or not body.statements:
        return None
    first = body.statements[0]
    if not (isinstance(first, A.Assign) and local(first.target) is v):
        return None

    def one(e: A.Expr) -> bool:
        return isinstance(e, A.IntegerLiteral) and e.value == 1

    if first.op == "+=" and one(first.value):
        return first
    val = first.value
    if first.op == "=" and isinstance(val, A.Binary) and val.op == "+" and (
            (local(val.left) is v and one(val.right)) or (one(val.left) and local(val.right) is v)):
        return first
    return None


def _untouched(v: VarSym) -> bool:
    """Whether nothing but its plain declaration names local ``v``: never read, assigned or passed
    ByRef, declared without a value.  No code is written for it, so it need not be looked at (a
    ``Dim`` of 26,000 unused names made sets of them all: docs/security.md, "Input size")."""
    d = v.decl
    return (not (v.read or v.assigned or v.boxed) and d is not None
            and d.initializer is None and not d.bounds and not d.new)


def _counters(p: ProcSym, info: Mapping[A.Node, object]) -> set[VarSym]:
    """The procedure's counters: Integer locals that can never be negative, because every store
    into them is a literal that is not negative, itself plus such a literal (``n = n + 1``,
    ``n += 1``), or an ascending ``For`` from such a literal; their default is 0 and an overflow
    stores nothing.  ``i Mod 3`` of a counter is Python's ``%`` (no test of the sign).

    Only locals that are neither Static nor passed ByRef (``boxed``): nothing but the procedure's
    own statements writes them."""
    decl = p.decl
    if decl is None:
        return set()
    cands = {v for v in p.locals.made()  # (one nothing looked up is untouched)
             if v.storage == "local" and not v.boxed and v.type in _INT_TYPES and not _untouched(v)}
    if not cands:
        return set()
    out = set(cands)
    declared = {v.decl: v for v in cands}  # (one look-up per declarator: a Dim can list 60,000 names)

    def target(e: A.Expr | None) -> VarSym | None:
        i = info.get(e) if e is not None else None
        return i.sym if isinstance(i, VarInfo) and i.sym in out else None

    def keeps_sign(v: VarSym, op: str, value: A.Expr | None) -> bool:
        if value is None:
            return False
        if op == "=" and isinstance(value, A.Binary) and value.op == "+":
            parts = (value.left, value.right)
            return (any(target(x) is v for x in parts)
                    and any(isinstance(x, A.IntegerLiteral) and x.value >= 0 for x in parts))
        return op in ("=", "+=") and isinstance(value, A.IntegerLiteral) and value.value >= 0

    for s in _walk_stmts(decl.body):
        if isinstance(s, A.Assign):
            v = target(s.target)
            if v is not None and not keeps_sign(v, s.op, s.value):
                out.discard(v)
        elif isinstance(s, A.For):
            v = target(s.var)
            if v is not None and not (keeps_sign(v, "=", s.start) and (s.step is None or _int_literal(s.step) == 1)):
                out.discard(v)
        elif isinstance(s, A.ForEach):
            v = target(s.var)
            if v is not None:
                out.discard(v)
        elif isinstance(s, A.VarDecl) and not s.compact:  # (simple names: no value stored)
            for d in s.declarators:
                v = declared.get(d)
                if v is not None and v in out and d.initializer is not None and not keeps_sign(v, "=", d.initializer):
                    out.discard(v)
    return out


def _ctext(c: A.Comment) -> str:
    from gpl2py.pywriter.emit import comment_text

    return comment_text(c)


def _binary_result(op: str, lt: t.GplType, rt: t.GplType) -> t.GplType:
    if op == "&":
        return t.STRING
    if op in ("/", "^"):
        return t.DOUBLE
    if op in ("<<", ">>", "\\"):
        return t.INTEGER
    if op == "+" and lt is t.STRING and rt is t.STRING:
        return t.STRING
    if lt.is_integral and rt.is_integral:
        return t.INTEGER
    return t.DOUBLE


_INT_TYPES = (t.BYTE, t.SHORT, t.INTEGER)


def _int_literal(e: A.Expr | None) -> int | None:
    if isinstance(e, A.IntegerLiteral):
        return e.value
    if isinstance(e, A.Unary) and e.op == "-" and isinstance(e.operand, A.IntegerLiteral):
        return -e.operand.value
    return None


def _pos_real(e: A.Expr | None) -> bool:
    return isinstance(e, A.RealLiteral) and e.value >= 0


def _neg_real(e: A.Expr | None) -> bool:
    return isinstance(e, A.Unary) and e.op == "-" and isinstance(e.operand, (A.RealLiteral, A.IntegerLiteral))


def _walk_stmts(block: A.Block):  # type: ignore[no-untyped-def]
    for s in block.statements:
        yield s
        for child in child_blocks(s):
            yield from _walk_stmts(child)


def _writes_or_leaves(body: A.Block, name: str, exits: bool = True) -> bool:
    """Whether the loop body may assign ``name`` or (``exits``) leave the loop early."""
    for s in _walk_stmts(body):
        if exits and isinstance(s, (A.GoTo, A.Label)):
            return True
        if exits and isinstance(s, A.Exit) and s.kind in ("For", "Sub", "Function", "Property", "Try"):
            return True
        if exits and isinstance(s, (A.Return, A.Throw, A.Try)):
            return True
        targets: list[A.Expr] = []
        if isinstance(s, A.Assign):
            targets.append(s.target)
        elif isinstance(s, (A.For, A.ForEach)):
            targets.append(s.var)
        elif isinstance(s, A.ReDim):
            targets.append(s.target)
        for tgt in targets:
            if isinstance(tgt, A.Name) and tgt.name.lower() == name:
                return True
    return False


def _has_exit(s: A.Stmt, kind: str) -> bool:
    """Whether an ``Exit <kind>`` inside ``s`` belongs to ``s`` (not to a nested construct of the
    same kind)."""
    return any(_exits(b, kind) for b in child_blocks(s))


def _exits(block: A.Block, kind: str) -> bool:
    """:func:`_has_exit` for one block.  (A module function: a closure calling itself is a
    reference cycle, which stays in memory until the next garbage collection, and the pipeline
    runs with the collector paused.)"""
    for st in block.statements:
        if isinstance(st, A.Exit) and st.kind == kind:
            return True
        if kind == "Select" and isinstance(st, A.Select):
            continue
        if kind == "Try" and isinstance(st, A.Try):
            continue
        if any(_exits(b, kind) for b in child_blocks(st)):
            return True
    return False


#: The lowering of each kind of statement (ProcLowerer.stmt); a kind without one raises.
_STMT_VISIT: dict[type[A.Stmt], Callable[[ProcLowerer, Any], None]] = {
    A.Label: ProcLowerer.s_Label,
    A.ErrorStmt: ProcLowerer.s_misplaced,
    A.VarDecl: ProcLowerer.s_VarDecl,
    A.Assign: ProcLowerer.s_Assign,
    A.CallStmt: ProcLowerer.s_CallStmt,
    A.If: ProcLowerer.s_If,
    A.While: ProcLowerer.s_While,
    A.DoLoop: ProcLowerer.s_DoLoop,
    A.For: ProcLowerer.s_For,
    A.ForEach: ProcLowerer.s_ForEach,
    A.Select: ProcLowerer.s_Select,
    A.Try: ProcLowerer.s_Try,
    A.GoTo: ProcLowerer.s_GoTo,
    A.Exit: ProcLowerer.s_Exit,
    A.Return: ProcLowerer.s_Return,
    A.Throw: ProcLowerer.s_Throw,
    A.ReDim: ProcLowerer.s_ReDim,
    A.ProcDecl: ProcLowerer.s_misplaced,
    A.PropertyDecl: ProcLowerer.s_misplaced,
    A.DelegateDecl: ProcLowerer.s_misplaced,
    A.ClassDecl: ProcLowerer.s_misplaced,
    A.ModuleDecl: ProcLowerer.s_misplaced,
}

__all__ = ["ProcLowerer", "Frame"]
