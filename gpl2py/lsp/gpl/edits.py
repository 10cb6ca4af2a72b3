"""Rename (project-wide, refused with a reason when it would change what a name means) and the
quick fixes of an undeclared name (did you mean, a missing Dim)."""

from __future__ import annotations

import difflib
import re
from typing import Any

from lsprotocol import types as T
from pygls.uris import from_fs_path

from gpl2py import messages as M
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, load_catalogue
from gpl2py.gpl.semantics.symbols import ClassSym, ModuleSym, ProcSym, PropSym, VarSym
from gpl2py.gpl.syntax import ast as A
from gpl2py.lsp import convert
from gpl2py.lsp.gpl.complete import (
    DECLARATION_KEYWORDS,
    EXPRESSION_KEYWORDS,
    STATEMENT_KEYWORDS,
    TYPE_NAMES,
    names_in_scope,
)
from gpl2py.lsp.gpl.index import Index, Occ, Refused, at_cursor, in_order, loaded_index, occ_range
from gpl2py.lsp.projects import ProjectState


_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


RESERVED = {w.lower() for w in STATEMENT_KEYWORDS + DECLARATION_KEYWORDS + EXPRESSION_KEYWORDS + TYPE_NAMES
            if " " not in w} | {"end", "then", "to", "step", "each", "in", "as", "byval", "byref", "optional",
                                "module", "call", "until", "case", "of", "preserve", "goto", "next", "loop"}


def _renamable(o: Occ | None) -> bool:
    return o is not None and isinstance(o.sym, (VarSym, ProcSym, PropSym, ClassSym, A.Label)) \
        and not (isinstance(o.sym, ProcSym) and o.sym.name.lower() == "new")


def prepare_rename(ls: Any, state: ProjectState, path: str, params: Any) -> T.Range | None:
    found = at_cursor(ls, state, path, params)
    if found is None or not _renamable(found[2]):
        raise Refused("only a variable, parameter, procedure, property, class or label of this project can be renamed")
    return occ_range(ls, found[1], found[2])  # type: ignore[arg-type]


def rename(ls: Any, state: ProjectState, path: str, params: T.RenameParams) -> T.WorkspaceEdit | None:
    found = at_cursor(ls, state, path, params)
    if found is None or not _renamable(found[2]):
        raise Refused("only a variable, parameter, procedure, property, class or label of this project can be renamed")
    index, _, o = found
    assert o is not None
    new = params.new_name.strip()
    if not _IDENT.fullmatch(new) or new.lower() in RESERVED:
        raise Refused(f"'{new}' is not a GPL name (a letter or _, then letters, digits or _; not a keyword)")
    problem = collision(o.sym, new, index)
    if problem is not None:
        raise Refused(problem)
    changes: dict[str, list[T.TextEdit]] = {}
    for x in in_order(index.occurrences(o.sym)):
        lines = convert.lines_of(state.last.files.get(x.path, "")) if state.last else []
        changes.setdefault(from_fs_path(x.path) or x.path, []).append(T.TextEdit(range=occ_range(ls, lines, x),
                                                                                  new_text=new))
    return T.WorkspaceEdit(changes=changes)


def collision(sym: object, new: str, index: Index) -> str | None:
    """Why renaming ``sym`` to ``new`` would change what a name means, or None."""
    key = new.lower()
    if key == getattr(sym, "name", "").lower():
        return None
    project = index.model.project
    if isinstance(sym, ClassSym) and len(index.class_names.get(sym.name.lower(), [])) > 1:
        return f"the project has several classes named '{sym.name}': their type names cannot be told apart"
    if isinstance(sym, A.Label):
        index.occurrences(sym)  # (every file's procedures known)
        for proc in (p for lst in index.procs.values() for _, _, p, _, _ in lst):
            if proc.labels.get(sym.name.lower()) is sym and key in proc.labels:
                return f"the procedure already has a label '{new}'"
        return None
    if isinstance(sym, VarSym) and sym.storage in ("local", "static", "param") and isinstance(sym.owner, ProcSym):
        proc = sym.owner
        clash = next((v for v in [*proc.params, *proc.locals.values()] if v.name.lower() == key), None)
        if clash is not None:
            return f"'{new}' is already declared in {proc.name}"
        if key == proc.name.lower() and proc.is_function:
            return f"'{new}' is the name of the Function {proc.name}, its result variable"
        scopes = _scope_of_proc(index, proc)
        hit = next((n for n, s in names_in_scope(index, None, *scopes) if n.lower() == key), None)
        if hit is not None:
            return f"'{new}' would hide '{hit}', which {proc.name} can use now"
        return None
    owner = getattr(sym, "owner", None) if not isinstance(sym, ClassSym) else (sym.outer or sym.module)
    members = getattr(owner, "members", {})
    if key in members:
        return f"{getattr(owner, 'name', 'the module')} already has a member '{new}'"
    if key in project.modules:
        return f"'{new}' is the name of a module"
    if project.public_members(new) and getattr(sym, "public", False):
        where = project.public_members(new)[0].where
        return f"'{new}' is already a Public name of {where}"
    cat = load_catalogue()
    if cat.lookup_class(new) or cat.lookup_function(new) or cat.lookup_constant(new):
        return f"'{new}' is a built-in name"
    for o in index.occurrences(sym):  # a local of the new name where the symbol is used would capture it
        for first, last, proc, _, _ in index.procs.get(o.path, ()):
            if first <= o.line <= last and any(v.name.lower() == key for v in [*proc.params, *proc.locals.values()]):
                return f"'{new}' is a local of {proc.name}, which uses '{getattr(sym, 'name', '')}'"
    return None


