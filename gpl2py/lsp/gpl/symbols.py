"""Document symbols (the outline of a file) and workspace symbols (by name, over the symbol tables)."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from lsprotocol import types as T
from pygls.uris import from_fs_path

from gpl2py.gpl.semantics.check import Model
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
from gpl2py.lsp.gpl.describe import proc_signature
from gpl2py.lsp.gpl.index import Occ, index_of, loaded_index, occ_range
from gpl2py.lsp.projects import ProjectState


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
    ready = loaded_index(ls, state, path)
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
                                selection_range=occ_range(ls, lines, o), detail=_detail(o.sym), children=[])
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
    return occ_range(ls, lines, o)


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
    return T.Location(uri=from_fs_path(o.path) or o.path, range=occ_range(ls, lines, o))
