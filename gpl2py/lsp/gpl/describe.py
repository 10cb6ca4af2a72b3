"""How a symbol reads in a hover, a completion item or a signature: its declaration as GPL writes
it, a built-in's signature and the runtime's description of it, a code's explanation."""

from __future__ import annotations

import importlib
import os
from functools import lru_cache
from typing import Any

from gpl2py import messages as M
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, BuiltinConstant, BuiltinFunction
from gpl2py.gpl.semantics.catalogue import Member as BuiltinMember
from gpl2py.gpl.semantics.check import Model
from gpl2py.gpl.semantics.symbols import ClassSym, DelegateSym, ModuleSym, ProcSym, PropSym, VarSym
from gpl2py.gpl.syntax import ast as A
from gpl2py.lsp.gpl.index import Index, Occ
from gpl2py.lsp.projects import ProjectState


def explain(code: str) -> str:
    """``gpl2py explain CODE``'s text."""
    try:
        m = M.message(code)
    except KeyError:
        return ""
    return f"**{m.code}** ({m.severity_name}): {m.template}\n\n{m.notes or ''}".strip()


def describe(o: Occ, index: Index, state: ProjectState) -> str:
    """The hover text of an occurrence: a declaration as GPL writes it, where it is declared."""
    sym = o.sym
    if isinstance(sym, BuiltinMember):
        text = _code(member_signature(sym, owner=o.owner.name if isinstance(o.owner, BuiltinClass) else ""))
        doc = builtin_doc(o.owner, sym)
        return text + (f"\n\n{doc}" if doc else "") + "\n\nbuilt-in member"
    if isinstance(sym, BuiltinFunction):
        doc = builtin_doc(None, sym)
        return _code(function_signature(sym)) + (f"\n\n{doc}" if doc else "") + "\n\nbuilt-in function"
    if isinstance(sym, BuiltinConstant):
        return _code(f"Const {sym.name} As {sym.type} = {_value(sym.value)}") + "\n\nbuilt-in constant"
    if isinstance(sym, BuiltinClass):
        return _code(f"Class {sym.name}") + "\n\nbuilt-in class"
    text = _code(declaration(sym, index.model))
    decl = index.declaration(sym)
    if decl is not None:
        text += f"\n\ndeclared at {_shown(decl.path)}:{decl.line}:{decl.col}"
    return text


def _shown(path: str) -> str:
    return os.path.basename(path)


def _code(text: str) -> str:
    return f"```gpl\n{text}\n```"


def _value(v: object) -> str:
    if isinstance(v, str):
        return '"' + v.replace('"', '""') + '"'
    if isinstance(v, bool):
        return "True" if v else "False"
    return repr(v) if isinstance(v, float) else str(v)


def declaration(sym: object, model: Model) -> str:
    """``sym`` as its declaration reads (the type the checker gave it)."""
    if isinstance(sym, VarSym):
        kind = {"param": ("ByRef " if sym.byref else "ByVal "), "static": "Static ", "field": "Dim ",
                "module": "Dim ", "local": "Dim "}.get(sym.storage, "Dim ")
        if sym.const:
            kind = "Const "
        elif sym.public and sym.storage in ("module", "field"):
            kind = "Public " + ("Shared " if sym.shared and sym.storage == "field" else "")
        where = {"local": "local", "static": "static local", "param": "parameter", "module": "module variable",
                 "field": "field"}.get(sym.storage, "")
        text = f"{kind}{sym.name} As {sym.type}"
        if sym.const:
            value = model.const_values.get(sym, _literal(sym))
            if value is not None:
                text += f" = {_value(value)}"
            where = "constant"
        owner = _owner_name(sym.owner)
        return f"{text}    ' {where}" + (f" of {owner}" if owner else "")
    if isinstance(sym, ProcSym):
        return proc_signature(sym, qualified=True)
    if isinstance(sym, PropSym):
        return f"{'Public ' if sym.public else ''}Property {sym.owner.name}.{sym.name} As {sym.type}"
    if isinstance(sym, ClassSym):
        return f"{'Public ' if sym.public else ''}Class {'.'.join(sym.path)}"
    if isinstance(sym, ModuleSym):
        return f"Module {sym.name}"
    if isinstance(sym, DelegateSym):
        params = ", ".join(f"{p.name} As {p.type}" for p in sym.params)
        return f"Delegate {sym.name}({params})" + (f" As {sym.result}" if sym.result is not t.VOID else "")
    if isinstance(sym, A.Label):
        return f"{sym.name}:    ' label"
    return ""


