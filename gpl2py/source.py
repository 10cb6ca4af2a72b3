"""Source positions and source files: the one place that knows what a "file:line:col" is.

Every token, AST node and diagnostic carries a :class:`Position` (start) and usually a :class:`Span`.
Lines and columns are 1-based, columns count characters (tabs count as one), as editors expect.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

#: What ends a physical line: exactly the lexer's line breaks (spec §1).  ``str.splitlines`` would
#: also split at form feeds, U+0085 and U+2028 and so number lines differently from every Position.
LINE_BREAK = re.compile(r"\r\n|\n|\r")


@dataclass(frozen=True, slots=True)
class Position:
    """A point in a source file; ``str()`` gives ``file:line:col``."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


@dataclass(frozen=True, slots=True)
class Span:
    """A half-open range ``[start, end)`` within one file."""

    start: Position
    end_line: int
    end_col: int

    @property
    def file(self) -> str:
        return self.start.file

    @property
    def line(self) -> int:
        return self.start.line

    @property
    def col(self) -> int:
        return self.start.col

    def __str__(self) -> str:
        return str(self.start)

    def to(self, other: Span) -> Span:
        """The span from the start of ``self`` to the end of ``other``."""
        return Span(self.start, other.end_line, other.end_col)


@dataclass(slots=True)
class SourceFile:
    """The text of one GPL source file, with the name used in diagnostics."""

    path: str
    text: str
    _lines: list[str] | None = field(default=None, repr=False)

    def line_text(self, line: int) -> str:
        """Physical line ``line`` (1-based) without its terminator, or ``""`` if out of range.

        Lines are counted as the lexer counts them (:data:`LINE_BREAK`), and a byte-order mark at
        the start is not part of line 1 (the lexer skips it), so excerpts match Positions.
        """
        if self._lines is None:
            self._lines = LINE_BREAK.split(self.text.removeprefix("\ufeff"))
        if 1 <= line <= len(self._lines):
            return self._lines[line - 1]
        return ""
