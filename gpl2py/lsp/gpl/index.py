"""Where each name of the last analysis is written and what it stands for: the occurrences a request looks up.

The check leaves the analysed project in the front end's memo (``pipeline.MODEL_KEY``): every
expression's meaning (``Model.info``: which variable, procedure, built-in member ...) and every
declaration's symbol.  :class:`Index` walks a file's tree on the first request that needs it and
records each *occurrence*: where a name is written and the symbol the checker gave it.  Nothing
here resolves a name the checker resolved: what ``check`` decided is what the editor shows.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from lsprotocol import types as T
from pygls.exceptions import JsonRpcException
from pygls.uris import from_fs_path

from gpl2py.gpl.pipeline import MODEL_KEY
from gpl2py.gpl.semantics.catalogue import BuiltinClass, BuiltinConstant, BuiltinFunction
from gpl2py.gpl.semantics.catalogue import Member as BuiltinMember
from gpl2py.gpl.semantics.check import Model
from gpl2py.gpl.semantics.info import (
    BuiltinClassInfo,
    BuiltinConstInfo,
    BuiltinFunctionInfo,
    BuiltinFunctionRefInfo,
    BuiltinMemberInfo,
    CallInfo,
    ClassInfo,
    Info,
    ModuleInfo,
    NewInfo,
    ProcRefInfo,
    PropInfo,
    ResultInfo,
    VarInfo,
)
from gpl2py.gpl.semantics.symbols import (
    ClassSym,
    DelegateSym,
    ModuleSym,
    OverloadSet,
    ProcSym,
    PropSym,
    VarSym,
)
from gpl2py.gpl.syntax import ast as A
from gpl2py.lsp import convert
from gpl2py.lsp.projects import ProjectState


@dataclass(frozen=True, slots=True)
class Occ:
    """A name written at ``line:col`` to ``end`` (1-based, characters, one line) of ``path``,
    standing for ``sym`` (a symbol of the project, a built-in's record, or a label's node);
    ``decl``: this is where it is declared."""

    path: str
    line: int
    col: int
    end: int
    sym: object
    decl: bool = False
    owner: object = None  # a built-in member's class


@dataclass
class Index:
    """The occurrences of the last analysis, file by file as requests need them (a hover walks
    the one file it is in), and each symbol's declaration, found from the symbol itself."""

    model: Model
    files: dict[str, list[Occ]] = field(default_factory=dict)
    decls: dict[int, Occ | None] = field(default_factory=dict)
    uses: dict[int, list[Occ]] = field(default_factory=dict)
    procs: dict[str, list[tuple[int, int, ProcSym, ClassSym | None, ModuleSym]]] = field(default_factory=dict)
    classes: dict[str, ClassSym] = field(default_factory=dict)  # ClassType key -> class
    class_names: dict[str, list[ClassSym]] = field(default_factory=dict)  # lower-case name -> classes
    units: dict[str, A.SourceUnit] = field(default_factory=dict)
    texts: dict[str, str] = field(default_factory=dict)  # the text each file was analysed with
    _lines: dict[str, list[str]] = field(default_factory=dict)

    def lines(self, path: str) -> list[str]:
        found = self._lines.get(path)
        if found is None:
            found = self._lines[path] = convert.lines_of(self.texts.get(path, ""))
        return found

    def occs(self, path: str) -> list[Occ]:
        """The occurrences of ``path``, walked on first use."""
        found = self.files.get(path)
        if found is None:
            unit = self.units.get(path)
            found = self.files[path] = _walk_file(self, path, unit) if unit is not None else []
        return found

    def at(self, path: str, line: int, col: int) -> Occ | None:
        for o in self.occs(path):
            if o.line == line and o.col <= col <= o.end:
                return o
        return None

    def occurrences(self, sym: object) -> list[Occ]:
        """Every occurrence of ``sym`` in the project (walks every file once)."""
        for path in self.units:
            self.occs(path)
        return self.uses.get(id(sym), [])

    def declaration(self, sym: object) -> Occ | None:
        """Where ``sym``'s name is written in its declaration."""
        key = id(sym)
        if key not in self.decls:
            self.decls[key] = _declaration(self, sym)
        return self.decls[key]

    def scope(self, path: str, line: int) -> tuple[ProcSym | None, ClassSym | None, ModuleSym | None]:
        """The procedure, class and module around ``line`` of ``path`` (from the last analysis)."""
        self.occs(path)
        for first, last, proc, cls, mod in self.procs.get(path, ()):
            if first <= line <= last:
                return proc, cls, mod
        for mod in self.model.project.module_list:
            if abspath(mod.path) == path and mod.decl is not None and mod.decl.span.line <= line <= mod.decl.span.end_line:
                return None, None, mod
        return None, None, None


