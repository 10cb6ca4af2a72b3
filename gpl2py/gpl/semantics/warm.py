"""Checking a project again after an edit, checking only what the edit can have changed (issue 23).

The language server checks a project after every pause in typing.  The semantic pass
(:class:`~gpl2py.gpl.semantics.check.Checker`) has three phases: it declares everything
(``collect``: a tenth of the work), checks each module's members and each top-level class
(``items``, ``check_item``: most of it), then folds the Consts and finds the start procedure
(``finish``).  The check of one module's bodies reads the declarations of the whole project and
the module's own bodies, never another module's bodies; so after an edit that leaves every
declaration as the rest of the project sees it, checking the other modules again would give what it
gave.  :func:`analyze_warm` keeps the last analysis (a :class:`WarmAnalysis`) and, after such an
edit, checks again only the members whose declaration changed.

How the result stays exactly a cold check's:

* **Declarations are collected again, from scratch**, into fresh symbol tables: the collection's
  diagnostics are a cold run's by construction.  The fresh tables are then paired with the kept
  ones, symbol by symbol (same modules, members in the same order, same kinds and numbers of
  parameters: :func:`_structure`), and the kept symbol objects take the fresh ones' facts
  (positions, syntax nodes, types), so that what the unchanged files' analysis points to (each
  expression's ``Info`` names a symbol) describes the new text.  A declaration whose name, type,
  access or parameters changed (:func:`_interface`) has the files that name it checked again too;
  when the structure differs -- a declaration added, removed or renamed -- the whole project is
  checked with the fresh tables, as a cold check does.
  When the only files that changed were parsed again one procedure at a time and each such
  procedure's declaration reads as before, collecting again would only point that procedure's
  symbol (and its parameters' and containers') at the new nodes: :func:`_rebind` does just that.
* **Each member's diagnostics are kept** and reported again, in the order a cold check reports
  them; the members checked again are those whose declaring node changed (every member of a file
  parsed whole, one procedure after ``syntax/reparse.py``) and every member of a file that names
  a declaration whose type changed.
* **Stubs** (names of protected code) are reported at their first use, so which file reports one
  depends on the order everything is checked in: an edit in a file whose check used the stub table,
  before the edit or after it, checks the whole project.
* **What needs the whole project** (the Consts' values, the start procedure) is found again every
  time; it is small.

Facts the checker records on symbols of other modules as it goes (a module variable passed ByRef
is ``boxed``, one read somewhere is ``read``) are kept when the module that recorded them is checked
again: they are what the lowering reads to shape the code, not diagnostics, and a fact that stays
true after the edit removed its cause only keeps a variable in a cell it no longer needs.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import cache
from itertools import islice

from gpl2py import messages as M
from gpl2py.diagnostics import Diagnostic, DiagnosticSink, Severity
from gpl2py.gpl.semantics.catalogue import Catalogue
from gpl2py.gpl.semantics.check import Checker, InfoTable, Model
from gpl2py.gpl.semantics.info import DYNAMIC_MEMBERS
from gpl2py.gpl.semantics.stubs import Stub, StubTable
from gpl2py.gpl.semantics.symbols import (
    ClassSym,
    DelegateSym,
    Locals,
    ModuleSym,
    OverloadSet,
    ProcSym,
    ProjectSyms,
    PropSym,
    VarSym,
)
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.shift import Shift
from gpl2py.source import Span

#: The Model's tables keyed by syntax nodes, which a member's check fills for its nodes.
_NODE_TABLES = ("proc_of_decl", "class_of_decl", "delegate_of_decl", "catch_var", "decl_new", "redeclared")
#: Fields of symbols that link symbols (kept as they are: the kept structure equals the fresh one),
#: or that the lowering fills in (``py_name``).
_LINKS = frozenset({"owner", "params", "locals", "labels", "members", "ctors", "procs", "prop", "getter",
                    "setter", "module", "outer", "py_name"})
#: Facts the checker records on a variable wherever it is used (module docstring).
_USE_FACTS = ("boxed", "assigned", "read")


@dataclass
class _Item:
    """What checking one member of a module (or one top-level class) left: its diagnostics, the
    nodes it added to the model's tables, and how often it used the stub table."""

    diags: list[Diagnostic]
    keys: dict[str, list[object]]
    nodes: list[A.Expr]
    byref: set[A.Expr]
    stub_uses: int


