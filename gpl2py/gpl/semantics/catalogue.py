"""The built-in classes, functions and constants GPL programs name without declaring them.

The runtime is the source of truth: ``gplrt.builtins`` lists them and its Python classes carry
their GPL signatures, following the conventions of ``runtime/gplrt/CATALOGUE.md`` (GPL members
start with an upper-case letter; properties, ``set_`` companions, ``typing.overload`` forms,
``Ref[T]`` ByRef parameters, ``do_`` statement forms, ``@not_simulated`` ...).  Reading them means
importing the runtime, and with it numpy, Pinocchio and Ruckig, which is most of a second: too
much for ``gpl2py check`` in an editor's loop.  So :mod:`gpl2py.gpl.semantics.catalogue_gen` reads
the runtime once, when it changes, and writes what it found to the data module
:data:`DATA_MODULE` (plain literals, committed with the package); this module only reads that
data.  ``tests/semantics/test_catalogue_data.py`` fails when the data module and a fresh reading
of the runtime differ, naming the command that regenerates it (:data:`REGENERATE`).

Lookups are case-insensitive; every entry keeps the runtime's canonical spelling, which the
lowering uses in generated code.
"""

from __future__ import annotations

import functools
import importlib
from dataclasses import dataclass, field

from gpl2py.gpl.semantics import types as t


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
    #: the runtime module that defines it (``gplrt.lang.conversions``): translation-time constant
    #: folding imports the function from there, not the whole runtime (semantics/consts.py)
    module: str = "gplrt.builtins"


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


DATA_MODULE = "gpl2py.gpl.semantics.builtins_data"
#: The command that rewrites :data:`DATA_MODULE` from the installed runtime.
REGENERATE = "python -m gpl2py.gpl.semantics.catalogue_gen"


class CatalogueDataError(RuntimeError):
    """The catalogue's data module is missing or unreadable (regenerate it: :data:`REGENERATE`)."""


_SPECIAL_TYPES: dict[str, t.GplType] = {"-": t.VOID, "*": t.ANY, "!": t.ERROR}


def type_code(typ: t.GplType) -> str:
    """The data module's spelling of a static type: a primitive's name (``Integer``), a built-in
    class's name after ``C:`` (``C:Location``), an array after ``A:`` (``A:Integer``, one rank),
    ``-`` no value, ``*`` any value, ``!`` an annotation the runtime got wrong."""
    if isinstance(typ, t.PrimitiveType):
        return typ.name
    if isinstance(typ, t.ClassType) and typ.builtin:
        return "C:" + typ.declared_name
    if isinstance(typ, t.ArrayType) and typ.rank == 1:
        return "A:" + type_code(typ.element)
    for code, special in _SPECIAL_TYPES.items():
        if typ is special:
            return code
    raise CatalogueDataError(f"the catalogue cannot hold the type {typ!r}")


class _Decoder:
    """Data module rows -> catalogue objects; equal rows give the same (shared) objects."""

    def __init__(self) -> None:
        self._types: dict[str, t.GplType] = dict(_SPECIAL_TYPES)
        self._forms: dict[tuple[object, ...], Form] = {}

    def type(self, code: str) -> t.GplType:
        typ = self._types.get(code)
        if typ is None:
            if code.startswith("C:"):
                typ = t.ClassType.of(code[2:], builtin=True)
            elif code.startswith("A:"):
                typ = t.ArrayType(self.type(code[2:]))
            else:
                prim = t.lookup_primitive(code)
                if prim is None:
                    raise CatalogueDataError(f"unknown type {code!r} in {DATA_MODULE}")
                typ = prim
            self._types[code] = typ
        return typ

    def form(self, rows: tuple[tuple[object, ...], ...]) -> Form:
        """``((name, type, byref, optional, default), ...)`` -> parameters."""
        form = self._forms.get(rows)
        if form is None:
            form = tuple(Param(name, self.type(code), byref, optional, default)  # type: ignore[arg-type]
                         for name, code, byref, optional, default in rows)
            self._forms[rows] = form
        return form

    def member(self, name: str, row: tuple[object, ...]) -> Member:
        kind, shared, result, forms, set_forms, simulated, action = row
        calls = tuple(self.form(f) for f in forms)  # type: ignore[union-attr]
        sets = tuple(self.form(f) for f in set_forms)  # type: ignore[union-attr]
        return Member(name, kind, shared, max(calls, key=len), self.type(result),  # type: ignore[arg-type]
                      settable=bool(sets), overloads=calls if len(calls) > 1 else (), set_forms=sets,
                      simulated=simulated, action=action)  # type: ignore[arg-type]

    def cls(self, name: str, row: tuple[object, ...]) -> BuiltinClass:
        python_name, is_global, ctor, members = row
        return BuiltinClass(name, python_name, is_global,  # type: ignore[arg-type]
                            None if ctor is None else self.form(ctor),  # type: ignore[arg-type]
                            {m.lower(): self.member(m, r) for m, r in members})  # type: ignore[union-attr]


def catalogue_from_data(data: dict[str, object]) -> Catalogue:
    """The catalogue the rows of the data module describe (``catalogue_gen.catalogue_data``)."""
    d = _Decoder()
    cat = Catalogue()
    for name, row in data["classes"]:  # type: ignore[attr-defined]
        cat.classes[name.lower()] = d.cls(name, row)
    for name, (python_name, module, params, result) in data["functions"]:  # type: ignore[attr-defined]
        cat.functions[name.lower()] = BuiltinFunction(name, python_name, d.form(params), d.type(result), module)
    for name, (python_name, code, value) in data["constants"]:  # type: ignore[attr-defined]
        cat.constants[name.lower()] = BuiltinConstant(name, python_name, d.type(code), value)
    for name, row in data["type_members"]:  # type: ignore[attr-defined]
        cat.type_members[name.lower()] = d.cls(name, row)
    return cat


@functools.lru_cache(maxsize=1)
def load_catalogue() -> Catalogue:
    """The catalogue of the runtime this gpl2py ships with, read from :data:`DATA_MODULE` once
    per process (importing the runtime itself would cost about a second: numpy, Pinocchio ...)."""
    try:
        data = importlib.import_module(DATA_MODULE).CATALOGUE
        return catalogue_from_data(data)
    except (ImportError, AttributeError, KeyError, TypeError, ValueError) as exc:
        raise CatalogueDataError(f"cannot read the built-in catalogue {DATA_MODULE} ({exc}); "
                                 f"regenerate it with: {REGENERATE}") from exc
