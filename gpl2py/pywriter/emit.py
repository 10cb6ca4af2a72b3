"""The line writer every lowering step emits into.

PEP 8 layout comes by construction: a line is an indentation level plus text, indentation is four
spaces, comments get ``# `` and two spaces before an inline comment, and the module writer puts two
blank lines around top-level definitions.  GPL comments are often longer than PEP 8's line: a long
comment line is re-flowed at word boundaries into several ``#`` lines, and a trailing comment that
would push its statement past the limit moves onto its own line(s) just above the statement.  Each line remembers the GPL line it came from, which
becomes the source map (``pywriter/sourcemap.py``).

Why text and not libcst nodes: generating through libcst's node tree and its code generator costs
far more than the whole rest of the pipeline (the transpile-speed target is ≤ 10x CPython's own
``compile()`` of the output); the structure below gives the same guarantees (consistent indentation,
comment placement, no hand-concatenated blocks) and the tests parse every generated module with
libcst and ``compile()`` to prove it is valid Python.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

from gpl2py.pywriter.text import escape
from gpl2py.pywriter.wrap import LIMIT, wrap
from gpl2py.source import Span


class Comment(Protocol):
    """A source comment as any front end's syntax tree holds it (GPL's ``ast.Comment`` is one):
    the writer needs its text, its line, and whether it is a kept directive (``#Region``)."""

    @property
    def span(self) -> Span: ...

    @property
    def text(self) -> str: ...

    @property
    def directive(self) -> bool: ...


@dataclass(slots=True)
class Line:
    """One logical line; ``comment`` is its trailing comment (``# ...``), kept apart from the code
    so that rendering can move it above the statement when the two do not fit on one line."""

    indent: int
    text: str
    gpl_line: int = 0
    comment: str = ""

    def attach(self, comment: str) -> None:
        """Add a trailing comment (a second one joins the first)."""
        self.comment = f"{self.comment}  {comment}" if self.comment else comment


def comment_text(c: Comment) -> str:
    """A source comment as a Python comment (GPL ``' note`` -> ``# note``; ``#Region`` kept after ``# ``).

    The text passes the input-text gate (:mod:`gpl2py.pywriter.text`): nothing in it can end the line."""
    text = escape(c.text.rstrip(), "comment")
    if c.directive:
        return "# " + text
    if not text:
        return "#"
    if text.startswith(" "):
        return "#" + text
    return "# " + text


#: What CPython compiles (docs/security.md, "Nesting"): a line indented at most MAX_INDENT levels
#: (its tokenizer stops at 100), and at most MAX_BLOCKS loops and ``try`` parts around any
#: statement of one function (CO_MAXBLOCKS).  tests/lower/test_nesting_limits.py checks both
#: against the running interpreter.
MAX_INDENT = 99
MAX_BLOCKS = 20

#: The blocks CPython's compiler counts for the body of each construct the lowering emits: a loop
#: body 1; a ``try`` body 1 (2 when the statement has both ``except`` and ``finally``); an
#: ``except ... as`` handler 2 (its name is cleaned up; 3 inside a ``finally``); a ``finally``
#: body 1; a ``with`` body 1.
BLOCKS = {"loop": 1, "try": 1, "try+finally": 2, "except": 2, "except+finally": 3, "finally": 1, "with": 1}


@dataclass(frozen=True, slots=True)
class Nesting:
    """What :meth:`Writer.begin_statement` remembers while one source statement is written: the
    deepest nesting reached before it, and whether the statement itself starts where CPython still
    compiles (if not, a statement around it is the one to blame)."""

    outer_level: int
    outer_blocks: int
    starts_inside: bool


@dataclass
class Writer:
    """Accumulates lines at the current indentation.

    It also keeps the nesting Python will see: :attr:`blocks` (loops and ``try`` parts open
    around the current line, as ``indent(blocks=...)`` declares them) and the deepest
    indentation and block count reached (:attr:`peak_level`, :attr:`peak_blocks`), so the
    lowering can refuse what CPython would not compile.  ``base`` is the indentation the text
    will get when it is placed in its module (a method's body sits inside its classes)."""

    lines: list[Line] = field(default_factory=list)
    level: int = 0
    gpl_line: int = 0
    base: int = 0
    blocks: int = 0
    peak_level: int = 0
    peak_blocks: int = 0
    _opened: list[int] = field(default_factory=list)
    def_at: int | None = None  # the index of the ``def`` line of a procedure's Writer

    def line(self, text: str, gpl_line: int | None = None) -> Line:
        ln = Line(self.level, text, self.gpl_line if gpl_line is None else gpl_line)
        self.lines.append(ln)
        level = self.level
        if text[:1] == " ":  # a line written with its own indentation ("    flag = False")
            level += (len(text) - len(text.lstrip(" "))) // 4
        if level > self.peak_level:
            self.peak_level = level
        return ln

    def deepest(self) -> tuple[int, int]:
        """The deepest absolute indentation and block count reached so far."""
        return self.base + self.peak_level, self.peak_blocks

    def fits_python(self) -> bool:
        """Whether everything written so far nests within what CPython compiles."""
        level, blocks = self.deepest()
        return level <= MAX_INDENT and blocks <= MAX_BLOCKS

    def begin_statement(self) -> Nesting:
        """Start measuring the nesting of one source statement (its lines and its blocks').  Each
        front end's statement lowering calls this before a statement and :meth:`too_deep` after
        it, so that the innermost statement whose Python would nest deeper than CPython compiles
        gets the error, once, wherever the limits are crossed (docs/security.md, "Nesting")."""
        outer = Nesting(self.peak_level, self.peak_blocks, False)
        self.peak_level, self.peak_blocks = self.level, self.blocks
        return Nesting(outer.outer_level, outer.outer_blocks, self.fits_python())

    def too_deep(self, begun: Nesting, blocks_are: str = "loop blocks of one program") -> str | None:
        """After the statement: why its Python does not compile when it is the innermost statement
        that does not fit ("its code would be ..."; ``blocks_are`` names the blocks in the source
        language's words), else None."""
        if not begun.starts_inside or self.fits_python():
            return None
        level, blocks = self.deepest()
        if level > MAX_INDENT:
            return f"its code would be indented {level} levels and Python allows {MAX_INDENT}"
        return f"its code would be inside {blocks} {blocks_are} and Python allows {MAX_BLOCKS}"

    def discard_since(self, start: int) -> None:
        """Drop the lines written since ``start`` (a statement that did not fit, replaced by what
        raises its error): the nesting is measured afresh from here."""
        del self.lines[start:]
        self.peak_level, self.peak_blocks = self.level, self.blocks

    def end_statement(self, begun: Nesting) -> None:
        """The statement is written: the deepest nesting so far includes the one before it."""
        self.peak_level = max(begun.outer_level, self.peak_level)
        self.peak_blocks = max(begun.outer_blocks, self.peak_blocks)

    def comments(self, comments: list[Comment]) -> None:
        for c in comments:
            self.line(comment_text(c), c.span.line)

    def trailing(self, c: Comment | None, start: int) -> None:
        """Attach ``c`` to the first line emitted since index ``start`` (or emit it alone)."""
        if c is None:
            return
        for ln in self.lines[start:]:
            if not ln.text.startswith("#"):
                ln.attach(comment_text(c))
                return
        self.line(comment_text(c), c.span.line)

    def indent(self, blocks: int = 0) -> None:
        """One level deeper; ``blocks``: the blocks CPython counts for this body (:data:`BLOCKS`)."""
        self.level += 1
        self._opened.append(blocks)
        self.blocks += blocks
        if self.blocks > self.peak_blocks:
            self.peak_blocks = self.blocks

    def dedent(self) -> None:
        self.level -= 1
        self.blocks -= self._opened.pop() if self._opened else 0

    def mark(self) -> int:
        return len(self.lines)

    def ensure_body(self, start: int) -> None:
        """A Python block needs a statement: add ``pass`` when only comments were emitted."""
        if self.only_comments(start):
            self.line("pass")

    def only_comments(self, start: int) -> bool:
        """Whether every line written since ``start`` is a comment (or there is none)."""
        return all(ln.text.startswith("#") for ln in self.lines[start:])

    def extend(self, other: Writer, extra_indent: int = 0) -> None:
        for ln in other.lines:
            self.lines.append(Line(ln.indent + extra_indent, ln.text, ln.gpl_line, ln.comment))

    def blank(self, count: int = 1) -> None:
        for _ in range(count):
            self.lines.append(Line(0, "", 0))

    def render(self) -> tuple[str, list[int]]:
        """The source text and, per Python line (1-based index - 1), the GPL line (0 = none)."""
        out: list[str] = []
        gmap: list[int] = []
        for ln in self.lines:
            if not ln.text:
                out.append("")
                gmap.append(ln.gpl_line)
                continue
            pad = "    " * ln.indent
            comment = inline_comment(ln.comment) if ln.comment else ""
            if comment and 4 * ln.indent + len(ln.text) + 2 + len(comment) > LIMIT:
                for text in wrap_comment(ln.indent, ln.comment):  # too long together: comment above
                    out.append(pad + text)
                    gmap.append(ln.gpl_line)
                comment = ""
            if ln.text.startswith("#"):
                pieces = [(ln.indent, text) for text in wrap_comment(ln.indent, ln.text)]
            else:
                pieces = wrap(ln.indent, ln.text)
            for i, (indent, text) in enumerate(pieces):
                if i == 0 and comment:
                    text = f"{text}  {comment}"
                out.append("    " * indent + text)
                gmap.append(ln.gpl_line)
        # no trailing blank lines; exactly one newline at the end
        while out and out[-1] == "":
            out.pop()
            gmap.pop()
        return "\n".join(out) + "\n", gmap


def inline_comment(comment: str) -> str:
    """``comment`` as it stands after code: PEP 8 wants exactly ``# `` before an inline comment's
    text (pycodestyle E262), so the spaces or tabs a GPL comment starts with (``x = 1   '   note``,
    kept to align columns) are dropped there; a comment on its own line keeps them."""
    if not comment.startswith("#"):
        return comment
    body = comment[1:].lstrip(" \t\xa0")
    return "# " + body if body else "#"


def wrap_comment(indent: int, text: str, limit: int = LIMIT) -> list[str]:
    """A ``#`` comment re-flowed at word boundaries to fit ``limit`` at ``indent``; every piece
    keeps the original's prefix (``#`` and the spaces after it).  A single word longer than the
    line (a URL) stays whole.  A piece never ends in spaces (PEP 8 W291), though a GPL comment may
    hold runs of them (aligned columns) that a break lands in."""
    if 4 * indent + len(text) <= limit:
        return [text]
    body = text.lstrip("#")
    prefix = text[: len(text) - len(body)]
    stripped = body.lstrip(" ")
    prefix += body[: len(body) - len(stripped)] or " "
    room = limit - 4 * indent - len(prefix)
    out: list[str] = []
    cur = ""
    for word in stripped.split(" "):
        if cur and len(cur) + 1 + len(word) > room:
            out.append((prefix + cur).rstrip())
            cur = word
        else:
            cur = f"{cur} {word}" if cur else word
    if cur or not out:
        out.append((prefix + cur).rstrip())
    return out
