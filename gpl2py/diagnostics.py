"""Diagnostics: what every layer reports instead of raising.

A :class:`Diagnostic` is ``path:line:col: error GPLnnnn: message`` plus an optional caret excerpt.
Layers never raise on bad input; they add to a :class:`DiagnosticSink` and carry on, so one run
reports every problem.  The codes and their wording live in :mod:`gpl2py.messages`.
"""

from __future__ import annotations

import json
import os
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Iterable, Iterator, Protocol, Sequence

from gpl2py.messages import INTERNAL_ERROR, Message, Severity  # (Severity lives with the messages)
from gpl2py.source import Position, SourceFile, Span


@dataclass(frozen=True, slots=True)
class Diagnostic:
    severity: Severity
    code: str
    message: str
    span: Span | None = None

    @property
    def position(self) -> Position | None:
        return self.span.start if self.span is not None else None

    def header(self, colour: bool = False) -> str:
        """``file:line:col: severity GPLnnnn: message`` on one line: a file name or a name quoted
        in the message cannot break it (docs/security.md), their line breaks and other control
        characters are shown as escapes.  ``colour``: the position bold, the severity and code in
        its colour (ANSI escapes, added around the escaped text)."""
        where = f"{one_line(self.span.file)}:{self.span.line}:{self.span.col}:" if self.span is not None else ""
        what = f"{self.severity.value} {self.code}"
        if colour:
            where = f"{_BOLD}{where}{_RESET}" if where else ""
            what = f"{_COLOURS[self.severity]}{what}{_RESET}"
        return f"{where} {what}: {one_line(self.message)}" if where else f"{what}: {one_line(self.message)}"

    def render(self, source: SourceFile | None = None, colour: bool = False) -> str:
        """The header line, followed by the source line and a caret when the text is known.

        A line longer than :data:`EXCERPT` characters is shown as a window of that many around
        the column, its cut ends marked ``...``: a line can be a whole file (a 7 MB string literal
        was 14.7 MB of output, and the caret under it as much again)."""
        text = self.header(colour)
        if source is None or self.span is None:
            return text
        line = source.line_text(self.span.line)
        if not line:
            return text
        col = max(self.span.col, 1)
        if self.span.end_line == self.span.line and self.span.end_col > col:
            width = self.span.end_col - col
        else:
            width = 1
        shown, col = excerpt(line, col)
        shown = shown.expandtabs(1)  # tabs count as one column, as in Position
        if not shown.isprintable():  # a control character (a form feed, a bidi override) shows as '?'
            shown = "".join(ch if ch.isprintable() else "?" for ch in shown)
        width = max(1, min(width, len(shown) - col + 1))
        caret = "^" * width
        if colour:
            caret = f"{_COLOURS[self.severity]}{caret}{_RESET}"
        return f"{text}\n    {shown}\n    {' ' * (col - 1)}{caret}"

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


#: The longest source line a diagnostic shows whole; a longer one is shown as a window of this
#: many characters around the column (:func:`excerpt`).  Real code's lines are shorter (the
#: corpus's longest is 113), so its diagnostics show their lines whole.
EXCERPT = 200
#: How many characters of a long line the window shows before the column.
EXCERPT_BEFORE = 60
_CUT = "..."


def excerpt(line: str, col: int) -> tuple[str, int]:
    """``line`` and the 1-based column ``col`` in it, or, for a line over :data:`EXCERPT`
    characters, the window of it a diagnostic shows: :data:`EXCERPT` characters from
    :data:`EXCERPT_BEFORE` before the column (fewer at the line's end), a cut end marked with
    ``...``, and where the column falls in that text."""
    if len(line) <= EXCERPT:
        return line, col
    start = max(0, min(col - 1 - EXCERPT_BEFORE, len(line) - EXCERPT))
    end = start + EXCERPT
    head = _CUT if start > 0 else ""
    tail = _CUT if end < len(line) else ""
    return f"{head}{line[start:end]}{tail}", col - start + len(head)


_BOLD, _RESET = "\x1b[1m", "\x1b[0m"
_COLOURS = {Severity.ERROR: "\x1b[1;31m", Severity.WARNING: "\x1b[1;33m", Severity.NOTE: "\x1b[1;36m"}