@dataclass
class WarmAnalysis:
    """The last analysis of a project and what :func:`analyze_warm` needs to redo part of it."""

    settings: tuple[object, ...]
    checker: Checker
    units: list[A.SourceUnit]
    collected: list[Diagnostic] = field(default_factory=list)  # the collection's diagnostics
    items: dict[object, _Item] = field(default_factory=dict)  # by the member's symbol
    finished: list[Diagnostic] = field(default_factory=list)  # ``finish``'s diagnostics
    #: how the last call went: "cold" (the whole project checked) or "warm" (what changed)
    how: str = "cold"
    #: what the last call checked: the files (cold), the members' names (warm)
    checked: list[str] = field(default_factory=list)

    #: members to check again whatever changed: their diagnostics name a line that an edit moved
    #: (:func:`shift_analysis`); and whether the declarations must be collected again for that
    stale: set[object] = field(default_factory=set)
    recollect: bool = False

    #: whether the Infos of each declaration of a module (each top-level class) hold one of
    #: ``info.DYNAMIC_MEMBERS``, by the id of its node
    dynamic: dict[int, tuple[A.Node, bool]] = field(default_factory=dict)

    @property
    def model(self) -> Model:
        return self.checker.model

    def dynamic_members(self) -> bool:
        """Whether some expression reads a member of a value of unknown type (what the lowering's
        ``ProjectNames.dynamic_members`` asks), walking only the declarations checked since last
        asked: walking every expression of the project after each edit took as long as checking a
        file."""
        found = False
        seen: dict[int, tuple[A.Node, bool]] = {}
        for unit in self.units:
            for top in unit.members:
                for node in (top.members if isinstance(top, A.ModuleDecl) else [top]):
                    kept = self.dynamic.get(id(node))
                    if kept is None or kept[0] is not node:
                        kept = (node, any(isinstance(i, DYNAMIC_MEMBERS) for _, i in InfoTable.walk(node)))
                    seen[id(node)] = kept
                    found = found or kept[1]
        self.dynamic = seen
        return found or any(isinstance(n._info, DYNAMIC_MEMBERS) for n in self.model.info.nodes())

    def diagnostics(self) -> list[Diagnostic]:
        """Every diagnostic of the analysis, in the order a cold check reports them."""
        out = list(self.collected)
        for _mod, member in _members(self.checker):
            out.extend(self.items[member].diags)
        out.extend(self.finished)
        return out


def analyze_warm(units: list[A.SourceUnit], catalogue: Catalogue, project_name: str = "",
                 start: str | None = None, *, kept: WarmAnalysis | None = None, protected: bool = False,
                 strict: bool = False, stub_provider: Callable[[Stub], str | None] | None = None,
                 start_span: Span | None = None, sources_missing: bool = False,
                 texts: Mapping[str, str] | None = None) -> WarmAnalysis:
    """:func:`~gpl2py.gpl.semantics.check.analyze` of ``units``, redoing only what changed since
    ``kept`` (the result of the last call for the same project, or None).  ``texts``: each unit's
    source text by its path, where the files that name a changed declaration are found (without
    them, a declaration whose type changed checks the whole project).  The diagnostics are
    :meth:`WarmAnalysis.diagnostics` (not reported to a sink: the caller replays them through its
    filter), equal to a cold analysis's."""
    settings = (project_name, start, start_span, protected, strict, sources_missing, id(catalogue))
    if kept is not None and kept.settings == settings and len(kept.units) == len(units) and not kept.recollect \
            and _rebind(kept, units):
        # (only procedures parsed again, their declarations as they were: no need to collect again)
        if _recheck(kept, None, units, kept.collected, start, start_span, texts):
            return kept
        kept = None  # (a stub met: the whole project; and ``kept`` may be half changed already)
    sink = DiagnosticSink()  # unfiltered: the caller's filter applies when they are replayed
    fresh = Checker(ProjectSyms(project_name), catalogue, sink,
                    StubTable(sink, protected=protected, strict=strict, provider=stub_provider))
    fresh.sources_missing = sources_missing
    fresh.collect(units)
    collected = list(sink)
    if kept is not None and kept.settings == settings and len(kept.units) == len(units):
        if _recheck(kept, fresh, units, collected, start, start_span, texts):
            return kept
    state = WarmAnalysis(settings, fresh, list(units), collected)
    state.checked = [u.path for u in units]
    for mod, member in _members(fresh):
        state.items[member] = _check(fresh, mod, member)
    state.finished = _finish(fresh, start, start_span)
    fresh.model.errors_reported = any(d.severity is Severity.ERROR for d in state.diagnostics())
    return state


