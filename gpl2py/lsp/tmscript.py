"""TMscript's features for the language server: the outline (the script's sections -- ``define``,
``main``, ``closestop``, ``errorstop`` -- and its functions), read off the scripts the last check
parsed (``gpl2py.tmscript.pipeline.SCRIPTS_KEY``).  Diagnostics come through the door like every
language's; the other features are GPL's only so far."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from lsprotocol import types as T

from gpl2py.lsp import outline
from gpl2py.lsp.projects import ProjectState
from gpl2py.tmscript.pipeline import SCRIPTS_KEY
from gpl2py.tmscript.syntax import ast as A


def _entries(state: ProjectState, path: str) -> Iterator[outline.Entry]:
    scripts = state.memo.get(SCRIPTS_KEY)
    tree = scripts.get(path) if isinstance(scripts, dict) else None
    if not isinstance(tree, A.Script):
        return
    found: list[outline.Entry] = []
    for name, block in tree.sections.items():
        found.append(outline.Entry(name, T.SymbolKind.Namespace, block.span, block.span))
    for fn in tree.functions:
        params = ", ".join(f"{p.type}{'[]' if p.array else ''} {p.name}" for p in fn.params)
        found.append(outline.Entry(fn.name, T.SymbolKind.Function, fn.span, fn.span, f"{fn.ret} ({params})"))
    yield from sorted(found, key=lambda e: (e.span.line, e.span.col))


def document_symbols(ls: Any, state: ProjectState, path: str, params: Any) -> list[T.DocumentSymbol] | None:
    return outline.document_symbols(ls, state, path, _entries)


def workspace_symbols(ls: Any, state: ProjectState, query: str) -> list[T.WorkspaceSymbol]:
    return outline.workspace_symbols(ls, state, query, _entries)


__all__ = ["document_symbols", "workspace_symbols"]
