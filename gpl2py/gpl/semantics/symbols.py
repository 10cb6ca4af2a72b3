"""Symbol tables: project -> module -> class -> procedure (spec §6, §8.3, §12).

Symbols are plain mutable dataclasses compared by identity; the semantic pass keys its tables on
them and the lowering reads them.  Every table is keyed by the lower-cased name because GPL is
case-insensitive (§1.7); each symbol keeps the spelling of its declaration, which the generated
Python uses everywhere.
"""

from __future__ import annotations

from array import array
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import TypeVar, Union

from gpl2py.gpl.semantics import types as t
from gpl2py.source import Span
from gpl2py.gpl.syntax import ast as A


#: VarSym's yes/no facts, one bit each of its ``_flags``
_VAR_FLAGS = ("public", "shared", "const", "byref", "optional", "boxed", "assigned", "read")


def _flag(bit: int) -> property:
    def get(self: VarSym) -> bool:
        return bool(self._flags & bit)

    def set_(self: VarSym, value: bool) -> None:
        self._flags = self._flags | bit if value else self._flags & ~bit

    return property(get, set_)


class VarSym:
    """A variable: local, Static local, parameter, module variable, class field or Const.

    ``storage`` is one of ``local``, ``static``, ``param``, ``module``, ``field``.
    ``boxed`` is set by the checker when a local is passed to a ByRef parameter: the lowering then
    keeps it in a cell for the whole procedure, which makes ByRef true aliasing (§9.3).
    ``declared_at`` is the declaring node (or a span): :attr:`span` reads the node's span when
    asked, so a project's variables do not keep a Span object each (docs/security.md, "Input size").
    The eight yes/no facts (``public`` ... ``read``) are bits of one integer, read and set like
    attributes: a slot each made a VarSym 152 bytes, and a ``Dim`` of many names holds one per
    name (96 bytes now).  Compared by identity, like every symbol.
    """

    __slots__ = ("name", "declared_at", "type", "storage", "owner", "decl", "default", "_flags")
    #: What a VarSym says, as a dataclass's fields would (the language server's warm re-check
    #: copies them from a fresh symbol onto the kept one: semantics/warm.py)
    FIELDS = ("name", "declared_at", "type", "storage", "owner", "decl", "default", *_VAR_FLAGS)

    def __init__(self, name: str, declared_at: A.Node | Span | None, type: t.GplType, storage: str,
                 owner: object = None, public: bool = False, shared: bool = False, const: bool = False,
                 decl: A.VarDeclarator | None = None, byref: bool = False, optional: bool = False,
                 default: A.Expr | None = None, boxed: bool = False, assigned: bool = False,
                 read: bool = False) -> None:
        self.name = name
        self.declared_at = declared_at
        self.type = type
        self.storage = storage
        self.owner = owner
        self.decl = decl
        self.default = default
        flags = 0
        for bit, value in enumerate((public, shared, const, byref, optional, boxed, assigned, read)):
            if value:
                flags |= 1 << bit
        self._flags = flags

    public = _flag(1)
    shared = _flag(2)
    const = _flag(4)
    byref = _flag(8)
    optional = _flag(16)
    boxed = _flag(32)
    assigned = _flag(64)
    read = _flag(128)

    def __repr__(self) -> str:
        flags = "".join(f", {f}=True" for i, f in enumerate(_VAR_FLAGS) if self._flags >> i & 1)
        return f"VarSym(name={self.name!r}, type={self.type!r}, storage={self.storage!r}{flags})"

    @property
    def span(self) -> Span | None:
        at = self.declared_at
        return at.span if isinstance(at, A.Node) else at


T = TypeVar("T")


