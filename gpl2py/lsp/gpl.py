"""GPL's navigation for the language server: hover, definition, references, highlight, symbols,
completion, signature help, rename and quick fixes, read off the last check's analysis.

The check leaves the analysed project in the front end's memo (``pipeline.MODEL_KEY``): every
expression's meaning (``Model.info``: which variable, procedure, built-in member ...) and every
declaration's symbol.  :class:`Index` walks the trees once per analysis and records where each
name is written and what it stands for -- an *occurrence* -- so that every request is a look-up:
the symbol under the cursor, its declaration, every occurrence of the same symbol.  Nothing here
resolves a name the checker resolved: what ``check`` decided is what the editor shows.

Completion and signature help work on the text being typed, which has not been checked yet (a
half-typed ``Cmd.`` is a syntax error): they find the enclosing procedure from the last analysis
and resolve the words before the cursor through its scopes, in the order of spec §6.4.
"""

from __future__ import annotations

import difflib
import importlib
import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from lsprotocol import types as T
from pygls.exceptions import JsonRpcException
from pygls.uris import from_fs_path

from gpl2py import messages as M
from gpl2py.gpl.pipeline import MODEL_KEY
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, BuiltinConstant, BuiltinFunction, Catalogue
from gpl2py.gpl.semantics.catalogue import Member as BuiltinMember
from gpl2py.gpl.semantics.catalogue import load_catalogue
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
from gpl2py.gpl.semantics.symbols import ClassSym, DelegateSym, ModuleSym, OverloadSet, ProcSym, PropSym, VarSym
from gpl2py.gpl.syntax import ast as A
from gpl2py.lsp import convert
from gpl2py.lsp.projects import ProjectState

# -- the index -----------------------------------------------------------------------------------


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
            if _abspath(mod.path) == path and mod.decl is not None and mod.decl.span.line <= line <= mod.decl.span.end_line:
                return None, None, mod
        return None, None, None


def _abspath(p: str) -> str:
    import os

    return os.path.abspath(p)


def index_of(state: ProjectState) -> Index | None:
    """The index of ``state``'s last analysis (built once per analysis)."""
    kept = state.memo.get(MODEL_KEY)
    if not isinstance(kept, tuple):
        return None
    project, units, model = kept
    cached = state.memo.get("lsp-index")
    if isinstance(cached, Index) and cached.model is model:
        return cached
    index = _build(units, model, state.last.files if state.last is not None else {})
    state.memo["lsp-index"] = index
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
                sym = self.model.local_of.get(node) if proc is not None else None
                if sym is None and proc is None:
                    owner = cls if cls is not None else mod
                    member = owner.members.get(node.name.lower()) if owner is not None else None
                    sym = member if isinstance(member, VarSym) and member.declared_at is node else None
                if sym is not None:
                    self.name(node, node.name, sym, decl=sym.declared_at is node)
            elif isinstance(node, A.Label) and proc is not None:
                if proc.labels.get(node.name.lower()) is node:
                    self.name(node, node.name, node, decl=True)
            elif isinstance(node, A.GoTo) and proc is not None:
                target = proc.labels.get(node.label.lower())
                if target is not None:
                    self.name(node, node.label, target, from_end=True)
            elif isinstance(node, A.Expr):
                self.expr(node)
            for child in reversed(list(node.children())):
                stack.append((child, proc, cls, mod))

    def expr(self, e: A.Expr) -> None:
        info = e._info
        if isinstance(e, A.New) and isinstance(info, NewInfo) and isinstance(info.sym, ClassSym):
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
        path = _abspath(unit.path)
        index.units[path] = unit
        index.texts[path] = texts.get(path, "")
    for cls in model.class_of_decl.values():
        if cls.type is not None:
            index.classes[cls.type.key] = cls
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
    path = _abspath(node._file)
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


# -- requests ---------------------------------------------------------------------------------------


class Refused(JsonRpcException):
    """A request gpl2py declines, with the reason shown to the user (LSP's RequestFailed)."""

    CODE = -32803


def _ready(ls: Any, state: ProjectState, path: str) -> tuple[Index, list[str]] | None:
    result = state.last
    if result is None:
        return None
    index = index_of(state)
    if index is None:
        return None
    return index, convert.lines_of(result.files.get(path, ""))


def _cursor(ls: Any, state: ProjectState, path: str, params: Any) -> tuple[Index, list[str], Occ | None] | None:
    ready = _ready(ls, state, path)
    if ready is None:
        return None
    index, lines = ready
    line, col = convert.from_client(lines, params.position, ls.workspace.position_codec)
    return index, lines, index.at(path, line, col)


def _location(ls: Any, state: ProjectState, o: Occ) -> T.Location:
    lines = convert.lines_of(state.last.files.get(o.path, "")) if state.last else []
    return T.Location(uri=from_fs_path(o.path) or o.path, range=_range(ls, lines, o))


