"""Per-project and per-module naming state shared by the lowering steps (docs/security.md, "Names").

A :class:`Scope` is one Python namespace: it hands out each name once, in a deterministic order,
so two things never share a Python name.  :class:`ProjectNames` fixes the Python name of every
module, stub module and stub, and the set of identifiers GPL code uses; :class:`ModuleContext`
collects the imports one generated module needs and hands out the local name of each runtime
helper (aliased with a leading ``_`` only when a GPL name in the project is spelled the same, so
``to_int32`` stays readable and never shadows a program name) and of each Static local.  The
rules for single names are in ``lower/names.py``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from collections.abc import Iterable
from typing import AbstractSet, Any

from gpl2py.gpl.lower.names import (
    PACKAGE_NAMES,
    RUNTIME_IMPORTS,
    module_base,
    overload_names,
    py_ident,
    runtime_names,
)
from gpl2py.kept import KeptErrors
from gpl2py.gpl.lower.stub_names import STUBS_MODULE_NAMES, stub_attr_base, stub_module_name
from gpl2py.gpl.semantics.catalogue import load_catalogue
from gpl2py.gpl.semantics.check import Model
from gpl2py.gpl.semantics.info import DYNAMIC_MEMBERS
from gpl2py.gpl.semantics.resolve import TOP_MODULE
from gpl2py.gpl.semantics.stubs import Stub
from gpl2py.gpl.semantics.symbols import (
    ClassSym, DelegateSym, Locals, ModuleSym, OverloadSet, ProcSym, PropSym, VarSym,
)




@dataclass
class Scope:
    """The names bound in one Python namespace.  :meth:`claim` returns ``preferred`` the first
    time and ``preferred_2``, ``preferred_3`` ... when it is taken, so every claimant gets its own
    name and the same input always gives the same names (claims happen in source order)."""

    taken: set[str] = field(default_factory=set)
    #: names bound already, read only: looked in as well as ``taken``, not copied into it
    outer: AbstractSet[str] = frozenset()

    def claim(self, preferred: str) -> str:
        name, n = preferred, 1
        while name in self.taken or name in self.outer:
            n += 1
            name = f"{preferred}_{n}"
        self.taken.add(name)
        return name


def builtin_names() -> frozenset[str]:
    """The names generated code imports from ``gplrt.builtins``: the catalogue's classes,
    functions, constants and value-type members (``Location``, ``CStr``, ``StringMembers``)."""
    cat = load_catalogue()
    tables: list[dict[str, Any]] = [cat.classes, cat.functions, cat.constants, cat.type_members]
    return frozenset(entry.python_name for table in tables for entry in table.values())


@dataclass
class ProjectNames:
    module_py: dict[ModuleSym, str] = field(default_factory=dict)
    taken: set[str] = field(default_factory=set)  # the runtime names a project name hides (alias)
    # stub modules (Module.Name of a module only protected code declares): lower name -> file
    stub_module_py: dict[str, str] = field(default_factory=dict)
    # Some expression reads a member of a value of unknown type (a stub's result): classes then
    # list their Public members for gplrt.lang.members (see lower/classes.py).
    dynamic_members: bool = False
    # overloaded procedures (one Python function each); the others keep py_ident(name)
    overload_py: dict[ProcSym, str] = field(default_factory=dict)
    stub_attr_py: dict[Stub, str] = field(default_factory=dict)  # each stub's name in its module
    runtime: frozenset[str] = field(default_factory=frozenset)  # every name a module may import

    def proc_name(self, p: ProcSym) -> str:
        """The Python name of procedure ``p`` (not a constructor or property accessor)."""
        return self.overload_py.get(p) or py_ident(p.name)

    @classmethod
    def build(cls, model: Model, dynamic_members: bool | None = None,
              kept: LocalsTaken | None = None) -> ProjectNames:
        """The names of ``model``'s project; ``dynamic_members``, when the caller knows it (the
        language server's warm analysis, semantics/warm.py), saves walking every expression;
        ``kept``, what an earlier build found among each procedure's locals (the same caller's)."""
        names = cls()
        names.runtime = runtime_names(builtin_names())
        taken: set[str] = set()
        top = model.project.modules.get(TOP_MODULE.lower())  # top-level classes (AMB-1)
        for mod in [*model.project.module_list, *([top] if top is not None else [])]:
            for m in mod.members.values():
                taken.add(py_ident(m.name))
        for c in model.project.classes:
            taken.update(py_ident(m.name) for m in c.members.values())
        tables = [mod.members for mod in model.project.module_list] + [c.members for c in model.project.classes]
        # a local's name is asked about only as an overload's, a module's or a runtime name: the
        # others stay out of the set (a Dim of 26,000 names made it as large: docs/security.md)
        wanted = {w for table in tables for m in table.values() if isinstance(m, OverloadSet)
                  for w in _overload_wanted(m)}
        stubs = model.stubs
        bases = {"_top_classes", *(module_base(mod.name) for mod in model.project.module_list),
                 *(module_base(spelled) for spelled in (stubs.modules.values() if stubs is not None else ()))}
        found = kept if kept is not None else LocalsTaken()
        for x in found.update(model.project.procs, names.runtime, bases, wanted):
            taken.update(x)
        for table in tables:
            for m in table.values():
                if isinstance(m, OverloadSet):
                    names._name_overloads(m, taken)
        # what ``alias`` asks: whether a runtime name is a project's too (not the project's names
        # themselves, which a long Dim makes tens of thousands of: docs/security.md, "Input size")
        names.taken = taken & names.runtime
        names.dynamic_members = dynamic_members if dynamic_members is not None else any(
            isinstance(i, DYNAMIC_MEMBERS) for i in model.info.values())
        # the package's namespace: its modules and stub modules never take a name a module
        # imports from the runtime or one the package defines (docs/security.md, "Names")
        package = Scope(set(names.runtime) | set(PACKAGE_NAMES) | {"sys"}, taken)
        mods = list(model.project.module_list)
        if top is not None:
            mods.append(top)
        for mod in mods:
            base = "_top_classes" if mod.name == TOP_MODULE else module_base(mod.name)
            name = _claim_module(package, base)
            names.module_py[mod] = name
            mod.py_name = name
        for key, spelled in sorted(stubs.modules.items()) if stubs is not None else ():
            names.stub_module_py[key] = _claim_module(package, module_base(spelled))
        if stubs is not None:
            names._name_stubs(stubs.ordered())
        return names

    def _name_stubs(self, stubs: list[Stub]) -> None:
        """One scope per stub module: its stubs, their setters (``set_<name>``) and the module's
        own names (``not_available``, ``_reset`` ...) never share a name."""
        scopes: dict[str, Scope] = {}
        for stub in stubs:
            module = stub_module_name(stub, self.stub_module_py)
            scope = scopes.setdefault(module, Scope(set(STUBS_MODULE_NAMES)))
            base = stub_attr_base(stub)
            setter = stub.builtin is not None and stub.assigned
            attr = scope.claim(base)
            while setter and "set_" + attr in scope.taken:
                attr = scope.claim(base)
            if setter:
                scope.taken.add("set_" + attr)
            self.stub_attr_py[stub] = attr

    def _name_overloads(self, group: OverloadSet, taken: set[str]) -> None:
        """One Python name per overload (names.overload_names), none equal to another name of
        the project; the names become taken."""
        for p, name in zip(group.procs, _overload_wanted(group)):
            while name in taken:
                name += "_"
            taken.add(name)
            self.overload_py[p] = name


def _overload_wanted(group: OverloadSet) -> list[str]:
    """The Python name each overload of ``group`` prefers (names.overload_names)."""
    return overload_names(group.name, [[str(v.type) for v in p.params] for p in group.procs])


class LocalsTaken:
    """Which Python names of each procedure's locals :meth:`ProjectNames.build` must keep out of
    the package's names, kept between builds (the language server's, one per project).

    A procedure's locals table is made again whenever its procedure is checked again
    (``semantics/warm.py``) and is not changed after its check, so what was found among its
    names holds as long as the table is the same object and the names asked about are the same;
    walking every local of the project on each edit was a tenth of an edit's check."""

    def __init__(self) -> None:
        self._asked: tuple[frozenset[str], frozenset[str], frozenset[str]] | None = None
        self._found: dict[int, tuple[Locals, int, frozenset[str]]] = {}  # id(locals) -> what, of how many

    def update(self, procs: Iterable[ProcSym], runtime: frozenset[str], bases: AbstractSet[str],
               wanted: AbstractSet[str]) -> list[frozenset[str]]:
        """For each of ``procs``, the names of its locals that are runtime names or one of
        ``bases`` followed by ``_mod``s or one of ``wanted`` followed by ``_``s."""
        asked = (runtime, frozenset(bases), frozenset(wanted))
        old = self._found if asked == self._asked else {}
        self._asked, self._found = asked, {}
        out = []
        for p in procs:
            table = p.locals
            hit = old.get(id(table))
            if hit is None or hit[0] is not table or hit[1] != len(table):
                hit = (table, len(table), frozenset(
                    x for x in map(py_ident, table.names())
                    if x in runtime or _stem_in(x, "_mod", bases) or _stem_in(x, "_", wanted)))
            self._found[id(table)] = hit
            out.append(hit[2])
        return out


