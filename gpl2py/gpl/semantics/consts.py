"""Constants folded at translation time (docs/design/real-code.md, "Constants across modules").

A module's or class's ``Const`` whose initializer is built from literals, built-in constants, the
pure conversion functions (``CInt``, ``CStr``, ``Chr`` ...: :data:`PURE_FUNCTIONS`) and other such
Consts -- of any module or class, in any order -- gets its value here, once the whole
project is typed.  The generated module then holds that value from the moment it is imported and
``_reset()`` keeps it, so ``Public Const N_ROB As Integer = Startup.NumRobots`` in a module that
initialises before ``Startup`` still sizes ``CmdObject(N_ROB)`` right.  A Const whose initializer
needs the running controller (``Controller.PDbNum(104) * 1000000``) keeps being evaluated by the
module's initializer, as before.

Values are computed with the runtime's own operators and conversions (``gplrt.lang``), the
functions the generated code would call, so a folded value is exactly the one the program would
compute; an expression that raises (overflow, division by zero) is left to raise at run time.
A chain of Consts that leads back to its start is GPL2042.

Those runtime modules are GPL's language semantics alone (no simulator: no numpy, Pinocchio or
Ruckig), and they are imported only when a project has a Const to fold; a pure built-in function
is imported from the module that defines it (``BuiltinFunction.module``), never through
``gplrt.builtins``, which would import the whole simulator.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinFunction
from gpl2py.gpl.semantics.info import BuiltinConstInfo, BuiltinFunctionInfo, VarInfo
from gpl2py.gpl.semantics.symbols import ProjectSyms, VarSym
from gpl2py.gpl.syntax import ast as A

#: GPL's binary operators in the runtime's ``gplrt.lang.operators`` (functions named there)
_BINARY_NAMES = {
    "+": "add", "-": "sub", "*": "mul", "/": "div", "\\": "idiv", "Mod": "mod", "^": "power",
    "<<": "shl", ">>": "shr", "&": "concat", "=": "eq", "<>": "ne", "<": "lt", ">": "gt", "<=": "le",
    ">=": "ge", "And": "and_", "Or": "or_", "Xor": "xor",
}
_UNARY_OPS = ("-", "+", "Not")
# Built-in functions whose result depends on their arguments alone (no controller state)
PURE_FUNCTIONS = frozenset({"CBool", "CByte", "CShort", "CInt", "CSng", "CDbl", "CStr", "Chr", "Asc",
                            "Hex", "Fix", "Int", "Len"})


class _NotConstant(Exception):
    """The expression needs the running program (a variable, a call, ...)."""


class _Semantics:
    """The runtime's operators and conversions (module docstring), imported on first use."""

    def __init__(self) -> None:
        conv = importlib.import_module("gplrt.lang.conversions")
        ops = importlib.import_module("gplrt.lang.operators")
        self.error: type[Exception] = importlib.import_module("gplrt.lang.errors").GplException
        self.convert: Callable[[Any, str], Any] = conv.convert
        self.binary: dict[str, Callable[[Any, Any], Any]] = {
            op: getattr(ops, name) for op, name in _BINARY_NAMES.items()}
        self.binary["AndAlso"] = lambda a, b: conv.to_bool(a) and conv.to_bool(b)
        self.binary["OrElse"] = lambda a, b: conv.to_bool(a) or conv.to_bool(b)
        self.unary: dict[str, Callable[[Any], Any]] = {"-": ops.neg, "+": conv.to_number, "Not": ops.not_}


_BINARY_OPS = frozenset(_BINARY_NAMES) | {"AndAlso", "OrElse"}


