"""Expressions -> Python source (docs/design/lowering.md, "Values and types").

Every lowered expression is a ``(code, precedence)`` pair so that parentheses appear only where
Python needs them.  Static types decide the shape: two Doubles add with a plain ``a + b``, an
Integer store from an arithmetic result gets ``chk_int32(...)``, and the runtime is called only
where GPL differs from Python (``\\``, ``Mod``, ``^``, string/number ``+``, Boolean -1, ...).
"""

from __future__ import annotations

import struct
from bisect import bisect_right
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from gpl2py.gpl.lower.context import ModuleContext
from gpl2py.gpl.lower.names import py_float, py_ident
from gpl2py.pywriter.text import py_string
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass
from gpl2py.diagnostics import InternalError
from gpl2py.gpl.semantics.check import Model, nothing_as_string
from gpl2py.gpl.semantics.info import (
    AddressOfInfo,
    BinaryInfo,
    ChainInfo,
    BuiltinConstInfo,
    BuiltinFunctionInfo,
    BuiltinMemberInfo,
    CallInfo,
    DelegateCallInfo,
    DynamicCallInfo,
    DynamicMemberInfo,
    ErrorInfo,
    IndexInfo,
    Info,
    LiteralInfo,
    MeInfo,
    NewInfo,
    NothingInfo,
    ParamInfo,
    PropInfo,
    ResultInfo,
    StubCallInfo,
    StubNameInfo,
    StubNewInfo,
    TypeNameInfo,
    UnaryInfo,
    VarInfo,
)
from gpl2py.gpl.semantics.symbols import ClassSym, DelegateSym, ProcSym, PropSym, VarSym
from gpl2py.gpl.syntax import ast as A

# Python operator precedences (higher binds tighter)
P_TOP, P_IF, P_OR, P_AND, P_NOT, P_CMP = 0, 1, 2, 3, 4, 5
P_BOR, P_BXOR, P_BAND, P_SHIFT, P_ADD, P_MUL, P_UNARY, P_POW, P_ATOM = 6, 7, 8, 9, 10, 11, 12, 13, 15

Code = tuple[str, int]

CONV = "gplrt.lang.conversions"
OPS = "gplrt.lang.operators"
BYREF = "gplrt.lang.byref"
MEMBERS = "gplrt.lang.members"
EXC = "gplrt.lang.exceptions"

_PLAIN_NUM = (t.BYTE, t.SHORT, t.INTEGER, t.SINGLE, t.DOUBLE)
_INTS = (t.BYTE, t.SHORT, t.INTEGER)
_INT_RANGE = {t.INTEGER: (-(2**31), 2**31 - 1), t.SHORT: (-32768, 32767), t.BYTE: (0, 255)}
_INT_OR_BOOL = (t.BYTE, t.SHORT, t.INTEGER, t.BOOLEAN)
_TO_INT = {t.INTEGER: "to_int32", t.SHORT: "to_int16", t.BYTE: "to_uint8"}
_CHK_INT = {t.INTEGER: "chk_int32", t.SHORT: "chk_int16", t.BYTE: "chk_uint8"}
_RUNTIME_CMP = {"=": "eq", "<>": "ne", "<": "lt", ">": "gt", "<=": "le", ">=": "ge"}
_PY_CMP = {"=": "==", "<>": "!=", "<": "<", ">": ">", "<=": "<=", ">=": ">="}
#: The comparison that is true exactly when the key is false, for operands without NaN.
_INVERSE_CMP = {"=": "<>", "<>": "=", "<": ">=", ">": "<=", "<=": ">", ">=": "<"}
_F32 = struct.Struct("f")
# How deep a chain of binary operators may nest in one Python expression (ExprLowerer.binary_chain).
# Measured on CPython 3.11: the compiler gives up near 2,990 nested ``a + b`` at the top of the
# stack but near 284 when the import runs 900 frames deep, and the tokenizer allows only 200 nested
# parentheses (helper calls such as ``idiv(idiv(a, b), c)`` nest one per operator).  100 keeps a 2x
# margin on each while leaving every chain a person would read in the nested form.
LONG_CHAIN = 100
# a run of this many ``&`` operators or more is lowered as one "".join((...)) (ExprLowerer.flat_concat)
FLAT_CONCAT_MIN = LONG_CHAIN


def negation(c: Code) -> Code:
    """``not c``; an operation is parenthesised (``not (a & b)``, ``not (i < n)``): Python's ``not``
    binds looser than any operator, which ``not a & b`` would leave the reader to remember."""
    return f"not {paren(c, P_ATOM)}", P_NOT


def paren(c: Code, min_prec: int) -> str:
    return c[0] if c[1] >= min_prec else f"({c[0]})"


def default_code(typ: t.GplType) -> str:
    """The Python literal for a new variable of ``typ`` (§4.1 defaults)."""
    if typ in _INTS:
        return "0"
    if typ in (t.SINGLE, t.DOUBLE):
        return "0.0"
    if typ is t.BOOLEAN:
        return "False"
    if typ is t.STRING:
        return '""'
    return "None"


def elem_type_code(typ: t.GplType) -> str:
    """The element type argument of GplArray/redim: a primitive's name, else None (Nothing)."""
    if isinstance(typ, t.PrimitiveType):
        return py_string(typ.name)
    return "None"


def annotation(typ: t.GplType) -> str | None:
    if typ in _INTS:
        return "int"
    if typ in (t.SINGLE, t.DOUBLE):
        return "float"
    if typ is t.BOOLEAN:
        return "bool"
    if typ is t.STRING:
        return "str"
    return None


def _round_half_away(x: float) -> int:
    i = int(x)
    f = x - i
    return i + 1 if f >= 0.5 else i - 1 if f <= -0.5 else i


