"""Tokens -> the TMscript tree (spec §2), by recursive descent with C precedence (spec §1.7).

Two entry points: :func:`parse_script` for a script project (``define``, ``main``, ``closestop``,
``errorstop``, functions) and :func:`parse_packet` for a statement list (a Listen-node packet, a
Script node).  A syntax error is reported and the parser skips to the next line, so one run
reports every bad line (the Listen node replies ``ERROR;`` with all of them, manual L17813).

Comments (the lexer's, in order) are attached as the parse meets them (:meth:`Parser.take`): a
statement takes those before its first token and those after it on its last line; a block those
after its ``{`` on that line (``opening``) and those after its last statement through its ``}``
line (``closing``); a top-level item those before it; the script those after its last item.  So
every comment lands on exactly one node, in source order (see ``ast``'s module doc).
"""

from __future__ import annotations

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.source import Span
from gpl2py.tmscript import messages as M
from gpl2py.tmscript.syntax import ast as A
from gpl2py.tmscript.syntax.lexer import PRIMITIVE_TYPES, Comment, Token, describe, tokenize

ASSIGN_OPS = frozenset({"=", "+=", "-=", "*=", "/=", "%=", "<<=", ">>=", "&=", "^=", "|="})
#: Binary operators by precedence level, loosest first (spec §1.7).
LEVELS: tuple[tuple[str, ...], ...] = (
    ("||",), ("&&",), ("|",), ("^",), ("&",), ("==", "!="), ("<", "<=", ">", ">="), ("<<", ">>"),
    ("+", "-"), ("*", "/", "%"),
)
PRECEDENCE = {op: level for level, ops in enumerate(LEVELS) for op in ops}
RELATIONAL = frozenset({"<", "<=", ">", ">=", "==", "!="})
#: How deep parentheses, unary operators and blocks may nest, and how many binary operators one
#: chain may have, before the parser refuses: the later phases recurse on the tree, and a
#: translation has a fixed stack (gpl2py.transpile.PIPELINE_FRAMES); and each operator is a call in
#: the Python, whose parser takes at most 200 nested parentheses (a chain of 200 ``&&`` was Python
#: that did not compile).  Not limits of TMscript's.
MAX_DEPTH = 50
MAX_CHAIN = 100


class _Bail(Exception):
    """A syntax error was reported: skip to the end of the line."""


