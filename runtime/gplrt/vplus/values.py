"""V+ variables: cells, growing arrays, the GLOBAL and LOCAL stores, the program registry.

Why every variable is a cell (docs/design/vplus-runtime.md §2): V+ passes a variable argument by
reference whatever the callee (L1169-1183) and an expression by value, decided at the call site,
and a read before the first assignment is an error (L4129-4143).  A cell (``.v``) gives both: the
callee always receives something with ``.v``, and the cell knows whether it was ever assigned.

Globals and LOCALs belong to the session (two simulations share nothing): ``G["name"]`` finds the
calling thread's session.  Programs belong to the process (they are code), registered by V+ name.
"""

from __future__ import annotations

import threading
import weakref
from collections.abc import Callable
from typing import Any

from gplrt.geometry.location import Location
from gplrt.session import Session, current_session
from gplrt.vplus.errors import ILLEGAL_INDEX, STRING_TOO_LONG, TYPE_MISMATCH, UNDEFINED_NAME, UNDEFINED_VALUE, VError

MAX_STRING = 128
MAX_INDEX = 32767
_UNSET: Any = object()


def vname(name: str) -> str:
    """The key of a V+ name: lower case, 15 significant characters after the sigil (L3787)."""
    name = name.strip().lower()
    sigil = name[0] if name[:1] in ("$", "#", "%") else ""
    return sigil + name[len(sigil):][:15]


def kind_of(value: Any) -> str:
    """The V+ data type of a Python value: real, string, transformation or precision point."""
    if isinstance(value, str):
        return "string"
    if isinstance(value, Location):
        return "ppoint" if value._type == 1 else "trans"
    return "real"


def check_value(value: Any) -> Any:
    """A value as a cell stores it: reals as float, strings at most 128 characters (§3.4)."""
    if isinstance(value, str):
        if len(value) > MAX_STRING:
            raise VError(STRING_TOO_LONG, detail=f"{len(value)} characters")
        return value
    if isinstance(value, Location):
        return value
    if isinstance(value, bool):
        return -1.0 if value else 0.0
    return float(value)


class Cell:
    """One V+ variable (or a temporary holding a by-value argument): ``.v`` reads and writes it."""

    __slots__ = ("name", "_value")

    def __init__(self, name: str = "", value: Any = _UNSET) -> None:
        self.name = name
        self._value = _UNSET if value is _UNSET else check_value(value)

    @property
    def v(self) -> Any:
        value = self._value
        if value is _UNSET:
            raise VError(UNDEFINED_VALUE, detail=self.name or "argument")
        return value

    @v.setter
    def v(self, value: Any) -> None:
        value = check_value(value)
        old = self._value
        if old is not _UNSET and type(old) is not type(value) and kind_of(old) != kind_of(value):
            raise VError(TYPE_MISMATCH, detail=f"{self.name}: {kind_of(old)} := {kind_of(value)}")
        self._value = value

    @property
    def defined(self) -> bool:
        return self._value is not _UNSET

    def clear(self) -> None:
        self._value = _UNSET

    def __repr__(self) -> str:
        return f"Cell({self.name!r}, {'undefined' if self._value is _UNSET else repr(self._value)})"


Ref = Cell  # what a parameter receives: anything with ``.v`` (a Cell or an ElementRef)


def byval(value: Any) -> Cell:
    """A by-value argument: a new cell holding ``value`` (L1193-1210)."""
    return Cell("", value)


def defined(ref: Any) -> float:
    """``DEFINED(x)``: -1 when the variable (cell, element reference or array) holds a value."""
    if isinstance(ref, VArray):
        return -1.0 if ref._data else 0.0
    return -1.0 if ref.defined else 0.0


def _index(i: Any) -> int:
    n = int(round_half_away(float(i)))
    if not 0 <= n <= MAX_INDEX:
        raise VError(ILLEGAL_INDEX, detail=str(n))
    return n


def round_half_away(x: float) -> float:
    """V+ rounds integer arguments half away from zero (L333-335, L3872-3873)."""
    return float(int(x + 0.5)) if x >= 0 else -float(int(-x + 0.5))


class ElementRef:
    """A reference to one array element, passed by reference (``CALL p(a[i])``)."""

    __slots__ = ("array", "key")

    def __init__(self, array: VArray, key: tuple[int, ...]) -> None:
        self.array = array
        self.key = key

    @property
    def v(self) -> Any:
        return self.array._get(self.key)

    @v.setter
    def v(self, value: Any) -> None:
        self.array._set(self.key, value)

    @property
    def defined(self) -> bool:
        return self.key in self.array._data


