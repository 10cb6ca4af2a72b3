"""The GPL lexer: source text -> tokens, plain tuples ``(kind, text, value, span)``.

It is the only layer that knows characters (spec §1).  One compiled master regular expression with
named groups scans the whole file (``re.finditer``); each match is one token plus the blanks before
it, so there is no per-character Python loop, and the group that matched (``m.lastindex``) says
what it is.  A token is a plain tuple and so is its span (:data:`~gpl2py.gpl.syntax.tokens.KIND`): the
lexer makes one per token and a plain tuple is the cheapest object Python builds.
:func:`tokenize` lists them as named :class:`~gpl2py.gpl.syntax.tokens.Token` records.  The token
stream is *logical-line* shaped:

* ``NEWLINE`` ends every logical line that holds at least one token.  Blank lines produce nothing.
* A line continuation (`` _`` at the end of a physical line, spec §1.3) produces nothing; the next
  physical line simply continues the statement.
* ``'`` comments become ``COMMENT`` tokens (value: the text after the apostrophe) right before the
  ``NEWLINE`` of their line, so the parser can attach them to statements (leading/trailing comments).
* Lines whose first non-blank character is ``#`` (``#Region "x"``, ``#End Region``) are ignored by GPL
  (spec §1.4); they become ``DIRECTIVE`` tokens so the parser can keep them as comments.
  ``#If``/``#Else``/``#ElseIf``/``#End If``/``#Const`` lines get a warning (AMB-27): GPL has no
  conditional compilation.

Decisions documented here (the spec leaves them open):

* **Comment after a continuation** (`` _ ' note``): VB forbids it and the spec recommends an error, but
  real exported GPL code contains it.  We accept it with warning GPL1005 and keep the comment: it is
  emitted just before the ``NEWLINE`` of the logical line, i.e. it becomes part of the statement's
  trailing comment.  The warning is given once per logical line, at its first such comment: vendor
  code annotates long continued expressions line by line, and a hundred identical warnings for one
  statement would bury everything else.
* A ``_`` followed only by blanks or a comment ends a continued line whenever the character before
  it cannot be part of a name: a blank (spec §1.3), but also ``,_`` ``)_`` ``&_`` ``"a"_``.  The
  manual asks for a blank before the ``_``; the vendor's own code glues it to a comma
  (``lcc.XYZ(a, b,_``, docs/design/real-code.md) and the controller compiles it.  ``x_`` is an
  identifier; a ``_`` glued to a number (``1_``) stays an error (GPL1006 and GPL1001).
* ``&H``/``&O`` literals are lexed greedily (spec §1.9), so ``String &HEAD`` is ``String`` followed by
  the hex literal ``&HEAD``.  Values are 32-bit two's complement (``&HFFFFFFFF`` = -1, AMB-36).
* String literals over 128 characters get a warning (AMB-35), non-ASCII characters in them an error.
* A letter directly after a number (``725L``, ``1.5F``) is reported: GPL has no type suffixes.
* A run of consecutive invalid characters (for example a non-ASCII word) is one diagnostic.
* A byte-order mark at the very start of the file is skipped silently (columns count after it).
* Ctrl-Z (U+001A) characters at the very end of the file are skipped silently: old DOS editors end
  text files with this end-of-file marker, and the project loader already accepts it as text.  A
  Ctrl-Z anywhere else is an invalid character like any other control character.
"""

from __future__ import annotations

import gc
import re
from sys import intern
from contextlib import contextmanager
from typing import Iterator

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import SourceFile, Span
from gpl2py.gpl.syntax.tokens import KEYWORDS, OPERATORS, RawToken, Token, TokenKind

# A string literal (S) is '"', runs of other characters and '""' pairs, '"'.  Its repetitions are
# possessive ('*+': nothing to back into), so the engine keeps no state per character and a literal
# of any length is matched in constant memory; '"(?:[^"]|"")*"' kept ~150 bytes a character (2 GB
# for a 7 MB literal, issue 20).  When the quotes after an opening quote do not pair up to a
# closing one, the string is unterminated (US) from that opening quote.
_MASTER = re.compile(
    r"""[ \t\f\v]*(?:
     (?P<W>[A-Za-z][A-Za-z0-9_]*|_+[A-Za-z0-9][A-Za-z0-9_]*)
    |(?P<N>(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)
    |(?P<H>&[Hh][0-9A-Fa-f]+|&[Oo][0-7]+)
    |(?P<O><<=|>>=|<>|<=|>=|<<|>>|[\^*/\\+\-&]=|[-+*/\\^&=<>(),.:])
    |(?P<NL>\r\n|\n|\r)
    |(?P<S>"[^"\r\n]*+(?:""[^"\r\n]*+)*+")
    |(?P<C>'[^\r\n]*)
    |(?P<CONT>_[ \t\f\v]*(?P<CC>'[^\r\n]*)?(?:\r\n|\n|\r|\Z))
    |(?P<US>"[^\r\n]*)
    |(?P<D>\#[^\r\n]*)
    |(?P<X>[^\x00-\x7f]+|.)
    )""",
    re.VERBOSE,
)

