"""One GPL Module -> one Python module (docs/design/lowering.md, "Output layout").

Layout of a generated module: docstring, imports, ``_this`` (only when a module variable is passed
ByRef), delegate classes, module variables at their defaults, Static-local globals, classes,
procedures, ``_init()`` (module variable and Shared field initializers in textual order, §12.2),
then the procedure registrations.  Importing the module runs nothing of the program.
"""

from __future__ import annotations

import os
from typing import NamedTuple

from gpl2py.diagnostics import Diagnostic, DiagnosticSink
from gpl2py.gpl.lower.classes import delegate_line, field_value, lower_class, register_line, register_lines
from gpl2py.gpl.lower.context import ModuleContext, ProjectNames
from gpl2py.pywriter.emit import Writer
from gpl2py.kept import KeptErrors
from gpl2py.gpl.lower.expressions import annotation, default_code
from gpl2py.gpl.lower.names import py_ident, py_literal
from gpl2py.pywriter.text import escape
from gpl2py.gpl.lower.statements import ProcLowerer, lower_procedure
from gpl2py.gpl.semantics.check import Model
from gpl2py.gpl.semantics.symbols import ClassSym, DelegateSym, ModuleSym, ProcSym, VarSym
from gpl2py.gpl.syntax import ast as A


def _import_lines(ctx: ModuleContext) -> list[str]:
    lines: list[str] = []
    if ctx.needs_this:
        lines.append("import sys")
        lines.append("")
    for module in sorted(ctx.imports):
        names = ctx.imports[module]
        parts = [n if a == n else f"{n} as {a}" for n, a in sorted(names.items())]
        text = f"from {module} import {', '.join(parts)}"
        if len(text) > 99:
            lines.append(f"from {module} import (")
            lines.extend(f"    {p}," for p in parts)
            lines.append(")")
        else:
            lines.append(text)
    if ctx.siblings:
        lines.append("")
        lines.append(f"from . import {', '.join(sorted(ctx.siblings))}")
    return lines


def _literal_value(e: A.Expr | None) -> bool:
    return isinstance(e, (A.IntegerLiteral, A.RealLiteral, A.StringLiteral, A.BooleanLiteral)) or (
        isinstance(e, A.Unary) and e.op == "-" and isinstance(e.operand, (A.IntegerLiteral, A.RealLiteral)))