class ConstFolder:
    """Computes the value of every foldable module and class Const of a project."""

    def __init__(self, info: Any, sink: DiagnosticSink) -> None:
        self.info = info  # check.Model.info (an InfoTable): what each name in an initializer refers to
        self.sink = sink
        self.values: dict[VarSym, object] = {}
        self._unfoldable: set[VarSym] = set()
        self._stack: list[VarSym] = []
        self._rt: _Semantics | None = None

    @property
    def rt(self) -> _Semantics:
        if self._rt is None:
            self._rt = _Semantics()
        return self._rt

    def _failures(self) -> tuple[type[Exception], ...]:
        """What folding an initializer may raise: it needs the program, or the runtime's operators
        refuse the values (the program will raise the same at run time).  A GPL error can only
        come from the runtime once it is imported, so a Const that is not foldable never imports it."""
        failures: tuple[type[Exception], ...] = (_NotConstant, ArithmeticError, ValueError, TypeError)
        return failures + (self._rt.error,) if self._rt is not None else failures

    def fold(self, consts: list[VarSym]) -> dict[VarSym, object]:
        for v in consts:
            try:
                self._const(v)
            except _NotConstant:
                pass
        return self.values

    def _const(self, v: VarSym) -> object:
        if v in self.values:
            return self.values[v]
        if v in self._unfoldable:
            raise _NotConstant
        if v in self._stack:
            self._cycle(v)
        d = v.decl
        if d is None or d.initializer is None or d.bounds is not None or not isinstance(v.type, t.PrimitiveType):
            self._unfoldable.add(v)
            raise _NotConstant
        self._stack.append(v)
        try:
            value = self.rt.convert(self._value(d.initializer), v.type.name)
        except self._failures():
            self._unfoldable.add(v)
            raise _NotConstant from None
        finally:
            self._stack.pop()
        self.values[v] = value
        return value

    def _cycle(self, v: VarSym) -> None:
        """``v`` is being folded already: report the loop once, at the Const it starts from."""
        loop = self._stack[self._stack.index(v):]
        if not any(c in self._unfoldable for c in loop):
            names = " -> ".join(_qualified(c) for c in [*loop, v])
            self.sink.report(M.CONST_CYCLE, v.span, name=v.name, cycle=names)
        self._unfoldable.update(loop)
        raise _NotConstant

    def _value(self, e: A.Expr) -> object:
        if isinstance(e, (A.IntegerLiteral, A.RealLiteral, A.StringLiteral, A.BooleanLiteral)):
            return e.value
        if isinstance(e, A.Unary) and e.op in _UNARY_OPS:
            return self.rt.unary[e.op](self._value(e.operand))
        if (isinstance(e, A.Binary) and e.op in _BINARY_OPS) or isinstance(e, A.Chain):
            return self._binary(e)
        info = self.info.get(e)
        if isinstance(info, VarInfo) and info.sym.const and info.sym.storage in ("module", "field"):
            return self._const(info.sym)
        if isinstance(info, BuiltinConstInfo):
            return info.sym.value
        if isinstance(info, BuiltinFunctionInfo) and info.sym.name in PURE_FUNCTIONS and isinstance(e, A.Invoke):
            args = [self._value(a) for a in e.args]
            return _builtin(info.sym)(*args)
        raise _NotConstant

    def _binary(self, e: A.Binary | A.Chain) -> object:
        """A left-leaning chain without recursing on its spine (real code has long ones)."""
        spine = [e]
        left = A.chain_left(e)
        while (isinstance(left, A.Binary) and left.op in _BINARY_OPS) or isinstance(left, A.Chain):
            spine.append(left)
            left = A.chain_left(left)
        value = self._value(left)
        binary = self.rt.binary
        for node in reversed(spine):
            if isinstance(node, A.Binary):
                value = binary[node.op](value, self._value(node.right))
                continue
            for k in range(len(node.ops)):
                op = node.op(k)
                if op not in _BINARY_OPS:
                    raise _NotConstant
                x = node.operands[k]
                value = binary[op](value, self._value(x) if isinstance(x, A.Node) else x)
        return value


def _builtin(func: BuiltinFunction) -> Callable[..., Any]:
    """The runtime's implementation of a pure built-in function, from the module that defines it
    (``gplrt.lang.conversions`` ...: the catalogue records it), not from ``gplrt.builtins``."""
    return getattr(importlib.import_module(func.module), func.python_name)  # type: ignore[no-any-return]


def _qualified(v: VarSym) -> str:
    """``Module.Name`` or ``Class.Name``: a loop may run through several modules."""
    owner = getattr(v.owner, "name", "")
    return f"{owner}.{v.name}" if owner else v.name


def project_consts(project: ProjectSyms) -> list[VarSym]:
    """Every module-level and class-level Const, modules in ProjectSource order."""
    out: list[VarSym] = []
    tables = [m.members for m in project.module_list] + [c.members for c in project.classes]
    for table in tables:
        out.extend(m for m in table.values() if isinstance(m, VarSym) and m.const)
    return out


def fold_constants(project: ProjectSyms, info: Any, sink: DiagnosticSink) -> dict[VarSym, object]:
    """The value of every module and class Const that translation can compute (module doc)."""
    return ConstFolder(info, sink).fold(project_consts(project))


__all__ = ["fold_constants", "ConstFolder"]
