"""The transpiler reads built-in signatures from the runtime's catalogue, following CATALOGUE.md."""

from __future__ import annotations

import types as pytypes

from gpl2py.semantics import types as t
from gpl2py.semantics.catalogue import build_catalogue, load_catalogue
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
