"""The GPL type vocabulary used in the annotations of built-in classes.

The transpiler reads the signatures of the built-in classes (see ``gplrt/CATALOGUE.md``) from their
type hints, so the hints must say *GPL* types, not just Python ones: ``Integer`` and ``Short`` are
both Python ``int`` at run time, but GPL converts (and range-checks) differently.  ``NewType`` keeps
them distinct for introspection at no run-time cost.

Run-time representation: Boolean -> ``bool`` (converted to -1/0 when used as a number), the integer
types -> ``int``, Single/Double -> ``float``, String -> ``str``, objects -> instances or ``None``
(GPL's ``Nothing``).
"""

from __future__ import annotations

from typing import NewType, Protocol, TypeVar

Boolean = NewType("Boolean", bool)
Byte = NewType("Byte", int)  # 0..255
Short = NewType("Short", int)  # 16-bit signed
Integer = NewType("Integer", int)  # 32-bit signed
Single = NewType("Single", float)
Double = NewType("Double", float)
String = NewType("String", str)
Object = NewType("Object", object)

T = TypeVar("T")


class Ref(Protocol[T]):
    """A ByRef argument: a cell aliasing the caller's variable, array element or field.

    A built-in member annotates a ByRef parameter as ``Ref[Integer]`` (for example
    ``Thread.TestAndSet``); the transpiler then passes a cell instead of a value.
    """

    def get(self) -> T: ...

    def set(self, value: T) -> None: ...


INTEGER_RANGES: dict[object, tuple[int, int]] = {
    Byte: (0, 255),
    Short: (-32768, 32767),
    Integer: (-2147483648, 2147483647),
}
