"""One V+ program -> one Python function (docs/design/vplus-runtime.md §2).

``.PROGRAM ros.rev.bytes($in, $out)`` becomes ``def ros_rev_bytes(s_in, s_out)`` registered as
``@vp.program("ros.rev.bytes")``; each parameter receives a reference (a cell, an element, an
array) and is read and written through ``.v``.  AUTO variables are new cells per call, LOCALs the
program's store, GLOBALs the session's (``vp.G``), bound to Python names at the top of the
function so that the body reads like the V+: ``str_len.v = vp.len_(s_in.v)``.

Blocks become Python blocks; FOR evaluates its bounds once and leaves its index past the end as
a V+ loop does; a GOTO to a step label of the program's top level is a jump of a dispatch loop
around the body (``_at``, ``_GoTo``), written only in a program that has one; one to a label in
its own FOR body is caught by that body, which goes round again from the label (``_into``).  Every Python line
keeps its V+ line (the source map), every ``;`` comment is carried.
"""

from __future__ import annotations

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.kept import KeptErrors
from gpl2py.pywriter.emit import BLOCKS, MAX_BLOCKS, Writer
from gpl2py.pywriter.text import py_string
from gpl2py.vplus import messages as M
from gpl2py.vplus.lower.expressions import Exprs
from gpl2py.vplus.lower.instructions import instruction
from gpl2py.vplus.lower.names import Names
from gpl2py.vplus.semantics.check import Model, ProgramInfo, Symbol, blocks
from gpl2py.vplus.syntax import ast as A


