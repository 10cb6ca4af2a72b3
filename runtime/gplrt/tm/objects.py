"""Parameterized objects (L14355-L14860): ``Robot[0]`` and ``IO["ControlBox"|"EndModule"]``.

``Robot[0].Joint``, ``.CoordRobot``, ``.CoordBase`` read the simulated robot; ``IO[m].DO[i] = v``
is queued behind the motions, ``InstantDO`` acts at once (L14655-L14659).  Reads give new arrays
(a value, not a view); the items are read only where the manual says so.
"""

from __future__ import annotations

from collections.abc import Callable

from gplrt.tm import context
from gplrt.tm.members import Members
from gplrt.tm.motion import Command
from gplrt.tm.values import Array, TMError, to_byte, to_float


class _RobotItem(Members):
    tm_name = "Robot[0]"

    @property
    def Joint(self) -> Array:
        return Array("float", context.robot().current_joints())

    @property
    def CoordRobot(self) -> Array:
        return Array("float", context.robot().tool())

    @property
    def CoordBase(self) -> Array:
        return Array("float", context.robot().tool_in_base())

    @property
    def BaseName(self) -> str:
        return context.robot().base_name

    @property
    def TCPName(self) -> str:
        return context.robot().tcp_name


class _Robots:
    item = _RobotItem  # (what ``Robot[0]`` gives: the front end checks its members)

    def __getitem__(self, i: object) -> _RobotItem:
        if i != 0:
            raise TMError(f"Robot[{i}] does not exist (only Robot[0])")
        return _RobotItem()


class _Channels:
    """One I/O table: reads the robot's list, writes queued (``queued``) or at once."""

    def __init__(self, get: Callable[[], list[object]], conv: Callable[[object], object], queued: bool,
                 writable: bool, kind: str) -> None:
        self.get, self.conv, self.queued, self.writable, self.kind = get, conv, queued, writable, kind

    def __getitem__(self, i: object) -> object:
        table = self.get()
        idx = int(i)  # type: ignore[call-overload]
        if not 0 <= idx < len(table):
            raise TMError(f"{self.kind}[{idx}] does not exist")
        return table[idx]

    def __setitem__(self, i: object, value: object) -> None:
        if not self.writable:
            return  # writing a read-only item is an invalid operation, ignored (L14433)
        table = self.get()
        idx = int(i)  # type: ignore[call-overload]
        if not 0 <= idx < len(table):
            raise TMError(f"{self.kind}[{idx}] does not exist")
        v = self.conv(value)

        def write() -> None:
            table[idx] = v
        if self.queued:
            context.robot().enqueue(Command("call", run=write))
        else:
            write()

    def __len__(self) -> int:
        return len(self.get())

    def __iter__(self):  # type: ignore[no-untyped-def]
        return iter(list(self.get()))


def _table(key: str, writable: bool) -> property:
    """The table ``key`` of a module; when ``writable``, assigning a whole array (``IO[m].DO =
    {0,0,…}``, L1112) writes every channel (queued for DO/AO).  A read-only one has no setter:
    assigning it is an invalid operation, ignored (L14433)."""

    def get(self: _Module) -> _Channels:
        return self._tables[key]

    def put(self: _Module, value: object) -> None:
        current = self._tables[key]
        if not isinstance(value, (list, tuple)):
            raise TMError(f'IO["{self._name}"].{key} is an array: assign it an array')
        if len(value) > len(current):
            raise TMError(f'IO["{self._name}"].{key} has {len(current)} channels, not {len(value)}')
        for i, v in enumerate(value):
            current[i] = v
    return property(get, put if writable else None)


class _Module(Members):
    """``IO["ControlBox"]``, ``IO["EndModule"]``: their I/O tables."""

    def __init__(self, name: str) -> None:
        self._name = name
        self.tm_name = f'IO["{name}"]'
        prefix = "ctrl" if name == "ControlBox" else "end"
        r = context.robot
        di = _Channels(lambda: getattr(r(), f"{prefix}_di"), to_byte, False, False, "DI")
        ai = _Channels(lambda: getattr(r(), f"{prefix}_ai"), to_float, False, False, "AI")
        self._tables = {
            "DI": di, "InstantDI": di, "AI": ai, "InstantAI": ai,
            "DO": _Channels(lambda: getattr(r(), f"{prefix}_do"), to_byte, True, True, "DO"),
            "InstantDO": _Channels(lambda: getattr(r(), f"{prefix}_do"), to_byte, False, True, "InstantDO"),
            "AO": _Channels(lambda: getattr(r(), f"{prefix}_ao"), to_float, True, True, "AO"),
            "InstantAO": _Channels(lambda: getattr(r(), f"{prefix}_ao"), to_float, False, True, "InstantAO"),
        }

    DI = _table("DI", False)
    InstantDI = _table("InstantDI", False)
    AI = _table("AI", False)
    InstantAI = _table("InstantAI", False)
    DO = _table("DO", True)
    InstantDO = _table("InstantDO", True)
    AO = _table("AO", True)
    InstantAO = _table("InstantAO", True)


class _IOs:
    item = _Module  # (what ``IO[name]`` gives)

    def __getitem__(self, name: object) -> _Module:
        if name not in ("ControlBox", "EndModule"):
            raise TMError(f'IO["{name}"] is not simulated (ControlBox, EndModule)')
        return _Module(str(name))


Robot = _Robots()
IO = _IOs()
