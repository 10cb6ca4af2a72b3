"""The typing pass: the static type and meaning of every expression, checked statements (spec §4-§11).

:func:`analyze` runs the whole semantic analysis of a project and returns a :class:`Model` that the
lowering reads.  For every expression node it records an :class:`Info`: the static type and *what
the node is*, as one typed record per kind (``semantics/info.py``: a :class:`VarInfo` for a
variable, a :class:`CallInfo` for a call of a user procedure, an :class:`IndexInfo` for an array
element, a :class:`BuiltinMemberInfo` for a built-in member, ...), so the lowering never has to
look a name up again.  Errors are reported to the sink with
positions and analysis carries on with the ERROR type, which silences follow-on errors, so one run
reports every independent mistake.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from sys import intern

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink, contained
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, Catalogue, Member, Param
from gpl2py.gpl.semantics.consts import fold_constants
from gpl2py.gpl.semantics.info import (
    CALLS,
    NAMES_NOT_VALUES,
    AddressOfInfo,
    BinaryInfo,
    ChainInfo,
    BuiltinClassInfo,
    BuiltinConstInfo,
    BuiltinFunctionInfo,
    BuiltinFunctionRefInfo,
    BuiltinMemberInfo,
    CallInfo,
    ClassInfo,
    DelegateCallInfo,
    DynamicCallInfo,
    DynamicMemberInfo,
    ErrorInfo,
    IndexInfo,
    Info,
    LiteralInfo,
    MeInfo,
    ModuleInfo,
    NewInfo,
    NothingInfo,
    ParamInfo,
    ProcRefInfo,
    PropInfo,
    ResultInfo,
    StubCallInfo,
    StubModuleInfo,
    StubNameInfo,
    StubNewInfo,
    StubRefInfo,
    TypeNameInfo,
    UnaryInfo,
    VarInfo,
)
from gpl2py.gpl.semantics.overloads import best_overloads, signature_text
from gpl2py.gpl.semantics.resolve import (
    TOP_MODULE,
    Collector,
    Found,
    FoundBuiltinClass,
    FoundBuiltinConstant,
    FoundBuiltinFunction,
    FoundMember,
    FoundModule,
    FoundResult,
    Resolver,
    visible,
)
from gpl2py.gpl.semantics.stubs import Stub, StubTable
from gpl2py.gpl.semantics.symbols import (
    ClassSym,
    DelegateSym,
    LocalRun,
    ModuleSym,
    OverloadSet,
    ProcSym,
    ProjectSyms,
    PropSym,
    VarSym,
    procedures,
)
from gpl2py.gpl.semantics.symbols import Member as UserMember
from gpl2py.source import Span
from gpl2py.gpl.syntax import ast as A


# One Info per literal type, shared by every literal (a third of all expressions in dense code;
# nothing changes a LiteralInfo): docs/security.md, "Input size".
_LITERAL = {typ: LiteralInfo(typ) for typ in (t.INTEGER, t.DOUBLE, t.STRING, t.BOOLEAN)}


class InfoTable:
    """``Model.info``: the :class:`Info` of each expression node, read and written as a mapping.

    Each expression keeps its Info in its own slot (``Expr._info``): a dict with an entry for every
    expression of a project took 3-5 bytes per byte of dense source, the slot one (docs/security.md,
    "Input size").  So a tree is analysed by one Model at a time.  :meth:`values` and
    :meth:`items` walk the trees given to :meth:`add_tree` (the parsed files) and the nodes given
    to :meth:`add_node` (those the semantic pass makes around parts of a tree), in no particular
    order; nodes the lowering adds are not walked.
    """

    __slots__ = ("_trees", "_nodes")

    def __init__(self) -> None:
        self._trees: list[A.Node] = []
        self._nodes: list[A.Expr] = []

    def add_tree(self, tree: A.Node) -> None:
        self._trees.append(tree)

    def add_node(self, node: A.Expr) -> None:
        """A node made by the semantic pass: its children, if any, belong to a tree already."""
        self._nodes.append(node)

    def __getitem__(self, node: A.Expr) -> Info:
        info = node._info
        if info is None:
            raise KeyError(node)
        return info  # type: ignore[return-value]

    def get(self, node: A.Expr, default: Info | None = None) -> Info | None:
        info = node._info
        return default if info is None else info  # type: ignore[return-value]

    def __setitem__(self, node: A.Expr, info: Info) -> None:
        node._info = info

    def __contains__(self, node: A.Expr) -> bool:
        return node._info is not None

    def items(self) -> Iterator[tuple[A.Expr, Info]]:
        for expr in self._nodes:
            if expr._info is not None:
                yield expr, expr._info  # type: ignore[misc]
        yield from self.walk(*self._trees)

    @staticmethod
    def walk(*trees: A.Node) -> Iterator[tuple[A.Expr, Info]]:
        """The Info of every expression of ``trees`` that has one."""
        stack = list(trees)
        while stack:  # (a loop, not recursion: an operator chain is as deep as it is long)
            node = stack.pop()
            info = getattr(node, "_info", None)  # (only expressions have one)
            if info is not None:
                yield node, info
            stack.extend(node.children())

    def values(self) -> Iterator[Info]:
        return (info for _, info in self.items())

    # -- what semantics/warm.py needs to check one file again --------------------------------------

    def replace_tree(self, old: A.Node, new: A.Node) -> None:
        """``new`` (a file parsed again) in place of ``old``."""
        self._trees[next(i for i, tree in enumerate(self._trees) if tree is old)] = new

    def node_count(self) -> int:
        return len(self._nodes)

    def nodes(self) -> list[A.Expr]:
        """The nodes given to :meth:`add_node`."""
        return self._nodes

    def nodes_since(self, count: int) -> list[A.Expr]:
        """The nodes given to :meth:`add_node` since there were ``count``."""
        return self._nodes[count:]

    def drop_nodes(self, ids: set[int]) -> None:
        """Forget the nodes (given by their ``id``) of a part of the project checked again."""
        if ids:
            self._nodes = [n for n in self._nodes if id(n) not in ids]


@dataclass
class Model:
    """The result of semantic analysis."""

    project: ProjectSyms
    resolver: Resolver
    info: InfoTable = field(default_factory=InfoTable)
    # Statement-level facts the lowering needs.
    proc_of_decl: dict[A.Node, ProcSym] = field(default_factory=dict)
    class_of_decl: dict[A.Node, ClassSym] = field(default_factory=dict)
    delegate_of_decl: dict[A.Node, DelegateSym] = field(default_factory=dict)
    catch_var: dict[A.CatchClause, A.Expr] = field(default_factory=dict)
    start: ProcSym | None = None
    byref_temps: set[A.Expr] = field(default_factory=set)
    decl_new: dict[A.VarDeclarator, A.New] = field(default_factory=dict)
    # a local declarator that declares an earlier declarator's variable -> that variable: a Dim
    # repeated in another block of the procedure (_declare_locals).  The others are found by name
    # (local_of): a dict entry per declarator was a tenth of a long Dim's memory (docs/security.md)
    redeclared: dict[A.VarDeclarator, VarSym] = field(default_factory=dict)
    stubs: StubTable | None = None  # names defined in protected code / missing built-in members
    # errors were reported before lowering, kept or ignored (it runs then for --keep-going or
    # ignored errors only): an expression without a meaning is one of them, not a gap in gpl2py
    errors_reported: bool = False
    # module and class Consts whose value translation computed (semantics/consts.py)
    const_values: dict[VarSym, object] = field(default_factory=dict)

    def type_of(self, e: A.Expr) -> t.GplType:
        i = self.info.get(e)
        return i.type if i is not None else t.ERROR

    def local_of(self, d: A.VarDeclarator, proc: ProcSym) -> VarSym | None:
        """The variable local declarator ``d`` of ``proc`` declares: its own, the earlier one a
        Dim in another block declares again, or None (a rejected duplicate, a name missing)."""
        v = self.redeclared.get(d)
        if v is not None:
            return v
        v = proc.locals.get(d.name.lower())
        return v if v is not None and v.decl == d else None  # (== : a CompactDeclarator is made anew when asked)


def _pinfo(params: Iterable[VarSym | Param]) -> tuple[ParamInfo, ...]:
    """The passing facts of a user procedure's parameters or a built-in member's."""
    return tuple(ParamInfo(p.name, p.type, p.byref, p.optional) for p in params)


def assignable(src: t.GplType, dst: t.GplType) -> bool:
    """Can a ``src`` value be stored in a ``dst`` variable (§4.2)?"""
    if t.permissive(src) or t.permissive(dst):
        return True
    if src is t.NOTHING and dst is t.STRING:
        return True  # Nothing stored into a String is the empty String (docs/design/real-code.md)
    if isinstance(dst, t.PrimitiveType):
        return isinstance(src, t.PrimitiveType)
    if src is t.NOTHING:
        return dst.is_reference
    if isinstance(dst, t.ClassType):
        return isinstance(src, t.ClassType) and src.key == dst.key
    if isinstance(dst, t.ArrayType):
        return isinstance(src, t.ArrayType) and src.rank == dst.rank and (
            src.element == dst.element or t.ERROR in (src.element, dst.element))
    return False


_COMPARE = {"=", "<>", "<", ">", "<=", ">="}


def nothing_as_string(op: str, lt: t.GplType, rt: t.GplType) -> tuple[t.GplType, t.GplType]:
    """The operand types of ``op`` with a Nothing beside a String read as a String.

    Real code compares Strings with Nothing (``s = Nothing``, ``s <> Nothing``) and tests
    ``s Is Nothing``; gpl2py makes Nothing the empty String wherever it meets one
    (docs/design/real-code.md), so comparisons and ``&`` see ``""``."""
    if op in _COMPARE or op == "&":
        if lt is t.STRING and rt is t.NOTHING:
            return lt, t.STRING
        if rt is t.STRING and lt is t.NOTHING:
            return t.STRING, rt
    return lt, rt


def _identity_operand(typ: t.GplType, other: t.GplType) -> bool:
    """Whether ``typ`` may stand on one side of ``Is`` with ``other`` on the other side.

    References and Nothing, as the manual says; a value of unknown type (a stub's result: it may
    be an object); and a String tested against Nothing, which real code does and which asks
    whether the String is empty (docs/design/real-code.md)."""
    if typ.is_reference or typ is t.NOTHING or t.permissive(typ):
        return True
    return typ is t.STRING and (other is t.NOTHING or other is t.ERROR)


def _scalar(typ: t.GplType) -> bool:
    return isinstance(typ, t.PrimitiveType) or t.permissive(typ)


@dataclass(frozen=True, slots=True)
class _LocalDecl:
    """One declaration of a local, with the blocks around it (innermost last) and the procedure's
    previous declaration of the same name (``None`` for the first).  Slots and a link rather than a
    list per name: a ``Dim`` of 66,666 names kept a dict and a list for each while the procedure
    was declared, a third of its peak memory (issue 20)."""

    var: VarSym
    keyword: str | None
    chain: list[A.Block]
    earlier: _LocalDecl | None

    def previous(self) -> Iterator[_LocalDecl]:
        """The earlier declarations of the name, latest first."""
        prev = self.earlier
        while prev is not None:
            yield prev
            prev = prev.earlier


#: What a declaration finds as its earlier one when the name was declared first in the procedure's
#: own block (a record each made a third of a long Dim's analysis peak: docs/security.md, "Input
#: size").  Such a declaration contains every other, so each later one is a duplicate: the
#: keyword that is not "Dim" says so to :meth:`Checker._redeclares`.
_FIRST_IN_BODY = _LocalDecl(None, None, [], None)  # type: ignore[arg-type]


class _Ctx:
    """Where an expression is being checked."""

    def __init__(self, module: ModuleSym, cls: ClassSym | None, proc: ProcSym | None) -> None:
        self.module = module
        self.cls = cls
        self.proc = proc
        self.blocks: list[str] = []  # enclosing constructs, for Exit checks

    @property
    def instance(self) -> bool:
        if self.proc is not None:
            return self.cls is not None and not self.proc.shared
        return self.cls is not None  # instance field initializers


class Checker:
    def __init__(self, project: ProjectSyms, catalogue: Catalogue, sink: DiagnosticSink,
                 stubs: StubTable | None = None) -> None:
        self.sink = sink
        self.stubs = stubs if stubs is not None else StubTable(sink)
        self.r = Resolver(project, catalogue, sink, self.stubs)
        self.model = Model(project, self.r, stubs=self.stubs)
        self.cat = catalogue
        self.sources_missing = False  # a source failed to load (analyze)
        # Infos that only say "a variable" or "an operator's result of this type" are shared by
        # every expression they describe (most expressions of dense code: docs/security.md,
        # "Input size"); nothing changes an Info of these kinds once made
        self._var_infos: dict[VarSym, VarInfo] = {}
        self._binary_infos: dict[t.GplType, Info] = {}
        # the ParamInfos of each parameter list, made once (``_params``)
        self._param_infos: dict[tuple[int, int], tuple[Sequence[VarSym | Param], tuple[ParamInfo, ...]]] = {}

    def use_sink(self, sink: DiagnosticSink) -> None:
        """Report to ``sink`` from now on (semantics/warm.py: each part's diagnostics on their own)."""
        self.sink = self.r.sink = self.stubs.sink = sink

    def forget_shared_infos(self) -> None:
        """Drop the Infos shared by variables and parameter lists (semantics/warm.py, before
        checking a file again: its old locals would stay alive in the table, and a declaration
        whose type changed would keep its old Info)."""
        self._var_infos.clear()
        self._param_infos.clear()

    def _params(self, params: Sequence[VarSym | Param], stop: int | None = None) -> tuple[ParamInfo, ...]:
        """The passing facts of ``params[:stop]``, made once per parameter list and shared by
        every call that passes it (one tuple per call was a twentieth of the analysis of dense
        code: docs/security.md, "Input size").  The lists are the procedures' and the catalogue's
        own, complete before checking starts; the table keeps each alive, so its id stays its own."""
        key = (id(params), len(params) if stop is None else stop)
        hit = self._param_infos.get(key)
        if hit is None:
            hit = self._param_infos[key] = (params, _pinfo(params[:stop]))
        return hit[1]

    # -- driver ----------------------------------------------------------------------------------

    def run(self, units: list[A.SourceUnit], start: str | None, start_span: Span | None = None) -> Model:
        self.collect(units)
        for mod, members in self.items():
            self.check_item(mod, members)
        self.finish(start, start_span)
        return self.model

    # The three phases of :meth:`run`, which ``semantics/warm.py`` also calls one by one to check
    # again only what an edit changed.

    def collect(self, units: list[A.SourceUnit]) -> None:
        """Declare everything ``units`` declare (the symbol tables, every declared type resolved)."""
        for unit in units:
            self.model.info.add_tree(unit)
        col = Collector(self.r, self.sink)
        col.collect_units(units)
        col.resolve_pending()
        col.check_overloads()

    def items(self) -> list[tuple[ModuleSym, list[object]]]:
        """What is checked, in order, each on its own: every module's members, and each top-level
        class alone (the synthetic module holding them gathers classes of several files)."""
        project = self.model.project
        out: list[tuple[ModuleSym, list[object]]] = []
        for mod in list(project.modules.values()):
            if mod is project.top:
                out.extend((mod, [m]) for m in mod.members.values())
            else:
                out.append((mod, list(mod.members.values())))
        return out

    def check_item(self, mod: ModuleSym, members: list[object]) -> None:
        """Check the bodies and initializers of ``members`` of ``mod``."""
        if mod is self.model.project.top:
            self.check_members(mod, members)
        else:
            with contained(self.sink, mod.span):  # a bug met in one module: the others are checked
                self._module(mod)

    def check_members(self, mod: ModuleSym, members: list[object]) -> None:
        """Check ``members`` of ``mod`` (semantics/warm.py checks one member at a time: a bug met in
        one then leaves the module's other members checked)."""
        with contained(self.sink, mod.span):
            self._container(mod, None, members)

    def _module(self, mod: ModuleSym) -> None:
        self._container(mod, None, list(mod.members.values()))

    def finish(self, start: str | None, start_span: Span | None) -> None:
        """What needs the whole checked project: the Consts' values and the start procedure."""
        project = self.model.project
        self.model.const_values = fold_constants(project, self.model.info, self.sink)
        if start:
            self._start(start, start_span)
        else:
            self._assume_main()
        self.model.errors_reported = self.sink.found_errors()

    def _assume_main(self) -> None:
        """No ProjectStart: the single Public parameterless ``Sub Main`` starts the project (a
        folder without Project.gpr, or one file); none or several leave it without a start."""
        found = [_parameterless(m.members.get("main")) for m in self.model.project.module_list]
        subs = [p for p in found if p is not None and p.kind == "Sub" and p.public]
        if len(subs) == 1:
            self.model.start = subs[0]  # the translation warns (GPL2032) when it writes the package

    def _start(self, start: str, span: Span | None) -> None:
        parts = start.split(".")
        proc: object = None
        declared = False  # some readable module declares the name (as anything)
        project = self.model.project
        if len(parts) == 2:
            mod = project.modules.get(parts[0].lower())
            proc = mod.members.get(parts[1].lower()) if mod else None
            declared = proc is not None
        elif len(parts) == 1:
            cands = [m.members.get(parts[0].lower()) for m in project.module_list]
            declared = any(c is not None for c in cands)
            cands = [c for c in cands if isinstance(c, (ProcSym, OverloadSet))]
            proc = cands[0] if len(cands) == 1 else None
        if isinstance(proc, OverloadSet):  # the thread starts it without arguments
            proc = _parameterless(proc) or proc.procs[0]
        if not isinstance(proc, ProcSym) and self.sources_missing:
            return  # perhaps in the file that failed to load: its error says what is wrong
        if not declared and self.stubs.protected:
            # not declared anywhere readable: in a project with protected files that is where it
            # lives, and saying so beats "not a Sub of this project" (the user sees the file)
            self.sink.report(M.START_PROTECTED, span, name=start)
            return
        if not isinstance(proc, ProcSym) or proc.params:
            self.sink.report(M.START_NOT_FOUND, span, name=start)
            return
        if not proc.public:
            self.sink.report(M.START_NOT_PUBLIC, proc.span, name=start)
        self.model.start = proc

    def _container(self, mod: ModuleSym, cls: ClassSym | None, members: list[object]) -> None:
        for m in members:
            if isinstance(m, VarSym):
                self._field_init(m, mod, cls)
            elif isinstance(m, (ProcSym, OverloadSet)):
                for p in procedures(m):
                    self._proc(p, mod, cls)
            elif isinstance(m, PropSym):
                for acc in (m.getter, m.setter):
                    if acc is not None:
                        self._proc(acc, mod, cls)
            elif isinstance(m, ClassSym):
                self.model.class_of_decl[m.decl] = m  # type: ignore[index]
                for ctor in m.ctors:
                    self._proc(ctor, mod, m)
                self._container(mod, m, list(m.members.values()))
            elif isinstance(m, DelegateSym):
                self.model.delegate_of_decl[m.decl] = m  # type: ignore[index]

    def _field_init(self, v: VarSym, mod: ModuleSym, cls: ClassSym | None) -> None:
        d = v.decl
        if d is None:
            return
        ctx = _Ctx(mod, cls if cls is not None else None, None)
        if cls is not None and v.shared:
            ctx = _Ctx(mod, cls, None)
            ctx.cls = cls
        try:
            self._declarator_exprs(d, v, ctx)
        except RecursionError:  # as for a statement (_block): an initializer nested past Python's stack
            self._too_deep(d.span)

    def _declarator_exprs(self, d: A.VarDeclarator, v: VarSym, ctx: _Ctx) -> None:
        if d.bounds:
            for b in d.bounds:
                if b is not None:
                    self._value(b, ctx)
            if d.initializer is not None:
                self.sink.report(M.TYPE_MISMATCH, d.initializer.span, src="initializer", dst="an array")
        if d.new:
            n = A.New(d.span, d.type or A.TypeRef(d.span, "?"), d.new_args)
            self.model.info.add_node(n)
            self._expr(n, ctx)
            self.model.decl_new[d] = n  # the declarator's As New, as an expression to lower
        if d.initializer is not None and not d.bounds:
            self._store_value(d.initializer, v.type, ctx)

    # -- procedures ------------------------------------------------------------------------------------

    def _proc(self, p: ProcSym, mod: ModuleSym, cls: ClassSym | None) -> None:
        decl = p.decl
        if decl is None:
            return
        self.model.proc_of_decl[decl] = p
        ctx = _Ctx(mod, cls, p)
        if isinstance(decl, A.ProcDecl):
            for v in p.params:  # (a duplicate parameter was reported and left out of p.params)
                if v.default is not None:
                    try:
                        self._store_value(v.default, v.type, ctx)
                    except RecursionError:
                        self._too_deep(v.default.span)
        # locals are visible in the whole procedure (§6.2): declare them all first
        self._declare_locals(decl.body, p, ctx, [], {})
        self._block(decl.body, ctx)

    def _declare_locals(self, block: A.Block, p: ProcSym, ctx: _Ctx, outer: list[A.Block],
                        seen: dict[str, _LocalDecl]) -> None:
        """Declare the locals of ``block`` and the blocks inside it in ``p.locals``.

        A declaration inside an If/Select/For/While/Try block (real code, docs/design/real-code.md)
        has procedure scope like any other.  ``outer`` is the chain of blocks around ``block``;
        ``seen`` the latest declaration made so far of each lower-cased name (see :meth:`_redeclares`)."""
        chain = [*outer, block]
        for s in block.statements:
            if isinstance(s, A.VarDecl):
                if s.compact and not outer:
                    self._declare_run(s, p, ctx, chain, seen)
                    continue
                for d in s.declarators:
                    if not d.name:
                        continue
                    typ = self.r.resolve_type(d.type, ctx.module, ctx.cls)
                    if d.bounds is not None and typ is not t.ERROR:
                        typ = t.ArrayType(typ, len(d.bounds))
                    self._declare_local(d, typ, s, p, outer, chain, seen)
            elif isinstance(s, A.Label):
                key = s.name.lower()
                if key in p.labels:
                    self.sink.report(M.DUPLICATE_LABEL, s.span, name=s.name)
                p.labels[key] = s
            for child in _child_blocks(s):
                self._declare_locals(child, p, ctx, chain, seen)
            if isinstance(s, A.Try) and s.catch is not None and s.catch.type is not None and s.catch.variable:
                key = s.catch.variable.lower()
                if key not in p.locals:
                    typ = self.r.resolve_type(s.catch.type, ctx.module, ctx.cls)
                    p.locals[key] = VarSym(s.catch.variable, s.catch, typ, "local", owner=p)

    def _declare_local(self, d: A.VarDeclarator, typ: t.GplType, s: A.VarDecl, p: ProcSym, outer: list[A.Block],
                       chain: list[A.Block], seen: dict[str, _LocalDecl]) -> None:
        """Declare the local of ``d`` (of type ``typ``), or report it a duplicate, or record it
        as the same variable declared again (:meth:`_declare_locals`)."""
        storage = "static" if s.keyword == "Static" else "local"
        v = VarSym(d.name, d, typ, storage, owner=p, const=s.is_const, decl=d)
        key = intern(d.name.lower())  # (one string per name, not one per local)
        earlier = seen.get(key)
        if earlier is None and key in p.locals and p.locals[key].decl is not None:
            earlier = _FIRST_IN_BODY  # (a name declared first in the body: no record)
        elif earlier is None and not outer and key not in p.locals:
            p.locals[key] = v  # any later declaration of it is a duplicate
            return
        here = _LocalDecl(v, s.keyword, chain, earlier)
        if key in p.locals:
            prev = p.locals[key]
            if self._redeclares(here):
                self.model.redeclared[d] = prev
            else:
                self.sink.report(M.DUPLICATE_DECLARATION, d.span, name=d.name, scope="procedure",
                                 line=prev.span.line if prev.span else 0)
        else:
            p.locals[key] = v
        seen[key] = here

    def _declare_run(self, s: A.VarDecl, p: ProcSym, ctx: _Ctx, chain: list[A.Block],
                     seen: dict[str, _LocalDecl]) -> None:
        """Declare the locals of a long Dim of simple names in the procedure's own block
        (``s.declarators`` a CompactDeclarators) as a :class:`LocalRun`: no symbol per name, but
        for a name the procedure declared before (a duplicate, or a parameter's name), which is
        declared as a list's declarator is (:meth:`_declare_local`)."""
        decls = s.declarators
        assert isinstance(decls, A.CompactDeclarators)
        run = LocalRun(decls, [], p)
        p.locals.add_run(run)
        for start, end, ref in decls.groups():
            typ = None
            for i in range(start, end):
                # (resolved per name, as for a list: an unknown type is reported at each)
                typ_i = self.r.resolve_type(ref, ctx.module, ctx.cls)
                if typ is None:
                    typ = typ_i
                    run.types.append(typ)
                key = decls.name(i).lower()
                if key in p.locals:
                    self._declare_local(decls[i], typ_i, s, p, [], chain, seen)
                else:
                    run.add(i, key)

    @staticmethod
    def _redeclares(here: _LocalDecl) -> bool:
        """Whether a Dim of a name the procedure already declares is the same variable again.

        VB accepts one name declared in two blocks that do not contain one another (the Then and
        Else of an If, two Cases); in GPL a local has procedure scope, so both declarations name
        one variable, which is sound only when they agree on its type.  Anything else stays a
        duplicate (GPL2002): two declarations in one block or in nested blocks, a Static or Const,
        another type (docs/design/real-code.md)."""
        if here.keyword != "Dim" or here.earlier is None:
            return False
        for prev in here.previous():
            if prev.keyword != "Dim" or prev.var.type != here.var.type or t.ERROR in (prev.var.type, here.var.type):
                return False
            if any(b is prev.chain[-1] for b in here.chain) or any(b is here.chain[-1] for b in prev.chain):
                return False  # one block holds the other (or both are the same block)
        return True

    # -- statements ---------------------------------------------------------------------------------------

    def _block(self, block: A.Block, ctx: _Ctx) -> None:
        for s in block.statements:
            try:
                self._stmt(s, ctx)
            except RecursionError:
                self._too_deep(s.span)

    def _too_deep(self, span: Span) -> None:
        """A statement, a module-level initializer or a parameter's default whose expression nests
        deeper than the checker's recursion reaches (500 chained calls or members, which the parser's
        depth limit does not count): GPL3005 at it, never a RecursionError out of the analysis."""
        self.sink.report(M.NOT_SUPPORTED, span, what="an expression this deeply nested")

    def _stmt(self, s: A.Stmt, ctx: _Ctx) -> None:
        p = ctx.proc
        assert p is not None
        if isinstance(s, A.VarDecl):
            if s.compact:
                return  # (simple names: nothing to check but their declaration)
            for d in s.declarators:
                v = self.model.local_of(d, p)
                if v is not None:
                    self._declarator_exprs(d, v, ctx)
        elif isinstance(s, A.Assign):
            self._assign(s, ctx)
        elif isinstance(s, A.CallStmt):
            self._call_stmt(s.expr, ctx)
        elif isinstance(s, A.If):
            self._cond(s.condition, ctx)
            self._block(s.then_body, ctx)
            for ei in s.elseifs:
                self._cond(ei.condition, ctx)
                self._block(ei.body, ctx)
            if s.else_body is not None:
                self._block(s.else_body, ctx)
        elif isinstance(s, A.For):
            vt = self._target(s.var, ctx, for_var=True)
            self._expr(s.var, ctx)  # Next reads the variable
            if vt is not t.ERROR and not (isinstance(vt, t.PrimitiveType) and vt.is_numeric and vt is not t.BOOLEAN):
                self.sink.report(M.TYPE_MISMATCH, s.var.span, src=str(vt), dst="a For loop variable")
            for e in (s.start, s.end, s.step):
                if e is not None:
                    self._numeric(e, ctx)
            self._loop(s.body, ctx, "For")
        elif isinstance(s, A.ForEach):
            vt = self._target(s.var, ctx)
            ct = self._value(s.collection, ctx)
            if isinstance(ct, t.ArrayType):
                if not assignable(ct.element, vt):
                    self.sink.report(M.TYPE_MISMATCH, s.var.span, src=str(ct.element), dst=str(vt))
            elif ct is not t.ERROR:
                self.sink.report(M.NOT_AN_ARRAY, s.collection.span, name=_text(s.collection))
            self._loop(s.body, ctx, "For")
        elif isinstance(s, A.While):
            self._cond(s.condition, ctx)
            self._loop(s.body, ctx, "While")
        elif isinstance(s, A.DoLoop):
            if s.condition is not None:
                self._cond(s.condition, ctx)
            self._loop(s.body, ctx, "Do")
        elif isinstance(s, A.Select):
            st = self._value(s.subject, ctx)
            if not _scalar(st):
                self.sink.report(M.TYPE_MISMATCH, s.subject.span, src=str(st), dst="a Select value")
            for c in s.cases:
                for item in c.items:
                    for e in item.children():
                        self._value(e, ctx)  # type: ignore[arg-type]
                self._loop(c.body, ctx, "Select")
        elif isinstance(s, A.Try):
            self._loop(s.body, ctx, "Try")
            if s.catch is not None:
                self._catch(s.catch, ctx)
                self._loop(s.catch.body, ctx, "Try")
            if s.finally_ is not None:
                self._loop(s.finally_.body, ctx, "Finally")
        elif isinstance(s, A.GoTo):
            if s.label.lower() not in p.labels:
                self.sink.report(M.UNKNOWN_LABEL, s.span, name=s.label)
        elif isinstance(s, A.Exit):
            self._exit(s, ctx)
        elif isinstance(s, A.Return):
            self._return(s, ctx)
        elif isinstance(s, A.Throw):
            if s.value is not None:
                vt = self._value(s.value, ctx)
                if vt is not t.ERROR and not (isinstance(vt, t.ClassType) and vt.key == "exception"):
                    self.sink.report(M.TYPE_MISMATCH, s.value.span, src=str(vt), dst="an Exception to Throw")
        elif isinstance(s, A.ReDim):
            tt = self._target(s.target, ctx)
            for b in s.bounds:
                self._numeric(b, ctx)
            if isinstance(tt, t.ArrayType):
                if tt.rank != len(s.bounds):
                    self.sink.report(M.SUBSCRIPT_COUNT, s.span, name=_text(s.target), rank=tt.rank,
                                     given=len(s.bounds))
            elif tt is not t.ERROR:
                self.sink.report(M.NOT_AN_ARRAY, s.target.span, name=_text(s.target))
        elif isinstance(s, (A.Label, A.ErrorStmt)):
            pass  # (an ErrorStmt: the parser reported the line)
        elif isinstance(s, (A.ProcDecl, A.ClassDecl, A.ModuleDecl, A.PropertyDecl, A.DelegateDecl)):
            pass  # misplaced; the parser reported it

    def _loop(self, body: A.Block, ctx: _Ctx, kind: str) -> None:
        ctx.blocks.append(kind)
        try:
            self._block(body, ctx)
        finally:
            ctx.blocks.pop()

    def _catch(self, c: A.CatchClause, ctx: _Ctx) -> None:
        if not c.variable:
            return
        ref = A.Name(c.span, c.variable)
        self.model.info.add_node(ref)
        vt = self._target(ref, ctx)
        if vt is not t.ERROR and not (isinstance(vt, t.ClassType) and vt.key == "exception"):
            self.sink.report(M.TYPE_MISMATCH, c.span, src="Exception", dst=f"the {vt} variable {c.variable}")
        self.model.catch_var[c] = ref

    def _exit(self, s: A.Exit, ctx: _Ctx) -> None:
        kind = s.kind
        p = ctx.proc
        assert p is not None
        if kind in ("Sub", "Function", "Property"):
            ok = (kind == "Sub" and p.kind in ("Sub", "New", "Set")) or (kind == "Function" and p.kind == "Function") \
                or (kind == "Property" and p.kind in ("Get", "Set"))
        elif kind == "Try":
            if ctx.blocks and "Finally" in ctx.blocks and ctx.blocks[-1] == "Finally":
                self.sink.report(M.EXIT_TRY_IN_FINALLY, s.span)
                return
            ok = "Try" in ctx.blocks
        else:
            ok = kind in ctx.blocks
        if not ok:
            self.sink.report(M.EXIT_OUTSIDE, s.span, kind=kind)

    def _return(self, s: A.Return, ctx: _Ctx) -> None:
        p = ctx.proc
        assert p is not None
        wants = p.result if p.kind == "Function" else (p.prop.type if p.kind == "Get" and p.prop else t.VOID)
        if s.value is None:
            if wants is not t.VOID and p.kind == "Get":
                self.sink.report(M.BAD_RETURN, s.span, detail="a property Get must return a value")
            return
        if wants is t.VOID:
            self.sink.report(M.BAD_RETURN, s.span, detail=f"'{p.name}' is a {p.kind} and cannot return a value")
            self._value(s.value, ctx)
            return
        self._store_value(s.value, wants, ctx)

    def _assign(self, s: A.Assign, ctx: _Ctx) -> None:
        tt = self._target(s.target, ctx)
        if s.op == "=":
            self._store_value(s.value, tt, ctx)
            return
        self._expr(s.target, ctx)  # a compound assignment reads its target too
        vt = self._value(s.value, ctx)
        op = s.op[:-1]
        rt = self._binary_type(op, tt, vt, s)
        if not assignable(rt, tt):
            self.sink.report(M.TYPE_MISMATCH, s.value.span, src=str(rt), dst=str(tt))

    def _call_stmt(self, e: A.Expr, ctx: _Ctx) -> None:
        info = self._expr(e, ctx, as_statement=True)
        if not isinstance(info, CALLS):
            self.sink.report(M.NOT_SUPPORTED, e.span, what=f"'{_text(e)}' as a statement (it is not a call)")

    # -- expressions: entry points ------------------------------------------------------------------------

    def _value(self, e: A.Expr, ctx: _Ctx) -> t.GplType:
        return self._value_check(e, self._expr(e, ctx))

    def _value_check(self, e: A.Expr, info: Info) -> t.GplType:
        if isinstance(info, TypeNameInfo):
            self.sink.report(M.NOT_A_VALUE, e.span, name=_text(e), what="type")
            info.type = t.ERROR
        elif info.type is t.VOID:
            self.sink.report(M.SUB_AS_VALUE, e.span, name=_text(e))
            info.type = t.ERROR
        elif isinstance(info, NAMES_NOT_VALUES):
            self.sink.report(M.NOT_A_VALUE, e.span, name=_text(e),
                             what="module" if isinstance(info, (ModuleInfo, StubModuleInfo)) else "class")
            info.type = t.ERROR
        return info.type

    def _numeric(self, e: A.Expr, ctx: _Ctx) -> t.GplType:
        vt = self._value(e, ctx)
        if not _scalar(vt):
            self.sink.report(M.TYPE_MISMATCH, e.span, src=str(vt), dst="a number")
        return vt

    def _cond(self, e: A.Expr, ctx: _Ctx) -> None:
        vt = self._value(e, ctx)
        if not _scalar(vt):
            self.sink.report(M.TYPE_MISMATCH, e.span, src=str(vt), dst="a condition")

    def _store_value(self, e: A.Expr, dst: t.GplType, ctx: _Ctx, info: Info | None = None) -> None:
        """Check ``e`` as a value stored into a ``dst`` variable (``info``: ``e`` is typed already)."""
        vt = self._value_check(e, info) if info is not None else self._value(e, ctx)
        if dst is t.STRING and isinstance(vt, t.PrimitiveType) and vt is not t.STRING:
            self.sink.report(M.IMPLICIT_TO_STRING, e.span, src=str(vt))
        if vt is t.NOTHING and isinstance(dst, t.PrimitiveType) and dst is not t.STRING:
            self.sink.report(M.TYPE_MISMATCH, e.span, src="Nothing", dst=str(dst))
        elif not assignable(vt, dst):
            self.sink.report(M.TYPE_MISMATCH, e.span, src=str(vt), dst=str(dst))

    def _target(self, e: A.Expr, ctx: _Ctx, for_var: bool = False) -> t.GplType:
        """Check an assignment target; returns its type."""
        info = self._expr(e, ctx, as_target=True)
        if isinstance(info, VarInfo):
            v = info.sym
            if v.const:
                self.sink.report(M.CONST_ASSIGN, e.span, name=v.name)
            v.assigned = True
            return info.type
        if isinstance(info, (ResultInfo, IndexInfo, ErrorInfo, StubNameInfo, DynamicMemberInfo)):
            return info.type
        if isinstance(info, PropInfo):
            prop = info.sym
            if prop.setter is None:
                self.sink.report(M.PROPERTY_ACCESS, e.span, name=prop.name, what="read-only")
            return prop.type
        if isinstance(info, BuiltinMemberInfo) and not info.on_value:
            m = info.sym
            if m.settable:
                return info.type  # the value's type in the assignment form used (_assigned_member)
            self.sink.report(M.PROPERTY_ACCESS, e.span, name=m.name, what="read-only")
            return t.ERROR
        self.sink.report(M.NOT_ASSIGNABLE, e.span, what=f"'{_text(e)}'")
        return t.ERROR

    # -- expressions ------------------------------------------------------------------------------------

    def _record(self, e: A.Expr, info: Info) -> Info:
        self.model.info[e] = info
        return info

    def _expr(self, e: A.Expr, ctx: _Ctx, as_statement: bool = False, as_target: bool = False) -> Info:
        if isinstance(e, A.IntegerLiteral):
            typ = t.INTEGER if -(2**31) <= e.value < 2**31 else t.DOUBLE
            return self._record(e, _LITERAL[typ])
        if isinstance(e, A.RealLiteral):
            return self._record(e, _LITERAL[t.DOUBLE])
        if isinstance(e, A.StringLiteral):
            return self._record(e, _LITERAL[t.STRING])
        if isinstance(e, A.BooleanLiteral):
            return self._record(e, _LITERAL[t.BOOLEAN])
        if isinstance(e, A.NothingLiteral):
            return self._record(e, NothingInfo(t.NOTHING))
        if isinstance(e, A.MeExpr):
            if not ctx.instance:
                self.sink.report(M.ME_OUTSIDE_INSTANCE, e.span)
                return self._record(e, ErrorInfo(t.ERROR))
            assert ctx.cls is not None
            return self._record(e, MeInfo(ctx.cls.type))
        if isinstance(e, A.Name):
            return self._record(e, self._name(e, ctx, as_statement, as_target))
        if isinstance(e, A.MemberAccess):
            return self._record(e, self._member(e, ctx, as_statement, as_target))
        if isinstance(e, A.Invoke):
            return self._record(e, self._invoke(e, ctx, as_target))
        if isinstance(e, A.Unary):
            ot = self._value(e.operand, ctx)
            if e.op == "Not":
                typ: t.GplType = t.BOOLEAN
            elif ot in (t.BOOLEAN, t.BYTE, t.SHORT):
                typ = t.INTEGER
            elif ot is t.STRING or (ot is t.ANY and e.op == "+"):
                typ = t.DOUBLE
            else:
                typ = ot
            if not _scalar(ot):
                self.sink.report(M.BAD_OPERANDS, e.span, op=e.op, left="", right=str(ot))
                typ = t.ERROR
            return self._record(e, UnaryInfo(typ))
        if isinstance(e, A.Binary):
            if e.op == "Is":
                lt = self._expr(e.left, ctx).type
                rt = self._expr(e.right, ctx).type
                for side, st, other in ((e.left, lt, rt), (e.right, rt, lt)):
                    if not _identity_operand(st, other):
                        self.sink.report(M.BAD_OPERANDS, side.span, op="Is", left=str(lt), right=str(rt))
                        break
                return self._record(e, BinaryInfo(t.BOOLEAN))
            return self._binary_chain(e, ctx)
        if isinstance(e, A.Chain):
            return self._binary_chain(e, ctx)
        if isinstance(e, A.New):
            return self._record(e, self._new(e, ctx))
        if isinstance(e, A.AddressOf):
            return self._record(e, self._addressof(e, ctx))
        return self._record(e, ErrorInfo(t.ERROR))

    def _binary_chain(self, e: A.Binary, ctx: _Ctx) -> Info:
        """Type a left-leaning chain of binary operators (``a & b & c ...``) without recursing on it.

        Real GPL code builds strings over hundreds of continued lines (`` & _``); the parser yields
        a left-leaning tree as deep as the chain is long, so one Python frame per operator would hit
        the recursion limit near 450 operands.  The left spine is walked in a loop instead: the
        leftmost operand is typed first, then each right operand in source order, so diagnostics come
        out in the same order as a recursive walk would give them.  ``Is`` ends the spine (its
        operands are references, not values, and it never chains in practice)."""
        spine: list[A.Binary | A.Chain] = [e]
        left = A.chain_left(e)
        while (isinstance(left, A.Binary) and left.op != "Is") or isinstance(left, A.Chain):
            spine.append(left)
            left = A.chain_left(left)
        lt = self._value(left, ctx)
        info: Info = BinaryInfo(t.ERROR)
        for node in reversed(spine):
            if isinstance(node, A.Chain):
                info = self._record(node, self._chain(node, lt, ctx))
                lt = info.type
                continue
            rt = self._value(node.right, ctx)
            typ = self._binary_type(node.op, lt, rt, node)
            shared = self._binary_infos.get(typ)
            if shared is None:
                shared = self._binary_infos[typ] = BinaryInfo(typ)
            info = self._record(node, shared)
            lt = info.type
        return info

    def _chain(self, e: A.Chain, lt: t.GplType, ctx: _Ctx) -> ChainInfo:
        """Type the operators of a Chain whose first operand has type ``lt``, as the nested
        Binary nodes it stands for would be typed (same order, same diagnostics at the same spans),
        keeping the type of each prefix in a byte."""
        types: list[t.GplType] = []
        index: dict[t.GplType, int] = {}
        codes = bytearray()
        operands, ops, names = e.operands, e.ops, A.CHAIN_OPS
        for k in range(len(ops)):
            x = operands[k]
            rt = self._value(x, ctx) if isinstance(x, A.Node) else t.INTEGER  # (an Integer literal)
            lt = self._binary_type(names[ops[k]], lt, rt, e, k)
            code = index.get(lt)
            if code is None:
                code = index[lt] = len(types)
                types.append(lt)
            codes.append(code)
        return ChainInfo(lt, tuple(types), bytes(codes), _LITERAL[t.INTEGER])

    def _binary_type(self, op: str, lt: t.GplType, rt: t.GplType, node: A.Node, k: int = -1) -> t.GplType:
        """The type of ``lt op rt``; ``node`` is the Binary (or, with ``k``, the Chain whose
        ``k``-th operator it is) where a misuse is reported."""
        if lt is t.ERROR or rt is t.ERROR:
            return t.ERROR
        lt, rt = nothing_as_string(op, lt, rt)
        if (lt is t.ANY or rt is t.ANY) and _scalar(lt) and _scalar(rt):
            # one operand of unknown type (a stub's value): the result type is known only for
            # operators whose result type does not depend on the operands; the runtime converts
            if op in _COMPARE or op in ("AndAlso", "OrElse"):
                return t.BOOLEAN
            if op == "&":
                return t.STRING
            if op in ("<<", ">>", "\\"):
                return t.INTEGER
            if op in ("/", "^"):
                return t.DOUBLE
            return t.ANY
        if not (_scalar(lt) and _scalar(rt)):
            if op in ("=", "<>") and (lt.is_reference or rt.is_reference):
                pass
            span = node.prefix_span(k) if isinstance(node, A.Chain) else node.span
            self.sink.report(M.BAD_OPERANDS, span, op=op, left=str(lt), right=str(rt))
            return t.ERROR
        if op in _COMPARE or op in ("AndAlso", "OrElse"):
            return t.BOOLEAN
        if op == "&":
            return t.STRING
        if op in ("And", "Or", "Xor"):
            return t.BOOLEAN if lt is t.BOOLEAN and rt is t.BOOLEAN else t.INTEGER
        if op in ("<<", ">>", "\\"):
            return t.INTEGER
        if op in ("/", "^"):
            return t.DOUBLE
        if op == "+" and lt is t.STRING and rt is t.STRING:
            return t.STRING
        if lt.is_integral and rt.is_integral:  # Booleans count as -1/0
            return t.INTEGER
        return t.DOUBLE

    # -- names and members ------------------------------------------------------------------------------

    def _found_info(self, found: Found, name: str, span: object, ctx: _Ctx, receiver: A.Expr | None,
                    as_statement: bool, as_target: bool, in_invoke: bool = False,
                    static: bool = False) -> Info:
        """``static``: a member reached through its class's name, so only Shared overloads count."""
        if isinstance(found, FoundResult):
            s = found.sym
            if as_statement:
                return self._proc_call_info(s, [], span, ctx, None)
            s.uses_result = True
            return ResultInfo(s.result, s)
        if isinstance(found, FoundModule):
            return ModuleInfo(t.VOID, found.sym)
        if isinstance(found, FoundBuiltinClass):
            b = found.sym
            return BuiltinClassInfo(b.type if not b.is_global else t.VOID, b)
        if isinstance(found, FoundBuiltinFunction):
            f = found.sym
            if sum(1 for p in f.params if not p.optional) > 0:
                self.sink.report(M.WRONG_ARG_COUNT, span, name=f.name,  # type: ignore[arg-type]
                                 expected=len(f.params), given=0)
            return BuiltinFunctionInfo(f.result, f, self._params(f.params))
        if isinstance(found, FoundBuiltinConstant):
            return BuiltinConstInfo(found.sym.type, found.sym)
        # user member
        s = found.sym
        if isinstance(s, VarSym):
            if not as_target:
                s.read = True
            if receiver is not None:
                return VarInfo(s.type, s, receiver=receiver)
            shared = self._var_infos.get(s)
            if shared is None or shared.type is not s.type:
                shared = self._var_infos[s] = VarInfo(s.type, s)
            return shared
        if isinstance(s, ProcSym):
            if in_invoke:
                return ProcRefInfo(s.result, s, receiver=receiver)
            return self._proc_call_info(s, [], span, ctx, receiver)
        if isinstance(s, OverloadSet):
            if in_invoke:  # the arguments choose the overload (_invoke)
                return ProcRefInfo(s.result, s, receiver=receiver, static=static)
            chosen = self._choose_overload(s, [], [], span, ctx, static)
            if chosen is None:
                return ErrorInfo(t.ERROR)
            return self._proc_call_info(chosen, [], span, ctx, receiver)
        if isinstance(s, PropSym):
            if s.getter is None and not as_target:
                self.sink.report(M.PROPERTY_ACCESS, span, name=s.name, what="write-only")  # type: ignore[arg-type]
            return PropInfo(s.type, s, receiver=receiver)
        if isinstance(s, ClassSym):
            return ClassInfo(t.VOID, s)
        if isinstance(s, DelegateSym):
            return ClassInfo(t.VOID, s)
        return ErrorInfo(t.ERROR)

    def _name(self, e: A.Name, ctx: _Ctx, as_statement: bool, as_target: bool) -> Info:
        found = self.r.lookup(e.name, ctx.proc, ctx.cls, ctx.module)
        if found is None:
            if e.name.lower() == "string":
                return BuiltinClassInfo(t.VOID, self.cat.type_members.get("string"))
            prim = t.lookup_primitive(e.name)
            if prim is not None:  # a type keyword as an argument: ToBitString(x, Short, True)
                return TypeNameInfo(t.VOID, prim)
            if self.stubs.protected:
                return self._stub_use(self.stubs.protected_name(e.name, e.span), as_statement, as_target)
            self.sink.report(M.UNDECLARED_NAME, e.span, name=e.name)
            return ErrorInfo(t.ERROR)
        if isinstance(found, str):
            self.sink.report(M.AMBIGUOUS_NAME, e.span, name=e.name, where=found)
            return ErrorInfo(t.ERROR)
        s = found.sym
        if isinstance(s, (VarSym, ProcSym, PropSym)) and s.owner is ctx.cls and ctx.cls is not None:
            if not getattr(s, "shared", False) and not ctx.instance:
                self.sink.report(M.ME_OUTSIDE_INSTANCE, e.span)
                return ErrorInfo(t.ERROR)
        return self._found_info(found, e.name, e.span, ctx, None, as_statement, as_target)

    def _member(self, e: A.MemberAccess, ctx: _Ctx, as_statement: bool, as_target: bool,
                in_invoke: bool = False) -> Info:
        if isinstance(e.target, A.Name) and self.stubs.protected \
                and self.r.lookup(e.target.name, ctx.proc, ctx.cls, ctx.module) is None \
                and t.lookup_primitive(e.target.name) is None and e.target.name.lower() != "string":
            # Module.Name of a module no readable source declares: a stub module
            self._record(e.target, StubModuleInfo(t.VOID, e.target.name))
            stub = self.stubs.protected_name(e.name, e.span, module=e.target.name)
            if in_invoke:
                return StubRefInfo(t.ANY, stub)
            return self._stub_use(stub, as_statement, as_target)
        tinfo = self._expr(e.target, ctx)
        if tinfo.type is t.ERROR and isinstance(tinfo, ErrorInfo):
            return ErrorInfo(t.ERROR)
        if tinfo.type is t.ANY and not isinstance(tinfo, (ModuleInfo, ClassInfo, BuiltinClassInfo)):
            # a member of a value of unknown type (from a stub): plain Python attribute access
            if as_statement:
                return DynamicCallInfo(t.ANY, e.name, receiver=e.target)
            return DynamicMemberInfo(t.ANY, e.name, receiver=e.target)
        if isinstance(tinfo, ModuleInfo):
            mod = tinfo.sym
            m = self._visible_member(mod.members, f"module {mod.name}", mod.name, e, ctx)
            if m is None:
                return ErrorInfo(t.ERROR)
            return self._found_info(FoundMember(m, mod), e.name, e.span, ctx, None,
                                    as_statement, as_target, in_invoke)
        if isinstance(tinfo, ClassInfo) and isinstance(tinfo.sym, ClassSym):
            cls: ClassSym = tinfo.sym
            m = self._visible_member(cls.members, f"class {cls.name}", cls.name, e, ctx)
            if m is None:
                return ErrorInfo(t.ERROR)
            if isinstance(m, (VarSym, ProcSym, PropSym, OverloadSet)) and not m.shared:
                self.sink.report(M.NO_SUCH_MEMBER, e.span, owner=f"class {cls.name} (Shared members)",
                                 member=e.name)
                return ErrorInfo(t.ERROR)
            return self._found_info(FoundMember(m, cls.module), e.name, e.span, ctx, None,
                                    as_statement, as_target, in_invoke, static=True)
        if isinstance(tinfo, BuiltinClassInfo):
            b = tinfo.sym
            bm = b.member(e.name) if b is not None else None
            if bm is None and b is not None and b.name != "String":
                stub = self.stubs.builtin_member(b.name, e.name, e.span, shared=True)
                return self._builtin_stub_use(stub, None, as_statement, as_target, in_invoke)
            if bm is None or (not bm.shared and not b.is_global):
                self.sink.report(M.NO_SUCH_MEMBER, e.span, owner=b.name if b else "?", member=e.name)
                return ErrorInfo(t.ERROR)
            return self._bmember_info(bm, b, e, None, True, in_invoke, value_type=b.name == "String",
                                      as_target=as_target)
        typ = tinfo.type
        if typ is t.ERROR:
            return ErrorInfo(t.ERROR)
        ucls = self.r.class_of(typ)
        if ucls is not None:
            # a nested class or delegate is reached through the class name, never an instance
            m = self._visible_member(ucls.members, f"class {ucls.name}", ucls.name, e, ctx,
                                     hidden=(ClassSym, DelegateSym))
            if m is None:
                return ErrorInfo(t.ERROR)
            return self._found_info(FoundMember(m, ucls.module), e.name, e.span, ctx, e.target,
                                    as_statement, as_target, in_invoke)
        if isinstance(typ, t.ArrayType):
            b = self.cat.type_members.get("array")
        else:
            b = self.r.builtin_of(typ)
        if b is None:
            self.sink.report(M.NOT_AN_OBJECT, e.span, type=str(typ), member=e.name)
            return ErrorInfo(t.ERROR)
        bm = b.member(e.name)
        if bm is None and isinstance(typ, t.ClassType):
            # through a variable of a global class (CTL As Controller) the member is the class's own
            stub = self.stubs.builtin_member(b.name, e.name, e.span, shared=b.is_global)
            return self._builtin_stub_use(stub, None if b.is_global else e.target, as_statement, as_target,
                                          in_invoke)
        if bm is None:
            self.sink.report(M.NO_SUCH_MEMBER, e.span, owner=str(typ), member=e.name)
            return ErrorInfo(t.ERROR)
        # a Shared member of a global class through a variable of its type (``Dim CTL As
        # Controller``: the variable is Nothing) is the class's own member
        return self._bmember_info(bm, b, e, None if b.is_global else e.target, b.is_global, in_invoke,
                                  value_type=isinstance(typ, (t.ArrayType,)) or typ is t.STRING,
                                  as_target=as_target)

    def _visible_member(self, members: dict[str, UserMember], label: str, owner: str,
                        e: A.MemberAccess, ctx: _Ctx,
                        hidden: tuple[type, ...] = ()) -> UserMember | None:
        """The member ``e.name`` of a user module or class, or None after reporting why not
        (no such member -- ``hidden`` kinds count as absent -- or a Private one seen from outside).
        One place for the rule, so module, class and instance access report it alike."""
        m = members.get(e.name.lower())
        if m is None or isinstance(m, hidden):
            self.sink.report(M.NO_SUCH_MEMBER, e.span, owner=label, member=e.name)
            return None
        if not visible(m, ctx.module, ctx.cls):
            self.sink.report(M.PRIVATE_MEMBER, e.span, name=e.name, owner=owner)
            return None
        return m

    def _bmember_info(self, bm: Member, b: BuiltinClass, e: A.Expr, receiver: A.Expr | None, static: bool,
                      in_invoke: bool, value_type: bool, as_target: bool = False) -> Info:
        on_value = value_type and b.name in ("String", "Array")
        if as_target and not in_invoke and bm.settable:  # ``X.M = v``
            return self._assigned_member(bm, BuiltinMemberInfo(bm.result, bm, b, receiver=receiver, static=static,
                                                               on_value=on_value), [], e.span)
        if bm.kind == "property":
            return BuiltinMemberInfo(bm.result, bm, b, receiver=receiver, static=static, on_value=on_value)
        form = bm.call_form(0) if not in_invoke else None
        info = BuiltinMemberInfo(bm.result, bm, b, self._params(form if form is not None else bm.params),
                                 receiver=receiver, static=static, on_value=on_value)
        if not in_invoke and form is None:
            self.sink.report(M.WRONG_ARG_COUNT, e.span, name=bm.name, expected=bm.min_args, given=0)
        return info

    def _assigned_member(self, m: Member, ci: BuiltinMemberInfo, args: list[A.Expr], span: object) -> Info:
        """``X.M = v`` or ``X.M(args) = v`` of a built-in member: the assignment form with that
        many arguments (Member.set_forms); its parameters, and the value's type as the type.  The
        arguments are checked by the caller against the returned parameters."""
        form = m.set_form(len(args))
        if form is None:
            if not _unparsed(args):
                self.sink.report(M.WRONG_ARG_COUNT, span, name=m.name,  # type: ignore[arg-type]
                                 expected=_count_text(m.set_min_args, m.set_max_args), given=len(args))
            return replace(ci, type=t.ERROR, sym=m, params=())
        return replace(ci, type=form[-1].type, sym=m, params=self._params(form, len(form) - 1))

    def _stub_use(self, stub: Stub, as_statement: bool, as_target: bool) -> Info:
        """A protected name used without parentheses: a call as a statement, else a value/target."""
        if as_statement:
            stub.called = True
            return StubCallInfo(t.ANY, stub)
        if as_target:
            stub.assigned = True
        return StubNameInfo(t.ANY, stub)

    def _builtin_stub_use(self, stub: Stub, receiver: A.Expr | None, as_statement: bool, as_target: bool,
                          in_invoke: bool) -> Info:
        """An unknown built-in member: always called (with the object first for an instance
        member); as an assignment target it is set through the stub's ``set_`` companion."""
        if in_invoke:
            return StubRefInfo(t.ANY, stub, receiver=receiver)
        if as_target:
            stub.assigned = True
            return StubNameInfo(t.ANY, stub, receiver=receiver)
        stub.called = True
        return StubCallInfo(t.ANY, stub, receiver=receiver)

    def _proc_call_info(self, p: ProcSym, args: list[A.Expr], span: object, ctx: _Ctx,
                        receiver: A.Expr | None) -> Info:
        if not (p.min_args <= len(args) <= len(p.params)) and not _unparsed(args):
            self.sink.report(M.WRONG_ARG_COUNT, span, name=p.name,  # type: ignore[arg-type]
                             expected=_count_text(p.min_args, len(p.params)), given=len(args))
        return CallInfo(p.result, p, self._params(p.params), receiver=receiver)

    # -- calls, indexing, New, AddressOf -----------------------------------------------------------------

    def _callee(self, e: A.Expr, ctx: _Ctx) -> Info:
        """The target of an Invoke, without turning a zero-argument procedure into a call."""
        if isinstance(e, A.Name):
            found = self.r.lookup(e.name, ctx.proc, ctx.cls, ctx.module)
            if found is None and self.stubs.protected and t.lookup_primitive(e.name) is None:
                return self._record(e, StubRefInfo(t.ANY, self.stubs.protected_name(e.name, e.span)))
            if found is None:
                self.sink.report(M.UNDECLARED_NAME, e.span, name=e.name)
                return self._record(e, ErrorInfo(t.ERROR))
            if isinstance(found, str):
                self.sink.report(M.AMBIGUOUS_NAME, e.span, name=e.name, where=found)
                return self._record(e, ErrorInfo(t.ERROR))
            if isinstance(found, FoundResult):  # a Function calling itself -- or another overload of its name
                callee = _overloads_of(found.sym)
                return self._record(e, ProcRefInfo(callee.result, callee))
            if isinstance(found.sym, (ProcSym, OverloadSet)):
                return self._record(e, ProcRefInfo(found.sym.result, found.sym))
            if isinstance(found, FoundBuiltinFunction):
                return self._record(e, BuiltinFunctionRefInfo(found.sym.result, found.sym))
            return self._record(e, self._found_info(found, e.name, e.span, ctx, None, False, False))
        if isinstance(e, A.MemberAccess):
            return self._record(e, self._member(e, ctx, False, False, in_invoke=True))
        return self._expr(e, ctx)

    def _invoke(self, e: A.Invoke, ctx: _Ctx, as_target: bool = False) -> Info:
        ci = self._callee(e.target, ctx)
        if as_target and isinstance(ci, BuiltinMemberInfo) and not ci.on_value and ci.sym.settable:
            info = self._assigned_member(ci.sym, ci, e.args, e.span)  # ``X.M(args) = v``
            self._args(e.args, info.params or [], ctx)
            return info
        if isinstance(ci, ErrorInfo):
            for a in e.args:
                self._expr(a, ctx)
            return ErrorInfo(t.ERROR)
        if isinstance(ci, StubRefInfo):
            stub = ci.stub
            stub.called = True
            for a in e.args:
                self._value(a, ctx)
            return StubCallInfo(t.ANY, stub, receiver=ci.receiver)
        if ci.type is t.ANY and isinstance(ci, (DynamicMemberInfo, StubNameInfo, DynamicCallInfo, StubCallInfo, VarInfo,
                                                IndexInfo, PropInfo)):
            # calling or indexing a value of unknown type: plain Python
            for a in e.args:
                self._value(a, ctx)
            return DynamicCallInfo(t.ANY)
        if isinstance(ci, ProcRefInfo) and isinstance(ci.sym, OverloadSet):
            infos = [self._expr(a, ctx) for a in e.args]
            chosen = self._choose_overload(ci.sym, e.args, infos, e.span, ctx, ci.static)
            if chosen is None:
                return ErrorInfo(t.ERROR)
            info = CallInfo(chosen.result, chosen, self._params(chosen.params), receiver=ci.receiver)
            self._args(e.args, info.params or [], ctx, infos)
            return info
        if isinstance(ci, ProcRefInfo):
            assert isinstance(ci.sym, ProcSym)
            info = self._proc_call_info(ci.sym, e.args, e.span, ctx, ci.receiver)
            self._args(e.args, info.params or [], ctx)
            return info
        if isinstance(ci, BuiltinFunctionRefInfo):
            f = ci.sym
            params = self._params(f.params)
            self._check_count(f.name, params, e.args, e.span)
            self._args(e.args, params, ctx)
            return BuiltinFunctionInfo(f.result, f, params)
        if isinstance(ci, BuiltinMemberInfo) and ci.sym.kind == "method":
            form = ci.sym.call_form(len(e.args))  # the overload called with that many arguments
            params = self._params(form) if form is not None else ci.params or ()
            if form is None and not _unparsed(e.args):
                self.sink.report(M.WRONG_ARG_COUNT, e.span, name=ci.sym.name,
                                 expected=_count_text(ci.sym.min_args, ci.sym.max_args), given=len(e.args))
            self._args(e.args, params, ctx)
            return replace(ci, params=params)
        typ = ci.type
        if isinstance(typ, t.ArrayType):
            if len(e.args) != typ.rank:
                self.sink.report(M.SUBSCRIPT_COUNT, e.span, name=_text(e.target), rank=typ.rank, given=len(e.args))
            for a in e.args:
                self._numeric(a, ctx)
            return IndexInfo(typ.element)
        d = self.r.delegate_of(typ)
        if d is not None:
            params = self._params(d.params)
            self._check_count(d.name, params, e.args, e.span)
            self._args(e.args, params, ctx)
            return DelegateCallInfo(d.result, d, params)
        if typ is not t.ERROR:
            self.sink.report(M.NOT_INDEXABLE, e.span, name=_text(e.target))
        for a in e.args:
            self._expr(a, ctx)
        return ErrorInfo(t.ERROR)

    def _check_count(self, name: str, params: Sequence[ParamInfo], args: list[A.Expr], span: object) -> None:
        lo = sum(1 for p in params if not p.optional)
        if not (lo <= len(args) <= len(params)) and not _unparsed(args):
            self.sink.report(M.WRONG_ARG_COUNT, span, name=name,  # type: ignore[arg-type]
                             expected=_count_text(lo, len(params)), given=len(args))

    def _args(self, args: list[A.Expr], params: Sequence[ParamInfo], ctx: _Ctx,
              infos: list[Info] | None = None) -> None:
        """Check each argument against its parameter.  ``infos``: the arguments were already
        typed (to choose an overload), so they are checked without being typed again."""
        for i, a in enumerate(args):
            p = params[i] if i < len(params) else None
            given = infos[i] if infos is not None else None
            if p is None:
                if given is None:
                    self._expr(a, ctx)
                continue
            if p.byref:
                info = given or self._expr(a, ctx)
                if not self._mark_byref(a, info, p):
                    self.model.byref_temps.add(a)
                    if p.type is not t.ERROR:
                        self.sink.report(M.BYREF_TEMPORARY, a.span, name=p.name)
                if info.type is t.VOID:
                    self.sink.report(M.SUB_AS_VALUE, a.span, name=_text(a))
                elif not assignable(info.type, p.type) and p.type is not t.ERROR:
                    self.sink.report(M.TYPE_MISMATCH, a.span, src=str(info.type), dst=str(p.type))
            elif t.permissive(p.type):  # Any-annotated runtime parameter: any value (or a type name)
                info = given or self._expr(a, ctx)
                if not isinstance(info, TypeNameInfo):
                    self._value_check(a, info)
            else:
                self._store_value(a, p.type, ctx, given)

    def _mark_byref(self, a: A.Expr, info: Info, p: ParamInfo) -> bool:
        """Whether ``a`` is a variable that can be passed by reference; boxes locals that are."""
        if isinstance(info, VarInfo):
            v = info.sym
            if v.const:
                return False
            if v.storage in ("local", "param") and not v.byref:
                v.boxed = True
            v.assigned = True
            v.read = True
            return True
        return isinstance(info, IndexInfo)

    def _new(self, e: A.New, ctx: _Ctx) -> Info:
        typ = self.r.resolve_type(e.type, ctx.module, ctx.cls)
        args = e.args or []
        if typ is t.ANY:  # a class from protected code
            for a in args:
                self._value(a, ctx)
            return StubNewInfo(t.ANY, self.stubs.stubs.get(e.type.name.lower()))
        if typ is t.ERROR:
            for a in args:
                self._expr(a, ctx)
            return ErrorInfo(t.ERROR)
        if isinstance(typ, t.PrimitiveType):
            self.sink.report(M.NOT_SUPPORTED, e.span, what=f"New {typ}")
            return ErrorInfo(t.ERROR)
        cls = self.r.class_of(typ)
        if cls is not None:
            if not cls.ctors:
                if args:
                    self.sink.report(M.NO_CTOR_OVERLOAD, e.span, cls=cls.name, count=len(args))
                return NewInfo(typ, cls)
            arg_types = [self._value(a, ctx) for a in args]
            best = best_overloads(cls.ctors, arg_types)
            if not best:
                self.sink.report(M.NO_CTOR_OVERLOAD, e.span, cls=cls.name, count=len(args))
                return NewInfo(typ, cls)
            ctor = best[0]
            if len(best) > 1 and not any(t.permissive(a) for a in arg_types):
                self.sink.report(M.AMBIGUOUS_OVERLOAD, e.span, name=f"New {cls.name}",
                                 candidates=_overload_list(best))
            for a, prm in zip(args, ctor.params):
                if prm.byref:
                    info = self.model.info[a]
                    if not self._mark_byref(a, info, ParamInfo(prm.name, prm.type, True)):
                        self.model.byref_temps.add(a)
            return NewInfo(typ, cls, ctor, self._params(ctor.params))
        d = self.r.delegate_of(typ)
        if d is not None:
            if len(args) != 1:
                self.sink.report(M.WRONG_ARG_COUNT, e.span, name=d.name, expected=1, given=len(args))
                return NewInfo(typ, d)
            a = args[0]
            if isinstance(a, A.AddressOf):
                self._addressof(a, ctx, d)
                self._record(a, self.model.info.get(a) or ErrorInfo(t.ERROR))
            else:
                self._store_value(a, t.STRING, ctx)
            return NewInfo(typ, d)
        b = self.r.builtin_of(typ)
        if b is None:
            return ErrorInfo(t.ERROR)
        if b.is_global:  # Move, Controller, ...: one per controller, never created
            self.sink.report(M.NEW_OF_GLOBAL_CLASS, e.span, cls=b.name)
            return ErrorInfo(t.ERROR)
        params = self._params(b.constructor or ())
        if b.constructor is not None and params:
            self._check_count(b.name, params, args, e.span)
        self._args(args, params, ctx)
        return NewInfo(typ, b, params=params)

    def _address_overload(self, group: OverloadSet, e: A.AddressOf, ctx: _Ctx, d: DelegateSym | None,
                          static: bool) -> ProcSym | None:
        """The overload ``AddressOf`` binds: the one whose parameters fit the delegate's (the
        template of ``New D(AddressOf f)``), or the only one there is."""
        cands = [p for p in group.procs if visible(p, ctx.module, ctx.cls) and (p.shared or not static)]
        if d is not None:
            cands = [p for p in cands if len(p.params) == len(d.params)]
            best = best_overloads(cands, [v.type for v in d.params])
        else:
            best = cands
        if len(best) == 1:
            return best[0]
        if not best:
            self.sink.report(M.NO_OVERLOAD, e.span, name=group.name, count=len(d.params) if d else 0,
                             candidates=_overload_list(group.procs))
        else:
            self.sink.report(M.AMBIGUOUS_OVERLOAD, e.span, name=group.name, candidates=_overload_list(best))
        return None

    def _choose_overload(self, group: OverloadSet, args: list[A.Expr], infos: list[Info], span: object,
                         ctx: _Ctx, static: bool) -> ProcSym | None:
        """The overload of ``group`` a call with these (already typed) arguments runs, or None
        after reporting why there is none (overloads.py has the rule).  Only the overloads
        visible from here count, and only Shared ones when the call names the class."""
        cands = [p for p in group.procs if visible(p, ctx.module, ctx.cls) and (p.shared or not static)]
        if not cands:  # the set is visible (checked by the caller), so some overload is Private
            self.sink.report(M.PRIVATE_MEMBER, span, name=group.name,  # type: ignore[arg-type]
                             owner=group.owner.name if group.owner is not None else "?")
            return None
        arg_types = [_arg_type(i) for i in infos]
        best = best_overloads(cands, arg_types)
        if not best:
            if not _unparsed(args):
                self.sink.report(M.NO_OVERLOAD, span, name=group.name,  # type: ignore[arg-type]
                                 count=len(args), candidates=_overload_list(cands))
            return None
        if len(best) > 1 and not any(t.permissive(a) for a in arg_types):
            self.sink.report(M.AMBIGUOUS_OVERLOAD, span, name=group.name,  # type: ignore[arg-type]
                             candidates=_overload_list(best))
        return best[0]

    def _addressof(self, e: A.AddressOf, ctx: _Ctx, d: DelegateSym | None = None) -> Info:
        ci = self._callee(e.target, ctx)
        if not isinstance(ci, ProcRefInfo):
            self.sink.report(M.ADDRESSOF_TARGET, e.span, what=f"'{_text(e.target)}'")
            return self._record(e, ErrorInfo(t.ERROR))
        if isinstance(ci.sym, OverloadSet):
            chosen = self._address_overload(ci.sym, e, ctx, d, ci.static)
            if chosen is None:
                return self._record(e, ErrorInfo(t.ERROR))
            ci = ProcRefInfo(chosen.result, chosen, receiver=ci.receiver)
        p = ci.sym
        assert isinstance(p, ProcSym)
        if d is not None and len(p.params) != len(d.params):
            self.sink.report(M.WRONG_ARG_COUNT, e.span, name=p.name, expected=len(d.params), given=len(p.params))
        return self._record(e, AddressOfInfo(d.type if d else t.ERROR, p, receiver=ci.receiver))


def _overloads_of(p: ProcSym) -> ProcSym | OverloadSet:
    """The overload set ``p`` belongs to, or ``p`` itself."""
    members = getattr(p.owner, "members", {})
    group = members.get(p.name.lower())
    return group if isinstance(group, OverloadSet) and p in group.procs else p


def _arg_type(info: Info) -> t.GplType:
    """The type an argument offers to overload resolution (a type or module name offers none)."""
    if isinstance(info, NAMES_NOT_VALUES):
        return t.ERROR
    return info.type


def _overload_list(procs: list[ProcSym]) -> str:
    return ", ".join(signature_text(p) for p in procs)


def _parameterless(member: object) -> ProcSym | None:
    """The procedure of ``member`` that can be called without arguments (ProjectStart, a module's
    Init, Sub Main), or None."""
    return next((p for p in procedures(member) if not p.params), None)


def _unparsed(args: list[A.Expr]) -> bool:
    """Some argument could not be parsed (the parser has reported why): the count of the
    arguments says nothing, so it is not checked — one error, not two."""
    return any(type(a) is A.ErrorExpr for a in args)


def _count_text(lo: int, hi: int) -> str:
    return str(hi) if lo == hi else f"{lo} to {hi}"


def _child_blocks(s: A.Stmt) -> list[A.Block]:
    out: list[A.Block] = []
    if isinstance(s, A.If):
        out.append(s.then_body)
        out.extend(ei.body for ei in s.elseifs)
        if s.else_body is not None:
            out.append(s.else_body)
    elif isinstance(s, (A.For, A.ForEach, A.While, A.DoLoop)):
        out.append(s.body)
    elif isinstance(s, A.Select):
        out.extend(c.body for c in s.cases)
    elif isinstance(s, A.Try):
        out.append(s.body)
        if s.catch is not None:
            out.append(s.catch.body)
        if s.finally_ is not None:
            out.append(s.finally_.body)
    return out


def child_blocks(s: A.Stmt) -> list[A.Block]:
    """The statement lists directly inside a statement (If branches, loop body, Try parts ...)."""
    return _child_blocks(s)


def _text(e: A.Expr) -> str:
    if isinstance(e, A.Name):
        return e.name
    if isinstance(e, A.MemberAccess):
        return f"{_text(e.target)}.{e.name}"
    if isinstance(e, A.Invoke):
        return f"{_text(e.target)}(...)"
    if isinstance(e, A.MeExpr):
        return "Me"
    return "expression"


def analyze(units: list[A.SourceUnit], sink: DiagnosticSink, catalogue: Catalogue,
            project_name: str = "", start: str | None = None, *, protected: bool = False,
            strict: bool = False, stub_provider: Callable[[Stub], str | None] | None = None,
            start_span: Span | None = None, sources_missing: bool = False) -> Model:
    """Semantic analysis of a parsed project (units in ProjectSource order).

    ``protected``: the project has protected (.gpp) files, so unknown names become stubs
    (``gpl2py.gpl.semantics.stubs``); ``strict`` reports every stub as an error; ``stub_provider``
    names the stand-in that implements a stub, for its warning.  ``start_span``: where ``start``
    is written (the ProjectStart value in Project.gpr), where a start procedure that does not
    exist is reported -- unless ``sources_missing``: a source failed to load (reported) and may be
    where it is, so its absence says nothing more."""
    checker = Checker(ProjectSyms(project_name), catalogue, sink,
                      StubTable(sink, protected=protected, strict=strict, provider=stub_provider))
    checker.sources_missing = sources_missing
    return checker.run(units, start, start_span)


__all__ = ["analyze", "Model", "Info", "InfoTable", "ParamInfo", "assignable", "child_blocks", "TOP_MODULE"]
