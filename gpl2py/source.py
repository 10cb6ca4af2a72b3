"""Source positions and source files: the one place that knows what a "file:line:col" is.

Every token, AST node and diagnostic carries a :class:`Position` (start) and usually a :class:`Span`.
Lines and columns are 1-based, columns count characters (tabs count as one), as editors expect.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from operator import itemgetter as _field

#: What ends a physical line: exactly the lexer's line breaks (spec §1).  ``str.splitlines`` would
#: also split at form feeds, U+0085 and U+2028 and so number lines differently from every Position.
LINE_BREAK = re.compile(r"\r\n|\n|\r")

_new = tuple.__new__


@dataclass(frozen=True, slots=True)
class Position:
    """A point in a source file; ``str()`` gives ``file:line:col``."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


class Span(tuple):  # type: ignore[type-arg]
    """A half-open range ``[start, end)`` within one file.

    Every token and AST node has one, so it keeps its five fields flat rather than a
    :class:`Position` plus two numbers: that saves a second object per node (docs/security.md,
    "Input size").  It is a tuple ``(file, line, col, end_line, end_col)`` read through named
    properties: immutable, compared and hashed by value in C, and built by one C call
    (:func:`make_span`), three times faster than filling five slots (the lexer makes one per
    token: benchmarks/parse_speed.py).  ``start`` builds the :class:`Position` on demand.
    """

    __slots__ = ()

    file: str = property(_field(0), doc="The file's name as diagnostics show it.")  # type: ignore[assignment]
    line: int = property(_field(1), doc="First line, 1-based.")  # type: ignore[assignment]
    col: int = property(_field(2), doc="First column, 1-based.")  # type: ignore[assignment]
    end_line: int = property(_field(3), doc="Last line.")  # type: ignore[assignment]
    end_col: int = property(_field(4), doc="Column just after the end.")  # type: ignore[assignment]

    def __new__(cls, start: Position, end_line: int, end_col: int) -> Span:
        return _new(cls, (start.file, start.line, start.col, end_line, end_col))

    @property
    def start(self) -> Position:
        return Position(self[0], self[1], self[2])

    def __repr__(self) -> str:
        return f"Span(start={self.start!r}, end_line={self[3]}, end_col={self[4]})"

    def __str__(self) -> str:
        return f"{self[0]}:{self[1]}:{self[2]}"

    def to(self, other: Span) -> Span:
        """The span from the start of ``self`` to the end of ``other``."""
        return _new(Span, (self[0], self[1], self[2], other[3], other[4]))

    def __reduce__(self) -> tuple[object, tuple[str, int, int, int, int]]:  # pickle, copy
        return make_span, tuple(self)  # type: ignore[return-value]


def make_span(file: str, line: int, col: int, end_line: int, end_col: int) -> Span:
    """``Span(Position(file, line, col), end_line, end_col)`` without building the Position."""
    return _new(Span, (file, line, col, end_line, end_col))


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
