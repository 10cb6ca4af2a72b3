"""V+ expressions -> Python text on the V+ runtime layer (docs/design/vplus-runtime.md §3-4).

Reals are Python floats, so ``+ - *`` between reals and ``/`` by a nonzero constant are written as
Python operators; everything with a V+ meaning of its own goes through ``vp``: relations give
-1/0 (``vp.lt``), AND/OR/XOR evaluate both sides (``vp.and_``), MOD, the bitwise operators, string
concatenation (128 characters at most), division by a value that may be zero.  A condition (IF,
WHILE, UNTIL, WAIT) is written as a Python condition where that reads the same: ``a < b``, ``not
c``, ``x.v != 0`` -- V+'s truth is "not zero".
"""

from __future__ import annotations

from collections.abc import Callable

from gpl2py.pywriter.text import py_string
from gpl2py.vplus.lower.names import runtime_name
from gpl2py.vplus.semantics.check import Model, Symbol
from gpl2py.vplus.semantics.types import T
from gpl2py.vplus.syntax import ast as A
from gpl2py.vplus.syntax.keywords import UNSIMULATED

_REL = {"==": "eq", "<>": "ne", "<": "lt", ">": "gt", "<=": "le", "=<": "le", ">=": "ge", "=>": "ge"}
_PY_REL = {"==": "==", "<>": "!=", "<": "<", ">": ">", "<=": "<=", "=<": "<=", ">=": ">=", "=>": ">="}
_CALLS = {"MOD": "mod", "AND": "and_", "OR": "or_", "XOR": "xor_", "BAND": "band", "BOR": "bor", "BXOR": "bxor"}
#: V+ functions whose runtime name is not the rule's (docs/design/vplus-runtime.md §4).
_FUNCTION_NAMES = {
    "TOOL": "tool_value", "BASE": "base_value", "PPOINT": "p_ppoint", "STATUS": "task_status",
    "TIME": "time_", "$TIME": "s_time", "ERROR": "error",
    # functions that share an instruction's name take _value (docs/design/vplus-runtime.md)
    "SPEED": "speed_value", "ACCEL": "accel_value", "DURATION": "duration_value", "CONFIG": "config_value",
    "SELECT": "select_value",
}
_CONSTANTS = {"TRUE": "vp.TRUE", "FALSE": "vp.FALSE", "ON": "vp.TRUE", "OFF": "vp.FALSE", "PI": "vp.PI"}
#: Functions that take a variable itself (its cell or array), not its value.
_BY_REF = frozenset(("DEFINED", "LAST", "TAS", "CAS"))
#: Functions that take a system name (PARAMETER(HAND.TIME)), written as a string.
_BY_NAME = frozenset(("PARAMETER", "SWITCH", "SELECT"))