def abspath(p: str) -> str:
    """The absolute path a diagnostic's or a node's file name stands for (the server's key)."""
    return os.path.abspath(p)


def index_of(state: ProjectState) -> Index | None:
    """The index of ``state``'s last analysis (built once per analysis)."""
    kept = state.memo.get(MODEL_KEY)
    if not isinstance(kept, tuple):
        return None
    project, units, model = kept
    cached = state.memo.get("lsp-index")
    if isinstance(cached, tuple) and cached[0] is kept:  # (each check leaves a new tuple: the
        return cached[1]                                # model is kept from one check to the next)
    index = _build(units, model, state.last.files if state.last is not None else {})
    state.memo["lsp-index"] = (kept, index)
    return index


def _symbol(sym: object) -> object:
    """The symbol references are kept under: one procedure for an overload set named alone."""
    if isinstance(sym, OverloadSet):
        return sym.procs[0] if sym.procs else sym
    if isinstance(sym, ProcSym) and sym.prop is not None:
        return sym.prop
    return sym


@lru_cache(maxsize=8192)
def _word(name: str) -> re.Pattern[str]:
    return re.compile(r"(?<![\w])" + re.escape(name) + r"(?![\w])", re.IGNORECASE)


class _Builder:
    def __init__(self, model: Model, index: Index, path: str, lines: list[str]) -> None:
        self.model, self.index, self.path, self.lines = model, index, path, lines
        self.out: list[Occ] = []
        self.typed: set[int] = set()  # the TypeRefs of New expressions, indexed with their class

    def add(self, line: int, col: int, name: str, sym: object, decl: bool = False, owner: object = None) -> None:
        sym = _symbol(sym)
        o = Occ(self.path, line, col, col + len(name), sym, decl, owner)
        self.out.append(o)
        if not isinstance(sym, (BuiltinMember, BuiltinFunction, BuiltinConstant, BuiltinClass)):
            self.index.uses.setdefault(id(sym), []).append(o)

    def find(self, node: A.Node, name: str, from_end: bool = False) -> tuple[int, int] | None:
        """Where ``name`` is written inside ``node`` (the first whole word; the last with
        ``from_end``, for ``obj.name``)."""
        line, col, end_line, end_col = node._line, node._col, node._end_line, node._end_col
        size = len(name)
        lines = self.lines
        if isinstance(node, A.Name):
            return line, col
        if from_end and 0 < end_line <= len(lines) and \
                lines[end_line - 1][end_col - 1 - size:end_col - 1].lower() == name.lower():
            return end_line, end_col - size  # ``obj.name``: the name ends the span
        pattern = _word(name.lower())
        rows = range(end_line, line - 1, -1) if from_end else range(line, end_line + 1)
        for row in rows:
            text = lines[row - 1] if 0 < row <= len(lines) else ""
            lo = col - 1 if row == line else 0
            hi = end_col - 1 if row == end_line else len(text)
            hits = list(pattern.finditer(text, lo, max(hi, lo)))
            if hits:
                m = hits[-1] if from_end else hits[0]
                return row, m.start() + 1
        return None

    def name(self, node: A.Node, name: str, sym: object, decl: bool = False, from_end: bool = False,
             owner: object = None) -> None:
        where = self.find(node, name, from_end)
        if where is not None:
            self.add(where[0], where[1], name, sym, decl, owner)

    def walk(self, unit: A.SourceUnit) -> None:
        stack: list[tuple[A.Node, ProcSym | None, ClassSym | None, ModuleSym | None]] = [(unit, None, None, None)]
        project = self.model.project
        while stack:
            node, proc, cls, mod = stack.pop()
            if isinstance(node, A.ModuleDecl):
                mod = project.modules.get(node.name.lower())
                if mod is not None and mod.decl is node:
                    self.name(node, node.name, mod, decl=True)
            elif isinstance(node, A.ClassDecl):
                cls = self.model.class_of_decl.get(node)
                if cls is not None:
                    self.name(node, node.name, cls, decl=True)
            elif isinstance(node, (A.ProcDecl, A.Accessor)):
                proc = self.model.proc_of_decl.get(node)
                if proc is not None and mod is not None:
                    span = node.span
                    self.index.procs.setdefault(self.path, []).append((span.line, span.end_line, proc, cls, mod))
                    if isinstance(node, A.ProcDecl):
                        self.name(node, node.name, proc, decl=True)
                    for v in proc.params:
                        if isinstance(v.declared_at, A.Param):
                            self.name(v.declared_at, v.name, v, decl=True)
            elif isinstance(node, A.PropertyDecl) and cls is not None:
                prop = cls.members.get(node.name.lower())
                if isinstance(prop, PropSym):
                    self.name(node, node.name, prop, decl=True)
            elif isinstance(node, A.DelegateDecl):
                d = self.model.delegate_of_decl.get(node)
                if d is not None:
                    self.name(node, node.name, d, decl=True)
            elif isinstance(node, A.VarDeclarator):
                sym = self.model.local_of(node, proc) if proc is not None else None
                if sym is None and proc is None:
                    owner = cls if cls is not None else mod
                    member = owner.members.get(node.name.lower()) if owner is not None else None
                    sym = member if isinstance(member, VarSym) and member.declared_at is node else None
                if sym is not None:
                    self.name(node, node.name, sym, decl=sym.declared_at == node)  # (== : CompactDeclarator)
            elif isinstance(node, A.Label) and proc is not None:
                if proc.labels.get(node.name.lower()) is node:
                    self.name(node, node.name, node, decl=True)
            elif isinstance(node, A.GoTo) and proc is not None:
                target = proc.labels.get(node.label.lower())
                if target is not None:
                    self.name(node, node.label, target, from_end=True)
            elif isinstance(node, A.TypeRef) and id(node) not in self.typed:
                # ``As Gripper``: the project's one class of that name (none is not a user class;
                # several: rename refuses, see edits.collision)
                named = self.index.class_names.get(node.parts[-1].lower(), [])
                if len(named) == 1:
                    self.name(node, node.parts[-1], named[0], from_end=True)
            elif isinstance(node, A.Expr):
                self.expr(node)
            # (a long Dim's declarators are made when asked: its children are only their types)
            for child in reversed(list(node.declarators if isinstance(node, A.VarDecl) else node.children())):
                stack.append((child, proc, cls, mod))

    def expr(self, e: A.Expr) -> None:
        info = e._info
        if isinstance(e, A.New) and isinstance(info, NewInfo) and isinstance(info.sym, ClassSym):
            self.typed.add(id(e.type))  # (the class the checker chose, not one found by name)
            self.name(e.type, e.type.parts[-1], info.sym, from_end=True)
            return
        if not isinstance(e, (A.Name, A.MemberAccess)) or info is None:
            return
        sym, owner = _meaning(info)
        if sym is not None:
            self.name(e, e.name, sym, from_end=isinstance(e, A.MemberAccess), owner=owner)


