"""Reads the built-in catalogue from the runtime and writes it to the transpiler's data module.

Run this whenever the runtime's built-ins change (a class, member, signature, overload, ``set_``
or ``do_`` companion, ``@not_simulated`` mark, constant or function of ``gplrt.builtins``)::

    python -m gpl2py.gpl.semantics.catalogue_gen            # rewrites gpl2py/gpl/semantics/builtins_data.py
    python -m gpl2py.gpl.semantics.catalogue_gen --check    # exit status 1 if it is out of date

:func:`build_catalogue` introspects a runtime module the way ``runtime/gplrt/CATALOGUE.md``
describes; :func:`catalogue_data` turns the result into rows of plain literals and :func:`render`
into the text of the data module, which :func:`gpl2py.gpl.semantics.catalogue.load_catalogue` reads
without importing the runtime.  The conventions read here:

* GPL members are the attributes whose name starts with an upper-case letter;
* properties are ``property`` objects (settable when they have a setter);
* an assignable member with arguments ``M(args)`` has a companion method ``set_M(args, value)``;
  a property may have one too (``Controller.PowerEnabled(timeout) = True`` beside
  ``Controller.PowerEnabled = True``);
* a member with several forms (``Vision.Result()`` / ``Result(tool, index)``, ``Robot.Tool = loc``
  / ``Robot.Tool(robot) = loc``) declares each with ``typing.overload``; otherwise its Python
  signature is its one GPL signature, and ``*args`` is refused (it would hide the real arity);
* Shared members are staticmethods/classmethods; global classes are exported as one instance;
* a ByRef parameter is annotated ``Ref[T]``;
* a member the simulated controller does not implement is marked by
  ``gplrt.lang.exceptions.not_simulated``: it keeps its real signature, so calls are checked, and
  raises -204 when it runs (``Member.simulated`` is False);
* a member whose statement form acts has a ``do_<Name>`` companion (``Member.action``).
"""

from __future__ import annotations

import importlib
import inspect
import typing
from pathlib import Path
from types import ModuleType
from typing import Any, Callable

from gpl2py import datamodule
from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import (
    DATA_MODULE,
    REGENERATE,
    BuiltinClass,
    BuiltinConstant,
    BuiltinFunction,
    Catalogue,
    Form,
    Member,
    Param,
    type_code,
)

_PRIMITIVE_BY_NEWTYPE_NAME = {
    "Boolean": t.BOOLEAN,
    "Byte": t.BYTE,
    "Short": t.SHORT,
    "Integer": t.INTEGER,
    "Single": t.SINGLE,
    "Double": t.DOUBLE,
    "String": t.STRING,
}
_PRIMITIVE_BY_PYTHON_TYPE: dict[object, t.GplType] = {
    bool: t.BOOLEAN,
    int: t.INTEGER,
    float: t.DOUBLE,
    str: t.STRING,
}


class _TypeMapper:
    """Turns runtime annotations into static GPL types."""

    def __init__(self, class_names: dict[type, str]) -> None:
        self._class_names = class_names

    def convert(self, annotation: Any) -> tuple[t.GplType, bool]:
        """Returns (type, byref)."""
        if annotation is None or annotation is type(None) or annotation is inspect.Parameter.empty:
            return t.VOID, False
        if annotation is Any or annotation is object:
            # "any value, the runtime converts" (CInt's value, Format, Console.Write): not the
            # error type, which would silence diagnostics about the argument
            return t.ANY, False
        origin = typing.get_origin(annotation)
        if origin is not None:
            args = [a for a in typing.get_args(annotation) if a is not type(None)]
            if getattr(origin, "__name__", "") == "Ref" and args:
                inner, _ = self.convert(args[0])
                return inner, True
            if origin in (typing.Union, getattr(__import__("types"), "UnionType", None)) and len(args) == 1:
                return self.convert(args[0])
            if (origin is list or getattr(origin, "__name__", "") == "GplArray") and args:
                inner, _ = self.convert(args[0])  # a GPL array of T (list[T] in plain Python code)
                return t.ArrayType(inner), False
            return t.ERROR, False
        supertype = getattr(annotation, "__supertype__", None)
        if supertype is not None:  # a NewType from gplrt.lang.gpltypes
            prim = _PRIMITIVE_BY_NEWTYPE_NAME.get(annotation.__name__)
            if prim is not None:
                return prim, False
            return t.ERROR, False
        if annotation in _PRIMITIVE_BY_PYTHON_TYPE:
            return _PRIMITIVE_BY_PYTHON_TYPE[annotation], False
        if isinstance(annotation, type) and annotation in self._class_names:
            return t.ClassType.of(self._class_names[annotation], builtin=True), False
        return t.ERROR, False