# characters that can be part of a name: a '_' right after one of these is not a continuation
_NAME_CHAR = re.compile(r"[A-Za-z0-9_]").fullmatch
_WORD_RUN = re.compile(r"\w*").match
_CONDITIONAL = re.compile(r"#\s*(if|else|elseif|end\s+if|const)\b", re.IGNORECASE)
_MAX_NAME = 128
_MAX_STRING = 128
#: How many spellings the scan remembers (``_tokenize``'s ``words``) before it starts afresh: the
#: few hundred a file uses thousands of times are soon back, and a file of tens of thousands of
#: names used once (``Dim v0, v1, ...``) does not keep a record for each while it is read (it was
#: 15 times that source: docs/security.md, "Input size")
_WORDS_KEPT = 4096

_K = TokenKind

_new = tuple.__new__


def _span(path: str, line: int, col: int, end_col: int) -> Span:
    """The :class:`Span` of a one-line range: for diagnostics (tokens keep plain tuples)."""
    return _new(Span, (path, line, col, line, end_col))


def tokenize(source: SourceFile, sink: DiagnosticSink) -> list[Token]:
    """Split ``source`` into tokens; problems go to ``sink``, never raised.

    The result always ends with an ``EOF`` token, and every non-empty logical line ends with
    ``NEWLINE`` (also the last one, even without a final line break).  These are the parser's
    tokens (:func:`token_chunks`) with named fields, for tools and tests that list tokens.
    """
    toks: list[Token] = []
    of = Token.of
    with gc_paused():
        for chunk in token_chunks(source, sink):
            toks.extend(map(of, chunk))
    return toks


#: Tokens per list :func:`token_chunks` hands out.  The parser holds one or two at a time, so a
#: file's tokens never all live at once (they are about half of the memory a parse needs at its
#: peak otherwise: docs/security.md, "Input size").  Two chunks of 4,096 were 1.6 MB, 30 times a
#: 50 kB source; 1,024 parse as fast (dense code, same sitting).
CHUNK = 1024


def token_chunks(source: SourceFile, sink: DiagnosticSink, chunk: int = CHUNK) -> Iterator[list[RawToken]]:
    """The tokens of ``source`` as the parser reads them, plain tuples ``(kind, text, value, span)``
    (:data:`~gpl2py.gpl.syntax.tokens.KIND`), in consecutive lists of ``chunk`` tokens, a few more at
    most (a line continued with a comment adds its comments), wherever they fall in a line: a file of
    one line of a million terms is handed out in pieces too.  Diagnostics are reported as the tokens
    are made."""
    return _tokenize(source, sink, chunk)


@contextmanager
def gc_paused() -> Iterator[None]:
    """Pause the cyclic garbage collector while building tokens or AST nodes.

    Tokens, spans and nodes form no reference cycles, but allocating hundreds of thousands of them
    triggers generational collections that re-scan everything built so far: with the collector
    running, lexing a 20,000-line file takes about twice as long.  Reference counting still frees
    everything as usual; the collector is re-enabled (if it was enabled) on exit, also on error.
    """
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()