def plural(n: int, word: str) -> str:
    """``n word`` or ``n words``: the one plural rule of every summary line (cli and run)."""
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


class InternalError(Exception):
    """A gap in gpl2py met at one node of the input (a kind of node or meaning a pass has no rule
    for): reported as GPL9000 at that node's position, never as ``None`` in the output or a
    statement silently dropped (``gpl2py.gpl.lower``'s visitors raise it)."""

    def __init__(self, span: Span | None, detail: str) -> None:
        super().__init__(detail)
        self.span = span


def internal_error_span(exc: BaseException) -> Span | None:
    """Where an unexpected exception happened in the input, when the pass that raised it knew."""
    return exc.span if isinstance(exc, InternalError) else None


@contextmanager
def contained(sink: DiagnosticSink, where: Span | None) -> Iterator[None]:
    """Run one part of a pass -- one file's parse, one module's analysis or lowering, a whole
    translation -- so that an unexpected exception in it (a bug in gpl2py) is internal error
    GPL9000 at ``where`` (or where the pass said it failed), and the caller goes on with the next
    part: a bug met in one file never hides the diagnostics of the others.  ``GPL2PY_TRACEBACK=1``
    lets the exception through instead, for a gpl2py developer (and the fuzz tests)."""
    try:
        yield
    except Exception as exc:
        if os.environ.get("GPL2PY_TRACEBACK"):
            raise
        sink.report(INTERNAL_ERROR, internal_error_span(exc) or where, detail=f"{type(exc).__name__}: {exc}")


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


class DiagnosticFilter(Protocol):
    """What a sink keeps (``gpl2py.selection.Selection``: --select, --ignore, ``gpl2py: ignore``)."""

    def __call__(self, diag: Diagnostic) -> bool: ...

    def fingerprint(self) -> list[object]: ...

    def add_sources(self, sources: Sequence[SourceFile], sink: DiagnosticSink) -> None: ...


class DiagnosticSink:
    """Collects diagnostics in the order they are reported.

    With a ``filter`` (``gpl2py.selection.Selection``), a diagnostic it does not keep is dropped
    as it arrives, so every later question (errors? how many warnings?) sees the filtered set.
    The errors it drops are kept aside (:attr:`ignored_errors`): an ignored error still means that
    the input has no meaning there, which the translation must know (it raises the controller's
    error at that line, ``gpl2py.gpl.lower``) though the user asked not to hear of it.
    """

    def __init__(self, filter: DiagnosticFilter | None = None) -> None:
        self._items: list[Diagnostic] = []
        self.filter = filter
        #: errors the filter dropped, in the order they were reported
        self.ignored_errors: list[Diagnostic] = []

    def child(self) -> DiagnosticSink:
        """An empty sink with the same filter (a pipeline stage that decides on its own errors)."""
        return DiagnosticSink(self.filter)

    def report(self, message: Message, span: Span | None, **args: object) -> Diagnostic:
        """Report ``message`` (a registry entry) formatted with ``args`` at ``span``."""
        diag = Diagnostic(message.severity, message.code, message.format(**args), span)
        self.add(diag)
        return diag

    def add(self, diag: Diagnostic) -> None:
        if self.filter is None or self.filter(diag):
            self._items.append(diag)
        elif diag.severity is Severity.ERROR:
            self.ignored_errors.append(diag)

    def extend(self, diags: Iterable[Diagnostic]) -> None:
        if self.filter is None:
            self._items.extend(diags)
        else:
            for d in diags:
                self.add(d)

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

    def found_errors(self) -> bool:
        """Errors reported, kept or ignored: whether some input has no meaning (not whether the
        run failed, which :meth:`has_errors` answers)."""
        return bool(self.ignored_errors) or self.has_errors()

    def sorted(self) -> list[Diagnostic]:
        """Diagnostics ordered by file, line and column (stable for equal positions)."""

        def key(d: Diagnostic) -> tuple[str, int, int]:
            if d.span is None:
                return ("", 0, 0)
            return (d.span.file, d.span.line, d.span.col)

        return sorted(self._items, key=key)

    def to_json(self) -> str:
        return json.dumps([d.to_json() for d in self.sorted()], indent=2)
