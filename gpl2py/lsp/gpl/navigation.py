"""Hover, go to definition, find references and document highlight: look-ups in the index."""

from __future__ import annotations

from typing import Any

from lsprotocol import types as T

from gpl2py.lsp import convert
from gpl2py.lsp.gpl.describe import describe, explain
from gpl2py.lsp.gpl.index import at_cursor, in_order, location, occ_range
from gpl2py.lsp.projects import ProjectState


def hover(ls: Any, state: ProjectState, path: str, params: T.HoverParams) -> T.Hover | None:
    found = at_cursor(ls, state, path, params)
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
                   range=occ_range(ls, lines, o) if o is not None else None)


def definition(ls: Any, state: ProjectState, path: str, params: Any) -> list[T.Location] | None:
    found = at_cursor(ls, state, path, params)
    if found is None or found[2] is None:
        return None
    index, _, o = found
    decl = index.declaration(o.sym)
    return [location(ls, state, decl)] if decl is not None else None


def references(ls: Any, state: ProjectState, path: str, params: T.ReferenceParams) -> list[T.Location] | None:
    found = at_cursor(ls, state, path, params)
    if found is None or found[2] is None:
        return None
    index, _, o = found
    keep = params.context.include_declaration
    return [location(ls, state, x) for x in in_order(index.occurrences(o.sym)) if keep or not x.decl]


def highlight(ls: Any, state: ProjectState, path: str, params: Any) -> list[T.DocumentHighlight] | None:
    found = at_cursor(ls, state, path, params)
    if found is None or found[2] is None:
        return None
    index, lines, o = found
    return [T.DocumentHighlight(range=occ_range(ls, lines, x),
                                kind=T.DocumentHighlightKind.Write if x.decl else T.DocumentHighlightKind.Read)
            for x in in_order(index.occurrences(o.sym)) if x.path == path]