def _tokenize(source: SourceFile, sink: DiagnosticSink, chunk: int) -> Iterator[list[RawToken]]:
    """The scan: one ``finditer`` over the file, dispatched on the group that matched.

    Every token is the plain tuple ``(kind, text, value, (path, line, col, line, end_col))``; a
    token never spans lines.  A diagnostic gets a :class:`Span` (:func:`_span`)."""
    text = source.text
    path = source.path
    toks: list[RawToken] = []
    append = toks.append
    kw = KEYWORDS.get
    # spelling -> (interned spelling, kind, length, too long for a name): one probe per word instead
    # of intern, lower, a keyword probe and len (a file uses a few hundred words thousands of times)
    words: dict[str, tuple[str, TokenKind, int, bool]] = {}
    words_get = words.get
    ops = OPERATORS
    IDENT = _K.IDENT
    NEWLINE = _K.NEWLINE
    line = 1
    begin = 0  # where the scan starts
    has_tokens = False  # does the current logical line hold a token yet?
    deferred: list[RawToken] = []  # comments after ' _' continuations, emitted before NEWLINE

    if text.startswith("\ufeff"):  # a UTF-8 byte-order mark from a Windows editor: not source text
        begin = 1
    stop = len(text)
    while stop > begin and text[stop - 1] == "\x1a":  # DOS end-of-file marker(s): not source
        stop -= 1
    base = begin - 1  # a column is the offset minus this: the offset where its line starts, less one
    for m in _MASTER.finditer(text, begin, stop):
        if len(toks) >= chunk:  # (tested per token, not per line: one line can be the whole file)
            yield toks
            toks = []
            append = toks.append
        g = m.lastindex
        if g == 1:  # word
            t = m.group(1)
            seen = words_get(t)
            if seen is None:
                t = intern(t)  # one string per name, however often it is used
                kind = kw(t.lower(), IDENT)
                if len(words) >= _WORDS_KEPT:  # (many distinct names, once each: a long Dim)
                    words.clear()
                seen = words[t] = (t, kind, len(t), kind is IDENT and len(t) > _MAX_NAME)
            t, kind, n, too_long = seen
            col = m.start(1) - base
            if too_long:
                sink.report(M.LEX_LONG_IDENTIFIER, _span(path, line, col, col + n), name=t[:20], length=n)
            append((kind, t, None, (path, line, col, line, col + n)))
            has_tokens = True
        elif g == 4:  # operator / punctuation
            t = m.group(4)
            col = m.start(4) - base
            append((ops[t], t, None, (path, line, col, line, col + len(t))))
            has_tokens = True
        elif g == 5:  # line break
            if has_tokens:
                col = m.start(5) - base
                if deferred:
                    toks.extend(deferred)
                    deferred.clear()
                append((NEWLINE, "", None, (path, line, col, line, col)))
                has_tokens = False
            line += 1
            base = m.end() - 1
        elif g == 2:  # number
            start = m.start(g)
            t = intern(m.group(g))  # a literal keeps its text: one string per spelling, like names
            col = start - base
            span = _span(path, line, col, col + len(t))
            if "." in t or "e" in t or "E" in t:
                value: object = float(t)
                if value == float("inf"):
                    sink.report(M.LEX_LITERAL_RANGE, span, text=_shown_number(t))
                    value = 0.0
                append((_K.REAL, t, value, span))
            else:
                append((_K.INTEGER, t, int(t) if len(t) < _LONG_DECIMAL else _long_decimal(t, span, sink), span))
            has_tokens = True
            _check_suffix(text, m.end(g), t, span, sink)
        elif g == 6:  # S
            start = m.start(g)
            t = m.group(g)
            col = start - base
            span = _span(path, line, col, col + len(t))
            value = t[1:-1].replace('""', '"')
            _check_string(value, span, sink)
            append((_K.STRING, t, value, span))
            has_tokens = True
        elif g == 7:  # C
            if deferred:  # keep source order: continuation comments come first
                toks.extend(deferred)
                deferred.clear()
            start = m.start(g)
            t = m.group(g)
            col = start - base
            append((_K.COMMENT, t, t[1:], _span(path, line, col, col + len(t))))
            has_tokens = True
        elif g == 3:  # H
            start = m.start(g)
            t = m.group(g)
            col = start - base
            span = _span(path, line, col, col + len(t))
            raw = int(t[2:], 16 if t[1] in "Hh" else 8)
            if raw > 0xFFFFFFFF:
                sink.report(M.LEX_LITERAL_RANGE, span, text=_shown_number(t))
                raw = 0
            elif raw >= 0x80000000:
                raw -= 0x100000000
            append((_K.INTEGER, t, raw, span))
            has_tokens = True
            _check_suffix(text, m.end(g), t, span, sink)
        elif g == 8:  # CONT
            start = m.start(g)
            col = start - base
            if start > 0 and _NAME_CHAR(text[start - 1]):
                # '_' glued to a number ('1_') is not a continuation: it cannot be one token's end
                span = _span(path, line, col, col + 1)
                sink.report(M.LEX_INVALID_CHAR, span, char="'_'")
                append((_K.ERROR, "_", None, span))
                has_tokens = True
            cc = m.group("CC")
            if cc is not None:
                ccol = m.start("CC") - base
                cspan = _span(path, line, ccol, ccol + len(cc))
                if not deferred:  # one warning per statement, however many lines it comments
                    sink.report(M.LEX_COMMENT_AFTER_CONTINUATION, cspan)
                deferred.append((_K.COMMENT, cc, cc[1:], cspan))
            line += 1
            base = m.end() - 1
        elif g == 11:  # D
            start = m.start(g)
            t = m.group(g)
            col = start - base
            span = _span(path, line, col, col + len(t))
            if has_tokens:
                sink.report(M.LEX_MISPLACED_HASH, span)
                append((_K.ERROR, "#", None, _span(path, line, col, col + 1)))
            else:
                d = t.rstrip()
                if _CONDITIONAL.match(d):
                    sink.report(M.LEX_CONDITIONAL_DIRECTIVE, span, directive=d.split("'")[0][:30])
                append((_K.DIRECTIVE, t, d, span))
            has_tokens = True
        elif g == 10:  # US
            start = m.start(g)
            t = m.group(g)
            col = start - base
            span = _span(path, line, col, col + len(t))
            sink.report(M.LEX_UNTERMINATED_STRING, span)
            value = t[1:].replace('""', '"')
            if not value.isascii():
                _check_string(value, span, sink)
            append((_K.STRING, t, value, span))
            has_tokens = True
        else:  # "X": a character (or a run of non-ASCII characters) no token can start with
            start = m.start(g)
            t = m.group(g)
            col = start - base
            span = _span(path, line, col, col + len(t))
            sink.report(M.LEX_INVALID_CHAR, span, char=_show(t))
            append((_K.ERROR, t, None, span))
            has_tokens = True

    col = stop - base
    if has_tokens or deferred:
        toks.extend(deferred)
        append((NEWLINE, "", None, (path, line, col, line, col)))
    append((_K.EOF, "", None, (path, line, col, line, col)))
    yield toks


