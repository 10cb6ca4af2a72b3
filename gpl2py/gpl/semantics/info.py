"""What semantics tells lowering about each expression: one typed record per kind of meaning.

The typing pass (``semantics/check.py``) records one :class:`Info` per expression node
(``Model.info``).  Each kind of meaning is its own class with the fields that kind has and no
others -- a variable (:class:`VarInfo`, its :class:`VarSym`), a call of a user procedure
(:class:`CallInfo`, the chosen :class:`ProcSym` and its parameters), a built-in member
(:class:`BuiltinMemberInfo`, the catalogue's :class:`Member` and class), a use of protected code
(:class:`StubCallInfo` ...), and so on -- as mypy's ``type_map`` and CPython's ``symtable`` hand
over typed records.  Consumers dispatch on the class (the lowering's visitor raises on a class it
has no method for), never on a string.

Records that are reached *through* an object (``obj.field``, ``obj.Method(...)``) derive from
:class:`Reached`, which adds the object expression, ``receiver``.  ``type`` is the expression's
static type; the typing pass may set it to ERROR after reporting a misuse (a module used as a
value), which is why the records are not frozen.  Records shared by many expressions (literals,
operators, a plain variable) are never changed otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, BuiltinConstant, BuiltinFunction, Member
from gpl2py.gpl.semantics.stubs import Stub
from gpl2py.gpl.semantics.symbols import ClassSym, DelegateSym, ModuleSym, OverloadSet, ProcSym, PropSym, VarSym
from gpl2py.gpl.syntax import ast as A


@dataclass(frozen=True)
class ParamInfo:
    """What the lowering needs to pass one argument: the parameter's type and passing mode."""

    name: str
    type: t.GplType
    byref: bool = False
    optional: bool = False


Params = tuple[ParamInfo, ...]


@dataclass(eq=False, slots=True)
class Info:
    """The meaning of one expression node: its static type; the subclass says what it is."""

    type: t.GplType


@dataclass(eq=False, slots=True)
class Reached(Info):
    """A meaning reached through an object expression (``receiver``), if any: ``obj.x``."""

    receiver: A.Expr | None = field(default=None, kw_only=True)


# -- values without a symbol -------------------------------------------------------------------------


@dataclass(eq=False, slots=True)
class LiteralInfo(Info):
    """A literal (``12``, ``"a"``, ``True``)."""


@dataclass(eq=False, slots=True)
class NothingInfo(Info):
    """``Nothing``."""


@dataclass(eq=False, slots=True)
class MeInfo(Info):
    """``Me``, the object of an instance method."""


@dataclass(eq=False, slots=True)
class UnaryInfo(Info):
    """The result of a unary operator."""


@dataclass(eq=False, slots=True)
class BinaryInfo(Info):
    """The result of a binary operator (``Is`` included)."""


@dataclass(eq=False, slots=True)
class ChainInfo(Info):
    """The result of a :class:`~gpl2py.gpl.syntax.ast.Chain` (``type``) and of each of its
    prefixes, the Binary nodes it stands for: prefix ``k`` (``first op1 x1 ... opk xk``) has type
    ``types[codes[k]]`` (a byte per operator, not a record).  ``literal`` is the meaning of the
    operands the chain keeps as values (Integer literals)."""

    types: tuple[t.GplType, ...] = ()
    codes: bytes = b""
    literal: Info | None = None

    def prefix_type(self, k: int) -> t.GplType:
        return self.types[self.codes[k]]


@dataclass(eq=False, slots=True)
class IndexInfo(Info):
    """An array element ``a(i, j)``."""


@dataclass(eq=False, slots=True)
class ErrorInfo(Info):
    """Something already reported as an error: nothing to lower."""


# -- user declarations -------------------------------------------------------------------------------


@dataclass(eq=False, slots=True)
class VarInfo(Reached):
    """A variable: local, parameter, Static, module variable or field (``sym.storage``)."""

    sym: VarSym


@dataclass(eq=False, slots=True)
class ResultInfo(Info):
    """The Function's own name used as its result variable."""

    sym: ProcSym


@dataclass(eq=False, slots=True)
class PropInfo(Reached):
    """A user Property read or assigned."""

    sym: PropSym


@dataclass(eq=False, slots=True)
class CallInfo(Reached):
    """A call of a user procedure (the overload chosen) with its parameters."""

    sym: ProcSym
    params: Params


