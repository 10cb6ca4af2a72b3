"""TMscript's TCP client: the ``Socket`` class and ``socket_*`` functions (manual §9,
L13396-L14356; spec §3.12) on the runtime's sockets.

``Socket ntd = "192.168.1.10", 12345 [, timeoutMs]`` declares a device named after its variable
(the front end passes the name); ``socket_open("ntd")`` connects, through ``gplrt.io.sockets``
(the connect time-out and the listen policy of the robot's session, docs/security.md).  Once
connected, a reader -- a thread of the robot's scheduler, as the rest of the TM layer -- keeps
receiving into the device's Received Buffer (L13484: when full, the oldest bytes are dropped);
``socket_read``/``socket_read_string`` take from it, waiting up to their read time in controller
time for data; ``socket_send``/``socket_sendline`` send a value's bytes (little-endian numbers,
UTF-8 text, L14160) and return the manual's status codes.

Not simulated: a flow project's automatic connection (a script opens its devices, L13439) and
the closing of a device when its block is left (L1320: the device lives until the robot's
session ends or ``socket_close``).
"""

from __future__ import annotations

from gplrt.io._codec import from_bytes
from gplrt.io.sockets import IPEndPoint, TcpClient
from gplrt.lang.errors import GplException
from gplrt.tm import context
from gplrt.tm.conversions import GetBytes, write_span
from gplrt.tm.motion import Robot, start_thread
from gplrt.tm.server import Conn
from gplrt.tm.values import Array, TMError, to_int, to_string

#: The Received Buffer's capacity in bytes (the manual gives none; the oldest bytes go first).
BUFFER_SIZE = 1024 * 1024


class Socket:
    """A TCP client device ``name`` to ``ip``:``port``; ``timeout`` ms for reads and writes
    (0-10000, default 10000, L13410)."""

    def __init__(self, name: str, ip: object, port: object, timeout: object = 10000) -> None:
        self.name, self.ip, self.port = name, to_string(ip), to_int(port)
        self.timeout = to_int(timeout)
        if not 0 <= self.timeout <= 10000:
            raise TMError(f"Socket {name}: the timeout {self.timeout} ms is not in 0-10000 (L13410)")
        self.robot = context.robot()
        self.buffer = bytearray()
        self.conn: Conn | None = None
        _devices(self.robot)[name.lower()] = self

    def open(self) -> bool:
        if self.conn is not None and not self.conn.closed:
            return True
        if not 0 < self.port < 65536 or not self.ip:
            return False
        client = TcpClient()
        try:
            client.Connect(IPEndPoint(self.ip, self.port))  # type: ignore[arg-type]
        except GplException:
            client.Close()
            return False
        self.conn = conn = Conn(client.Client())
        start_thread(self.robot.sched, f"tm-socket-{self.name}", lambda: self._receive(conn))
        return True

    def _receive(self, conn: Conn) -> None:
        """The reader: everything the peer sends goes to the Received Buffer."""
        try:
            while True:
                data = conn.recv()
                if not data:
                    break
                self.buffer += data
                if len(self.buffer) > BUFFER_SIZE:
                    del self.buffer[:len(self.buffer) - BUFFER_SIZE]
                self.robot._notify()
        finally:
            conn.closed = True
            self.robot._notify()

    def close(self) -> bool:
        conn, self.conn = self.conn, None
        if conn is not None:
            conn.close()
        self.buffer.clear()
        return True

    def wait(self, ready: object, ms: int) -> None:
        """Wait up to ``ms`` of controller time for ``ready()`` (new data wakes the wait)."""
        if ms <= 0:
            return
        robot = self.robot
        end = robot.clock.now() + ms / 1000.0
        with robot.sched.adopted():
            while not ready() and not robot.clock.reached(end):  # type: ignore[operator]
                robot.sched.wait(robot.changed, end)


def _devices(robot: Robot) -> dict[str, Socket]:
    found = getattr(robot, "_socket_devices", None)
    if found is None:
        found = robot._socket_devices = {}  # type: ignore[attr-defined]
    return found  # type: ignore[no-any-return]


def _device(name: object) -> Socket | None:
    return _devices(context.robot()).get(to_string(name).lower())


def _known(name: object, what: str) -> Socket:
    dev = _device(name)
    if dev is None:
        raise TMError(f"{what}: no Socket device named {to_string(name)!r}")
    return dev


def socket_open(name: object) -> bool:
    """Connect the device (L13442)."""
    return _known(name, "socket_open").open()