def _hints(func: Callable[..., Any]) -> dict[str, Any]:
    try:
        return typing.get_type_hints(func, include_extras=True)
    except Exception:  # unresolved forward references: fall back to raw annotations
        return dict(getattr(func, "__annotations__", {}))


class CatalogueError(TypeError):
    """The runtime declares a GPL member the catalogue cannot read (a bug in the runtime)."""


def _params(func: Callable[..., Any], mapper: _TypeMapper, skip_first: bool) -> tuple[Param, ...]:
    hints = _hints(func)
    out: list[Param] = []
    sig = inspect.signature(func)
    for i, (name, p) in enumerate(sig.parameters.items()):
        if skip_first and i == 0:
            continue
        if p.kind is p.VAR_POSITIONAL:
            raise CatalogueError(f"{func.__qualname__} takes *{name}: declare its GPL forms with "
                                 "typing.overload (runtime/gplrt/CATALOGUE.md)")
        if p.kind in (p.VAR_KEYWORD, p.KEYWORD_ONLY):
            continue
        typ, byref = mapper.convert(hints.get(name, inspect.Parameter.empty))
        optional = p.default is not inspect.Parameter.empty
        out.append(Param(name, typ, byref, optional, p.default if optional else None))
    return tuple(out)


def _result(func: Callable[..., Any], mapper: _TypeMapper) -> t.GplType:
    hints = _hints(func)
    if "return" not in hints:
        return t.VOID
    typ, _ = mapper.convert(hints["return"])
    return typ


def _forms(func: Callable[..., Any], mapper: _TypeMapper, skip_first: bool) -> tuple[Form, ...]:
    """Every GPL form of a runtime function: its ``typing.overload`` declarations, if it has any,
    else its own signature."""
    overloads = typing.get_overloads(func)
    if overloads:
        return tuple(_params(o, mapper, skip_first) for o in overloads)
    return (_params(func, mapper, skip_first),)


def _set_forms(cls: type, name: str, prop: property | None, mapper: _TypeMapper,
               skip_first: bool) -> tuple[Form, ...]:
    """The assignment forms of member ``name``: the property's setter (``X.M = v``) and the forms
    of the ``set_<name>`` companion (``X.M(args) = v``), each ending with the value."""
    forms: list[Form] = []
    if prop is not None and prop.fset is not None:
        forms.append((Param("value", _result(prop.fget, mapper) if prop.fget else t.ERROR),))
    raw = inspect.getattr_static(cls, f"set_{name}", None)
    if raw is not None:
        func = raw.__func__ if isinstance(raw, (staticmethod, classmethod)) else raw
        skip = skip_first if inspect.isfunction(raw) else isinstance(raw, classmethod)
        forms.extend(f for f in _forms(func, mapper, skip) if f)
    return tuple(forms)


def _simulated(func: Callable[..., Any]) -> bool:
    return not getattr(func, "__gpl_not_simulated__", False)


