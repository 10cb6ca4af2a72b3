"""Completion and signature help on the text being typed.

The text has not been checked yet (a half-typed ``Cmd.`` is a syntax error): the words before the
cursor are resolved through the scopes of the enclosing procedure of the last analysis, in the
order of spec §6.4.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

from lsprotocol import types as T
from pygls.uris import from_fs_path

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import (
    BuiltinClass,
    BuiltinConstant,
    BuiltinFunction,
    Catalogue,
    load_catalogue,
)
from gpl2py.gpl.semantics.catalogue import Member as BuiltinMember
from gpl2py.gpl.semantics.symbols import ClassSym, ModuleSym, OverloadSet, ProcSym, PropSym, VarSym
from gpl2py.lsp import convert
from gpl2py.lsp.gpl.describe import (
    builtin_param_text,
    function_signature,
    member_signature,
    param_text,
    proc_signature,
)
from gpl2py.lsp.gpl.index import Index, loaded_index
from gpl2py.lsp.projects import ProjectState


STATEMENT_KEYWORDS = ("Dim", "Static", "Const", "If", "ElseIf", "Else", "End If", "For", "For Each", "Next",
                      "While", "End While", "Do", "Loop", "Select Case", "Case", "End Select", "Try", "Catch",
                      "Finally", "End Try", "Return", "Exit", "GoTo", "Throw", "ReDim")


DECLARATION_KEYWORDS = ("Public", "Private", "Shared", "Dim", "Const", "Sub", "Function", "Property", "Class",
                        "Delegate", "End Module", "End Class")


EXPRESSION_KEYWORDS = ("New", "Not", "And", "AndAlso", "Or", "OrElse", "Xor", "Mod", "Is", "True", "False",
                       "Nothing", "Me", "AddressOf")


TYPE_NAMES = ("Integer", "Short", "Byte", "Single", "Double", "Boolean", "String", "Object")


_CHAIN = re.compile(r"([A-Za-z_]\w*(?:\s*\.\s*[A-Za-z_]\w*)*)\s*\.\s*(\w*)$")


_AS = re.compile(r"\b(As(?:\s+New)?|New)\s+(\w*)$", re.IGNORECASE)


def _current_lines(ls: Any, path: str, state: ProjectState) -> list[str]:
    uri = from_fs_path(path) or path
    doc = ls.workspace.text_documents.get(uri)
    if doc is not None:
        return convert.lines_of(doc.source)
    return convert.lines_of(state.last.files.get(path, "")) if state.last else []


def _typing(ls: Any, state: ProjectState, path: str, params: Any) -> tuple[Index, int, str] | None:
    """The index, the cursor's line and the code before the cursor in the text being typed;
    None inside a comment or a string, or before the first check."""
    ready = loaded_index(ls, state, path)
    if ready is None:
        return None
    lines = _current_lines(ls, path, state)
    line, col = convert.from_client(lines, params.position, ls.workspace.position_codec)
    before = _code_part((lines[line - 1] if 0 < line <= len(lines) else "")[:col - 1])
    return (ready[0], line, before) if before is not None else None


def completion(ls: Any, state: ProjectState, path: str, params: T.CompletionParams) -> T.CompletionList | None:
    typing = _typing(ls, state, path, params)
    if typing is None:
        return None
    index, line, before = typing
    proc, cls, mod = index.scope(path, line)
    chain = _CHAIN.search(before)
    items: list[T.CompletionItem] = []
    if chain is not None:
        target = resolve_chain([p.strip() for p in chain.group(1).split(".")], index, proc, cls, mod)
        items = [_item(name, sym, owner) for name, sym, owner in members_of(target, index, mod)]
    elif _AS.search(before):
        items = [T.CompletionItem(label=n, kind=T.CompletionItemKind.Keyword) for n in TYPE_NAMES]
        items += [T.CompletionItem(label=c.name, kind=T.CompletionItemKind.Class, detail="built-in class")
                  for c in load_catalogue().classes.values()]
        items += [T.CompletionItem(label=c.name, kind=T.CompletionItemKind.Class) for c in index.classes.values()]
    else:
        at_start = re.fullmatch(r"\s*(\w+:\s*)?\w*", before) is not None
        words = (STATEMENT_KEYWORDS if proc is not None else DECLARATION_KEYWORDS) if at_start else EXPRESSION_KEYWORDS
        items = [T.CompletionItem(label=k, kind=T.CompletionItemKind.Keyword) for k in words]
        items += [_item(name, sym, None) for name, sym in names_in_scope(index, proc, cls, mod)]
    return T.CompletionList(is_incomplete=False, items=items)


def _code_part(text: str) -> str | None:
    """``text`` if the cursor after it is in code, None in a comment or a string literal."""
    quoted = False
    for ch in text:
        if ch == '"':
            quoted = not quoted
        elif ch == "'" and not quoted:
            return None
    return None if quoted else text


def _item(name: str, sym: object, owner: object) -> T.CompletionItem:
    kind, detail = T.CompletionItemKind.Variable, None
    if isinstance(sym, BuiltinMember):
        kind = T.CompletionItemKind.Property if sym.kind == "property" else T.CompletionItemKind.Method
        detail = member_signature(sym)
    elif isinstance(sym, BuiltinFunction):
        kind, detail = T.CompletionItemKind.Function, function_signature(sym)
    elif isinstance(sym, BuiltinConstant):
        kind, detail = T.CompletionItemKind.Constant, f"As {sym.type}"
    elif isinstance(sym, (BuiltinClass, ClassSym)):
        kind = T.CompletionItemKind.Class
    elif isinstance(sym, ModuleSym):
        kind = T.CompletionItemKind.Module
    elif isinstance(sym, OverloadSet):
        kind, detail = T.CompletionItemKind.Function, " | ".join(proc_signature(p) for p in sym.procs)
    elif isinstance(sym, ProcSym):
        kind = T.CompletionItemKind.Method if isinstance(sym.owner, ClassSym) else T.CompletionItemKind.Function
        detail = proc_signature(sym)
    elif isinstance(sym, PropSym):
        kind, detail = T.CompletionItemKind.Property, f"Property {sym.name} As {sym.type}"
    elif isinstance(sym, VarSym):
        kind = T.CompletionItemKind.Constant if sym.const else (
            T.CompletionItemKind.Field if sym.storage in ("field", "module") else T.CompletionItemKind.Variable)
        detail = f"{sym.name} As {sym.type}"
    return T.CompletionItem(label=name, kind=kind, detail=detail)


def names_in_scope(index: Index, proc: ProcSym | None, cls: ClassSym | None,
                   mod: ModuleSym | None) -> Iterator[tuple[str, object]]:
    """Every name usable unqualified at a place, nearest first (spec §6.4), each once."""
    seen: set[str] = set()

    def once(items: Any) -> Iterator[tuple[str, object]]:
        for name, sym in items:
            if name.lower() not in seen:
                seen.add(name.lower())
                yield name, sym

    if proc is not None:
        yield from once((v.name, v) for v in proc.params)
        yield from once((v.name, v) for v in proc.locals.values())
    c = cls
    while c is not None:
        yield from once((getattr(m, "name", k), m) for k, m in c.members.items())
        c = c.outer
    if mod is not None:
        yield from once((getattr(m, "name", k), m) for k, m in mod.members.items())
    project = index.model.project
    for other in project.module_list:
        yield from once((getattr(m, "name", k), m) for k, m in other.members.items() if getattr(m, "public", False))
        yield from once([(other.name, other)])
    if project.top is not None:
        yield from once((getattr(m, "name", k), m) for k, m in project.top.members.items())
    cat = load_catalogue()
    yield from once((c.name, c) for c in cat.classes.values())
    yield from once((f.name, f) for f in cat.functions.values())
    yield from once((k.name, k) for k in cat.constants.values())


def resolve_chain(parts: list[str], index: Index, proc: ProcSym | None, cls: ClassSym | None,
                  mod: ModuleSym | None) -> object:
    """What ``a.b.c`` names at a place: a module, a class (for its Shared members), a built-in
    class, or a value's type; None when unknown."""
    if not parts:
        return None
    first = parts[0].lower()
    target: object = None
    for name, sym in names_in_scope(index, proc, cls, mod):
        if name.lower() == first:
            target = sym
            break
    if target is None and first == "string":
        target = load_catalogue().type_members.get("string")
    for part in parts[1:]:
        found = None
        for name, sym, _ in members_of(target, index, mod):
            if name.lower() == part.lower():
                found = sym
                break
        target = _value_type(found) if not isinstance(found, (ModuleSym, ClassSym, BuiltinClass)) else found
        if target is None:
            return None
    return _value_type(target) if not isinstance(target, (ModuleSym, ClassSym, BuiltinClass)) else target