def _range(ls: Any, lines: list[str], o: Occ) -> T.Range:
    codec = ls.workspace.position_codec
    return T.Range(convert.position(lines, o.line, o.col, codec), convert.position(lines, o.line, o.end, codec))


def hover(ls: Any, state: ProjectState, path: str, params: T.HoverParams) -> T.Hover | None:
    found = _cursor(ls, state, path, params)
    if found is None:
        return None
    index, lines, o = found
    parts = [describe(o, index, state)] if o is not None else []
    line, col = convert.from_client(lines, params.position, ls.workspace.position_codec)
    for d in (state.last.by_file.get(path, []) if state.last else []):
        if d.span is not None and d.span.line <= line <= d.span.end_line:
            parts.append(explain(d.code))
    parts = [p for p in parts if p]
    if not parts:
        return None
    return T.Hover(contents=T.MarkupContent(kind=T.MarkupKind.Markdown, value="\n\n---\n\n".join(parts)),
                   range=_range(ls, lines, o) if o is not None else None)


def explain(code: str) -> str:
    """``gpl2py explain CODE``'s text."""
    m = next((x for x in M.all_messages() if x.code == code), None)
    if m is None:
        return ""
    return f"**{m.code}** ({m.severity_name}): {m.template}\n\n{m.notes or ''}".strip()


def describe(o: Occ, index: Index, state: ProjectState) -> str:
    """The hover text of an occurrence: a declaration as GPL writes it, where it is declared."""
    sym = o.sym
    if isinstance(sym, BuiltinMember):
        text = _code(member_signature(sym, owner=o.owner.name if isinstance(o.owner, BuiltinClass) else ""))
        doc = builtin_doc(o.owner, sym)
        return text + (f"\n\n{doc}" if doc else "") + "\n\nbuilt-in member"
    if isinstance(sym, BuiltinFunction):
        doc = builtin_doc(None, sym)
        return _code(function_signature(sym)) + (f"\n\n{doc}" if doc else "") + "\n\nbuilt-in function"
    if isinstance(sym, BuiltinConstant):
        return _code(f"Const {sym.name} As {sym.type} = {_value(sym.value)}") + "\n\nbuilt-in constant"
    if isinstance(sym, BuiltinClass):
        return _code(f"Class {sym.name}") + "\n\nbuilt-in class"
    text = _code(declaration(sym, index.model))
    decl = index.declaration(sym)
    if decl is not None:
        text += f"\n\ndeclared at {_shown(decl.path)}:{decl.line}:{decl.col}"
    return text


def _shown(path: str) -> str:
    import os

    return os.path.basename(path)


def _code(text: str) -> str:
    return f"```gpl\n{text}\n```"


def _value(v: object) -> str:
    if isinstance(v, str):
        return '"' + v.replace('"', '""') + '"'
    if isinstance(v, bool):
        return "True" if v else "False"
    return repr(v) if isinstance(v, float) else str(v)


def declaration(sym: object, model: Model) -> str:
    """``sym`` as its declaration reads (the type the checker gave it)."""
    if isinstance(sym, VarSym):
        kind = {"param": ("ByRef " if sym.byref else "ByVal "), "static": "Static ", "field": "Dim ",
                "module": "Dim ", "local": "Dim "}.get(sym.storage, "Dim ")
        if sym.const:
            kind = "Const "
        elif sym.public and sym.storage in ("module", "field"):
            kind = "Public " + ("Shared " if sym.shared and sym.storage == "field" else "")
        where = {"local": "local", "static": "static local", "param": "parameter", "module": "module variable",
                 "field": "field"}.get(sym.storage, "")
        text = f"{kind}{sym.name} As {sym.type}"
        if sym.const:
            value = model.const_values.get(sym, _literal(sym))
            if value is not None:
                text += f" = {_value(value)}"
            where = "constant"
        owner = _owner_name(sym.owner)
        return f"{text}    ' {where}" + (f" of {owner}" if owner else "")
    if isinstance(sym, ProcSym):
        return proc_signature(sym, qualified=True)
    if isinstance(sym, PropSym):
        return f"{'Public ' if sym.public else ''}Property {sym.owner.name}.{sym.name} As {sym.type}"
    if isinstance(sym, ClassSym):
        return f"{'Public ' if sym.public else ''}Class {'.'.join(sym.path)}"
    if isinstance(sym, ModuleSym):
        return f"Module {sym.name}"
    if isinstance(sym, DelegateSym):
        params = ", ".join(f"{p.name} As {p.type}" for p in sym.params)
        return f"Delegate {sym.name}({params})" + (f" As {sym.result}" if sym.result is not t.VOID else "")
    if isinstance(sym, A.Label):
        return f"{sym.name}:    ' label"
    return ""


def _literal(v: VarSym) -> object:
    init = v.decl.initializer if v.decl is not None else None
    if isinstance(init, (A.IntegerLiteral, A.RealLiteral, A.StringLiteral, A.BooleanLiteral)):
        return init.value
    return None