def _meaning(info: Info) -> tuple[object, object]:
    """What the name ``e`` stands for, and a built-in member's class."""
    if isinstance(info, (VarInfo, PropInfo, ModuleInfo, ClassInfo, ResultInfo)):
        return info.sym, None
    if isinstance(info, (CallInfo, ProcRefInfo)):
        return info.sym, None
    if isinstance(info, BuiltinMemberInfo):
        return info.sym, info.owner
    if isinstance(info, (BuiltinFunctionInfo, BuiltinFunctionRefInfo, BuiltinConstInfo)):
        return info.sym, None
    if isinstance(info, BuiltinClassInfo) and info.sym is not None:
        return info.sym, None
    return None, None


def _build(units: list[A.SourceUnit], model: Model, texts: dict[str, str]) -> Index:
    index = Index(model)
    for unit in units:
        path = abspath(unit.path)
        index.units[path] = unit
        index.texts[path] = texts.get(path, "")
    for cls in model.class_of_decl.values():
        if cls.type is not None:
            index.classes[cls.type.key] = cls
        index.class_names.setdefault(cls.name.lower(), []).append(cls)
    return index


def _walk_file(index: Index, path: str, unit: A.SourceUnit) -> list[Occ]:
    b = _Builder(index.model, index, path, index.lines(path))
    b.walk(unit)
    _calls(unit, b)
    return sorted(b.out, key=lambda o: (o.line, o.col))


