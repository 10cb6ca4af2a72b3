"""The outline of a file and symbols by name for a language whose front end leaves only its parsed
files in the memo (V+, TMscript): a list of :class:`Entry` per file, made by the language's module
(``gpl2py/lsp/vplus.py``, ``gpl2py/lsp/tmscript.py``), answered here in the protocol's types."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from lsprotocol import types as T
from pygls.uris import from_fs_path

from gpl2py.lsp import convert
from gpl2py.lsp.projects import ProjectState
from gpl2py.source import Span


@dataclass(frozen=True)
class Entry:
    """One declaration of a file: its name, kind, extent and where its name is written."""

    name: str
    kind: T.SymbolKind
    span: Span
    name_span: Span
    detail: str | None = None


#: A language's entries: (project, absolute path of a file) -> the file's declarations.
Entries = Callable[[ProjectState, str], Iterable[Entry]]


def document_symbols(ls: Any, state: ProjectState, path: str, entries: Entries) -> list[T.DocumentSymbol] | None:
    if state.last is None or path not in state.last.files:
        return None
    lines = convert.lines_of(state.last.files[path])
    codec = ls.workspace.position_codec
    return [T.DocumentSymbol(name=e.name, kind=e.kind, range=convert.span_range(e.span, lines, codec),
                             selection_range=convert.span_range(e.name_span, lines, codec), detail=e.detail)
            for e in entries(state, path)]


def workspace_symbols(ls: Any, state: ProjectState, query: str, entries: Entries) -> list[T.WorkspaceSymbol]:
    if state.last is None:
        return []
    q = query.lower()
    codec = ls.workspace.position_codec
    out = []
    for path, text in state.last.files.items():
        lines = None
        for e in entries(state, path):
            if q in e.name.lower():
                lines = lines if lines is not None else convert.lines_of(text)
                out.append(T.WorkspaceSymbol(name=e.name, kind=e.kind, location=T.Location(
                    uri=from_fs_path(path) or path, range=convert.span_range(e.name_span, lines, codec))))
    return out


__all__ = ["Entries", "Entry", "document_symbols", "workspace_symbols"]