def _owner_name(owner: object) -> str:
    if isinstance(owner, ProcSym):
        return owner.name
    if isinstance(owner, (ClassSym, ModuleSym)):
        return owner.name
    return ""


def proc_signature(p: ProcSym, qualified: bool = False) -> str:
    params = ", ".join(_param_text(v) for v in p.params)
    shared = p.shared and isinstance(p.owner, ClassSym)  # (a module's procedures are all shared)
    head = f"{'Public ' if p.public else ''}{'Shared ' if shared else ''}{p.kind} "
    owner = f"{p.owner.name}." if qualified and isinstance(p.owner, (ModuleSym, ClassSym)) else ""
    tail = f" As {p.result}" if p.is_function else ""
    return f"{head}{owner}{p.name}({params}){tail}"


def _param_text(v: VarSym) -> str:
    text = f"{'ByRef ' if v.byref else ''}{v.name} As {v.type}"
    return f"Optional {text}" if v.optional else text


def member_signature(m: BuiltinMember, form: tuple[Any, ...] | None = None, owner: str = "") -> str:
    """``Function Location.Inverse() As Location``: a built-in member as GPL would declare it."""
    form = m.params if form is None else form
    params = ", ".join(_bparam(p) for p in form)
    tail = f" As {m.result}" if m.result is not t.VOID else ""
    name = f"{owner}.{m.name}" if owner else m.name
    shared = "Shared " if m.shared else ""
    if m.kind == "property" and not form:
        return f"{shared}Property {name}{tail}"
    return f"{shared}{'Function' if tail else 'Sub'} {name}({params}){tail}"


def function_signature(f: BuiltinFunction) -> str:
    tail = f" As {f.result}" if f.result is not t.VOID else ""
    return f"Function {f.name}({', '.join(_bparam(p) for p in f.params)}){tail}"


def _bparam(p: Any) -> str:
    text = f"{'ByRef ' if p.byref else ''}{p.name} As {p.type}"
    return f"Optional {text}" if p.optional else text


def builtin_doc(owner: BuiltinClass | None, sym: object) -> str:
    """The first paragraph of the runtime's docstring for a built-in (its GPL description): the
    catalogue keeps signatures only, the runtime is where each built-in is written and described.
    The runtime is imported on the first such hover (about a second, once per server)."""
    if isinstance(sym, BuiltinFunction):
        return _doc(sym.module, sym.python_name, "")
    if isinstance(owner, BuiltinClass) and isinstance(sym, BuiltinMember):
        return _doc("gplrt.builtins", owner.python_name, sym.name)
    return ""


@lru_cache(maxsize=4096)
def _doc(module: str, name: str, member: str) -> str:
    try:
        obj = getattr(importlib.import_module(module), name, None)
        if member:
            cls = obj if isinstance(obj, type) else type(obj)
            obj = getattr(cls, member, None)
            if isinstance(obj, property):
                obj = obj.fget
    except Exception:  # noqa: BLE001 - a description is a nicety; the signature is shown anyway
        return ""
    doc = (getattr(obj, "__doc__", None) or "").strip()
    return " ".join(doc.split("\n\n")[0].split()) if doc else ""


def definition(ls: Any, state: ProjectState, path: str, params: Any) -> list[T.Location] | None:
    found = _cursor(ls, state, path, params)
    if found is None or found[2] is None:
        return None
    index, _, o = found
    decl = index.declaration(o.sym)
    return [_location(ls, state, decl)] if decl is not None else None


def references(ls: Any, state: ProjectState, path: str, params: T.ReferenceParams) -> list[T.Location] | None:
    found = _cursor(ls, state, path, params)
    if found is None or found[2] is None:
        return None
    index, _, o = found
    keep = params.context.include_declaration
    return [_location(ls, state, x) for x in _sorted(index.occurrences(o.sym)) if keep or not x.decl]


def _sorted(occs: list[Occ]) -> list[Occ]:
    return sorted(set(occs), key=lambda o: (o.path, o.line, o.col))


def highlight(ls: Any, state: ProjectState, path: str, params: Any) -> list[T.DocumentHighlight] | None:
    found = _cursor(ls, state, path, params)
    if found is None or found[2] is None:
        return None
    index, lines, o = found
    return [T.DocumentHighlight(range=_range(ls, lines, x),
                                kind=T.DocumentHighlightKind.Write if x.decl else T.DocumentHighlightKind.Read)
            for x in _sorted(index.occurrences(o.sym)) if x.path == path]


# -- symbols -------------------------------------------------------------------------------------------

_KINDS: list[tuple[type, T.SymbolKind]] = [
    (ModuleSym, T.SymbolKind.Module), (ClassSym, T.SymbolKind.Class), (PropSym, T.SymbolKind.Property),
    (DelegateSym, T.SymbolKind.Interface),
]


