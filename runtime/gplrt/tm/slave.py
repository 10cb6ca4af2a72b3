"""The TM Ethernet Slave: port 5891, ``$TMSVR`` reads and writes of the robot's data table
(manual §16, L19694-L20556).

Modes (L20005): 2 string ``Item=Value`` lines, 3 JSON ``[{"Item":…, "Value":…}]``, 1 binary
(2-byte little-endian name length, UTF-8 name, 2-byte length, little-endian value) write items;
12/13/11 request reads in the same three forms, answered in that mode.  A write is answered
``ID,0,00,OK`` or ``ID,0,<code>,<text>[;item]`` with the codes of L20040-L20060.  The table holds
the items clients read (robot model, joints, flange and tool poses, joint speeds, error, project
state) and the writable control-box and end-module outputs.  The server does not broadcast
periodically (clients here request what they read).
"""

from __future__ import annotations

import json
import struct
from collections.abc import Callable
from dataclasses import dataclass

from gplrt.tm import context
from gplrt.tm.motion import Robot
from gplrt.tm.packets import encode
from gplrt.tm.server import Conn, Server
from gplrt.tm.values import TMError, format_value

PORT = 5891


@dataclass
class Item:
    type: str  # byte int float bool string (an element's type for arrays)
    size: int  # 1 scalar, n array
    get: Callable[[], object]
    set: Callable[[object], None] | None = None


class Table:
    """The Ethernet Slave's data table of one robot."""

    def __init__(self, robot: Robot) -> None:
        r = robot
        items: dict[str, Item] = {
            "Robot_Model": Item("string", 1, lambda: r.arm.name),
            "Robot_Link": Item("byte", 1, lambda: 1),
            "Robot_Error": Item("bool", 1, lambda: r.error_code != 0),
            "Error_Code": Item("int", 1, lambda: r.error_code),
            "Project_Run": Item("bool", 1, lambda: r.project_running),
            "Project_Pause": Item("bool", 1, lambda: r.paused),
            "Get_Control": Item("bool", 1, lambda: True),
            "Joint_Angle": Item("float", 6, r.current_joints),
            "Joint_Speed": Item("float", 6, r.joint_speeds),
            "Coord_Robot_Flange": Item("float", 6, r.flange),
            "Coord_Robot_Tool": Item("float", 6, r.tool),
            "Coord_Base_Tool": Item("float", 6, r.tool_in_base),
            "TCP_Mass": Item("float", 1, lambda: r.tool_mass),
            "Payload": Item("float", 1, lambda: r.load),
        }
        for i in range(len(r.ctrl_do)):
            items[f"Ctrl_DO{i}"] = Item("byte", 1, (lambda i=i: r.ctrl_do[i]), (lambda v, i=i: r.ctrl_do.__setitem__(i, v)))
        for i in range(len(r.ctrl_di)):
            items[f"Ctrl_DI{i}"] = Item("byte", 1, lambda i=i: r.ctrl_di[i])
        for i in range(len(r.end_do)):
            items[f"End_DO{i}"] = Item("byte", 1, (lambda i=i: r.end_do[i]), (lambda v, i=i: r.end_do.__setitem__(i, v)))
        for i in range(len(r.end_di)):
            items[f"End_DI{i}"] = Item("byte", 1, lambda i=i: r.end_di[i])
        for i in range(len(r.ctrl_ao)):
            items[f"Ctrl_AO{i}"] = Item("float", 1, (lambda i=i: r.ctrl_ao[i]), (lambda v, i=i: r.ctrl_ao.__setitem__(i, v)))
        self.items = items

    def read(self, name: str) -> object:
        item = self.items.get(name)
        if item is None:
            raise TMError(f"the Ethernet Slave has no item {name!r}")
        return item.get()

    def write(self, name: str, value: object) -> int:
        """0 written, 4 no such item, 5 read only, 7 value of the wrong type or size (L20040)."""
        item = self.items.get(name)
        if item is None:
            return 4
        if item.set is None:
            return 5
        v = _coerce(item, value)
        if v is None:
            return 7
        item.set(v)
        return 0


def _coerce(item: Item, value: object) -> object | None:
    if item.size != 1:
        return None
    if item.type == "byte":
        if isinstance(value, bool) or not isinstance(value, (int, float)) or int(value) != value or not 0 <= value <= 255:
            return None
        return int(value)
    if item.type == "float":
        return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else None
    return None


def table() -> Table:
    """The current robot's table (``svr_read``/``svr_write``)."""
    r = context.robot()
    t = getattr(r, "_svr_table", None)
    if t is None:
        t = Table(r)
        r._svr_table = t  # type: ignore[attr-defined]
    return t


def _text(value: object) -> str:
    """A value in the string mode: ``{1,2}`` arrays, ``"text"`` strings, ``true``."""
    if isinstance(value, str):
        return '"' + value + '"'
    if isinstance(value, (list, tuple)):
        return "{" + ",".join(_text(v) for v in value) + "}"
    if isinstance(value, float):
        return repr(value)
    return format_value(value)


def _parse_text(text: str) -> object:
    t = text.strip()
    if t in ("true", "false"):
        return t == "true"
    if t.startswith('"') and t.endswith('"') and len(t) >= 2:
        return t[1:-1]
    if t.startswith("{") and t.endswith("}"):
        inner = t[1:-1].strip()
        return [_parse_text(x) for x in inner.split(",")] if inner else []
    try:
        return int(t, 0)
    except ValueError:
        return float(t)


