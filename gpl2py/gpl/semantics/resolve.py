"""Declarations and name resolution (spec §6.4, §8.3, §12).

:func:`collect` builds the symbol tables of a whole project in one pass over the syntax trees, so
that every later lookup may refer forward (a procedure may call one declared further down, a
module may use another module's Public variable).  :class:`Resolver` answers "what does this name
mean here?" with the lookup order of §6.4:

1. procedure locals, parameters and the function-name result variable;
2. members of the enclosing class and its enclosing classes;
3. the enclosing module's members;
4. Public members of all other modules, if unique (ambiguity is an error), from an index of the
   project's Public names built once (``ProjectSyms.public_members``);
5. modules and top-level classes by name, then built-in classes, functions and constants.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, BuiltinConstant, BuiltinFunction, Catalogue
from gpl2py.gpl.semantics.stubs import StubTable
from gpl2py.gpl.semantics.symbols import (
    ClassSym,
    DelegateSym,
    Member,
    ModuleSym,
    OverloadSet,
    ProcSym,
    ProjectSyms,
    PropSym,
    VarSym,
)
from gpl2py.gpl.syntax import ast as A

# The synthetic module that holds top-level classes (AMB-1: Public and module-less).
TOP_MODULE = "_Top"


@dataclass(frozen=True, slots=True)
class FoundMember:
    """A lookup found a declaration of the project (a local, a member of a class or module, a
    Public member of another module), declared in ``module``."""

    sym: Member
    module: ModuleSym | None = None


@dataclass(frozen=True, slots=True)
class FoundResult:
    """A lookup found the Function's own name inside it: its result variable (or a call)."""

    sym: ProcSym


@dataclass(frozen=True, slots=True)
class FoundModule:
    """A lookup found a module's name."""

    sym: ModuleSym


@dataclass(frozen=True, slots=True)
class FoundBuiltinClass:
    sym: BuiltinClass


@dataclass(frozen=True, slots=True)
class FoundBuiltinFunction:
    sym: BuiltinFunction


@dataclass(frozen=True, slots=True)
class FoundBuiltinConstant:
    sym: BuiltinConstant


#: The result of a name lookup: one typed record per kind of declaration found.
Found = FoundMember | FoundResult | FoundModule | FoundBuiltinClass | FoundBuiltinFunction | FoundBuiltinConstant