def _value_type(sym: object) -> object:
    """The type whose members ``sym.`` lists: a variable's, a property's, a function's result."""
    if isinstance(sym, (VarSym, PropSym)):
        return sym.type
    if isinstance(sym, ProcSym) and sym.is_function:
        return sym.result
    if isinstance(sym, OverloadSet):
        return sym.result
    if isinstance(sym, BuiltinMember):
        return sym.result
    if isinstance(sym, BuiltinFunction):
        return sym.result
    if isinstance(sym, t.GplType):
        return sym
    return None


def members_of(target: object, index: Index, here: ModuleSym | None) -> list[tuple[str, object, object]]:
    """``(name, member, its built-in class)`` of what ``target.`` reaches."""
    cat: Catalogue = load_catalogue()
    if isinstance(target, ModuleSym):
        return [(getattr(m, "name", k), m, None) for k, m in target.members.items()
                if target is here or getattr(m, "public", False)]
    if isinstance(target, ClassSym):  # the class's name: its Shared members, Consts and nested classes
        return [(getattr(m, "name", k), m, None) for k, m in target.members.items()
                if getattr(m, "shared", False) or getattr(m, "const", False) or isinstance(m, ClassSym)]
    if isinstance(target, BuiltinClass):  # the class's name: its Shared members (a global class's: all)
        every = target.is_global or target is cat.type_members.get("string")
        return [(m.name, m, target) for m in target.members.values() if every or m.shared]
    if isinstance(target, t.ClassType):
        if target.builtin:
            b = cat.classes.get(target.key)
            return [(m.name, m, b) for m in b.members.values()] if b is not None else []
        c = index.classes.get(target.key)
        if c is not None:
            return [(getattr(m, "name", k), m, None) for k, m in c.members.items() if not isinstance(m, ClassSym)]
        return []
    if isinstance(target, t.GplType):
        b = cat.members_of(target)
        return [(m.name, m, b) for m in b.members.values()] if b is not None else []
    return []


