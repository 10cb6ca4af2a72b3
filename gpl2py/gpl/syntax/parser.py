"""The GPL parser: tokens -> :class:`~gpl2py.gpl.syntax.ast.SourceUnit` (hand-written recursive descent).

:func:`parse` never raises on bad input.  It reports diagnostics to the sink and recovers at
statement boundaries, so one run reports every error:

* Within a line, only the first error is reported; the rest of the logical line is skipped.
* Block statements always open their block even when their header line is broken, so the matching
  ``End …`` is still found and no cascade follows.
* A block ends at any line that closes a construct that is open *somewhere* on the stack of open
  constructs (``End If``, ``Next``, ``Loop``, ``Case``, ``Catch``, ``End Sub``, a new ``Sub`` …).
  If it is not the innermost construct's own end, that construct reports "not closed" once, at its
  opening line, and the enclosing construct carries on.  A closer that matches nothing open
  (``End If`` with no ``If``) is reported once and skipped.

Grammar decisions beyond the spec's EBNF (spec §3), each an extension that real code uses:

* ``Select Case x`` and ``Select x``; ``Case a To b`` and ``Case Is > x`` are accepted (VB forms).
* ``Else If c Then`` at the end of a line is read as ``ElseIf`` (warning GPL1118).
* Single-line ``If c Then stmt Else stmt`` (AMB-15); nested single-line Ifs are allowed.
* ``For Each v In xs`` is parsed into :class:`~gpl2py.gpl.syntax.ast.ForEach`.
* ``Catch ex As Exception`` is accepted (AMB-32); a bare ``Catch`` is an error (manual §10.1).
* ``Optional`` parameters with defaults are accepted; ``ParamArray`` is reported.
* ``Throw`` without an operand parses (``value=None``); semantics decides.
* ``Exit Property`` is accepted (AMB-34).
* ``Property Name() As T`` (an empty parameter list, the usual VB spelling) is accepted like
  ``Property Name As T``: the manual omits the parentheses, but they are optional on every other
  parameterless declaration (spec §3.3) and say nothing different here.  A non-empty list is reported.
* A ``Class`` at the top level of a file is accepted (AMB-1).
* ``ReDim Preserve`` is accepted: the manuals never mention it, but the vendor's own code uses it
  and the controller runs it (docs/design/real-code.md).
* ``Dim``/``Static``/``Const`` inside If/Select/For/While/Do/Try blocks are accepted: the manual
  (§3.2.6) allows declarations only at a procedure's outermost level, but real code declares in
  blocks and the controller compiles it; the variable has procedure scope (semantics).
* ``IsNot`` is parsed and reported as not supported in GPL (spec §15); VB statements (``GoSub``, ``With``, ``On Error``, ``Enum`` …) get a "not supported in GPL" diagnostic
  when they appear in statement or member position.  They remain usable as names otherwise.
* A line holding only ``:`` (a documentation ellipsis in the manuals) is an error, like any other
  use of ``:`` as a statement separator.
"""

from __future__ import annotations

import sys

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.messages import Message
from gpl2py.source import SourceFile, Span
from gpl2py.gpl.syntax import ast as A
from gpl2py.gpl.syntax.lexer import gc_paused, token_chunks
from gpl2py.gpl.syntax.tokens import COMPOUND_ASSIGN, KEYWORD_KINDS, KIND, SPAN, TEXT, VALUE, RawToken, TokenKind, describe

K = TokenKind
_new = tuple.__new__  # _new(Span, (file, line, col, end_line, end_col)): a Span in one C call


def _at(tok: RawToken) -> Span:
    """Where a diagnostic about ``tok`` points (a token keeps its span as a plain tuple)."""
    return _new(Span, tok[SPAN])


# precedence (higher binds tighter), spec §3.7
_P_XOR, _P_OR, _P_AND, _P_NOT, _P_REL, _P_SHIFT, _P_CONCAT = 1, 2, 3, 4, 5, 6, 7
_P_ADD, _P_MOD, _P_IDIV, _P_MUL, _P_UNARY, _P_POW = 8, 9, 10, 11, 12, 13

_BINOPS: dict[TokenKind, tuple[int, str]] = {
    K.XOR: (_P_XOR, "Xor"),
    K.OR: (_P_OR, "Or"),
    K.ORELSE: (_P_OR, "OrElse"),
    K.AND: (_P_AND, "And"),
    K.ANDALSO: (_P_AND, "AndAlso"),
    K.EQ: (_P_REL, "="),
    K.NE: (_P_REL, "<>"),
    K.LT: (_P_REL, "<"),
    K.GT: (_P_REL, ">"),
    K.LE: (_P_REL, "<="),
    K.GE: (_P_REL, ">="),
    K.IS: (_P_REL, "Is"),
    K.SHL: (_P_SHIFT, "<<"),
    K.SHR: (_P_SHIFT, ">>"),
    K.AMP: (_P_CONCAT, "&"),
    K.PLUS: (_P_ADD, "+"),
    K.MINUS: (_P_ADD, "-"),
    K.MOD: (_P_MOD, "Mod"),
    K.BACKSLASH: (_P_IDIV, "\\"),
    K.STAR: (_P_MUL, "*"),
    K.SLASH: (_P_MUL, "/"),
    K.CARET: (_P_POW, "^"),
}

_CASE_IS_OPS = {K.EQ: "=", K.NE: "<>", K.LT: "<", K.GT: ">", K.LE: "<=", K.GE: ">="}

# Closing lines: kind of the construct they close.  "END" needs the next token; "MOD" means a
# modifier that may start a declaration; "<decl>" closes any procedure, class or module.
_END_KINDS: dict[TokenKind, str] = {
    K.IF: "If",
    K.SUB: "Sub",
    K.FUNCTION: "Function",
    K.PROPERTY: "Property",
    K.GET: "Get",
    K.SET: "Set",
    K.CLASS: "Class",
    K.MODULE: "Module",
    K.SELECT: "Select",
    K.TRY: "Try",
    K.WHILE: "While",
}
_CLOSERS: dict[TokenKind, str] = {
    K.END: "END",
    K.ELSE: "If",
    K.ELSEIF: "If",
    K.CASE: "Select",
    K.CATCH: "Try",
    K.FINALLY: "Try",
    K.NEXT: "For",
    K.LOOP: "Do",
    K.SUB: "<decl>",
    K.FUNCTION: "<decl>",
    K.PROPERTY: "<decl>",
    K.CLASS: "<decl>",
    K.MODULE: "<decl>",
    K.DELEGATE: "<decl>",
    K.PUBLIC: "MOD",
    K.PRIVATE: "MOD",
    K.SHARED: "MOD",
}
_DECL_CONTAINERS = frozenset({"Sub", "Function", "Property", "Get", "Set", "Class", "Module"})
_PROC_KINDS = frozenset({"Sub", "Function"})
_DECL_WORDS = frozenset({K.SUB, K.FUNCTION, K.PROPERTY, K.CLASS, K.DELEGATE, K.MODULE})
_MODIFIER_KINDS = frozenset({K.PUBLIC, K.PRIVATE, K.SHARED})

_EXIT_KINDS = {
    K.SUB: "Sub",
    K.FUNCTION: "Function",
    K.PROPERTY: "Property",
    K.FOR: "For",
    K.DO: "Do",
    K.WHILE: "While",
    K.SELECT: "Select",
    K.TRY: "Try",
}

# VB words that are not GPL, recognised in statement position (not reserved: spec §1.8).
_UNSUPPORTED_STATEMENTS: dict[str, str] = {
    "gosub": "GoSub",
    "with": "With",
    "on": "On Error",
    "resume": "Resume",
    "erase": "Erase",
    "continue": "Continue",
    "option": "Option",
    "imports": "Imports",
    "stop": "Stop",
    "using": "Using",
    "synclock": "SyncLock",
    "enum": "Enum",
    "structure": "Structure",
    "interface": "Interface",
    "namespace": "Namespace",
    "event": "Event",
    "raiseevent": "RaiseEvent",
    "addhandler": "AddHandler",
    "removehandler": "RemoveHandler",
    "inherits": "Inherits",
    "implements": "Implements",
    "wend": "Wend",
    "rem": "REM comments",
    "let": "Let",
    "print": "Print",
    "mid": "Mid statement",
    "error": "Error statement",
    "yield": "Yield",
}
_UNSUPPORTED_HINTS: dict[str, str] = {
    "Wend": " (use 'End While')",
    "REM comments": " (start comments with ')",
    "On Error": " (use Try ... Catch)",
    "Resume": " (use Try ... Catch)",
    "GoSub": " (call a Sub instead)",
    "Continue": " (use GoTo a label before 'Next'/'Loop')",
}
_UNSUPPORTED_MODIFIERS: dict[str, str] = {
    "friend": "Friend",
    "protected": "Protected",
    "overrides": "Overrides",
    "overridable": "Overridable",
    "overloads": "Overloads",
    "readonly": "ReadOnly",
    "writeonly": "WriteOnly",
    "mustoverride": "MustOverride",
    "notoverridable": "NotOverridable",
    "mustinherit": "MustInherit",
    "notinheritable": "NotInheritable",
    "shadows": "Shadows",
    "partial": "Partial",
    "withevents": "WithEvents",
    "async": "Async",
    "iterator": "Iterator",
}
# Tokens that may follow a name used as a variable/procedure (so an unsupported VB word followed
# by one of these is just a name).
_NAME_FOLLOWERS = frozenset(
    {K.EQ, K.LPAREN, K.DOT, K.COLON, *COMPOUND_ASSIGN.keys()}
)
_EXPR_STARTS = frozenset(
    {K.IDENT, K.ME, K.INTEGER, K.REAL, K.STRING, K.TRUE, K.FALSE, K.NOTHING, K.NEW, K.ADDRESSOF, K.LPAREN}
)
_LAYOUT = frozenset({K.NEWLINE, K.COMMENT, K.EOF, K.DIRECTIVE})
_UNARY_KINDS = frozenset({K.MINUS, K.PLUS, K.NOT})
_STMT_END = frozenset({K.NEWLINE, K.COMMENT, K.EOF, K.ELSE})
_LINE_END = frozenset({K.NEWLINE, K.COMMENT, K.EOF})