class Resolver:
    """Type and name lookups over a project's symbol tables and the built-in catalogue."""

    def __init__(self, project: ProjectSyms, catalogue: Catalogue, sink: DiagnosticSink,
                 stubs: StubTable | None = None) -> None:
        self.project = project
        self.cat = catalogue
        self.sink = sink
        self.stubs = stubs if stubs is not None else StubTable(sink)
        self.class_by_key: dict[str, ClassSym] = {}
        self.delegate_by_key: dict[str, DelegateSym] = {}

    # -- types ---------------------------------------------------------------------------------

    def resolve_type(self, ref: A.TypeRef | None, module: ModuleSym | None, cls: ClassSym | None,
                     report: bool = True) -> t.GplType:
        """The static type named by ``ref`` as seen from ``module``/``cls`` (ERROR if unknown)."""
        if ref is None:
            return t.ERROR
        prim = t.lookup_primitive(ref.name)
        if prim is not None:
            return prim
        parts = ref.parts
        sym = self._lookup_type_path(parts, module, cls)
        if sym is not None:
            return sym.type
        if len(parts) == 1:
            # a global class (Controller, Math ...) is a type too: a variable of it stands for
            # the class (check.py, docs/design/real-code.md)
            b = self.cat.lookup_class(parts[0])
            if b is not None:
                return b.type
        if len(parts) == 1 and parts[0].lower() == "object":
            # VB's universal type: GPL has none [000 L852-855], so it is neither unknown (a typo)
            # nor a class of the protected code, and the message says what to do instead
            if report:
                self.sink.report(M.NO_OBJECT_TYPE, ref.span)
            return t.ERROR
        if self.stubs.protected and len(parts) <= 2 and not (
                len(parts) == 2 and parts[0].lower() in self.project.modules):
            # a class of the protected code: values of it have the permissive type ANY
            module = parts[0] if len(parts) == 2 else None
            self.stubs.protected_name(parts[-1], ref.span, module=module).created = True
            return t.ANY
        if report:
            self.sink.report(M.UNKNOWN_TYPE, ref.span, name=ref.name)
        return t.ERROR

    def _lookup_type_path(self, parts: list[str], module: ModuleSym | None,
                          cls: ClassSym | None) -> ClassSym | DelegateSym | None:
        first = parts[0].lower()
        start: object = None
        # nested/enclosing classes first, then the module, then modules by name, then Public names
        c = cls
        while c is not None and start is None:
            if c.name.lower() == first:
                start = c
            else:
                m = c.members.get(first)
                if isinstance(m, (ClassSym, DelegateSym)):
                    start = m
            c = c.outer
        if start is None and module is not None:
            m = module.members.get(first)
            if isinstance(m, (ClassSym, DelegateSym)):
                start = m
        if start is None and first in self.project.modules and len(parts) > 1:
            start = self.project.modules[first]
        if start is None:
            top = self.project.modules.get(TOP_MODULE.lower())
            if top is not None and isinstance(top.members.get(first), ClassSym):
                start = top.members[first]
        if start is None:
            cands = [p.member for p in self.project.public_members(first)
                     if isinstance(p.member, (ClassSym, DelegateSym))]
            if len(cands) == 1:
                start = cands[0]
        for part in parts[1:]:
            if isinstance(start, (ModuleSym, ClassSym)):
                start = start.members.get(part.lower())
            else:
                return None
        return start if isinstance(start, (ClassSym, DelegateSym)) else None

    def class_of(self, typ: t.GplType) -> ClassSym | None:
        if isinstance(typ, t.ClassType) and not typ.builtin:
            return self.class_by_key.get(typ.key)
        return None

    def delegate_of(self, typ: t.GplType) -> DelegateSym | None:
        if isinstance(typ, t.ClassType) and not typ.builtin:
            return self.delegate_by_key.get(typ.key)
        return None

    def builtin_of(self, typ: t.GplType) -> BuiltinClass | None:
        return self.cat.members_of(typ)

    # -- names -----------------------------------------------------------------------------------

    def lookup(self, name: str, proc: ProcSym | None, cls: ClassSym | None,
               module: ModuleSym | None) -> Found | None | str:
        """Find ``name``; returns a :class:`Found`, ``None`` (undeclared) or the text of an
        ambiguity (``"A, B"`` module names) for the caller to report."""
        key = name.lower()
        if proc is not None:
            v = proc.locals.get(key)
            if v is not None:
                return FoundMember(v, proc.module)
            if proc.is_function and proc.kind == "Function" and proc.name.lower() == key:
                return FoundResult(proc)
        c = cls
        while c is not None:
            m = c.members.get(key)
            if m is not None:
                return FoundMember(m, c.module)
            c = c.outer
        if module is not None:
            m = module.members.get(key)
            if m is not None:
                return FoundMember(m, module)
        if key in self.project.modules and key != TOP_MODULE.lower():
            return FoundModule(self.project.modules[key])
        pub = self.project.public_members(key)
        if len(pub) == 1:
            return FoundMember(pub[0].member, pub[0].module)
        if len(pub) > 1:
            return ", ".join(p.where for p in pub)
        b = self.cat.lookup_class(key)
        if b is not None:
            return FoundBuiltinClass(b)
        f = self.cat.lookup_function(key)
        if f is not None:
            return FoundBuiltinFunction(f)
        k = self.cat.lookup_constant(key)
        if k is not None:
            return FoundBuiltinConstant(k)
        return None


# -- collecting declarations ---------------------------------------------------------------------


def _access(modifiers: Iterable[str], default_public: bool = False) -> bool:
    mods = {m.lower() for m in modifiers}
    if "public" in mods:
        return True
    if "private" in mods:
        return False
    return default_public


def _shared(modifiers: Iterable[str]) -> bool:
    return any(m.lower() == "shared" for m in modifiers)