def lower_module(model: Model, names: ProjectNames, mod: ModuleSym, sink: DiagnosticSink, *,
                 text: bool = True, reuse: dict[A.Stmt, Lowered] | None = None) -> LoweredModule:
    """The text of the generated module and, per line, the GPL line it came from.  ``text=False``
    (``gpl2py check``, the language server: the lowering's diagnostics only) stops once every
    procedure and initializer is lowered, with no text: writing it out (PEP 8 line breaking, the
    assembly) reports nothing and was a third of the lowering's time.

    ``reuse`` (with ``text=False``: the language server, with no error reported): what lowering
    each procedure and class declaration of the module reported the last time, by its node, which
    a node lowered then is not lowered again for; it is left holding this module's.  What a
    procedure's lowering reports (a GoTo it cannot translate, nesting Python cannot compile) is
    about its own statements."""
    ctx = ModuleContext(model, names, mod, KeptErrors(sink))
    body = Writer()
    decl = mod.decl
    members: list[A.Stmt] = decl.members if decl is not None else [
        c.decl for c in mod.members.values() if isinstance(c, ClassSym) and c.decl is not None]
    init_low = ProcLowerer(ctx, None, None, sink)
    # delegates and module variables (defaults; initializers run in _init)
    for m in members:
        if isinstance(m, A.DelegateDecl):
            d = mod.members.get(m.name.lower())
            if isinstance(d, DelegateSym):
                body.gpl_line = m.span.line
                body.comments(m.leading_comments)
                mark = body.mark()
                body.line(delegate_line(ctx, d))
                body.trailing(m.trailing_comment, mark)
        elif isinstance(m, A.VarDecl):
            body.gpl_line = m.span.line
            body.comments(m.leading_comments)
            mark = body.mark()
            for d in m.declarators:
                v = mod.members.get(d.name.lower())
                if not isinstance(v, VarSym) or v.decl is not d:
                    continue
                ann = annotation(v.type)
                value = default_code(v.type)
                if _literal_value(d.initializer) and not d.bounds:
                    value = init_low.conv(d.initializer, v.type)[0]  # type: ignore[arg-type]
                elif v in model.const_values:  # a Const folded at translation time
                    value = py_literal(model.const_values[v])
                body.line(f"{py_ident(v.name)}{': ' + ann if ann else ''} = {value}")
            body.trailing(m.trailing_comment, mark)
    # classes and procedures, in source order
    procs: list[ProcSym] = []
    classes: list[ClassSym] = []
    defs = Writer()
    before = dict(reuse) if reuse is not None else None
    if reuse is not None:
        reuse.clear()
    for m in members:
        sym = mod.members.get(getattr(m, "name", "").lower()) if hasattr(m, "name") else None
        if isinstance(m, A.ClassDecl) and isinstance(sym, ClassSym) and sym.decl is m:
            if not _reused(m, before, reuse, ctx, sink):
                own = _Own(m, reuse, ctx, sink)
                defs.blank(2)
                defs.extend(lower_class(ctx, sym, own.sink))
                own.done()
            classes.append(sym)
        elif isinstance(m, A.ProcDecl) and m in model.proc_of_decl:
            proc = model.proc_of_decl[m]  # (each overload of a name is a declaration of its own)
            if not _reused(m, before, reuse, ctx, sink):
                own = _Own(m, reuse, ctx, sink)
                defs.blank(2)
                defs.extend(lower_procedure(ctx, proc, None, own.sink, method=False))
                own.done()
            procs.append(proc)
    # _init: module variables and Shared fields, textual order
    init = Writer()
    init.level = 1
    for m in members:
        if isinstance(m, A.VarDecl):
            for d in m.declarators:
                v = mod.members.get(d.name.lower())
                if isinstance(v, VarSym) and v.decl is d and v not in model.const_values and initialised(d):
                    init.gpl_line = d.span.line
                    init_low.globals.add(py_ident(v.name))
                    init.line(f"{py_ident(v.name)} = {field_value(init_low, v)}")
        elif isinstance(m, A.ClassDecl):
            cls = mod.members.get(m.name.lower())
            if isinstance(cls, ClassSym):
                _shared_inits(ctx, cls, init, init_low)
    # _reset: every module variable and Shared field back to its default (§12.2 step 1), so an
    # initializer that calls a function sees later variables at their defaults, in every session
    resets: list[tuple[str, str]] = []  # (target, value)
    for m in members:
        if isinstance(m, A.VarDecl):
            for d in m.declarators:
                v = mod.members.get(d.name.lower())
                if isinstance(v, VarSym) and v.decl is d:
                    resets.append((py_ident(v.name), reset_value(ctx, v)))
        elif isinstance(m, A.ClassDecl):
            cls = mod.members.get(m.name.lower())
            if isinstance(cls, ClassSym):
                resets.extend(_shared_resets(ctx, cls))
    seen_statics: set[str] = set()
    for name, value in ctx.statics:  # Static locals start afresh in a new session too
        if name not in seen_statics:
            seen_statics.add(name)
            resets.append((name, value))
    entries: set[str] = set()
    if resets:
        entries.add("_reset")
        defs.blank(2)
        defs.line("def _reset() -> None:")
        defs.indent()
        defs.line('"""Module variables, Shared fields and Static locals at their defaults (§12.2, step 1)."""')
        names_reset = sorted({target for target, _ in resets if "." not in target})
        if names_reset:
            defs.line("global " + ", ".join(names_reset))
        for target, value in resets:
            defs.line(f"{target} = {value}")
        defs.dedent()
    if init.lines:
        entries.add("_init")
        defs.blank(2)
        defs.line("def _init() -> None:")
        defs.indent()
        defs.line('"""Module variable and Shared field initializers, in textual order (§12.2)."""')
        if init_low.globals:
            defs.line("global " + ", ".join(sorted(init_low.globals)))
        defs.dedent()
        defs.extend(init)
    if not text:
        return LoweredModule("", [], frozenset(entries))
    # registrations
    reg_lines: list[str] = []
    for p in procs:
        reg_lines.append(register_line(ctx, mod.name, p, ""))
    for c in classes:
        reg_lines.extend(register_lines(ctx, c))
    if ctx.statics:
        if body.lines:  # apart from what precedes; at the top, the blank lines before body suffice
            body.line("")
        body.line("# Static locals (§6.2): one per procedure, kept between calls")
        seen: set[str] = set()
        for name, value in ctx.statics:
            if name not in seen:
                seen.add(name)
                body.line(f"{name} = {value}")
    # assemble
    out = Writer()
    source = mod.path
    what = f"Module {mod.name}" if decl is not None else "Top-level classes"
    out.line(f'"""{what}, transpiled by gpl2py from {escape(os.path.basename(source), "docstring")}."""')
    if decl is not None:
        out.comments(decl.leading_comments)
        if decl.trailing_comment is not None:  # the comment on the 'Module Name' line
            out.comments([decl.trailing_comment])
    imports = _import_lines(ctx)
    if imports:
        out.blank()
        for line in imports:
            out.line(line)
    if ctx.needs_this:
        out.blank()
        out.line("_this = sys.modules[__name__]  # module variables passed ByRef alias attributes of this module")
    if body.lines:
        out.blank(2 if imports else 1)
        out.extend(body)
    out.extend(defs)
    if decl is not None:
        out.comments(decl.end_comments)
        if decl.end_comment is not None:  # the comment on the 'End Module' line
            out.comments([decl.end_comment])
    if reg_lines:
        out.blank(2)
        for line in reg_lines:
            out.line(line)
    text, lines = out.render()
    return LoweredModule(text, lines, frozenset(entries))