def _scope_of_proc(index: Index, proc: ProcSym) -> tuple[ClassSym | None, ModuleSym | None]:
    index.occurrences(proc)  # (every file's procedures known)
    for lst in index.procs.values():
        for _, _, p, cls, mod in lst:
            if p is proc:
                return cls, mod
    return None, proc.module


def code_actions(ls: Any, state: ProjectState, path: str, params: T.CodeActionParams) -> list[T.CodeAction] | None:
    ready = loaded_index(ls, state, path)
    if ready is None:
        return None
    index, lines = ready
    codec = ls.workspace.position_codec
    out: list[T.CodeAction] = []
    uri = from_fs_path(path) or path
    for d in params.context.diagnostics:
        if d.code != M.UNDECLARED_NAME.code:
            continue
        line, col = convert.from_client(lines, d.range.start, codec)
        m = re.match(r"'(.+)' is not declared$", d.message)
        if m is None:
            continue
        name = m.group(1)
        proc, cls, mod = index.scope(path, line)
        candidates = [n for n, s in names_in_scope(index, proc, cls, mod)
                      if not isinstance(s, (BuiltinClass, ModuleSym))]
        close = difflib.get_close_matches(name, candidates, n=2, cutoff=0.8)
        if len(close) == 1 or (close and difflib.SequenceMatcher(None, name.lower(), close[0].lower()).ratio() >
                               difflib.SequenceMatcher(None, name.lower(), close[1].lower()).ratio() + 0.1):
            out.append(T.CodeAction(title=f"Change '{name}' to '{close[0]}'", kind=T.CodeActionKind.QuickFix,
                                    diagnostics=[d], is_preferred=True,
                                    edit=T.WorkspaceEdit(changes={uri: [T.TextEdit(range=d.range, new_text=close[0])]})))
        dim = _missing_dim(index, path, line, col, name, proc)
        if dim is not None:
            at, indent, typ = dim
            text = f"{indent}Dim {name} As {typ}\n"
            pos = T.Position(line=at - 1, character=0)
            out.append(T.CodeAction(title=f"Declare 'Dim {name} As {typ}'", kind=T.CodeActionKind.QuickFix,
                                    diagnostics=[d],
                                    edit=T.WorkspaceEdit(changes={uri: [T.TextEdit(range=T.Range(pos, pos),
                                                                                   new_text=text)]})))
    return out


def _missing_dim(index: Index, path: str, line: int, col: int, name: str,
                 proc: ProcSym | None) -> tuple[int, str, str] | None:
    """Where to declare an undeclared ``name`` assigned at ``line:col`` (the first line of its
    procedure's body), with its indentation and the type its assigned value has."""
    if proc is None or not isinstance(proc.decl, A.ProcDecl):
        return None
    unit = index.units.get(path)
    if unit is None:
        return None
    model = index.model
    typ: t.GplType | None = None
    stack: list[A.Node] = [proc.decl.body]
    while stack and typ is None:
        node = stack.pop()
        target = value = None
        if isinstance(node, A.Assign):
            target, value = node.target, node.value
        elif isinstance(node, A.For):
            target, value = node.var, node.start
        if isinstance(target, A.Name) and target.name.lower() == name.lower() and target.span.line == line \
                and target.span.col == col:
            typ = model.type_of(value) if value is not None else None
        stack.extend(node.children())
    if typ is None or typ in (t.ERROR, t.VOID, t.ANY):
        return None
    body = proc.decl.body.statements
    first = body[0].span.line if body else proc.decl.span.line + 1
    rows = convert.lines_of(index.texts.get(path, ""))
    row = rows[first - 1] if body and first - 1 < len(rows) else ""
    indent = row[:len(row) - len(row.lstrip())] if body else " " * (proc.decl.span.col + 3)
    return first, indent, str(typ)