class ExprLowerer:
    """Lowers expressions of one procedure (or of module/class initializers)."""

    def __init__(self, ctx: ModuleContext, proc: ProcSym | None, cls: ClassSym | None) -> None:
        self.ctx = ctx
        self.model: Model = ctx.model
        self.proc = proc
        self.cls = cls
        self.globals: set[str] = set()
        # Integer locals known to be >= 0 where they are used (counters of ascending For loops
        # from a non-negative start that the body never writes)
        self.nonneg: set[VarSym] = set()
        self.chain_temps = 0  # temporaries made for long operator chains (chain_temp)
        self.left_flat = False  # binop's result begins with its left operand unwrapped
        #: the text of each Integer range check made (``chk_int32(x)``) -> its argument (``x``)
        self.int_checks: dict[str, str] = {}
        # the Python locals of the procedure: a global of this module spelled the same (a class
        # ``Station`` in ``Dim Station As New Station``) is reached as ``_this.Station``

    # -- helpers -----------------------------------------------------------------------------------

    def rt(self, module: str, name: str) -> str:
        return self.ctx.helper(module, name)

    def info(self, e: A.Node) -> Info:
        return self.model.info[e]

    def type_of(self, e: A.Expr) -> t.GplType:
        i = self.model.info.get(e)
        return i.type if i is not None else t.ERROR

    def val(self, e: A.Expr) -> str:
        return self.expr(e)[0]

    def sub(self, e: A.Expr, min_prec: int) -> str:
        return paren(self.expr(e), min_prec)

    def call(self, func: str, *args: str) -> Code:
        return f"{func}({', '.join(args)})", P_ATOM

    # -- names of variables -------------------------------------------------------------------------

    def local_name(self, v: VarSym) -> str:
        return py_ident(v.name)

    def static_name(self, v: VarSym) -> str:
        p = v.owner
        parts: list[str] = []
        if isinstance(p, ProcSym):
            owner = p.owner
            if isinstance(owner, ClassSym):
                parts.extend(owner.path)
            if p.kind in ("Get", "Set"):
                parts.append(f"{p.name}{p.kind}")
            elif p.kind == "New":
                parts.extend((p.name, str(p.overload_index)))
            else:
                parts.append(self.ctx.names.overload_py.get(p, p.name))  # one per overload
        parts.append(v.name)
        return self.ctx.static_global(v, "_s_" + "_".join(parts))

    def static_flag(self, v: VarSym) -> str:
        """The module global that says Static ``v``'s initializer has run."""
        return self.ctx.static_global(v, self.static_name(v) + "_done", role="done")

    def var_code(self, v: VarSym, receiver: A.Expr | None) -> Code:
        st = v.storage
        if st == "temp":
            return v.name, P_ATOM
        if st in ("local", "param"):
            n = self.local_name(v)
            if st == "param" and v.byref:
                return f"{n}.value", P_ATOM
            if v.boxed:
                return f"{n}.value", P_ATOM
            return n, P_ATOM
        if st == "static":
            return self.static_name(v), P_ATOM
        if st == "module":
            return self.module_var_ref(v), P_ATOM
        # field
        if v.shared:
            return self.owner_ref(v) + py_ident(v.name), P_ATOM
        recv = "self" if receiver is None else self.sub(receiver, P_ATOM)
        return f"{recv}.{py_ident(v.name)}", P_ATOM

    def class_ref(self, cls: ClassSym | DelegateSym) -> str:
        """How this procedure names a user class or delegate class (``ModuleContext.class_ref``,
        through ``_this`` when a local hides the outermost name)."""
        root: object = cls
        while True:
            outer = root.outer if isinstance(root, ClassSym) else getattr(root, "owner", None)
            if not isinstance(outer, ClassSym):
                break
            root = outer
        return self.unhidden(self.ctx.class_ref(cls), root)

    def owner_ref(self, sym: VarSym | ProcSym | PropSym) -> str:
        """The qualifier of a module-level or Shared member (``""``, ``"mod."``, ``"Cls."``)."""
        if isinstance(sym.owner, ClassSym):
            return self.class_ref(sym.owner) + "."
        return self.ctx.member_owner_ref(sym)

    def unhidden(self, ref: str, root: object, head: str | None = None) -> str:
        """``ref``, a reference that starts with ``head``, the Python name of ``root`` (a global
        of some module; by default ``py_ident`` of its name), or ``_this.<ref>`` when ``root``
        belongs to this module and a local of the procedure has that Python name."""
        head = py_ident(getattr(root, "name", "")) if head is None else head
        if self.ctx.owner_module(root) is self.ctx.mod and self.is_local_py(head):
            self.ctx.needs_this = True
            return "_this." + ref
        return ref

    def is_local_py(self, head: str) -> bool:
        """Whether a local (or parameter) of the procedure has the Python name ``head``.  Asked of
        the few names ``py_ident`` can have come from, not of a set of every local's Python name
        (a ``Dim`` of 26,000 names made one per procedure lowered: docs/security.md, "Input size")."""
        if self.proc is None:
            return False
        spellings = {head}
        if head.startswith("_u_"):
            spellings.add(head[2:])
        if head.endswith("_"):
            spellings.add(head[:-1])
        for name in spellings:
            v = self.proc.locals.get(name.lower())
            if v is not None and v.storage in ("local", "param") and py_ident(v.name) == head:
                return True
        return False

    def module_var_ref(self, v: VarSym) -> str:
        """A module variable; ``_this.name`` when a local of the procedure hides it (§6.4)."""
        prefix = self.ctx.member_owner_ref(v)
        if not prefix and self.proc is not None and v.name.lower() in self.proc.locals:
            self.ctx.needs_this = True
            return "_this." + py_ident(v.name)
        return prefix + py_ident(v.name)

    def shadowed(self, v: VarSym) -> bool:
        return (self.proc is not None and v.storage == "module" and v.name.lower() in self.proc.locals
                and not self.ctx.member_owner_ref(v))

    # -- expressions -------------------------------------------------------------------------------

    def expr(self, e: A.Expr) -> Code:
        """``e`` as Python: dispatched on the class of its meaning (``semantics/info.py``) through
        :data:`_VISIT`.  A meaning without a rule is a gap in gpl2py: :class:`InternalError`
        (GPL9000 at ``e``), never ``None`` in the output."""
        i = self.model.info.get(e)
        if i is None:
            return self.unlowered(e, "no meaning recorded")
        visit = _VISIT.get(type(i))
        if visit is None:  # a name that is not a value (reported, with --keep-going), or a gap
            return self.unlowered(e, f"no lowering for {type(i).__name__}")
        return visit(self, e, i)

    def unlowered(self, e: A.Expr, why: str) -> Code:
        """An expression the analysis could not give a meaning: after an error (kept with
        ``--keep-going`` or ignored) a call that raises the controller's error for it when
        reached (:meth:`fault`); with no error reported, a gap in gpl2py."""
        if self.model.errors_reported:
            return self.fault(e), P_ATOM
        raise InternalError(e.span, f"{why} (a {type(e).__name__} expression)")

    def fault(self, node: A.Node) -> str:
        """The call that raises, when reached, the controller's error for the error reported at
        ``node`` (``compile_error(-729, "GPL2001: 'x' is not declared")``: gpl2py/kept.py).  An
        expression as much as a statement: it never returns."""
        code, subject = self.ctx.kept.at(node.span)
        return f"{self.rt(EXC, 'compile_error')}({code}, {py_string(subject)})"

    # -- one method per kind of meaning (_VISIT) ------------------------------------------------------

    def x_literal(self, e: A.Expr, i: LiteralInfo) -> Code:
        return self.literal(e)

    def x_nothing(self, e: A.Expr, i: NothingInfo) -> Code:
        return "None", P_ATOM

    def x_me(self, e: A.Expr, i: MeInfo) -> Code:
        return "self", P_ATOM

    def x_error(self, e: A.Expr, i: ErrorInfo) -> Code:
        return self.unlowered(e, "an error that was never reported")

    def x_var(self, e: A.Expr, i: VarInfo) -> Code:
        return self.var_code(i.sym, i.receiver)

    def x_result(self, e: A.Expr, i: ResultInfo) -> Code:
        return "_result", P_ATOM

    def x_call(self, e: A.Expr, i: CallInfo) -> Code:
        return self.user_call(i, e.args if isinstance(e, A.Invoke) else [])

    def x_prop(self, e: A.Expr, i: PropInfo) -> Code:
        return self.prop_ref(i.sym, i.receiver), P_ATOM

    def x_index(self, e: A.Expr, i: IndexInfo) -> Code:
        assert isinstance(e, A.Invoke)
        return self.index_code(e), P_ATOM

    def x_bfunc(self, e: A.Expr, i: BuiltinFunctionInfo) -> Code:
        return self.builtin_function(i, e.args if isinstance(e, A.Invoke) else [])

    def x_bconst(self, e: A.Expr, i: BuiltinConstInfo) -> Code:
        return self.ctx.builtin(i.sym.python_name), P_ATOM

    def x_bmember(self, e: A.Expr, i: BuiltinMemberInfo) -> Code:
        return self.builtin_member(i, e, e.args if isinstance(e, A.Invoke) else None)

    def x_delegate_call(self, e: A.Expr, i: DelegateCallInfo) -> Code:
        assert isinstance(e, A.Invoke)
        args = self.args_code(e.args, i.params)
        return f"{self.sub(e.target, P_ATOM)}({', '.join(args)})", P_ATOM

    def x_new(self, e: A.Expr, i: NewInfo) -> Code:
        assert isinstance(e, A.New)
        return self.new_code(e, i)

    def x_addressof(self, e: A.Expr, i: AddressOfInfo) -> Code:
        return self.proc_ref(i.sym, i.receiver), P_ATOM

    def x_typename(self, e: A.Expr, i: TypeNameInfo) -> Code:
        return py_string(str(i.sym)), P_ATOM  # ToBitString(x, Short, ...): the type's name

    def x_stub(self, e: A.Expr, i: StubCallInfo | StubNameInfo | StubNewInfo) -> Code:
        """A use of protected code or of a built-in member the catalogue lacks
        (``gpl2py.gpl.semantics.stubs``): plain Python, since nothing is known to convert; the stub
        raises -204 unless the user supplied it."""
        stub = i.stub
        if stub is None:  # New of a class nothing declares (reported)
            return self.unlowered(e, "a stub without a name")
        args = [self.val(a) for a in e.args] if isinstance(e, (A.Invoke, A.New)) and e.args else []
        ref = self.ctx.stub_ref(stub)
        receiver = i.receiver if isinstance(i, (StubCallInfo, StubNameInfo)) else None
        if stub.builtin is not None and not stub.shared and receiver is not None:
            args.insert(0, self.val(receiver))  # an instance member receives its object first
        if isinstance(i, StubNameInfo) and stub.builtin is None and stub.kind != "procedure":
            return ref, P_ATOM  # a variable of the protected code
        return f"{ref}({', '.join(args)})", P_ATOM

    def x_dynamic_member(self, e: A.Expr, i: DynamicMemberInfo) -> Code:
        # never a raw Python attribute: the runtime admits GPL members only (docs/security.md)
        assert i.receiver is not None
        return self.dynamic_member(i.receiver, i.name), P_ATOM

    def x_dynamic_call(self, e: A.Expr, i: DynamicCallInfo) -> Code:
        """A call of a value of unknown type (``f(1)`` where ``f`` is a stub's value), or of one
        of its members (``obj.Go``)."""
        if isinstance(e, A.Invoke):
            args = [self.val(a) for a in e.args]
            return f"{self.sub(e.target, P_ATOM)}({', '.join(args)})", P_ATOM
        assert isinstance(e, A.MemberAccess)
        return f"{self.dynamic_member(e.target, e.name)}()", P_ATOM

    def x_unary(self, e: A.Expr, i: UnaryInfo) -> Code:
        assert isinstance(e, A.Unary)
        return self.unary(e)

    def x_binary(self, e: A.Expr, i: BinaryInfo) -> Code:
        assert isinstance(e, A.Binary)
        if e.op == "Is":
            return self.identity(e, negate=False)
        return self.binary_chain(e)

    def x_chain(self, e: A.Expr, i: ChainInfo) -> Code:
        assert isinstance(e, A.Chain)
        return self.binary_chain(e)

    def _chains(self, e: A.Expr) -> bool:
        """Whether ``e`` continues a left-leaning operator chain that :meth:`binary_chain` folds."""
        if isinstance(e, A.Chain):
            return isinstance(self.model.info.get(e), ChainInfo)
        if not isinstance(e, A.Binary) or e.op == "Is":
            return False
        return isinstance(self.model.info.get(e), BinaryInfo)

    def binary_chain(self, e: A.Binary | A.Chain) -> Code:
        """Lower ``e`` and the binary operators down its left operand in a loop, not by recursion.

        GPL code continues string building over hundreds of lines (``s = s & "..." & _``); the
        parser gives a left-leaning tree as deep as the chain (or, from ``CHAIN_MIN`` operators
        on, a :class:`~gpl2py.gpl.syntax.ast.Chain`, which :class:`_Steps` reads as the same
        operators), and one Python frame per operator reached the recursion limit near 1,000
        operands.  The leftmost operand is lowered first, then each operator folds in its right
        operand in source order, so the output is what the recursive form gave (Python's
        left-associative operators need no parentheses for it), except that a very long run of
        ``&`` becomes one flat join (:meth:`flat_concat`) and a chain that would nest deeper than
        ``LONG_CHAIN`` is cut into steps (:meth:`chunked`)."""
        spine: list[A.Binary | A.Chain] = [e]
        while self._chains(A.chain_left(spine[-1])):
            spine.append(A.chain_left(spine[-1]))  # type: ignore[arg-type]
        first = A.chain_left(spine[-1])
        acc: Code = self.expr(first)
        acc_type = self.type_of(first)
        steps = _Steps(spine[::-1], self.model.info)
        n = len(steps)
        chunks: list[str] = []  # the finished steps of a long chain, each ``temp := <code>``
        temp = ""
        depth = 0  # how deep ``acc`` nests operators since the last step
        long = steps.not_boolean() > LONG_CHAIN
        wrapped = False  # the last operator put ``acc`` inside a call or parentheses
        left_node: A.Expr = first  # the GPL expression ``acc`` stands for
        at = 0
        while at < n:
            if depth >= LONG_CHAIN or wrapped:
                temp = temp or self.chain_temp()
                chunks.append(f"{temp} := {acc[0]}")
                acc, depth = (temp, P_ATOM), 0
            run = 0
            while at + run < n and steps.op(at + run) == "&":
                run += 1
            if run >= FLAT_CONCAT_MIN:
                acc = self.flat_concat(acc, acc_type, (steps.right(k) for k in range(at, at + run)))
                acc_type = t.STRING
                at += run
                depth += 1
                left_node = steps.node(at - 1)
                continue
            op, right = steps.op(at), steps.right(at)
            if op in ("AndAlso", "OrElse"):
                prec = P_AND if op == "AndAlso" else P_OR
                # Python's and/or are associative like AndAlso/OrElse: a left operand of the same
                # operator needs no parentheses and adds no depth (one flat BoolOp however long)
                cond = self.cond_code(acc, acc_type)
                self.left_flat = (cond is acc or (acc_type in _PLAIN_NUM and acc[1] > P_CMP)) and cond[1] >= prec
                left = paren(cond, prec)
                right_code = paren(self.cond(right), prec + 1)
                acc = (f"{left} and {right_code}", P_AND) if op == "AndAlso" else (f"{left} or {right_code}", P_OR)
            else:
                acc = self.binop(op, (*acc, acc_type), (*self.expr(right), self.type_of(right)), left_node, right)
                depth += 1
            acc_type = steps.type(at)
            left_node = steps.node(at)
            at += 1
            # in a long chain, an operator that wraps the running value (``div(_chain1, x)``,
            # ``(_chain1 == x) == y``) ends its step: one readable line each, no nesting to wrap
            wrapped = long and not self.left_flat
        return self.chunked(chunks, acc)

    def chain_temp(self) -> str:
        """A fresh name for the running value of a long chain (``_chain1``, ``_chain2``, ...): a
        GPL name starting with ``_`` is emitted as ``_u...`` (py_ident), so it cannot meet a
        program's own variable."""
        self.chain_temps += 1
        return f"_chain{self.chain_temps}"

    @staticmethod
    def chunked(chunks: list[str], last: Code) -> Code:
        """A long chain as a tuple of steps that each fold up to ``LONG_CHAIN`` operators into the
        running value, the last one giving the result: ``(_chain1 := a + ... + z, _chain1 + ...)[-1]``.

        Why this form and not a runtime ``fold_left(op, first, *rest)``: the elements of a tuple run
        in order and each step is the nested form's own code, so every operator keeps its exact
        conversions, overflow checks and short-circuits, and operands and operators interleave just
        as in the nested form (a ``1 / 0`` early in the chain raises before a later operand's
        function is called; a fold over pre-evaluated operands would call it first).  The tuple is
        flat for CPython's compiler however many steps it has, and a step nests at most
        ``LONG_CHAIN`` operators; an operator lowered to a helper call is a step of its own
        (``_chain1 := div(_chain1, x)``), so no step nests calls.  A chain of ``AndAlso`` or
        ``OrElse`` stays one ``and``/``or`` expression: Python's BoolOp is flat already."""
        if not chunks:
            return last
        return f"({', '.join([*chunks, last[0]])})[-1]", P_ATOM

    def flat_concat(self, first: Code, first_type: t.GplType, run: Iterable[A.Expr]) -> Code:
        """A long run of ``&`` as one ``"".join((...))`` call instead of nested ``+``.

        CPython's compiler recurses on nested binary operations and gives up near 3,000 operands
        (fewer when the import happens deep in a call stack), while a tuple display is flat.  Short
        chains keep the more readable ``a + b`` form; only a run of at least ``FLAT_CONCAT_MIN``
        operators, which nobody reads operand by operand anyway, takes this form."""
        parts = [self.concat_part(first, first_type)]
        parts += [self.concat_part(self.expr(x), self.type_of(x)) for x in run]
        return f'"".join(({", ".join(parts)}))', P_ATOM

    def concat_part(self, c: Code, typ: t.GplType) -> str:
        """Operand code of ``&`` converted to a String (§4.4: ``&`` converts both sides)."""
        if typ is t.STRING:
            return c[0]
        if typ is t.ERROR:
            return self.call(self.rt(CONV, "to_string"), c[0])[0]
        return self.coerce(c, typ, t.STRING)[0]

    def literal(self, e: A.Expr) -> Code:
        if isinstance(e, A.IntegerLiteral):
            if 0 <= e.value < 2**31 and e.text[:2].lower() == "&h":
                return f"0x{e.value:X}", P_ATOM  # keep the program's hexadecimal spelling
            if -(2**31) <= e.value < 2**31:
                return str(e.value), (P_UNARY if e.value < 0 else P_ATOM)
            return py_float(float(e.value)), P_ATOM
        if isinstance(e, A.RealLiteral):
            return py_float(e.value), (P_UNARY if e.value < 0 else P_ATOM)
        if isinstance(e, A.StringLiteral):
            return py_string(e.value), P_ATOM
        if isinstance(e, A.BooleanLiteral):
            return ("True" if e.value else "False"), P_ATOM
        raise InternalError(e.span, f"a literal {type(e).__name__}")

    # -- conversions ---------------------------------------------------------------------------------

    def conv(self, e: A.Expr, dst: t.GplType) -> Code:
        """``e`` converted to ``dst`` as a store would (§4.2 rule 3)."""
        src = self.type_of(e)
        # constants are folded: a literal, or a negated one (-3100), converted at translation time
        lit: A.Expr = e
        sign = 1
        if isinstance(e, A.Unary) and e.op == "-" and isinstance(e.operand, (A.IntegerLiteral, A.RealLiteral)) \
                and not (isinstance(e.operand, A.IntegerLiteral) and e.operand.text[:2].lower() in ("&h", "&o")):
            lit, sign = e.operand, -1
        if isinstance(lit, A.IntegerLiteral) and dst in _INT_RANGE:
            lo, hi = _INT_RANGE[dst]
            if lo <= sign * lit.value <= hi:
                return str(sign * lit.value), (P_UNARY if sign * lit.value < 0 else P_ATOM)
        if isinstance(lit, (A.IntegerLiteral, A.RealLiteral)):
            number = sign * lit.value
            if dst in _INT_RANGE and isinstance(lit, A.RealLiteral) and abs(number) < 2**62:
                r = _round_half_away(number)
                lo, hi = _INT_RANGE[dst]
                if lo <= r <= hi:
                    return str(r), (P_UNARY if r < 0 else P_ATOM)
            if dst is t.DOUBLE:
                return py_float(float(number)), (P_UNARY if number < 0 else P_ATOM)
            if dst is t.SINGLE:
                try:
                    value = _F32.unpack(_F32.pack(float(number)))[0]
                    if value not in (float("inf"), float("-inf")):  # too large: -710 at run time
                        return py_float(value), (P_UNARY if value < 0 else P_ATOM)
                except OverflowError:
                    pass
        c = self.expr(e)
        return self.coerce(c, src, dst, may_overflow=self.may_overflow(e, dst))

    def may_overflow(self, e: A.Expr, dst: t.GplType) -> bool:
        """Whether storing integer-typed ``e`` into ``dst`` needs a range check at run time.

        An interval analysis over the static types proves most checks unnecessary: in
        ``acc = ((acc * 75 + i) And &H7FFF) + (i \\ 3) - (i >> 2)`` the And is 0..32767 and the
        rest is bounded by Integer's range divided by 3 and 4, so the sum always fits.
        """
        bounds = self.int_interval(e)
        if bounds is None or dst not in _INT_RANGE:
            return _may_overflow(e)
        lo, hi = _INT_RANGE[dst]
        return not (lo <= bounds[0] and bounds[1] <= hi)

    def int_interval(self, e: A.Expr) -> tuple[int, int] | None:
        """Exact bounds of an integer-valued expression from its operands' static types, or None."""
        if isinstance(e, A.IntegerLiteral):
            return (e.value, e.value)
        typ = self.type_of(e)
        if isinstance(e, A.Unary) and e.op == "-":
            inner = self.int_interval(e.operand)
            return None if inner is None else (-inner[1], -inner[0])
        if isinstance(e, (A.Binary, A.Chain)) and typ in _INT_OR_BOOL:
            return self._binary_interval(e)
        if typ is t.BOOLEAN:
            return (-1, 0)
        if typ in _INT_RANGE:
            return _INT_RANGE[typ]
        return None

    def _binary_interval(self, e: A.Binary | A.Chain) -> tuple[int, int] | None:
        """Bounds of an integer operator chain, folded along its left spine in a loop (a sum over
        hundreds of continued lines must not recurse once per operator)."""
        spine: list[A.Binary | A.Chain] = [e]
        while isinstance(A.chain_left(spine[-1]), (A.Binary, A.Chain)) \
                and self.type_of(A.chain_left(spine[-1])) in _INT_OR_BOOL:
            spine.append(A.chain_left(spine[-1]))  # type: ignore[arg-type]
        acc = self.int_interval(A.chain_left(spine[-1]))
        for node in reversed(spine):
            if isinstance(node, A.Binary):
                if acc is None:
                    return None
                acc = self._fold_interval(node.op, acc, self.int_interval(node.right))
                continue
            info = self.model.info.get(node)
            for k in range(len(node.ops)):
                if acc is None:
                    return None
                if k and info.prefix_type(k - 1) not in _INT_OR_BOOL:
                    acc = self.int_interval_of_type(info.prefix_type(k - 1))
                    if acc is None:
                        return None
                x = node.literal(k)
                right = (x, x) if x is not None else self.int_interval(node.operands[k])  # type: ignore[arg-type]
                acc = self._fold_interval(node.op(k), acc, right)
        return acc

    @staticmethod
    def int_interval_of_type(typ: t.GplType) -> tuple[int, int] | None:
        """The bounds of any value of ``typ`` (None: not an integer type)."""
        if typ is t.BOOLEAN:
            return (-1, 0)
        return _INT_RANGE.get(typ)

    @staticmethod
    def _fold_interval(op: str, a: tuple[int, int], b: tuple[int, int] | None) -> tuple[int, int] | None:
        """The bounds of ``a op b`` for one integer operator, or None when they are not known."""
        if b is None:
            return None
        op = op.lower()
        if op == "+":
            return (a[0] + b[0], a[1] + b[1])
        if op == "-":
            return (a[0] - b[1], a[1] - b[0])
        if op == "*":
            products = [x * y for x in a for y in b]
            return (min(products), max(products))
        if op in ("\\", "mod"):  # |a \ b| <= |a| / min|b|; |a Mod b| < |b| and <= |a|
            m = max(abs(a[0]), abs(a[1]))
            if op == "mod":
                m = min(m, max(abs(b[0]), abs(b[1])))
            elif b[0] > 0 or b[1] < 0:  # a divisor that cannot be 0 (0 raises -709 anyway)
                m //= min(abs(b[0]), abs(b[1]))
            return (-m, m)
        if op == ">>":
            if b[0] == b[1] and 0 <= b[0] < 32:
                return (a[0] >> b[0], a[1] >> b[0])
            return (min(a[0], 0), max(a[1], 0))
        if op in ("and", "or", "xor", "<<"):
            if op == "and" and (a[0] >= 0 or b[0] >= 0):  # a non-negative mask bounds the result
                return (0, min(x[1] for x in (a, b) if x[0] >= 0))
            if op in ("or", "xor") and a[0] >= 0 and b[0] >= 0:
                return (0, (1 << max(a[1], b[1]).bit_length()) - 1)
            return _INT_RANGE[t.INTEGER]  # bitwise results are 32-bit (§4.4)
        return None

    def range_checked(self, c: Code, dst: t.GplType) -> Code:
        """``c`` (an int) checked against ``dst``'s range by the runtime's ``chk_*`` call.  An
        Integer check is remembered in :attr:`int_checks` (the call's text -> its argument), so a
        store can test the range inline instead (``ProcLowerer.checked``) without re-reading text."""
        code = self.call(self.rt(CONV, _CHK_INT[dst]), c[0])
        if dst is t.INTEGER:
            self.int_checks[code[0]] = c[0]
        return code

    def coerce(self, c: Code, src: t.GplType, dst: t.GplType, may_overflow: bool = True) -> Code:
        if src is t.NOTHING and dst is t.STRING:
            return '""', P_ATOM  # Nothing stored into a String is "" (docs/design/real-code.md)
        if dst is t.ERROR or src is t.ERROR or not isinstance(dst, t.PrimitiveType):
            return c
        if dst in _INT_RANGE:
            if src is dst:
                if may_overflow:
                    return self.range_checked(c, dst)
                return c
            if src in _INTS:
                lo, hi = _INT_RANGE[dst]
                slo, shi = _INT_RANGE[src]  # type: ignore[index]
                if lo <= slo and shi <= hi and not may_overflow:
                    return c
                return self.range_checked(c, dst)
            if src is t.BOOLEAN and dst is not t.BYTE:
                return self.call(self.rt(CONV, "bool_num"), c[0])
            return self.call(self.rt(CONV, _TO_INT[dst]), c[0])
        if dst is t.DOUBLE:
            if src in (t.DOUBLE, t.SINGLE):
                return c
            if src in _INTS:
                return self.call("float", c[0])
            return self.call(self.rt(CONV, "to_double"), c[0])
        if dst is t.SINGLE:
            if src is t.SINGLE and not may_overflow:
                return c
            return self.call(self.rt(CONV, "to_single"), c[0])
        if dst is t.BOOLEAN:
            if src is t.BOOLEAN:
                return c
            if src in _PLAIN_NUM:
                return f"{paren(c, P_CMP + 1)} != 0", P_CMP
            return self.call(self.rt(CONV, "to_bool"), c[0])
        if dst is t.STRING:
            if src is t.STRING:
                return c
            if src is t.SINGLE:
                return self.call(self.rt(CONV, "to_string_single"), c[0])
            return self.call(self.rt(CONV, "to_string"), c[0])
        return c

    def cond(self, e: A.Expr) -> Code:
        """``e`` as a Python condition (non-zero is True, §4.3)."""
        return self.cond_code(self.expr(e), self.type_of(e))

    def cond_code(self, c: Code, src: t.GplType) -> Code:
        """Already lowered code ``c`` of static type ``src`` as a Python condition."""
        if src is t.BOOLEAN:
            return c
        if src in _PLAIN_NUM:
            return f"{paren(c, P_CMP + 1)} != 0", P_CMP
        return self.call(self.rt(CONV, "to_bool"), c[0])

    def negated_cond(self, e: A.Expr) -> Code:
        """``Not e`` as a Python condition: a loop's exit test.  A comparison of integers, or of two
        Strings, is inverted (``eol < 0`` rather than ``not eol >= 0``): only a NaN tells the two
        apart, and neither type has one; so is ``=`` or ``<>`` of two Booleans.  ``a Is b`` becomes
        ``a is not b``, ``Not a Is b`` ``a is b``, and ``Not x`` of a Boolean or a number the test
        of ``x``."""
        if isinstance(e, A.Binary) and e.op == "Is":
            return self.identity(e, negate=True)
        if isinstance(e, A.Unary) and e.op == "Not":
            if isinstance(e.operand, A.Binary) and e.operand.op == "Is":
                return self.identity(e.operand, negate=False)  # While Not x Is Nothing
            if self.type_of(e.operand) is t.BOOLEAN or self.type_of(e.operand) in _PLAIN_NUM:
                return self.cond(e.operand)  # While Not done: the test is done itself
        if isinstance(e, A.Binary) and e.op in _INVERSE_CMP:
            lt, rt_ = self.type_of(e.left), self.type_of(e.right)
            if ((lt in _INTS and rt_ in _INTS) or (lt is t.STRING and rt_ is t.STRING)
                    or (lt is t.BOOLEAN and rt_ is t.BOOLEAN and e.op in ("=", "<>"))):
                return self.binop(_INVERSE_CMP[e.op], (*self.expr(e.left), lt), (*self.expr(e.right), rt_),
                                  e.left, e.right)
        return negation(self.cond(e))

    # -- operators --------------------------------------------------------------------------------------

    def unary(self, e: A.Unary) -> Code:
        ot = self.type_of(e.operand)
        if e.op == "Not":
            if isinstance(e.operand, A.Binary) and e.operand.op == "Is":  # Not x Is Nothing
                return self.identity(e.operand, negate=True)
            if ot is t.BOOLEAN:
                return f"not {self.sub(e.operand, P_NOT)}", P_NOT
            if ot in _PLAIN_NUM:
                return f"{self.sub(e.operand, P_CMP + 1)} == 0", P_CMP
            return self.call(self.rt(OPS, "not_"), self.val(e.operand))
        if e.op == "-":
            if ot in _PLAIN_NUM:
                return f"-{self.sub(e.operand, P_UNARY)}", P_UNARY
            return self.call(self.rt(OPS, "neg"), self.val(e.operand))
        # unary plus
        if ot in _PLAIN_NUM:
            return self.expr(e.operand)
        return self.call(self.rt(CONV, "to_number"), self.val(e.operand))

    def identity(self, e: A.Binary, negate: bool) -> Code:
        """``a Is b`` (``Not a Is b`` when ``negate``).

        Objects compare by identity.  A String tested against Nothing asks whether it is empty:
        gpl2py stores Nothing into a String as "" (docs/design/real-code.md), so ``s Is Nothing``
        is ``s == ""``.  A value of unknown type (a stub's result) may be either, which the runtime
        decides (``is_nothing``)."""
        types = (self.type_of(e.left), self.type_of(e.right))
        if t.NOTHING in types:
            value, vt = (e.right, types[1]) if types[0] is t.NOTHING else (e.left, types[0])
            if vt is t.STRING:
                return f"{self.sub(value, P_CMP + 1)} {'!=' if negate else '=='} \"\"", P_CMP
            if vt is t.ANY:
                test = self.call(self.rt(OPS, "is_nothing"), self.val(value))
                return (f"not {test[0]}", P_NOT) if negate else test
        op = "is not" if negate else "is"
        return f"{self.sub(e.left, P_CMP + 1)} {op} {self.sub(e.right, P_CMP + 1)}", P_CMP

    def binop(self, op: str, left: tuple[str, int, t.GplType], right: tuple[str, int, t.GplType],
              left_node: A.Expr | None = None, right_node: A.Expr | None = None) -> Code:
        """``left op right`` from the operands' code and static types; ``left_node`` and
        ``right_node``, when given, are the GPL operands, whose literal values and variables let
        some operators stay plain Python.  Sets :attr:`left_flat`: whether the result begins
        with the left operand as it was, unwrapped (:meth:`binary_chain` ends a step otherwise)."""
        self.left_flat = False
        lc: Code = (left[0], left[1])
        rc: Code = (right[0], right[1])
        lt, rt_ = left[2], right[2]
        if t.NOTHING in (lt, rt_):  # Nothing beside a String is "" (nothing_as_string)
            lt2, rt2 = nothing_as_string(op, lt, rt_)
            if lt2 is not lt:
                lc, lt = ('""', P_ATOM), lt2
            if rt2 is not rt_:
                rc, rt_ = ('""', P_ATOM), rt2
        plain = lt in _PLAIN_NUM and rt_ in _PLAIN_NUM
        if op in ("+", "-", "*"):
            if plain or (op == "+" and lt is t.STRING and rt_ is t.STRING):
                prec = P_ADD if op != "*" else P_MUL
                return f"{self.left(lc, prec)} {op} {paren(rc, prec + 1)}", prec
            name = {"+": "add", "-": "sub", "*": "mul"}[op]
            return self.call(self.rt(OPS, name), lc[0], rc[0])
        if op == "/":
            value = _number(right_node)
            if plain and value is not None and value != 0:
                return f"{self.left(lc, P_MUL)} / {paren(rc, P_MUL + 1)}", P_MUL
            return self.call(self.rt(OPS, "div"), lc[0], rc[0])
        ints = lt in _INTS and rt_ in _INTS
        lit = _integer(right_node)
        var = self.plain_variable(left_node)
        if op == "\\" and ints and lit is not None and lit > 0:
            if var is not None and var.sym in self.nonneg:
                self.left_flat = True
                return f"{lc[0]} // {lit}", P_MUL  # a counter that cannot be negative here
            if var is not None:
                # truncation toward zero (§4.4) without a call: floor division on the magnitude
                self.left_flat = True
                return f"{lc[0]} // {lit} if {lc[0]} >= 0 else -(-{lc[0]} // {lit})", P_IF
            return f"int({paren(lc, P_MUL)} / {lit})", P_ATOM
        if op == "Mod" and ints and lit is not None and lit > 0 and var is not None:
            # the remainder has the dividend's sign (§4.4): Python's % on the magnitude, no call
            self.left_flat = True
            if var.sym in self.nonneg:
                return f"{lc[0]} % {lit}", P_MUL  # a counter that cannot be negative here
            return f"{lc[0]} % {lit} if {lc[0]} >= 0 else -(-{lc[0]} % {lit})", P_IF
        if op == ">>" and ints and lit is not None and 0 <= lit <= 31 and lc[1] == P_ATOM:
            self.left_flat = True
            return f"{lc[0]} >> {lit}", P_SHIFT  # an Integer variable: Python's shift is arithmetic
        if op in ("\\", "Mod", "^", "<<", ">>"):
            name = {"\\": "idiv", "Mod": "mod", "^": "power", "<<": "shl", ">>": ">>"}[op]
            if op == ">>":
                name = "shr"
            return self.call(self.rt(OPS, name), lc[0], rc[0])
        if op == "&":
            parts = []
            for c, typ in ((lc, lt), (rc, rt_)):
                if typ is t.STRING:
                    parts.append(paren(c, P_ADD + 1) if parts else self.left(c, P_ADD))
                else:
                    parts.append(self.coerce(c, typ if typ is not t.ERROR else t.DOUBLE, t.STRING)[0]
                                 if typ is not t.ERROR else self.call(self.rt(CONV, "to_string"), c[0])[0])
            return f"{parts[0]} + {parts[1]}", P_ADD
        if op in _PY_CMP:
            both_str = lt is t.STRING and rt_ is t.STRING
            if lt is t.BOOLEAN and rt_ is t.BOOLEAN and op in ("=", "<>"):
                simple = _against_boolean_literal(op, (lc, left_node), (rc, right_node))
                if simple is not None:
                    return simple
            if plain or both_str or (lt is t.BOOLEAN and rt_ is t.BOOLEAN and op in ("=", "<>")):
                return f"{self.left(lc, P_CMP + 1)} {_PY_CMP[op]} {paren(rc, P_CMP + 1)}", P_CMP
            if (lt is t.BOOLEAN or lt in _PLAIN_NUM) and (rt_ is t.BOOLEAN or rt_ in _PLAIN_NUM):
                if lt is t.BOOLEAN:
                    lc = self.call(self.rt(CONV, "bool_num"), lc[0])
                if rt_ is t.BOOLEAN:
                    rc = self.call(self.rt(CONV, "bool_num"), rc[0])
                return f"{self.left(lc, P_CMP + 1)} {_PY_CMP[op]} {paren(rc, P_CMP + 1)}", P_CMP
            return self.call(self.rt(OPS, _RUNTIME_CMP[op]), lc[0], rc[0])
        if op in ("And", "Or", "Xor"):
            pyop, prec = {"And": ("&", P_BAND), "Or": ("|", P_BOR), "Xor": ("^", P_BXOR)}[op]
            if (lt is t.BOOLEAN and rt_ is t.BOOLEAN) or (lt in _INTS and rt_ in _INTS):
                # arithmetic operands keep visible parentheses: (a + b) & 255, not a + b & 255; a left
                # operand of the same operator needs none (a & b & c: Python's & is left-associative,
                # and 200 nested parentheses are more than Python's tokenizer takes)
                left = self.left(lc, prec if lc[1] == prec else P_UNARY)
                return f"{left} {pyop} {paren(rc, P_UNARY)}", prec
            name = {"And": "and_", "Or": "or_", "Xor": "xor"}[op]
            return self.call(self.rt(OPS, name), lc[0], rc[0])
        return self.call(self.rt(OPS, "eq"), lc[0], rc[0])

    def left(self, c: Code, min_prec: int) -> str:
        """The left operand of an infix operator, parenthesised if it binds looser than
        ``min_prec``; records in :attr:`left_flat` whether it stays as it was."""
        self.left_flat = c[1] >= min_prec
        return paren(c, min_prec)

    def plain_variable(self, e: A.Expr | None) -> VarInfo | None:
        """``e``'s meaning when it is a variable read by its bare Python name, cheap and free of
        effects to read twice (a local, parameter, Static or module variable; not a cell or a
        field), else None."""
        if not isinstance(e, A.Name):
            return None
        i = self.model.info.get(e)
        if not isinstance(i, VarInfo) or i.receiver is not None:
            return None
        v = i.sym
        if v.boxed or v.byref or v.storage not in ("local", "param", "static", "module"):
            return None
        if v.storage == "module" and (self.ctx.member_owner_ref(v) or self.shadowed(v)):
            return None  # mod.x, or _this.x
        return i

    # -- calls and members -------------------------------------------------------------------------------

    def args_code(self, args: list[A.Expr], params: Sequence[ParamInfo]) -> list[str]:
        out: list[str] = []
        for i, a in enumerate(args):
            p = params[i] if i < len(params) else None
            if p is None or (p.type is t.ERROR and not p.byref):
                out.append(self.val(a))
            elif p.byref:
                out.append(self.cell(a, p.type))
            else:
                out.append(self.conv(a, p.type)[0])
        return out

    def cell(self, a: A.Expr, dst: t.GplType = t.ERROR) -> str:
        """The ByRef cell for argument ``a`` (§9.3: a variable, element or field aliases); a value
        that is not a variable goes in a temporary box, as the parameter's type ``dst`` holds it
        (a Nothing passed to a ByRef String is "")."""
        i = self.model.info.get(a)
        if a not in self.model.byref_temps and i is not None:
            if isinstance(i, VarInfo):
                v = i.sym
                if v.storage in ("local", "param"):
                    return self.local_name(v)  # a boxed local, or a ByRef parameter's own cell
                attr = self.rt(BYREF, "AttrRef")
                if v.storage == "static":
                    self.ctx.needs_this = True
                    return f"{attr}(_this, {py_string(self.static_name(v))})"
                if v.storage == "module":
                    module = self.ctx.module_ref(self.ctx.owner_module(v))
                    if module is None:
                        self.ctx.needs_this = True
                        return f"{attr}(_this, {py_string(py_ident(v.name))})"
                    return f"{attr}({module}, {py_string(py_ident(v.name))})"
                if v.shared and isinstance(v.owner, ClassSym):
                    return f"{attr}({self.class_ref(v.owner)}, {py_string(py_ident(v.name))})"
                recv = "self" if i.receiver is None else self.val(i.receiver)
                return f"{attr}({recv}, {py_string(py_ident(v.name))})"
            if isinstance(i, IndexInfo):
                assert isinstance(a, A.Invoke)
                idx = [self.val(x) for x in a.args]
                key = idx[0] if len(idx) == 1 else "(" + ", ".join(idx) + ")"
                return f"{self.rt(BYREF, 'ItemRef')}({self.val(a.target)}, {key})"
        value = self.conv(a, dst)[0] if self.type_of(a) is t.NOTHING else self.val(a)
        return f"{self.rt(BYREF, 'Box')}({value})"

    def user_call(self, i: CallInfo, args: list[A.Expr]) -> Code:
        return f"{self.proc_ref(i.sym, i.receiver)}({', '.join(self.args_code(args, i.params))})", P_ATOM

    def proc_ref(self, p: ProcSym, receiver: A.Expr | None) -> str:
        name = self.ctx.names.proc_name(p)
        if isinstance(p.owner, ClassSym) and not p.shared:
            recv = "self" if receiver is None else self.sub(receiver, P_ATOM)
            return f"{recv}.{name}"
        if isinstance(p.owner, ClassSym):
            return self.owner_ref(p) + name
        return self.unhidden(self.ctx.member_owner_ref(p) + name, p, name)

    def prop_ref(self, prop: PropSym, receiver: A.Expr | None) -> str:
        if prop.shared:
            return f"{self.class_ref(prop.owner)}._get_{py_ident(prop.name)}()"
        recv = "self" if receiver is None else self.sub(receiver, P_ATOM)
        return f"{recv}.{py_ident(prop.name)}"

    def index_code(self, e: A.Invoke) -> str:
        if len(e.args) == 1:
            arg = e.args[0]
            ai = self.model.info.get(arg)
            tt = self.type_of(e.target)
            safe = (isinstance(arg, A.IntegerLiteral) and arg.value >= 0) or (
                isinstance(ai, VarInfo) and ai.sym in self.nonneg)
            if safe and isinstance(tt, t.ArrayType) and tt.rank == 1:
                # The subscript cannot be negative, so the element list itself does the upper-bound
                # check (IndexError, which a Catch receives as -767): no Python-level call.
                return f"{self.sub(e.target, P_ATOM)}._data[{self.val(arg)}]"
        # no subscript at all is an error already reported ('a(,)'): --keep-going output must
        # still be Python, and a[()] fails at run time as the program would
        idx = ", ".join(self.val(x) for x in e.args) or "()"
        return f"{self.sub(e.target, P_ATOM)}[{idx}]"

    def builtin_function(self, i: BuiltinFunctionInfo, args: list[A.Expr]) -> Code:
        f = i.sym
        if f.name == "Chr" and len(args) == 1 and self.type_of(args[0]) in _INTS:
            return f"chr({self.sub(args[0], P_BAND + 1)} & 255)", P_ATOM  # low 8 bits (AMB-23)
        if f.name == "CStr" and len(args) == 1 and self.type_of(args[0]) is t.SINGLE:
            return self.call(self.rt(CONV, "to_string_single"), self.val(args[0]))
        if f.name == "CStr" and len(args) == 1 and self.type_of(args[0]) in _INTS:
            return f"str({self.val(args[0])})", P_ATOM  # an integer's digits (to_string's rule)
        if f.name == "Len" and len(args) == 1 and self.type_of(args[0]) is t.STRING:
            return f"len({self.val(args[0])})", P_ATOM  # a String is never None (Nothing is "")
        return self.call(self.ctx.builtin(f.python_name), *self.args_code(args, i.params))

    def builtin_member(self, i: BuiltinMemberInfo, e: A.Expr, args: list[A.Expr] | None,
                       statement: bool = False) -> Code:
        """A built-in member read or called; ``statement``: its statement form (``Member.action``)."""
        m, b = i.sym, i.owner
        acode = self.args_code(args or [], i.params or [])
        if i.on_value and b.name == "String":
            if m.name == "Length" and i.receiver is not None:
                return f"len({self.val(i.receiver)})", P_ATOM
            if m.name == "IndexOf" and i.receiver is not None and len(acode) == 1 \
                    and self.type_of(args[0]) is t.STRING:  # type: ignore[index]
                return f"{self.sub(i.receiver, P_ATOM)}.find({acode[0]})", P_ATOM
            sm = self.ctx.builtin(b.python_name)
            if i.static:
                return f"{sm}.{m.name}({', '.join(acode)})", P_ATOM
            assert i.receiver is not None
            return f"{sm}.{m.name}({', '.join([self.val(i.receiver), *acode])})", P_ATOM
        if i.static and b.name == "Math" and m.name in _PLAIN_MATH and args is not None \
                and all(self.type_of(a) in _PLAIN_NUM for a in args):
            # numeric arguments: the math module gives the same values (a domain error such as
            # Sqrt(-1) is a ValueError that as_gpl_exception maps to -707)
            return f"{self.rt('math', _PLAIN_MATH[m.name])}({', '.join(acode)})", P_ATOM
        if i.static and b.name == "Console" and args and len(acode) == 1 and self.type_of(args[0]) is t.SINGLE:
            acode = [self.call(self.rt(CONV, "to_string_single"), acode[0])[0]]  # 7 digits (AMB-22)
        name = m.action if statement and m.action else m.name
        if i.static:
            head = f"{self.ctx.builtin(b.python_name)}.{name}"
        else:
            assert i.receiver is not None
            head = f"{self.sub(i.receiver, P_ATOM)}.{name}"
        if m.kind == "property" and not statement:
            return head, P_ATOM
        return f"{head}({', '.join(acode)})", P_ATOM

    def new_code(self, e: A.New, i: NewInfo) -> Code:
        target = i.sym
        args = e.args or []
        if isinstance(target, ClassSym):
            ref = self.class_ref(target)
            acode = self.args_code(args, i.params or [])
            if len(target.ctors) > 1 and i.ctor is not None:
                return f"{ref}._create_{i.ctor.overload_index}({', '.join(acode)})", P_ATOM
            return f"{ref}({', '.join(acode)})", P_ATOM
        if isinstance(target, DelegateSym):
            ref = self.class_ref(target)
            if args and isinstance(args[0], A.AddressOf):
                return f"{ref}({self.val(args[0])})", P_ATOM
            mod = self.ctx.mod.name
            return f"{ref}.from_name({self.conv(args[0], t.STRING)[0]}, {py_string(mod)})", P_ATOM
        if isinstance(target, BuiltinClass):
            acode = self.args_code(args, i.params or [])
            if target.name == "Thread" and args:
                # The start procedure (a String) resolves as seen from the module executing the
                # New, Private procedures included (gplrt.threads.thread): name that module, as
                # delegates do, so the runtime never has to infer it from the Python caller.
                acode.append(f"_module={py_string(self.ctx.mod.name)}")
            return self.call(self.ctx.builtin(target.python_name), *acode)
        raise InternalError(e.span, f"New of a {type(target).__name__}")

    def dynamic_member(self, receiver: A.Expr, name: str) -> str:
        """``receiver.name`` where the receiver's class is unknown (gplrt.lang.members)."""
        return f"{self.rt(MEMBERS, 'get_member')}({self.val(receiver)}, {py_string(name)})"