def _recheck(kept: WarmAnalysis, fresh: Checker | None, units: list[A.SourceUnit], collected: list[Diagnostic],
             start: str | None, start_span: Span | None, texts: Mapping[str, str] | None) -> bool:
    """Check again the items of the files that changed since ``kept``, and of the files that name a
    declaration whose type or parameters changed; False (``kept`` then is stale) when the whole
    project must be checked: a declaration added, removed or renamed, a stub met.  ``fresh``: the
    declarations collected again, or None when :func:`_rebind` already pointed the kept ones at
    the new nodes."""
    changed = {i for i, (a, b) in enumerate(zip(kept.units, units)) if a is not b}
    old = kept.checker
    differs: set[str] = set()
    pairs = _pair_projects(old.model.project, fresh.model.project, differs) if fresh is not None else []
    if pairs is None:
        return False
    again = set(changed)
    if differs:
        if texts is None:
            return False
        named = re.compile(r"(?<!\w)(?:" + "|".join(re.escape(n) for n in sorted(differs)) + r")(?!\w)",
                           re.IGNORECASE)
        again |= {i for i, u in enumerate(units) if i not in changed and named.search(texts.get(u.path, "x"))}
    members = _members(old)
    redo = _changed_members(members, kept.units, units, changed) | kept.stale
    for i in again - changed:  # (the files naming a changed declaration: all their members)
        nodes = _member_nodes(units[i])
        redo.update(m for _mod, m in members if any(id(n) in nodes for n in _nodes_of(m)))
        for key in nodes:
            kept.dynamic.pop(key, None)  # (their Infos are made again)
    if any(kept.items[m].stub_uses for m in redo):
        return False  # which file reports a stub depends on the order everything is checked in
    _transplant(pairs)
    for m in redo:  # (checked again: each procedure starts from its parameters, as collected)
        for proc in _procs_under(m):
            proc.locals = Locals((v.name.lower(), v) for v in proc.params)
            proc.labels = {}
            proc.uses_result = False
    model = old.model
    stale = [kept.items.pop(m) for m in redo]
    for item in stale:
        for name in _NODE_TABLES:
            table = getattr(model, name)
            for key in item.keys[name]:
                table.pop(key, None)
        model.byref_temps.difference_update(item.byref)
    model.info.drop_nodes({id(n) for item in stale for n in item.nodes})
    for i in changed:
        model.info.replace_tree(kept.units[i], units[i])
    kept.units = list(units)
    old.forget_shared_infos()
    uses = old.stubs.uses
    for mod, member in members:
        if member in redo:
            kept.items[member] = _check(old, mod, member)
    if old.stubs.uses != uses:
        return False  # a stub met for the first time, or again: which file reports it needs the order
    kept.collected = collected
    kept.finished = _finish(old, start, start_span)
    model.errors_reported = any(d.severity is Severity.ERROR for d in kept.diagnostics())
    kept.how = "warm"
    kept.stale, kept.recollect = set(), False
    kept.checked = [_name_of(m) for _mod, m in members if m in redo]
    return True


def _members(checker: Checker) -> list[tuple[ModuleSym, object]]:
    """What is checked, one member at a time: each member of each module, each top-level class."""
    return [(mod, m) for mod, members in checker.items() for m in members]


def _nodes_of(member: object) -> list[object]:
    """The syntax nodes that declare ``member`` (an overload set: each overload's)."""
    if isinstance(member, OverloadSet):
        return [p.decl for p in member.procs]
    return [getattr(member, "decl", None)]


def _member_nodes(unit: A.SourceUnit) -> set[int]:
    """The ids of the nodes that declare the members of ``unit``'s modules (each declarator of a
    variable declaration), and of its top-level classes."""
    out: set[int] = set()
    for top in unit.members:
        for node in (top.members if isinstance(top, A.ModuleDecl) else [top]):
            out.add(id(node))
            if isinstance(node, A.VarDecl):
                out.update(id(d) for d in node.declarators)
    return out


