"""ByRef cells alias the caller's storage: locals (box), module variables, elements, fields."""

from __future__ import annotations

import sys
import threading
import types

import pytest

from gplrt.lang.arrays import GplArray
from gplrt.lang.byref import AttrRef, Box, FieldRef, ItemRef, ModuleVarRef
from gplrt.lang.errors import GplException
from gplrt.lang.gpltypes import Integer


def increment(p) -> None:
    """Sub Increment(ByRef p As Integer): p = p + 1"""
    p.set(p.get() + 1)


def test_box_round_trip_and_write_back() -> None:
    x = 5
    cell = Box(x)
    increment(cell)
    x = cell.value  # the lowering's write-back
    assert x == 6


def test_module_variable_cell_truly_aliases() -> None:
    mod = types.ModuleType("gpl_test_mod")
    mod.my_lock = 0
    sys.modules["gpl_test_mod"] = mod
    try:
        cell = ModuleVarRef(mod, "my_lock")
        increment(cell)
        assert mod.my_lock == 1
        mod.my_lock = 10  # another thread changes the variable: the callee sees it
        assert cell.get() == 10
    finally:
        del sys.modules["gpl_test_mod"]


def test_array_element_cell_aliases_the_element() -> None:
    a = GplArray(Integer, 3)
    cell = ItemRef(a, 2)
    increment(cell)
    increment(cell)
    assert a[2] == 2
    a[2] = 40
    assert cell.get() == 40
    m = GplArray(Integer, 1, 1)
    c2 = ItemRef(m, (1, 0))
    c2.set(7)
    assert m[1, 0] == 7


def test_array_element_cell_checks_index_at_the_call() -> None:
    a = GplArray(Integer, 3)
    with pytest.raises(GplException) as info:
        ItemRef(a, -1)
    assert info.value.ErrorCode == -767
    with pytest.raises(GplException) as info:
        ItemRef(None, 0)
    assert info.value.ErrorCode == -757


def test_field_cell_aliases_the_field() -> None:
    class Counter:
        __slots__ = ("count",)

        def __init__(self) -> None:
            self.count = 0

    obj = Counter()
    cell = FieldRef(obj, "count")
    increment(cell)
    assert obj.count == 1
    obj.count = 5
    assert cell.get() == 5
    assert AttrRef is FieldRef


def test_aliasing_is_visible_across_threads() -> None:
    """The TestAndSet pattern: a worker spins on the caller's variable through the cell."""
    holder = types.SimpleNamespace(flag=0)
    cell = AttrRef(holder, "flag")
    seen = []

    def worker() -> None:
        while cell.get() == 0:
            pass
        seen.append(cell.get())

    t = threading.Thread(target=worker, daemon=True)  # a broken alias spins forever: do not hang the run
    t.start()
    holder.flag = 3
    t.join(timeout=5)
    assert seen == [3]
