"""Diagnostics: what every layer reports instead of raising.

A :class:`Diagnostic` is ``path:line:col: error GPLnnnn: message`` plus an optional caret excerpt.
Layers never raise on bad input; they add to a :class:`DiagnosticSink` and carry on, so one run
reports every problem.  The codes and their wording live in :mod:`gpl2py.messages`.
"""

from __future__ import annotations

import enum
import json
from dataclasses import dataclass
from typing import Iterable, Iterator

from gpl2py.messages import Message
from gpl2py.source import Position, SourceFile, Span


class Severity(enum.Enum):
    ERROR = "error"
    WARNING = "warning"
    NOTE = "note"


@dataclass(frozen=True, slots=True)
class Diagnostic:
    severity: Severity
    code: str
    message: str
    span: Span | None = None

    @property
    def position(self) -> Position | None:
        return self.span.start if self.span is not None else None

    def header(self) -> str:
        """``file:line:col: severity GPLnnnn: message`` on one line: a file name or a name quoted
        in the message cannot break it (docs/security.md), their line breaks and other control
        characters are shown as escapes."""
        where = f"{one_line(self.span.file)}:{self.span.line}:{self.span.col}: " if self.span is not None else ""
        return f"{where}{self.severity.value} {self.code}: {one_line(self.message)}"

    def render(self, source: SourceFile | None = None) -> str:
        """The header line, followed by the source line and a caret when the text is known."""
        text = self.header()
        if source is None or self.span is None:
            return text
        line = source.line_text(self.span.line)
        if not line:
            return text
        shown = line.expandtabs(1)  # tabs count as one column, as in Position
        if not shown.isprintable():  # a control character (a form feed, a bidi override) shows as '?'
            shown = "".join(ch if ch.isprintable() else "?" for ch in shown)
        col = max(self.span.col, 1)
        if self.span.end_line == self.span.line and self.span.end_col > col:
            width = self.span.end_col - col
        else:
            width = 1
        width = max(1, min(width, len(shown) - col + 1))
        return f"{text}\n    {shown}\n    {' ' * (col - 1)}{'^' * width}"

    def to_json(self) -> dict[str, object]:
        pos = self.span.start if self.span else None
        return {
            "severity": self.severity.value,
            "code": self.code,
            "message": self.message,
            "file": pos.file if pos else None,
            "line": pos.line if pos else None,
            "column": pos.col if pos else None,
        }


def one_line(text: str) -> str:
    """``text`` with every character Python does not call printable -- line breaks, other
    controls, bidirectional overrides, other separators than the space -- as ``\\xNN``,
    ``\\uNNNN`` or ``\\UNNNNNNNN``, so that it shows as one line, in its order."""
    if text.isprintable():
        return text
    return "".join(ch if ch.isprintable() else _escape(ch) for ch in text)


def _escape(ch: str) -> str:
    o = ord(ch)
    return f"\\x{o:02x}" if o < 256 else f"\\u{o:04x}" if o < 0x10000 else f"\\U{o:08x}"


class DiagnosticSink:
    """Collects diagnostics in the order they are reported."""

    def __init__(self) -> None:
        self._items: list[Diagnostic] = []

    def report(self, message: Message, span: Span | None, **args: object) -> Diagnostic:
        """Report ``message`` (a registry entry) formatted with ``args`` at ``span``."""
        diag = Diagnostic(message.severity, message.code, message.format(**args), span)
        self._items.append(diag)
        return diag

    def add(self, diag: Diagnostic) -> None:
        self._items.append(diag)

    def extend(self, diags: Iterable[Diagnostic]) -> None:
        self._items.extend(diags)

    def __iter__(self) -> Iterator[Diagnostic]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self._items if d.severity is Severity.ERROR]

    @property
    def warnings(self) -> list[Diagnostic]:
        return [d for d in self._items if d.severity is Severity.WARNING]

    def has_errors(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self._items)

    def sorted(self) -> list[Diagnostic]:
        """Diagnostics ordered by file, line and column (stable for equal positions)."""

        def key(d: Diagnostic) -> tuple[str, int, int]:
            if d.span is None:
                return ("", 0, 0)
            return (d.span.file, d.span.line, d.span.col)

        return sorted(self._items, key=key)

    def to_json(self) -> str:
        return json.dumps([d.to_json() for d in self.sorted()], indent=2)