class ProgramLowerer:
    """Writes one program.  ``functions`` maps a program's V+ key to the Python expression that
    calls it from this module (``ros_rev_bytes`` or ``other_module.ros_rev_bytes``)."""

    def __init__(self, model: Model, info: ProgramInfo, functions: dict[str, str], sink: DiagnosticSink,
                 reactions: frozenset[str] = frozenset()) -> None:
        self.model = model
        #: REACTE in the project: each statement that can fail is a resumable unit (vp.step), so
        #: that RETURNE goes on after it; REACT/REACTI: loops pass a safepoint each time round
        self.steps = "REACTE" in reactions
        self.safepoints = bool(reactions & {"REACT", "REACTI"})
        self.info = info
        self.functions = functions
        self.sink = sink
        self.kept = KeptErrors(sink, M.PROGRAM_NOT_EXECUTABLE, M.RUNTIME_CODES)  # (lines that raise)
        reserved = {f.split(".")[0] for f in functions.values()}
        self.names = Names(reserved)
        self.x = Exprs(model, self.var)
        self.w = Writer()
        self.loops: list[tuple[str, A.Stmt]] = []  # ("for", stmt) / ("while", stmt) / ("do", stmt)
        self.temps = 0
        self.top_labels: dict[int, int] = {}  # label -> segment number, when the program jumps
        #: EXIT n / NEXT n (n > 1): the flag of each loop they leave to (``_leave1``), and for each
        #: loop they pass through, the flags to test right after it ends (see ``_plan_exits``)
        self.leave_flag: dict[int, str] = {}
        self.after_loop: dict[int, list[tuple[str, A.Exit]]] = {}
        self.exit_target: dict[int, A.Stmt] = {}
        #: GOTO into a block: the targets whose label is not on the top level, and for each
        #: statement the ones at or inside it (see ``_plan_entries``)
        self.nested_targets: frozenset[int] = frozenset()
        self.inside: dict[int, frozenset[int]] = {}
        #: a GOTO within a FOR body: each FOR's labels that such a GOTO enters, and whether any
        #: GOTO goes elsewhere (then the program needs its dispatch loop)
        self.for_labels: dict[int, frozenset[int]] = {}
        self.jumps_out = False
        #: the statements replaced because Python would not compile them, with why (reported
        #: once the body is written: see ``_too_deep``)
        self.too_deep: list[tuple[A.Stmt, str]] = []

    # --- names ----------------------------------------------------------------------------------

    def var(self, sym: Symbol) -> str:
        name = sym.name
        sigil = name[0] if name[:1] in "$#%" else ""
        return self.names.name(sym, sigil, name[len(sigil):], "_arr" if sym.array and self._twin(sym) else "")

    def _twin(self, sym: Symbol) -> bool:
        """Whether a scalar of the same name is visible too (``AUTO a`` and ``AUTO a[5]``)."""
        scalar = sym.key[:-2]
        return scalar in self.info.names or scalar in self.model.globals

    def _program(self, name: str) -> str:
        """A program as EXECUTE and REACT take it: its function, or its name when the project
        does not define it (the runtime then stops with *Undefined program*)."""
        return self.functions.get(A.key("", name)) or py_string(name)

    def _temp(self, what: str) -> str:
        self.temps += 1
        return f"_{what}{self.temps}"

    # --- the function ---------------------------------------------------------------------------

    def lower(self) -> Writer:
        prog = self.info.program
        w = self.w
        params = [self.var(p) for p in self.info.params]
        w.gpl_line = prog.span.line
        w.line(f"@vp.program({py_string(prog.name)})")
        w.line(f"def {self.functions[prog.key]}({', '.join(params)}) -> None:")
        w.indent()
        start = w.mark()
        w.comments(prog.comments)  # (those above .PROGRAM and on its line)
        body = self._body_text()
        for s, detail in self.too_deep:
            self.sink.report(M.NESTED_TOO_DEEPLY, s.span, detail=detail)
        self._declarations()
        w.extend(body)
        w.ensure_body(start)
        w.dedent()
        return w

    def _body_text(self) -> Writer:
        """The statements, written to a Writer of their own (the declarations go above them once
        every symbol the body names is known)."""
        outer = self.w
        self.w = Writer(level=outer.level)
        prog = self.info.program
        self._plan_exits(prog.body, [])
        gotos = _has_goto(prog.body)
        if gotos:
            self._plan_entries(prog.body)
        if self.jumps_out:
            self._dispatch(prog.body)
        elif self.nested_targets:  # (every GOTO goes to a label in its own FOR body)
            self.w.gpl_line = prog.body[0].span.line
            self.w.line("_into = 0  # a step label inside a FOR body that a GOTO enters, until it is reached")
            self.block(prog.body)
        else:
            self.block(prog.body)
        self.w.comments(prog.trailing)
        body, self.w = self.w, outer
        return body

    def _declarations(self) -> None:
        """The program's AUTO, LOCAL and GLOBAL lines, in their order and with their comments,
        then a binding for every other global the body uses (in the order it uses them)."""
        w = self.w
        done = set(self.info.params)
        for decl in self.info.program.decls:
            w.gpl_line = decl.span.line
            w.comments([c for c in decl.comments if c.span.line < decl.span.line])
            start = w.mark()
            for item in decl.items:
                sym = self.model.symbol_of.get(id(item.var))
                if sym is not None and sym not in done:
                    done.add(sym)
                    self._declare(sym)
            for c in decl.comments:
                if c.span.line >= decl.span.line:
                    w.trailing(c, start)
        for sym in list(self.names.of):
            if isinstance(sym, Symbol) and sym not in done:
                done.add(sym)
                w.gpl_line = sym.span.line if sym.span.file == self.info.path else self.info.program.span.line
                self._declare(sym)

    def _declare(self, sym: Symbol) -> None:
        w = self.w
        name = self.var(sym)
        vname = py_string(sym.name)
        if sym.scope == "AUTO":
            if sym.array:
                sizes = [self.x.value(d) for d in sym.dims or []]
                w.line(f"{name} = vp.VArray({', '.join([vname] + sizes)})")
            else:
                w.line(f"{name} = vp.Cell({vname})")
        elif sym.scope == "LOCAL":
            store = f"vp.local_store({py_string(self.info.program.name)})"
            w.line(f"{name} = {store}.array({vname})" if sym.array else f"{name} = {store}[{vname}]")
        elif sym.scope == "GLOBAL":
            w.line(f"{name} = vp.G.array({vname})" if sym.array else f"{name} = vp.G[{vname}]")

    def _dispatch(self, body: list[A.Stmt]) -> None:
        """A body with GOTOs: segments at its top-level labels, run from ``_at`` on; a GOTO raises
        ``_GoTo(label)`` and the loop goes on at that label's segment."""
        w = self.w
        segments: list[list[A.Stmt]] = [[]]
        entries: dict[int, int] = {}  # a label inside a block -> the segment of its top statement
        for s in body:
            if s.label is not None and segments[-1]:
                segments.append([])
            if s.label is not None:
                self.top_labels[s.label] = len(segments) - 1
            for label in sorted(self.inside.get(id(s), ())):
                entries[label] = len(segments) - 1
            segments[-1].append(s)
        labels = ", ".join(f"{k}: {v}" for k, v in {**self.top_labels, **entries}.items())
        w.gpl_line = body[0].span.line if body else self.info.program.span.line
        w.line(f"_labels = {{{labels}}}  # step label -> segment")
        w.line("_at = 0")
        if self.nested_targets:
            w.line("_into = 0  # a step label inside a block that a GOTO enters, until it is reached")
        w.line("while True:")
        w.indent(blocks=1)
        w.line("try:")
        w.indent(blocks=1)
        for n, seg in enumerate(segments):
            w.gpl_line = seg[0].span.line if seg else w.gpl_line
            w.line(f"if _at <= {n}:")
            w.indent()
            start = w.mark()
            self.block(seg)
            w.ensure_body(start)
            w.dedent()
        w.line("return")
        w.dedent()
        w.line("except _GoTo as jump:")
        w.indent(blocks=2)
        w.line("_at = _labels[jump.label]")
        if self.nested_targets:
            w.line("_into = jump.label")
        w.dedent()
        w.dedent()

    # --- statements -----------------------------------------------------------------------------

    def block(self, body: list[A.Stmt]) -> None:
        if not self.nested_targets:
            for s in body:
                self.stmt(s)
            return
        # A GOTO may enter this block at a label further down: the statements before it are
        # skipped while ``_into`` names a label after them (consecutive ones under one test).
        later: list[frozenset[int]] = []
        seen: frozenset[int] = frozenset()
        for s in reversed(body):
            later.append(seen)
            seen = seen | self.inside.get(id(s), frozenset())
        later.reverse()
        w = self.w
        i = 0
        while i < len(body):
            skip = later[i]
            if not skip:
                self.stmt(body[i])
                i += 1
                continue
            w.gpl_line = body[i].span.line
            w.line(f"if _into not in {_labels_text(skip)}:  # (entered further down by a GOTO)")
            w.indent()
            while i < len(body) and later[i] == skip:
                self.stmt(body[i])
                i += 1
            w.dedent()

    def stmt(self, s: A.Stmt) -> None:  # noqa: C901 (one dispatch over the statement kinds)
        w, x = self.w, self.x
        w.gpl_line = s.span.line
        before = [c for c in s.comments if c.span.line < s.span.line]
        after = [c for c in s.comments if c.span.line >= s.span.line]
        w.comments(before)
        start = w.mark()
        begun = w.begin_statement()
        if self.kept.any() and self.kept.on_lines(s.span, whole=False):
            self._kept(s)
        elif self.steps and isinstance(s, _RESUMABLE) and (not isinstance(s, A.Instr) or s.word):
            w.line(f"with vp.step({s.span.line}):")
            w.indent(BLOCKS["with"])
            self._simple(s)
            w.dedent()
        else:
            self._simple(s)
        detail = w.too_deep(begun)
        if detail is not None:
            self._too_deep(s, start, detail)
        w.end_statement(begun)
        if s.label is not None and w.mark() > start:
            first = w.lines[start]
            first.attach(f"# step {s.label}")
        for c in after:
            w.trailing(c, start)

    def _kept(self, s: A.Stmt) -> None:
        """A statement translated despite an error on its line (``--keep-going``, or the error
        ignored): it raises V+'s error for the fault when reached (gpl2py.kept)."""
        self._raise(s, *self.kept.at(s.span))

    def _raise(self, s: A.Stmt, code: int, subject: str) -> None:
        """The line that raises V+ error ``code`` in place of ``s``, in a step of its own so that
        REACTE traps it and RETURNE goes on after it (a block with it) -- unless the step's block
        would itself be one more than Python compiles (``s`` nested too deeply, replaced by this
        line at the depth where it starts)."""
        step = self.steps and self.w.blocks + BLOCKS["with"] <= MAX_BLOCKS
        if step:
            self.w.line(f"with vp.step({s.span.line}):")
            self.w.indent(BLOCKS["with"])
        self.w.line(f"vp.compile_error({code}, {py_string(subject)})")
        if step:
            self.w.dedent()

    def _too_deep(self, s: A.Stmt, start: int, detail: str) -> None:
        """``s`` is the innermost statement whose Python would nest deeper than CPython compiles:
        its code is replaced by the line that raises *Not implemented* when reached, and GPL4702
        is reported at it when the program is written -- unless a statement around it is replaced
        too (its own header's step block can be the one too many), which then has the one error."""
        w = self.w
        w.discard_since(start)
        inside = _nested_ids(s)
        self.too_deep = [(t, d) for t, d in self.too_deep if id(t) not in inside]
        self.too_deep.append((s, detail))
        w.gpl_line = s.span.line
        self._raise(s, M.RUNTIME_CODES[M.NESTED_TOO_DEEPLY.code],
                    f"{M.NESTED_TOO_DEEPLY.code}: {M.NESTED_TOO_DEEPLY.format(detail=detail)}")

    def _simple(self, s: A.Stmt) -> None:  # noqa: C901 (one dispatch over the statement kinds)
        w, x = self.w, self.x
        if s.label is not None and s.label in self.nested_targets:
            w.line("_into = 0  # (the GOTO's label is reached)")
        if id(s) in self.leave_flag:  # a loop that an EXIT n / NEXT n of an inner loop leaves to
            w.line(f"{self.leave_flag[id(s)]} = False  # set by an inner loop's EXIT or NEXT with a count")
        if isinstance(s, A.Assign | A.SetLoc):
            w.line(f"{self._target(s.target)} = {x.value(s.value)}")
        elif isinstance(s, A.Here):
            frames = [x.value(f) for f in s.frames]
            w.line(f"vp.here_into({', '.join([x.ref(s.target)] + frames)})")
        elif isinstance(s, A.If):
            self._if(s)
        elif isinstance(s, A.IfGoto):
            w.line(f"if {self._guarded(s.cond, s.span.line)}:")
            w.indent()
            self._goto(s.target, s)
            w.dedent()
        elif isinstance(s, A.Goto):
            self._goto(s.target, s)
        elif isinstance(s, A.Case):
            self._case(s)
        elif isinstance(s, A.While) and self.steps:  # the test a resumable unit of its own
            w.line("while True:  # WHILE ... DO")
            self._loop_body("while", s, s.body, test=s.cond)
        elif isinstance(s, A.While):
            enter = self._into_any(s.body)
            test = x.condition(s.cond)
            w.line(f"while {f'_into in {_labels_text(enter)} or ({test})' if enter else test}:")
            self._loop_body("while", s, s.body)
        elif isinstance(s, A.DoUntil):
            w.line("while True:  # DO ... UNTIL")
            self._loop_body("do", s, s.body, until=s.cond)
        elif isinstance(s, A.For):
            self._for(s)
        elif isinstance(s, A.Exit):
            self._exit(s)
        elif isinstance(s, A.CallStmt):
            args = [x.argument(a) for a in s.args]
            fn = self.functions.get(A.key("", s.name))
            if s.dynamic is not None or fn is None:  # by name: V+'s *Undefined program* if none
                name = x.value(s.dynamic) if s.dynamic is not None else py_string(s.name)
                w.line(f"vp.calls({', '.join([name] + args)})")
            else:
                w.line(f"{fn}({', '.join(args)})")
        elif isinstance(s, A.Return):
            w.line("return")
        elif isinstance(s, A.Execute):
            task = x.value(s.task) if s.task is not None else "0"
            args = [x.argument(a) for a in s.args]
            rest = [f"cycles={x.value(s.rest[0])}"] if s.rest and s.rest[0] is not None else []
            w.line(f"vp.execute({', '.join([task, self._program(s.program)] + args + rest)})")
        elif isinstance(s, A.React):
            self._react(s)
        elif isinstance(s, A.Instr):
            if s.word:
                for text in instruction(s, x).split("\n"):
                    w.line(text)
            elif s.label is not None:
                w.line("pass")

    def _target(self, v: A.Var) -> str:
        sym = self.model.symbol_of[id(v)]
        name = self.var(sym)
        if v.index is not None:
            return f"{name}[{', '.join(self.x.value(i) for i in v.index)}]"
        return f"{name}.v"

    def _guarded(self, cond: A.Expr, line: int, into: frozenset[int] = frozenset(),
                 away: frozenset[int] = frozenset()) -> str:
        """The condition of a block's header; under REACTE its evaluation is a resumable unit of
        its own, into a temporary that is false if the handler resumes after it
        (docs/design/vplus-runtime.md §7).  A GOTO entering the block (``_into`` in ``into``)
        makes it true, one entering another branch (``away``) false, neither evaluating it."""
        if not self.steps:
            test = self.x.condition(cond)
            if away:
                test = f"_into not in {_labels_text(away)} and ({test})"
            return f"_into in {_labels_text(into)} or ({test})" if into else test
        temp = self._temp("c")
        self.w.line(f"{temp} = {f'_into in {_labels_text(into)}' if into else 'False'}")
        skip = into | away
        if skip:
            self.w.line(f"if _into not in {_labels_text(skip)}:")
            self.w.indent()
        self.w.line(f"with vp.step({line}):")
        self.w.indent(BLOCKS["with"])
        self.w.line(f"{temp} = {self.x.condition(cond)}")
        self.w.dedent()
        if skip:
            self.w.dedent()
        return temp

    def _into_any(self, body: list[A.Stmt] | None) -> frozenset[int]:
        """The labels a GOTO may enter at, in ``body``."""
        found: frozenset[int] = frozenset()
        for s in body or []:
            found = found | self.inside.get(id(s), frozenset())
        return found

    def _if(self, s: A.If) -> None:
        w = self.w
        w.line(f"if {self._guarded(s.cond, s.span.line, self._into_any(s.then), self._into_any(s.orelse))}:")
        self._suite(s.then)
        orelse = s.orelse
        while orelse is not None:
            if len(orelse) == 1 and isinstance(orelse[0], A.If) and not orelse[0].comments and orelse[0].label is None \
                    and not self.steps and not self.inside.get(id(orelse[0])):
                inner = orelse[0]
                w.gpl_line = inner.span.line
                w.line(f"elif {self.x.condition(inner.cond)}:")
                self._suite(inner.then)
                orelse = inner.orelse
            else:
                w.line("else:")
                self._suite(orelse)
                orelse = None

    def _suite(self, body: list[A.Stmt], blocks: int = 0) -> None:
        w = self.w
        w.indent(blocks)
        start = w.mark()
        self.block(body)
        w.ensure_body(start)
        w.dedent()

    def _case(self, s: A.Case) -> None:
        w, x = self.w, self.x
        subject = x.value(s.subject)
        entered = self._into_any([arm_stmt for arm in s.arms for arm_stmt in arm.body])
        if not (isinstance(s.subject, A.Var) and s.subject.index is None):
            temp = self._temp("case")
            if entered:  # (not evaluated when a GOTO enters an arm)
                w.line(f"{temp} = None if _into in {_labels_text(entered)} else {subject}  # CASE ... OF")
            else:
                w.line(f"{temp} = {subject}  # CASE ... OF")
            subject = temp
        first = True
        for arm in s.arms:
            w.gpl_line = arm.span.line
            if not first and s.arms[s.arms.index(arm) - 1].values is None:
                break  # (an arm after ANY: an error, translated with --keep-going as never reached)
            if arm.values == []:  # (a VALUE list that did not parse: never matches)
                w.line("if False:" if first else "elif False:")
            elif arm.values is None:
                if first:
                    w.line("if True:  # ANY")
                else:
                    w.line("else:  # ANY")
            else:
                values = [x.value(v) for v in arm.values]
                test = f"{subject} == {values[0]}" if len(values) == 1 else f"{subject} in ({', '.join(values)})"
                if entered:
                    into = self._into_any(arm.body)
                    test = f"_into not in {_labels_text(entered)} and {test}"
                    if into:
                        test = f"_into in {_labels_text(into)} or ({test})"
                w.line(f"{'if' if first else 'elif'} {test}:")
            for c in arm.comments:
                w.trailing(c, w.mark() - 1)
            self._suite(arm.body)
            first = False

    def _loop_body(self, kind: str, s: A.Stmt, body: list[A.Stmt], until: A.Expr | None = None,
                   step: str | None = None, test: A.Expr | None = None,
                   local: frozenset[int] = frozenset()) -> None:
        """A loop's body; ``local``: the step labels in a FOR body that a GOTO in it jumps to --
        the body catches the jump and goes round again from the label (``_into``)."""
        w = self.w
        self.loops.append((kind, s))
        w.indent(blocks=1)
        start = w.mark()
        if local:
            w.line("try:")
            w.indent(blocks=1)
        if test is not None:  # WHILE's test at the top of the body (under REACTE)
            w.line(f"if not {self._guarded(test, s.span.line, self._into_any(body))}:")
            w.indent()
            w.line("break")
            w.dedent()
        if self.safepoints:  # a reaction armed by REACT runs here, once per time round
            w.line("vp.safepoint()")
        self.block(body)
        if until is not None:
            w.gpl_line = until.span.line
            w.line(f"if {self._guarded(until, until.span.line)}:  # UNTIL")
            w.indent()
            w.line("break")
            w.dedent()
        if local:
            w.ensure_body(start + 1)
            w.dedent()
            w.line("except _GoTo as jump:  # a GOTO to a label in this FOR body")
            w.indent(blocks=2)
            w.line(f"if jump.label not in {_labels_text(local)}:")
            w.indent()
            w.line("raise")
            w.dedent()
            w.line("_into = jump.label")
            w.line("continue  # (from the label, without the step)")
            w.dedent()
        if step is not None:
            w.line(step)
        w.ensure_body(start)
        w.dedent()
        self.loops.pop()
        for flag, ex in self.after_loop.get(id(s), []):  # an EXIT n / NEXT n left this loop
            w.line(f"if {flag}:")
            w.indent()
            target = self.exit_target[id(ex)]
            if ex.word == "NEXT" and self.loops and self.loops[-1][1] is target:
                w.line(f"{flag} = False")
                self._next(*self.loops[-1])
            else:
                w.line("break")
            w.dedent()

    def _for(self, s: A.For) -> None:
        w, x = self.w, self.x
        index = self._target(s.var)
        stop = x.value(s.stop)
        if not _constant(s.stop):
            temp = self._temp("to")
            w.line(f"{temp} = {stop}  # the end is evaluated once")
            stop = temp
        step_value = x.value(s.step) if s.step is not None else "1"
        if s.step is not None and not _constant(s.step):
            temp = self._temp("step")
            w.line(f"{temp} = {step_value}")
            step_value = temp
        w.line(f"{index} = {x.value(s.start)}")
        if _constant(s.step) or s.step is None:
            negative = s.step is not None and _const_value(s.step) < 0
            test = f"{index} {'>=' if negative else '<='} {stop}"
        else:
            test = f"({index} <= {stop} if {step_value} > 0 else {index} >= {stop})"
        local = self.for_labels.get(id(s), frozenset())
        if local:  # (a GOTO within the body goes on at its label, without a test of the end)
            test = f"_into in {_labels_text(local)} or {test if test.startswith('(') else f'({test})'}"
        w.line(f"while {test}:  # FOR")
        increment = f"{index} += {step_value}" if not step_value.startswith("-") else f"{index} -= {step_value[1:]}"
        self._loop_body("for", s, s.body, step=increment, local=local)

    def _plan_entries(self, body: list[A.Stmt]) -> None:
        """The GOTO targets inside blocks, and which statements hold them.  A label inside a FOR
        loop is entered by a GOTO in the same loop (at any depth): the FOR's body catches the jump
        and runs again from the label (``for_labels``) without going through the FOR statement,
        as V+ does.  A GOTO from outside the FOR to it is GPL4700 (entering the body would skip
        the evaluation of the end and step); that GOTO stays a jump the program does not catch."""
        targets = _goto_targets(body)
        owner: dict[int, A.For | None] = {}  # a label -> the innermost FOR around it (None: none)
        gotos: list[tuple[A.Goto | A.IfGoto, tuple[A.For, ...]]] = []

        def find(stmts: list[A.Stmt], top: bool, fors: tuple[A.For, ...]) -> None:
            for s in stmts:
                if not top and s.label is not None and s.label in targets:
                    owner.setdefault(s.label, fors[-1] if fors else None)
                if isinstance(s, A.Goto | A.IfGoto):
                    gotos.append((s, fors))
                inner = fors + (s,) if isinstance(s, A.For) else fors
                for b in blocks(s):
                    find(b, False, inner)

        find(body, True, ())
        for g, fors in gotos:
            loop = owner.get(g.target)
            if loop is not None and not any(f is loop for f in fors):
                self.sink.report(M.GOTO_INTO_FOR, g.span, label=g.target)
        for label, loop in owner.items():
            if loop is not None:
                self.for_labels[id(loop)] = self.for_labels.get(id(loop), frozenset()) | {label}

        def walk(stmts: list[A.Stmt]) -> frozenset[int]:
            found: frozenset[int] = frozenset()
            for s in stmts:
                here = frozenset({s.label}) if s.label in owner else frozenset()
                for b in blocks(s):
                    below = walk(b)
                    if not isinstance(s, A.For):  # (a FOR's own labels stay inside it)
                        here = here | below
                if here:
                    self.inside[id(s)] = here
                found = found | here
            return found

        walk(body)  # (a label of the top level is no entry: the dispatch loop goes there)
        self.nested_targets = frozenset(owner)
        self.jumps_out = any(owner.get(label) is None for label in targets)

    def _plan_exits(self, body: list[A.Stmt], loops: list[A.Stmt]) -> None:
        """Find each EXIT n / NEXT n (n > 1) and the loop it leaves to.  Python breaks one loop:
        the statement sets that loop's flag and breaks; each loop it passes through is followed by
        ``if flag: break``, and the last by the outer loop's NEXT (or ``break`` for EXIT)."""
        for s in body:
            if isinstance(s, A.Exit) and s.count is not None and loops:  # (none: GPL4309)
                n = _whole(s.count)
                if n is None or n < 1 or n > len(loops):
                    reason = ("the count must be a whole number" if n is None or n < 1 else
                              f"only {len(loops)} loop{'s' if len(loops) != 1 else ''} enclose{'s' if len(loops) == 1 else ''} it")
                    self.sink.report(M.EXIT_COUNT, s.span, word=s.word, count=_count_text(s.count), reason=reason)
                elif n > 1:
                    target = loops[-n]
                    flag = self.leave_flag.setdefault(id(target), self._temp("leave"))
                    self.exit_target[id(s)] = target
                    for inner in loops[-n + 1:]:
                        self.after_loop.setdefault(id(inner), []).append((flag, s))
            inner_loops = loops + [s] if isinstance(s, A.While | A.DoUntil | A.For) else loops
            for b in blocks(s):
                self._plan_exits(b, inner_loops)

    def _exit(self, s: A.Exit) -> None:
        w = self.w
        if not self.loops:
            return
        target = self.exit_target.get(id(s))
        if target is not None:  # EXIT n / NEXT n, n > 1
            w.line(f"{self.leave_flag[id(target)]} = True")
            w.line(f"break  # {s.word} {_count_text(s.count)}")
            return
        if s.word == "EXIT":
            w.line("break")
            return
        self._next(*self.loops[-1])

    def _next(self, kind: str, loop: A.Stmt) -> None:
        """NEXT of ``loop``: its step (FOR) or its UNTIL test (DO), then the next time round."""
        w = self.w
        if kind == "for":
            assert isinstance(loop, A.For)
            step = self.x.value(loop.step) if loop.step is not None else "1"
            index = self._target(loop.var)
            w.line(f"{index} += {step}  # NEXT" if not step.startswith("-") else f"{index} -= {step[1:]}  # NEXT")
        elif kind == "do":
            assert isinstance(loop, A.DoUntil)
            w.line(f"if {self.x.condition(loop.cond)}:  # NEXT tests UNTIL")
            w.indent()
            w.line("break")
            w.dedent()
        w.line("continue")

    def _goto(self, label: int, s: A.Stmt) -> None:
        self.w.line(f"raise _GoTo({label})  # GOTO {label}")

    def _react(self, s: A.React) -> None:
        w, x = self.w, self.x
        if s.word == "REACTE":
            w.line(f"vp.reacte({self._program(s.program) if s.program else 'None'})")
            return
        args = [x.argument(a) for a in s.args]
        extra = [f"priority={x.value(s.priority)}"] if s.priority is not None else []
        assert s.signal is not None
        call = [x.value(s.signal), self._program(s.program)] + args + extra
        w.line(f"vp.{s.word.lower()}({', '.join(call)})")