def _kind(sym: object) -> T.SymbolKind | None:
    if isinstance(sym, ProcSym):
        if sym.name.lower() == "new":
            return T.SymbolKind.Constructor
        return T.SymbolKind.Method if isinstance(sym.owner, ClassSym) else T.SymbolKind.Function
    if isinstance(sym, VarSym):
        if sym.storage not in ("module", "field"):
            return None
        return T.SymbolKind.Constant if sym.const else (T.SymbolKind.Field if sym.storage == "field"
                                                        else T.SymbolKind.Variable)
    return next((k for cls, k in _KINDS if isinstance(sym, cls)), None)


def _container(sym: object) -> object:
    owner = getattr(sym, "owner", None)
    if isinstance(sym, ClassSym):
        owner = sym.outer if sym.outer is not None else sym.module
    return owner


def document_symbols(ls: Any, state: ProjectState, path: str, params: Any) -> list[T.DocumentSymbol] | None:
    ready = _ready(ls, state, path)
    if ready is None:
        return None
    index, lines = ready
    nodes: dict[int, T.DocumentSymbol] = {}
    top: list[T.DocumentSymbol] = []
    for o in index.occs(path):
        kind = _kind(o.sym) if o.decl else None
        if kind is None:
            continue
        node = T.DocumentSymbol(name=getattr(o.sym, "name", ""), kind=kind, range=_extent(ls, lines, o),
                                selection_range=_range(ls, lines, o), detail=_detail(o.sym), children=[])
        nodes[id(o.sym)] = node
        parent = nodes.get(id(_container(o.sym)))
        (parent.children if parent is not None else top).append(node)  # type: ignore[union-attr]
    return top


def _extent(ls: Any, lines: list[str], o: Occ) -> T.Range:
    decl = getattr(o.sym, "decl", None)
    if isinstance(decl, A.Node):
        span = decl.span
        if span.line <= o.line <= span.end_line:
            return convert.span_range(span, lines, ls.workspace.position_codec)
    return _range(ls, lines, o)


def _detail(sym: object) -> str | None:
    if isinstance(sym, ProcSym):
        return proc_signature(sym).split(" ", 1)[-1] if sym.params or sym.is_function else None
    if isinstance(sym, (VarSym, PropSym)):
        return f"As {sym.type}"
    return None


def workspace_symbols(ls: Any, state: ProjectState, query: str) -> list[T.WorkspaceSymbol]:
    """Modules, classes, procedures, properties, Consts and module variables whose name holds
    ``query`` (case-insensitive), from the symbol tables: no file is walked."""
    if state.last is None:
        return []
    index = index_of(state)
    if index is None:
        return []
    q = query.lower()
    out = []
    for sym, container in _declared(index.model):
        name = getattr(sym, "name", "")
        kind = _kind(sym)
        if kind is None or q not in name.lower():
            continue
        o = index.declaration(sym)
        if o is not None:
            out.append(T.WorkspaceSymbol(name=name, kind=kind, location=_location_in(ls, index.lines(o.path), o),
                                         container_name=getattr(container, "name", None)))
    return out


def _declared(model: Model) -> Iterator[tuple[object, object]]:
    """Every module, its members, and the members of its classes, with what holds them."""
    project = model.project
    for mod in [*project.module_list, *([project.top] if project.top is not None else [])]:
        if mod is not project.top:
            yield mod, None
        stack: list[tuple[object, object]] = [(m, mod if mod is not project.top else None) for m in mod.members.values()]
        while stack:
            sym, owner = stack.pop()
            if isinstance(sym, OverloadSet):
                stack.extend((p, owner) for p in sym.procs)
                continue
            yield sym, owner
            if isinstance(sym, ClassSym):
                stack.extend((m, sym) for m in sym.members.values())


def _location_in(ls: Any, lines: list[str], o: Occ) -> T.Location:
    return T.Location(uri=from_fs_path(o.path) or o.path, range=_range(ls, lines, o))


# -- completion and signature help -----------------------------------------------------------------

STATEMENT_KEYWORDS = ("Dim", "Static", "Const", "If", "ElseIf", "Else", "End If", "For", "For Each", "Next",
                      "While", "End While", "Do", "Loop", "Select Case", "Case", "End Select", "Try", "Catch",
                      "Finally", "End Try", "Return", "Exit", "GoTo", "Throw", "ReDim")
DECLARATION_KEYWORDS = ("Public", "Private", "Shared", "Dim", "Const", "Sub", "Function", "Property", "Class",
                        "Delegate", "End Module", "End Class")
EXPRESSION_KEYWORDS = ("New", "Not", "And", "AndAlso", "Or", "OrElse", "Xor", "Mod", "Is", "True", "False",
                       "Nothing", "Me", "AddressOf")
TYPE_NAMES = ("Integer", "Short", "Byte", "Single", "Double", "Boolean", "String", "Object")

_CHAIN = re.compile(r"([A-Za-z_]\w*(?:\s*\.\s*[A-Za-z_]\w*)*)\s*\.\s*(\w*)$")
_AS = re.compile(r"\b(As(?:\s+New)?|New)\s+(\w*)$", re.IGNORECASE)