def _changed_members(members: list[tuple[ModuleSym, object]], old: list[A.SourceUnit], new: list[A.SourceUnit],
                     changed: set[int]) -> set[object]:
    """The members declared by a file of ``changed`` whose declaring node is not shared by its old
    and new trees (the whole file when it was parsed again; one procedure after
    ``syntax/reparse.py``), whether their symbols still name the old nodes or already the new."""
    redo: set[object] = set()
    for i in changed:
        before, after = _member_nodes(old[i]), _member_nodes(new[i])
        kept, either = before & after, before | after  # (a symbol names its old node, or its new one)
        redo.update(m for _mod, m in members
                    if any(id(n) in either for n in _nodes_of(m)) and not all(id(n) in kept for n in _nodes_of(m)))
    return redo


def _procs_under(member: object) -> list[ProcSym]:
    """Every procedure a member holds: itself, its overloads, its accessors, a class's methods."""
    if isinstance(member, ProcSym):
        return [member]
    if isinstance(member, OverloadSet):
        return list(member.procs)
    if isinstance(member, PropSym):
        return [p for p in (member.getter, member.setter) if p is not None]
    if isinstance(member, ClassSym):
        return [*member.ctors, *(p for m in member.members.values() for p in _procs_under(m))]
    return []


def _name_of(member: object) -> str:
    return str(getattr(member, "name", ""))


def _check(checker: Checker, mod: ModuleSym, member: object) -> _Item:
    """Check one member with a sink of its own, noting what it added to the model."""
    model = checker.model
    sink = DiagnosticSink()
    checker.use_sink(sink)
    sizes = {name: len(getattr(model, name)) for name in _NODE_TABLES}
    nodes, byref, uses = model.info.node_count(), set(model.byref_temps), checker.stubs.uses
    checker.check_members(mod, [member])
    keys = {}
    for name in _NODE_TABLES:
        table = getattr(model, name)
        keys[name] = list(islice(reversed(table), len(table) - sizes[name]))
    return _Item(list(sink), keys, model.info.nodes_since(nodes), model.byref_temps - byref,
                 checker.stubs.uses - uses)


def _finish(checker: Checker, start: str | None, start_span: Span | None) -> list[Diagnostic]:
    sink = DiagnosticSink()
    checker.use_sink(sink)
    checker.finish(start, start_span)
    return list(sink)


# -- pairing the kept symbols with the fresh ones -------------------------------------------------------


def _shape(e: object) -> object:
    """What an expression says, without where it is (a parameter's default, compared)."""
    if isinstance(e, A.Node):
        return (type(e).__name__, *(_shape(getattr(e, f.name)) for f in dataclasses.fields(e)
                                    if not f.name.startswith("_") and f.name not in ("span", "leading_comments")))
    if isinstance(e, list):
        return tuple(_shape(x) for x in e)
    return e


def _interface(s: object) -> tuple[object, ...]:
    """What the rest of a project sees of a declaration: its name, type, access, parameters."""
    if isinstance(s, VarSym):
        return (s.name, s.type, s.storage, s.public, s.shared, s.const, s.byref, s.optional, _shape(s.default))
    if isinstance(s, ProcSym):
        return (s.name, s.kind, s.result, s.public, s.shared, s.overload_index)
    if isinstance(s, PropSym):
        return (s.name, s.type, s.public, s.shared)
    if isinstance(s, DelegateSym):
        return (s.name, s.result, s.public, s.type)
    if isinstance(s, ClassSym):
        return (s.name, s.public, s.type)
    return (getattr(s, "name", None),)


def _structure(s: object) -> tuple[object, ...]:
    """What must not change for the kept symbols to stand for the fresh ones: how many parameters,
    constructors, overloads and accessors; a module's name, file and place."""
    if isinstance(s, (ProcSym, DelegateSym)):
        return (len(s.params),)
    if isinstance(s, ClassSym):
        return (len(s.ctors),)
    if isinstance(s, OverloadSet):
        return (len(s.procs),)
    if isinstance(s, PropSym):
        return (s.getter is None, s.setter is None)
    if isinstance(s, ModuleSym):
        return (s.name, s.path, s.order)
    return ()


def _pair_projects(old: ProjectSyms, new: ProjectSyms, differs: set[str]) -> list[tuple[object, object]] | None:
    """Every (kept, fresh) pair of symbols, or None when the two projects declare different
    things; ``differs`` gets the name (lower case) by which the rest of the project refers to each
    declaration whose :func:`_interface` changed."""
    out: list[tuple[object, object]] = []
    pairing = _Pairing(out, differs)
    if not pairing.tables(old.modules, new.modules, None):  # (the synthetic module of top-level classes too)
        return None
    by_fresh = {id(b): a for a, b in out}
    for olds, news in ((old.procs, new.procs), (old.classes, new.classes)):
        if len(olds) != len(news) or any(by_fresh.get(id(b)) is not a for a, b in zip(olds, news)):
            return None
    return out