class LocalRun:
    """The locals a long ``Dim`` of simple names declares (its declarators a
    :class:`~gpl2py.gpl.syntax.ast.CompactDeclarators`), found by name without a symbol each: an
    open-addressing table of the names' indices, keyed by the hash of the lower-cased name.  The
    :class:`VarSym` of a name is made when it is looked up (the names the program uses), one kept
    per name.  A name the Dim declares again, or one the procedure declared before it, is not in
    the table: it was declared the way a short Dim's is (``Checker._declare_locals``).

    Why: a ``Dim`` of 26,000 names held a VarSym, a dict entry and an interned name per name, a
    third of its memory (issue 20, docs/security.md "Input size"); a name costs eight bytes of
    the table here."""

    __slots__ = ("decls", "types", "owner", "_table", "_declared", "_made")

    def __init__(self, decls: A.CompactDeclarators, types: list[t.GplType], owner: ProcSym) -> None:
        self.decls = decls
        self.types = types  # each group's
        self.owner = owner
        size = 8
        while size < 2 * len(decls):
            size *= 2
        self._table = array("i", [-1]) * size
        self._declared = bytearray(len(decls))  # 1 for a name in the table
        self._made: dict[int, VarSym] = {}

    def _slot(self, key: str) -> tuple[int, int]:
        """The slot of ``key`` (lower-case) in the table, and the index there (-1: not there)."""
        table, decls = self._table, self.decls
        mask = len(table) - 1
        slot = hash(key) & mask
        while True:
            i = table[slot]
            if i < 0 or decls.name(i).lower() == key:
                return slot, i
            slot = (slot + 1) & mask

    def add(self, i: int, key: str) -> None:
        """Name ``i`` (``key`` lower-cased) is declared here; it is not yet."""
        self._table[self._slot(key)[0]] = i
        self._declared[i] = 1

    def __contains__(self, key: str) -> bool:
        return self._slot(key)[1] >= 0

    def get(self, key: str) -> VarSym | None:
        i = self._slot(key)[1]
        return None if i < 0 else self.var(i)

    def var(self, i: int) -> VarSym:
        """The variable of name ``i`` (made on first use)."""
        v = self._made.get(i)
        if v is None:
            d = self.decls[i]
            v = self._made[i] = VarSym(d.name, d, self.types[self.decls.group(i)], "local", owner=self.owner,
                                       decl=d)
        return v

    def indices(self) -> Iterator[int]:
        """The indices of the names declared here, in order (one at a time: a list of them was a
        quarter of the lowering's peak)."""
        declared = self._declared
        return (i for i in range(len(declared)) if declared[i])

    def __len__(self) -> int:
        return self._declared.count(1)

    def made(self) -> list[VarSym]:
        """The variables made so far, in declaration order."""
        return [self._made[i] for i in sorted(self._made)]


class Locals:
    """A procedure's parameters and locals by lower-cased name, in declaration order: a dict of
    symbols and the :class:`LocalRun` of each long ``Dim``, which makes a symbol only for a name
    looked up.  It answers as the dict of every symbol would (``get``, ``[]``, ``in``,
    ``values``), and :meth:`made` gives only the symbols that exist: a name no statement names
    has none, so it was never read, assigned or passed ByRef (what the lowering asks)."""

    __slots__ = ("_vars", "_runs")

    def __init__(self, items: Iterable[tuple[str, VarSym]] = ()) -> None:
        self._vars: dict[str, VarSym] = dict(items)
        self._runs: list[tuple[int, LocalRun]] = []  # each run, after how many of _vars

    def get(self, key: str, default: VarSym | None = None) -> VarSym | None:
        v = self._vars.get(key)
        if v is not None:
            return v
        for _, run in self._runs:  # (a procedure has none, but for a long Dim)
            v = run.get(key)
            if v is not None:
                return v
        return default

    def __getitem__(self, key: str) -> VarSym:
        v = self.get(key)
        if v is None:
            raise KeyError(key)
        return v

    def __setitem__(self, key: str, v: VarSym) -> None:
        self._vars[key] = v

    def __contains__(self, key: object) -> bool:
        return key in self._vars or any(key in run for _, run in self._runs)

    def add_run(self, run: LocalRun) -> None:
        """The locals of a long Dim, declared after those declared so far."""
        self._runs.append((len(self._vars), run))

    def _in_order(self, of_item: Callable[[str, VarSym], T],
                  of_run: Callable[[LocalRun], Iterable[T]]) -> Iterator[T]:
        """What ``of_item`` gives of each name and symbol and ``of_run`` of each run, in declaration
        order."""
        runs = iter(self._runs)
        at, run = next(runs, (-1, None))
        for k, (key, v) in enumerate(self._vars.items()):
            while run is not None and at == k:
                yield from of_run(run)
                at, run = next(runs, (-1, None))
            yield of_item(key, v)
        while run is not None:
            yield from of_run(run)
            at, run = next(runs, (-1, None))

    def values(self) -> Iterator[VarSym]:
        """Every local, in declaration order (a symbol made for each name of a long Dim)."""
        return self._in_order(lambda _, v: v, lambda run: map(run.var, run.indices()))

    def items(self) -> Iterator[tuple[str, VarSym]]:
        return self._in_order(lambda key, v: (key, v),
                              lambda run: ((run.decls.name(i).lower(), run.var(i)) for i in run.indices()))

    def __iter__(self) -> Iterator[str]:
        """The lower-cased names, in declaration order."""
        return self._in_order(lambda key, _: key, lambda run: (run.decls.name(i).lower() for i in run.indices()))

    keys = __iter__

    def __len__(self) -> int:
        return len(self._vars) + sum(len(run) for _, run in self._runs)

    def made(self) -> Iterator[VarSym]:
        """The locals that have a symbol, in declaration order: all but the names of a long Dim
        that nothing looked up (so nothing reads, assigns or passes them)."""
        return self._in_order(lambda _, v: v, LocalRun.made)

    def names(self) -> Iterator[str]:
        """The spelling of every local, in declaration order, without making a symbol."""
        return self._in_order(lambda _, v: v.name, lambda run: map(run.decls.name, run.indices()))

    def __repr__(self) -> str:
        return f"Locals({list(self._vars)!r}, runs={len(self._runs)})"


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
    locals: Locals = field(default_factory=Locals)
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

    @property
    def init_proc(self) -> ProcSym | None:
        """The class's ``Shared Sub Init()``, which the controller runs at start-up like a module's
        ``Init`` (real code: ``Class_gpofile.gpl:74``, "Init routine called automatically at
        startup"; docs/design/real-code.md).  An instance ``Init`` needs an object: never run."""
        return next((p for p in procedures(self.members.get("init"))
                     if not p.params and p.shared and p.kind == "Sub"), None)

    def classes(self) -> list[ClassSym]:
        """This class and the classes nested in it, outer first, in declaration order."""
        out = [self]
        for m in self.members.values():
            if isinstance(m, ClassSym):
                out.extend(m.classes())
        return out


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
        return next((p for p in procedures(self.members.get("init")) if not p.params), None)


