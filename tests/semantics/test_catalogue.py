"""The transpiler reads built-in signatures from the runtime's catalogue, following CATALOGUE.md."""

from __future__ import annotations

import types as pytypes
import typing
from typing import Any

import pytest

from gpl2py.gpl.semantics import types as t
from gpl2py.gpl.semantics.catalogue import BuiltinClass, load_catalogue
from gpl2py.gpl.semantics.catalogue_gen import CatalogueError, build_catalogue
from gplrt.lang.errors import GplException
from gplrt.lang.exceptions import not_simulated
from gplrt.lang.gpltypes import Boolean, Double, Integer, Ref, String


class Widget:
    """A fake built-in class exercising every convention."""

    def __init__(self, size: Integer = 0) -> None:
        self._size = size
        self._angles = [0.0] * 4

    @property
    def Size(self) -> Integer:
        return Integer(self._size)

    @Size.setter
    def Size(self, value: Integer) -> None:
        self._size = value

    @property
    def Area(self) -> Double:
        return Double(float(self._size) ** 2)

    def Angle(self, axis: Integer) -> Double:
        return Double(self._angles[axis])

    def set_Angle(self, axis: Integer, value: Double) -> None:
        self._angles[axis] = value

    def Grow(self, by: Integer, twice: Boolean = Boolean(False)) -> None:
        self._size += by * (2 if twice else 1)

    def Clone(self) -> Widget:
        return Widget(self._size)

    @staticmethod
    def Distance(a: Widget, b: Widget) -> Double:
        return Double(abs(a._size - b._size))

    def helper_not_gpl(self) -> None:
        """Lower-case names are Python-side helpers, invisible to GPL."""


class _Machine:
    @property
    def Speed(self) -> Integer:
        return Integer(50)

    def Lock(self, cell: Ref[Integer], value: Integer) -> Integer:
        old = cell.get()
        cell.set(value)
        return old


class _StringMembers:
    @staticmethod
    def Length(s: String) -> Integer:
        return Integer(len(s))

    @staticmethod
    def Substring(s: String, start: Integer, length: Integer = Integer(-1)) -> String:
        return String(s[start:] if length < 0 else s[start : start + length])


def _cstr(value: Double) -> String:
    return String(str(value))


def fake_module() -> pytypes.ModuleType:
    mod = pytypes.ModuleType("fake_builtins")
    mod.Widget = Widget
    mod.Machine = _Machine()
    mod.StringMembers = _StringMembers
    mod.CStr = _cstr
    mod.GPL_Righty = 1
    mod.CLASSES = {"Widget": "Widget"}
    mod.GLOBAL_CLASSES = {"Machine": "Machine"}
    mod.FUNCTIONS = {"CStr": "CStr"}
    mod.CONSTANTS = {"GPL_Righty": "GPL_Righty"}
    mod.TYPE_MEMBERS = {"String": "StringMembers"}
    return mod


def test_class_members_follow_the_conventions() -> None:
    cat = build_catalogue(fake_module())
    w = cat.lookup_class("WIDGET")
    assert w is not None and not w.is_global
    assert [p.name for p in w.constructor or ()] == ["size"]
    size = w.member("size")
    assert size is not None and size.kind == "property" and size.settable
    assert size.result is t.INTEGER
    area = w.member("Area")
    assert area is not None and not area.settable and area.result is t.DOUBLE
    angle = w.member("angle")
    assert angle is not None and angle.kind == "method" and angle.settable
    assert [p.type for p in angle.params] == [t.INTEGER]
    grow = w.member("Grow")
    assert grow is not None and grow.result is t.VOID
    assert (grow.min_args, grow.max_args) == (1, 2)
    clone = w.member("clone")
    assert clone is not None and clone.result == t.ClassType.of("Widget", builtin=True)
    dist = w.member("Distance")
    assert dist is not None and dist.shared and len(dist.params) == 2
    assert w.member("helper_not_gpl") is None
    assert w.member("set_Angle") is None


def test_global_class_and_byref_parameter() -> None:
    cat = build_catalogue(fake_module())
    m = cat.lookup_class("machine")
    assert m is not None and m.is_global and m.constructor is None
    lock = m.member("LOCK")
    assert lock is not None and lock.shared
    assert lock.params[0].byref and lock.params[0].type is t.INTEGER
    assert not lock.params[1].byref


def test_functions_constants_and_value_type_members() -> None:
    cat = build_catalogue(fake_module())
    f = cat.lookup_function("cstr")
    assert f is not None and f.result is t.STRING and f.params[0].type is t.DOUBLE
    c = cat.lookup_constant("gpl_righty")
    assert c is not None and c.value == 1 and c.type is t.INTEGER
    s = cat.members_of(t.STRING)
    assert s is not None
    sub = s.member("substring")
    assert sub is not None and [p.name for p in sub.params] == ["start", "length"]
    assert sub.params[1].optional and not sub.shared


