"""The checked TMscript tree -> Python text, through the shared writer (``gpl2py.pywriter``).

A script project becomes a module: ``define`` (which sets the globals: it runs when the project
runs, not at import, L996), ``main``/``closestop``/``errorstop`` and the functions as ``def``s,
and a ``run()`` that runs them as the controller does.
A Listen-node packet becomes ``def script(v):`` whose node variables are attributes of ``v`` (they
outlive the packet, L17838).  Values follow ``gplrt.tm.values``: every store converts to the
declared type (``tm.to_int``, ``tm.Array``), arithmetic goes through ``tm.add``/``tm.div``/... (int
wrap, binary32 floats, text concatenation), conditions through ``tm.truth`` unless they are already
a bool.  Built-ins are ``tm.Name``; a deferred argument (``ThreadRun(f())``, ``WaitFor(c, ms)``) is a
``lambda``.  Each line records its TMscript line, so a run-time error names the script's line.

Comments go where the parser attached them (``syntax/ast.py``), through the writer's comment
facilities (``Writer.comments``, ``Writer.trailing``): those before a statement on lines of their
own above its Python, one on its line at the end of the statement's first line (the writer moves it
above when the two do not fit), those of a ``{`` line at the end of the ``if``/``while``/``def``
line, those ending a block (or the file) after its last statement.  A comment line keeps its own
TMscript line in the source map; statements keep theirs.
"""

from __future__ import annotations

import keyword
import math
from collections.abc import Iterator

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.pywriter.emit import Writer
from gpl2py.pywriter.text import escape, py_string
from gpl2py.tmscript import messages as M
from gpl2py.tmscript.semantics.check import Info, Var, pyname
from gpl2py.tmscript.semantics.library import DEFERRED, DEFERRED_WITH_TWO, DEVICES, OBJECTS
from gpl2py.tmscript.syntax import ast as A
from gpl2py.tmscript.syntax.lexer import Comment

ARITH = {"+": "add", "-": "sub", "*": "mul", "/": "div", "%": "mod", "&": "bit_and", "|": "bit_or",
         "^": "bit_xor", "<<": "shl", ">>": "shr"}
CONVERT = {"byte": "to_byte", "int": "to_int", "float": "to_float", "double": "to_double",
           "bool": "to_bool", "string": "to_string"}
DEFAULTS = {"byte": "0", "int": "0", "float": "tm.to_float(0)", "double": "tm.to_double(0)",
            "bool": "False", "string": '""'}
BOOLEAN_OPS = frozenset({"==", "!=", "<", "<=", ">", ">=", "&&", "||"})


class Unsupported(Exception):
    """A construct the lowering does not translate (reported by the pipeline: :meth:`report`)."""

    def __init__(self, node: A.Node, what: str) -> None:
        super().__init__(what)
        self.node, self.what = node, what

    def report(self, sink: DiagnosticSink) -> None:
        sink.report(M.TM_UNSUPPORTED, self.node.span, what=self.what)


class NestedTooDeeply(Unsupported):
    """``node`` is the innermost statement whose Python would nest deeper than CPython compiles
    (docs/security.md, "Nesting"): ``what`` says how deep."""

    def report(self, sink: DiagnosticSink) -> None:
        sink.report(M.TM_NESTED_TOO_DEEPLY, self.node.span, detail=self.what)