class Lowered(NamedTuple):
    """What lowering one declaration of a module reported, and the Static locals it declared."""

    diags: list[Diagnostic]
    statics: list[tuple[str, str]]


def _reused(node: A.Stmt, before: dict[A.Stmt, Lowered] | None, reuse: dict[A.Stmt, Lowered] | None,
            ctx: ModuleContext, sink: DiagnosticSink) -> bool:
    """Replay the last lowering of ``node`` if there was one (``lower_module``'s ``reuse``)."""
    kept = before.get(node) if before is not None else None
    if kept is None or reuse is None:
        return False
    sink.extend(kept.diags)
    ctx.statics.extend(kept.statics)
    reuse[node] = kept
    return True


class _Own:
    """Lowering one declaration: with ``reuse``, its diagnostics and Static locals are noted."""

    def __init__(self, node: A.Stmt, reuse: dict[A.Stmt, Lowered] | None, ctx: ModuleContext,
                 sink: DiagnosticSink) -> None:
        self.node, self.reuse, self.ctx, self.outer = node, reuse, ctx, sink
        self.sink = DiagnosticSink() if reuse is not None else sink  # (unfiltered, replayed below)
        self.statics = len(ctx.statics)

    def done(self) -> None:
        if self.reuse is not None:
            diags = list(self.sink)
            self.outer.extend(diags)
            self.reuse[self.node] = Lowered(diags, self.ctx.statics[self.statics:])


class LoweredModule(NamedTuple):
    """A generated module: its text, the GPL line of each of its lines, and which of ``_reset`` /
    ``_init`` it defines (a module with nothing to reset or initialise has neither, and the
    package's ``init()`` does not call them)."""

    text: str
    lines: list[int]
    entries: frozenset[str]


def initialised(d: A.VarDeclarator) -> bool:
    """Whether declaring ``d`` stores something of its own (an initializer, ``New``, array
    bounds): a variable without one keeps the default ``_reset()`` gave it, so ``_init()`` has
    nothing to do for it (the controller runs no code for a bare declaration)."""
    return d.initializer is not None or bool(d.new) or bool(d.bounds and all(b is not None for b in d.bounds))


def reset_value(ctx: ModuleContext, v: VarSym) -> str:
    """What ``_reset()`` stores: the default of the type, or the value of a Const folded at
    translation time, which stays valid whatever order the modules initialise in."""
    if v in ctx.model.const_values:
        return py_literal(ctx.model.const_values[v])
    return default_code(v.type)


def _shared_resets(ctx: ModuleContext, cls: ClassSym) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    for m in cls.members.values():
        if isinstance(m, VarSym) and m.shared:
            out.append((f"{ctx.class_ref(cls)}.{py_ident(m.name)}", reset_value(ctx, m)))
        elif isinstance(m, ClassSym):
            out.extend(_shared_resets(ctx, m))
    return out


def _shared_inits(ctx: ModuleContext, cls: ClassSym, init: Writer, low: ProcLowerer) -> None:
    shared_low = ProcLowerer(ctx, None, cls, low.sink)
    for m in cls.decl.members if cls.decl is not None else []:
        if isinstance(m, A.VarDecl):
            for d in m.declarators:
                v = cls.members.get(d.name.lower())
                if isinstance(v, VarSym) and v.decl is d and v.shared and v not in ctx.model.const_values \
                        and initialised(d):
                    init.gpl_line = d.span.line
                    init.line(f"{ctx.class_ref(cls)}.{py_ident(v.name)} = {field_value(shared_low, v)}")
        elif isinstance(m, A.ClassDecl):
            inner = cls.members.get(m.name.lower())
            if isinstance(inner, ClassSym):
                _shared_inits(ctx, inner, init, low)
