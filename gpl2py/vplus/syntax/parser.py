"""V+ tokens -> :class:`gpl2py.vplus.syntax.ast.Module`: a recursive-descent parser, line by line.

A file is a sequence of ``.PROGRAM`` ... ``.END`` programs and data sections (``.LOCATIONS``,
``.REALS``, ``.DOUBLES``, ``.STRINGS``).  Inside a program each line is ``[label] [instruction]
[;comment]``; blocks (IF, CASE, DO, WHILE, FOR) span lines and close with their own line.
Expressions follow the User's Guide's order of evaluation (L4324-4349): NOT/COM and unary minus,
then ``* / MOD AND BAND``, then ``+ - OR BOR XOR BXOR``, then the relations; ``:`` composes
locations and binds tightest.  Keywords are recognised by position, never reserved (``belt`` is a
name).  The robot-sandbox simulator's looser dialect (IF without THEN, WHILE without DO, ELSEIF,
ELIF) is read with a warning naming it.

Errors never raise: a bad line is reported at its column, skipped, and the parse goes on.
"""

from __future__ import annotations

from collections.abc import Callable

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.messages import Message
from gpl2py.source import SourceFile, Span
from gpl2py.vplus import messages as M
from gpl2py.vplus.syntax import ast as A
from gpl2py.vplus.syntax.keywords import GENERIC, MODIFIERS, TIER3, UNIT, ZERO_ARG
from gpl2py.vplus.syntax.lexer import lex
from gpl2py.vplus.syntax.tokens import Comment, Kind, Token

_REL = frozenset(("==", "<", ">", "<=", "=<", ">=", "=>", "<>"))
_ADD = frozenset(("+", "-", "OR", "BOR", "XOR", "BXOR"))
_MUL = frozenset(("*", "/", "MOD", "AND", "BAND"))
_LOGICAL = frozenset(("AND", "OR", "XOR"))
_SECTIONS = frozenset(("LOCATIONS", "REALS", "DOUBLES", "STRINGS"))
_DECL = frozenset(("AUTO", "LOCAL", "GLOBAL"))
_QUALIFIERS = frozenset(("DOUBLE", "REAL", "LOC"))
#: How deep an expression may nest (parentheses, arguments, indices, unary operators) before it is
#: refused: the parser recurses about 12 frames per level, within the pipeline's 990 frames
#: (with MAX_BLOCKS blocks around it).
MAX_DEPTH = 40
#: How many binary operators an expression may chain (in all its nesting levels together): the
#: parser loops over a chain, but the tree is as deep as the chain and the checks and the lowering
#: walk it recursively.
MAX_CHAIN = 120


#: How many blocks may nest in a program (as TMscript's parser allows): the parser and the later
#: passes recurse per block, about 6 frames a level here, and an expression at the innermost
#: level still needs its own (MAX_DEPTH); CPython compiles at most 20 loops around a statement
#: anyway (the lowering's GPL4702).
MAX_BLOCKS = 50


class _TooDeep(Exception):
    """Abandons a program whose blocks nest past :data:`MAX_BLOCKS`, after its one error."""


class _LineError(Exception):
    """Abandons the current line after its error was reported."""


def parse(src: SourceFile, sink: DiagnosticSink) -> A.Module:
    """The syntax tree of one V+ file; every problem is a diagnostic in ``sink``."""
    lexed = lex(src, sink)
    return _Parser(src.path, lexed.tokens, lexed.comments, sink).module()