class Lowerer:
    def __init__(self, info: Info, packet: bool) -> None:
        self.info, self.packet = info, packet
        self.w = Writer()
        self.temps = 0
        self.steps: list[list[A.Node] | None] = []  # per enclosing loop: a for's step (continue runs it)
        self.in_switch: list[bool] = []

    def temp(self, stem: str) -> str:
        self.temps += 1
        return f"_{stem}{self.temps}"

    # --- expressions ----------------------------------------------------------------------------
    def var_ref(self, var: Var) -> str:
        return f"v.{var.pyname}" if var.storage == "node" else var.pyname

    def expr(self, e: A.Node) -> str:
        if isinstance(e, A.Num):
            if isinstance(e.value, int):
                return repr(e.value)
            value = float(e.value)  # (a literal past the double's range is inf: the conversion rejects it)
            return repr(value) if math.isfinite(value) else f'float("{value}")'
        if isinstance(e, A.Str):
            parts = self.info.interpolations.get(id(e))
            if not parts:
                return py_string(e.value)
            out, pos = "", 0  # 'name' inside the string: its value (L628-L656)
            for start, end, var in parts:
                piece = py_string(e.value[pos:start])
                out = piece if not out else f"tm.add({out}, {piece})"
                out = f"tm.add({out}, {self.var_ref(var)})"
                pos = end
            return f"tm.add({out}, {py_string(e.value[pos:])})"
        if isinstance(e, A.Bool):
            return "True" if e.value else "False"
        if isinstance(e, A.ArrayLit):
            return "[" + ", ".join(self.expr(x) for x in e.items) + "]"
        if isinstance(e, A.Name):
            var = self.info.names.get(id(e))
            if var is not None:
                return self.var_ref(var)
            if e.name in OBJECTS:
                return f"tm.{e.name}"
            return py_string(e.name)  # a bare word is its own text (L602)
        if isinstance(e, A.Call):
            return self.call(e)
        if isinstance(e, A.Index):
            index = self.expr(e.index) if e.index2 is None else f"{self.expr(e.index)}, {self.expr(e.index2)}"
            return f"{self.expr(e.obj)}[{index}]"
        if isinstance(e, A.Member):
            return f"{self.expr(e.obj)}.{e.name}"
        if isinstance(e, A.Unary):
            inner = self.expr(e.operand)
            if e.op == "-":
                return f"tm.neg({inner})"
            if e.op == "+":
                return inner
            if e.op == "!":
                return f"not {self.cond(e.operand)}"
            if e.op == "~":
                return f"tm.invert({inner})"
            return self.increment(e.operand, e.op, prefix=True)
        if isinstance(e, A.Postfix):
            return self.increment(e.operand, e.op, prefix=False)
        if isinstance(e, A.Binary):
            return self.binary(e)
        if isinstance(e, A.Cond):
            return f"({self.expr(e.then)} if {self.cond(e.cond)} else {self.expr(e.other)})"
        if isinstance(e, A.Assign):
            return self.assign_expr(e)
        if isinstance(e, A.Cast):
            arr = ", array=True" if e.array else ""
            return f'tm.cast("{e.type}", {self.expr(e.operand)}{arr})'
        raise Unsupported(e, type(e).__name__)

    def binary(self, e: A.Binary) -> str:
        op = e.op
        if op in ARITH:
            return f"tm.{ARITH[op]}({self.expr(e.left)}, {self.expr(e.right)})"
        if op == "&&":
            return f"({self.cond(e.left)} and {self.cond(e.right)})"
        if op == "||":
            return f"({self.cond(e.left)} or {self.cond(e.right)})"
        if op == "==":
            return f"tm.eq({self.expr(e.left)}, {self.expr(e.right)})"
        if op == "!=":
            return f"not tm.eq({self.expr(e.left)}, {self.expr(e.right)})"
        return f"({self.expr(e.left)} {op} {self.expr(e.right)})"

    def cond(self, e: A.Node) -> str:
        """``e`` as a Python condition (a bool already, or ``tm.truth``)."""
        if isinstance(e, A.Bool):
            return "True" if e.value else "False"
        if isinstance(e, A.Binary) and e.op in BOOLEAN_OPS:
            return self.expr(e)
        if isinstance(e, A.Unary) and e.op == "!":
            return self.expr(e)
        return f"tm.truth({self.expr(e)})"

    def call(self, e: A.Call) -> str:
        kind = self.info.calls.get(id(e))
        args = [self.expr(a) for a in e.args]
        callee = e.callee
        if kind == "method" and isinstance(callee, A.Member):
            return f"{self.expr(callee.obj)}.{callee.name}({', '.join(args)})"
        if not isinstance(callee, A.Name):  # ('(x)(1)': an error the checks reported; Python that compiles)
            return f"{self.expr(callee)}({', '.join(args)})"
        if kind == "user":
            return f"{pyname(callee.name)}({', '.join(args)})"
        if args and (callee.name in DEFERRED or (callee.name in DEFERRED_WITH_TWO and len(args) == 2)):
            args[0] = self.deferred(e.args[0], args[0])
        scope = self.info.scopes.get(id(e))
        if scope is not None:  # (a name given at run time: the variables visible here, L6650)
            args.append(f"scope={self.scope_map(scope)}")
        if callee.name == "GetString" and e.args and self.is_byte_scalar(e.args[0]):
            args.append("as_byte=True")  # (a byte and an int are both Python ints at run time)
        # (pyname: a function no one declared is an error the checks reported, and 'tm.lambda(1)'
        # in --keep-going output was Python that does not compile)
        return f"tm.{pyname(callee.name)}({', '.join(args)})"

    def scope_map(self, scope: dict[str, Var]) -> str:
        """The variables ``scope`` as a Python map from their TMscript names: ``dict(a=a, ...)``
        (the writer packs a call's arguments on lines of PEP 8 length), or a ``{"a": a}`` literal
        when a name is a Python keyword."""
        items = sorted(scope.items())
        if all(n.isidentifier() and not keyword.iskeyword(n) for n, _ in items):
            return "dict(" + ", ".join(f"{n}={self.var_ref(v)}" for n, v in items) + ")"
        return "{" + ", ".join(f"{py_string(n)}: {self.var_ref(v)}" for n, v in items) + "}"

    def is_byte_scalar(self, node: A.Node) -> bool:
        """Whether ``node`` is a variable declared ``byte`` (not an array): ``GetString`` shows its
        bit pattern in 8 bits, an int's in 32 (L5162)."""
        var = self.info.names.get(id(node)) if isinstance(node, A.Name) else None
        return var is not None and var.type == "byte" and not var.array

    def deferred(self, node: A.Node, text: str) -> str:
        """A deferred argument: a ``lambda``, or, when it assigns a variable of the function
        (``WaitFor((st = ThreadState(t)) == 2, 1000)``, L2035), a nested ``def`` declaring it
        ``nonlocal``/``global`` so that the assignment reaches the variable and not the lambda."""
        assigned = sorted({(v.storage, v.pyname) for v in self.assigned_vars(node) if v.storage != "node"})
        if not assigned:
            return f"lambda: {text}"
        name = self.temp("deferred")
        self.w.blank()
        self.line(f"def {name}():", node)
        self.w.indent()
        for storage, words in (("local", "nonlocal"), ("global", "global")):
            names = [n for s, n in assigned if s == storage]
            if names:
                self.line(f"{words} {', '.join(names)}", node)
        self.line(f"return {text}", node)
        self.w.dedent()
        self.w.blank()
        return name

    def assigned_vars(self, node: A.Node) -> list[Var]:
        out: list[Var] = []
        for n in walk(node):
            target = None
            if isinstance(n, A.Assign):
                target = n.target
            elif isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
                target = n.operand
            var = self.target_var(target) if target is not None else None
            if var is not None:
                out.append(var)
        return out

    def convert(self, var: Var, value: str, node: A.Node | None = None) -> str:
        """``value`` converted for a store into ``var`` (nothing to convert for a literal of its type)."""
        if var.cls is not None:
            return value
        if var.array:
            return f'tm.Array("{var.type}", {value})'
        if node is not None:
            if var.type in ("int", "byte") and isinstance(node, A.Num) and isinstance(node.value, int) \
                    and (0 <= node.value <= 255 or (var.type == "int" and -2**31 <= node.value < 2**31)):
                return value
            if var.type == "string" and isinstance(node, A.Str):
                return value
            if var.type == "bool" and isinstance(node, A.Bool):
                return value
        return f"tm.{CONVERT[var.type]}({value})"

    def target_var(self, target: A.Node) -> Var | None:
        return self.info.names.get(id(target)) if isinstance(target, A.Name) else None

    def new_value(self, e: A.Assign) -> str:
        value = self.expr(e.value)
        if e.op != "=":
            value = f"tm.{ARITH[e.op[:-1]]}({self.expr(e.target)}, {value})"
        return value

    def assign_expr(self, e: A.Assign) -> str:
        """An assignment used as a value (``(st = ThreadState(t)) == 2``, L2035)."""
        var = self.target_var(e.target)
        value = self.new_value(e)
        if var is not None:
            conv = self.convert(var, value, e.value if e.op == "=" else None)
            if var.storage == "node":
                return f'tm.assign(v, "{var.pyname}", {conv})'
            return f"({var.pyname} := {conv})"
        if isinstance(e.target, A.Index):
            return f"tm.setitem({self.expr(e.target.obj)}, {self.expr(e.target.index)}, {value})"
        if isinstance(e.target, A.Member):
            return f'tm.assign({self.expr(e.target.obj)}, "{e.target.name}", {value})'
        raise Unsupported(e, "this assignment")

    def increment(self, target: A.Node, op: str, prefix: bool) -> str:
        one = "tm.add" if op == "++" else "tm.sub"
        var = self.target_var(target)
        if var is None:
            raise Unsupported(target, f"'{op}' on this operand")
        ref = self.var_ref(var)
        new = f"tm.{CONVERT[var.type]}({one}({ref}, 1))"
        setter = f'tm.assign(v, "{var.pyname}", {new})' if var.storage == "node" else f"({var.pyname} := {new})"
        if prefix:
            return setter
        back = "tm.sub" if op == "++" else "tm.add"
        return f"tm.{CONVERT[var.type]}({back}({setter}, 1))"

    # --- comments -------------------------------------------------------------------------------
    def carry(self, comments: tuple[Comment, ...] | list[Comment], head: int | None) -> None:
        """``comments`` that follow the start of a statement: each at the end of line ``head``
        (the statement's first), the later lines of a ``/* */`` comment on lines of their own after
        what is written (as they are in the script); with no ``head``, every one on its own line."""
        for c in comments:
            if head is None or c.cont:
                self.w.comments([c])
            else:
                self.w.trailing(c, head)

    def head(self, start: int) -> int | None:
        """The index of the first line of the statement written since ``start`` at the current
        indentation: past comments, blank lines and the ``def`` a deferred argument puts above it."""
        lines, level = self.w.lines, self.w.level
        for i in range(start, len(lines)):
            ln = lines[i]
            if ln.text and ln.indent == level and not ln.text.startswith(("#", "def ")):
                return i
        return None

    # --- statements -----------------------------------------------------------------------------
    def line(self, text: str, node: A.Node) -> None:
        self.w.line(text, node.span.line)

    def statements(self, body: list[A.Node], block: A.Block | None = None, header: int | None = None) -> None:
        """``body``'s Python at the current indentation; ``block``: the block it is the body of,
        whose opening comments go at the end of line ``header`` (the ``if``, ``while`` or ``def``
        above) and whose closing ones after the last statement."""
        start = self.w.mark()
        if block is not None:
            self.carry(block.opening, header)
        scoped: list[int] = []  # the marks of the ``with`` bodies opened for devices
        for st in body:
            if self.scoped_device(st):
                assert isinstance(st, A.ClassDecl)
                var = self.info.names[id(st)]
                assert var is not None
                args = ", ".join([py_string(st.name)] + [self.expr(a) for a in st.args])
                used = any(v is var for k, v in self.info.names.items() if k != id(st))
                target = f" as {var.pyname}" if used else ""  # (the functions name it by its text)
                before, after = split(st)
                self.w.comments(before)
                begun = self.w.begin_statement()
                self.line(f"with tm.{st.cls}({args}){target}:", st)
                self.carry(after, self.w.mark() - 1)
                self.w.indent(blocks=1)  # (a with body is a block as CPython counts them)
                detail = self.w.too_deep(begun, "loop blocks of one function")
                if detail is not None:
                    raise NestedTooDeeply(st, detail)
                self.w.end_statement(begun)
                scoped.append(self.w.mark())
            else:
                self.statement(st)
        if block is not None:
            self.w.comments(block.closing)
        for mark in reversed(scoped):
            self.w.ensure_body(mark)
            self.w.dedent()
        self.w.ensure_body(start)

    def scoped_device(self, st: A.Node) -> bool:
        """Whether ``st`` declares a device that the end of its block closes (L1320,
        L1335-L1345): a Socket, SerialPort or Modbus variable local to a function.  The rest of
        the block becomes the body of ``with tm.Socket(...) as name:``, so leaving it in any way
        (its end, ``return``, ``break``, an error) closes the device.  A ``define`` global lives
        until the project stops, a Listen node's variable until the node is left."""
        if not isinstance(st, A.ClassDecl) or st.cls not in DEVICES:
            return False
        var = self.info.names.get(id(st))
        return var is not None and var.storage == "local"

    def statement(self, st: A.Node) -> None:
        before, after = split(st)
        self.w.comments(before)
        start = self.w.mark()
        begun = self.w.begin_statement()
        head = self._statement(st)
        detail = self.w.too_deep(begun, "loop blocks of one function")
        if detail is not None:
            raise NestedTooDeeply(st, detail)
        self.w.end_statement(begun)
        if after:
            self.carry(after, self.head(start) if head is None else head)

    def _statement(self, st: A.Node) -> int | None:  # noqa: C901 (one dispatch over the statement kinds)
        """Writes ``st``; the index of its head line when that is not its first (a ``for``'s
        ``while`` after its initialisation)."""
        head: int | None = None
        if isinstance(st, A.Decl):
            for d in st.declarators:
                var = self.info.names[id(d)]
                assert var is not None
                if d.init is None:
                    value = "tm.Array(\"%s\")" % st.type if st.array else DEFAULTS[st.type]
                else:
                    value = self.convert(var, self.expr(d.init), d.init)
                self.line(f"{self.var_ref(var)} = {value}", d)
        elif isinstance(st, A.ClassDecl):
            var = self.info.names[id(st)]
            assert var is not None
            args = ", ".join([py_string(st.name)] + [self.expr(a) for a in st.args])
            self.line(f"{self.var_ref(var)} = tm.{st.cls}({args})", st)
        elif isinstance(st, A.ExprStmt):
            self.expr_statement(st.expr)
        elif isinstance(st, A.Block):
            self.statements(st.body, st)
        elif isinstance(st, A.If):
            self.if_chain(st, "if")
        elif isinstance(st, A.While):
            self.line(f"while {self.cond(st.cond)}:", st)
            self.loop_body(st.body, None)
        elif isinstance(st, A.DoWhile):
            first = self.temp("first")
            self.line(f"{first} = True", st)
            self.line(f"while {first} or {self.cond(st.cond)}:", st)
            head = self.w.mark() - 1
            self.w.indent(blocks=1)
            self.line(f"{first} = False", st)
            self.w.dedent()
            self.loop_body(st.body, None, head)
        elif isinstance(st, A.For):
            for s in st.init:
                self.statement(s) if isinstance(s, A.Decl) else self.expr_statement(s)
            cond = "True" if st.cond is None else self.cond(st.cond)
            self.line(f"while {cond}:", st)
            head = self.w.mark() - 1
            self.loop_body(st.body, st.step)
        elif isinstance(st, A.Switch):
            self.switch(st)
        elif isinstance(st, A.Jump):
            if not self.steps and (st.word == "continue" or not self.in_switch):
                # outside every loop (and switch): GPL5307, reported by the checks; --keep-going
                # output had a 'continue' Python refuses to compile
                self.line("pass", st)
            elif st.word == "continue":
                step = next((s for s in reversed(self.steps)), None)
                for s in step or []:
                    self.expr_statement(s)
                self.line("continue", st)
            elif self.in_switch and self.in_switch[-1]:
                raise Unsupported(st, "'break' inside a switch case other than as its last statement")
            else:
                self.line("break", st)
        elif isinstance(st, A.Return):
            if st.value is None:
                self.line("return", st)
            else:
                self.line(f"return {self.return_value(st.value)}", st)
        else:
            raise Unsupported(st, type(st).__name__)
        return head

    def return_value(self, value: A.Node) -> str:
        fn = self.function
        text = self.expr(value)
        if fn is not None and fn.ret != "void":
            if fn.ret_array:
                return f'tm.Array("{fn.ret}", {text})'
            return f"tm.{CONVERT[fn.ret]}({text})"
        return text

    function: A.Function | None = None

    def expr_statement(self, e: A.Node) -> None:
        if isinstance(e, A.Assign):
            var = self.target_var(e.target)
            value = self.new_value(e)
            if var is not None:
                value = self.convert(var, value, e.value if e.op == "=" else None)
                self.line(f"{self.var_ref(var)} = {value}", e)
                return
            if isinstance(e.target, A.Index | A.Member):
                self.line(f"{self.expr(e.target)} = {value}", e)
                return
            # anything else is GPL5104, reported by the checks; --keep-going output evaluates the
            # value and stores nothing (it was '"num" = ...', which does not compile)
            self.line(value, e)
            return
        if isinstance(e, (A.Postfix, A.Unary)) and e.op in ("++", "--"):
            var = self.target_var(e.operand)
            if var is not None:
                one = "tm.add" if e.op == "++" else "tm.sub"
                ref = self.var_ref(var)
                self.line(f"{ref} = tm.{CONVERT[var.type]}({one}({ref}, 1))", e)
                return
        self.line(self.expr(e), e)

    def if_chain(self, st: A.If, word: str) -> None:
        """``if`` (its comments are the statement's) or ``elif`` with its comments."""
        before, after = split(st) if word == "elif" else ([], [])
        self.w.comments(before)
        self.line(f"{word} {self.cond(st.cond)}:", st)
        self.carry(after, self.w.mark() - 1)
        self.body(st.then)
        other = st.other
        if isinstance(other, A.If):
            self.if_chain(other, "elif")
        elif other is not None:
            self.line("else:", other)
            self.body(other)

    def body(self, st: A.Node) -> None:
        """The body of the line just written (``if ...:``, ``else:``)."""
        header = self.w.mark() - 1
        self.w.indent()
        if isinstance(st, A.Block):
            self.statements(st.body, st, header)
        else:
            self.statements([st])
        self.w.dedent()

    def loop_body(self, body: A.Node, step: list[A.Node] | None, header: int | None = None) -> None:
        """The body of a loop whose ``while`` line is ``header`` (by default the line just written)."""
        header = self.w.mark() - 1 if header is None else header
        self.w.indent(blocks=1)
        self.steps.append(step)
        self.in_switch.append(False)
        start = self.w.mark()
        # A turn of the loop is a scheduling point of the shared scheduler (the motion executor, the
        # connections, other threads get their turn: TM threads run one at a time, as GPL's), and
        # where a Listen node's priority command ends a looping script.
        self.line("tm.tick()", body)
        if isinstance(body, A.Block):
            self.statements(body.body, body, header)
        else:
            self.statements([body])
        for s in step or []:
            self.expr_statement(s)
        self.w.ensure_body(start)
        self.in_switch.pop()
        self.steps.pop()
        self.w.dedent()

    def switch(self, st: A.Switch) -> None:
        subject = self.temp("switch")
        self.line(f"{subject} = {self.expr(st.subject)}", st)
        word = "if"
        default: A.Case | None = None
        for c in st.cases:
            if c.label is None:
                default = c
                continue
            label = self.expr(c.label)
            test = f"tm.eq({subject}, {label})" if c.op in (None, "==") else (
                f"not tm.eq({subject}, {label})" if c.op == "!=" else f"{subject} {c.op} {label}")
            self.case_line(f"{word} {test}:", c)
            self.case_body(c)
            word = "elif"
        if default is not None:
            self.case_line("else:" if word == "elif" else "if True:", default)
            self.case_body(default)
        self.w.comments(st.closing)

    def case_line(self, text: str, c: A.Case) -> None:
        """A case's ``if``/``elif``/``else`` line with the case's comments."""
        before, after = split(c)
        self.w.comments(before)
        self.line(text, c)
        self.carry(after, self.w.mark() - 1)

    def case_body(self, c: A.Case) -> None:
        body = list(c.body)
        end: tuple[Comment, ...] = ()
        if body and isinstance(body[-1], A.Jump) and body[-1].word == "break":
            end = body.pop().comments  # the case's end (fall-through is not documented, spec §2.1)
        self.w.indent()
        self.in_switch.append(True)
        self.statements(body, A.Block(c.span, body, closing=end))  # (the comments of its 'break' kept)
        self.in_switch.pop()
        self.w.dedent()

    # --- units ----------------------------------------------------------------------------------
    def define_def(self, tree: A.Script) -> bool:
        """The ``define`` section as ``def define():``, which ``run()`` calls first: "When the
        project is running, it prioritizes all the variables in the definition section" (L996),
        before ``main``, "the first function to call when the project is running" (L1015).  So
        importing the module runs nothing of the script (an initialiser may read a device that is
        attached only for the run, or fail), each run starts from the initial values, and an
        initialiser's error is a run-time error of the project, which runs ``errorstop``.
        ``errorstop``/``closestop`` may read a global whose initialiser did not run: such a global
        first gets its type's default (a class variable ``tm.Unset``, whose use is an error).
        Whether there was a section to write."""
        decls = [st for st in tree.define if isinstance(st, A.Decl | A.ClassDecl)]  # (else GPL5103)
        block = tree.sections.get("define")
        if not decls:
            if block is not None and (block.comments or block.opening or block.closing):
                self.w.comments([*block.comments, *block.opening, *block.closing])  # (a define of comments)
                self.w.blank(2)
            return False
        section = block if block is not None else decls[0]
        declared = [d for st in decls for d in (st.declarators if isinstance(st, A.Decl) else [st])]
        names = list(dict.fromkeys(self.declared_var(d).pyname for d in declared))
        if block is not None:
            self.w.comments(block.comments)  # (those above 'define')
        header = self.w.mark()
        self.line("def define():", section)
        self.w.indent()
        self.line('"""The define section: run() sets the globals anew each time the project runs."""', section)
        self.line(f"global {', '.join(names)}", section)
        read = self.read_after_error(tree)
        unset = False
        defaults: list[tuple[Var, A.Node]] = []
        for d in declared:
            var = self.declared_var(d)
            unset = unset or self.runs_code(var, d)
            if unset and var.pyname in read:
                defaults.append((var, d))
        if defaults:
            self.line("# (what errorstop reads if an initialiser before these fails)", section)
        for var, d in defaults:
            default = (f"tm.Unset({py_string(var.name)})" if var.cls is not None else
                       f'tm.Array("{var.type}")' if var.array else DEFAULTS[var.type])
            self.line(f"{var.pyname} = {default}", d)
        self.statements(decls, block, header)
        self.w.dedent()
        self.w.blank(2)
        return True

    def declared_var(self, node: A.Node) -> Var:
        var = self.info.names[id(node)]
        assert var is not None
        return var

    def runs_code(self, var: Var, d: A.Node) -> bool:
        """Whether the initialiser of ``var`` (declared by ``d``) is more than a literal it
        stores as written: only such an initialiser can fail."""
        init = d.init if isinstance(d, A.Declarator) else d
        if init is None:
            return False
        if not isinstance(init, A.Num | A.Str | A.Bool) or self.info.interpolations.get(id(init)):
            return True
        value = self.expr(init)
        return self.convert(var, value, init) != value

    def read_after_error(self, tree: A.Script) -> set[str]:
        """The globals ``errorstop`` and ``closestop`` (and the functions they call) read: their
        Python names."""
        out: set[str] = set()
        todo: list[A.Node] = [tree.sections[n] for n in ("errorstop", "closestop") if n in tree.sections]
        seen: set[str] = set()
        while todo:
            for n in walk(todo.pop()):
                var = self.info.names.get(id(n)) if isinstance(n, A.Name) else None
                if var is not None and var.storage == "global":
                    out.add(var.pyname)
                out.update(v.pyname for v in self.info.scopes.get(id(n), {}).values() if v.storage == "global")
                if isinstance(n, A.Call) and isinstance(n.callee, A.Name) and self.info.calls.get(id(n)) == "user":
                    fn = self.info.functions.get(n.callee.name)
                    if fn is not None and fn.name not in seen:
                        seen.add(fn.name)
                        todo.append(fn.body)
        return out

    def function_def(self, name: str, params: list[A.Param], body: A.Block, node: A.Node, fn: A.Function | None) -> None:
        self.function = fn
        names = ", ".join(pyname(p.name) for p in params)
        self.w.comments(node.comments)  # (those above it in the script)
        header = self.w.mark()
        self.line(f"def {pyname(name)}({names}):", node)
        self.w.indent()
        assigned = sorted(self.info.globals_assigned.get(name, set()))
        if assigned:
            self.line(f"global {', '.join(assigned)}", node)
        for p in params:
            conv = f'tm.Array("{p.type}", {pyname(p.name)})' if p.array else f"tm.{CONVERT[p.type]}({pyname(p.name)})"
            self.line(f"{pyname(p.name)} = {conv}", p)
        self.statements(body.body, body, header)
        self.w.dedent()
        self.w.blank(2)
        self.function = None