_PLAIN_MATH = {"Sin": "sin", "Cos": "cos", "Tan": "tan", "Atan": "atan", "Atan2": "atan2", "Sqrt": "sqrt"}

#: The lowering of each kind of meaning (ExprLowerer.expr).  Kinds that name something rather than
#: give a value (a module, a class, a procedure before its arguments) are absent: meeting one as a
#: value is a gap in gpl2py (GPL9000), which the analysis never lets through.
_VISIT: dict[type[Info], Callable[[ExprLowerer, A.Expr, Any], Code]] = {
    LiteralInfo: ExprLowerer.x_literal,
    NothingInfo: ExprLowerer.x_nothing,
    MeInfo: ExprLowerer.x_me,
    ErrorInfo: ExprLowerer.x_error,
    VarInfo: ExprLowerer.x_var,
    ResultInfo: ExprLowerer.x_result,
    CallInfo: ExprLowerer.x_call,
    PropInfo: ExprLowerer.x_prop,
    IndexInfo: ExprLowerer.x_index,
    BuiltinFunctionInfo: ExprLowerer.x_bfunc,
    BuiltinConstInfo: ExprLowerer.x_bconst,
    BuiltinMemberInfo: ExprLowerer.x_bmember,
    DelegateCallInfo: ExprLowerer.x_delegate_call,
    NewInfo: ExprLowerer.x_new,
    AddressOfInfo: ExprLowerer.x_addressof,
    TypeNameInfo: ExprLowerer.x_typename,
    StubCallInfo: ExprLowerer.x_stub,
    StubNameInfo: ExprLowerer.x_stub,
    StubNewInfo: ExprLowerer.x_stub,
    DynamicMemberInfo: ExprLowerer.x_dynamic_member,
    DynamicCallInfo: ExprLowerer.x_dynamic_call,
    UnaryInfo: ExprLowerer.x_unary,
    BinaryInfo: ExprLowerer.x_binary,
    ChainInfo: ExprLowerer.x_chain,
}