def socket_close(name: object) -> bool:
    """Disconnect it; its Received Buffer is cleared (L13470)."""
    return _known(name, "socket_close").close()


def _condition(x: object) -> bytes:
    """A prefix or suffix condition: ``string`` (UTF-8) or ``byte[]``."""
    return to_string(x).encode("utf-8") if isinstance(x, str) else bytes(int(b) & 0xFF for b in x)  # type: ignore[attr-defined]


def _take(dev: Socket, args: tuple[object, ...]) -> bytes:
    """What a read takes from the Received Buffer (L13505-L13856): all; a fixed count (nothing
    until that many are there); or the first match of a prefix and a suffix (fetch option 0/1
    anywhere, 2/3 at the start; 1/3 without the prefix and suffix).  The last int is a read
    time in ms to wait for it."""
    buf = dev.buffer
    if not args:
        data = bytes(buf)
        buf.clear()
        return data
    if not isinstance(args[0], (str, list, tuple)):
        n = to_int(args[0])
        ms = to_int(args[1]) if len(args) > 1 else 0
        if n <= 0:
            dev.wait(lambda: bool(buf), ms)
            data = bytes(buf)
            buf.clear()
            return data
        dev.wait(lambda: len(buf) >= n, ms)
        if len(buf) < n:
            return b""
        data = bytes(buf[:n])
        del buf[:n]
        return data
    if len(args) < 2:
        raise TMError("socket_read: a prefix needs a suffix condition")
    prefix, suffix = _condition(args[0]), _condition(args[1])
    option = to_int(args[2]) if len(args) > 2 else 0
    ms = to_int(args[3]) if len(args) > 3 else 0
    if option not in (0, 1, 2, 3):
        raise TMError(f"socket_read: fetch option {option} is not 0-3")
    found: list[tuple[int, int]] = []

    def match() -> bool:
        span = _match(bytes(buf), prefix, suffix, option >= 2)
        if span is not None:
            found.append(span)
        return span is not None
    dev.wait(match, ms)
    if not found and not match():
        return b""
    start, end = found[-1]
    data = bytes(buf[start:end])
    del buf[:end]
    if option in (1, 3):
        data = data[len(prefix):len(data) - len(suffix)]
    return data


def _match(data: bytes, prefix: bytes, suffix: bytes, at_start: bool) -> tuple[int, int] | None:
    """(start, end) of the first ``prefix``...``suffix`` in ``data``, or None."""
    if not prefix and not suffix:
        return (0, len(data)) if data else None
    start = data.find(prefix) if prefix else 0
    if start < 0 or (at_start and start != 0):
        return None
    if not suffix:
        return start, len(data)
    end = data.find(suffix, start + len(prefix))
    return None if end < 0 else (start, end + len(suffix))


def socket_read(name: object, *args: object) -> Array:
    """Bytes from the device's Received Buffer (L13505): ``(dev)``, ``(dev, n [, ms])``,
    ``(dev, prefix, suffix [, option [, ms]])``; ``byte[0]`` when nothing matches."""
    return Array("byte", _take(_known(name, "socket_read"), args))


def socket_read_string(name: object, *args: object) -> str:
    """As ``socket_read``, as UTF-8 text (L13857)."""
    return _take(_known(name, "socket_read_string"), args).decode("utf-8", errors="replace")


def _send(name: object, value: object, start: object, length: object, line: bool) -> int:
    dev = _device(name)
    if dev is None:
        return -3
    part = write_span(value, start, length)
    data = bytes(GetBytes(part)) + (b"\r\n" if line else b"")
    if not data:
        return 0
    if not dev.open():
        return -2
    conn = dev.conn
    assert conn is not None
    try:
        conn.sock.Send(from_bytes(data))  # type: ignore[arg-type]
    except GplException:
        return -1
    return 1


def socket_send(name: object, value: object, start: object = 0, length: object = 0) -> int:
    """Send ``value``'s bytes (L14149): 1 sent, 0 nothing to send, -1 a socket error, -2 cannot
    connect, -3 no such device."""
    return _send(name, value, start, length, False)


def socket_sendline(name: object, value: object, start: object = 0, length: object = 0) -> int:
    """``socket_send`` and CR LF (L14252)."""
    return _send(name, value, start, length, True)


__all__ = ["Socket", "socket_close", "socket_open", "socket_read", "socket_read_string", "socket_send",
           "socket_sendline"]