def _current_lines(ls: Any, path: str, state: ProjectState) -> list[str]:
    uri = from_fs_path(path) or path
    doc = ls.workspace.text_documents.get(uri)
    if doc is not None:
        return convert.lines_of(doc.source)
    return convert.lines_of(state.last.files.get(path, "")) if state.last else []


def _typing(ls: Any, state: ProjectState, path: str, params: Any) -> tuple[Index, int, str] | None:
    """The index, the cursor's line and the code before the cursor in the text being typed;
    None inside a comment or a string, or before the first check."""
    ready = _ready(ls, state, path)
    if ready is None:
        return None
    lines = _current_lines(ls, path, state)
    line, col = convert.from_client(lines, params.position, ls.workspace.position_codec)
    before = _code_part((lines[line - 1] if 0 < line <= len(lines) else "")[:col - 1])
    return (ready[0], line, before) if before is not None else None


def completion(ls: Any, state: ProjectState, path: str, params: T.CompletionParams) -> T.CompletionList | None:
    typing = _typing(ls, state, path, params)
    if typing is None:
        return None
    index, line, before = typing
    proc, cls, mod = index.scope(path, line)
    chain = _CHAIN.search(before)
    items: list[T.CompletionItem] = []
    if chain is not None:
        target = resolve_chain([p.strip() for p in chain.group(1).split(".")], index, proc, cls, mod)
        items = [_item(name, sym, owner) for name, sym, owner in members_of(target, index, mod)]
    elif _AS.search(before):
        items = [T.CompletionItem(label=n, kind=T.CompletionItemKind.Keyword) for n in TYPE_NAMES]
        items += [T.CompletionItem(label=c.name, kind=T.CompletionItemKind.Class, detail="built-in class")
                  for c in load_catalogue().classes.values()]
        items += [T.CompletionItem(label=c.name, kind=T.CompletionItemKind.Class) for c in index.classes.values()]
    else:
        at_start = re.fullmatch(r"\s*(\w+:\s*)?\w*", before) is not None
        words = (STATEMENT_KEYWORDS if proc is not None else DECLARATION_KEYWORDS) if at_start else EXPRESSION_KEYWORDS
        items = [T.CompletionItem(label=k, kind=T.CompletionItemKind.Keyword) for k in words]
        items += [_item(name, sym, None) for name, sym in names_in_scope(index, proc, cls, mod)]
    return T.CompletionList(is_incomplete=False, items=items)


def _code_part(text: str) -> str | None:
    """``text`` if the cursor after it is in code, None in a comment or a string literal."""
    quoted = False
    for ch in text:
        if ch == '"':
            quoted = not quoted
        elif ch == "'" and not quoted:
            return None
    return None if quoted else text


def _item(name: str, sym: object, owner: object) -> T.CompletionItem:
    kind, detail = T.CompletionItemKind.Variable, None
    if isinstance(sym, BuiltinMember):
        kind = T.CompletionItemKind.Property if sym.kind == "property" else T.CompletionItemKind.Method
        detail = member_signature(sym)
    elif isinstance(sym, BuiltinFunction):
        kind, detail = T.CompletionItemKind.Function, function_signature(sym)
    elif isinstance(sym, BuiltinConstant):
        kind, detail = T.CompletionItemKind.Constant, f"As {sym.type}"
    elif isinstance(sym, (BuiltinClass, ClassSym)):
        kind = T.CompletionItemKind.Class
    elif isinstance(sym, ModuleSym):
        kind = T.CompletionItemKind.Module
    elif isinstance(sym, OverloadSet):
        kind, detail = T.CompletionItemKind.Function, " | ".join(proc_signature(p) for p in sym.procs)
    elif isinstance(sym, ProcSym):
        kind = T.CompletionItemKind.Method if isinstance(sym.owner, ClassSym) else T.CompletionItemKind.Function
        detail = proc_signature(sym)
    elif isinstance(sym, PropSym):
        kind, detail = T.CompletionItemKind.Property, f"Property {sym.name} As {sym.type}"
    elif isinstance(sym, VarSym):
        kind = T.CompletionItemKind.Constant if sym.const else (
            T.CompletionItemKind.Field if sym.storage in ("field", "module") else T.CompletionItemKind.Variable)
        detail = f"{sym.name} As {sym.type}"
    return T.CompletionItem(label=name, kind=kind, detail=detail)