def _members(cls: type, mapper: _TypeMapper, *, all_shared: bool, value_type: bool) -> dict[str, Member]:
    members: dict[str, Member] = {}
    for klass in reversed(cls.__mro__):
        if klass is object or klass is BaseException or klass is Exception:
            continue
        for name, raw in vars(klass).items():
            if not name[:1].isupper():
                continue
            if isinstance(raw, property):
                result = _result(raw.fget, mapper) if raw.fget else t.VOID
                set_forms = _set_forms(cls, name, raw, mapper, skip_first=True)
                members[name.lower()] = Member(
                    name, "property", all_shared, (), result, settable=bool(set_forms),
                    set_forms=set_forms, simulated=raw.fget is None or _simulated(raw.fget),
                )
            elif isinstance(raw, (staticmethod, classmethod)) or inspect.isfunction(raw):
                if inspect.isfunction(raw):  # an instance method: ``self`` is not a GPL parameter
                    func, shared_here, skip = raw, all_shared, True
                else:
                    func = raw.__func__
                    # A classmethod's first parameter is the class; a value type's staticmethods
                    # take the value itself first, except the type's Shared members (String.Compare).
                    shared_here = not value_type or name in getattr(cls, "shared_members", ())
                    skip = isinstance(raw, classmethod) or not shared_here
                forms = _forms(func, mapper, skip_first=skip)
                set_forms = _set_forms(cls, name, None, mapper, skip_first=True)
                action = f"do_{name}" if callable(getattr(cls, f"do_{name}", None)) else None
                members[name.lower()] = Member(
                    name,
                    "method",
                    shared_here,
                    max(forms, key=len),
                    _result(func, mapper),
                    settable=bool(set_forms),
                    overloads=forms if len(forms) > 1 else (),
                    set_forms=set_forms,
                    simulated=_simulated(func),
                    action=action,
                )
    return members


def build_catalogue(module: ModuleType) -> Catalogue:
    """Read the tables of ``module`` (normally ``gplrt.builtins``) into a :class:`Catalogue`."""
    classes: dict[str, str] = getattr(module, "CLASSES", {})
    globals_: dict[str, str] = getattr(module, "GLOBAL_CLASSES", {})
    functions: dict[str, str] = getattr(module, "FUNCTIONS", {})
    constants: dict[str, str] = getattr(module, "CONSTANTS", {})
    type_members: dict[str, str] = getattr(module, "TYPE_MEMBERS", {})

    class_names: dict[type, str] = {}
    for gpl_name, py_name in classes.items():
        class_names[getattr(module, py_name)] = gpl_name
    for gpl_name, py_name in globals_.items():
        class_names[type(getattr(module, py_name))] = gpl_name
    mapper = _TypeMapper(class_names)

    cat = Catalogue()
    for gpl_name, py_name in classes.items():
        cls = getattr(module, py_name)
        init = cls.__dict__.get("__init__")
        ctor = _params(init, mapper, skip_first=True) if init is not None else ()
        cat.classes[gpl_name.lower()] = BuiltinClass(
            gpl_name, py_name, False, ctor, _members(cls, mapper, all_shared=False, value_type=False)
        )
    for gpl_name, py_name in globals_.items():
        cls = type(getattr(module, py_name))
        cat.classes[gpl_name.lower()] = BuiltinClass(
            gpl_name, py_name, True, None, _members(cls, mapper, all_shared=True, value_type=False)
        )
    for gpl_name, py_name in functions.items():
        func = getattr(module, py_name)
        cat.functions[gpl_name.lower()] = BuiltinFunction(
            gpl_name, py_name, _params(func, mapper, skip_first=False), _result(func, mapper),
            _defining_module(module, func, py_name),
        )
    for gpl_name, py_name in constants.items():
        value = getattr(module, py_name)
        typ = _PRIMITIVE_BY_PYTHON_TYPE.get(type(value), t.ERROR)
        cat.constants[gpl_name.lower()] = BuiltinConstant(gpl_name, py_name, typ, value)
    for type_name, py_name in type_members.items():
        cls = getattr(module, py_name)
        cat.type_members[type_name.lower()] = BuiltinClass(
            type_name, py_name, False, None, _members(cls, mapper, all_shared=False, value_type=True)
        )
    return cat


def _defining_module(module: ModuleType, func: Callable[..., Any], py_name: str) -> str:
    """Where a function of ``module`` is defined, when importing it from there gives the same
    function (constant folding imports it without the rest of the runtime); else ``module``."""
    home = getattr(func, "__module__", None)
    if home and home != module.__name__:
        try:
            if getattr(importlib.import_module(home), py_name, None) is func:
                return home
        except ImportError:
            pass
    return module.__name__