#: The statements a REACTE handler resumes after (RETURNE): everything but blocks and jumps.
_RESUMABLE = (A.Assign, A.SetLoc, A.Here, A.CallStmt, A.Execute, A.React, A.Instr)


def _constant(e: A.Expr | None) -> bool:
    if e is None:
        return True
    if isinstance(e, A.Num):
        return True
    if isinstance(e, A.Unary) and e.op == "-":
        return _constant(e.operand)
    if isinstance(e, A.Paren):
        return _constant(e.inner)
    return False


def _const_value(e: A.Expr) -> float:
    if isinstance(e, A.Num):
        return e.value
    if isinstance(e, A.Unary):
        return -_const_value(e.operand)
    if isinstance(e, A.Paren):
        return _const_value(e.inner)
    return 0.0


def _whole(e: A.Expr) -> int | None:
    """The count of EXIT n / NEXT n when it is a whole-number constant."""
    if not _constant(e):
        return None
    value = _const_value(e)
    return int(value) if value == int(value) else None


def _count_text(e: A.Expr | None) -> str:
    if e is None:
        return ""
    n = _whole(e)
    return str(n) if n is not None else "n"


def _labels_text(labels: frozenset[int]) -> str:
    """A set of step labels as a Python tuple, in order: ``(100,)``."""
    items = sorted(labels)
    return f"({items[0]},)" if len(items) == 1 else f"({', '.join(map(str, items))})"


def _goto_targets(body: list[A.Stmt]) -> dict[int, A.Stmt]:
    """Each label a GOTO or IF ... GOTO names, with the first statement that names it."""
    found: dict[int, A.Stmt] = {}
    for s in body:
        if isinstance(s, A.Goto | A.IfGoto):
            found.setdefault(s.target, s)
        for b in blocks(s):
            for label, at in _goto_targets(b).items():
                found.setdefault(label, at)
    return found


def _has_goto(body: list[A.Stmt]) -> bool:
    for s in body:
        if isinstance(s, A.Goto | A.IfGoto):
            return True
        if any(_has_goto(b) for b in blocks(s)):
            return True
    return False


def _nested_ids(s: A.Stmt) -> set[int]:
    """The ids of the statements in the blocks of ``s``, at any depth."""
    found: set[int] = set()
    todo = [s]
    while todo:
        for b in blocks(todo.pop()):
            for inner in b:
                found.add(id(inner))
                todo.append(inner)
    return found