def names_in_scope(index: Index, proc: ProcSym | None, cls: ClassSym | None,
                   mod: ModuleSym | None) -> Iterator[tuple[str, object]]:
    """Every name usable unqualified at a place, nearest first (spec §6.4), each once."""
    seen: set[str] = set()

    def once(items: Any) -> Iterator[tuple[str, object]]:
        for name, sym in items:
            if name.lower() not in seen:
                seen.add(name.lower())
                yield name, sym

    if proc is not None:
        yield from once((v.name, v) for v in proc.params)
        yield from once((v.name, v) for v in proc.locals.values())
    c = cls
    while c is not None:
        yield from once((getattr(m, "name", k), m) for k, m in c.members.items())
        c = c.outer
    if mod is not None:
        yield from once((getattr(m, "name", k), m) for k, m in mod.members.items())
    project = index.model.project
    for other in project.module_list:
        yield from once((getattr(m, "name", k), m) for k, m in other.members.items() if getattr(m, "public", False))
        yield from once([(other.name, other)])
    if project.top is not None:
        yield from once((getattr(m, "name", k), m) for k, m in project.top.members.items())
    cat = load_catalogue()
    yield from once((c.name, c) for c in cat.classes.values())
    yield from once((f.name, f) for f in cat.functions.values())
    yield from once((k.name, k) for k in cat.constants.values())


def resolve_chain(parts: list[str], index: Index, proc: ProcSym | None, cls: ClassSym | None,
                  mod: ModuleSym | None) -> object:
    """What ``a.b.c`` names at a place: a module, a class (for its Shared members), a built-in
    class, or a value's type; None when unknown."""
    if not parts:
        return None
    first = parts[0].lower()
    target: object = None
    for name, sym in names_in_scope(index, proc, cls, mod):
        if name.lower() == first:
            target = sym
            break
    if target is None and first == "string":
        target = load_catalogue().type_members.get("string")
    for part in parts[1:]:
        found = None
        for name, sym, _ in members_of(target, index, mod):
            if name.lower() == part.lower():
                found = sym
                break
        target = _value_type(found) if not isinstance(found, (ModuleSym, ClassSym, BuiltinClass)) else found
        if target is None:
            return None
    return _value_type(target) if not isinstance(target, (ModuleSym, ClassSym, BuiltinClass)) else target


def _value_type(sym: object) -> object:
    """The type whose members ``sym.`` lists: a variable's, a property's, a function's result."""
    if isinstance(sym, (VarSym, PropSym)):
        return sym.type
    if isinstance(sym, ProcSym) and sym.is_function:
        return sym.result
    if isinstance(sym, OverloadSet):
        return sym.result
    if isinstance(sym, BuiltinMember):
        return sym.result
    if isinstance(sym, BuiltinFunction):
        return sym.result
    if isinstance(sym, t.GplType):
        return sym
    return None


def members_of(target: object, index: Index, here: ModuleSym | None) -> list[tuple[str, object, object]]:
    """``(name, member, its built-in class)`` of what ``target.`` reaches."""
    cat: Catalogue = load_catalogue()
    if isinstance(target, ModuleSym):
        return [(getattr(m, "name", k), m, None) for k, m in target.members.items()
                if target is here or getattr(m, "public", False)]
    if isinstance(target, ClassSym):  # the class's name: its Shared members, Consts and nested classes
        return [(getattr(m, "name", k), m, None) for k, m in target.members.items()
                if getattr(m, "shared", False) or getattr(m, "const", False) or isinstance(m, ClassSym)]
    if isinstance(target, BuiltinClass):
        static = target.is_global or target is not cat.type_members.get("string")
        return [(m.name, m, target) for m in target.members.values() if m.shared or target.is_global or not static]
    if isinstance(target, t.ClassType):
        if target.builtin:
            b = cat.classes.get(target.key)
            return [(m.name, m, b) for m in b.members.values()] if b is not None else []
        c = index.classes.get(target.key)
        if c is not None:
            return [(getattr(m, "name", k), m, None) for k, m in c.members.items() if not isinstance(m, ClassSym)]
        return []
    if isinstance(target, t.GplType):
        b = cat.members_of(target)
        return [(m.name, m, b) for m in b.members.values()] if b is not None else []
    return []


def signature_help(ls: Any, state: ProjectState, path: str, params: Any) -> T.SignatureHelp | None:
    typing = _typing(ls, state, path, params)
    if typing is None:
        return None
    index, line, before = typing
    call = _open_call(before)
    if call is None:
        return None
    head, active = call
    m = re.search(r"([A-Za-z_]\w*(?:\s*\.\s*[A-Za-z_]\w*)*)\s*$", head)
    if m is None:
        return None
    parts = [p.strip() for p in m.group(1).split(".")]
    proc, cls, mod = index.scope(path, line)
    owner = resolve_chain(parts[:-1], index, proc, cls, mod) if len(parts) > 1 else None
    if len(parts) > 1:
        callee, owner = next(((sym, b) for name, sym, b in members_of(owner, index, mod)
                              if name.lower() == parts[-1].lower()), (None, None))
    else:
        callee = next((sym for name, sym in names_in_scope(index, proc, cls, mod) if name.lower() == parts[0].lower()),
                      None)
    sigs = _signatures(callee, owner)
    if not sigs:
        return None
    best = next((i for i, s in enumerate(sigs) if len(s.parameters or []) > active), 0)
    return T.SignatureHelp(signatures=sigs, active_signature=best, active_parameter=active)