def _binary_value(item: Item, value: object) -> bytes:
    fmt = {"byte": "B", "int": "<i", "float": "<f", "bool": "?"}.get(item.type)
    if item.type == "string":
        return str(value).encode("utf-8")
    assert fmt is not None
    if isinstance(value, (list, tuple)):
        return b"".join(struct.pack(fmt, v) for v in value)
    return struct.pack(fmt, value)


class EthernetSlave:
    def __init__(self, robot: Robot, host: str = "127.0.0.1", port: int = PORT) -> None:
        self.robot = robot
        self.table = Table(robot)
        robot._svr_table = self.table  # type: ignore[attr-defined]
        self.host, self.port = host, port
        self._server: Server | None = None

    def serve(self) -> EthernetSlave:
        """Listen (port 0: a free one, see ``port``) on threads of the robot's scheduler, with the
        runtime's sockets (``gplrt.tm.server``)."""
        self._server = Server(self.robot.sim, self.host, self.port, self._serve_conn, "tm-svr")
        self.port = self._server.port
        self.robot.drive()
        return self

    def close(self) -> None:
        if self._server is not None:
            self._server.close()
            self._server = None
            self.robot.undrive()

    def _serve_conn(self, conn: Conn) -> None:
        for frame in conn.frames():
            if frame.error or frame.header != b"TMSVR":
                reply = encode("CPERR", f"{frame.error or 3:02X}".encode())
            else:
                reply = self._request(frame.data)
            conn.send(reply)
            if conn.closed:
                return

    def _request(self, data: bytes) -> bytes:
        ident, _, rest = data.partition(b",")
        mode_text, _, content = rest.partition(b",")
        tid = ident.decode("utf-8", "replace")
        if not tid.isalnum() or not tid.isascii():
            return encode("CPERR", b"04")

        def status(code: int, text: str) -> bytes:
            return encode("TMSVR", f"{tid},0,{code:02X},{text}".encode())
        try:
            mode = int(mode_text)
        except ValueError:
            return status(1, "NotSupport")
        if mode in (11, 12, 13):
            return self._read(tid, mode, content, status)
        if mode not in (1, 2, 3):
            return status(1, "NotSupport")
        try:
            pairs = self._decode(mode, content)
        except (ValueError, KeyError, TypeError, UnicodeDecodeError, struct.error):
            return status(3, "InvalidData")
        for name, value in pairs:
            code = self.table.write(name, value)
            if code:
                word = {4: "NotExist", 5: "ReadOnly", 7: "ValueError"}[code]
                return status(code, f"{word};{name}")
        return status(0, "OK")

    def _decode(self, mode: int, content: bytes) -> list[tuple[str, object]]:
        if mode == 2:
            out = []
            for line in content.decode("utf-8").split("\r\n"):
                if line:
                    name, eq, value = line.partition("=")
                    if not eq:
                        raise ValueError(line)
                    out.append((name, _parse_text(value)))
            return out
        if mode == 3:
            data = json.loads(content.decode("utf-8"))
            data = data if isinstance(data, list) else [data]
            return [(str(d["Item"]), d["Value"]) for d in data]
        out2: list[tuple[str, object]] = []
        i = 0
        while i < len(content):
            (n,) = struct.unpack_from("<H", content, i)
            name = content[i + 2:i + 2 + n].decode("utf-8")
            i += 2 + n
            (m,) = struct.unpack_from("<H", content, i)
            raw = content[i + 2:i + 2 + m]
            i += 2 + m
            item = self.table.items.get(name)
            if item is None:
                out2.append((name, None))
                continue
            fmt = {"byte": "B", "int": "<i", "float": "<f", "bool": "?"}.get(item.type, "B")
            vals = [v[0] for v in struct.iter_unpack(fmt, raw)] if item.type != "string" else [raw.decode()]
            out2.append((name, vals[0] if len(vals) == 1 else vals))
        return out2

    def _read(self, tid: str, mode: int, content: bytes, status: Callable[[int, str], bytes]) -> bytes:
        if mode == 11:
            names, i = [], 0
            while i < len(content):
                (n,) = struct.unpack_from("<H", content, i)
                names.append(content[i + 2:i + 2 + n].decode("utf-8"))
                i += 2 + n
        elif mode == 13:
            try:
                parsed = json.loads(content.decode("utf-8"))
            except ValueError:
                return status(3, "InvalidData")
            names = [str(x["Item"] if isinstance(x, dict) else x) for x in (parsed if isinstance(parsed, list) else [parsed])]
        else:
            names = [n for n in content.decode("utf-8", "replace").split("\r\n") if n]
        for name in names:
            if name not in self.table.items:
                return status(4, f"NotExist;{name}")
        values = [(name, self.table.items[name], self.table.items[name].get()) for name in names]
        if mode == 12:
            body = "\r\n".join(f"{n}={_text(v)}" for n, _, v in values).encode("utf-8")
        elif mode == 13:
            body = json.dumps([{"Item": n, "Value": v} for n, _, v in values]).encode("utf-8")
        else:
            body = b"".join(struct.pack("<H", len(n.encode())) + n.encode()
                            + struct.pack("<H", len(b := _binary_value(it, v))) + b for n, it, v in values)
        return encode("TMSVR", f"{tid},{mode},".encode() + body)