def _stem_in(name: str, suffix: str, stems: AbstractSet[str]) -> bool:
    """Whether ``name`` is one of ``stems`` followed by ``suffix`` none or more times (the names
    ``_claim_module`` and ``_name_overloads`` try for a stem)."""
    while name not in stems:
        if not name.endswith(suffix):
            return False
        name = name[:-len(suffix)]
    return True


def _claim_module(package: Scope, base: str) -> str:
    """A module file name: ``base``, else ``base_mod``, ``base_mod_mod`` ... (unique in the package)."""
    name = base
    while name in package.taken or name in package.outer:
        name += "_mod"
    package.taken.add(name)
    return name


class ModuleContext:
    """Imports and names for one generated module."""

    def __init__(self, model: Model, names: ProjectNames, mod: ModuleSym, kept: KeptErrors) -> None:
        self.model = model
        self.names = names
        self.mod = mod
        self.kept = kept  # the errors code that keeps one raises (gpl2py/kept.py)
        self.imports: dict[str, dict[str, str]] = {}  # python module -> {name: alias}
        self.siblings: set[str] = set()
        self.needs_this = False
        self.statics: list[tuple[str, str]] = []  # module globals holding Static locals
        self._static_scope = Scope()  # their names: ``_s_<Proc>_<name>`` is not one-to-one
        self._static_names: dict[tuple[VarSym, str], str] = {}

    def alias(self, name: str) -> str:
        """How the generated code spells runtime helper ``name`` (without importing it)."""
        return "_" + name if name in self.names.taken else name

    def helper(self, module: str, name: str) -> str:
        """Import ``name`` from ``module`` and return how the generated code spells it.

        Only names listed in ``names.RUNTIME_IMPORTS`` (or the catalogue's, from ``gplrt.builtins``)
        may be imported: the table is what keeps module files from hiding a helper, so a helper
        missing from it is a bug in gpl2py, reported here rather than as a broken package."""
        allowed = RUNTIME_IMPORTS.get(module)
        if not (name in allowed if allowed is not None else module == "gplrt.builtins" and name in self.names.runtime):
            raise AssertionError(f"runtime name {module}.{name} is missing from names.RUNTIME_IMPORTS")
        alias = self.alias(name)
        self.imports.setdefault(module, {})[name] = alias
        return alias

    def static_global(self, v: VarSym, preferred: str, role: str = "value") -> str:
        """The module global holding Static local ``v`` (``role`` ``"value"``) or its
        initialised-once flag (``"done"``): ``preferred`` unless another Static took it first
        (``_s_A_B_C`` is both ``A_B.C`` and ``A.B_C``)."""
        key = (v, role)
        name = self._static_names.get(key)
        if name is None:
            name = self._static_scope.claim(preferred)
            self._static_names[key] = name
        return name

    def builtin(self, py_name: str) -> str:
        return self.helper("gplrt.builtins", py_name)

    def module_prefix(self, mod: ModuleSym | None) -> str:
        """``""`` for this module, else ``"sibling."`` (and the sibling is imported)."""
        name = self.module_ref(mod)
        return "" if name is None else name + "."

    def module_ref(self, mod: ModuleSym | None) -> str | None:
        """None for this module, else the name of the sibling module (imported)."""
        if mod is None or mod is self.mod:
            return None
        name = self.names.module_py[mod]
        self.siblings.add(name)
        return name

    def stub_ref(self, stub: Stub) -> str:
        """How this module names a stub: ``vendor_lib.Proc`` or ``_stubs.Foo`` (imported)."""
        return ".".join(self.stub_parts(stub))

    def stub_parts(self, stub: Stub) -> tuple[str, str]:
        """The module (imported) and attribute that :meth:`stub_ref` joins: ``("_stubs", "Foo")``."""
        name = stub_module_name(stub, self.names.stub_module_py)
        self.siblings.add(name)
        return name, self.names.stub_attr_py[stub]

    def owner_module(self, sym: object) -> ModuleSym | None:
        owner = getattr(sym, "owner", None)
        if isinstance(sym, ClassSym):
            return sym.module
        while isinstance(owner, ClassSym):
            owner = owner.module
        if isinstance(owner, ProcSym):
            return owner.module
        return owner if isinstance(owner, ModuleSym) else None

    def class_ref(self, cls: ClassSym | DelegateSym) -> str:
        """How this module names a user class or delegate class (``Outer.Inner``, ``mod.Cls``)."""
        if isinstance(cls, ClassSym):
            path = [py_ident(n) for n in cls.path]
            return self.module_prefix(cls.module) + ".".join(path)
        owner = cls.owner
        if isinstance(owner, ClassSym):
            return self.class_ref(owner) + "." + py_ident(cls.name)
        return self.module_prefix(owner if isinstance(owner, ModuleSym) else None) + py_ident(cls.name)

    def member_owner_ref(self, sym: VarSym | ProcSym | PropSym) -> str:
        """The qualifier of a module-level or Shared member (``""``, ``"mod."`` or ``"Cls."``)."""
        owner = sym.owner
        if isinstance(owner, ClassSym):
            return self.class_ref(owner) + "."
        return self.module_prefix(owner if isinstance(owner, ModuleSym) else None)