@dataclass
class _Pairing:
    out: list[tuple[object, object]]
    differs: set[str]

    def tables(self, a: dict[str, object], b: dict[str, object], ref: str | None) -> bool:
        return list(a) == list(b) and all(self.pair(a[k], b[k], ref or k) for k in a)

    def lists(self, a: list[object], b: list[object], ref: str) -> bool:
        return len(a) == len(b) and all(self.pair(x, y, ref) for x, y in zip(a, b))

    def pair(self, a: object, b: object, ref: str) -> bool:
        """Pair ``a`` with ``b`` and what they hold; ``ref``: the name the project uses them by
        (a parameter's procedure, a property's accessors, a class's constructors)."""
        if type(a) is not type(b) or _structure(a) != _structure(b):
            return False
        if _interface(a) != _interface(b):
            self.differs.add(ref.lower())
        self.out.append((a, b))
        if isinstance(a, ModuleSym):
            return self.tables(a.members, b.members, None)  # type: ignore[arg-type, union-attr]
        if isinstance(a, ClassSym):
            return self.tables(a.members, b.members, None) and self.lists(a.ctors, b.ctors, a.name)  # type: ignore[arg-type, union-attr]
        if isinstance(a, (ProcSym, DelegateSym)):
            return self.lists(a.params, b.params, ref)  # type: ignore[union-attr, arg-type]
        if isinstance(a, PropSym):
            return self.lists([x for x in (a.getter, a.setter) if x is not None],
                              [x for x in (b.getter, b.setter) if x is not None], ref)  # type: ignore[union-attr]
        if isinstance(a, OverloadSet):
            return self.lists(a.procs, b.procs, ref)  # type: ignore[arg-type, union-attr]
        return True


def _transplant(pairs: list[tuple[object, object]]) -> None:
    """The kept symbols take the fresh ones' facts (where they are, their syntax nodes, their types)."""
    for old, new in pairs:
        if _same_node(old, new):
            continue  # declared by a file that did not change: the same facts
        for name in _facts(type(old)):
            if name in _USE_FACTS:
                setattr(old, name, getattr(old, name) or getattr(new, name))
            else:
                setattr(old, name, getattr(new, name))


def _rebind(kept: WarmAnalysis, units: list[A.SourceUnit]) -> bool:
    """When every file that changed was parsed again one procedure at a time (``syntax/reparse.py``)
    and each such procedure's declaration reads as it did (name, modifiers, parameters, result,
    where it is), point the kept symbols at the new nodes -- all that collecting the declarations
    again would change -- and say True; else False, with nothing changed."""
    plan: list[tuple[object, A.Node, A.Node]] = []
    for old, new in zip(kept.units, units):
        if old is not new and not _plan(kept.model, old.members, new.members, plan):
            return False
    for sym, old, new in plan:
        if isinstance(sym, ProcSym):
            assert isinstance(old, A.ProcDecl) and isinstance(new, A.ProcDecl)
            sym.span = new.span
            for v in sym.params:
                param = new.params[next(i for i, p in enumerate(old.params) if p is v.declared_at)]
                v.declared_at, v.default = param, param.default
        sym.decl = new  # type: ignore[attr-defined]
    return True


def _plan(model: Model, old: list[A.Stmt], new: list[A.Stmt], plan: list[tuple[object, A.Node, A.Node]]) -> bool:
    """What :func:`_rebind` changes for the declarations ``old`` -> ``new`` of a file or container."""
    if len(old) != len(new):
        return False
    for a, b in zip(old, new):
        if a is b:
            continue
        if isinstance(a, A.ModuleDecl) and isinstance(b, A.ModuleDecl):
            sym: object = model.project.modules.get(a.name.lower())
            if getattr(sym, "decl", None) is not a or not _plan(model, a.members, b.members, plan):
                return False
        elif isinstance(a, A.ClassDecl) and isinstance(b, A.ClassDecl):
            sym = model.class_of_decl.get(a)
            if sym is None or not _plan(model, a.members, b.members, plan):
                return False
        elif isinstance(a, A.ProcDecl) and isinstance(b, A.ProcDecl):
            sym = model.proc_of_decl.get(a)
            if sym is None or _header(a) != _header(b) or any(
                    not any(p is v.declared_at for p in a.params) for v in sym.params):  # type: ignore[attr-defined]
                return False
        else:
            return False
        plan.append((sym, a, b))
    return True