class VArray:
    """A V+ array of up to 3 dimensions, 0-based, growing as it is assigned (L3986-4049).

    ``a[i]``, ``a[i, j]``; an element never assigned reads as *Undefined value*, whatever the
    array's type: allocation is not assignment (L4013-4022, L4129-4143; docs/design/vplus.md,
    "string array elements")."""

    __slots__ = ("name", "_data", "_kind", "_lock")

    def __init__(self, name: str = "", *sizes: Any) -> None:
        self.name = name
        self._data: dict[tuple[int, ...], Any] = {}
        self._kind: str | None = "string" if name.startswith("$") else None
        self._lock = threading.Lock()

    @staticmethod
    def _key(index: Any) -> tuple[int, ...]:
        if isinstance(index, tuple):
            if not 1 <= len(index) <= 3:
                raise VError(ILLEGAL_INDEX, detail=f"{len(index)} indices")
            return tuple(_index(i) for i in index)
        return (_index(index),)

    def _get(self, key: tuple[int, ...]) -> Any:
        try:
            return self._data[key]
        except KeyError:
            raise VError(UNDEFINED_VALUE, detail=f"{self.name}[{', '.join(map(str, key))}]") from None

    def _set(self, key: tuple[int, ...], value: Any) -> None:
        value = check_value(value)
        kind = kind_of(value)
        with self._lock:  # (extension is interlocked between tasks: L4028-4049)
            if self._kind is None:
                self._kind = kind
            elif self._kind != kind:
                raise VError(TYPE_MISMATCH, detail=f"{self.name}: {self._kind} array := {kind}")
            self._data[key] = value

    def __getitem__(self, index: Any) -> Any:
        return self._get(self._key(index))

    def __setitem__(self, index: Any, value: Any) -> None:
        self._set(self._key(index), value)

    def ref(self, *index: Any) -> ElementRef:
        """The element as a by-reference argument."""
        return ElementRef(self, self._key(index if len(index) != 1 else index[0]))

    def last(self, dim: int = 1) -> float:
        """``LAST(a[])``: the highest index assigned in dimension ``dim`` (1-based), -1 if none."""
        keys = [k[dim - 1] for k in self._data if len(k) >= dim]
        return float(max(keys)) if keys else -1.0

    def __repr__(self) -> str:
        return f"VArray({self.name!r}, {len(self._data)} elements)"


def last(array: VArray, dim: Any = 1) -> float:
    """``LAST(array[])`` / ``LAST(array[], dim)``."""
    return array.last(int(dim))


class Store:
    """A namespace of V+ variables: the globals of a session, or one program's LOCALs."""

    def __init__(self) -> None:
        self._cells: dict[str, Cell] = {}
        self._arrays: dict[str, VArray] = {}
        self._lock = threading.Lock()

    def __getitem__(self, name: str) -> Cell:
        key = vname(name)
        cell = self._cells.get(key)
        if cell is None:
            with self._lock:
                cell = self._cells.setdefault(key, Cell(key))
        return cell

    def array(self, name: str) -> VArray:
        key = vname(name)
        arr = self._arrays.get(key)
        if arr is None:
            with self._lock:
                arr = self._arrays.setdefault(key, VArray(key))
        return arr

    def names(self) -> list[str]:
        return sorted(k for k, c in self._cells.items() if c.defined) + sorted(
            k + "[]" for k, a in self._arrays.items() if a._data)


class SessionData:
    """What V+ keeps per session: globals, LOCAL stores (per program), and the layer's other
    per-session state, which the modules that own it hang here by name."""

    def __init__(self) -> None:
        self.globals = Store()
        self.locals: dict[str, Store] = {}
        self.extra: dict[str, Any] = {}
        self.lock = threading.RLock()


_sessions: weakref.WeakKeyDictionary[Session, SessionData] = weakref.WeakKeyDictionary()
_sessions_lock = threading.Lock()


def session_data(session: Session | None = None) -> SessionData:
    s = session if session is not None else current_session()
    data = _sessions.get(s)
    if data is None:
        with _sessions_lock:
            data = _sessions.setdefault(s, SessionData())
    return data


class _Globals:
    """``G["name"]``: the global cell of that name in the calling thread's session."""

    __slots__ = ()

    def __getitem__(self, name: str) -> Cell:
        return session_data().globals[name]

    def array(self, name: str) -> VArray:
        return session_data().globals.array(name)


G = _Globals()


def local_store(program: str) -> Store:
    """The LOCAL variables of ``program``: one store shared by every call and task (L4069-4082)."""
    data = session_data()
    key = vname(program)
    store = data.locals.get(key)
    if store is None:
        with data.lock:
            store = data.locals.setdefault(key, Store())
    return store


# -- programs -------------------------------------------------------------------------------------

_programs: dict[str, Callable[..., Any]] = {}


def program(name: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Register a generated function as the V+ program ``name`` (for CALLS, EXECUTE, REACT)."""

    def register(fn: Callable[..., Any]) -> Callable[..., Any]:
        _programs[vname(name)] = fn
        fn.vplus_name = name  # type: ignore[attr-defined]
        return fn

    return register


def find_program(name: str | Callable[..., Any]) -> Callable[..., Any]:
    """A program by V+ name (or the function itself); unknown -> *Undefined program or variable name*."""
    if callable(name):
        return name
    fn = _programs.get(vname(str(name)))
    if fn is None:
        raise VError(UNDEFINED_NAME, detail=str(name))
    return fn


def calls(name: str, *args: Any) -> Any:
    """``CALLS $name(args)``: call the program whose name the string holds (L4432-4448)."""
    return find_program(name)(*args)
