"""ByRef cells: what a caller passes for a ``ByRef`` parameter (spec gpl-language.md §9.3).

GPL ByRef is true aliasing, not copy-in/copy-out: ``acquire_sem(ByRef sem_var As Integer)`` loops
on ``Thread.TestAndSet(sem_var, 1)`` while other threads change the caller's ``my_lock``
[000 L4770-4795].  So the callee receives a cell over the caller's storage and reads ``p.get()``
and writes ``p.set(v)`` (the ``gpltypes.Ref`` protocol):

* ``Box(value)`` -- a local variable that the procedure passes ByRef somewhere (the lowering keeps
  such a local in its Box for the whole procedure, docs/design/lowering.md), or a temporary for a
  non-variable argument (AMB-33);
* ``AttrRef(obj, "name")`` -- a module variable (``obj`` is the module object) or an object field;
  ``ModuleVarRef`` and ``FieldRef`` are the same class under the names the lowering reads best;
* ``ItemRef(array, index)`` -- an array element; ``index`` is an int or a tuple of ints.  The
  element is checked when the cell is made, as the controller evaluates the argument at the call
  (-767 for a bad index), and every access goes through the array's own bounds check.

Cells do not convert values: the callee's parameter type is the caller's variable type (GPL
requires the types to match), and conversion on store is the lowering's job.  Each cell is a
``__slots__`` object with two tiny methods and a ``value`` attribute (a plain slot on ``Box``, a
property on the others), which generated code uses.
"""

from __future__ import annotations

from typing import Any

from gplrt.lang.errors import OBJECT_NOT_INSTANTIATED, GplException

__all__ = ["Box", "AttrRef", "ItemRef", "ModuleVarRef", "FieldRef"]


class Box:
    """A cell holding its own value (a local variable or a temporary)."""

    __slots__ = ("value",)

    def __init__(self, value: Any = None) -> None:
        self.value = value

    def get(self) -> Any:
        return self.value

    def set(self, value: Any) -> None:
        self.value = value

    def __repr__(self) -> str:
        return f"Box({self.value!r})"


class AttrRef:
    """A cell aliasing attribute ``name`` of ``obj``: a module variable or an object field."""

    __slots__ = ("obj", "name")

    def __init__(self, obj: Any, name: str) -> None:
        self.obj = obj
        self.name = name

    def get(self) -> Any:
        return getattr(self.obj, self.name)

    def set(self, value: Any) -> None:
        setattr(self.obj, self.name, value)

    # ``cell.value`` works on every cell kind: generated code reads and writes ByRef parameters
    # with it, which on a Box (the common case, a caller's local) is a plain slot access.
    value = property(get, set)

    def __repr__(self) -> str:
        return f"AttrRef({type(self.obj).__name__}, {self.name!r})"


ModuleVarRef = AttrRef
FieldRef = AttrRef


class ItemRef:
    """A cell aliasing one element of a GPL array (``array[index]``)."""

    __slots__ = ("array", "index")

    def __init__(self, array: Any, index: Any) -> None:
        if array is None:
            raise GplException(OBJECT_NOT_INSTANTIATED, detail="array not allocated")
        array[index]  # noqa: B018 -- the argument is evaluated (and checked) at the call
        self.array = array
        self.index = index

    def get(self) -> Any:
        return self.array[self.index]

    def set(self, value: Any) -> None:
        self.array[self.index] = value

    value = property(get, set)

    def __repr__(self) -> str:
        return f"ItemRef({self.index!r})"