def _declaration(index: Index, sym: object) -> Occ | None:
    """The occurrence of ``sym``'s name in its declaration, from the node that declares it."""
    node: object = None
    name = getattr(sym, "name", "")
    if isinstance(sym, VarSym):
        node = sym.declared_at
    elif isinstance(sym, (ProcSym, PropSym, ClassSym, ModuleSym, DelegateSym)):
        node = sym.decl
        if isinstance(node, A.Accessor) and isinstance(sym, ProcSym) and sym.prop is not None:
            node, name = sym.prop.decl, sym.prop.name
    elif isinstance(sym, A.Label):
        node = sym
    if not isinstance(node, A.Node) or not name:
        return None
    path = abspath(node._file)
    b = _Builder(index.model, index, path, index.lines(path))
    where = b.find(node, name)
    return Occ(path, where[0], where[1], where[1] + len(name), sym, True) if where is not None else None


def _calls(unit: A.SourceUnit, b: _Builder) -> None:
    """A call names the overload it chose: ``F(1)``'s name stands for that procedure, where its
    target alone (an overload set) would stand for the first."""
    stack: list[A.Node] = [unit]
    while stack:
        node = stack.pop()
        if isinstance(node, A.Invoke) and isinstance(node._info, CallInfo):
            target = node.target
            if isinstance(target, (A.Name, A.MemberAccess)) and isinstance(target._info, ProcRefInfo) \
                    and isinstance(target._info.sym, OverloadSet):
                chosen = node._info.sym
                where = b.find(target, target.name, from_end=isinstance(target, A.MemberAccess))
                if where is not None:
                    _replace(b, where, target.name, chosen)
        stack.extend(node.children())


def _replace(b: _Builder, where: tuple[int, int], name: str, sym: object) -> None:
    for i, o in enumerate(b.out):
        if (o.line, o.col) == where:
            old = b.index.uses.get(id(o.sym), [])
            if o in old:
                old.remove(o)
            b.out[i] = Occ(o.path, o.line, o.col, o.end, sym)
            b.index.uses.setdefault(id(sym), []).append(b.out[i])
            return


class Refused(JsonRpcException):
    """A request gpl2py declines, with the reason shown to the user (LSP's RequestFailed)."""

    CODE = -32803


def loaded_index(ls: Any, state: ProjectState, path: str) -> tuple[Index, list[str]] | None:
    result = state.last
    if result is None:
        return None
    index = index_of(state)
    if index is None:
        return None
    return index, convert.lines_of(result.files.get(path, ""))


def at_cursor(ls: Any, state: ProjectState, path: str, params: Any) -> tuple[Index, list[str], Occ | None] | None:
    ready = loaded_index(ls, state, path)
    if ready is None:
        return None
    index, lines = ready
    line, col = convert.from_client(lines, params.position, ls.workspace.position_codec)
    return index, lines, index.at(path, line, col)


def location(ls: Any, state: ProjectState, o: Occ) -> T.Location:
    lines = convert.lines_of(state.last.files.get(o.path, "")) if state.last else []
    return T.Location(uri=from_fs_path(o.path) or o.path, range=occ_range(ls, lines, o))


def occ_range(ls: Any, lines: list[str], o: Occ) -> T.Range:
    codec = ls.workspace.position_codec
    return T.Range(convert.position(lines, o.line, o.col, codec), convert.position(lines, o.line, o.end, codec))


def in_order(occs: list[Occ]) -> list[Occ]:
    return sorted(set(occs), key=lambda o: (o.path, o.line, o.col))
