"""Static GPL types, as the semantic pass sees them.

GPL is statically typed (§6.1): every variable, parameter and function result has a declared type,
so every expression has a static type.  Types are small immutable values compared with ``==``; the
primitive ones are singletons.  Names are case-insensitive, so class types compare by lower-cased
name and keep their declared spelling for messages.
"""

from __future__ import annotations

from dataclasses import dataclass, field


class GplType:
    """Base of all static types."""

    @property
    def name(self) -> str:
        raise NotImplementedError

    def __str__(self) -> str:
        return self.name

    is_numeric = False
    is_integral = False
    is_reference = False


@dataclass(frozen=True, eq=False)
class PrimitiveType(GplType):
    """Boolean, Byte, Short, Integer, Single, Double and String (values, not references)."""

    _name: str
    numeric: bool
    integral: bool
    # Inclusive value range for integral types (used for overflow checks when storing).
    low: int | None = None
    high: int | None = None

    @property
    def name(self) -> str:
        return self._name

    @property
    def is_numeric(self) -> bool:  # type: ignore[override]
        return self.numeric

    @property
    def is_integral(self) -> bool:  # type: ignore[override]
        return self.integral

    def __repr__(self) -> str:
        return self._name


BOOLEAN = PrimitiveType("Boolean", numeric=True, integral=True, low=-1, high=0)
BYTE = PrimitiveType("Byte", numeric=True, integral=True, low=0, high=255)
SHORT = PrimitiveType("Short", numeric=True, integral=True, low=-32768, high=32767)
INTEGER = PrimitiveType("Integer", numeric=True, integral=True, low=-(2**31), high=2**31 - 1)
SINGLE = PrimitiveType("Single", numeric=True, integral=False)
DOUBLE = PrimitiveType("Double", numeric=True, integral=False)
STRING = PrimitiveType("String", numeric=False, integral=False)

PRIMITIVES: dict[str, PrimitiveType] = {
    t.name.lower(): t for t in (BOOLEAN, BYTE, SHORT, INTEGER, SINGLE, DOUBLE, STRING)
}


@dataclass(frozen=True)
class ClassType(GplType):
    """A built-in or user class (including Exception and delegate classes): a reference type.

    Identity is the lower-cased qualified ``key`` ("location" for a built-in, "module.class" for a
    user class); ``declared_name`` keeps the spelling for messages and generated code.
    """

    key: str
    declared_name: str = field(compare=False)
    builtin: bool = field(default=False, compare=False)

    @classmethod
    def of(cls, declared_name: str, *, qualifier: str = "", builtin: bool = False) -> ClassType:
        key = f"{qualifier}.{declared_name}" if qualifier else declared_name
        return cls(key.lower(), declared_name, builtin)

    @property
    def name(self) -> str:
        return self.declared_name

    @property
    def is_reference(self) -> bool:  # type: ignore[override]
        return True


@dataclass(frozen=True)
class ArrayType(GplType):
    """An array of ``element`` with ``rank`` dimensions (1..4); arrays are references (§4.5)."""

    element: GplType
    rank: int = 1

    @property
    def name(self) -> str:
        return f"{self.element.name}({',' * (self.rank - 1)})"

    @property
    def is_reference(self) -> bool:  # type: ignore[override]
        return True


@dataclass(frozen=True, eq=False)
class _SpecialType(GplType):
    _name: str

    @property
    def name(self) -> str:
        return self._name

    def __repr__(self) -> str:
        return self._name


# The type of the literal ``Nothing``: assignable to every reference type.
NOTHING = _SpecialType("Nothing")
# The "type" of a Sub call used as a value: always an error where a value is needed.
VOID = _SpecialType("(no value)")
# Stands in after an error so one mistake does not cascade into many diagnostics.
ERROR = _SpecialType("(error)")
# Any value, converted by whoever receives it: a runtime parameter annotated ``Any`` (CInt's value,
# Format, Console.Write) and whatever a stub for protected code stands for (its type is unknown).
# Unlike ERROR it is not the trace of a mistake: it accepts every use without a diagnostic, and the
# lowering converts it at run time wherever a typed value is needed (``to_int32(x)``).
ANY = _SpecialType("(any)")


def permissive(typ: GplType) -> bool:
    """Whether ``typ`` accepts every use silently (ERROR after a reported mistake, or ANY)."""
    return typ is ERROR or typ is ANY


def numeric_rank(t: GplType) -> int:
    """Order of numeric widening: Boolean < Byte < Short < Integer < Single < Double."""
    order = (BOOLEAN, BYTE, SHORT, INTEGER, SINGLE, DOUBLE)
    return order.index(t) if t in order else -1


def lookup_primitive(name: str) -> PrimitiveType | None:
    return PRIMITIVES.get(name.lower())