def _header(d: A.ProcDecl) -> tuple[object, ...]:
    """A procedure's declaration as the symbol tables see it, where it starts included (not where
    it ends: Enter in its body moves its End line, and :func:`_rebind` gives the symbol the new
    span)."""
    return (d.kind, d.name, tuple(d.modifiers), tuple(A.dump(p) for p in d.params),
            A.dump(d.return_type) if d.return_type is not None else None, d._file, d._line, d._col)


def _same_node(old: object, new: object) -> bool:
    """Whether both symbols come from the same syntax node (their file's tree was reused)."""
    node = getattr(old, "decl", None)
    if isinstance(old, VarSym) and isinstance(old.declared_at, A.Node):
        node = old.declared_at
    if node is None:
        return False
    return node is (new.declared_at if isinstance(new, VarSym) and isinstance(old, VarSym)
                    and isinstance(old.declared_at, A.Node) else getattr(new, "decl", None))


# -- lines added or removed -------------------------------------------------------------------------


def shift_analysis(kept: WarmAnalysis, old_unit: A.SourceUnit, shift: Shift) -> bool:
    """Move what ``kept`` copied out of the nodes of ``old_unit``'s file that an edit adding or
    removing lines moved (``syntax/reparse.py`` moved the nodes themselves, in place): the spans of
    the symbols (a ProcSym's, a ClassSym's ... a VarSym reads its node's), the kept diagnostics,
    the stubs' first uses.  False when ``kept`` is not the analysis of ``old_unit`` (its last check
    did not finish): it cannot be moved and must be dropped.

    A diagnostic whose message names a line (a duplicate declaration's "line 12") cannot be moved
    without being made again: its member is checked again (``stale``), and when it is one of the
    collection's, the declarations are collected again (``recollect``)."""
    if not any(u is old_unit for u in kept.units):
        return False
    for sym in _symbols(kept.model.project):
        if isinstance(sym, VarSym):
            if isinstance(sym.declared_at, Span):
                sym.declared_at = shift.span(sym.declared_at)
        else:
            sym.span = shift.span(sym.span)  # type: ignore[attr-defined]
    for member, item in kept.items.items():
        if any(_names_a_line(d) and shift.moves(d.span) for d in item.diags):
            kept.stale.add(member)
        item.diags = shift.diagnostics(item.diags)
    if any(_names_a_line(d) and shift.moves(d.span) for d in kept.collected):
        kept.recollect = True
    kept.collected = shift.diagnostics(kept.collected)
    kept.finished = shift.diagnostics(kept.finished)
    for stub in kept.checker.stubs.stubs.values():
        stub.span = shift.span(stub.span)
    return True


def _names_a_line(d: Diagnostic) -> bool:
    """Whether the message of ``d`` names a line (which moving its span would leave stale)."""
    return d.code == M.DUPLICATE_DECLARATION.code


def _symbols(project: ProjectSyms) -> list[object]:
    """Every symbol of a project but the locals (whose positions are their nodes')."""
    out: list[object] = []
    stack: list[object] = [*project.modules.values(), *project.procs, *project.classes]
    seen: set[int] = set()
    while stack:
        sym = stack.pop()
        if id(sym) in seen:
            continue
        seen.add(id(sym))
        out.append(sym)
        if isinstance(sym, (ModuleSym, ClassSym)):
            stack.extend(sym.members.values())
            if isinstance(sym, ClassSym):
                stack.extend(sym.ctors)
        elif isinstance(sym, (ProcSym, DelegateSym)):
            stack.extend(sym.params)
        elif isinstance(sym, OverloadSet):
            stack.extend(sym.procs)
        elif isinstance(sym, PropSym):
            stack.extend(p for p in (sym.getter, sym.setter) if p is not None)
    return out


@cache
def _facts(kind: type) -> tuple[str, ...]:
    """The fields of a symbol class that :func:`_transplant` copies (a dataclass's fields, or the
    ``FIELDS`` a slotted symbol such as ``VarSym`` names)."""
    names = getattr(kind, "FIELDS", None) or tuple(f.name for f in dataclasses.fields(kind))
    return tuple(name for name in names if name not in _LINKS)


__all__ = ["WarmAnalysis", "analyze_warm", "shift_analysis"]