def split(node: A.Node) -> tuple[list[Comment], list[Comment]]:
    """``node``'s comments: those before its first token, and those after it."""
    if not node.comments:
        return [], []
    start = (node.span.line, node.span.col)
    before = [c for c in node.comments if (c.span.line, c.span.col) < start]
    return before, list(node.comments[len(before):])


def walk(node: A.Node) -> Iterator[A.Node]:
    """``node`` and every node below it."""
    stack = [node]
    while stack:
        n = stack.pop()
        yield n
        for v in vars(n).values():
            if isinstance(v, A.Node):
                stack.append(v)
            elif isinstance(v, list):
                stack.extend(x for x in v if isinstance(x, A.Node))


def lower_packet(tree: A.Script, info: Info) -> tuple[str, list[int]]:
    """A packet's statements as ``def script(v):`` (text, and the TMscript line of each line)."""
    lo = Lowerer(info, packet=True)
    lo.w.line("def script(v):", 0)
    lo.w.indent()
    lo.statements(tree.statements, A.Block(tree.span, tree.statements, closing=tree.closing))
    lo.w.dedent()
    return lo.w.render()


def lower_script(tree: A.Script, info: Info, title: str) -> tuple[str, list[int]]:
    """A script project as a module."""
    lo = Lowerer(info, packet=False)
    w = lo.w
    w.line(f'"""TMscript project {escape(title, "docstring")}, translated by gpl2py."""', 0)
    w.blank()
    w.line("from gplrt import tm", 0)
    w.blank(2)
    has_define = lo.define_def(tree)
    for name in ("main", "closestop", "errorstop"):
        block = tree.sections.get(name)
        if block is not None:
            lo.function_def(name, [], block, block, None)
    for fn in tree.functions:
        lo.function_def(fn.name, fn.params, fn.body, fn, fn)
    if tree.closing:  # (the comments after the script's last item)
        w.comments(tree.closing)
        w.blank(2)
    stops = ", ".join(f"{n}={n if n in tree.sections else 'None'}" for n in ("closestop", "errorstop"))
    w.line("def run():", 0)
    w.indent()
    w.line('"""Run the project as the robot does: define, main, then closestop or errorstop."""', 0)
    define = ", define=define" if has_define else ""
    w.line(f"return tm.run_project({'main' if 'main' in tree.sections else 'None'}, {stops}{define})", 0)
    w.dedent()
    w.blank(2)
    w.line('if __name__ == "__main__":', 0)
    w.indent()
    w.line("run()", 0)
    w.dedent()
    return w.render()