class _Parser:
    def __init__(self, path: str, tokens: list[Token], comments: list[Comment], sink: DiagnosticSink) -> None:
        self.path = path
        self.sink = sink
        self.lines: list[list[Token]] = []
        cur: list[Token] = []
        for t in tokens:
            if t.kind is Kind.NEWLINE:
                self.lines.append(cur)
                cur = []
            elif t.kind is not Kind.EOF:
                cur.append(t)
        self.eof = tokens[-1]
        self.comment_at = {c.span.line: c for c in comments}
        self.n = 0  # the current line's index in self.lines
        self.toks: list[Token] = []
        self.i = 0
        self.depth = 0
        self.chain = 0  # binary operators on the way to the current operand (MAX_CHAIN)
        self.pending: list[Comment] = []  # full-line comments waiting for the next statement
        self.nested = 0  # how many blocks enclose the current line
        self.no_compose = False  # in a VALUE list, where ':' ends the list

    # --- lines ------------------------------------------------------------------------------

    def _line_no(self, n: int) -> int:
        return n + 1

    def _comment(self, n: int) -> Comment | None:
        return self.comment_at.get(n + 1)

    def _begin(self, n: int) -> None:
        self.toks = self.lines[n]
        self.i = 0

    @property
    def tok(self) -> Token:
        if self.i < len(self.toks):
            return self.toks[self.i]
        return self._end_token()

    def _end_token(self) -> Token:
        col = self.toks[-1].span.end_col if self.toks else 1
        return Token(Kind.NEWLINE, "", _point(self.path, self.n + 1, col))

    def _peek(self, k: int = 1) -> Token:
        j = self.i + k
        return self.toks[j] if j < len(self.toks) else self._end_token()

    def _next(self) -> Token:
        t = self.tok
        self.i += 1
        return t

    def _at_end(self) -> bool:
        return self.i >= len(self.toks)

    def _error(self, message: Message, span: Span, **args: object) -> None:
        self.sink.report(message, span, **args)

    def _fail(self, what: str) -> None:
        t = self.tok
        self._error(M.EXPECTED, t.span, what=what, found=t.shown())
        raise _LineError

    def _expect_op(self, op: str) -> Token:
        if not self.tok.is_op(op):
            self._fail(f"'{op}'")
        return self._next()

    def _expect_end(self) -> None:
        if not self._at_end():
            self._fail("end of line")

    # --- the file -----------------------------------------------------------------------------

    def module(self) -> A.Module:
        mod = A.Module(self.path, [], [])
        outside_reported = False
        while self.n < len(self.lines):
            toks = self.lines[self.n]
            c = self._comment(self.n)
            if not toks:
                if c is not None:
                    self.pending.append(c)
                self.n += 1
                continue
            first = toks[0]
            if first.kind is Kind.DIRECTIVE and first.upper == "PROGRAM":
                prog = self._program()
                if prog is not None:
                    mod.programs.append(prog)
                outside_reported = False
                continue
            if first.kind is Kind.DIRECTIVE and first.upper in _SECTIONS:
                mod.comments.extend(self.pending)
                self.pending = []
                mod.data.append(self._section(first))
                continue
            if first.kind is Kind.DIRECTIVE and first.upper != "END":
                self._error(M.UNKNOWN_SECTION, first.span, name="." + first.text)
                self._skip_to_end()
                continue
            if not outside_reported:
                self._error(M.OUTSIDE_PROGRAM, first.span)
                outside_reported = True
            self.n += 1
        mod.comments.extend(self.pending)
        self.pending = []
        return mod

    def _skip_to_end(self) -> None:
        self.n += 1
        while self.n < len(self.lines):
            toks = self.lines[self.n]
            self.n += 1
            if toks and toks[0].kind is Kind.DIRECTIVE and toks[0].upper == "END":
                return

    def _program(self) -> A.Program | None:
        start = self.n
        self._begin(start)
        head = self._next()
        comments = self.pending
        self.pending = []
        c = self._comment(start)
        if c is not None:
            comments.append(c)
        name, name_span, params = "", head.span, []
        try:
            if self.tok.kind is not Kind.NAME or self.tok.sigil:
                self._fail("a program name")
            nt = self._next()
            name, name_span = nt.text, nt.span
            if self.tok.is_op("("):
                self._next()
                params = self._params()
            self._expect_end()
        except _LineError:
            pass
        self.n += 1
        prog = A.Program(head.span, name, name_span, params, [], [], comments)
        try:
            body, end = self._block(set(), prog)
        except _TooDeep:  # (one error; the rest of the program is skipped to its .END)
            body, end = [], None
            while self.n < len(self.lines):
                toks = self.lines[self.n]
                if toks and toks[0].kind is Kind.DIRECTIVE:
                    if toks[0].upper == "END":
                        self.n += 1
                        end = toks[0]
                    break
                self.n += 1
            self.pending = []
        if end is None:
            self._error(M.MISSING_DOT_END, name_span, name=name or ".PROGRAM")
        else:
            prog.end_span = end.span
        prog.trailing = self.pending
        self.pending = []
        executable = False
        for s in body:
            if not isinstance(s, A.Decl):
                executable = executable or bool(getattr(s, "word", "x"))  # (a labelled no-op is not)
            elif executable:
                self._error(M.LATE_DECLARATION, s.span, kind=s.kind)
        prog.decls = [s for s in body if isinstance(s, A.Decl)]
        prog.body = [s for s in body if not isinstance(s, A.Decl)]
        if not name:
            return None
        return prog

    def _params(self) -> list[A.Param]:
        params: list[A.Param] = []
        if self.tok.is_op(")"):
            self._next()
            return params
        while True:
            t = self.tok
            if t.kind is not Kind.NAME:
                self._fail("a parameter name")
            self._next()
            var = A.Var(t.span, t.sigil, t.text)
            if self.tok.is_op("["):
                self._next()
                self._expect_op("]")
                var.whole = True
            params.append(A.Param(t.span, var))
            if self.tok.is_op(","):
                self._next()
                continue
            self._expect_op(")")
            return params

    def _section(self, head: Token) -> A.DataSection:
        kind = head.upper
        section = A.DataSection(head.span, kind, [])
        self.n += 1
        while self.n < len(self.lines):
            toks = self.lines[self.n]
            self._begin(self.n)
            self.n += 1
            if not toks:
                continue
            if toks[0].kind is Kind.DIRECTIVE:
                if toks[0].upper == "END":
                    return section
                self.n -= 1
                return section
            datum = self._datum(kind)
            if datum is not None:
                section.data.append(datum)
        return section

    def _datum(self, kind: str) -> A.Datum | None:
        t = self._next()
        if t.kind is not Kind.NAME:
            self._error(M.BAD_DATA_LINE, t.span, section="." + kind, reason="a variable name must come first")
            return None
        var = A.Var(t.span, t.sigil, t.text)
        try:
            if self.tok.is_op("["):
                self._next()
                var.index = self._expr_list("]")
            if kind == "STRINGS":
                if self.tok.kind is not Kind.STRING:
                    self._fail("a string")
                s = self._next()
                self._expect_end()
                return A.Datum(t.span, var, [], s.text)
            values: list[float] = []
            while not self._at_end():
                if self.tok.is_op(","):
                    self._next()
                    continue
                sign = 1.0
                if self.tok.is_op("-", "+"):
                    sign = -1.0 if self._next().text == "-" else 1.0
                if self.tok.kind is not Kind.NUMBER:
                    self._fail("a number")
                values.append(sign * self._next().value)
        except _LineError:
            return None
        want = {"REALS": (1,), "DOUBLES": (1,)}.get(kind)
        if want is not None and len(values) not in want:
            self._error(M.BAD_DATA_LINE, t.span, section="." + kind, reason=f"one value expected, {len(values)} given")
            return None
        if kind == "LOCATIONS" and not var.sigil and len(values) != 6:
            self._error(M.BAD_DATA_LINE, t.span, section="." + kind,
                        reason=f"a transformation has 6 values (x y z yaw pitch roll), {len(values)} given")
            return None
        if kind == "LOCATIONS" and var.sigil not in ("", "#"):
            self._error(M.BAD_DATA_LINE, t.span, section="." + kind, reason="only locations belong here")
            return None
        return A.Datum(t.span, var, values)

    # --- blocks -------------------------------------------------------------------------------

    def _block(self, stop: set[str], prog: A.Program) -> tuple[list[A.Stmt], Token | None]:
        """Lines up to one whose first word is in ``stop`` (returned, the line not consumed) or up
        to ``.END`` (returned as the terminator, consumed when ``stop`` is empty)."""
        body: list[A.Stmt] = []
        if stop and self.nested >= MAX_BLOCKS:
            head = self.lines[self.n - 1] if 0 < self.n <= len(self.lines) else []
            self._error(M.BLOCKS_TOO_DEEP, head[0].span if head else self.tok.span, limit=MAX_BLOCKS)
            raise _TooDeep
        self.nested += bool(stop)
        try:
            return self._lines(stop, prog, body)
        finally:
            self.nested -= bool(stop)

    def _lines(self, stop: set[str], prog: A.Program, body: list[A.Stmt]) -> tuple[list[A.Stmt], Token | None]:
        while self.n < len(self.lines):
            toks = self.lines[self.n]
            c = self._comment(self.n)
            if not toks:
                if c is not None:
                    self.pending.append(c)
                self.n += 1
                continue
            first = toks[0]
            if first.kind is Kind.DIRECTIVE:
                if first.upper == "END":
                    if not stop:
                        self.n += 1
                    return body, first
                return body, None  # .PROGRAM or a section: the program has no .END
            self._begin(self.n)
            label = self._label()
            word = self.tok.upper if self.tok.kind is Kind.NAME and not self.tok.sigil else ""
            if word in stop and not self._peek().is_op("=", "["):  # (value = 3 is an assignment)
                if label is not None or self.pending:  # a label on the closing line, comments above
                    body.append(A.Instr(self.tok.span, "", label=label, comments=self.pending))
                    self.pending = []
                return body, self.tok
            if word in ("END", "ELSE", "UNTIL", "VALUE", "ANY", "ELSEIF", "ELIF") and not self._peek().is_op("=", "["):
                self._error(M.NO_BLOCK, self.tok.span, word=word,
                            block="DO" if word == "UNTIL" else "CASE" if word in ("VALUE", "ANY") else
                            "IF" if word != "END" else "IF, CASE, WHILE or FOR")
                self.n += 1
                continue
            stmt = self._statement(prog, label)
            if stmt is not None:
                if label is not None:
                    stmt.label = label
                body.append(stmt)
        return body, None

    def _label(self) -> int | None:
        t = self.tok
        if t.kind is not Kind.NUMBER:
            return None
        self._next()
        if not t.text.isdigit() or int(t.text) > 65535:
            self._error(M.BAD_LABEL, t.span, text=t.text)
            return None
        return int(t.text)

    def _statement(self, prog: A.Program, label: int | None) -> A.Stmt | None:
        """The statement starting at the current line (which it consumes, with any block lines)."""
        n = self.n
        pending = self.pending
        self.pending = []
        t = self.tok
        if self._at_end():  # a label alone on its line
            self.n += 1
            stmt: A.Stmt | None = A.Instr(t.span, "") if label is not None else None
        else:
            try:
                stmt = self._dispatch(prog)
            except _LineError:  # (kept in place, empty: a translation that keeps the error
                stmt = A.Instr(t.span, "")  # makes the line raise it: gpl2py.kept)
                if self.n == n:
                    self.n += 1
        if stmt is not None:
            stmt.comments = pending + stmt.comments
            c = self._comment(n)
            if c is not None:
                stmt.comments.append(c)
        else:
            self.pending = pending + self.pending
        return stmt

    def _dispatch(self, prog: A.Program) -> A.Stmt:
        t = self.tok
        if t.kind is not Kind.NAME:
            self._fail("an instruction")
        nxt = self._peek()
        word = t.upper if not t.sigil else ""
        if t.sigil or (nxt.is_op("=", "[") and word not in ("DECOMPOSE",)) or not word:
            return self._one_line(self._assignment())
        if word in _DECL:
            if self.nested:
                self._error(M.LATE_DECLARATION, t.span, kind=word)
            return self._one_line(self._declaration())
        handler = _HANDLERS.get(word)
        if handler is not None:
            return handler(self, prog)  # type: ignore[no-any-return]
        if word in GENERIC or word in TIER3:
            return self._one_line(self._generic())
        self._error(M.UNKNOWN_INSTRUCTION, t.span, name=t.text)
        raise _LineError

    def _one_line(self, stmt: A.Stmt) -> A.Stmt:
        self._expect_end()
        self.n += 1
        return stmt

    # --- simple statements --------------------------------------------------------------------

    def _assignment(self) -> A.Stmt:
        target = self._var()
        self._expect_op("=")
        value = self._expr()
        return A.Assign(target.span.to(value.span), target, value)

    def _var(self) -> A.Var:
        t = self.tok
        if t.kind is not Kind.NAME:
            self._fail("a variable")
        self._next()
        var = A.Var(t.span, t.sigil, t.text)
        if self.tok.is_op("["):
            self._next()
            if self.tok.is_op("]"):
                var.whole = True
                end = self._next()
            else:
                var.index = self._expr_list("]")
                end = self.toks[self.i - 1]
            var.span = t.span.to(end.span)
        return var

    def _declaration(self) -> A.Decl:
        head = self._next()
        qualifier = ""
        if self.tok.is_word(*_QUALIFIERS) and self._peek().kind is Kind.NAME:
            qualifier = self._next().upper
        items: list[A.DeclItem] = []
        while True:
            t = self.tok
            if t.kind is not Kind.NAME:
                self._fail("a variable name")
            self._next()
            var = A.Var(t.span, t.sigil, t.text)
            dims = None
            if self.tok.is_op("["):
                self._next()
                if self.tok.is_op("]"):
                    self._next()
                    var.whole = True
                else:
                    dims = self._expr_list("]")
            items.append(A.DeclItem(t.span, var, dims))
            if not self.tok.is_op(","):
                break
            self._next()
        return A.Decl(head.span, head.upper, qualifier, items)

    def _generic(self) -> A.Instr:
        head = self._next()
        word = head.upper
        instr = A.Instr(head.span, word, tier3=word in TIER3)
        if word in TIER3:
            self._error(M.UNSUPPORTED_INSTRUCTION, head.span, name=head.text)
        if self.tok.is_op("(") and word in UNIT and self._unit_follows():
            self._next()
            instr.unit = self._items(")")
        if not self._at_end() and not self.tok.is_op("="):
            instr.args = self._items(None)
        if self.tok.is_op("="):
            self._next()
            instr.target = instr.args
            instr.args = self._items(None)
        while self.tok.is_word(*MODIFIERS):
            instr.modifiers.append(self._next().upper)
        return instr

    def _unit_follows(self) -> bool:
        """At ``(``: whether it opens a unit (``ACCEL (1) 100``) rather than a value (``ACCEL (50)``):
        a unit is followed by more of the instruction; for the I/O instructions always a unit."""
        if self.toks[self.i - 1].upper not in ("ACCEL", "PROMPT"):
            return True
        depth, j = 0, self.i
        while j < len(self.toks):
            t = self.toks[j]
            if t.is_op("("):
                depth += 1
            elif t.is_op(")"):
                depth -= 1
                if depth == 0:
                    break
            j += 1
        after = self.toks[j + 1] if j + 1 < len(self.toks) else None
        return after is not None and after.kind is not Kind.OP

    def _items(self, close: str | None) -> list[A.Expr | None]:
        """Comma-separated values and format items, empty positions None, up to ``close`` (consumed)
        or to the end of the expression list."""
        items: list[A.Expr | None] = []
        if close is not None and self.tok.is_op(close):
            self._next()
            return items
        while True:
            if self.tok.is_op(",") or (close is not None and self.tok.is_op(close)) or self._at_end() \
                    or self.tok.is_op("="):
                items.append(None)
            else:
                items.append(self._item())
            if self.tok.is_op(","):
                self._next()
                continue
            break
        if close is not None:
            self._expect_op(close)
        if items == [None]:
            return []
        return items

    def _item(self) -> A.Expr:
        """A value or an output format (``/S``, ``/I0``, ``/C2``)."""
        t = self.tok
        if t.is_op("/"):
            nt = self._peek()
            if nt.kind is Kind.NAME and not nt.sigil and not nt.spaced:
                self._next()
                self._next()
                letter, arg = nt.text[0].upper(), nt.text[1:]
                return A.Format(t.span.to(nt.span), letter, arg)
        return self._expr()

    # --- control statements -------------------------------------------------------------------

    def _if(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        cond = self._expr()
        if self.tok.is_word("GOTO"):
            self._next()
            target, tspan = self._label_ref()
            return self._one_line(A.IfGoto(head.span, cond, target, tspan))
        if self.tok.is_word("THEN"):
            self._next()
        elif self._at_end():
            self._error(M.DIALECT_IF_THEN, head.span)
        else:
            self._fail("THEN")
        self._expect_end()
        return self._if_rest(head, cond, prog)

    def _if_rest(self, head: Token, cond: A.Expr, prog: A.Program) -> A.Stmt:
        stmt = A.If(head.span, cond, [], None)
        self.n += 1
        stmt.then, end = self._block({"ELSE", "ELSEIF", "ELIF", "END"}, prog)
        if end is None or end.kind is Kind.DIRECTIVE:
            self._error(M.BLOCK_NOT_CLOSED, head.span, block="IF", where=".END")
            return stmt
        word = end.upper
        if word in ("ELSEIF", "ELIF"):
            self._error(M.DIALECT_ELSEIF, end.span, word=end.text)
            self._next()
            cond2 = self._expr()
            if self.tok.is_word("THEN"):
                self._next()
            self._expect_end()
            inner = self._if_rest(end, cond2, prog)  # consumes up to and with the shared END
            stmt.orelse = [inner]
            return stmt
        if word == "ELSE":
            self._next()
            self._expect_end()
            self.n += 1
            stmt.orelse, end = self._block({"END"}, prog)
            if end is None or end.kind is Kind.DIRECTIVE:
                self._error(M.BLOCK_NOT_CLOSED, head.span, block="IF", where=".END")
                return stmt
        self._close()
        return stmt

    def _close(self) -> None:
        """At a block's END (or UNTIL handled by the caller): the END line is consumed."""
        self._next()
        self._expect_end_soft()
        self.n += 1

    def _expect_end_soft(self) -> None:
        if not self._at_end():
            t = self.tok
            self._error(M.EXPECTED, t.span, what="end of line", found=t.shown())

    def _case(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        subject = self._expr()
        if not self.tok.is_word("OF"):
            self._fail("OF")
        self._next()
        self._expect_end()
        stmt = A.Case(head.span, subject, [])
        self.n += 1
        body, end = self._block({"VALUE", "ANY", "END"}, prog)
        for s in body:  # lines before the first VALUE
            self._error(M.EXPECTED, s.span, what="VALUE, ANY or END", found="an instruction")
        while end is not None and end.kind is not Kind.DIRECTIVE and end.upper != "END":
            arm_head = self._next()
            values: list[A.Expr] | None = [] if arm_head.upper == "VALUE" else None
            if stmt.arms and stmt.arms[-1].values is None:  # after ANY
                self._error(M.EXPECTED, arm_head.span, what="END after ANY", found=arm_head.shown())
            try:
                if arm_head.upper == "VALUE":  # (the ':' ends the list: no location composition)
                    self.no_compose = True
                    try:
                        values = [self._expr()]
                        while self.tok.is_op(","):
                            self._next()
                            values.append(self._expr())
                    finally:
                        self.no_compose = False
                    self._expect_op(":")
                elif self.tok.is_op(":"):
                    self._next()
                self._expect_end()
            except _LineError:
                pass
            arm = A.CaseArm(arm_head.span, values, [])
            c = self._comment(self.n)
            if c is not None:
                arm.comments.append(c)
            self.n += 1
            arm.body, end = self._block({"VALUE", "ANY", "END"}, prog)
            stmt.arms.append(arm)
        if end is None or end.kind is Kind.DIRECTIVE:
            self._error(M.BLOCK_NOT_CLOSED, head.span, block="CASE", where=".END")
            return stmt
        self._close()
        return stmt

    def _do(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        self._expect_end()
        stmt = A.DoUntil(head.span, [], A.Num(head.span, 0.0, "0"))
        self.n += 1
        stmt.body, end = self._block({"UNTIL"}, prog)
        if end is None or end.kind is Kind.DIRECTIVE:
            self._error(M.BLOCK_NOT_CLOSED, head.span, block="DO", where=".END")
            return stmt
        self._next()
        try:
            stmt.cond = self._expr()
            self._expect_end()
        except _LineError:
            pass
        self.n += 1
        return stmt

    def _while(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        cond = self._expr()
        if self.tok.is_word("DO"):
            self._next()
        elif self._at_end():
            self._error(M.DIALECT_WHILE_DO, head.span)
        else:
            self._fail("DO")
        self._expect_end()
        stmt = A.While(head.span, cond, [])
        return self._loop_body(stmt, head, "WHILE", prog)

    def _loop_body(self, stmt: A.While | A.For, head: Token, block: str, prog: A.Program) -> A.Stmt:
        self.n += 1
        stmt.body, end = self._block({"END"}, prog)
        if end is None or end.kind is Kind.DIRECTIVE:
            self._error(M.BLOCK_NOT_CLOSED, head.span, block=block, where=".END")
            return stmt
        self._close()
        return stmt

    def _for(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        var = self._var()
        self._expect_op("=")
        start = self._expr()
        if not self.tok.is_word("TO"):
            self._fail("TO")
        self._next()
        stop = self._expr()
        step = None
        if self.tok.is_word("STEP"):
            self._next()
            step = self._expr()
        self._expect_end()
        stmt = A.For(head.span, var, start, stop, step, [])
        return self._loop_body(stmt, head, "FOR", prog)

    def _label_ref(self) -> tuple[int, Span]:
        t = self.tok
        if t.kind is not Kind.NUMBER or not t.text.isdigit() or int(t.text) > 65535:
            self._fail("a step label")
        self._next()
        return int(t.text), t.span

    def _goto(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        target, tspan = self._label_ref()
        return self._one_line(A.Goto(head.span, target, tspan))

    def _exit(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        count = None if self._at_end() else self._expr()
        return self._one_line(A.Exit(head.span, head.upper, count))

    def _call(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        if head.upper == "CALLS":
            e = self._primary()
            if isinstance(e, A.Call) and e.sigil == "$":
                dyn: A.Expr = A.Var(e.span, "$", e.name)
                return self._one_line(A.CallStmt(head.span, "", e.span, e.args, dynamic=dyn))
            self._expect_op("(")
            args = self._items(")")
            return self._one_line(A.CallStmt(head.span, "", e.span, args, dynamic=e))
        t = self.tok
        if t.kind is not Kind.NAME or t.sigil:
            self._fail("a program name")
        self._next()
        args: list[A.Expr | None] = []
        if self.tok.is_op("("):
            self._next()
            args = self._items(")")
        return self._one_line(A.CallStmt(head.span, t.text, t.span, args))

    def _return(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        return self._one_line(A.Return(head.span, head.upper))

    def _execute(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        task = None
        if not (self.tok.kind is Kind.NAME and not self.tok.sigil and self._peek().is_op("(")):
            task = self._expr()
            if self.tok.is_op(","):
                self._next()
        t = self.tok
        if t.kind is not Kind.NAME or t.sigil:
            self._fail("a program name")
        self._next()
        args: list[A.Expr | None] = []
        if self.tok.is_op("("):
            self._next()
            args = self._items(")")
        rest: list[A.Expr | None] = []
        if self.tok.is_op(","):
            self._next()
            rest = self._items(None)
        return self._one_line(A.Execute(head.span, task, t.text, t.span, args, rest))

    def _react(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        word = head.upper
        signal = None
        if word != "REACTE":
            signal = self._expr()
            self._expect_op(",")
        t = self.tok
        if word == "REACTE" and self._at_end():
            return self._one_line(A.React(head.span, word, None, "", head.span, [], None))
        if t.kind is not Kind.NAME or t.sigil:
            self._fail("a program name")
        self._next()
        args: list[A.Expr | None] = []
        if self.tok.is_op("("):
            self._next()
            args = self._items(")")
        priority = None
        if word != "REACTE" and self.tok.is_op(","):
            self._next()
            priority = self._expr()
        return self._one_line(A.React(head.span, word, signal, t.text, t.span, args, priority))

    def _set(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        target = self._var()
        self._expect_op("=")
        value = self._expr()
        return self._one_line(A.SetLoc(head.span.to(value.span), target, value))

    def _here(self, prog: A.Program) -> A.Stmt:
        head = self._next()
        e = self._expr()
        chain: list[A.Expr] = []
        while isinstance(e, A.Binary) and e.op == ":":
            chain.insert(0, e.right)
            e = e.left
        chain.insert(0, e)
        target = chain.pop()
        if not isinstance(target, A.Var):
            self._error(M.EXPECTED, target.span, what="a location variable", found="an expression")
            raise _LineError
        return self._one_line(A.Here(head.span, chain, target))

    # --- expressions --------------------------------------------------------------------------

    def _expr_list(self, close: str) -> list[A.Expr]:
        out = [self._expr()]
        while self.tok.is_op(","):
            self._next()
            out.append(self._expr())
        self._expect_op(close)
        return out

    def _expr(self) -> A.Expr:
        self.depth += 1
        try:
            if self.depth > MAX_DEPTH:
                self._error(M.TOO_DEEP, self.tok.span)
                raise _LineError
            return self._relation()
        finally:
            self.depth -= 1

    def _relation(self) -> A.Expr:
        left = self._additive()
        ops = 0
        try:
            while self.tok.kind is Kind.OP and self.tok.text in _REL:
                op_tok = self._next()
                op = op_tok.text
                ops += self._deeper(op_tok)
                right = self._additive()
                for side in (left, right):
                    if isinstance(side, A.Binary) and side.op in _LOGICAL:
                        self._error(M.PRECEDENCE, side.span, op=side.op, rel=op, left=_shown(side.left))
                        break
                left = A.Binary(left.span.to(right.span), op, left, right)
        finally:
            self.chain -= ops
        return left

    def _deeper(self, at: Token) -> int:
        """One more operator in a chain: the tree is one level deeper (``a + b + c`` is
        ``(a + b) + c``), and every later pass walks it recursively: :data:`MAX_CHAIN` (a
        1,000-term sum was a RecursionError)."""
        self.chain += 1
        if self.chain > MAX_CHAIN:
            self.chain -= 1
            self._error(M.TOO_DEEP, at.span)
            raise _LineError
        return 1

    def _binop(self, ops: frozenset[str]) -> str | None:
        t = self.tok
        if t.kind is Kind.OP and t.text in ops:
            return t.text
        if t.kind is Kind.NAME and not t.sigil and t.upper in ops:
            return t.upper
        return None

    def _additive(self) -> A.Expr:
        return self._level(_ADD, self._multiplicative)

    def _multiplicative(self) -> A.Expr:
        return self._level(_MUL, self._unary)

    def _level(self, ops: frozenset[str], operand: Callable[[], A.Expr]) -> A.Expr:
        """One level of the precedence table: operands joined left to right by ``ops``."""
        left = operand()
        count = 0
        try:
            while (op := self._binop(ops)) is not None:
                count += self._deeper(self._next())
                right = operand()
                left = A.Binary(left.span.to(right.span), op, left, right)
        finally:
            self.chain -= count
        return left

    def _unary(self) -> A.Expr:
        t = self.tok
        if t.is_op("-", "+") or t.is_word("NOT", "COM"):
            self._next()
            self.depth += 1
            try:
                if self.depth > MAX_DEPTH:
                    self._error(M.TOO_DEEP, t.span)
                    raise _LineError
                operand = self._unary()
            finally:
                self.depth -= 1
            if t.text == "+":
                return operand
            return A.Unary(t.span.to(operand.span), t.upper if t.kind is Kind.NAME else t.text, operand)
        return self._compose()

    def _compose(self) -> A.Expr:
        left = self._primary()
        count = 0
        try:
            while self.tok.is_op(":") and not self.no_compose:
                count += self._deeper(self._next())
                right = self._primary()
                left = A.Binary(left.span.to(right.span), ":", left, right)
        finally:
            self.chain -= count
        return left

    def _primary(self) -> A.Expr:
        t = self.tok
        if t.kind is Kind.NUMBER:
            self._next()
            return A.Num(t.span, t.value, t.text)
        if t.kind is Kind.STRING:
            self._next()
            return A.Str(t.span, t.text)
        if t.is_op("("):
            self._next()
            inner = self._expr()
            end = self._expect_op(")")
            return A.Paren(t.span.to(end.span), inner)
        if t.kind is Kind.NAME:
            self._next()
            if self.tok.is_op("("):
                return self._call_args(t)
            if self.tok.is_op("["):
                self.i -= 1
                return self._var()
            if (t.sigil + t.upper) in ZERO_ARG:
                return A.Call(t.span, t.sigil, t.text, [], parens=False)
            return A.Var(t.span, t.sigil, t.text)
        self._fail("a value")
        raise AssertionError  # (unreachable: _fail raises)

    def _call_args(self, name: Token) -> A.Expr:
        self._next()  # (
        call = A.Call(name.span, name.sigil, name.text, [])
        if name.upper in ("SHIFT", "SCALE") and not name.sigil:
            call.args = [self._expr()]
            if not self.tok.is_word("BY"):
                self._fail("BY")
            self._next()
            call.by = self._items(")")
        else:
            call.args = self._items(")")
        call.span = name.span.to(self.toks[self.i - 1].span)
        return call


def _point(path: str, line: int, col: int) -> Span:
    from gpl2py.source import make_span

    return make_span(path, line, col, line, col)


def _shown(e: A.Expr) -> str:
    if isinstance(e, A.Var):
        return e.shown
    if isinstance(e, A.Num):
        return e.text
    if isinstance(e, A.Call):
        return f"{e.sigil}{e.name}(...)" if e.parens else e.sigil + e.name
    return "..."


_HANDLERS = {
    "IF": _Parser._if, "CASE": _Parser._case, "DO": _Parser._do, "WHILE": _Parser._while,
    "FOR": _Parser._for, "GOTO": _Parser._goto, "EXIT": _Parser._exit, "NEXT": _Parser._exit,
    "CALL": _Parser._call, "CALLS": _Parser._call, "RETURN": _Parser._return, "RETURNE": _Parser._return,
    "EXECUTE": _Parser._execute, "REACT": _Parser._react, "REACTI": _Parser._react,
    "REACTE": _Parser._react, "SET": _Parser._set, "HERE": _Parser._here,
}