def _literal(v: VarSym) -> object:
    init = v.decl.initializer if v.decl is not None else None
    if isinstance(init, (A.IntegerLiteral, A.RealLiteral, A.StringLiteral, A.BooleanLiteral)):
        return init.value
    return None


def _owner_name(owner: object) -> str:
    if isinstance(owner, ProcSym):
        return owner.name
    if isinstance(owner, (ClassSym, ModuleSym)):
        return owner.name
    return ""


def proc_signature(p: ProcSym, qualified: bool = False) -> str:
    params = ", ".join(param_text(v) for v in p.params)
    shared = p.shared and isinstance(p.owner, ClassSym)  # (a module's procedures are all shared)
    head = f"{'Public ' if p.public else ''}{'Shared ' if shared else ''}{p.kind} "
    owner = f"{p.owner.name}." if qualified and isinstance(p.owner, (ModuleSym, ClassSym)) else ""
    tail = f" As {p.result}" if p.is_function else ""
    return f"{head}{owner}{p.name}({params}){tail}"


def param_text(v: VarSym) -> str:
    text = f"{'ByRef ' if v.byref else ''}{v.name} As {v.type}"
    return f"Optional {text}" if v.optional else text


def member_signature(m: BuiltinMember, form: tuple[Any, ...] | None = None, owner: str = "") -> str:
    """``Function Location.Inverse() As Location``: a built-in member as GPL would declare it."""
    form = m.params if form is None else form
    params = ", ".join(builtin_param_text(p) for p in form)
    tail = f" As {m.result}" if m.result is not t.VOID else ""
    name = f"{owner}.{m.name}" if owner else m.name
    shared = "Shared " if m.shared else ""
    if m.kind == "property" and not form:
        return f"{shared}Property {name}{tail}"
    return f"{shared}{'Function' if tail else 'Sub'} {name}({params}){tail}"


def function_signature(f: BuiltinFunction) -> str:
    tail = f" As {f.result}" if f.result is not t.VOID else ""
    return f"Function {f.name}({', '.join(builtin_param_text(p) for p in f.params)}){tail}"


def builtin_param_text(p: Any) -> str:
    text = f"{'ByRef ' if p.byref else ''}{p.name} As {p.type}"
    return f"Optional {text}" if p.optional else text


def builtin_doc(owner: BuiltinClass | None, sym: object) -> str:
    """The first paragraph of the runtime's docstring for a built-in (its GPL description): the
    catalogue keeps signatures only, the runtime is where each built-in is written and described.
    The runtime is imported on the first such hover (about a second, once per server)."""
    if isinstance(sym, BuiltinFunction):
        return _doc(sym.module, sym.python_name, "")
    if isinstance(owner, BuiltinClass) and isinstance(sym, BuiltinMember):
        return _doc("gplrt.builtins", owner.python_name, sym.name)
    return ""


@lru_cache(maxsize=4096)
def _doc(module: str, name: str, member: str) -> str:
    try:
        obj = getattr(importlib.import_module(module), name, None)
        if member:
            cls = obj if isinstance(obj, type) else type(obj)
            obj = getattr(cls, member, None)
            if isinstance(obj, property):
                obj = obj.fget
    except Exception:  # noqa: BLE001 - a description is a nicety; the signature is shown anyway
        return ""
    doc = (getattr(obj, "__doc__", None) or "").strip()
    return " ".join(doc.split("\n\n")[0].split()) if doc else ""