@dataclass(eq=False, slots=True)
class ProcRefInfo(Reached):
    """A procedure named before its arguments are known (the target of an Invoke or an
    AddressOf); ``static``: reached through its class's name (only Shared overloads count)."""

    sym: ProcSym | OverloadSet
    static: bool = False


@dataclass(eq=False, slots=True)
class AddressOfInfo(Reached):
    """``AddressOf proc`` (bound to ``receiver`` for ``AddressOf obj.m``)."""

    sym: ProcSym


@dataclass(eq=False, slots=True)
class DelegateCallInfo(Info):
    """A call through a delegate value."""

    sym: DelegateSym
    params: Params


@dataclass(eq=False, slots=True)
class NewInfo(Info):
    """``New T(args)``: a user class (``ctor``: the constructor chosen, if it has any), a
    delegate class or a built-in class."""

    sym: ClassSym | DelegateSym | BuiltinClass
    ctor: ProcSym | None = None
    params: Params | None = None


@dataclass(eq=False, slots=True)
class ModuleInfo(Info):
    """A module name (``Module.x`` qualifies with it)."""

    sym: ModuleSym


@dataclass(eq=False, slots=True)
class ClassInfo(Info):
    """A user class or delegate class name."""

    sym: ClassSym | DelegateSym


@dataclass(eq=False, slots=True)
class TypeNameInfo(Info):
    """A primitive type's keyword as an argument (``ToBitString(x, Short, True)``)."""

    sym: t.PrimitiveType


# -- built-ins ---------------------------------------------------------------------------------------


@dataclass(eq=False, slots=True)
class BuiltinClassInfo(Info):
    """A built-in class name (``Robot``, ``String``)."""

    sym: BuiltinClass | None


@dataclass(eq=False, slots=True)
class BuiltinFunctionInfo(Info):
    """A call of a built-in function (``CStr(x)``, ``Len(s)``)."""

    sym: BuiltinFunction
    params: Params


@dataclass(eq=False, slots=True)
class BuiltinFunctionRefInfo(Info):
    """A built-in function named before its arguments are known (an Invoke's target)."""

    sym: BuiltinFunction


@dataclass(eq=False, slots=True)
class BuiltinConstInfo(Info):
    """A built-in constant (``GPL_CR``)."""

    sym: BuiltinConstant


@dataclass(eq=False, slots=True)
class BuiltinMemberInfo(Reached):
    """A member of a built-in class, read, called or assigned.  ``static``: reached through the
    class (or a variable of a global class); ``on_value``: a member of a String or array value,
    which the runtime's helper receives first (``StringMembers.Trim(s)``)."""

    sym: Member
    owner: BuiltinClass
    params: Params | None = None
    static: bool = False
    on_value: bool = False


# -- protected code and values of unknown type -------------------------------------------------------


@dataclass(eq=False, slots=True)
class StubCallInfo(Reached):
    """A call of a name of protected code or of a member the catalogue lacks (a stub)."""

    stub: Stub | None


@dataclass(eq=False, slots=True)
class StubNameInfo(Reached):
    """A stub used without parentheses: a variable of protected code, or an unknown built-in
    member assigned."""

    stub: Stub


@dataclass(eq=False, slots=True)
class StubRefInfo(Reached):
    """A stub named before its arguments are known (an Invoke's target)."""

    stub: Stub


@dataclass(eq=False, slots=True)
class StubNewInfo(Info):
    """``New T`` of a class from protected code."""

    stub: Stub | None


@dataclass(eq=False, slots=True)
class StubModuleInfo(Info):
    """A module no readable source declares (``Module.x`` of protected code)."""

    name: str


@dataclass(eq=False, slots=True)
class DynamicMemberInfo(Reached):
    """``obj.name`` where ``obj``'s class is unknown (a stub's value): the runtime finds it."""

    name: str


@dataclass(eq=False, slots=True)
class DynamicCallInfo(Reached):
    """A call of a value of unknown type, or of ``obj.name`` on one (``name`` then set)."""

    name: str | None = None


#: Kinds that name something rather than give a value (a module, a class, a type keyword).
NAMES_NOT_VALUES = (TypeNameInfo, ModuleInfo, ClassInfo, BuiltinClassInfo, StubModuleInfo)
#: Kinds that may stand as a statement: calls.
CALLS = (CallInfo, BuiltinFunctionInfo, BuiltinMemberInfo, DelegateCallInfo, ErrorInfo, StubCallInfo,
         DynamicCallInfo)
#: Kinds whose member access goes through the runtime (every class lists its members then).
DYNAMIC_MEMBERS = (DynamicMemberInfo, DynamicCallInfo)
