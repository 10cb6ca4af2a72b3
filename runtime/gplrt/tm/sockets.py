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

The Received Buffer, the reads and the device's end (closed when the block that declared it is
left, L1320, or when the project stops) are ``gplrt.tm.devices``'.  Not simulated: a flow
project's automatic connection (a script opens its devices, L13439).
"""

from __future__ import annotations

from gplrt.io._codec import from_bytes
from gplrt.io.sockets import IPEndPoint, TcpClient
from gplrt.lang.errors import GplException
from gplrt.tm.conversions import GetBytes, write_span
from gplrt.tm.devices import Device, find, take, text
from gplrt.tm.motion import start_thread
from gplrt.tm.server import Conn
from gplrt.tm.values import Array, TMError, to_int, to_string


class Socket(Device):
    """A TCP client device ``name`` to ``ip``:``port``; ``timeout`` ms for reads and writes
    (0-10000, default 10000, L13410)."""

    kind = "socket"

    def __init__(self, name: str, ip: object, port: object, timeout: object = 10000) -> None:
        self.ip, self.port = to_string(ip), to_int(port)
        self.timeout = to_int(timeout)
        if not 0 <= self.timeout <= 10000:
            raise TMError(f"Socket {name}: the timeout {self.timeout} ms is not in 0-10000 (L13410)")
        self.conn: Conn | None = None
        super().__init__(name)

    def open(self) -> bool:
        if self.conn is not None and not self.conn.closed:
            return True
        if not 0 < self.port < 65536 or not self.ip:
            return False
        client = TcpClient()
        try:
            with self.robot.sched.adopted():  # (so that the open connection paces the robot's time)
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
                self.received(data)
        finally:
            conn.closed = True
            self.robot._notify()

    def close(self) -> bool:
        conn, self.conn = self.conn, None
        if conn is not None:
            conn.close()
        self.buffer.clear()
        return True


def _device(name: object) -> Socket | None:
    return find("socket", name)  # type: ignore[no-any-return]


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


def socket_read(name: object, *args: object) -> Array:
    """Bytes from the device's Received Buffer (L13505): ``(dev)``, ``(dev, n [, ms])``,
    ``(dev, prefix, suffix [, option [, ms]])``, ``(dev, suffix [, option [, ms]])``;
    ``byte[0]`` when nothing matches."""
    return Array("byte", take(_known(name, "socket_read"), args, "socket_read"))


def socket_read_string(name: object, *args: object) -> str:
    """As ``socket_read``, as UTF-8 text; a count is of characters (L13857)."""
    return text(take(_known(name, "socket_read_string"), args, "socket_read_string", chars=True))


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