# Nesting limits.  Each block level costs about six Python frames and each expression level about
# four; parse() makes sure the recursion limit covers both limits at once.
_MAX_EXPR_DEPTH = 150
_MAX_BLOCK_DEPTH = 100
_RECURSION_NEEDED = 4000


def parse(source: SourceFile, sink: DiagnosticSink) -> A.SourceUnit:
    """Parse one GPL file.  Never raises on bad input: problems are reported to ``sink``.

    Pathologically nested input is cut off with diagnostic GPL1117 at fixed depths; the Python
    recursion limit is raised (if lower) for the duration of the call so those depths are reachable.
    """
    limit = sys.getrecursionlimit()
    if limit < _RECURSION_NEEDED:
        sys.setrecursionlimit(_RECURSION_NEEDED)
    try:
        with gc_paused():
            return Parser(source, sink).parse_unit()
    finally:
        if limit < _RECURSION_NEEDED:
            sys.setrecursionlimit(limit)


def parse_expression(source: SourceFile, sink: DiagnosticSink) -> A.Expr:
    """Parse ``source`` as one expression (tests, REPL-style tools).  Trailing tokens are reported."""
    with gc_paused():
        p = Parser(source, sink)
        expr = p.expression()
    p.end_of_line(None)
    if p.kind is not K.EOF:
        p.error(M.PARSE_TRAILING_TOKENS, p.tok, found=describe(p.tok))
    return expr


def _chain(spine: A.Expr, depth: int, op: str, right: A.Expr) -> A.Chain:
    """The run of ``depth`` nested Binary nodes ``spine`` continued by ``op right``, as one
    :class:`~gpl2py.gpl.syntax.ast.Chain` (the run has reached ``CHAIN_MIN`` operators)."""
    nodes: list[A.Binary] = []
    for _ in range(depth):
        assert isinstance(spine, A.Binary)
        nodes.append(spine)
        spine = spine.left
    chain = A.Chain.of(spine)
    for node in reversed(nodes):
        chain.append(node.op, node.right)
    chain.append(op, right)
    return chain


