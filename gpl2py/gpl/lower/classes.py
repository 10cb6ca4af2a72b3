"""User classes -> Python classes (docs/design/lowering.md, "Classes, delegates, built-ins").

Instance fields are ``__slots__`` attributes created by ``__init__`` (initializers first, then the
user's ``New``, AMB-7); Shared fields are class attributes whose initializers run in the module's
``_init()`` with the module variables (§8.3).  Several ``Sub New`` overloads become ``_new_<k>``
methods plus one ``_create_<k>`` classmethod each -- the semantic pass already chose the overload,
so ``New C(1)`` lowers to ``C._create_1(1)`` -- and an ``__init__(*args)`` that picks by argument
count for hand-written Python.
"""

from __future__ import annotations

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.gpl.lower.context import ModuleContext
from gpl2py.pywriter.emit import MAX_INDENT, Line, Writer
from gpl2py.gpl.lower.expressions import default_code
from gpl2py.gpl.lower.names import py_ident, py_literal
from gpl2py.pywriter.text import py_string
from gpl2py.gpl.lower.statements import ProcLowerer, lower_procedure
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.symbols import ClassSym, DelegateSym, ProcSym, PropSym, VarSym, procedures
from gpl2py.gpl.syntax import ast as A


_UNFOLDED = object()


def field_value(low: ProcLowerer, v: VarSym) -> str:
    """The initial value of a field or module variable: array, New, initializer or default."""
    d = v.decl
    if d is not None:
        value = low.declarator_value(d, v)
        if value is not None:
            return value
    return default_code(v.type)


def delegate_line(ctx: ModuleContext, d: DelegateSym) -> str:
    fn = ctx.helper("gplrt.lang.delegates", "delegate_type")
    return f"{py_ident(d.name)} = {fn}({py_string(d.name)}, {len(d.params)})"