@dataclass(eq=False)
class OverloadSet:
    """Procedures of one module or class that share a name (real GPL overloads them by
    parameter list; docs/design/real-code.md).  The member table holds the set in place of a
    single :class:`ProcSym`; the checker picks one overload per call (argument count, then
    argument types), so the lowering only ever sees the chosen :class:`ProcSym`.

    ``procs`` keeps declaration order; ``procs[k].overload_index == k``.
    """

    name: str
    span: Span | None
    owner: Union[ModuleSym, ClassSym, None]
    procs: list[ProcSym] = field(default_factory=list)

    @property
    def public(self) -> bool:
        """Public if any overload is (each call still checks the overload it picks)."""
        return any(p.public for p in self.procs)

    @property
    def shared(self) -> bool:
        return any(p.shared for p in self.procs)

    @property
    def result(self) -> t.GplType:
        """The result type when every overload agrees, else ERROR (a call's type is the chosen
        overload's)."""
        first = self.procs[0].result
        return first if all(p.result == first for p in self.procs) else t.ERROR


Member = Union[VarSym, ProcSym, PropSym, ClassSym, DelegateSym, OverloadSet]


def procedures(member: object) -> list[ProcSym]:
    """The procedures a member table entry stands for: the overloads of a set, the procedure
    itself, or none (a variable, class ...)."""
    if isinstance(member, OverloadSet):
        return list(member.procs)
    if isinstance(member, ProcSym):
        return [member]
    return []


@dataclass(frozen=True)
class PublicName:
    """A Public name reachable without qualification (§6.4): a module's Public member, a
    top-level class, or a Public Shared/Const member of a top-level class.  ``where`` names the
    module or class that declares it (for the ambiguity message)."""

    where: str
    module: ModuleSym
    member: Member


@dataclass
class ProjectSyms:
    """Everything declared in a project."""

    name: str
    modules: dict[str, ModuleSym] = field(default_factory=dict)
    module_list: list[ModuleSym] = field(default_factory=list)
    # Top-level classes (AMB-1) are Public and module-less; they live in a synthetic module.
    procs: list[ProcSym] = field(default_factory=list)
    classes: list[ClassSym] = field(default_factory=list)

    # the synthetic module holding top-level classes (resolve.TOP_MODULE), if any
    top: ModuleSym | None = None
    # every name public_members() answers for, built on first use (see there)
    _public: dict[str, tuple[PublicName, ...]] | None = field(default=None, repr=False)

    def public_members(self, name: str) -> tuple[PublicName, ...]:
        """Every Public ``name`` that may be used unqualified (the "unambiguous Public name"
        rule, §6.4): Public members of all modules and, as real code uses them, top-level
        classes and the Public Shared or Const members of top-level classes (a top-level class
        is reachable like a module: ``Station.LoadFile``, ``STA_FL_PAL``).  Modules come in
        project order, then the top-level classes.

        Every name that is not local, not a member of the enclosing class or module and not a
        module asks here (``Console``, ``CInt`` and every other built-in too), so the answer
        comes from an index of all Public names, built once: scanning every module per lookup
        made a project's analysis grow with the square of its number of modules.  Whoever
        changes a member table after the first lookup calls :meth:`names_changed`."""
        index = self._public
        if index is None:
            index = self._public = self._index_public()
        return index.get(name.lower(), ())

    def names_changed(self) -> None:
        """A module's or top-level class's member table changed: index again on next use."""
        self._public = None

    def _index_public(self) -> dict[str, tuple[PublicName, ...]]:
        index: dict[str, list[PublicName]] = {}
        for mod in self.module_list:
            for key, m in mod.members.items():
                if getattr(m, "public", False):
                    index.setdefault(key, []).append(PublicName(mod.name, mod, m))
        top = self.top
        if top is not None:
            for key, cls in top.members.items():
                if isinstance(cls, ClassSym):
                    index.setdefault(key, []).append(PublicName(cls.name, top, cls))
            for c in top.members.values():
                if not isinstance(c, ClassSym) or not c.public:
                    continue
                for key, m in c.members.items():
                    if not isinstance(m, ClassSym) and getattr(m, "public", False) \
                            and (getattr(m, "shared", False) or getattr(m, "const", False)):
                        index.setdefault(key, []).append(PublicName(c.name, top, m))
        return {key: tuple(found) for key, found in index.items()}