class _Steps:
    """The operators of a left spine of Binary and Chain nodes (``spine``, innermost first) as
    one sequence, by index: the operator, its right operand, the type of the result so far and
    the node that result is (a Binary, or the Chain for any of its prefixes: neither is a variable
    or a literal, all that :meth:`ExprLowerer.binop` asks of a left operand).  A Chain's operands
    kept as values are made nodes one at a time, so a long chain is never a tree in memory."""

    __slots__ = ("_nodes", "_starts", "_info")

    def __init__(self, spine: list[A.Binary | A.Chain], info: Any) -> None:
        self._nodes = spine
        self._starts: list[int] = []
        self._info = info
        at = 0
        for node in spine:
            self._starts.append(at)
            at += len(node.ops) if isinstance(node, A.Chain) else 1
        self._starts.append(at)

    def __len__(self) -> int:
        return self._starts[-1]

    def _find(self, i: int) -> tuple[A.Binary | A.Chain, int]:
        j = bisect_right(self._starts, i) - 1
        return self._nodes[j], i - self._starts[j]

    def op(self, i: int) -> str:
        node, k = self._find(i)
        return node.op if isinstance(node, A.Binary) else node.op(k)

    def right(self, i: int) -> A.Expr:
        node, k = self._find(i)
        if isinstance(node, A.Binary):
            return node.right
        x = node.operand(k)
        if x._info is None:  # an operand kept as a value: its meaning is the chain's record's
            x._info = self._info.get(node).literal
        return x

    def type(self, i: int) -> t.GplType:
        node, k = self._find(i)
        info = self._info.get(node)
        if info is None:
            return t.ERROR
        return info.prefix_type(k) if isinstance(node, A.Chain) else info.type

    def node(self, i: int) -> A.Expr:
        return self._find(i)[0]

    def not_boolean(self) -> int:
        """How many operators are neither ``AndAlso`` nor ``OrElse``."""
        count = 0
        boolean = (A.CHAIN_CODES["AndAlso"], A.CHAIN_CODES["OrElse"])
        for node in self._nodes:
            if isinstance(node, A.Binary):
                count += node.op not in ("AndAlso", "OrElse")
            else:
                count += len(node.ops) - node.ops.count(boolean[0]) - node.ops.count(boolean[1])
        return count


