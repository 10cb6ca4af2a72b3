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


class Span:
    """A half-open range ``[start, end)`` within one file.

    Every token and AST node holds one, so it keeps its five fields flat rather than a
    :class:`Position` plus two numbers: that saves a second object per node (about a fifth of
    the memory of a syntax tree, docs/security.md "Input size").  It is immutable and compares and
    hashes by value, like a frozen dataclass; ``start`` builds the :class:`Position` on demand.
    """

    __slots__ = ("file", "line", "col", "end_line", "end_col")

    file: str
    line: int
    col: int
    end_line: int
    end_col: int

    def __init__(self, start: Position, end_line: int, end_col: int) -> None:
        _set_file(self, start.file)
        _set_line(self, start.line)
        _set_col(self, start.col)
        _set_end_line(self, end_line)
        _set_end_col(self, end_col)

    @property
    def start(self) -> Position:
        return Position(self.file, self.line, self.col)

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"Span is immutable (cannot set {name!r})")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Span):
            return NotImplemented
        return (self.file, self.line, self.col, self.end_line, self.end_col) == \
            (other.file, other.line, other.col, other.end_line, other.end_col)

    def __hash__(self) -> int:
        return hash((self.file, self.line, self.col, self.end_line, self.end_col))

    def __repr__(self) -> str:
        return f"Span(start={self.start!r}, end_line={self.end_line}, end_col={self.end_col})"

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"

    def to(self, other: Span) -> Span:
        """The span from the start of ``self`` to the end of ``other``."""
        return make_span(self.file, self.line, self.col, other.end_line, other.end_col)

    def __reduce__(self) -> tuple[object, tuple[str, int, int, int, int]]:  # pickle, copy
        return make_span, (self.file, self.line, self.col, self.end_line, self.end_col)


# The slot descriptors: make_span (the lexer's hottest path) fills them without __init__'s call.
_new = object.__new__
_set_file = Span.file.__set__  # type: ignore[attr-defined]
_set_line = Span.line.__set__  # type: ignore[attr-defined]
_set_col = Span.col.__set__  # type: ignore[attr-defined]
_set_end_line = Span.end_line.__set__  # type: ignore[attr-defined]
_set_end_col = Span.end_col.__set__  # type: ignore[attr-defined]


def make_span(file: str, line: int, col: int, end_line: int, end_col: int) -> Span:
    """``Span(Position(file, line, col), end_line, end_col)`` without building the Position."""
    span = _new(Span)
    _set_file(span, file)
    _set_line(span, line)
    _set_col(span, col)
    _set_end_line(span, end_line)
    _set_end_col(span, end_col)
    return span


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