class Parser:
    """Recursive-descent parser over the token list; see the module docstring for recovery rules."""

    def __init__(self, source: SourceFile, sink: DiagnosticSink) -> None:
        self.source = source
        self.sink = sink
        self.compact_dims = False  # a Dim was held compactly (:meth:`_compact`)
        # The tokens are a window onto the lexer's output (token_chunks): the current token, the
        # ones peeked at, and back to the last token that is not layout (for prev).  The
        # window slides in next(), so the file's tokens never all live at once.
        self._chunks = token_chunks(source, sink)
        self.toks: list[RawToken] = next(self._chunks)
        self.more = True  # the lexer has more chunks
        self.pos = 0
        self.last = len(self.toks) - 1
        # The current token, and its kind on its own: the parser tests the kind several times a
        # token, and an attribute of the parser is the cheapest thing to read (next() sets both).
        self.tok: RawToken = self.toks[0]
        self.kind: TokenKind = self.tok[KIND]
        self.failed = False  # an error was reported on the current logical line
        self.open: list[str] = []  # constructs whose end has not been seen, innermost last
        self.in_proc = False
        self.depth = 0  # expression nesting depth (recursion guard)
        self.aborted = False  # the block nesting limit was hit and the rest of the file skipped

    # ---------------------------------------------------------------------------------- tokens

    def next(self) -> RawToken:
        """Consume the current token (returned); the one after it becomes current."""
        tok = self.tok
        pos = self.pos
        if pos < self.last or (self.more and self._slide()):
            self.pos = pos = self.pos + 1  # (not pos + 1: _slide() moves pos back by what it drops)
            self.tok = cur = self.toks[pos]
            self.kind = cur[KIND]
        return tok

    def _slide(self) -> bool:
        """Move the window on by one chunk of tokens, keeping the current token and what
        :attr:`prev` may look back at; ``False`` when the lexer has nothing left."""
        chunk = next(self._chunks, None)
        if chunk is None:
            self.more = False
            return False
        toks = self.toks
        keep = self.pos
        while keep > 0 and toks[keep][KIND] in _LAYOUT:
            keep -= 1
        self.toks = toks[keep:] + chunk
        self.pos -= keep
        self.last = len(self.toks) - 1
        return True

    def _extend(self) -> bool:
        """Add the lexer's next chunk to the window (for a look far ahead)."""
        chunk = next(self._chunks, None)
        if chunk is None:
            self.more = False
            return False
        self.toks.extend(chunk)
        self.last = len(self.toks) - 1
        return True

    @property
    def prev(self) -> RawToken:
        """The last consumed token that is not a NEWLINE or COMMENT (where spans end)."""
        toks = self.toks
        i = self.pos - 1 if self.kind is not K.EOF or self.pos == 0 else self.pos
        while i > 0 and toks[i][KIND] in _LAYOUT:
            i -= 1
        return toks[max(i, 0)]

    def peek(self, offset: int = 1) -> RawToken:
        i = self.pos + offset
        while i > self.last and self.more and self._extend():
            pass
        return self.toks[i] if i <= self.last else self.toks[self.last]

    def span_from(self, start: RawToken | Span) -> Span:
        """From the start of ``start`` (a token or a span) to the end of the last token consumed."""
        s = start if isinstance(start, Span) else start[SPAN]
        end = self.prev[SPAN]
        if end[3] < s[1] or (end[3] == s[1] and end[4] < s[2]):  # (nothing consumed since)
            return _new(Span, s)
        return _new(Span, (s[0], s[1], s[2], end[3], end[4]))

    def error(self, message: Message, where: RawToken | Span, /, **args: object) -> None:
        """Report a line-local error: only the first one per logical line is reported."""
        if self.failed:
            return
        self.failed = True
        if not isinstance(where, Span):  # a token
            if where[KIND] is K.ERROR:
                return  # the lexer already reported this character
            where = _at(where)
        self.sink.report(message, where, **args)

    def expect(self, kind: TokenKind, what: str | None = None) -> RawToken | None:
        if self.kind is kind:
            return self.next()
        tok = self.tok
        self.error(M.PARSE_EXPECTED, tok, expected=what or f"'{kind.value}'", found=describe(tok))
        return None

    def word(self, what: str) -> RawToken | None:
        """An identifier, or any keyword (member names after '.' may be keywords: ``tl.Stop``)."""
        k = self.kind
        if k is K.IDENT or k in KEYWORD_KINDS:
            return self.next()
        tok = self.tok
        self.error(M.PARSE_EXPECTED, tok, expected=what, found=describe(tok))
        return None

    def ident(self, what: str) -> RawToken | None:
        if self.kind is K.IDENT:
            return self.next()
        tok = self.tok
        self.error(M.PARSE_EXPECTED, tok, expected=what, found=describe(tok))
        return None

    # ---------------------------------------------------------------------------- line handling

    def comments(self) -> tuple[A.Comment, ...]:
        """Full-line comments and '#' lines at the current position (consumed)."""
        k = self.kind
        if k is not K.COMMENT and k is not K.DIRECTIVE:
            return ()
        out: list[A.Comment] = []
        while True:
            tok = self.tok
            k = self.kind
            if k is K.COMMENT or k is K.DIRECTIVE:
                self.next()
                out.append(A.Comment(_at(tok), tok[VALUE], k is K.DIRECTIVE))  # type: ignore[arg-type]
                if self.kind is K.NEWLINE:
                    self.next()
            else:
                return tuple(out)

    def end_of_line(self, node: A.Stmt | None) -> A.Comment | None:
        """Finish a logical line: attach its comment to ``node`` and consume the ``NEWLINE``.

        Anything else before the end of the line is reported (unless the line already failed)
        and skipped.  Returns the trailing comment.
        """
        tok = self.tok
        k = self.kind
        if k is not K.NEWLINE and k is not K.COMMENT and k is not K.EOF:
            if k is K.COLON:
                self.error(M.PARSE_COLON_SEPARATOR, tok)
            else:
                self.error(M.PARSE_TRAILING_TOKENS, tok, found=describe(tok))
            while k is not K.NEWLINE and k is not K.COMMENT and k is not K.EOF:
                self.next()
                k = self.kind
        comment = None
        if k is K.COMMENT:
            comment = self._trailing_comment()
            k = self.kind
        if k is K.NEWLINE:
            self.next()
        self.failed = False
        if comment is not None and node is not None:
            node.trailing_comment = comment
        return comment

    def _trailing_comment(self) -> A.Comment:
        first = self.next()
        texts = [first[VALUE]]
        while self.kind is K.COMMENT:  # several (a continuation comment + the line's own)
            texts.append(self.next()[VALUE])
        # (joined once: a statement continued over 50,000 commented lines copied its text as often)
        return A.Comment(_at(first), " ".join(texts))  # type: ignore[arg-type]

    def skip_line(self) -> A.Comment | None:
        self.failed = True
        return self.end_of_line(None)

    def at_line_end(self) -> bool:
        return self.kind in _LINE_END

    # -------------------------------------------------------------------------------- closers

    def closer(self) -> str | None:
        """If the current line closes a construct, the kind it closes (else ``None``)."""
        c = _CLOSERS.get(self.kind)
        if c is None:
            return None
        if c == "END":
            return _END_KINDS.get(self.peek()[KIND])
        if c == "MOD":
            i = 1
            while self.peek(i)[KIND] in _MODIFIER_KINDS:
                i += 1
            return "<decl>" if self.peek(i)[KIND] in _DECL_WORDS else None
        return c

    def is_open(self, kind: str) -> bool:
        if kind == "<decl>":
            return any(k in _DECL_CONTAINERS for k in self.open)
        if kind in _PROC_KINDS:  # 'End Sub' typed for 'End Function' (or back) still ends the procedure
            return any(k in _PROC_KINDS for k in self.open)
        return kind in self.open

    def stray_closer(self, kind: str) -> None:
        """A closing line that matches no open construct: report once, skip the line."""
        tok = self.tok
        if kind == "<decl>":
            # a declaration where statements were expected and no container is open: handled
            # by the caller (top level), never reached from blocks
            self.skip_line()
            return
        text = tok[TEXT]
        if tok[KIND] is K.END:
            text = f"End {self.peek()[TEXT]}"
        opener = "Select" if kind == "Select" else kind
        self.sink.report(M.PARSE_UNMATCHED_END, _at(tok), closer=text, opener=opener)
        self.skip_line()

    def unclosed(self, opener: str, closer: str, start: RawToken) -> None:
        if self.aborted:
            return  # everything after the nesting limit was skipped: do not cascade
        tok = self.tok
        found = describe(tok)
        if tok[KIND] is K.END:
            found = f"'End {self.peek()[TEXT]}'"
        elif tok[KIND] is not K.EOF and tok[KIND] is not K.NEWLINE:
            found = f"'{tok[TEXT]}'"
        self.sink.report(M.PARSE_UNCLOSED_BLOCK, _at(start), opener=opener, closer=closer, found=found)

    # --------------------------------------------------------------------------------- blocks

    def block(self) -> A.Block:
        """Statements up to (not including) a line that closes an open construct, or EOF."""
        start = self.tok
        stmts: list[A.Stmt] = []
        pending: tuple[A.Comment, ...] = ()
        while True:
            comments = self.comments()
            if pending:
                comments = pending + comments
                pending = ()
            k = self.kind
            if k is K.EOF:
                break
            kind = self.closer()
            if kind is not None:
                if self.is_open(kind):
                    break
                self.stray_closer(kind)
                pending = comments
                continue
            n = len(stmts)
            self.statement(stmts)
            if len(stmts) > n:
                if comments:
                    stmts[n].leading_comments = comments + stmts[n].leading_comments
            elif comments:
                pending = comments
        return A.Block(self.span_from(start) if stmts else start[SPAN], stmts, end_comments=comments)

    def too_deep(self, what: str) -> bool:
        """Report and skip the rest of the file if one more nested construct would pass the limit.

        Every nested construct (blocks, and classes inside classes) is on :attr:`open`; recursion
        this deep would exhaust the Python stack, so nothing after this point is parsed.
        """
        if len(self.open) <= _MAX_BLOCK_DEPTH:
            return False
        self.sink.report(M.PARSE_TOO_DEEP, _at(self.tok), what=what, limit=_MAX_BLOCK_DEPTH)
        self.aborted = True
        while self.kind is not K.EOF:
            self.next()
        return True

    def deeper(self, where: RawToken, what: str) -> bool:
        """Enter one more level of expression nesting; ``False`` (with GPL1117) past the limit.

        Every recursive expression rule goes through here, so no spelling of deep nesting
        (parentheses, signs, ``^-``, arguments, single-line Ifs) can exhaust the Python stack.
        On ``True`` the caller must ``self.depth -= 1`` when it leaves the level.
        """
        self.depth += 1
        if self.depth <= _MAX_EXPR_DEPTH:
            return True
        self.error(M.PARSE_TOO_DEEP, where, what=what, limit=_MAX_EXPR_DEPTH)
        self.depth -= 1
        return False

    def body(self, kind: str) -> A.Block:
        """The block of a construct of ``kind`` (pushed on the open stack while it is parsed)."""
        if self.too_deep("blocks"):
            return A.Block(self.tok[SPAN], [])
        self.open.append(kind)
        try:
            return self.block()
        finally:
            self.open.pop()

    def proc_body(self, kind: str) -> A.Block:
        saved = self.in_proc
        self.in_proc = True
        try:
            return self.body(kind)
        finally:
            self.in_proc = saved

    def close_end(self, kind: str, start: RawToken, node: A.Stmt) -> bool:
        """Consume ``End <kind>`` (attaching its comment to ``node.end_comment``) or report.

        A procedure closed by the other procedure keyword (``Function … End Sub``) is one error at
        the ``End`` line, and the procedure ends there: reporting the ``End Sub`` as stray and the
        Function as unclosed would give two errors for one typo, far from where it is.
        """
        tok = self.tok
        found = _END_KINDS.get(self.peek()[KIND]) if tok[KIND] is K.END else None
        if found != kind and kind in _PROC_KINDS and found in _PROC_KINDS:
            self.sink.report(
                M.PARSE_EXPECTED, _at(tok).to(self.peek()[SPAN]), expected=f"'End {kind}'",
                found=f"'End {self.peek()[TEXT]}'",
            )
            found = kind
        if found == kind:
            self.next()
            self.next()
            comment = self.end_of_line(None)
            if comment is not None:
                node.end_comment = comment  # type: ignore[attr-defined]
            return True
        self.unclosed(kind, f"End {kind}", start)
        return False

    # ----------------------------------------------------------------------------- top level

    def parse_unit(self) -> A.SourceUnit:
        start = self.tok
        members: list[A.Stmt] = []
        while True:
            comments = self.comments()
            tok = self.tok
            if tok[KIND] is K.EOF:
                break
            c = _CLOSERS.get(tok[KIND])
            if c is not None and c != "<decl>" and c != "MOD":
                kind = self.closer()
                if kind is not None:
                    self.stray_closer(kind)
                    continue
            member = self.member("file")
            if member is not None:
                member.leading_comments = comments + member.leading_comments
                members.append(member)
        return A.SourceUnit(self.span_from(start), self.source.path, members, end_comments=comments,
                            compact_dims=self.compact_dims)

    def members(self, container: str, start: RawToken, node: A.Stmt) -> list[A.Stmt]:
        """Members of a Module or Class up to its ``End``; sets ``node.end_comments``."""
        out: list[A.Stmt] = []
        if self.too_deep("classes"):
            return out
        self.open.append(container)
        try:
            while True:
                comments = self.comments()
                k = self.kind
                if k is K.EOF:
                    self.unclosed(container, f"End {container}", start)
                    break
                if k is K.END:
                    kind = _END_KINDS.get(self.peek()[KIND])
                    if kind == container:
                        self.next()
                        self.next()
                        c = self.end_of_line(None)
                        if c is not None:
                            node.end_comment = c  # type: ignore[attr-defined]
                        break
                    if kind is not None and kind in self.open:
                        self.unclosed(container, f"End {container}", start)
                        break
                    if kind is not None:
                        self.stray_closer(kind)
                        continue
                if k is K.MODULE:  # modules do not nest: the current one was not closed
                    self.unclosed(container, f"End {container}", start)
                    break
                member = self.member(container)
                if member is not None:
                    member.leading_comments = comments + member.leading_comments
                    out.append(member)
            node.end_comments = comments  # type: ignore[attr-defined]
        finally:
            self.open.pop()
        return out

    def modifiers(self) -> list[str]:
        mods: list[str] = []
        while True:
            tok = self.tok
            k = self.kind
            if k is K.PUBLIC or k is K.PRIVATE or k is K.SHARED:
                mods.append(k.value)
                self.next()
            elif k is K.IDENT and tok[TEXT].lower() in _UNSUPPORTED_MODIFIERS:
                nxt = self.peek()[KIND]
                if nxt in _NAME_FOLLOWERS or nxt is K.AS or nxt in _LINE_END:
                    return mods  # a variable that happens to be called e.g. 'Friend'
                word = _UNSUPPORTED_MODIFIERS[tok[TEXT].lower()]
                self.error(M.PARSE_UNSUPPORTED, tok, what=f"'{word}'", hint="")
                self.next()
            else:
                return mods

    def member(self, container: str) -> A.Stmt | None:
        """One declaration in a Module, a Class or (misplaced) at the top of the file."""
        start = self.tok
        mods = self.modifiers()
        tok = self.tok
        k = self.kind
        if container == "file" and k is not K.MODULE and k is not K.CLASS:
            if k in _DECL_WORDS or k in (K.DIM, K.CONST, K.STATIC) or mods:
                what = "a variable" if k not in _DECL_WORDS else f"a {k.value}"
                self.sink.report(M.PARSE_OUTSIDE_MODULE, _at(start), what=what)
        if k is K.SUB or k is K.FUNCTION:
            return self.procedure(start, mods)
        if k is K.PROPERTY:
            if container != "Class":
                self.sink.report(
                    M.PARSE_MISPLACED_DECLARATION,
                    _at(tok),
                    what="a Property",
                    where="outside a Class (properties are class members)",
                )
            return self.property_decl(start, mods)
        if k is K.CLASS:
            return self.class_decl(start, mods)
        if k is K.MODULE:
            if container != "file":
                self.sink.report(
                    M.PARSE_MISPLACED_DECLARATION, _at(tok), what="a Module", where=f"inside a {container}"
                )
            if mods:
                self.sink.report(M.PARSE_BAD_MODIFIER, _at(start), modifier=mods[0], where="on a Module")
            return self.module_decl(start)
        if k is K.DELEGATE:
            return self.delegate_decl(start, mods)
        if k is K.DIM or k is K.CONST:
            self.next()
            return self._member_var(start, tok[KIND].value, mods)
        if k is K.STATIC:
            self.next()
            if self.kind is K.SUB or self.kind is K.FUNCTION:
                self.error(M.PARSE_UNSUPPORTED, tok, what="'Static' procedures", hint="")
                self.failed = False
                return self.procedure(start, mods)
            self.error(
                M.PARSE_MISPLACED_DECLARATION, tok, what="a Static variable", where="outside a procedure"
            )
            self.failed = False
            return self._member_var(start, "Static", mods)
        if mods and k is K.IDENT:
            return self._member_var(start, None, mods)
        if k is K.IDENT:
            low = tok[TEXT].lower()
            word = _UNSUPPORTED_STATEMENTS.get(low)
            if word is not None and self.peek()[KIND] not in _NAME_FOLLOWERS:
                self.error(M.PARSE_UNSUPPORTED, tok, what=f"'{word}'", hint=_UNSUPPORTED_HINTS.get(word, ""))
                self.skip_line()
                return None
        where = "the file" if container == "file" else f"a {container}"
        self.error(M.PARSE_STATEMENT_OUTSIDE_PROCEDURE, tok, found=describe(tok), container=where)
        self.skip_line()
        return None

    def _member_var(self, start: RawToken, keyword: str | None, mods: list[str]) -> A.VarDecl:
        node = self.var_decl(start, keyword, mods, compact=keyword == "Dim" and not mods)
        self.end_of_line(node)
        return node

    def module_decl(self, start: RawToken) -> A.ModuleDecl:
        self.next()  # Module
        name = self.ident("a module name")
        node = A.ModuleDecl(start[SPAN], name[TEXT] if name else "", [])
        self.end_of_line(node)
        node.members = self.members("Module", start, node)
        node.span = self.span_from(start)
        return node

    def class_decl(self, start: RawToken, mods: list[str]) -> A.ClassDecl:
        self.next()  # Class
        name = self.ident("a class name")
        node = A.ClassDecl(start[SPAN], name[TEXT] if name else "", mods, [])
        self.end_of_line(node)
        saved = self.in_proc
        self.in_proc = False
        try:
            node.members = self.members("Class", start, node)
        finally:
            self.in_proc = saved
        node.span = self.span_from(start)
        return node

    # ------------------------------------------------------------------------- declarations

    def type_ref(self) -> A.TypeRef | None:
        first = self.ident("a type name")
        if first is None:
            return None
        parts = [first[TEXT]]
        while self.kind is K.DOT:
            self.next()
            w = self.word("a type name after '.'")
            if w is None:
                break
            parts.append(w[TEXT])
        return A.TypeRef(self.span_from(first), ".".join(parts))

    def var_decl(self, start: RawToken, keyword: str | None, mods: list[str],
                 compact: bool = False) -> A.VarDecl:
        """``[mods] [Dim|Static|Const] name[(bounds)] {, …} As [New] T [= init] {, group}``.

        ``compact``: a ``Dim`` in a procedure, whose declarators are held as one
        :class:`~gpl2py.gpl.syntax.ast.CompactDeclarators` once it has ``DIM_MIN`` names, every
        one simple so far (no bounds, ``New`` or value: a name that has one turns them back into
        a list)."""
        declarators: list[A.VarDeclarator] = []
        pending: list[A.VarDeclarator] = []
        is_const = keyword == "Const"
        run: A.CompactDeclarators | None = None  # the names so far, compactly
        while True:
            name = self.ident("a variable name")
            if name is None:
                break
            bounds: list[A.Expr | None] | None = None
            if self.kind is K.LPAREN:
                bounds = self.array_suffix()
                if len(bounds) > 4:
                    self.error(M.PARSE_ARRAY_RANK, name, name=name[TEXT], rank=len(bounds))
                if run is not None:
                    declarators, pending = run.declarators()
                    run = None
                compact = False
            if run is not None:
                at = name[SPAN]
                run.add(name[TEXT], at[1], at[2])
            else:
                d = A.VarDeclarator(self.span_from(name), name[TEXT], bounds, None)
                pending.append(d)
                if compact and len(declarators) + len(pending) >= A.DIM_MIN:
                    run = self._compact(declarators, pending)
                    declarators, pending = [], []
            k = self.kind
            if k is K.COMMA:
                self.next()
                continue
            if k is K.AS:
                self.next()
                group_new = False
                new_args: list[A.Expr] | None = None
                if self.kind is K.NEW:
                    self.next()
                    group_new = True
                    type_ = self.type_ref()
                    if self.kind is K.LPAREN:
                        new_args = self.arguments()
                else:
                    type_ = self.type_ref()
                init: A.Expr | None = None
                if self.kind is K.EQ:
                    self.next()
                    init = self.expression()
                elif is_const:
                    self.error(M.PARSE_EXPECTED, self.tok, expected="'=' and the constant's value", found=describe(self.tok))
                if run is not None and not group_new and init is None and type_ is not None:
                    end = self.prev[SPAN]
                    run.close_group(type_, end[3], end[4])
                    if self.kind is K.COMMA:
                        self.next()
                        continue
                    break
                if run is not None:
                    declarators, pending = run.declarators()
                    run = None
                compact = compact and not group_new and init is None and type_ is not None
                if (group_new or init is not None) and len(pending) > 1:
                    self.error(M.PARSE_NEW_NEEDS_ONE_NAME, pending[0].span)
                for p in pending:
                    p.type = type_
                    p.new = group_new
                    p.span = p.span.to(self.prev[SPAN])
                last = pending[-1]
                last.new_args = new_args
                last.initializer = init
                if init is not None and last.bounds is not None:
                    self.error(M.PARSE_ARRAY_INITIALIZER, init.span)
                declarators.extend(pending)
                pending = []
                if self.kind is K.COMMA:
                    self.next()
                    continue
                break
            break
        if run is not None:
            if run.typed() == len(run):
                return A.VarDecl(self.span_from(start), keyword, mods, run.done())
            declarators, pending = run.declarators()
        if pending:
            self.error(M.PARSE_MISSING_TYPE, pending[-1].span, name=pending[-1].name)
            if self.kind is K.EQ:  # 'Const x = 1': parse the value anyway
                self.next()
                pending[-1].initializer = self.expression()
            declarators.extend(pending)
        node = A.VarDecl(self.span_from(start), keyword, mods, declarators)
        return node

    def _compact(self, declarators: list[A.VarDeclarator], pending: list[A.VarDeclarator]) -> A.CompactDeclarators:
        """The simple declarators so far, those of closed groups and those waiting for their type,
        as a :class:`~gpl2py.gpl.syntax.ast.CompactDeclarators`."""
        run = A.CompactDeclarators(self.source.path)
        self.compact_dims = True
        for i, d in enumerate(declarators):
            run.add(d.name, d._line, d._col)
            if i + 1 == len(declarators) or declarators[i + 1].type is not d.type:
                assert d.type is not None
                run.close_group(d.type, d._end_line, d._end_col)
        for d in pending:
            run.add(d.name, d._line, d._col)
        return run

    def array_suffix(self) -> list[A.Expr | None]:
        self.next()  # (
        k = self.kind
        if k is K.RPAREN:
            self.next()
            return [None]
        if k is K.COMMA:
            rank = 1
            while self.kind is K.COMMA:
                self.next()
                rank += 1
            self.expect(K.RPAREN)
            return [None] * rank
        bounds: list[A.Expr | None] = [self.expression()]
        while self.kind is K.COMMA:
            self.next()
            bounds.append(self.expression())
        if self.kind is K.TO:
            self.error(M.PARSE_UNSUPPORTED, self.tok, what="an array lower bound ('x To y')", hint=" (arrays start at 0)")
        self.expect(K.RPAREN)
        return bounds

    def params(self) -> list[A.Param]:
        """``( [param {, param}] )``; the current token is ``(``."""
        self.next()
        out: list[A.Param] = []
        if self.kind is K.RPAREN:
            self.next()
            return out
        while True:
            p = self.param()
            if p is None:
                break
            out.append(p)
            if self.kind is K.COMMA:
                self.next()
                continue
            self.expect(K.RPAREN, "',' or ')'")
            break
        return out

    def param(self) -> A.Param | None:
        start = self.tok
        by_ref = False
        optional = False
        while True:
            tok = self.tok
            k = self.kind
            if k is K.BYVAL:
                self.next()
            elif k is K.BYREF:
                by_ref = True
                self.next()
            elif k is K.IDENT and self.peek()[KIND] in (K.IDENT, K.BYVAL, K.BYREF):
                low = tok[TEXT].lower()
                if low == "optional":
                    optional = True
                    self.next()
                elif low == "paramarray":
                    self.error(M.PARSE_UNSUPPORTED, tok, what="'ParamArray'", hint="")
                    self.next()
                else:
                    break
            else:
                break
        name = self.ident("a parameter name")
        if name is None:
            return None
        rank = 0
        if self.kind is K.LPAREN:
            self.next()
            rank = 1
            while self.kind is K.COMMA:
                self.next()
                rank += 1
            self.expect(K.RPAREN, "')' (array parameters are written 'name()')")
        type_: A.TypeRef | None = None
        if self.kind is K.AS:
            self.next()
            type_ = self.type_ref()
        else:
            self.error(M.PARSE_MISSING_TYPE, name, name=name[TEXT])
        default: A.Expr | None = None
        if self.kind is K.EQ:
            self.next()
            default = self.expression()
        return A.Param(self.span_from(start), name[TEXT], type_, by_ref, rank, optional, default)

    def procedure(self, start: RawToken, mods: list[str]) -> A.ProcDecl:
        kw = self.next()  # Sub | Function
        kind = kw[KIND].value
        tok = self.tok
        if tok[KIND] is K.IDENT or (tok[KIND] is K.NEW and kind == "Sub"):
            self.next()
            name = tok[TEXT]
        else:
            self.error(M.PARSE_EXPECTED, tok, expected=f"a {kind} name", found=describe(tok))
            name = ""
        params: list[A.Param] = []
        if self.kind is K.LPAREN:
            params = self.params()
        ret: A.TypeRef | None = None
        if self.kind is K.AS:
            self.next()
            ret = self.type_ref()
            if kind == "Sub":
                self.error(M.PARSE_UNSUPPORTED, kw, what="a return type on a Sub", hint=" (use a Function)")
        elif kind == "Function":
            self.error(M.PARSE_FUNCTION_NEEDS_TYPE, self.tok, what="Function", name=name)
        node = A.ProcDecl(self.span_from(start), kind, name, mods, params, ret, A.Block(start[SPAN], []))
        self.end_of_line(node)
        node.body = self.proc_body(kind)
        self.close_end(kind, start, node)
        node.span = self.span_from(start)
        return node

    def property_decl(self, start: RawToken, mods: list[str]) -> A.PropertyDecl:
        self.next()  # Property
        name_tok = self.ident("a property name")
        name = name_tok[TEXT] if name_tok else ""
        if self.kind is K.LPAREN:
            if self.peek()[KIND] is K.RPAREN:  # 'Property Name() As T': an empty list, as on Subs
                self.next()
                self.next()
            else:
                self.error(M.PARSE_UNSUPPORTED, self.tok, what="a property with parameters", hint="")
                self.params()
        type_: A.TypeRef | None = None
        if self.kind is K.AS:
            self.next()
            type_ = self.type_ref()
        else:
            self.error(M.PARSE_FUNCTION_NEEDS_TYPE, self.tok, what="Property", name=name)
        node = A.PropertyDecl(self.span_from(start), name, mods, type_, None, None)
        self.end_of_line(node)
        self.open.append("Property")
        try:
            while True:
                comments = self.comments()
                tok = self.tok
                k = self.kind
                if k is K.GET or k is K.SET:
                    acc = self.accessor()
                    acc.leading_comments = comments + acc.leading_comments
                    if k is K.GET:
                        if node.getter is not None:
                            self.sink.report(M.PARSE_EXPECTED, _at(tok), expected="one Get block", found="a second 'Get'")
                        node.getter = acc
                    else:
                        if node.setter is not None:
                            self.sink.report(M.PARSE_EXPECTED, _at(tok), expected="one Set block", found="a second 'Set'")
                        node.setter = acc
                    continue
                node.end_comments = comments
                if k is K.END and self.peek()[KIND] is K.PROPERTY:
                    self.next()
                    self.next()
                    c = self.end_of_line(None)
                    if c is not None:
                        node.end_comment = c
                    break
                kind = self.closer()
                if k is K.EOF or (kind is not None and self.is_open(kind)):
                    self.unclosed("Property", "End Property", start)
                    break
                self.error(M.PARSE_EXPECTED, tok, expected="'Get', 'Set' or 'End Property'", found=describe(tok))
                self.skip_line()
        finally:
            self.open.pop()
        if node.getter is None and node.setter is None:
            self.sink.report(M.PARSE_PROPERTY_NEEDS_ACCESSOR, _at(start), name=name)
        node.span = self.span_from(start)
        return node

    def accessor(self) -> A.Accessor:
        start = self.next()  # Get | Set
        kind = start[KIND].value
        param: A.Param | None = None
        if self.kind is K.LPAREN:
            params = self.params()
            if kind == "Get" and params:
                self.error(M.PARSE_UNSUPPORTED, start, what="parameters on Get", hint="")
            if kind == "Set":
                if len(params) > 1:
                    self.error(M.PARSE_EXPECTED, start, expected="one Set parameter", found=f"{len(params)}")
                param = params[0] if params else None
        node = A.Accessor(self.span_from(start), kind, param, A.Block(start[SPAN], []))
        self.end_of_line(node)
        node.body = self.proc_body(kind)
        self.close_end(kind, start, node)
        node.span = self.span_from(start)
        return node

    def delegate_decl(self, start: RawToken, mods: list[str]) -> A.DelegateDecl:
        self.next()  # Delegate
        kw = self.tok
        if kw[KIND] is not K.SUB and kw[KIND] is not K.FUNCTION:
            self.error(M.PARSE_EXPECTED, kw, expected="'Sub' or 'Function'", found=describe(kw))
            self.skip_line()
            return A.DelegateDecl(self.span_from(start), "Sub", "", mods, [], None)
        self.next()
        kind = kw[KIND].value
        name = self.ident("a delegate name")
        params: list[A.Param] = []
        if self.kind is K.LPAREN:
            params = self.params()
        ret: A.TypeRef | None = None
        if self.kind is K.AS:
            self.next()
            ret = self.type_ref()
        elif kind == "Function":
            self.error(M.PARSE_FUNCTION_NEEDS_TYPE, self.tok, what="Delegate Function", name=name[TEXT] if name else "")
        node = A.DelegateDecl(self.span_from(start), kind, name[TEXT] if name else "", mods, params, ret)
        self.end_of_line(node)
        return node

    # --------------------------------------------------------------------------- statements

    def statement(self, out: list[A.Stmt]) -> None:
        """Parse one logical line of a procedure body into ``out`` (a label may add two nodes)."""
        tok = self.tok
        k = self.kind
        if (k is K.IDENT or k is K.INTEGER) and self.peek()[KIND] is K.COLON:
            self.next()
            self.next()
            label = A.Label(self.span_from(tok), tok[TEXT])
            out.append(label)
            if self.kind in _LINE_END:
                self.end_of_line(label)
                return
            tok = self.tok
            k = self.kind
        if k is K.COLON:
            self.error(M.PARSE_COLON_SEPARATOR, tok)
            self.unreadable(tok, out)
            return
        handler = _BLOCK_STATEMENTS.get(k)
        if handler is not None:
            node = handler(self)
            if node is not None:
                out.append(node)
            return
        node = self.simple_statement()
        if node is not None:
            out.append(node)
            self.end_of_line(node)
        else:
            self.unreadable(tok, out)

    def unreadable(self, start: RawToken, out: list[A.Stmt]) -> None:
        """Skip the rest of a statement line that failed (reported), leaving an ErrorStmt for it."""
        node = A.ErrorStmt(_at(start))
        comment = self.skip_line()
        node.span = self.span_from(start)
        node.trailing_comment = comment
        out.append(node)

    def simple_statement(self) -> A.Stmt | None:
        """A statement that fits on one line (does not consume the end of the line)."""
        tok = self.tok
        k = self.kind
        if k is K.IDENT:
            nk = self.peek()[KIND]
            if nk not in _NAME_FOLLOWERS:
                word = _UNSUPPORTED_STATEMENTS.get(tok[TEXT].lower())
                if word is not None:
                    self.error(M.PARSE_UNSUPPORTED, tok, what=f"'{word}'", hint=_UNSUPPORTED_HINTS.get(word, ""))
                    return None
            return self.expression_statement()
        handler = _SIMPLE_STATEMENTS.get(k)
        if handler is not None:
            return handler(self)
        return self.expression_statement()

    def expression_statement(self) -> A.Stmt | None:
        start = self.tok
        if start[KIND] not in _EXPR_STARTS:
            self.error(M.PARSE_EXPECTED, start, expected="a statement", found=describe(start))
            return None
        target = self.postfix()
        k = self.kind
        if k is K.EQ:
            self.next()
            value = self.expression()
            return A.Assign(self.span_from(start), target, "=", value)
        op = COMPOUND_ASSIGN.get(k)
        if op is not None:
            self.next()
            value = self.expression()
            return A.Assign(self.span_from(start), target, op, value)
        if isinstance(target, (A.Name, A.MemberAccess, A.Invoke)):
            if self.kind is K.IDENT and self.tok[TEXT].lower() == "isnot":
                self.error(M.PARSE_UNSUPPORTED, self.tok, what="'IsNot'", hint=" (write 'Not a Is b')")
            return A.CallStmt(self.span_from(start), target)
        if isinstance(target, A.ErrorExpr):
            return None
        what = {
            A.New: "a New expression",
            A.MeExpr: "'Me'",
            A.AddressOf: "an AddressOf expression",
        }.get(type(target), "a value")
        self.error(M.PARSE_NOT_A_STATEMENT, target.span, what=what)
        return None

    def _declaration_statement(self) -> A.Stmt | None:
        start = self.tok
        mods = self.modifiers()
        if mods:
            self.error(M.PARSE_BAD_MODIFIER, start, modifier=mods[0], where="inside a procedure (locals use Dim or Static)")
            self.failed = False
        tok = self.tok
        if tok[KIND] in (K.DIM, K.STATIC, K.CONST):
            self.next()
            keyword = tok[KIND].value
        else:
            keyword = None
        # a declaration inside a block (If, Select, For, Try ...) is legal: real code does it and the
        # controller compiles it (docs/design/real-code.md); it has procedure scope (semantics)
        node = self.var_decl(start, keyword, mods, compact=keyword == "Dim" and not mods)
        self.end_of_line(node)
        return node

    # -- block statements (each consumes its own lines)

    def if_statement(self) -> A.Stmt | None:
        start = self.next()  # If
        cond = self.expression()
        if self.kind is K.THEN:
            self.next()
        else:
            self.error(M.PARSE_EXPECTED, self.tok, expected="'Then'", found=describe(self.tok))
            if self.kind not in _LINE_END:
                # 'If c stmt': more on the line means a single-line If with a missing Then; a
                # block If would swallow the rest of the procedure and report a second error.
                node = A.If(self.span_from(start), cond, A.Block(start[SPAN], []), single_line=True)
                self.end_of_line(node)
                return node
        if not self.failed and self.kind not in _LINE_END:
            node = self.single_line_if(start, cond)
            self.end_of_line(node)
            return node
        node = A.If(start[SPAN], cond, A.Block(start[SPAN], []))
        node.then_body = self._if_body(node)
        while True:
            tok = self.tok
            if tok[KIND] is K.ELSEIF or (tok[KIND] is K.ELSE and self.peek()[KIND] is K.IF):
                if tok[KIND] is K.ELSE:
                    self.sink.report(M.PARSE_ELSE_IF, _at(tok))
                    self.next()
                self.next()
                c = self.expression()
                if self.kind is K.THEN:
                    self.next()
                else:
                    self.error(M.PARSE_EXPECTED, self.tok, expected="'Then'", found=describe(self.tok))
                clause = A.ElseIfClause(self.span_from(tok), c, A.Block(tok[SPAN], []))
                clause.body = self._if_body(clause)
                node.elseifs.append(clause)
                continue
            if tok[KIND] is K.ELSE:
                self.next()
                else_comment = self.end_of_line(None)
                body = self.body("If")
                body.header_comment = else_comment
                if node.else_body is not None:
                    self.sink.report(M.PARSE_EXPECTED, _at(tok), expected="'End If' (only one Else per If)", found="'Else'")
                node.else_body = body
                continue
            break
        if self.kind is K.END and self.peek()[KIND] is K.IF:
            self.next()
            self.next()
            c2 = self.end_of_line(None)
            node.end_comment = c2
        else:
            self.unclosed("If", "End If", start)
        node.span = self.span_from(start)
        return node

    def _if_body(self, owner: A.Stmt) -> A.Block:
        self.end_of_line(owner)
        return self.body("If")

    def single_line_if(self, start: RawToken, cond: A.Expr) -> A.If:
        then_stmt = self._single_line_part()
        else_body: A.Block | None = None
        if self.kind is K.ELSE:
            else_tok = self.next()
            else_stmt = self._single_line_part()
            else_body = A.Block(else_tok[SPAN], [else_stmt] if else_stmt else [])
        then_body = A.Block(then_stmt.span if then_stmt else start[SPAN], [then_stmt] if then_stmt else [])
        return A.If(self.span_from(start), cond, then_body, [], else_body, single_line=True)

    def _single_line_part(self) -> A.Stmt | None:
        tok = self.tok
        k = self.kind
        if k is K.IF:
            if not self.deeper(tok, "single-line If statements"):
                return None
            try:
                start = self.next()
                cond = self.expression()
                self.expect(K.THEN)
                if self.kind in _LINE_END:
                    self.error(M.PARSE_BLOCK_IN_SINGLE_LINE_IF, tok, what="a block If")
                    return None
                return self.single_line_if(start, cond)
            finally:
                self.depth -= 1
        if k in _BLOCK_STATEMENTS or k in (K.DIM, K.STATIC, K.CONST, K.PUBLIC, K.PRIVATE, K.SHARED):
            what = f"'{tok[TEXT]}'"
            self.error(M.PARSE_BLOCK_IN_SINGLE_LINE_IF, tok, what=what)
            return None
        if (k is K.IDENT or k is K.INTEGER) and self.peek()[KIND] is K.COLON:
            self.error(M.PARSE_BLOCK_IN_SINGLE_LINE_IF, tok, what="a label")
            return None
        if k in _LINE_END:
            self.error(M.PARSE_EXPECTED, tok, expected="a statement after 'Then'", found=describe(tok))
            return None
        return self.simple_statement()

    def for_statement(self) -> A.Stmt | None:
        start = self.next()  # For
        node: A.For | A.ForEach
        if self.kind is K.IDENT and self.tok[TEXT].lower() == "each":
            self.next()
            var = self.postfix()
            if self.kind is K.IDENT and self.tok[TEXT].lower() == "in":
                self.next()
            else:
                self.error(M.PARSE_EXPECTED, self.tok, expected="'In'", found=describe(self.tok))
            coll = self.expression()
            node = A.ForEach(self.span_from(start), var, coll, A.Block(start[SPAN], []))
        else:
            var = self.postfix()
            if self.kind is K.AS:
                self.error(M.PARSE_UNSUPPORTED, self.tok, what="declaring the loop variable in 'For'", hint=" (declare it with Dim at the top of the procedure)")
            self.expect(K.EQ, "'='")
            first = self.expression()
            self.expect(K.TO, "'To'")
            last = self.expression()
            step = None
            if self.kind is K.STEP:
                self.next()
                step = self.expression()
            node = A.For(self.span_from(start), var, first, last, step, A.Block(start[SPAN], []))
        self.end_of_line(node)
        node.body = self.body("For")
        if self.kind is K.NEXT:
            self.next()
            if self.kind not in _LINE_END:
                node.next_var = self.postfix()
                if self.kind is K.COMMA:
                    self.error(M.PARSE_UNSUPPORTED, self.tok, what="'Next' with several loop variables", hint=" (close each For with its own Next)")
            node.end_comment = self.end_of_line(None)
        else:
            self.unclosed("For", "Next", start)
        node.span = self.span_from(start)
        return node

    def while_statement(self) -> A.Stmt | None:
        start = self.next()
        cond = self.expression()
        node = A.While(self.span_from(start), cond, A.Block(start[SPAN], []))
        self.end_of_line(node)
        node.body = self.body("While")
        self.close_end("While", start, node)
        node.span = self.span_from(start)
        return node

    def do_statement(self) -> A.Stmt | None:
        start = self.next()
        cond: A.Expr | None = None
        until = False
        top = False
        k = self.kind
        if k is K.WHILE or k is K.UNTIL:
            self.next()
            until = k is K.UNTIL
            top = True
            cond = self.expression()
        node = A.DoLoop(self.span_from(start), cond, top, until, A.Block(start[SPAN], []))
        self.end_of_line(node)
        node.body = self.body("Do")
        if self.kind is K.LOOP:
            loop_tok = self.next()
            k = self.kind
            if k is K.WHILE or k is K.UNTIL:
                self.next()
                c = self.expression()
                if top:
                    self.error(M.PARSE_DO_TWO_CONDITIONS, loop_tok)
                else:
                    node.condition = c
                    node.until = k is K.UNTIL
            node.end_comment = self.end_of_line(None)
        else:
            self.unclosed("Do", "Loop", start)
        node.span = self.span_from(start)
        return node

    def select_statement(self) -> A.Stmt | None:
        if self.too_deep("blocks"):  # its Case blocks are parsed by block(), not body(): check here
            return None
        start = self.next()  # Select
        if self.kind is K.CASE:
            self.next()
        subject = self.expression()
        node = A.Select(self.span_from(start), subject, [])
        self.end_of_line(node)
        self.open.append("Select")
        try:
            pre = self.block()
            if pre.statements:
                self.sink.report(M.PARSE_CASE_OUTSIDE_SELECT, pre.statements[0].span)
            pending = pre.end_comments  # comments between 'Select' and the first 'Case'
            seen_else = False
            while self.kind is K.CASE:
                case_tok = self.next()
                clause = self.case_clause(case_tok)
                if seen_else:
                    self.sink.report(M.PARSE_EXPECTED, _at(case_tok), expected="'End Select' after the 'Case Else' block", found="'Case'")
                seen_else = seen_else or clause.is_else
                clause.leading_comments = pending + clause.leading_comments
                pending = ()
                node.cases.append(clause)
            node.end_comments = pending
        finally:
            self.open.pop()
        self.close_end("Select", start, node)
        node.span = self.span_from(start)
        return node

    def case_clause(self, case_tok: RawToken) -> A.CaseClause:
        items: list[A.CaseValue | A.CaseRange | A.CaseIs] = []
        is_else = False
        if self.kind is K.ELSE:
            self.next()
            is_else = True
        else:
            while True:
                tok = self.tok
                if tok[KIND] is K.IS:
                    self.next()
                    op = _CASE_IS_OPS.get(self.kind)
                    if op is None:
                        self.error(M.PARSE_EXPECTED, self.tok, expected="a comparison operator after 'Case Is'", found=describe(self.tok))
                        break
                    self.next()
                    value = self.expression()
                    items.append(A.CaseIs(self.span_from(tok), op, value))
                else:
                    op = _CASE_IS_OPS.get(tok[KIND])
                    if op is not None and tok[KIND] is not K.EQ:  # VB shorthand 'Case > 5'
                        self.next()
                        value = self.expression()
                        items.append(A.CaseIs(self.span_from(tok), op, value))
                    else:
                        low = self.expression()
                        if self.kind is K.TO:
                            self.next()
                            high = self.expression()
                            items.append(A.CaseRange(self.span_from(tok), low, high))
                        else:
                            items.append(A.CaseValue(low.span, low))
                if self.kind is K.COMMA:
                    self.next()
                    continue
                break
        clause = A.CaseClause(self.span_from(case_tok), items, A.Block(case_tok[SPAN], []), is_else)
        self.end_of_line(clause)
        clause.body = self.block()
        return clause

    def try_statement(self) -> A.Stmt | None:
        start = self.next()  # Try
        node = A.Try(start[SPAN], A.Block(start[SPAN], []), None, None)
        self.end_of_line(node)
        node.body = self.body("Try")
        while True:
            tok = self.tok
            if tok[KIND] is K.CATCH:
                self.next()
                var: str | None = None
                type_: A.TypeRef | None = None
                if self.kind is K.IDENT:
                    var = self.next()[TEXT]
                    if self.kind is K.AS:
                        self.next()
                        type_ = self.type_ref()
                    if self.kind is K.IDENT and self.tok[TEXT].lower() == "when":
                        self.error(M.PARSE_UNSUPPORTED, self.tok, what="'Catch … When'", hint=" (a Catch catches every error)")
                elif self.kind in _LINE_END:
                    self.error(M.PARSE_CATCH_NEEDS_VARIABLE, tok)
                clause = A.CatchClause(self.span_from(tok), var, type_, A.Block(tok[SPAN], []))
                self.end_of_line(clause)
                clause.body = self.body("Try")
                if node.catch is not None:
                    self.sink.report(M.PARSE_DUPLICATE_CLAUSE, _at(tok), clause="Catch")
                elif node.finally_ is not None:
                    self.sink.report(M.PARSE_EXPECTED, _at(tok), expected="'End Try' after Finally", found="'Catch'")
                else:
                    node.catch = clause
                continue
            if tok[KIND] is K.FINALLY:
                self.next()
                fin = A.FinallyClause(tok[SPAN], A.Block(tok[SPAN], []))
                self.end_of_line(fin)
                fin.body = self.body("Try")
                if node.finally_ is not None:
                    self.sink.report(M.PARSE_DUPLICATE_CLAUSE, _at(tok), clause="Finally")
                else:
                    node.finally_ = fin
                continue
            break
        if node.catch is None and node.finally_ is None:
            self.sink.report(M.PARSE_EXPECTED, _at(start), expected="a Catch or Finally block in this Try", found=describe(self.tok))
        self.close_end("Try", start, node)
        node.span = self.span_from(start)
        return node

    # -- simple statements (do not consume the end of the line)

    def goto_statement(self) -> A.Stmt | None:
        start = self.next()
        tok = self.tok
        if tok[KIND] is K.IDENT or tok[KIND] is K.INTEGER:
            self.next()
            return A.GoTo(self.span_from(start), tok[TEXT])
        self.error(M.PARSE_EXPECTED, tok, expected="a label after 'GoTo'", found=describe(tok))
        return None

    def exit_statement(self) -> A.Stmt | None:
        start = self.next()
        kind = _EXIT_KINDS.get(self.kind)
        if kind is None:
            self.error(M.PARSE_EXPECTED, self.tok, expected="Sub, Function, Property, For, Do, While, Select or Try after 'Exit'", found=describe(self.tok))
            return None
        self.next()
        return A.Exit(self.span_from(start), kind)

    def return_statement(self) -> A.Stmt | None:
        start = self.next()
        value = None if self.kind in _STMT_END else self.expression()
        return A.Return(self.span_from(start), value)

    def throw_statement(self) -> A.Stmt | None:
        start = self.next()
        value = None if self.kind in _STMT_END else self.expression()
        return A.Throw(self.span_from(start), value)

    def call_statement(self) -> A.Stmt | None:
        start = self.next()  # Call
        expr = self.postfix()
        if isinstance(expr, A.ErrorExpr):
            return None
        if not isinstance(expr, (A.Name, A.MemberAccess, A.Invoke)):
            self.error(M.PARSE_EXPECTED, expr.span, expected="a procedure after 'Call'", found="an expression")
            return None
        return A.CallStmt(self.span_from(start), expr, call_keyword=True)

    def redim_statement(self) -> A.Stmt | None:
        start = self.next()  # ReDim
        preserve = False
        tok = self.tok
        if tok[KIND] is K.IDENT and tok[TEXT].lower() == "preserve" and self.peek()[KIND] is K.IDENT:
            # real code uses it and the controller runs it (docs/design/real-code.md)
            self.next()
            preserve = True
        expr = self.postfix()
        if isinstance(expr, A.Invoke) and expr.args:
            return A.ReDim(self.span_from(start), expr.target, expr.args, preserve)
        if not isinstance(expr, A.ErrorExpr):
            self.error(M.PARSE_EXPECTED, expr.span, expected="an array with its new bounds, e.g. 'ReDim a(9)'", found=describe(self.tok))
        return None

    def end_statement(self) -> A.Stmt | None:
        tok = self.tok
        nxt = self.peek()
        if nxt[KIND] in _LINE_END:
            self.error(M.PARSE_UNSUPPORTED, tok, what="the 'End' statement", hint=" (use Exit Sub or Controller methods)")
        else:
            self.error(M.PARSE_UNSUPPORTED, tok, what=f"'End {nxt[TEXT]}'", hint="")
        return None

    def set_statement(self) -> A.Stmt | None:
        self.error(M.PARSE_UNSUPPORTED, self.tok, what="'Set' assignment", hint=" (assign object variables with '=')")
        return None

    def misplaced_keyword(self) -> A.Stmt | None:
        tok = self.tok
        self.error(M.PARSE_EXPECTED, tok, expected="a statement", found=describe(tok))
        return None

    # --------------------------------------------------------------------------- expressions

    def expression(self, min_prec: int = 0) -> A.Expr:
        """Precedence climbing over :data:`_BINOPS` (spec §3.7), all operators left-associative."""
        left = self.unary() if self.kind in _UNARY_KINDS else self.postfix()
        binops = _BINOPS
        between = A.span_between
        run_prec, run = -1, 0  # the precedence of the run of operators being read, its length
        while True:
            info = binops.get(self.kind)
            if info is None:
                tok = self.tok
                if tok[KIND] is K.IDENT and tok[TEXT].lower() == "isnot" and min_prec <= _P_REL:
                    self.error(M.PARSE_UNSUPPORTED, tok, what="'IsNot'", hint=" (write 'Not a Is b')")
                    self.next()
                    right = self.expression(_P_REL + 1)
                    span = between(left, right)
                    left = A.Unary(span, "Not", A.Binary(span, "Is", left, right))
                    run_prec, run = -1, 0
                    continue
                return left
            prec = info[0]
            if prec < min_prec:
                return left
            self.next()
            if prec == _P_POW:
                right = self.pow_operand()
            else:
                right = self.expression(prec + 1)
            op = info[1]
            if op == "Is":  # (never in a Chain: semantics types its operands as references)
                run_prec, run = -1, 0
            elif prec != run_prec:
                run_prec, run = prec, 1
            else:
                run += 1
            if run > A.CHAIN_MIN:
                left.append(op, right)  # type: ignore[attr-defined]
            elif run == A.CHAIN_MIN:
                left = _chain(left, run - 1, op, right)
            else:
                left = A.Binary(between(left, right), op, left, right)

    def pow_operand(self) -> A.Expr:
        """The right operand of ``^``: a postfix expression, optionally negated (``x ^ -1``)."""
        tok = self.tok
        if tok[KIND] is K.MINUS or tok[KIND] is K.PLUS:
            if not self.deeper(tok, "expressions"):
                return A.ErrorExpr(tok[SPAN])
            self.next()
            operand = self.pow_operand()
            self.depth -= 1
            return A.Unary(self.span_from(tok), tok[KIND].value, operand)
        return self.postfix()

    def unary(self) -> A.Expr:
        tok = self.tok
        k = self.kind
        if k is K.MINUS or k is K.PLUS or k is K.NOT:
            if not self.deeper(tok, "expressions"):
                return A.ErrorExpr(tok[SPAN])
            self.next()
            operand = self.expression(_P_UNARY if k is not K.NOT else _P_REL)
            self.depth -= 1
            return A.Unary(_at(tok).to(operand.span), k.value, operand)
        return self.postfix()

    def postfix(self) -> A.Expr:
        if self.kind is K.IDENT:  # (primary's commonest case, inlined: a third of all calls)
            _, text, _, span = self.next()
            expr: A.Expr = A.Name(span, text)
        else:
            expr = self.primary()
        while True:
            k = self.kind
            if k is K.DOT:
                self.next()
                name = self.word("a member name after '.'")
                if name is None:
                    return expr
                expr = A.MemberAccess(A.span_to(expr, name[SPAN]), expr, name[TEXT])
            elif k is K.LPAREN:
                args = self.arguments()
                expr = A.Invoke(A.span_to(expr, self.prev[SPAN]), expr, args)
            else:
                return expr

    def arguments(self) -> list[A.Expr]:
        """``( [expr {, expr}] )``; the current token is ``(``."""
        self.next()
        args: list[A.Expr] = []
        if self.kind is K.RPAREN:
            self.next()
            return args
        if not self.deeper(self.tok, "expressions"):
            return [A.ErrorExpr(self.tok[SPAN])]  # (arguments unknown: the call's count is not checked)
        while True:
            if self.kind is K.COMMA or self.kind is K.RPAREN:
                self.error(M.PARSE_EXPECTED, self.tok, expected="an argument (arguments cannot be omitted)", found=describe(self.tok))
                break
            args.append(self.expression())
            k = self.kind
            if k is K.COMMA:
                self.next()
                continue
            if k is K.RPAREN:
                self.next()
            elif k is K.COLON and self.peek()[KIND] is K.EQ:
                self.error(M.PARSE_UNSUPPORTED, self.tok, what="named arguments (':=')", hint="")
            else:
                self.error(M.PARSE_EXPECTED, self.tok, expected="',' or ')'", found=describe(self.tok))
            break
        self.depth -= 1
        return args

    def primary(self) -> A.Expr:
        tok = self.tok
        k = self.kind
        if k is K.IDENT:
            self.next()
            return A.Name(tok[SPAN], tok[TEXT])
        if k is K.INTEGER:
            self.next()
            return A.IntegerLiteral(tok[SPAN], tok[VALUE], tok[TEXT])  # type: ignore[arg-type]
        if k is K.STRING:
            self.next()
            return A.StringLiteral(tok[SPAN], tok[VALUE])  # type: ignore[arg-type]
        if k is K.REAL:
            self.next()
            return A.RealLiteral(tok[SPAN], tok[VALUE], tok[TEXT])  # type: ignore[arg-type]
        if k is K.LPAREN:
            if not self.deeper(tok, "parentheses"):
                return A.ErrorExpr(tok[SPAN])
            self.next()
            inner = self.expression()
            self.expect(K.RPAREN, "')'")
            self.depth -= 1
            return inner
        if k is K.TRUE or k is K.FALSE:
            self.next()
            return A.BooleanLiteral(tok[SPAN], k is K.TRUE)
        if k is K.NOTHING:
            self.next()
            return A.NothingLiteral(tok[SPAN])
        if k is K.ME:
            self.next()
            return A.MeExpr(tok[SPAN])
        if k is K.NEW:
            self.next()
            type_ = self.type_ref()
            if type_ is None:
                return A.ErrorExpr(tok[SPAN])
            args = self.arguments() if self.kind is K.LPAREN else None
            return A.New(self.span_from(tok), type_, args)
        if k is K.ADDRESSOF:
            self.next()
            name = self.ident("a procedure name after 'AddressOf'")
            if name is None:
                return A.ErrorExpr(tok[SPAN])
            target: A.Expr = A.Name(name[SPAN], name[TEXT])
            while self.kind is K.DOT:
                self.next()
                member = self.word("a member name after '.'")
                if member is None:
                    break
                target = A.MemberAccess(self.span_from(name), target, member[TEXT])
            return A.AddressOf(self.span_from(tok), target)
        self.error(M.PARSE_EXPECTED_EXPRESSION, tok, found=describe(tok))
        return A.ErrorExpr(tok[SPAN])


