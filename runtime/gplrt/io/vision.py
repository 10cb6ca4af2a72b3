"""GPL ``Vision`` and ``VisResult`` (D0 §15): a PreciseVision client, simulated.

A real controller talks to PreciseVision on a PC (TCP port 1410, DataID 424) with a protocol the
manuals do not document, so the simulator cannot speak it.  Instead a *vision server* object can be
configured; without one every call that would talk to the PC raises -4000 *Cannot connect to vision
server* with the detail "no vision server configured in the simulator" — the same code a controller
reports when the PC is absent, so programs' error handling behaves as on a real cell.

    from gplrt.io.vision import ScriptedVisionServer, VisionToolResult, set_vision_server
    server = ScriptedVisionServer()
    server.add_process("Main", {"part1": [VisionToolResult(loc=some_location)]})
    set_vision_server(server)

Decisions: ``Result(tool, index)`` is 1-based (D0:4487-4489, EX-30); ``VisResult.Info(n)`` is
0-based like GPL arrays (undocumented); a tool the process does not have -> -4013, an index out of
range -> -4014, an unknown process -> -4012, results asked before any ``Process`` -> -4013.
``Process`` waits for completion (D0:4359-4362) and replaces this object's results only.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Any, Protocol, overload

from gplrt.lang.errors import (
    VISION_CANNOT_CONNECT,
    VISION_INVALID_INDEX,
    VISION_PROPERTY_NOT_FOUND,
    VISION_UNKNOWN_PROCESS,
    VISION_UNKNOWN_TOOL,
    GplException,
)
from gplrt.io.sockets import dotted_quad
from gplrt.lang.conversions import to_int32
from gplrt.lang.gpltypes import Boolean, Double, Integer, String


STATUS_NONE, STATUS_RUNNING, STATUS_ERROR, STATUS_OK = 0, 1, 2, 3


@dataclass
class VisionToolResult:
    """One result set of a vision tool, as a simulated server reports it."""

    loc: Any = None  # a gplrt Location (Cartesian), or None
    info: list[float] = field(default_factory=list)
    info_string: str = ""
    inspect_actual: float = 0.0
    inspect_passed: bool = False
    error_code: int = 0


class VisionServer(Protocol):
    """What the simulator plugs in place of a PreciseVision PC."""

    def process(self, name: str, instance: int) -> dict[str, list[VisionToolResult]]:
        """Run vision process ``name``; its tools' result sets (raise GplException on failure)."""
        ...

    def get_property(self, tool: str, prop: str) -> str: ...

    def set_property(self, tool: str, prop: str, value: str) -> None: ...


class ScriptedVisionServer:
    """A vision server that returns results scripted by a test or a simulation setup."""

    def __init__(self) -> None:
        self.processes: dict[str, dict[str, list[VisionToolResult]]] = {}
        self.properties: dict[tuple[str, str], str] = {}
        self.runs: list[str] = []

    def add_process(self, name: str, tools: dict[str, list[VisionToolResult]]) -> None:
        self.processes[name] = tools

    def process(self, name: str, instance: int) -> dict[str, list[VisionToolResult]]:
        self.runs.append(name)
        if name not in self.processes:
            raise GplException(VISION_UNKNOWN_PROCESS, detail=f"vision process {name!r}")
        return {tool: list(sets) for tool, sets in self.processes[name].items()}

    def get_property(self, tool: str, prop: str) -> str:
        if (tool, prop) not in self.properties:
            raise GplException(VISION_PROPERTY_NOT_FOUND, detail=f"{tool}.{prop}")
        return self.properties[(tool, prop)]

    def set_property(self, tool: str, prop: str, value: str) -> None:
        self.properties[(tool, prop)] = value


_server: VisionServer | None = None
_server_lock = threading.Lock()


def set_vision_server(server: VisionServer | None) -> None:
    """Plug a simulated vision server in (``None`` = no vision PC, calls raise -4000)."""
    global _server
    with _server_lock:
        _server = server


def _connect() -> VisionServer:
    with _server_lock:
        server = _server
    if server is None:
        raise GplException(
            VISION_CANNOT_CONNECT,
            detail="no vision server configured in the simulator (gplrt.io.vision.set_vision_server)",
        )
    return server


class VisResult:
    """``New VisResult``: one result set (normally returned by ``Vision.Result``)."""

    def __init__(self, *, _data: VisionToolResult | None = None, _process_id: int = 0) -> None:
        self._data = _data if _data is not None else VisionToolResult()
        self._process_id = _process_id

    @property
    def ErrorCode(self) -> Integer:
        return Integer(self._data.error_code)

    def Info(self, n: Integer) -> Double:
        """The n-th numeric information item (0-based)."""
        i = to_int32(n)
        if not 0 <= i < len(self._data.info):
            raise GplException(VISION_INVALID_INDEX, detail=f"Info({i}) of {len(self._data.info)} items")
        return Double(float(self._data.info[i]))

    @property
    def InfoCount(self) -> Integer:
        return Integer(len(self._data.info))

    @property
    def InfoString(self) -> String:
        return String(self._data.info_string)

    @property
    def InspectActual(self) -> Double:
        return Double(self._data.inspect_actual)

    @property
    def InspectPassed(self) -> Boolean:
        return Boolean(self._data.inspect_passed)

    @property
    def Loc(self) -> Any:
        """The result's Cartesian Location (``Nothing`` if the tool gave none)."""
        return self._data.loc

    @property
    def ProcessID(self) -> Integer:
        return Integer(self._process_id)

    @property
    def Type(self) -> Integer:
        """Always 0 ("currently always zero", D0:4429)."""
        return Integer(0)