def signature_help(ls: Any, state: ProjectState, path: str, params: Any) -> T.SignatureHelp | None:
    typing = _typing(ls, state, path, params)
    if typing is None:
        return None
    index, line, before = typing
    call = _open_call(before)
    if call is None:
        return None
    head, active = call
    m = re.search(r"([A-Za-z_]\w*(?:\s*\.\s*[A-Za-z_]\w*)*)\s*$", head)
    if m is None:
        return None
    parts = [p.strip() for p in m.group(1).split(".")]
    proc, cls, mod = index.scope(path, line)
    owner = resolve_chain(parts[:-1], index, proc, cls, mod) if len(parts) > 1 else None
    if len(parts) > 1:
        callee, owner = next(((sym, b) for name, sym, b in members_of(owner, index, mod)
                              if name.lower() == parts[-1].lower()), (None, None))
    else:
        callee = next((sym for name, sym in names_in_scope(index, proc, cls, mod) if name.lower() == parts[0].lower()),
                      None)
    sigs = _signatures(callee, owner)
    if not sigs:
        return None
    best = next((i for i, s in enumerate(sigs) if len(s.parameters or []) > active), 0)
    return T.SignatureHelp(signatures=sigs, active_signature=best, active_parameter=active)


def _open_call(text: str) -> tuple[str, int] | None:
    """The text before the innermost unclosed ``(`` and the index of the argument being typed."""
    depth, commas, quoted = 0, [0], False
    opens: list[int] = []
    for i, ch in enumerate(text):
        if ch == '"':
            quoted = not quoted
        elif quoted:
            continue
        elif ch == "(":
            opens.append(i)
            commas.append(0)
        elif ch == ")" and opens:
            opens.pop()
            commas.pop()
        elif ch == "," and opens:
            commas[-1] += 1
    del depth
    if not opens:
        return None
    return text[:opens[-1]], commas[-1]


def _signatures(callee: object, owner: object) -> list[T.SignatureInformation]:
    def info(label: str, names: list[str]) -> T.SignatureInformation:
        return T.SignatureInformation(label=label, parameters=[T.ParameterInformation(label=n) for n in names])

    if isinstance(callee, OverloadSet):
        return [info(proc_signature(p), [param_text(v) for v in p.params]) for p in callee.procs]
    if isinstance(callee, ProcSym):
        return [info(proc_signature(callee), [param_text(v) for v in callee.params])]
    if isinstance(callee, BuiltinMember):
        name = owner.name if isinstance(owner, BuiltinClass) else ""
        return [info(member_signature(callee, f, name), [builtin_param_text(p) for p in f]) for f in callee.call_forms]
    if isinstance(callee, BuiltinFunction):
        return [info(function_signature(callee), [builtin_param_text(p) for p in callee.params])]
    return []