class Parser:
    def __init__(self, toks: list[Token], sink: DiagnosticSink, comments: list[Comment] | None = None) -> None:
        self.toks, self.pos, self.sink, self.depth, self.chain = toks, 0, sink, 0, 0
        self.comments = comments or []
        self.taken = 0  # comments[:taken] are attached

    # --- comments -------------------------------------------------------------------------------
    def take(self, before: Token | None = None, through: int | None = None) -> tuple[Comment, ...]:
        """The comments not attached yet that start before ``before`` and on line ``through`` or
        above (no bound for None), with the rest of a ``/* */`` comment whose first line is
        taken."""
        cs, i = self.comments, self.taken
        if i == len(cs):
            return ()
        first = i
        while i < len(cs):
            span = cs[i].span
            if before is not None and (span.line, span.col) >= (before.span.line, before.span.col):
                break
            if through is not None and span.line > through:
                break
            i += 1
        while first < i < len(cs) and cs[i].cont:
            i += 1
        self.taken = i
        return tuple(cs[first:i]) if i > first else ()

    # --- tokens ---------------------------------------------------------------------------------
    @property
    def tok(self) -> Token:
        return self.toks[self.pos]

    def peek(self, k: int = 1) -> Token:
        return self.toks[min(self.pos + k, len(self.toks) - 1)]

    def next(self) -> Token:
        t = self.toks[self.pos]
        if t.kind != "eof":
            self.pos += 1
        return t

    def accept_op(self, text: str) -> Token | None:
        if self.tok.is_op(text):
            return self.next()
        return None

    def expect_op(self, text: str) -> Token:
        if not self.tok.is_op(text):
            self.fail(M.TM_EXPECTED, self.tok.span, expected=f"'{text}'", found=describe(self.tok))
        return self.next()

    def fail(self, message: M.Message, span: Span, **args: object) -> None:  # type: ignore[name-defined]
        self.sink.report(message, span, **args)
        raise _Bail

    def skip_nl(self) -> None:
        while self.tok.kind == "nl":
            self.next()

    def end_line(self) -> None:
        if self.tok.kind in ("nl", "eof") or self.tok.is_op("}"):
            if self.tok.kind == "nl":
                self.next()
            return
        self.fail(M.TM_TRAILING, self.tok.span, found=describe(self.tok))

    def recover(self) -> None:
        """Skip the rest of the line (and of a block left open on it)."""
        while self.tok.kind not in ("nl", "eof"):
            self.next()
        if self.tok.kind == "nl":
            self.next()

    def nested(self, span: Span) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            self.fail(M.TM_NOT_HERE, span, what="nesting this deep", where=f"(more than {MAX_DEPTH} levels)")

    # --- entry points ---------------------------------------------------------------------------
    def script(self, span: Span) -> A.Script:
        out = A.Script(span, packet=False)
        self.skip_nl()
        while self.tok.kind != "eof":
            taken = self.taken
            try:
                self.top_item(out)
            except _Bail:
                self.depth = 0
                self.taken = taken  # (the comments of what was skipped go with what follows)
                self.recover()
            self.skip_nl()
        out.closing = self.take()
        return out

    def packet(self, span: Span) -> A.Script:
        out = A.Script(span, packet=True)
        self.skip_nl()
        while self.tok.kind != "eof":
            out.statements.extend(self.statement_line())
            self.skip_nl()
        out.closing = self.take()
        return out

    def top_item(self, out: A.Script) -> None:
        t = self.tok
        if t.kind == "kw" and t.text in A.SECTIONS and not self.peek().is_op("("):
            lead = self.take(t)
            self.next()
            self.skip_nl()
            if t.text in out.sections or (t.text == "define" and out.define):
                self.sink.report(M.TM_SECTION_TWICE, t.span, name=t.text)
            block = self.block()
            block.comments = lead
            if t.text == "define":
                out.define.extend(block.body)
                out.sections.setdefault("define", block)
            else:
                out.sections[t.text] = block
            return
        if (t.is_kw("void") or t.text in PRIMITIVE_TYPES) and t.kind == "kw":
            lead = self.take(t)
            fn = self.function()
            fn.comments = lead
            out.functions.append(fn)
            return
        self.fail(M.TM_EXPECTED, t.span, expected="'define', 'main', 'closestop', 'errorstop' or a function",
                  found=describe(t))

    def function(self) -> A.Function:
        start = self.next()
        ret, ret_array = start.text, False
        if ret != "void" and self.accept_op("["):
            self.expect_op("]")
            ret_array = True
        name = self.ident("a function name")
        self.expect_op("(")
        params: list[A.Param] = []
        if not self.tok.is_op(")"):
            while True:
                pt = self.tok
                if not (pt.kind == "kw" and pt.text in PRIMITIVE_TYPES):
                    self.fail(M.TM_EXPECTED, pt.span, expected="a parameter type", found=describe(pt))
                self.next()
                arr = bool(self.accept_op("[") and self.expect_op("]"))
                pname = self.ident("a parameter name")
                params.append(A.Param(pt.span, pt.text, arr, pname.text))
                if not self.accept_op(","):
                    break
        self.expect_op(")")
        self.skip_nl()
        body = self.block()
        return A.Function(start.span.to(body.span), ret, ret_array, name.text, params, body)

    def ident(self, what: str) -> Token:
        if self.tok.kind != "id":
            self.fail(M.TM_EXPECTED, self.tok.span, expected=what, found=describe(self.tok))
        return self.next()

    # --- statements -----------------------------------------------------------------------------
    def block(self) -> A.Block:
        start = self.expect_op("{")
        if self.depth >= MAX_DEPTH:  # one error for the whole block, and on after its '}'
            self.sink.report(M.TM_NOT_HERE, start.span, what="nesting this deep", where=f"(more than {MAX_DEPTH} levels)")
            self.skip_block()
            raise _Bail
        self.nested(start.span)
        body: list[A.Node] = []
        self.skip_nl()
        opening = self.take(self.tok, start.span.line)
        while not self.tok.is_op("}"):
            if self.tok.kind == "eof":
                self.depth -= 1
                self.fail(M.TM_EXPECTED, self.tok.span, expected="'}'", found=describe(self.tok))
            body.extend(self.statement_line())
            self.skip_nl()
        closing = self.take(self.tok)
        end = self.next()
        self.depth -= 1
        return A.Block(start.span.to(end.span), body, opening, closing + self.take(self.tok, end.span.line))

    def skip_block(self) -> None:
        """Skip to just after the '}' that closes the block whose '{' was just read (or to the end)."""
        open_braces = 1
        while self.tok.kind != "eof":
            t = self.next()
            if t.is_op("{"):
                open_braces += 1
            elif t.is_op("}"):
                open_braces -= 1
                if not open_braces:
                    return

    def statement_line(self) -> list[A.Node]:
        """One statement and the end of its line; [] after a reported error."""
        self.chain = 0
        depth, taken = self.depth, self.taken
        try:
            st = self.statement()
            self.end_line()
            return [st]
        except _Bail:
            self.depth = depth
            self.taken = taken  # (the comments of the line skipped go with what follows)
            self.recover()
            return []

    def body(self) -> tuple[A.Node, tuple[Comment, ...]]:
        """A braced block, or one statement on this or the next line (L1633, L1754); and the
        comments after the head (``if (x)``) on its line when the statement is on the next line
        (they go at the end of the head's line; a block keeps them as its opening ones)."""
        head = self.take(self.tok) if self.tok.kind == "nl" else ()
        self.skip_nl()
        if self.tok.is_op("{"):
            block = self.block()
            block.opening = head + block.opening
            return block, ()
        return self.statement(), head

    def statement(self) -> A.Node:
        """One statement with its comments: those before it, and those after it on its last line."""
        lead = self.take(self.tok)
        st = self._statement()
        st.comments = lead + st.comments + self.take(self.tok, st.span.end_line)
        return st

    def _statement(self) -> A.Node:
        t = self.tok
        if t.is_op("{"):
            return self.block()
        if t.kind == "kw":
            word = t.text
            if word in PRIMITIVE_TYPES:
                return self.declaration()
            if word == "if":
                return self.if_stmt()
            if word == "while":
                self.next()
                cond = self.paren_expr()
                body, head = self.body()
                return A.While(t.span.to(body.span), cond, body, comments=head)
            if word == "do":
                self.next()
                self.skip_nl()
                body = self.block()
                self.skip_nl()
                if not self.tok.is_kw("while"):
                    self.fail(M.TM_EXPECTED, self.tok.span, expected="'while' after the 'do' block", found=describe(self.tok))
                self.next()
                cond = self.paren_expr()
                return A.DoWhile(t.span.to(cond.span), body, cond)
            if word == "for":
                return self.for_stmt()
            if word == "switch":
                return self.switch_stmt()
            if word in ("break", "continue"):
                self.next()
                return A.Jump(t.span, word)
            if word == "return":
                self.next()
                value = None
                if self.tok.kind not in ("nl", "eof") and not self.tok.is_op("}"):
                    value = self.expression()
                return A.Return(t.span if value is None else t.span.to(value.span), value)
            self.fail(M.TM_NOT_HERE, t.span, what=f"'{word}'", where="here")
        if t.kind == "id" and t.text in A.CLASS_TYPES and self.peek().kind == "id":
            self.next()
            name = self.next()
            self.expect_op("=")
            args = [self.expression()]
            while self.accept_op(","):
                args.append(self.expression())
            return A.ClassDecl(t.span.to(args[-1].span), t.text, name.text, args)
        expr = self.expression()
        return A.ExprStmt(expr.span, expr)

    def declaration(self) -> A.Decl:
        t = self.next()
        array = False
        if self.accept_op("["):
            self.expect_op("]")
            array = True
        decls: list[A.Declarator] = []
        while True:
            name = self.ident("a variable name")
            init = None
            if self.accept_op("="):
                init = self.assignment()
            decls.append(A.Declarator(name.span if init is None else name.span.to(init.span), name.text, init))
            if not self.accept_op(","):
                break
        return A.Decl(t.span.to(decls[-1].span), t.text, array, decls)

    def paren_expr(self) -> A.Node:
        self.expect_op("(")
        e = self.expression()
        self.expect_op(")")
        return e

    def if_stmt(self) -> A.If:
        t = self.next()
        cond = self.paren_expr()
        then, head = self.body()
        other: A.Node | None = None
        save = self.pos
        self.skip_nl()
        if self.tok.is_kw("else"):
            self.next()
            if self.tok.is_kw("if"):
                other = self.if_stmt()
            else:
                other, else_head = self.body()
                other.comments = else_head + other.comments  # (above it, in the else part)
        else:
            self.pos = save
        return A.If(t.span.to((other or then).span), cond, then, other, comments=head)

    def for_stmt(self) -> A.For:
        t = self.next()
        self.expect_op("(")
        init: list[A.Node] = []
        if not self.tok.is_op(";"):
            if self.tok.kind == "kw" and self.tok.text in PRIMITIVE_TYPES:
                init.append(self.declaration())
            else:
                init = self.expr_list()
        self.expect_op(";")
        cond = None if self.tok.is_op(";") else self.expression()
        self.expect_op(";")
        step = [] if self.tok.is_op(")") else self.expr_list()
        self.expect_op(")")
        body, head = self.body()
        return A.For(t.span.to(body.span), init, cond, step, body, comments=head)

    def expr_list(self) -> list[A.Node]:
        out = [self.expression()]
        while self.accept_op(","):
            out.append(self.expression())
        return out

    def switch_stmt(self) -> A.Switch:
        t = self.next()
        subject = self.paren_expr()
        self.skip_nl()
        start = self.expect_op("{")
        if self.depth >= MAX_DEPTH:  # (as a block: a switch in a switch recursed without a limit)
            self.sink.report(M.TM_NOT_HERE, start.span, what="nesting this deep", where=f"(more than {MAX_DEPTH} levels)")
            self.skip_block()
            raise _Bail
        self.nested(start.span)
        try:
            return self._switch_body(t, subject)
        finally:
            self.depth -= 1

    def _switch_body(self, t: Token, subject: A.Node) -> A.Switch:
        opening = self.take(self.tok, self.toks[self.pos - 1].span.line)  # (on the '{' line)
        self.skip_nl()
        cases: list[A.Case] = []
        while not self.tok.is_op("}"):
            lead = self.take(self.tok)
            c = self.tok
            if c.is_kw("case"):
                self.next()
                op = None
                if self.tok.kind == "op" and self.tok.text in RELATIONAL:
                    op = self.next().text
                label: A.Node | None = self.expression()
            elif c.is_kw("default"):
                self.next()
                op, label = None, None
            elif c.kind == "eof":
                self.fail(M.TM_EXPECTED, c.span, expected="'}'", found=describe(c))
            else:
                self.fail(M.TM_EXPECTED, c.span, expected="'case' or 'default'", found=describe(c))
            self.accept_op(":")  # (the manual writes none; a C habit is tolerated)
            lead += self.take(self.tok, self.toks[self.pos - 1].span.line)
            self.skip_nl()
            body: list[A.Node] = []
            while not (self.tok.is_kw("case") or self.tok.is_kw("default") or self.tok.is_op("}") or self.tok.kind == "eof"):
                body.extend(self.statement_line())
                self.skip_nl()
            cases.append(A.Case(c.span, op, label, body, comments=lead))
        closing = self.take(self.tok)
        end = self.next()
        return A.Switch(t.span.to(end.span), subject, cases, closing + self.take(self.tok, end.span.line),
                        comments=opening)

    # --- expressions ----------------------------------------------------------------------------
    def expression(self) -> A.Node:
        return self.assignment()

    def assignment(self) -> A.Node:
        left = self.conditional()
        if self.tok.kind == "op" and self.tok.text in ASSIGN_OPS:
            op = self.next()
            if not isinstance(left, (A.Name, A.Index, A.Member)):
                self.fail(M.TM_NOT_ASSIGNABLE, op.span, op=op.text)
            value = self.assignment()
            return A.Assign(left.span.to(value.span), op.text, left, value)
        return left

    def conditional(self) -> A.Node:
        cond = self.binary(0)
        q = self.tok
        if self.accept_op("?"):
            self.chain += 1  # (a ? b : c ? d : ... recurses once per '?': a chain like the operators')
            if self.chain > MAX_CHAIN:
                self.fail(M.TM_NOT_HERE, q.span, what="an expression this long", where=f"(more than {MAX_CHAIN} operators)")
            then = self.expression()
            self.expect_op(":")
            other = self.conditional()
            return A.Cond(cond.span.to(other.span), cond, then, other)
        return cond

    def binary(self, level: int) -> A.Node:
        """Operators of ``level`` (an index of LEVELS) and tighter, by precedence climbing: one
        call per operand, not one per level (11 levels: the parser's cost was mostly these)."""
        left = self.unary()
        while True:
            t = self.tok
            if t.kind != "op":
                return left
            op_level = PRECEDENCE.get(t.text, -1)
            if op_level < level:
                return left
            self.next()
            self.chain += 1
            if self.chain > MAX_CHAIN:
                self.fail(M.TM_NOT_HERE, t.span, what="an expression this long", where=f"(more than {MAX_CHAIN} operators)")
            right = self.binary(op_level + 1)
            left = A.Binary(left.span.to(right.span), t.text, left, right)

    def unary(self) -> A.Node:
        t = self.tok
        if t.kind == "op" and t.text in ("-", "+", "!", "~", "++", "--"):
            self.next()
            self.nested(t.span)
            operand = self.unary()
            self.depth -= 1
            if t.text == "-" and isinstance(operand, A.Num) and not operand.text.startswith("-"):
                return A.Num(t.span.to(operand.span), -operand.value, "-" + operand.text)
            return A.Unary(t.span.to(operand.span), t.text, operand)
        if t.is_op("(") and self.peek().kind == "kw" and self.peek().text in PRIMITIVE_TYPES:
            type_word = self.peek().text
            k, array = 2, False
            if self.peek(2).is_op("[") and self.peek(3).is_op("]"):
                k, array = 4, True
            if self.peek(k).is_op(")"):
                self.pos += k + 1
                self.nested(t.span)
                operand = self.unary()
                self.depth -= 1
                return A.Cast(t.span.to(operand.span), type_word, array, operand)
        return self.postfix()

    def postfix(self) -> A.Node:
        e = self.primary()
        while True:
            t = self.tok
            if t.kind == "op" and t.text in "([":
                self.nested(t.span)
                e = self.call_or_index(e, t)
                self.depth -= 1
            elif t.is_op("."):
                self.next()
                name = self.ident("a member name")
                e = A.Member(e.span.to(name.span), e, name.text)
            elif t.kind == "op" and t.text in ("++", "--"):
                self.next()
                e = A.Postfix(e.span.to(t.span), t.text, e)
            else:
                return e

    def call_or_index(self, e: A.Node, t: Token) -> A.Node:
        """``e(args)`` or ``e[index]`` / ``e[index, index2]`` (``t`` is the opening token)."""
        self.next()
        if t.is_op("("):
            args: list[A.Node] = []
            self.skip_nl()
            if not self.tok.is_op(")"):
                args = self.expr_list()
            end = self.expect_op(")")
            return A.Call(e.span.to(end.span), e, args)
        index = self.expression()
        index2 = self.expression() if self.accept_op(",") else None
        end = self.expect_op("]")
        return A.Index(e.span.to(end.span), e, index, index2)

    def primary(self) -> A.Node:
        t = self.tok
        if t.kind == "num":
            self.next()
            return A.Num(t.span, t.value, t.text)  # type: ignore[arg-type]
        if t.kind == "str":
            self.next()
            return A.Str(t.span, t.value)  # type: ignore[arg-type]
        if t.kind == "id":
            self.next()
            if t.text in ("true", "True", "false", "False"):
                return A.Bool(t.span, t.text in ("true", "True"))
            if t.text == "empty":
                return A.Str(t.span, "")
            if t.text in ("newline", "NewLine"):
                return A.Str(t.span, "\r\n")
            return A.Name(t.span, t.text)
        if t.is_op("("):
            self.next()
            self.nested(t.span)
            e = self.expression()
            self.depth -= 1
            self.expect_op(")")
            return e
        if t.is_op("{"):
            self.next()
            self.nested(t.span)
            items: list[A.Node] = []
            self.skip_nl()
            while not self.tok.is_op("}"):
                items.append(self.expression())
                self.skip_nl()
                if not self.accept_op(","):
                    break
                self.skip_nl()
            self.skip_nl()
            end = self.expect_op("}")
            self.depth -= 1
            return A.ArrayLit(t.span.to(end.span), items)
        self.fail(M.TM_EXPECTED_EXPRESSION, t.span, found=describe(t))
        raise AssertionError  # (fail raises)


def parse_script(text: str, file: str, sink: DiagnosticSink) -> A.Script:
    """A script project's tree."""
    comments: list[Comment] = []
    toks = tokenize(text, file, sink, comments=comments)
    return Parser(toks, sink, comments).script(toks[0].span)


def parse_packet(text: str, file: str, sink: DiagnosticSink) -> A.Script:
    """A statement list's tree (a Listen-node packet's SCRIPT, a Script node)."""
    comments: list[Comment] = []
    toks = tokenize(text, file, sink, comments=comments)
    return Parser(toks, sink, comments).packet(toks[0].span)