def test_the_real_runtime_catalogue_has_the_exception_class() -> None:
    exc = load_catalogue().lookup_class("Exception")
    assert exc is not None and exc.python_name == "GplException"
    code = exc.member("errorcode")
    assert code is not None and code.settable and code.result is t.INTEGER
    msg = exc.member("Message")
    assert msg is not None and msg.kind == "method" and msg.result is t.STRING


class _Panel:
    """A fake global class with the forms real members have: a property also assigned with an
    argument, setters whose argument lists differ from the getter's, overloaded calls."""

    @property
    def Power(self) -> Boolean:
        return Boolean(True)

    @Power.setter
    def Power(self, value: Boolean) -> None: ...

    def set_Power(self, timeout: Double, value: Boolean) -> None: ...

    def Custom(self, robot: Integer = Integer(0), index: Integer = Integer(1)) -> Double:
        return Double(0.0)

    @typing.overload
    def set_Custom(self, value: Double) -> None: ...

    @typing.overload
    def set_Custom(self, index: Integer, value: Double) -> None: ...

    def set_Custom(self, *args: Any) -> None: ...

    @typing.overload
    def Pick(self) -> String: ...

    @typing.overload
    def Pick(self, name: String, index: Integer) -> String: ...

    def Pick(self, *args: Any) -> String:
        return String("")

    @not_simulated
    def Jog(self, mode: Integer, axis: Integer, speed: Double = Double(50.0)) -> None:
        """Not simulated: the catalogue still reads this signature."""


def _panel() -> BuiltinClass:
    mod = fake_module()
    mod.Panel = _Panel()
    mod.GLOBAL_CLASSES = {"Machine": "Machine", "Panel": "Panel"}
    panel = build_catalogue(mod).lookup_class("Panel")
    assert panel is not None
    return panel


def test_a_property_with_a_set_companion_is_assigned_bare_and_with_arguments() -> None:
    power = _panel().member("power")
    assert power is not None and power.kind == "property" and power.settable
    assert (power.min_args, power.max_args) == (0, 0)  # read bare only
    assert (power.set_min_args, power.set_max_args) == (0, 1)
    bare, timed = power.set_form(0), power.set_form(1)
    assert bare is not None and [p.type for p in bare] == [t.BOOLEAN]
    assert timed is not None and [(p.name, p.type) for p in timed] == [("timeout", t.DOUBLE), ("value", t.BOOLEAN)]
    assert power.set_form(2) is None


def test_overloads_declare_the_forms_of_setters_and_calls() -> None:
    panel = _panel()
    custom = panel.member("Custom")
    assert custom is not None and (custom.min_args, custom.max_args) == (0, 2)
    assert (custom.set_min_args, custom.set_max_args) == (0, 1)  # Custom(index) = v: not the getter's
    one = custom.set_form(1)
    assert one is not None and [p.name for p in one] == ["index", "value"]
    pick = panel.member("Pick")
    assert pick is not None and (pick.min_args, pick.max_args) == (0, 2)
    assert pick.call_form(0) == () and pick.call_form(1) is None
    two = pick.call_form(2)
    assert two is not None and [p.type for p in two] == [t.STRING, t.INTEGER]


def test_a_member_that_is_not_simulated_keeps_its_signature() -> None:
    panel = _panel()
    jog = panel.member("jog")
    assert jog is not None and not jog.simulated
    assert (jog.min_args, jog.max_args) == (2, 3) and jog.params[2].optional
    power = panel.member("Power")
    assert power is not None and power.simulated
    with pytest.raises(GplException) as info:
        _Panel().Jog(1, 2)
    assert info.value.ErrorCode == -204 and "Panel.Jog" in info.value.Message()


def test_star_args_in_a_gpl_member_is_refused() -> None:
    """``*args`` read as "no parameters" made every call of Move.Trigger an arity error; the
    reader now says which member hides its signature instead."""

    class _Bad:
        def Trigger(self, *args: Any) -> None: ...

    mod = fake_module()
    mod.Bad = _Bad()
    mod.GLOBAL_CLASSES = {"Bad": "Bad"}
    with pytest.raises(CatalogueError, match=r"_Bad.Trigger takes \*args"):
        build_catalogue(mod)


def test_every_runtime_member_declares_its_signature() -> None:
    """No member of the real runtime hides its parameters (the catalogue builds), and the
    simulator's gaps are the members marked not_simulated."""
    cat = load_catalogue()
    move = cat.lookup_class("Move")
    assert move is not None
    speeds = move.member("SetSpeeds")
    assert speeds is not None and not speeds.simulated and (speeds.min_args, speeds.max_args) == (2, 2)
    trigger = move.member("Trigger")
    assert trigger is not None and trigger.simulated and (trigger.min_args, trigger.max_args) == (3, 4)