class Collector:
    """First pass: every module, class, procedure, property, delegate and module/class variable."""

    def __init__(self, resolver: Resolver, sink: DiagnosticSink) -> None:
        self.r = resolver
        self.sink = sink
        self.pending_types: list[tuple[object, A.TypeRef | None, ModuleSym, ClassSym | None, int]] = []
        self.overload_sets: list[tuple[dict[str, Member], OverloadSet]] = []

    def collect_units(self, units: list[A.SourceUnit]) -> None:
        project = self.r.project
        top: ModuleSym | None = None
        for order, unit in enumerate(units):
            for member in unit.members:
                if isinstance(member, (A.ModuleDecl, A.ClassDecl)) and not member.name:
                    continue
                if isinstance(member, A.ModuleDecl):
                    key = member.name.lower()
                    if key in project.modules:
                        prev = project.modules[key]
                        self.sink.report(M.DUPLICATE_DECLARATION, member.span, name=member.name,
                                         scope="project", line=prev.span.line if prev.span else 0)
                        continue
                    mod = ModuleSym(member.name, member.span, unit.path, member, order=len(project.module_list))
                    project.modules[key] = mod
                    project.module_list.append(mod)
                    project.names_changed()
                    self._members(mod, None, member.members)
                elif isinstance(member, A.ClassDecl):
                    if top is None:
                        top = ModuleSym(TOP_MODULE, None, unit.path, None, order=-1)
                        project.modules[TOP_MODULE.lower()] = top
                        project.top = top
                    self._class(top, None, member, default_public=True)

    # -- members ------------------------------------------------------------------------------------

    def _declare(self, table: dict[str, Member], name: str, sym: Member, span: object, scope: str) -> bool:
        key = name.lower()
        if key in ("_init", "_new"):
            self.sink.report(M.RESERVED_NAME, span, name=name)  # type: ignore[arg-type]
            return False
        prev = table.get(key)
        if prev is not None:
            line = prev.span.line if getattr(prev, "span", None) else 0
            self.sink.report(M.DUPLICATE_DECLARATION, span, name=name, scope=scope, line=line)  # type: ignore[arg-type]
            return False
        table[key] = sym
        self.r.project.names_changed()  # (a table no lookup indexes: harmless)
        return True

    def _overload(self, table: dict[str, Member], p: ProcSym) -> bool:
        """Add ``p`` to the procedures already declared under its name (real GPL overloads
        procedures by parameter list, docs/design/real-code.md); False when the name is free or
        taken by something that is not a procedure (then it is declared, or reported, as usual).
        Overloads with the same parameter types are reported once the types are known
        (:meth:`check_overloads`)."""
        prev = table.get(p.name.lower())
        if isinstance(prev, ProcSym) and prev.kind in ("Sub", "Function"):
            group = OverloadSet(prev.name, prev.span, prev.owner, [prev])
            table[p.name.lower()] = group
            self.r.project.names_changed()
            self.overload_sets.append((table, group))
        elif isinstance(prev, OverloadSet):
            group = prev
        else:
            return False
        p.overload_index = len(group.procs)
        group.procs.append(p)
        return True

    def check_overloads(self) -> None:
        """Report an overload whose parameter types repeat an earlier one's (no call could tell
        them apart) and drop it, so the rest of the pipeline sees well-formed sets."""
        for table, group in self.overload_sets:
            kept: list[ProcSym] = []
            for p in group.procs:
                same = next((q for q in kept if _signature(q) == _signature(p)), None)
                if same is not None:
                    self.sink.report(M.DUPLICATE_DECLARATION, p.span, name=p.name, scope="overload set",
                                     line=same.span.line if same.span else 0)
                    self.r.project.procs.remove(p)
                    continue
                p.overload_index = len(kept)
                kept.append(p)
            group.procs = kept
            if len(kept) == 1:  # nothing left to choose from: a plain procedure again
                kept[0].overload_index = 0
                table[group.name.lower()] = kept[0]
                self.r.project.names_changed()

    def _members(self, mod: ModuleSym, cls: ClassSym | None, members: list[A.Stmt]) -> None:
        table = cls.members if cls is not None else mod.members
        scope = "class" if cls is not None else "module"
        for m in members:
            if not getattr(m, "name", "x"):
                continue  # a declaration the parser could not read (already reported)
            if isinstance(m, A.VarDecl):
                public = _access(m.modifiers)
                # a Const is implicitly Shared: one value for the class, usable in Shared
                # procedures (real code: corpus Class_station.gpl:120; docs/design/real-code.md)
                shared = cls is None or m.is_const or _shared(m.modifiers)
                for d in m.declarators:
                    if not d.name:
                        continue
                    v = VarSym(d.name, d, t.ERROR, "field" if cls is not None else "module",
                               owner=cls or mod, public=public, shared=shared, const=m.is_const, decl=d)
                    if self._declare(table, d.name, v, d.span, scope):
                        self.pending_types.append((v, d.type, mod, cls, len(d.bounds) if d.bounds is not None else 0))
            elif isinstance(m, A.ProcDecl):
                p = self._proc(m, mod, cls)
                if m.name.lower() == "new" and cls is not None:
                    p.overload_index = len(cls.ctors)
                    cls.ctors.append(p)
                    continue
                if not self._overload(table, p):
                    self._declare(table, m.name, p, m.span, scope)
            elif isinstance(m, A.PropertyDecl) and cls is not None:
                prop = PropSym(m.name, m.span, t.ERROR, cls, _access(m.modifiers), _shared(m.modifiers), decl=m)
                self.pending_types.append((prop, m.type, mod, cls, 0))
                for acc in (m.getter, m.setter):
                    if acc is None:
                        continue
                    params: list[VarSym] = []
                    if acc.kind == "Set":
                        pname = acc.param.name if acc.param is not None else "value"
                        pv = VarSym(pname, acc.param or acc, t.ERROR, "param")
                        params.append(pv)
                        self.pending_types.append(
                            (pv, acc.param.type if acc.param is not None and acc.param.type else m.type, mod, cls, 0))
                    ps = ProcSym(m.name, acc.span, acc.kind, params, t.VOID, cls, prop.public, prop.shared,
                                 decl=acc, prop=prop)
                    for pv in params:
                        ps.locals[pv.name.lower()] = pv
                        pv.owner = ps
                    if acc.kind == "Get":
                        prop.getter = ps
                    else:
                        prop.setter = ps
                self._declare(table, m.name, prop, m.span, scope)
            elif isinstance(m, A.DelegateDecl):
                d = DelegateSym(m.name, m.span, [], t.VOID, cls or mod, _access(m.modifiers), m)
                qual = ".".join(([mod.name] if mod.name != TOP_MODULE else []) + (cls.path if cls else []) + [m.name])
                d.type = t.ClassType.of(qual)
                self.r.delegate_by_key[d.type.key] = d
                d.params = [self._param(p, mod, cls) for p in m.params]
                if m.return_type is not None:
                    self.pending_types.append((d, m.return_type, mod, cls, -1))
                self._declare(table, m.name, d, m.span, scope)
            elif isinstance(m, A.ClassDecl):
                self._class(mod, cls, m, default_public=False)

    def _class(self, mod: ModuleSym, outer: ClassSym | None, decl: A.ClassDecl, default_public: bool) -> None:
        cls = ClassSym(decl.name, decl.span, mod, outer, _access(decl.modifiers, default_public), decl)
        qual = ".".join(([mod.name] if mod.name != TOP_MODULE else []) + cls.path)
        cls.type = t.ClassType.of(qual)
        table = outer.members if outer is not None else mod.members
        if self._declare(table, decl.name, cls, decl.span, "class" if outer else "module"):
            self.r.class_by_key[cls.type.key] = cls
            self.r.project.classes.append(cls)
        self._members(mod, cls, decl.members)

    def _param(self, p: A.Param, mod: ModuleSym, cls: ClassSym | None) -> VarSym:
        v = VarSym(p.name, p, t.ERROR, "param", byref=p.by_ref, optional=p.optional, default=p.default)
        self.pending_types.append((v, p.type, mod, cls, p.array_rank))
        return v

    def _proc(self, decl: A.ProcDecl, mod: ModuleSym, cls: ClassSym | None) -> ProcSym:
        kind = "New" if (cls is not None and decl.name.lower() == "new") else decl.kind
        p = ProcSym(decl.name, decl.span, kind, [], t.VOID, cls or mod,
                    _access(decl.modifiers), cls is None or _shared(decl.modifiers), decl)
        optional_seen = False
        for prm in decl.params:
            v = self._param(prm, mod, cls)
            v.owner = p
            if prm.name.lower() in p.locals:
                # reported; the first parameter of that name stays the one (a second would be a
                # duplicate argument in Python, and --keep-going output must still compile)
                self.sink.report(M.DUPLICATE_DECLARATION, prm.span, name=prm.name, scope="procedure",
                                 line=decl.span.line)
                continue
            if optional_seen and not v.optional:
                # reported; treated as Optional with the type's default from here on
                self.sink.report(M.REQUIRED_AFTER_OPTIONAL, prm.span, name=prm.name)
                v.optional = True
            optional_seen = optional_seen or v.optional
            p.params.append(v)
            p.locals[prm.name.lower()] = v
        if decl.kind == "Function":
            if decl.return_type is not None:
                self.pending_types.append((p, decl.return_type, mod, cls, -1))
            else:
                p.result = t.ERROR
        self.r.project.procs.append(p)
        return p

    def resolve_pending(self) -> None:
        """Resolve declared types once every class is known (types may refer forward)."""
        for sym, ref, mod, cls, rank in self.pending_types:
            typ = self.r.resolve_type(ref, mod, cls)
            if rank > 0 and typ is not t.ERROR:
                typ = t.ArrayType(typ, rank)
            if isinstance(sym, ProcSym) or isinstance(sym, DelegateSym):
                sym.result = typ
            else:
                sym.type = typ  # type: ignore[union-attr]
        self.pending_types.clear()


def _signature(p: ProcSym) -> tuple[object, ...]:
    """What tells overloads apart: the parameter types in order (not names, not ByRef)."""
    return tuple(v.type for v in p.params)


def visible(member: object, from_module: ModuleSym | None, from_class: ClassSym | None) -> bool:
    """Whether a member can be named from the given place (Private is module/class local)."""
    if getattr(member, "public", True):
        return True
    owner = getattr(member, "owner", None)
    if isinstance(member, ClassSym):
        owner = member.outer or member.module
    if isinstance(owner, ModuleSym):
        return owner is from_module
    if isinstance(owner, ClassSym):
        c = from_class
        while c is not None:
            if c is owner:
                return True
            c = c.outer
        return False
    return True


__all__ = ["Resolver", "Collector", "Found", "visible", "TOP_MODULE"]
