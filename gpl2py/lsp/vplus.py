"""V+'s features for the language server: the outline (its programs and data sections), read off
the files the last check parsed (``gpl2py.vplus.pipeline.MODULES_KEY``).  Diagnostics come through
the door like every language's; the other features (hover, definition ...) are GPL's only so far."""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

from lsprotocol import types as T

from gpl2py.lsp import outline
from gpl2py.lsp.projects import ProjectState
from gpl2py.vplus.pipeline import MODULES_KEY


def _entries(state: ProjectState, path: str) -> Iterator[outline.Entry]:
    modules = state.memo.get(MODULES_KEY)
    for mod in modules if isinstance(modules, list) else ():
        if os.path.abspath(mod.path) != path:
            continue
        for prog in mod.programs:
            params = ", ".join(p.var.sigil + p.var.name + ("[]" if p.var.whole else "") for p in prog.params)
            yield outline.Entry(prog.name, T.SymbolKind.Function, prog.span, prog.name_span, f"({params})")
        for data in mod.data:
            yield outline.Entry(f".{data.kind}", T.SymbolKind.Namespace, data.span, data.span)


def document_symbols(ls: Any, state: ProjectState, path: str, params: Any) -> list[T.DocumentSymbol] | None:
    return outline.document_symbols(ls, state, path, _entries)


def workspace_symbols(ls: Any, state: ProjectState, query: str) -> list[T.WorkspaceSymbol]:
    return outline.workspace_symbols(ls, state, query, _entries)


__all__ = ["document_symbols", "workspace_symbols"]