class Vision:
    """``New Vision``: an empty client object; ``Process``/``Result``/``ResultCount`` connect on demand."""

    def __init__(self) -> None:
        self._ip = ""
        self._instance = 1
        self._status = STATUS_NONE
        self._error = 0
        self._results: dict[str, list[VisionToolResult]] | None = None
        self._process_id = 0

    @property
    def IPAddress(self) -> String:
        return String(self._ip)

    @IPAddress.setter
    def IPAddress(self, value: String) -> None:
        self._ip = dotted_quad(str(value))  # the rule IPEndPoint follows (-1704 otherwise)

    @property
    def Instance(self) -> Integer:
        return Integer(self._instance)

    @Instance.setter
    def Instance(self, value: Integer) -> None:
        self._instance = to_int32(value)

    @property
    def ErrorCode(self) -> Integer:
        """0 after a successful process, negative after a failed one."""
        return Integer(self._error)

    @property
    def Status(self) -> Integer:
        """0 none, 1 running, 2 complete with error, 3 complete OK."""
        return Integer(self._status)

    def Disconnect(self) -> None:
        """Close the connection (nothing to close in simulation; results are kept)."""

    def Process(self, vision_process_name: String, vision_process_id: Integer = Integer(0)) -> None:
        """Run a vision process and wait for it; replaces this object's results."""
        server = _connect()
        self._status = STATUS_RUNNING
        try:
            results = server.process(str(vision_process_name), self._instance)
        except GplException as exc:
            self._status, self._error, self._results = STATUS_ERROR, exc.ErrorCode, None
            raise
        self._status, self._error, self._results = STATUS_OK, 0, results
        self._process_id = to_int32(vision_process_id)

    def _tool(self, tool_name: str) -> list[VisionToolResult]:
        """The result sets of a tool of the last process; ``""`` is the default tool, the
        process's first (TCS 3.0C1 asks for "the default result" without naming a tool)."""
        _connect()
        if self._results is not None and tool_name == "" and self._results:
            return next(iter(self._results.values()))
        if self._results is None or tool_name not in self._results:
            raise GplException(VISION_UNKNOWN_TOOL, detail=f"no results for vision tool {tool_name!r}")
        return self._results[tool_name]

    def ResultCount(self, vision_tool_name: String = String("")) -> Integer:
        """Number of result sets the tool produced in the last process (no name: the default
        tool's, as ``vis.ResultCount`` reads in TCS; docs/design/real-code.md)."""
        return Integer(len(self._tool(str(vision_tool_name))))

    def Result(self, vision_tool_name: String = String(""), index: Integer = Integer(1),
               location_object: Any = None) -> VisResult:
        """Result set ``index`` (1 = first) of a tool; ``Result()`` is the default tool's first
        (TCS's "default result").  ``location_object`` is accepted for the dictionary's
        three-argument form and not used."""
        sets = self._tool(str(vision_tool_name))
        i = to_int32(index)
        if not 1 <= i <= len(sets):
            raise GplException(VISION_INVALID_INDEX, detail=f"Result({vision_tool_name!r}, {i}) of {len(sets)}")
        return VisResult(_data=sets[i - 1], _process_id=self._process_id)

    def ToolProperty(self, tool: String, prop: String | None = None) -> String:
        """A tool property (or a ``"system"`` property) of the vision server:
        ``ToolProperty("tool.prop")`` or ``ToolProperty(tool, prop)``."""
        return String(_connect().get_property(*_tool_and_property(tool, prop)))

    @overload
    def set_ToolProperty(self, tool_prop: String, value: String) -> None: ...

    @overload
    def set_ToolProperty(self, tool: String, prop: String, value: String) -> None: ...

    def set_ToolProperty(self, tool: String, *rest: String) -> None:
        """``vis.ToolProperty("tool.prop") = v`` or ``vis.ToolProperty(tool, prop) = v``."""
        prop = rest[0] if len(rest) > 1 else None
        _connect().set_property(*_tool_and_property(tool, prop), str(rest[-1]))


def _tool_and_property(tool: Any, prop: Any) -> tuple[str, str]:
    """The tool and property a ``ToolProperty`` call names: ``("tool.prop")`` is split at its
    last dot; a name without one names no property (-4017)."""
    if prop is not None:
        return str(tool), str(prop)
    name, dot, prop_name = str(tool).rpartition(".")
    if not dot:
        raise GplException(VISION_PROPERTY_NOT_FOUND, detail=f"{tool!r} is not \"tool.property\"")
    return name, prop_name


__all__ = ["Vision", "VisResult", "ScriptedVisionServer", "VisionToolResult", "set_vision_server"]
