"""TMscript text -> tokens (spec §1.1-§1.4).

Statements end at the end of a line (a trailing ``\\`` joins the next one, manual L1351-L1377);
``//`` and ``/* */`` are comments (L1196-L1224); strings have no backslash escapes, ``""`` is a
quote (L580-L600); numbers are decimal, ``0x``/``0b`` integers or decimals with an exponent
(L498-L512).  A newline inside ``( )`` or ``[ ]`` does not end the statement (multi-line
argument lists in the manual's examples).  Errors are diagnostics; the lexer
never raises on input.

Comments are no tokens: when the caller asks for them they are collected apart, in order, as
:class:`Comment` (the parser attaches them to statements, the lowering carries them into the
Python), one per source line, so a ``/* */`` over three lines is three ``#`` lines each mapped
to its own line.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import Span, make_span
from gpl2py.tmscript import messages as M

KEYWORDS = frozenset({
    "define", "main", "closestop", "errorstop", "if", "else", "switch", "case", "default", "for",
    "while", "do", "break", "continue", "return", "void",
    "byte", "int", "float", "double", "bool", "string",
})
PRIMITIVE_TYPES = ("byte", "int", "float", "double", "bool", "string")
#: Longest first: the lexer takes the longest operator that matches.
OPERATORS = sorted("""<<= >>= ++ -- += -= *= /= %= &= ^= |= << >> <= >= == != && || + - * / % < > = ! ~ & ^ | ? :
( ) [ ] { } , ; .""".split(), key=len, reverse=True)

_OPERATOR = re.compile("|".join(re.escape(op) for op in OPERATORS))
_WORD = re.compile(r"[A-Za-z0-9_]+")


@dataclass(slots=True)
class Token:
    """``kind``: ``num`` (``value`` int or float), ``str`` (``value`` the text), ``id``, ``kw``,
    ``op``, ``nl`` (end of a statement line) or ``eof``."""

    kind: str
    text: str
    span: Span
    value: object = None

    def is_op(self, text: str) -> bool:
        return self.kind == "op" and self.text == text

    def is_kw(self, text: str) -> bool:
        return self.kind == "kw" and self.text == text


@dataclass(slots=True, frozen=True)
class Comment:
    """A ``//`` comment, or one line of a ``/* */`` comment: its text without the ``//``, ``/*``
    or ``*/``, and where it is (the Python writer's Comment).  ``cont``: a line after the first
    of a ``/* */`` comment (it stays with the line before it)."""

    span: Span
    text: str
    cont: bool = False
    directive: bool = False


def describe(tok: Token) -> str:
    """A token as a message names it."""
    if tok.kind == "eof":
        return "the end of the script"
    if tok.kind == "nl":
        return "the end of the line"
    return f"'{tok.text}'"


def tokenize(text: str, file: str, sink: DiagnosticSink, first_line: int = 1,
             comments: list[Comment] | None = None) -> list[Token]:
    """The tokens of ``text``; positions in ``file`` from line ``first_line``.  Its comments are
    appended to ``comments`` when it is given."""
    toks: list[Token] = []
    i, n = 0, len(text)
    line, col0 = first_line, 0  # col0: index of the current line's first character
    depth = 0  # open ( [ {: a newline inside does not end the statement
    if text.startswith("\ufeff"):
        i = col0 = 1

    def span(start: int, sline: int, scol0: int) -> Span:
        return make_span(file, sline, start - scol0 + 1, line, i - col0 + 1)

    while i < n:
        c = text[i]
        if c == "\r" or c == "\n":
            if c == "\r" and text.startswith("\r\n", i):
                i += 1
            if depth == 0 and toks and toks[-1].kind != "nl":
                toks.append(Token("nl", "\n", make_span(file, line, i - col0 + 1, line, i - col0 + 2)))
            i += 1
            line, col0 = line + 1, i
            continue
        if c in " \t\f\v\u00a0":
            i += 1
            continue
        if c == "\\":  # continuation: the next line is part of this one
            j = i + 1
            while j < n and text[j] in " \t":
                j += 1
            if j >= n or text[j] in "\r\n":
                if j < n and text.startswith("\r\n", j):
                    j += 1
                i = j + 1
                line, col0 = line + 1, i
                continue
        if text.startswith("//", i):
            start = i
            while i < n and text[i] not in "\r\n":
                i += 1
            if comments is not None:
                comments.append(Comment(span(start, line, col0), text[start + 2:i]))
            continue
        if text.startswith("/*", i):
            sline, scol0, start = line, col0, i
            end = text.find("*/", i + 2)
            if end < 0:
                i = n
                sink.report(M.TM_UNTERMINATED_COMMENT, make_span(file, sline, start - scol0 + 1, sline, start - scol0 + 3))
                break
            piece = i + 2  # (where the text of the comment's current line starts)
            k = i
            while k < end:
                if text[k] == "\n" or text[k] == "\r":
                    if comments is not None:
                        _block_line(comments, text, file, (line, col0), (start, scol0), piece, k, k)
                    if text.startswith("\r\n", k):
                        k += 1
                    line, col0 = line + 1, k + 1
                    piece = k + 1
                k += 1
            i = end + 2
            if comments is not None:
                _block_line(comments, text, file, (line, col0), (start, scol0), piece, end, i)
            continue
        start, sline, scol0 = i, line, col0
        if c == '"':
            i += 1
            parts: list[str] = []
            closed = False
            while i < n and text[i] not in "\r\n":
                if text[i] == '"':
                    if text.startswith('""', i):
                        parts.append('"')
                        i += 2
                        continue
                    i += 1
                    closed = True
                    break
                parts.append(text[i])
                i += 1
            if not closed:
                sink.report(M.TM_UNTERMINATED_STRING, span(start, sline, scol0))
            toks.append(Token("str", text[start:i], span(start, sline, scol0), "".join(parts)))
            continue
        if c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit()):
            i = _number_end(text, i)
            raw = text[start:i]
            value = _number_value(raw)
            if value is None:
                sink.report(M.TM_BAD_NUMBER, span(start, sline, scol0), text=raw)
                value = 0
            toks.append(Token("num", raw, span(start, sline, scol0), value))
            continue
        if c.isascii() and (c.isalpha() or c == "_"):  # identifiers are ASCII (L467-L470)
            m = _WORD.match(text, i)
            assert m is not None
            i = m.end()
            word = text[start:i]
            toks.append(Token("kw" if word in KEYWORDS else "id", word, span(start, sline, scol0)))
            continue
        m = _OPERATOR.match(text, i)
        if m is not None:
            op = m.group()
            i += len(op)
            if op in "([":
                depth += 1
            elif op in ")]" and depth:
                depth -= 1
            toks.append(Token("op", op, span(start, sline, scol0)))
        else:
            i += 1
            sink.report(M.TM_INVALID_CHAR, span(start, sline, scol0), char=repr(c))
    if toks and toks[-1].kind != "nl":
        toks.append(Token("nl", "\n", make_span(file, line, i - col0 + 1, line, i - col0 + 1)))
    toks.append(Token("eof", "", make_span(file, line, i - col0 + 1, line, i - col0 + 1)))
    return toks


def _block_line(comments: list[Comment], text: str, file: str, at: tuple[int, int], opener: tuple[int, int],
                piece: int, stop: int, end: int) -> None:
    """One line of the ``/* */`` comment whose ``/*`` is at ``opener`` (its index, and the index
    where its line starts): ``text[piece:stop]``, on the line ``at`` (its number, and the index
    where it starts), which ends at index ``end`` (past the ``*/`` on the last line).  A line
    after the first loses up to as many leading blanks as the ``/*`` had columns before it: the
    lines keep their alignment under the Python's own indentation."""
    line, col0 = at
    start, first = opener[0], piece == opener[0] + 2
    body = text[piece:stop]
    if not first:
        lead = len(body) - len(body.lstrip(" \t"))
        body = body[min(lead, opener[0] - opener[1]):]
        start = col0
    comments.append(Comment(make_span(file, line, start - col0 + 1, line, end - col0 + 1), body, cont=not first))


def _number_end(text: str, i: int) -> int:
    n = len(text)
    if text[i] == "0" and i + 1 < n and text[i + 1] in "xXbB":
        i += 2
        while i < n and (text[i].isalnum() or text[i] == "_"):
            i += 1
        return i
    while i < n and (text[i].isdigit() or text[i] == "."):
        i += 1
    if i < n and text[i] in "eE" and (i + 1 < n and (text[i + 1].isdigit() or
                                                     (text[i + 1] in "+-" and i + 2 < n and text[i + 2].isdigit()))):
        i += 2
        while i < n and text[i].isdigit():
            i += 1
    while i < n and (text[i].isalnum() or text[i] == "_"):  # (a malformed tail, reported whole)
        i += 1
    return i


def _number_value(raw: str) -> int | float | None:
    """The value of a number literal (``int`` for integer forms, ``float`` otherwise)."""
    low = raw.lower()
    try:
        if low.startswith("0x"):
            return int(low[2:], 16)
        if low.startswith("0b"):
            return int(low[2:], 2)
        if any(ch in low for ch in ".e"):
            return float(low)
        return int(low, 10)
    except ValueError:
        return None