def lower_class(ctx: ModuleContext, cls: ClassSym, sink: DiagnosticSink) -> Writer:
    w = Writer()
    decl = cls.decl
    assert decl is not None
    depth = len(cls.path)  # the class statement is indented depth - 1 levels, its methods' bodies depth + 1
    if depth + 1 > MAX_INDENT:
        sink.report(M.NESTED_TOO_DEEPLY, decl.span,
                    detail=f"its methods would be indented {depth + 1} levels and Python allows {MAX_INDENT}")
        w.line(f"{py_ident(cls.name)} = None  # nested too deeply for Python (reported)")
        return w
    w.gpl_line = decl.span.line
    w.comments(decl.leading_comments)
    mark = w.mark()
    w.line(f"class {py_ident(cls.name)}:")
    w.trailing(decl.trailing_comment, mark)
    w.indent()
    w.line(f'"""GPL class {cls.name}."""')
    instance_fields = [m for m in cls.fields() if not m.shared]
    slots = ", ".join(py_string(py_ident(f.name)) for f in instance_fields)
    w.line(f"__slots__ = ({slots}{',' if len(instance_fields) == 1 else ''})")
    if ctx.names.dynamic_members:
        w.line(f"_gpl_members_ = {{{gpl_members(cls)}}}")
    for member in decl.members:
        if isinstance(member, A.VarDecl):
            shared = [v for v in _declared(cls, member) if v.shared]
            if shared:
                w.gpl_line = member.span.line
                w.comments(member.leading_comments)
                mark = w.mark()
                for v in shared:
                    folded = ctx.model.const_values.get(v, _UNFOLDED)
                    value = default_code(v.type) if folded is _UNFOLDED else py_literal(folded)
                    w.line(f"{py_ident(v.name)} = {value}")
                w.trailing(member.trailing_comment, mark)
    for member in decl.members:
        if isinstance(member, A.DelegateDecl):
            d = cls.members.get(member.name.lower())
            if isinstance(d, DelegateSym):
                w.gpl_line = member.span.line
                w.comments(member.leading_comments)
                mark = w.mark()
                w.line(delegate_line(ctx, d))
                w.trailing(member.trailing_comment, mark)
        elif isinstance(member, A.ClassDecl):
            inner = cls.members.get(member.name.lower())
            if isinstance(inner, ClassSym) and inner.decl is member:
                w.blank()
                w.extend(lower_class(ctx, inner, sink), extra_indent=w.level)
    # constructors and field initialisation
    fields = _field_lines(ProcLowerer(ctx, None, cls, sink), cls, decl)
    if not cls.ctors:
        if fields.lines:
            w.blank()
            w.line("def __init__(self) -> None:")
            w.extend(fields, extra_indent=w.level + 1)
    elif len(cls.ctors) == 1:
        w.blank()
        w.extend(_method(ctx, cls, cls.ctors[0], sink, fields), extra_indent=w.level)
    else:
        w.blank()
        w.line("def __init__(self, *args) -> None:")
        w.indent()
        w.line("self._init_fields()")
        for k, (c, test) in enumerate(_ctor_dispatch(ctx, cls.ctors)):
            w.line(f"{'if' if k == 0 else 'elif'} {test}:")
            w.line(f"    self._new_{c.overload_index}({'*args' if c.params else ''})")
        w.dedent()
        w.blank()
        w.line("def _init_fields(self) -> None:")
        w.extend(fields if fields.lines else _pass(), extra_indent=w.level + 1)
        for c in cls.ctors:
            w.blank()
            w.extend(_method(ctx, cls, c, sink), extra_indent=w.level)
            names = ", ".join(py_ident(p.name) for p in c.params)
            w.blank()
            w.line("@classmethod")
            w.line(f"def _create_{c.overload_index}(cls{', ' if names else ''}{names}):")
            w.indent()
            w.line("self = cls.__new__(cls)")
            w.line("self._init_fields()")
            w.line(f"self._new_{c.overload_index}({names})")
            w.line("return self")
            w.dedent()
    for member in decl.members:
        sym = cls.members.get(getattr(member, "name", "").lower()) if hasattr(member, "name") else None
        proc = ctx.model.proc_of_decl.get(member) if isinstance(member, A.ProcDecl) else None
        if proc is not None and proc.kind != "New":  # (each overload is a declaration of its own)
            w.blank()
            w.extend(_method(ctx, cls, proc, sink), extra_indent=w.level)
        elif isinstance(member, A.PropertyDecl) and isinstance(sym, PropSym) and sym.decl is member:
            w.blank()
            w.gpl_line = member.span.line
            w.comments(member.leading_comments)  # the Property line's comments, above its accessors
            if member.trailing_comment is not None:
                w.comments([member.trailing_comment])
            first = True
            for acc in (sym.getter, sym.setter):
                if acc is not None:
                    if not first:
                        w.blank()
                    first = False
                    w.extend(_method(ctx, cls, acc, sink), extra_indent=w.level)
            if sym.getter is None and sym.setter is not None and not sym.shared:
                name = py_ident(sym.name)
                w.line(f"{name} = property(fset=_set_{name})  # write-only property")
            w.comments(member.end_comments)
            if member.end_comment is not None:
                w.comments([member.end_comment])
    w.comments(decl.end_comments)
    if decl.end_comment is not None:
        w.comments([decl.end_comment])
    w.dedent()
    return w


def _declared(cls: ClassSym, member: A.VarDecl) -> list[VarSym]:
    """The fields ``member`` declares (a declarator reported as a duplicate declares none)."""
    out = []
    for d in member.declarators:
        v = cls.members.get(d.name.lower())
        if isinstance(v, VarSym) and v.decl is d:
            out.append(v)
    return out


def _field_lines(low: ProcLowerer, cls: ClassSym, decl: A.ClassDecl) -> Writer:
    """``self.<field> = <value>`` for every instance field, in declaration order, each declaration
    with its comments (the line's comment trails the first of its fields)."""
    w = Writer()
    for member in decl.members:
        if isinstance(member, A.VarDecl):
            fields = [v for v in _declared(cls, member) if not v.shared]
            if fields:
                w.gpl_line = member.span.line
                w.comments(member.leading_comments)
                mark = w.mark()
                for v in fields:
                    w.line(f"self.{py_ident(v.name)} = {field_value(low, v)}")
                w.trailing(member.trailing_comment, mark)
    return w


def _pass() -> Writer:
    w = Writer()
    w.line("pass")
    return w


def gpl_members(cls: ClassSym) -> str:
    """The Public members of ``cls`` for ``gplrt.lang.members``: GPL name (lower case) -> Python
    name.  Only a project that reads members of values of unknown type needs it (a stub's result
    may be one of its objects); the runtime reaches nothing of a class that is not listed."""
    members = sorted((m.name.lower(), py_ident(m.name)) for m in cls.members.values()
                     if isinstance(m, (VarSym, ProcSym, PropSym)) and m.public)
    return ", ".join(f"{py_string(k)}: {py_string(v)}" for k, v in members)