def _block_declaration(p: Parser) -> A.Stmt | None:
    return p._declaration_statement()


# Statements that consume their own lines (block statements and declarations).
_BLOCK_STATEMENTS = {
    K.IF: Parser.if_statement,
    K.FOR: Parser.for_statement,
    K.WHILE: Parser.while_statement,
    K.DO: Parser.do_statement,
    K.SELECT: Parser.select_statement,
    K.TRY: Parser.try_statement,
    K.DIM: _block_declaration,
    K.STATIC: _block_declaration,
    K.CONST: _block_declaration,
    K.PUBLIC: _block_declaration,
    K.PRIVATE: _block_declaration,
    K.SHARED: _block_declaration,
}

# One-line statements introduced by a keyword.
_SIMPLE_STATEMENTS = {
    K.GOTO: Parser.goto_statement,
    K.EXIT: Parser.exit_statement,
    K.RETURN: Parser.return_statement,
    K.THROW: Parser.throw_statement,
    K.CALL: Parser.call_statement,
    K.REDIM: Parser.redim_statement,
    K.END: Parser.end_statement,
    K.SET: Parser.set_statement,
    K.GET: Parser.misplaced_keyword,
    K.THEN: Parser.misplaced_keyword,
    K.TO: Parser.misplaced_keyword,
    K.STEP: Parser.misplaced_keyword,
    K.AS: Parser.misplaced_keyword,
    K.UNTIL: Parser.misplaced_keyword,
    K.BYVAL: Parser.misplaced_keyword,
    K.BYREF: Parser.misplaced_keyword,
    K.DELEGATE: Parser.misplaced_keyword,
}
