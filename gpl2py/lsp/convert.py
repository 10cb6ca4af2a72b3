"""gpl2py's positions and diagnostics in the protocol's terms.

gpl2py counts lines and columns from 1, columns in characters (``gpl2py.source``); the protocol
counts from 0, columns in the code units the client and server agreed on (UTF-16 unless the client
offers another), so a column is converted with the line's text.  A diagnostic keeps its code, and
its ``codeDescription`` points at the code's entry in docs/diagnostics.md when the documentation is
installed beside the package (a checkout); the hover over a diagnostic shows ``gpl2py explain``'s
text for it wherever gpl2py runs (gpl2py.lsp.gpl).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from lsprotocol import types as T
from pygls.uris import from_fs_path
from pygls.workspace.position_codec import PositionCodec

from gpl2py.diagnostics import Diagnostic
from gpl2py.messages import Severity
from gpl2py.source import LINE_BREAK, Span

_SEVERITY = {Severity.ERROR: T.DiagnosticSeverity.Error, Severity.WARNING: T.DiagnosticSeverity.Warning,
             Severity.NOTE: T.DiagnosticSeverity.Information}


def lines_of(text: str) -> list[str]:
    """The physical lines as gpl2py numbers them (the lexer's line breaks, no byte-order mark)."""
    return LINE_BREAK.split(text.removeprefix("\ufeff"))


def position(lines: list[str], line: int, col: int, codec: PositionCodec) -> T.Position:
    """gpl2py's ``line:col`` (1-based, characters) as a protocol position."""
    text = lines[line - 1] if 0 < line <= len(lines) else ""
    return T.Position(line=max(line - 1, 0), character=codec.client_num_units(text[:max(col - 1, 0)]))


def span_range(span: Span, lines: list[str], codec: PositionCodec) -> T.Range:
    return T.Range(start=position(lines, span.line, span.col, codec),
                   end=position(lines, span.end_line, span.end_col, codec))


def from_client(lines: list[str], pos: T.Position, codec: PositionCodec) -> tuple[int, int]:
    """A protocol position as gpl2py's ``(line, col)``, 1-based, in characters."""
    text = lines[pos.line] if 0 <= pos.line < len(lines) else ""
    units = 0
    for i, ch in enumerate(text):
        if units >= pos.character:
            return pos.line + 1, i + 1
        units += codec.client_num_units(ch)
    return pos.line + 1, len(text) + 1


def diagnostic(d: Diagnostic, lines: list[str], codec: PositionCodec) -> T.Diagnostic:
    span = d.span
    rng = span_range(span, lines, codec) if span is not None else T.Range(T.Position(0, 0), T.Position(0, 0))
    href = _docs_href(d.code)
    return T.Diagnostic(range=rng, message=d.message, severity=_SEVERITY.get(d.severity), code=d.code,
                        source="gpl2py", code_description=T.CodeDescription(href=href) if href else None)


@lru_cache(maxsize=1)
def _docs() -> str | None:
    doc = Path(__file__).resolve().parents[2] / "docs" / "diagnostics.md"
    return from_fs_path(str(doc)) if doc.is_file() else None


def _docs_href(code: str) -> str | None:
    base = _docs()
    return f"{base}#{code.lower()}" if base else None


__all__ = ["diagnostic", "from_client", "lines_of", "position", "span_range"]
