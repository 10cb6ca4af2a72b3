"""Symbol tables: project -> module -> class -> procedure (spec §6, §8.3, §12).

Symbols are plain mutable dataclasses compared by identity; the semantic pass keys its tables on
them and the lowering reads them.  Every table is keyed by the lower-cased name because GPL is
case-insensitive (§1.7); each symbol keeps the spelling of its declaration, which the generated
Python uses everywhere.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

from gpl2py.semantics import types as t
from gpl2py.source import Span
from gpl2py.syntax import ast as A


@dataclass(eq=False)
class VarSym:
    """A variable: local, Static local, parameter, module variable, class field or Const.

    ``storage`` is one of ``local``, ``static``, ``param``, ``module``, ``field``.
    ``boxed`` is set by the checker when a local is passed to a ByRef parameter: the lowering then
    keeps it in a cell for the whole procedure, which makes ByRef true aliasing (§9.3).
    """

    name: str
    span: Span | None
    type: t.GplType
    storage: str
    owner: object = None
    public: bool = False
    shared: bool = False
    const: bool = False
    decl: A.VarDeclarator | None = None
    byref: bool = False
    optional: bool = False
    default: A.Expr | None = None
    boxed: bool = False
    assigned: bool = False
    read: bool = False


@dataclass(eq=False)
class ProcSym:
    """A Sub, Function, constructor (``New``) or property accessor (kind ``Get``/``Set``)."""

    name: str
    span: Span | None
    kind: str
    params: list[VarSym]
    result: t.GplType
    owner: Union[ModuleSym, ClassSym, None]
    public: bool = False
    shared: bool = False
    decl: A.ProcDecl | A.Accessor | None = None
    locals: dict[str, VarSym] = field(default_factory=dict)
    labels: dict[str, A.Label] = field(default_factory=dict)
    uses_result: bool = False
    prop: PropSym | None = None
    overload_index: int = 0

    @property
    def min_args(self) -> int:
        return sum(1 for p in self.params if not p.optional)

    @property
    def is_function(self) -> bool:
        return self.result is not t.VOID

    @property
    def module(self) -> ModuleSym | None:
        owner = self.owner
        while isinstance(owner, ClassSym):
            owner = owner.outer if owner.outer is not None else owner.module
        return owner if isinstance(owner, ModuleSym) else None


@dataclass(eq=False)
class PropSym:
    name: str
    span: Span | None
    type: t.GplType
    owner: ClassSym
    public: bool = False
    shared: bool = False
    getter: ProcSym | None = None
    setter: ProcSym | None = None
    decl: A.PropertyDecl | None = None


@dataclass(eq=False)
class DelegateSym:
    name: str
    span: Span | None
    params: list[VarSym]
    result: t.GplType
    owner: Union[ModuleSym, ClassSym, None]
    public: bool = False
    decl: A.DelegateDecl | None = None
    type: t.ClassType = field(default=None)  # type: ignore[assignment]


@dataclass(eq=False)
class ClassSym:
    name: str
    span: Span | None
    module: ModuleSym | None
    outer: ClassSym | None
    public: bool = False
    decl: A.ClassDecl | None = None
    members: dict[str, Member] = field(default_factory=dict)
    ctors: list[ProcSym] = field(default_factory=list)
    type: t.ClassType = field(default=None)  # type: ignore[assignment]

    @property
    def path(self) -> list[str]:
        """Declared names from the module down: ``["Station", "Gripper"]`` (module excluded)."""
        names = [self.name]
        outer = self.outer
        while outer is not None:
            names.insert(0, outer.name)
            outer = outer.outer
        return names

    def fields(self) -> list[VarSym]:
        return [m for m in self.members.values() if isinstance(m, VarSym)]


@dataclass(eq=False)
class ModuleSym:
    name: str
    span: Span | None
    path: str  # the source file (diagnostic path)
    decl: A.ModuleDecl | None = None
    members: dict[str, Member] = field(default_factory=dict)
    order: int = 0
    py_name: str = ""

    @property
    def init_proc(self) -> ProcSym | None:
        m = self.members.get("init")
        return m if isinstance(m, ProcSym) and not m.params else None


Member = Union[VarSym, ProcSym, PropSym, ClassSym, DelegateSym]


@dataclass
class ProjectSyms:
    """Everything declared in a project."""

    name: str
    modules: dict[str, ModuleSym] = field(default_factory=dict)
    module_list: list[ModuleSym] = field(default_factory=list)
    # Top-level classes (AMB-1) are Public and module-less; they live in a synthetic module.
    procs: list[ProcSym] = field(default_factory=list)
    classes: list[ClassSym] = field(default_factory=list)

    def public_members(self, name: str) -> list[tuple[ModuleSym, Member]]:
        """Public members called ``name`` in all modules (the "unambiguous Public name" rule)."""
        key = name.lower()
        out = []
        for mod in self.module_list:
            m = mod.members.get(key)
            if m is not None and getattr(m, "public", False):
                out.append((mod, m))
        return out