def _may_overflow(e: A.Expr) -> bool:
    """Whether an integer-typed expression can leave the Integer range (bitwise results cannot)."""
    if isinstance(e, A.Binary):
        return e.op in ("+", "-", "*", "\\", "^")
    if isinstance(e, A.Chain):
        return any(e.ops.count(A.CHAIN_CODES[op]) for op in ("+", "-", "*", "\\", "^"))
    if isinstance(e, A.Unary):
        return e.op == "-"
    return False


def _number(e: A.Expr | None) -> int | float | None:
    """The value of a number literal, negated or not (``3``, ``-0.5``), else None."""
    sign = 1
    if isinstance(e, A.Unary) and e.op == "-":
        e, sign = e.operand, -1
    if isinstance(e, (A.IntegerLiteral, A.RealLiteral)):
        return sign * e.value
    return None


def _integer(e: A.Expr | None) -> int | None:
    """The value of an Integer literal, negated or not, else None."""
    value = _number(e)
    return value if isinstance(value, int) and -(2**31) <= value < 2**31 else None


def _against_boolean_literal(op: str, left: tuple[Code, A.Expr | None],
                             right: tuple[Code, A.Expr | None]) -> Code | None:
    """``flag = True`` as ``flag``, ``flag = False`` / ``flag <> True`` as ``not flag`` (PEP 8:
    never compare to True with ``==``).  Exact for two Booleans; the literal side has no effects
    to lose.  ``None`` when neither side is a literal."""
    for (_, lit), (other, _) in ((right, left), (left, right)):
        if isinstance(lit, A.BooleanLiteral):
            if lit.value == (op == "="):
                return other
            return f"not {paren(other, P_NOT)}", P_NOT
    return None