def _open_call(text: str) -> tuple[str, int] | None:
    """The text before the innermost unclosed ``(`` and the index of the argument being typed."""
    depth, commas, quoted = 0, [0], False
    opens: list[int] = []
    for i, ch in enumerate(text):
        if ch == '"':
            quoted = not quoted
        elif quoted:
            continue
        elif ch == "(":
            opens.append(i)
            commas.append(0)
        elif ch == ")" and opens:
            opens.pop()
            commas.pop()
        elif ch == "," and opens:
            commas[-1] += 1
    del depth
    if not opens:
        return None
    return text[:opens[-1]], commas[-1]


def _signatures(callee: object, owner: object) -> list[T.SignatureInformation]:
    def info(label: str, names: list[str]) -> T.SignatureInformation:
        return T.SignatureInformation(label=label, parameters=[T.ParameterInformation(label=n) for n in names])

    if isinstance(callee, OverloadSet):
        return [info(proc_signature(p), [_param_text(v) for v in p.params]) for p in callee.procs]
    if isinstance(callee, ProcSym):
        return [info(proc_signature(callee), [_param_text(v) for v in callee.params])]
    if isinstance(callee, BuiltinMember):
        name = owner.name if isinstance(owner, BuiltinClass) else ""
        return [info(member_signature(callee, f, name), [_bparam(p) for p in f]) for f in callee.call_forms]
    if isinstance(callee, BuiltinFunction):
        return [info(function_signature(callee), [_bparam(p) for p in callee.params])]
    return []


# -- rename and code actions ----------------------------------------------------------------------

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
RESERVED = {w.lower() for w in STATEMENT_KEYWORDS + DECLARATION_KEYWORDS + EXPRESSION_KEYWORDS + TYPE_NAMES
            if " " not in w} | {"end", "then", "to", "step", "each", "in", "as", "byval", "byref", "optional",
                                "module", "call", "until", "case", "of", "preserve", "goto", "next", "loop"}


def _renamable(o: Occ | None) -> bool:
    return o is not None and isinstance(o.sym, (VarSym, ProcSym, PropSym, ClassSym, A.Label)) \
        and not (isinstance(o.sym, ProcSym) and o.sym.name.lower() == "new")


def prepare_rename(ls: Any, state: ProjectState, path: str, params: Any) -> T.Range | None:
    found = _cursor(ls, state, path, params)
    if found is None or not _renamable(found[2]):
        raise Refused("only a variable, parameter, procedure, property, class or label of this project can be renamed")
    return _range(ls, found[1], found[2])  # type: ignore[arg-type]


def rename(ls: Any, state: ProjectState, path: str, params: T.RenameParams) -> T.WorkspaceEdit | None:
    found = _cursor(ls, state, path, params)
    if found is None or not _renamable(found[2]):
        raise Refused("only a variable, parameter, procedure, property, class or label of this project can be renamed")
    index, _, o = found
    assert o is not None
    new = params.new_name.strip()
    if not _IDENT.fullmatch(new) or new.lower() in RESERVED:
        raise Refused(f"'{new}' is not a GPL name (a letter or _, then letters, digits or _; not a keyword)")
    problem = collision(o.sym, new, index)
    if problem is not None:
        raise Refused(problem)
    changes: dict[str, list[T.TextEdit]] = {}
    for x in _sorted(index.occurrences(o.sym)):
        lines = convert.lines_of(state.last.files.get(x.path, "")) if state.last else []
        changes.setdefault(from_fs_path(x.path) or x.path, []).append(T.TextEdit(range=_range(ls, lines, x),
                                                                                  new_text=new))
    return T.WorkspaceEdit(changes=changes)


def collision(sym: object, new: str, index: Index) -> str | None:
    """Why renaming ``sym`` to ``new`` would change what a name means, or None."""
    key = new.lower()
    if key == getattr(sym, "name", "").lower():
        return None
    project = index.model.project
    if isinstance(sym, A.Label):
        index.occurrences(sym)  # (every file's procedures known)
        for proc in (p for lst in index.procs.values() for _, _, p, _, _ in lst):
            if proc.labels.get(sym.name.lower()) is sym and key in proc.labels:
                return f"the procedure already has a label '{new}'"
        return None
    if isinstance(sym, VarSym) and sym.storage in ("local", "static", "param") and isinstance(sym.owner, ProcSym):
        proc = sym.owner
        clash = next((v for v in [*proc.params, *proc.locals.values()] if v.name.lower() == key), None)
        if clash is not None:
            return f"'{new}' is already declared in {proc.name}"
        if key == proc.name.lower() and proc.is_function:
            return f"'{new}' is the name of the Function {proc.name}, its result variable"
        scopes = _scope_of_proc(index, proc)
        hit = next((n for n, s in names_in_scope(index, None, *scopes) if n.lower() == key), None)
        if hit is not None:
            return f"'{new}' would hide '{hit}', which {proc.name} can use now"
        return None
    owner = getattr(sym, "owner", None) if not isinstance(sym, ClassSym) else (sym.outer or sym.module)
    members = getattr(owner, "members", {})
    if key in members:
        return f"{getattr(owner, 'name', 'the module')} already has a member '{new}'"
    if key in project.modules:
        return f"'{new}' is the name of a module"
    if project.public_members(new) and getattr(sym, "public", False):
        where = project.public_members(new)[0].where
        return f"'{new}' is already a Public name of {where}"
    cat = load_catalogue()
    if cat.lookup_class(new) or cat.lookup_function(new) or cat.lookup_constant(new):
        return f"'{new}' is a built-in name"
    for o in index.occurrences(sym):  # a local of the new name where the symbol is used would capture it
        for first, last, proc, _, _ in index.procs.get(o.path, ()):
            if first <= o.line <= last and any(v.name.lower() == key for v in [*proc.params, *proc.locals.values()]):
                return f"'{new}' is a local of {proc.name}, which uses '{getattr(sym, 'name', '')}'"
    return None