#: Decimal integer literals this long may pass the Double range (1.8E+308 has 309 digits); shorter
#: ones are read with ``int`` directly.
_LONG_DECIMAL = 309


def _long_decimal(t: str, span: Span, sink: DiagnosticSink) -> int:
    """The value of a long decimal literal, or 0 after GPL1007 when it is beyond the Double range.

    A decimal literal past the Integer range is a Double (semantics), so one past the Double range
    is out of range like ``1E+400``.  Deciding that before ``int(t)`` also keeps Python's limit on
    converting strings of over 4,300 digits (a ValueError) away from the input; leading zeros
    count for nothing."""
    digits = t.lstrip("0")
    if len(digits) <= _LONG_DECIMAL:
        value = int(digits or "0")
        try:
            float(value)
            return value
        except OverflowError:
            pass
    sink.report(M.LEX_LITERAL_RANGE, span, text=_shown_number(t))
    return 0


def _shown_number(t: str) -> str:
    """A numeric literal as a message quotes it: a very long one is cut, with its length."""
    return t if len(t) <= 40 else f"{t[:20]}... ({len(t)} characters)"


def _show(chars: str) -> str:
    """A readable rendering of offending characters: ``'é' (U+00E9)``."""
    if len(chars) == 1:
        return f"{chars!r} (U+{ord(chars):04X})"
    shown = chars if len(chars) <= 20 else chars[:20] + "..."
    return f"{shown!r} (starting with U+{ord(chars[0]):04X})"


def _check_string(value: str, span: Span, sink: DiagnosticSink) -> None:
    if len(value) > _MAX_STRING:
        sink.report(M.LEX_LONG_STRING, span, length=len(value))
    if not value.isascii():
        bad = next(c for c in value if not c.isascii())
        sink.report(M.LEX_NON_ASCII_STRING, span, char=_show(bad))


def _check_suffix(text: str, end: int, number: str, span: Span, sink: DiagnosticSink) -> None:
    """Report ``725L``-style suffixes: a letter or ``_`` glued to the end of a number."""
    if end < len(text):
        c = text[end]
        if c.isalpha() or c == "_":
            stop = _WORD_RUN(text, end).end()  # (letters, digits, '_': isalnum() or '_', in C)
            sink.report(M.LEX_LITERAL_SUFFIX, span, suffix=text[end:stop], number=number)
