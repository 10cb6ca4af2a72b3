"""Per-project and per-module naming state shared by the lowering steps.

:class:`ProjectNames` fixes the Python name of every module and the set of identifiers GPL code
uses; :class:`ModuleContext` collects the imports one generated module needs and hands out the
local name of each runtime helper (aliased with a leading ``_`` only when a GPL name in the
project is spelled the same, so ``to_int32`` stays readable and never shadows a program name).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gpl2py.lower.names import overload_names, py_ident, snake_case
from gpl2py.lower.stub_names import stub_attr, stub_module_name
from gpl2py.semantics.check import Model
from gpl2py.semantics.resolve import TOP_MODULE
from gpl2py.semantics.stubs import Stub
from gpl2py.semantics.symbols import ClassSym, DelegateSym, ModuleSym, OverloadSet, ProcSym, PropSym, VarSym


# Info kinds that name a member of a value whose class is unknown at translation time.
DYNAMIC_MEMBER_KINDS = frozenset({"extattr", "extinvoke"})


@dataclass
class ProjectNames:
    module_py: dict[ModuleSym, str] = field(default_factory=dict)
    taken: set[str] = field(default_factory=set)
    # stub modules (Module.Name of a module only protected code declares): lower name -> file
    stub_module_py: dict[str, str] = field(default_factory=dict)
    # Some expression reads a member of a value of unknown type (a stub's result): classes then
    # list their Public members for gplrt.lang.members (see lower/classes.py).
    dynamic_members: bool = False
    # overloaded procedures (one Python function each); the others keep py_ident(name)
    overload_py: dict[ProcSym, str] = field(default_factory=dict)

    def proc_name(self, p: ProcSym) -> str:
        """The Python name of procedure ``p`` (not a constructor or property accessor)."""
        return self.overload_py.get(p) or py_ident(p.name)

    @classmethod
    def build(cls, model: Model) -> ProjectNames:
        names = cls()
        taken: set[str] = set()
        for mod in model.project.module_list:
            for m in mod.members.values():
                taken.add(py_ident(m.name))
        for p in model.project.procs:
            taken.update(py_ident(v.name) for v in p.locals.values())
        for c in model.project.classes:
            taken.update(py_ident(m.name) for m in c.members.values())
        tables = [mod.members for mod in model.project.module_list] + [c.members for c in model.project.classes]
        for table in tables:
            for m in table.values():
                if isinstance(m, OverloadSet):
                    names._name_overloads(m, taken)
        names.taken = taken
        names.dynamic_members = any(i.kind in DYNAMIC_MEMBER_KINDS for i in model.info.values())
        used: set[str] = set()
        mods = list(model.project.module_list)
        top = model.project.modules.get(TOP_MODULE.lower())
        if top is not None:
            mods.append(top)
        for mod in mods:
            base = "_top_classes" if mod.name == TOP_MODULE else snake_case(mod.name)
            name = base
            while name in used or name in taken or name in ("init", "main", "sys"):
                name += "_mod"
            used.add(name)
            names.module_py[mod] = name
            mod.py_name = name
        stubs = model.stubs
        for key, spelled in sorted(stubs.modules.items()) if stubs is not None else ():
            name = snake_case(spelled)
            while name in used or name in taken or name in ("init", "main", "sys"):
                name += "_mod"
            used.add(name)
            names.stub_module_py[key] = name
        return names


    def _name_overloads(self, group: OverloadSet, taken: set[str]) -> None:
        """One Python name per overload (names.overload_names), none equal to another name of
        the project; the names become taken."""
        wanted = overload_names(group.name, [[str(v.type) for v in p.params] for p in group.procs])
        for p, name in zip(group.procs, wanted):
            while name in taken:
                name += "_"
            taken.add(name)
            self.overload_py[p] = name


class ModuleContext:
    """Imports and names for one generated module."""

    def __init__(self, model: Model, names: ProjectNames, mod: ModuleSym) -> None:
        self.model = model
        self.names = names
        self.mod = mod
        self.imports: dict[str, dict[str, str]] = {}  # python module -> {name: alias}
        self.siblings: set[str] = set()
        self.needs_this = False
        self.statics: list[tuple[str, str]] = []  # module globals holding Static locals

    def alias(self, name: str) -> str:
        """How the generated code spells runtime helper ``name`` (without importing it)."""
        return "_" + name if name in self.names.taken else name

    def helper(self, module: str, name: str) -> str:
        """Import ``name`` from ``module`` and return how the generated code spells it."""
        alias = self.alias(name)
        self.imports.setdefault(module, {})[name] = alias
        return alias

    def builtin(self, py_name: str) -> str:
        return self.helper("gplrt.builtins", py_name)

    def module_prefix(self, mod: ModuleSym | None) -> str:
        """``""`` for this module, else ``"sibling."`` (and the sibling is imported)."""
        if mod is None or mod is self.mod:
            return ""
        name = self.names.module_py[mod]
        self.siblings.add(name)
        return name + "."

    def stub_ref(self, stub: Stub) -> str:
        """How this module names a stub: ``vendor_lib.Proc`` or ``_stubs.Foo`` (imported)."""
        name = stub_module_name(stub, self.names.stub_module_py)
        self.siblings.add(name)
        return f"{name}.{stub_attr(stub)}"

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