class Exprs:
    """Writes the expressions of one program: ``var(sym)`` names a symbol's Python variable."""

    def __init__(self, model: Model, var: Callable[[Symbol], str]) -> None:
        self.model = model
        self.var = var

    def type_of(self, e: A.Expr) -> T:
        return self.model.type_of.get(id(e), T.UNKNOWN)

    # --- values ---------------------------------------------------------------------------------

    def value(self, e: A.Expr) -> str:
        return self._v(e)[0]

    def _v(self, e: A.Expr) -> tuple[str, int]:  # noqa: C901 (one dispatch over the expression kinds)
        """The text of ``e`` and the Python precedence of its top (ATOM, NEG, MUL, ADD, REL)."""
        if isinstance(e, A.Num):
            text = number(e.value)
            return text, NEG if text.startswith("-") else ATOM
        if isinstance(e, A.Str):
            return py_string(e.value), ATOM
        if isinstance(e, A.Paren):
            return self._v(e.inner)
        if isinstance(e, A.Format):
            return f"vp.fmt({py_string('/' + e.letter + e.arg)})", ATOM
        if isinstance(e, A.Var):
            return self.read(e), ATOM
        if isinstance(e, A.Unary):
            if e.op == "-":
                text, prec = self._v(e.operand)
                return "-" + (text if prec >= NEG else f"({text})"), NEG
            return f"vp.{'not_' if e.op == 'NOT' else 'com'}({self.value(e.operand)})", ATOM
        if isinstance(e, A.Binary):
            return self.binary(e)
        if isinstance(e, A.Call):
            return self.call(e), ATOM
        raise AssertionError(f"unknown expression {type(e).__name__}")

    def read(self, v: A.Var) -> str:
        sym = self.model.symbol_of[id(v)]
        name = self.var(sym)
        if v.whole:
            return name
        if v.index is not None:
            return f"{name}[{', '.join(self.value(i) for i in v.index)}]"
        return f"{name}.v"

    def ref(self, v: A.Var) -> str:
        """The variable itself, for a by-reference argument: a cell, an element, an array."""
        sym = self.model.symbol_of[id(v)]
        name = self.var(sym)
        if v.index is not None:
            return f"{name}.ref({', '.join(self.value(i) for i in v.index)})"
        return name

    def argument(self, e: A.Expr | None) -> str:
        """A CALL argument: a variable by reference, anything else by value, an omitted one
        undefined (User's Guide L1169-1217)."""
        if e is None:
            return "vp.Cell()"
        if isinstance(e, A.Var):
            return self.ref(e)
        return f"vp.byval({self.value(e)})"

    def binary(self, e: A.Binary) -> tuple[str, int]:
        op = e.op
        if op == ":":
            chain: list[A.Expr] = []
            node: A.Expr = e
            while isinstance(node, A.Binary) and node.op == ":":
                chain.insert(0, node.right)
                node = node.left
            chain.insert(0, node)
            return f"vp.compose({', '.join(self.value(x) for x in chain)})", ATOM
        if op in _REL:
            return f"vp.{_REL[op]}({self.value(e.left)}, {self.value(e.right)})", ATOM
        if op in _CALLS:
            return f"vp.{_CALLS[op]}({self.value(e.left)}, {self.value(e.right)})", ATOM
        strings = T.STRING in (self.type_of(e.left), self.type_of(e.right))
        if op == "+" and strings:
            return f"vp.add({self.value(e.left)}, {self.value(e.right)})", ATOM
        if op == "/" and not (isinstance(e.right, A.Num) and e.right.value != 0):
            return f"vp.div({self.value(e.left)}, {self.value(e.right)})", ATOM
        prec = MUL if op in ("*", "/") else ADD
        return f"{self._operand(e.left, prec, False)} {op} {self._operand(e.right, prec, True)}", prec

    def _operand(self, e: A.Expr, prec: int, right: bool) -> str:
        text, own = self._v(e)
        return text if own > prec or (own == prec and not right) else f"({text})"

    def call(self, e: A.Call) -> str:
        word = e.upper
        if word in _CONSTANTS and not e.args:
            return _CONSTANTS[word]
        if word in UNSIMULATED:
            return f"vp.unsupported({py_string(word)})"
        fn = "vp." + _FUNCTION_NAMES.get(word, runtime_name(e.sigil + e.name.upper()).lower())
        if word in _BY_NAME:
            args = [py_string(a.shown.upper()) if isinstance(a, A.Var) else self.value(a) if a is not None else "None"
                    for a in e.args]
        elif word in _BY_REF:
            args = [self.ref(a) if isinstance(a, A.Var) and i == 0 else self.value(a) if a is not None else "None"
                    for i, a in enumerate(e.args)]
        else:
            args = [self.value(a) if a is not None else "None" for a in e.args]
        if e.by is not None:
            args += [self.value(a) if a is not None else "0" for a in e.by]
        return f"{fn}({', '.join(args)})"

    # --- conditions -----------------------------------------------------------------------------

    def condition(self, e: A.Expr) -> str:
        """``e`` as a Python condition: true when the V+ value is not zero."""
        if isinstance(e, A.Paren):
            return self.condition(e.inner)
        if isinstance(e, A.Binary) and e.op in _PY_REL and T.STRING not in (self.type_of(e.left), self.type_of(e.right)):
            return f"{self._operand(e.left, REL, False)} {_PY_REL[e.op]} {self._operand(e.right, REL, True)}"
        if isinstance(e, A.Unary) and e.op == "NOT":
            inner = self.condition(e.operand)
            return f"not {inner}" if _simple_condition(inner) else f"not ({inner})"
        if isinstance(e, A.Binary) and e.op in ("AND", "OR") and _pure(e.left) and _pure(e.right):
            word = e.op.lower()
            parts = []
            for side in (e.left, e.right):
                c = self.condition(side)
                parts.append(c if _simple_condition(c) or (isinstance(side, A.Binary) and side.op == e.op)
                             else f"({c})")
            return f"{parts[0]} {word} {parts[1]}"
        if isinstance(e, A.Call) and e.upper in ("TRUE", "ON"):
            return "True"
        if isinstance(e, A.Call) and e.upper in ("FALSE", "OFF"):
            return "False"
        if isinstance(e, A.Call) and e.upper in ("SIG", "DEFINED"):
            return f"vp.truth({self.value(e)})"
        if isinstance(e, A.Num):
            return "True" if e.value else "False"
        return f"{self._operand(e, REL, False)} != 0"


def number(value: float) -> str:
    """A V+ number as a Python literal: integers without a point (``11000``), others as Python
    prints them (``0.1``)."""
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return repr(value)


#: Python precedences of the texts :meth:`Exprs._v` makes (higher binds tighter).
ATOM, NEG, MUL, ADD, REL = 9, 8, 6, 5, 3


def _simple_condition(text: str) -> bool:
    return " and " not in text and " or " not in text


def _pure(e: A.Expr) -> bool:
    """No function call with a side effect in ``e`` (so Python's short-circuit changes nothing)."""
    if isinstance(e, A.Call):
        return e.upper in ("SIG", "DEFINED", "TIMER", "TRUE", "FALSE", "ON", "OFF", "PI") and all(
            a is None or _pure(a) for a in e.args)
    if isinstance(e, A.Binary):
        return _pure(e.left) and _pure(e.right)
    if isinstance(e, A.Unary):
        return _pure(e.operand)
    if isinstance(e, A.Paren):
        return _pure(e.inner)
    if isinstance(e, A.Var):
        return all(_pure(i) for i in e.index or ())
    return True