def _scope_of_proc(index: Index, proc: ProcSym) -> tuple[ClassSym | None, ModuleSym | None]:
    index.occurrences(proc)  # (every file's procedures known)
    for lst in index.procs.values():
        for _, _, p, cls, mod in lst:
            if p is proc:
                return cls, mod
    return None, proc.module


def code_actions(ls: Any, state: ProjectState, path: str, params: T.CodeActionParams) -> list[T.CodeAction] | None:
    ready = _ready(ls, state, path)
    if ready is None:
        return None
    index, lines = ready
    codec = ls.workspace.position_codec
    out: list[T.CodeAction] = []
    uri = from_fs_path(path) or path
    for d in params.context.diagnostics:
        if d.code != M.UNDECLARED_NAME.code:
            continue
        line, col = convert.from_client(lines, d.range.start, codec)
        m = re.match(r"'(.+)' is not declared$", d.message)
        if m is None:
            continue
        name = m.group(1)
        proc, cls, mod = index.scope(path, line)
        candidates = [n for n, s in names_in_scope(index, proc, cls, mod)
                      if not isinstance(s, (BuiltinClass, ModuleSym))]
        close = difflib.get_close_matches(name, candidates, n=2, cutoff=0.8)
        if len(close) == 1 or (close and difflib.SequenceMatcher(None, name.lower(), close[0].lower()).ratio() >
                               difflib.SequenceMatcher(None, name.lower(), close[1].lower()).ratio() + 0.1):
            out.append(T.CodeAction(title=f"Change '{name}' to '{close[0]}'", kind=T.CodeActionKind.QuickFix,
                                    diagnostics=[d], is_preferred=True,
                                    edit=T.WorkspaceEdit(changes={uri: [T.TextEdit(range=d.range, new_text=close[0])]})))
        dim = _missing_dim(index, path, line, col, name, proc)
        if dim is not None:
            at, indent, typ = dim
            text = f"{indent}Dim {name} As {typ}\n"
            pos = T.Position(line=at - 1, character=0)
            out.append(T.CodeAction(title=f"Declare 'Dim {name} As {typ}'", kind=T.CodeActionKind.QuickFix,
                                    diagnostics=[d],
                                    edit=T.WorkspaceEdit(changes={uri: [T.TextEdit(range=T.Range(pos, pos),
                                                                                   new_text=text)]})))
    return out


def _missing_dim(index: Index, path: str, line: int, col: int, name: str,
                 proc: ProcSym | None) -> tuple[int, str, str] | None:
    """Where to declare an undeclared ``name`` assigned at ``line:col`` (the first line of its
    procedure's body), with its indentation and the type its assigned value has."""
    if proc is None or not isinstance(proc.decl, A.ProcDecl):
        return None
    unit = index.units.get(path)
    if unit is None:
        return None
    model = index.model
    typ: t.GplType | None = None
    stack: list[A.Node] = [proc.decl.body]
    while stack and typ is None:
        node = stack.pop()
        target = value = None
        if isinstance(node, A.Assign):
            target, value = node.target, node.value
        elif isinstance(node, A.For):
            target, value = node.var, node.start
        if isinstance(target, A.Name) and target.name.lower() == name.lower() and target.span.line == line \
                and target.span.col == col:
            typ = model.type_of(value) if value is not None else None
        stack.extend(node.children())
    if typ is None or typ in (t.ERROR, t.VOID, t.ANY):
        return None
    body = proc.decl.body.statements
    first = body[0].span.line if body else proc.decl.span.line + 1
    rows = convert.lines_of(index.texts.get(path, ""))
    row = rows[first - 1] if body and first - 1 < len(rows) else ""
    indent = row[:len(row) - len(row.lstrip())] if body else " " * (proc.decl.span.col + 3)
    return first, indent, str(typ)


__all__ = ["Index", "Occ", "Refused", "code_actions", "completion", "definition", "document_symbols", "highlight",
           "hover", "index_of", "prepare_rename", "references", "rename", "signature_help", "workspace_symbols"]