# -- the data module ---------------------------------------------------------------------------------

#: Values a parameter default or a constant may have in the data module (plain literals).
_LITERALS = (type(None), bool, int, float, str)


def _literal(value: object, what: str) -> object:
    if not isinstance(value, _LITERALS) or (isinstance(value, float) and value != value):
        raise CatalogueError(f"{what} is {value!r}: the catalogue holds only None, booleans, numbers "
                             "and strings (runtime/gplrt/CATALOGUE.md)")
    return value


def _form_rows(form: Form, where: str) -> tuple[tuple[object, ...], ...]:
    return tuple((p.name, type_code(p.type), p.byref, p.optional,
                  _literal(p.default, f"the default of {where}({p.name})")) for p in form)


def _member_row(m: Member, where: str) -> tuple[object, ...]:
    return (m.kind, m.shared, type_code(m.result), tuple(_form_rows(f, where) for f in m.call_forms),
            tuple(_form_rows(f, where) for f in m.set_forms), m.simulated, m.action)


def _class_row(c: BuiltinClass) -> tuple[object, ...]:
    ctor = None if c.constructor is None else _form_rows(c.constructor, f"{c.name}.New")
    members = tuple((m.name, _member_row(m, f"{c.name}.{m.name}")) for m in c.members.values())
    return (c.python_name, c.is_global, ctor, members)


def catalogue_data(cat: Catalogue) -> dict[str, tuple[object, ...]]:
    """The rows :func:`gpl2py.gpl.semantics.catalogue.catalogue_from_data` reads back into ``cat``:
    tuples of strings, booleans, numbers and None, in the runtime's order."""
    return {
        "classes": tuple((c.name, _class_row(c)) for c in cat.classes.values()),
        "functions": tuple((f.name, (f.python_name, f.module, _form_rows(f.params, f.name), type_code(f.result)))
                           for f in cat.functions.values()),
        "constants": tuple((k.name, (k.python_name, type_code(k.type), _literal(k.value, k.name)))
                           for k in cat.constants.values()),
        "type_members": tuple((c.name, _class_row(c)) for c in cat.type_members.values()),
    }


def render(data: dict[str, tuple[object, ...]]) -> str:
    """The text of the data module: one class, member, function or constant per line."""
    out = [
        '"""The built-in catalogue, as read from the runtime (gplrt.builtins).',
        "",
        f"Generated by ``{REGENERATE}``: do not edit.  Rows are described in",
        "gpl2py/gpl/semantics/catalogue_gen.py (writer) and gpl2py/gpl/semantics/catalogue.py (reader).",
        '"""',
        "",
        "# fmt: off",
        "CATALOGUE = {",
    ]
    for table in ("classes", "functions", "constants", "type_members"):
        out.append(f"    {table!r}: (")
        for name, row in data[table]:  # type: ignore[misc]
            if table in ("classes", "type_members"):
                python_name, is_global, ctor, members = row
                out.append(f"        ({name!r}, ({python_name!r}, {is_global!r}, {ctor!r}, (")
                out.extend(f"            {member!r}," for member in members)
                out.append("        ))),")
            else:
                out.append(f"        {(name, row)!r},")
        out.append("    ),")
    out.append("}")
    return "\n".join(out) + "\n"


def data_path() -> Path:
    """Where the data module lives in this checkout or installation."""
    return Path(__file__).with_name(DATA_MODULE.rsplit(".", 1)[1] + ".py")


def generate(module_name: str = "gplrt.builtins") -> str:
    """The data module's text for the runtime installed now."""
    return render(catalogue_data(build_catalogue(importlib.import_module(module_name))))


def main(argv: list[str] | None = None) -> int:
    return datamodule.main(REGENERATE, "Write the built-in catalogue read from the runtime to gpl2py's data module.",
                           generate, data_path(), argv)


if __name__ == "__main__":
    raise SystemExit(main())