def _ctor_dispatch(ctx: ModuleContext, ctors: list[ProcSym]) -> list[tuple[ProcSym, str]]:
    """How ``__init__(*args)`` (for hand-written Python; generated code calls ``_create_<k>``)
    picks among several ``Sub New``: by argument count, and among constructors with the same
    count by the Python types of the arguments (``isinstance(args[0], str)``), the last declared
    of them taking whatever the others did not."""
    groups: dict[int, list[ProcSym]] = {}
    for c in ctors:
        groups.setdefault(len(c.params), []).append(c)
    out: list[tuple[ProcSym, str]] = []
    for count, group in groups.items():
        required = min(c.min_args for c in group)
        size = f"len(args) == {count}" if required == count else f"{required} <= len(args) <= {count}"
        for i, c in enumerate(group):
            tests = [_isinstance_test(ctx, k, p.type) for k, p in enumerate(c.params)] if i < len(group) - 1 else []
            out.append((c, " and ".join([size, *[x for x in tests if x]])))
    return out


def _isinstance_test(ctx: ModuleContext, k: int, typ: t.GplType) -> str:
    """``isinstance(args[k], <the Python type of a GPL typ value>)``, or "" if it cannot be told."""
    py = {t.BOOLEAN: "bool", t.BYTE: "int", t.SHORT: "int", t.INTEGER: "int", t.SINGLE: "float",
          t.DOUBLE: "float", t.STRING: "str"}.get(typ)  # type: ignore[call-overload]
    if py is None and isinstance(typ, t.ClassType):
        user = ctx.model.resolver.class_of(typ)
        builtin = ctx.model.resolver.builtin_of(typ)
        if user is not None:
            py = ctx.class_ref(user)
        elif builtin is not None and not builtin.is_global:
            py = ctx.builtin(builtin.python_name)
    if py is None and isinstance(typ, t.ArrayType):
        py = ctx.helper("gplrt.lang.arrays", "GplArray")
    return f"isinstance(args[{k}], {py})" if py else ""


def _method(ctx: ModuleContext, cls: ClassSym, p: ProcSym, sink: DiagnosticSink,
            fields: Writer | None = None) -> Writer:
    out = lower_procedure(ctx, p, cls, sink, method=True)
    if fields is not None and fields.lines:
        # field initialisers run before the user's New (AMB-7): right after the def line
        assert out.def_at is not None
        at = out.def_at
        indent = out.lines[at].indent + 1
        out.lines[at + 1:at + 1] = [Line(indent + f.indent, f.text, f.gpl_line, f.comment) for f in fields.lines]
    return out


def register_lines(ctx: ModuleContext, cls: ClassSym) -> list[str]:
    """Registry entries for the Shared procedures of ``cls`` and its nested classes (§9.4).

    The registry helper is imported only when an entry uses it: a class with no Shared procedure
    registers nothing, and an unused import would fail pyflakes."""
    out: list[str] = []
    qual = ".".join(([cls.module.name] if cls.module and cls.module.name != "_Top" else []) + cls.path)
    ref = ctx.class_ref(cls)
    for m in cls.members.values():
        for p in procedures(m):
            if p.shared:
                out.append(register_line(ctx, qual, p, ref + ".", public=p.public and cls.public))
        if isinstance(m, ClassSym):
            out.extend(register_lines(ctx, m))
    return out


def register_line(ctx: ModuleContext, qualifier: str, p: ProcSym, prefix: str,
                  public: bool | None = None) -> str:
    """``register_procedure("Module", "Proc", gpl_entry(Proc), ...)`` for procedure ``p`` (§9.4):
    into this package's own registry (gplrt.lang.procedures).  An overload also passes its
    index, so the registry keeps every overload of the name and a lookup by name can choose
    by argument count."""
    reg = ctx.helper("gplrt.lang.procedures", "register_procedure")
    entry = ctx.helper("gplrt.lang.exceptions", "gpl_entry")
    overload = f", overload={p.overload_index}" if p in ctx.names.overload_py else ""
    return (f"{reg}({py_string(qualifier)}, {py_string(p.name)}, {entry}({prefix}{ctx.names.proc_name(p)}), "
            f"public={p.public if public is None else public}{overload}, package=__package__)")
