"""V+ source text -> tokens, line by line (spec §1.2-1.4).

Each physical line ends in a :attr:`Kind.NEWLINE` token; ``;`` starts a comment (kept apart, in
:attr:`Lexed.comments`, for the generated Python); a ``.`` word at the start of a line is a
:attr:`Kind.DIRECTIVE` (``.PROGRAM``, ``.END``, ``.LOCATIONS`` ...).  A byte-order mark at the start
and Ctrl-Z end-of-file marks are skipped (User's Guide L534-535, L7211).  Nothing raises: a bad
character or an unclosed string is a diagnostic at its exact column, and lexing goes on.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import LINE_BREAK, SourceFile, make_span
from gpl2py.vplus import messages as M
from gpl2py.vplus.syntax.tokens import Comment, Kind, Token

_DIGITS = frozenset("0123456789")
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9._]*")
_DECIMAL = re.compile(r"(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
_OPS2 = ("==", "<=", "=<", ">=", "=>", "<>")
_OPS1 = frozenset("<>=+-*/:,()[]")
_BASED = {"B": (2, re.compile(r"[01]+")), "H": (16, re.compile(r"[0-9A-Fa-f]+"))}
_OCTAL = re.compile(r"[0-7]+")


@dataclass
class Lexed:
    """A file's tokens and its comments, in order."""

    tokens: list[Token] = field(default_factory=list)
    comments: list[Comment] = field(default_factory=list)


def lex(src: SourceFile, sink: DiagnosticSink) -> Lexed:
    """Every token of ``src`` (the last one :attr:`Kind.EOF`)."""
    out = Lexed()
    text = src.text.removeprefix("\ufeff")
    lines = LINE_BREAK.split(text)
    path = src.path
    for n, line in enumerate(lines, start=1):
        _lex_line(path, n, line, out, sink)
    last = len(lines)
    out.tokens.append(Token(Kind.EOF, "", make_span(path, last, len(lines[-1]) + 1, last, len(lines[-1]) + 1)))
    return out


def _lex_line(path: str, n: int, line: str, out: Lexed, sink: DiagnosticSink) -> None:
    toks = out.tokens
    i, end = 0, len(line)
    first = True
    spaced = True

    def span(a: int, b: int):  # type: ignore[no-untyped-def]
        return make_span(path, n, a + 1, n, b + 1)

    while i < end:
        c = line[i]
        if c in " \t\f\x1a":  # blanks; Ctrl-Z marks the end of a DOS file
            i += 1
            spaced = True
            continue
        if c == ";":
            out.comments.append(Comment(span(i, end), line[i + 1:]))
            break
        if c == "." and first and i + 1 < end and line[i + 1].isascii() and line[i + 1].isalpha():
            m = _NAME.match(line, i + 1)
            assert m is not None
            toks.append(Token(Kind.DIRECTIVE, m.group(), span(i, m.end()), spaced=spaced))
            i = m.end()
        elif c.isascii() and c.isalpha():
            m = _NAME.match(line, i)
            assert m is not None
            toks.append(Token(Kind.NAME, m.group(), span(i, m.end()), spaced=spaced))
            i = m.end()
        elif c in "$#%" and i + 1 < end and line[i + 1].isascii() and line[i + 1].isalpha():
            m = _NAME.match(line, i + 1)
            assert m is not None
            toks.append(Token(Kind.NAME, m.group(), span(i, m.end()), sigil=c, spaced=spaced))
            i = m.end()
        elif c in _DIGITS or (c == "." and i + 1 < end and line[i + 1] in _DIGITS):  # (not "²": isdigit is true of it)
            m = _DECIMAL.match(line, i)
            assert m is not None
            j = m.end()
            if j < end and (line[j].isalpha() or line[j] in "._"):  # 12abc, 1.2.3
                k = j
                while k < end and (line[k].isalnum() or line[k] in "._"):
                    k += 1
                sink.report(M.BAD_NUMBER, span(i, k), text=line[i:k])
                toks.append(Token(Kind.NUMBER, line[i:k], span(i, k), 0.0, spaced=spaced))
                i = k
            else:
                value = float(m.group())
                if math.isinf(value):  # past the double range (User's Guide L3887-3889)
                    sink.report(M.BAD_NUMBER, span(i, j), text=m.group())
                    value = 0.0
                toks.append(Token(Kind.NUMBER, m.group(), span(i, j), value, spaced=spaced))
                i = j
        elif c == "^":
            i = _based(path, n, line, i, toks, sink, spaced)
        elif c == "'":
            if i + 1 < end and 32 <= ord(line[i + 1]) <= 126:
                toks.append(Token(Kind.NUMBER, line[i:i + 2], span(i, i + 2), float(ord(line[i + 1])), spaced=spaced))
                i += 2
            else:
                sink.report(M.BAD_ASCII_CONSTANT, span(i, i + 1))
                i += 1
        elif c == '"':
            j = line.find('"', i + 1)
            if j < 0:
                sink.report(M.UNTERMINATED_STRING, span(i, end))
                toks.append(Token(Kind.STRING, line[i + 1:], span(i, end), spaced=spaced))
                i = end
            else:
                toks.append(Token(Kind.STRING, line[i + 1:j], span(i, j + 1), spaced=spaced))
                i = j + 1
        elif line.startswith(_OPS2, i) and line[i:i + 2] in _OPS2:
            toks.append(Token(Kind.OP, line[i:i + 2], span(i, i + 2), spaced=spaced))
            i += 2
        elif c in _OPS1:
            toks.append(Token(Kind.OP, c, span(i, i + 1), spaced=spaced))
            i += 1
        else:
            sink.report(M.BAD_CHARACTER, span(i, i + 1), char=repr(c))
            i += 1
        first = False
        spaced = False
    toks.append(Token(Kind.NEWLINE, "", span(end, end)))


def _based(path: str, n: int, line: str, i: int, toks: list[Token], sink: DiagnosticSink, spaced: bool) -> int:
    """``^B1001``, ``^H23FF``, ``^346`` (octal), ``^D...`` (a double constant): the index after it."""
    j = i + 1
    letter = line[j].upper() if j < len(line) else ""
    if letter in _BASED:
        base, digits = _BASED[letter]
        m = digits.match(line, j + 1)
    elif letter == "D":
        base, m = 10, _DECIMAL.match(line, j + 1)
    else:
        base, m = 8, _OCTAL.match(line, j)
    stop = m.end() if m else (j + 1 if letter in _BASED or letter == "D" else j)
    while stop < len(line) and line[stop].isalnum():
        stop += 1
        m = None
    text = line[i:stop]
    sp = make_span(path, n, i + 1, n, stop + 1)
    if m is None or m.end() != stop:
        sink.report(M.BAD_NUMBER, sp, text=text or "^")
        value = 0.0
    else:
        try:
            value = float(m.group()) if base == 10 else float(int(m.group(), base))
        except (OverflowError, ValueError):
            value = math.inf
        if math.isinf(value):
            sink.report(M.BAD_NUMBER, sp, text=text)
            value = 0.0
    toks.append(Token(Kind.NUMBER, text, sp, value, spaced=spaced))
    return max(stop, i + 1)
