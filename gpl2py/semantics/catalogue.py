"""The built-in classes, functions and constants, read from the runtime's own catalogue.

The transpiler keeps no list of its own: it introspects ``gplrt.builtins`` (the tables and the
Python classes they name) and turns type hints into :mod:`gpl2py.semantics.types`.  The
conventions it relies on are written down in ``runtime/gplrt/CATALOGUE.md``:

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
  ``gplrt.lang.exceptions.not_simulated``: it keeps its real signature, so calls are checked here,
  and raises -204 when it runs (``Member.simulated`` is False).

Lookups are case-insensitive; every entry keeps the runtime's canonical spelling, which the
lowering uses in generated code.
"""

from __future__ import annotations

import functools
import importlib
import inspect
import typing
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any, Callable

from gpl2py.semantics import types as t

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


@dataclass(frozen=True)
class Param:
    name: str
    type: t.GplType
    byref: bool = False
    optional: bool = False
    default: object = None


Form = tuple[Param, ...]


def _min_args(form: Form) -> int:
    return sum(1 for p in form if not p.optional)


def _pick(forms: tuple[Form, ...], count: int) -> Form | None:
    """The first form that accepts ``count`` arguments."""
    return next((f for f in forms if _min_args(f) <= count <= len(f)), None)


@dataclass(frozen=True)
class Member:
    """A GPL member of a built-in class (or of a value type such as String).

    ``params`` is the call form with the most parameters; ``overloads`` holds every call form when
    the runtime declares several (``typing.overload``).  ``set_forms`` are the ways to assign the
    member, each the argument list followed by the value: ``(value,)`` for ``X.M = v`` (a property
    setter, or ``set_M(value)``), ``(index, value)`` for ``X.M(i) = v``.
    """

    name: str  # canonical spelling, as in the runtime
    kind: str  # "property" | "method"
    shared: bool
    params: Form
    result: t.GplType  # t.VOID for Subs
    settable: bool = False  # has at least one assignment form
    overloads: tuple[Form, ...] = ()
    set_forms: tuple[Form, ...] = ()
    simulated: bool = True  # False: the runtime only raises -204 (``not_simulated``)
    # The Python method that the member's statement form calls, when used as a statement it acts
    # rather than reads: ``Robot.RapidDecel(1)`` alone stops robot 1 (``do_RapidDecel``;
    # CATALOGUE.md rule 10).  None: a statement evaluates the member like any call.
    action: str | None = None

    @property
    def call_forms(self) -> tuple[Form, ...]:
        return self.overloads or (self.params,)

    @property
    def min_args(self) -> int:
        return min(_min_args(f) for f in self.call_forms)

    @property
    def max_args(self) -> int:
        return max(len(f) for f in self.call_forms)

    def call_form(self, count: int) -> Form | None:
        """The parameters of the form called with ``count`` arguments (None: no such form)."""
        return _pick(self.call_forms, count)

    @property
    def set_min_args(self) -> int:
        return min((_min_args(f) - 1 for f in self.set_forms), default=0)

    @property
    def set_max_args(self) -> int:
        return max((len(f) - 1 for f in self.set_forms), default=0)

    def set_form(self, count: int) -> Form | None:
        """The assignment form with ``count`` arguments before the value: its parameters, the
        value's last (None: the member cannot be assigned that way)."""
        return next((f for f in self.set_forms if _min_args(f) - 1 <= count <= len(f) - 1), None)


@dataclass(frozen=True)
class BuiltinClass:
    name: str  # GPL spelling
    python_name: str  # name exported by gplrt.builtins
    is_global: bool  # only Shared members, exported as one instance
    constructor: tuple[Param, ...] | None  # None: cannot be created with New
    members: dict[str, Member] = field(default_factory=dict)  # keyed by lower-case name

    @property
    def type(self) -> t.ClassType:
        return t.ClassType.of(self.name, builtin=True)

    def member(self, name: str) -> Member | None:
        return self.members.get(name.lower())


@dataclass(frozen=True)
class BuiltinFunction:
    name: str
    python_name: str
    params: tuple[Param, ...]
    result: t.GplType


@dataclass(frozen=True)
class BuiltinConstant:
    name: str
    python_name: str
    type: t.GplType
    value: object


@dataclass
class Catalogue:
    classes: dict[str, BuiltinClass] = field(default_factory=dict)
    functions: dict[str, BuiltinFunction] = field(default_factory=dict)
    constants: dict[str, BuiltinConstant] = field(default_factory=dict)
    # Members of value types, keyed by the type's lower-case name ("string").
    type_members: dict[str, BuiltinClass] = field(default_factory=dict)

    def lookup_class(self, name: str) -> BuiltinClass | None:
        return self.classes.get(name.lower())

    def lookup_function(self, name: str) -> BuiltinFunction | None:
        return self.functions.get(name.lower())

    def lookup_constant(self, name: str) -> BuiltinConstant | None:
        return self.constants.get(name.lower())

    def members_of(self, typ: t.GplType) -> BuiltinClass | None:
        """The member catalogue for a static type, built-in class or value type."""
        if isinstance(typ, t.ClassType) and typ.builtin:
            return self.classes.get(typ.key)
        return self.type_members.get(typ.name.lower())


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
            gpl_name, py_name, _params(func, mapper, skip_first=False), _result(func, mapper)
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


@functools.lru_cache(maxsize=1)
def load_catalogue() -> Catalogue:
    """The catalogue of the installed runtime (read once per process)."""
    return build_catalogue(importlib.import_module("gplrt.builtins"))
