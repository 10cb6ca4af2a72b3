"""GPL networking on real sockets: IPEndPoint, Socket, TcpClient, TcpListener, UdpClient (D0 §12).

All network I/O goes through :class:`Socket` objects obtained from ``TcpClient.Client``,
``TcpListener.AcceptSocket`` and ``UdpClient.Client``.  Strings are bytes, one per character
(Latin-1), so binary protocols such as the TFTP examples (EX-20/21) work unchanged.

Where servers listen (docs/security.md, "Network"): a GPL program is untrusted, so whatever local
address it binds — blank or ``"0.0.0.0"`` ("any address" on a controller), a port only, or an
explicit address such as its controller's own LAN IP — binds **loopback** (``127.0.0.1``) unless
the user opted in with :attr:`NetworkConfig.listen` (``gpl2py run --listen ADDRESS``,
``Simulation(listen=...)``):

* ``listen = "127.0.0.1"`` (default): every bind goes to loopback, keeping its port;
* ``listen = <an address of this computer>``: binds of blank, ``0.0.0.0`` or any explicit
  non-loopback address go to that one interface;
* ``listen = "0.0.0.0"``: the program's own choice stands — blank and ``0.0.0.0`` bind every
  interface, an explicit address binds that address, or every interface when this computer does not
  have it (a program written for a controller whose IP this PC lacks).

A loopback address the program asks for (``127.x.x.x``) is always bound as asked.  A UDP socket that
sends before it was bound is bound first, as the kernel would otherwise bind it to every interface:
to loopback when it sends to loopback, else to the one address that reaches the peer.  The
program's own ``IPEndPoint`` objects keep the address it wrote (a listener binds a copy), so GPL
code that reads them back sees what it asked for; ``TcpListener.LocalEndPoint`` ([P]) tells where
the socket really is, which is what a client must connect to.

Every wait (connect, accept, receive, send) goes through :func:`gplrt.io._blocking.blocking_call`;
accept, receive and send wait in short slices (:func:`gplrt.io._blocking.wait_ready`), so a thread
blocked in them ends on ``Thread.Abort``, and a ``Close``/``Stop`` from another thread wakes it
with -1707 *Socket not open* (Python cannot wake a blocked ``accept``/``select`` by closing the
descriptor).

Error codes (gpl-dictionary.md §14; the mapping is ours, the manual gives none):

* receive/accept/connect/send timeout -> -1705 *Network timeout*
* connection refused -> -1702 *Connection refused*; address not parseable -> -1704
* using a closed or never-connected socket -> -1707 *Socket not open*
* peer reset the connection, or sending after the peer closed it -> -1708 *Connection closed*;
  an orderly close by the peer makes ``Receive`` return 0 (EX-18 loops until it does)
* port already bound by someone else -> -304 *Device already in use* (no network-specific code
  exists in the controller's table; the port is the "device" that is in use)
* ``Receive`` on a non-blocking socket with no data -> -523 *No data available* (returning 0 would
  read as "connection closed")
* a connected socket connected again -> -1706 *Already connected*

A Socket or TcpListener whose object is freed without ``Close``/``Stop`` closes its connection then,
as on a controller (otherwise virtual time would stay paced to real time for the rest of the run).

Where a program listens (:class:`Listening`): a server -- a started ``TcpListener``, a ``UdpClient``
bound to a local endpoint -- is announced to :attr:`NetworkConfig.on_listen` as soon as a client may
reach it (``gpl2py run`` prints ``note: listening on 127.0.0.1:10100 (thread TcpCom1)``), and
:meth:`NetworkConfig.listening` tells which servers are open now (``Cell.serve``).  Why announce
rather than let a user probe the port: TCS serves one client per port and stops listening while it
has one, so a probing connection costs the real client its turn.
"""

from __future__ import annotations

import array
import errno
import fcntl
import os
import re
import select
import socket as _socket
import termios
import threading
import time
import weakref
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from gplrt.io import _blocking
from gplrt.io._blocking import blocking_call, wait_ready
from gplrt.io._codec import as_text, from_bytes, to_bytes
from gplrt.lang.errors import (
    ALREADY_CONNECTED,
    CONNECTION_CLOSED,
    CONNECTION_REFUSED,
    INVALID_ADDRESS,
    NETWORK_TIMEOUT,
    NO_CONNECTION,
    NO_DATA,
    OBJECT_NOT_INSTANTIATED,
    PORT_IN_USE,
    SOCKET_NOT_OPEN,
    VALUE_OUT_OF_RANGE,
    GplException,
    host_reason,
)
from gplrt.lang.conversions import to_int32
from gplrt.lang.gpltypes import Boolean, Integer, Ref, String
from gplrt.session import current_session
from gplrt.thread_binding import current_ctx


LOOPBACK = "127.0.0.1"
ANY = "0.0.0.0"


@dataclass(frozen=True)
class Listening:
    """A server of the program: where a client reaches it, and the GPL thread that opened it."""

    address: str  # the address really bound (module docstring), e.g. "127.0.0.1"
    port: int  # the port really bound (a program that asked for port 0 gets one chosen for it)
    protocol: str  # "TCP" (a TcpListener) or "UDP" (a UdpClient bound to a local endpoint)
    thread: str  # the GPL thread's name; "" when Python code outside any GPL thread opened it

    def __str__(self) -> str:
        """``127.0.0.1:10100`` for TCP, ``127.0.0.1:69/udp`` for UDP."""
        where = f"{self.address}:{self.port}"
        return where if self.protocol == "TCP" else f"{where}/{self.protocol.lower()}"


@dataclass
class NetworkConfig:
    """One session's network (``Session.network``): where its servers may listen (module
    docstring), how long a connect waits, and the servers its program has opened."""

    listen: str = LOOPBACK  # the user's opt-in: an address of this computer, or ANY
    connect_timeout: float | None = 30.0  # seconds; a real controller's TCP gives up eventually
    #: Every server the session's program opened, TcpListener or bound UdpClient (``listening``).
    servers: weakref.WeakSet[TcpListener | UdpClient] = field(default_factory=weakref.WeakSet, repr=False,
                                                              compare=False)
    #: Called with a :class:`Listening` each time a server starts listening (a TcpListener started
    #: again after a Stop is announced again), on the GPL thread that opened it, once a client may
    #: connect.  ``gpl2py run`` prints it.
    on_listen: list[Callable[[Listening], None]] = field(default_factory=list, repr=False, compare=False)

    def opened(self, server: TcpListener | UdpClient, where: Listening) -> None:
        """A server of the program now listens at ``where``: keep it, and announce it."""
        self.servers.add(server)
        for hook in list(self.on_listen):
            hook(where)

    def listening(self) -> list[Listening]:
        """Where the session's program listens now (a TcpListener from ``Start`` until ``Stop``, a
        bound UdpClient until ``Close``), ordered by port."""
        found = [where for server in list(self.servers) if (where := server._open_at()) is not None]
        return sorted(found, key=lambda w: (w.port, w.protocol))

    def listening_ports(self) -> set[int]:
        """The TCP ports the session's program listens on now (:meth:`listening`).

        For a Python client that must not connect before its server listens (``Cell.serve``): a
        probing connection would be a client of its own — TCS serves one connection per port and
        stops listening while it has it.
        """
        return {where.port for where in self.listening() if where.protocol == "TCP"}


def _announce(server: TcpListener | UdpClient, sock: _socket.socket, protocol: str) -> Listening:
    """Tell the session that ``server`` listens on ``sock`` now (:meth:`NetworkConfig.opened`)."""
    address, port = sock.getsockname()[:2]
    ctx = current_ctx()
    where = Listening(str(address), int(port), protocol, ctx.name if ctx is not None else "")
    current_session().network.opened(server, where)
    return where


def configure_network(listen: str | None = None, connect_timeout: float | None = -1.0) -> NetworkConfig:
    """Change the current session's network switches; ``listen`` is checked by
    :func:`listen_address` (``Simulation(listen=...)`` sets it when the session is made)."""
    config = current_session().network
    if listen is not None:
        config.listen = listen_address(listen)
    if connect_timeout is None or connect_timeout >= 0:
        config.connect_timeout = connect_timeout
    return config


def network_config() -> NetworkConfig:
    """The current session's network switches."""
    return current_session().network


def listen_address(text: str) -> str:
    """``text`` as an address servers may listen on: ``0.0.0.0``, loopback, or an IPv4 address
    this computer has (checked by binding a throwaway socket).  ValueError says what is wrong."""
    try:
        address = dotted_quad(str(text))
    except GplException:
        raise ValueError(f"{text!r} is not an IPv4 address (n.n.n.n)") from None
    if not address:
        raise ValueError("the listen address is empty: give 127.0.0.1, 0.0.0.0 or an address of this computer")
    probe = _socket.socket(_socket.AF_INET, _socket.SOCK_DGRAM)
    try:
        probe.bind((address, 0))
    except OSError as exc:
        raise ValueError(f"{address} is not an address of this computer ({exc.strerror})") from None
    finally:
        probe.close()
    return address


def _is_loopback(address: str) -> bool:
    return address.startswith("127.")


def _bind_address(requested: str) -> str:
    """Where a bind the program asked for at ``requested`` ("" = any) really goes (module doc)."""
    if _is_loopback(requested):
        return requested
    listen = current_session().network.listen
    if listen == ANY:
        return requested or ANY
    return listen


def _os_error(exc: OSError, what: str) -> GplException:
    """Translate a socket OSError into the controller's code."""
    if isinstance(exc, TimeoutError | _socket.timeout):
        return GplException(NETWORK_TIMEOUT, detail=f"{what}: timed out")
    code = exc.errno
    if code == errno.EADDRINUSE:
        return GplException(PORT_IN_USE, detail=f"{what}: address already in use")
    if code == errno.ECONNREFUSED:
        return GplException(CONNECTION_REFUSED, detail=what)
    if code in (errno.ECONNRESET, errno.EPIPE, errno.ECONNABORTED, errno.ESHUTDOWN):
        return GplException(CONNECTION_CLOSED, detail=f"{what}: {host_reason(exc)}")
    if code == errno.EISCONN:
        return GplException(ALREADY_CONNECTED, detail=what)
    if code in (errno.ENOTCONN, errno.EBADF):
        return GplException(SOCKET_NOT_OPEN, detail=what)
    if code in (errno.EADDRNOTAVAIL, errno.EINVAL, errno.EAFNOSUPPORT):
        return GplException(INVALID_ADDRESS, detail=f"{what}: {host_reason(exc)}")
    return GplException(NO_CONNECTION, detail=f"{what}: {host_reason(exc)}")  # unreachable, and the rest


_DOTTED_QUAD = re.compile(r"(\d{1,3})\.(\d{1,3})\.(\d{1,3})\.(\d{1,3})", re.ASCII)


def dotted_quad(text: str) -> str:
    """``text`` as a canonical dotted-quad IPv4 address ("" for blank), else -1704.

    Exactly four decimal parts of one to three ASCII digits, each 0..255; blanks around the
    address are ignored (as they always were).  Not ``inet_aton``, which also takes the historic
    short forms ("1.2.3" is 1.2.0.3), hex and octal parts and anything after a space: a program
    that wrote those meant something else, and a controller rejects them.  Leading zeros are
    decimal and dropped ("192.168.000.010" is stored as "192.168.0.10"), so the address the
    socket reaches is the one the program wrote, not inet_aton's octal reading of it.
    """
    text = text.strip()
    if not text:
        return ""
    match = _DOTTED_QUAD.fullmatch(text)
    parts = [int(p) for p in match.groups()] if match else []
    if not parts or max(parts) > 255:
        raise GplException(INVALID_ADDRESS, detail=f"{text!r} is not a dotted IPv4 address (n.n.n.n, each 0-255)")
    return ".".join(map(str, parts))


class IPEndPoint:
    """``New IPEndPoint(ip [, port])``: an IP address (dotted quad text) and a port.

    ``""`` means "any address"; an omitted port is 0 (for a UDP/TCP local endpoint: any port; for
    Modbus: the standard port 502).

    Decision (the manual is silent on the accepted text; every example is a dotted quad, and no
    GPL member resolves names): only a dotted-quad IPv4 address is accepted (``dotted_quad``);
    host names ("localhost") and IPv6 were already -1704 *Invalid network address* and stay so.
    """

    def __init__(self, ip: String = String(""), port: Integer = Integer(0)) -> None:
        self._ip = ""
        self._port = 0
        self.IPAddress = ip
        self.Port = port

    @property
    def IPAddress(self) -> String:
        return String(self._ip)

    @IPAddress.setter
    def IPAddress(self, value: String) -> None:
        self._ip = dotted_quad(str(value))

    @property
    def Port(self) -> Integer:
        return Integer(self._port)

    @Port.setter
    def Port(self, value: Integer) -> None:
        port = to_int32(value)  # GPL's Integer conversion: CInt rounding, -717/-710, not int()
        if not 0 <= port <= 65535:
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"port {port}")
        self._port = port

    def Clone(self) -> IPEndPoint:
        """[P] An independent copy ("many classes" have Clone, D0:596-637)."""
        return IPEndPoint(String(self._ip), Integer(self._port))

    def _remote(self) -> tuple[str, int]:
        """Address to reach: a blank IP means this machine."""
        return (self._ip or "127.0.0.1", self._port)

    def __repr__(self) -> str:
        return f"IPEndPoint({self._ip!r}, {self._port})"


def _endpoint(address: Any) -> IPEndPoint:
    return IPEndPoint(String(address[0]), Integer(address[1]))


def _seconds(ms: int) -> float | None:
    """GPL timeouts are milliseconds; 0 (or less) means wait forever, as in .NET."""
    return ms / 1000.0 if ms > 0 else None


class Socket:
    """A TCP connection or UDP endpoint.  Not useful to create with ``New`` (D0:3057-3061):
    obtain one from ``TcpClient.Client``, ``TcpListener.AcceptSocket`` or ``UdpClient.Client``."""

    def __init__(self, *, _sock: _socket.socket | None = None, _kind: int = _socket.SOCK_STREAM) -> None:
        # Keyword-only, underscored: Python-side plumbing, not GPL constructor arguments.
        sock, kind = _sock, _kind
        self._sock = sock if sock is not None else _socket.socket(_socket.AF_INET, kind)
        self._kind = self._sock.type
        self._closed = False
        self._peer_closed = False
        self._connected = sock is not None and kind == _socket.SOCK_STREAM and _peer(sock) is not None
        self._blocking = True
        self._recv_ms = 0
        self._send_ms = 0
        self._bound_for_sending = False  # UDP: SendTo has made sure the socket is bound
        self._lock = threading.RLock()
        self._release = _blocking.opened()  # paces virtual time while the socket is open
        self._freed = weakref.finalize(self, _free_later, self._sock, self._release)
        self._sock.settimeout(None)

    # -- state ---------------------------------------------------------------------------------

    def _open(self) -> _socket.socket:
        if self._closed:
            raise GplException(SOCKET_NOT_OPEN, detail="the socket is closed")
        return self._sock

    def _check_open(self) -> None:
        """Between wait slices: the socket was closed by another thread meanwhile."""
        if self._closed:
            raise GplException(SOCKET_NOT_OPEN, detail="the socket was closed while waiting")

    def _connected_tcp(self) -> _socket.socket:
        sock = self._open()
        if self._kind == _socket.SOCK_STREAM and not self._connected:
            raise GplException(SOCKET_NOT_OPEN, detail="the TCP socket is not connected")
        return sock

    @property
    def Available(self) -> Integer:
        """Bytes that can be received now without waiting."""
        sock = self._open()
        count = array.array("i", [0])
        fcntl.ioctl(sock.fileno(), termios.FIONREAD, count)
        return Integer(count[0])

    @property
    def Blocking(self) -> Boolean:
        return Boolean(self._blocking)

    @Blocking.setter
    def Blocking(self, value: Boolean) -> None:
        self._blocking = bool(value)

    @property
    def Connected(self) -> Boolean:
        """[P] True while a TCP connection is open and the peer has not closed it (.NET name)."""
        return Boolean(self._connected and not self._closed and not self._peer_closed)

    @property
    def KeepAlive(self) -> Boolean:
        return Boolean(bool(self._open().getsockopt(_socket.SOL_SOCKET, _socket.SO_KEEPALIVE)))

    @KeepAlive.setter
    def KeepAlive(self, value: Boolean) -> None:
        self._open().setsockopt(_socket.SOL_SOCKET, _socket.SO_KEEPALIVE, 1 if value else 0)

    @property
    def NoDelay(self) -> Boolean:
        """[P] TCP_NODELAY (Nagle off); not in the seed manuals, offered as .NET has it."""
        return Boolean(bool(self._open().getsockopt(_socket.IPPROTO_TCP, _socket.TCP_NODELAY)))

    @NoDelay.setter
    def NoDelay(self, value: Boolean) -> None:
        self._open().setsockopt(_socket.IPPROTO_TCP, _socket.TCP_NODELAY, 1 if value else 0)

    @property
    def ReceiveTimeout(self) -> Integer:
        """Milliseconds ``Receive``/``ReceiveFrom`` wait before -1705; 0 = forever."""
        return Integer(self._recv_ms)

    @ReceiveTimeout.setter
    def ReceiveTimeout(self, value: Integer) -> None:
        self._recv_ms = max(0, to_int32(value))

    @property
    def SendTimeout(self) -> Integer:
        """Milliseconds ``Send``/``SendTo`` wait for buffer space before -1705; 0 = forever."""
        return Integer(self._send_ms)

    @SendTimeout.setter
    def SendTimeout(self, value: Integer) -> None:
        self._send_ms = max(0, to_int32(value))

    @property
    def RemoteEndPoint(self) -> IPEndPoint | None:
        """The peer of a connected socket (``Nothing`` if not connected)."""
        address = _peer(self._open())
        return _endpoint(address) if address is not None else None

    # -- operations ----------------------------------------------------------------------------

    def Close(self) -> None:
        """Close the connection (a second Close does nothing)."""
        with self._lock:
            if not self._closed:
                self._closed = True
                self._connected = False
                self._freed.detach()
                self._sock.close()
                self._release()

    def Connect(self, remote_endpoint: IPEndPoint) -> None:
        """Connect to a TCP server (for UDP: fix the default peer of Send/Receive)."""
        sock = self._open()
        if self._connected and self._kind == _socket.SOCK_STREAM:
            raise GplException(ALREADY_CONNECTED, detail=repr(remote_endpoint))
        if remote_endpoint is None:
            raise GplException(OBJECT_NOT_INSTANTIATED, detail="Connect needs an IPEndPoint")
        address = remote_endpoint._remote()
        timeout = current_session().network.connect_timeout

        def connect() -> None:
            # Non-blocking connect, then wait in slices for the outcome, so Thread.Abort and Close
            # reach a thread whose peer never answers the SYN (up to connect_timeout otherwise).
            sock.setblocking(False)
            try:
                err = sock.connect_ex(address)
                if err in (errno.EINPROGRESS, errno.EALREADY, errno.EWOULDBLOCK):
                    if not wait_ready(lambda step: _ready(sock, step, write=True), timeout, self._check_open):
                        raise TimeoutError(errno.ETIMEDOUT, "connect timed out")
                    self._check_open()
                    err = sock.getsockopt(_socket.SOL_SOCKET, _socket.SO_ERROR)
                if err:
                    raise OSError(err, os.strerror(err))
            finally:
                if not self._closed:
                    sock.setblocking(True)

        try:
            blocking_call(connect, timeout)
        except OSError as exc:
            raise _os_error(exc, f"connect to {address[0]}:{address[1]}") from None
        self._connected = True

    def Receive(self, input_buffer: Ref[String], max_length: Integer = Integer(1500)) -> Integer:
        """Receive up to ``max_length`` bytes into ``input_buffer``; returns the count.

        0 means the peer closed the connection (EX-18).  Waits up to ``ReceiveTimeout`` ms.
        """
        sock = self._connected_tcp() if self._kind == _socket.SOCK_STREAM else self._open()
        data, _ = self._receive(sock, to_int32(max_length), from_=False)
        if not data and self._kind == _socket.SOCK_STREAM:
            self._peer_closed = True
        input_buffer.set(String(from_bytes(data)))
        return Integer(len(data))

    def ReceiveFrom(
        self, input_buffer: Ref[String], max_length: Integer, remote_endpoint: Ref[IPEndPoint]
    ) -> Integer:
        """Receive one datagram; the sender is stored in ``remote_endpoint`` (allocated if Nothing)."""
        sock = self._open()
        data, address = self._receive(sock, to_int32(max_length), from_=True)
        input_buffer.set(String(from_bytes(data)))
        current = remote_endpoint.get()
        if isinstance(current, IPEndPoint) and address is not None:
            current.IPAddress, current.Port = address[0], address[1]
        elif address is not None:
            remote_endpoint.set(_endpoint(address))
        return Integer(len(data))

    def _receive(self, sock: _socket.socket, size: int, *, from_: bool) -> tuple[bytes, Any]:
        if size <= 0:  # Receive and ReceiveFrom alike: Python's recv would raise ValueError
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"max_length {size}")
        timeout = _seconds(self._recv_ms) if self._blocking else 0.0

        deadline = None if timeout is None else time.monotonic() + timeout

        def wait_and_receive() -> tuple[bytes, Any]:
            while True:
                left = None if deadline is None else max(0.0, deadline - time.monotonic())
                if not wait_ready(lambda step: _ready(sock, step), left, self._check_open):
                    if not self._blocking:
                        raise GplException(NO_DATA, detail="non-blocking socket has no data")
                    raise GplException(NETWORK_TIMEOUT, detail=f"no data within {self._recv_ms} ms")
                self._check_open()
                try:  # another reader may have taken the data since select said it was there
                    if from_:
                        return sock.recvfrom(size, _socket.MSG_DONTWAIT)
                    return sock.recv(size, _socket.MSG_DONTWAIT), None
                except BlockingIOError:
                    continue

        try:
            return blocking_call(wait_and_receive, timeout)
        except OSError as exc:
            raise _os_error(exc, "receive") from None

    def Send(self, output_buffer: String, max_length: Integer = Integer(-1)) -> Integer:
        """Send a String (its first ``max_length`` bytes if given); returns the bytes sent."""
        sock = self._connected_tcp() if self._kind == _socket.SOCK_STREAM else self._open()
        if self._peer_closed:
            raise GplException(CONNECTION_CLOSED, detail="the peer closed the connection")
        data = to_bytes(as_text(output_buffer))
        limit = to_int32(max_length)
        if limit >= 0:
            data = data[:limit]
        self._send(sock, data, None, "send")
        return Integer(len(data))

    def SendTo(self, output_buffer: String, max_length: Integer, remote_endpoint: IPEndPoint) -> Integer:
        """Send one datagram to ``remote_endpoint``; ``max_length`` > 0 truncates (0 = all, EX-20)."""
        sock = self._open()
        if remote_endpoint is None:
            raise GplException(OBJECT_NOT_INSTANTIATED, detail="SendTo needs an IPEndPoint")
        data = to_bytes(as_text(output_buffer))
        limit = to_int32(max_length)
        if limit > 0:
            data = data[:limit]
        address = remote_endpoint._remote()
        what = f"send to {address[0]}:{address[1]}"
        if not self._bound_for_sending and self._kind == _socket.SOCK_DGRAM:
            try:
                _bind_for_sending(sock, address)
            except OSError as exc:
                raise _os_error(exc, what) from None
            self._bound_for_sending = True
        self._send(sock, data, address, what)
        return Integer(len(data))

    def _send(self, sock: _socket.socket, data: bytes, address: Any, what: str) -> None:
        """Send all of ``data`` (one datagram to ``address`` for UDP) within ``SendTimeout``."""
        timeout = _seconds(self._send_ms)
        deadline = None if timeout is None else time.monotonic() + timeout

        def send() -> None:
            view = memoryview(data)
            while True:
                left = None if deadline is None else max(0.0, deadline - time.monotonic())
                if not wait_ready(lambda step: _ready(sock, step, write=True), left, self._check_open):
                    raise GplException(NETWORK_TIMEOUT, detail=f"{what}: buffer full for {self._send_ms} ms")
                self._check_open()
                try:
                    if address is not None:
                        sock.sendto(view, _socket.MSG_DONTWAIT, address)
                        return
                    view = view[sock.send(view, _socket.MSG_DONTWAIT):]
                except BlockingIOError:
                    continue
                if not view:
                    return

        try:
            blocking_call(send, timeout)
        except OSError as exc:
            raise _os_error(exc, what) from None

    def __repr__(self) -> str:
        state = "closed" if self._closed else ("connected" if self._connected else "open")
        return f"<Socket {state}>"


def _free_later(sock: _socket.socket, release: _blocking.Release) -> None:
    """A Socket or TcpListener freed without Close/Stop (its object went out of scope, as GPL code
    often lets it): close the connection and end its real-time hold, as a controller frees the
    socket with its last reference.  Runs inside garbage collection, possibly on a thread that
    holds other runtime locks, so the release (which takes the scheduler lock) runs on a helper
    thread instead of here."""
    sock.close()
    try:
        threading.Thread(target=release, name="gplrt socket release", daemon=True).start()
    except RuntimeError:  # interpreter shutdown: nobody left to pace
        pass


def _ready(sock: _socket.socket, step: float, write: bool = False) -> bool:
    """Whether ``sock`` can be read (written) now, waiting up to ``step`` seconds.

    A socket closed by another thread counts as ready: the caller's check then reports -1707.
    """
    try:
        fd = sock.fileno()
        if fd < 0:
            return True
        readable, writable, _ = select.select([] if write else [fd], [fd] if write else [], [], step)
    except (OSError, ValueError):
        return True
    return bool(readable or writable)


def _bind(sock: _socket.socket, endpoint: IPEndPoint, verb: str) -> tuple[str, int]:
    """Bind ``sock`` where ``endpoint`` may go (module docstring); returns the address bound.

    A refusal is the controller's error naming the address this computer refused (``verb`` says
    for what): -304 *Device already in use* ``- listen on 0.0.0.0:10100: address already in use``.
    That is the address tried last, not the one the program wrote, which may be a controller's IP
    this computer does not have."""
    address = (_bind_address(endpoint._ip), endpoint._port)
    try:
        try:
            sock.bind(address)
        except OSError as exc:
            fallback = LOOPBACK if _is_loopback(address[0]) else current_session().network.listen
            if exc.errno != errno.EADDRNOTAVAIL or address[0] == fallback:
                raise
            address = (fallback, address[1])  # the controller's own IP, which this PC does not have
            sock.bind(address)
    except OSError as exc:
        raise _os_error(exc, f"{verb} {address[0]}:{address[1]}") from None
    return address


def _bind_for_sending(sock: _socket.socket, destination: tuple[str, int]) -> None:
    """Bind an unbound UDP socket before it sends to ``destination`` (module docstring): the
    kernel's own choice would be every interface, open to datagrams from the whole network."""
    if sock.getsockname()[1] != 0:
        return  # bound by UdpClient(endpoint), or by Connect (which binds the routed address)
    if _is_loopback(destination[0]):
        sock.bind((LOOPBACK, 0))
        return
    listen = current_session().network.listen
    if listen not in (LOOPBACK, ANY):
        sock.bind((listen, 0))  # the one interface the user opened
        return
    route = _socket.socket(_socket.AF_INET, _socket.SOCK_DGRAM)
    try:
        route.connect(destination)  # no packet: asks the routing table which address reaches it
        sock.bind((route.getsockname()[0], 0))
    finally:
        route.close()


def _peer(sock: _socket.socket) -> Any:
    try:
        return sock.getpeername()
    except OSError:
        return None


class TcpClient:
    """``New TcpClient([ep])``: a TCP client, connected immediately when ``ep`` is given."""

    def __init__(self, remote_endpoint: IPEndPoint | None = None) -> None:
        self._socket = Socket(_kind=_socket.SOCK_STREAM)
        if remote_endpoint is not None:
            self._socket.Connect(remote_endpoint)

    def Client(self) -> Socket:
        """The embedded Socket used for I/O."""
        return self._socket

    def Connect(self, remote_endpoint: IPEndPoint) -> None:
        """[P] Same as ``Client.Connect`` (.NET has it; not in the seed manuals)."""
        self._socket.Connect(remote_endpoint)

    def Close(self) -> None:
        self._socket.Close()


class TcpListener:
    """``New TcpListener(ep)``: a TCP server for the local endpoint ``ep`` (blank IP = any)."""

    BACKLOG = 8

    def __init__(self, local_endpoint: IPEndPoint) -> None:
        if local_endpoint is None:
            raise GplException(OBJECT_NOT_INSTANTIATED, detail="TcpListener needs an IPEndPoint")
        self._endpoint = local_endpoint.Clone()
        self._sock: _socket.socket | None = None
        self._where: Listening | None = None
        self._stop_lock = threading.Lock()

    def Start(self) -> None:
        """Bind and listen; a port already bound elsewhere raises -304."""
        if self._sock is not None:
            return
        sock = _socket.socket(_socket.AF_INET, _socket.SOCK_STREAM)
        # Like a controller (and .NET), allow re-binding a port whose old connections linger in
        # TIME_WAIT; a port actively bound by another socket is still refused.
        sock.setsockopt(_socket.SOL_SOCKET, _socket.SO_REUSEADDR, 1)
        try:
            address = _bind(sock, self._endpoint, "listen on")
            sock.listen(self.BACKLOG)
            sock.setblocking(False)  # AcceptSocket waits in select slices, never inside accept()
        except OSError as exc:
            sock.close()
            raise _os_error(exc, f"listen on {address[0]}:{address[1]}") from None
        except GplException:
            sock.close()
            raise
        self._sock = sock
        self._release = _blocking.opened()  # paces virtual time while listening
        self._freed = weakref.finalize(self, _free_later, sock, self._release)
        self._where = _announce(self, sock, "TCP")

    def _open_at(self) -> Listening | None:
        """Where it listens now (``NetworkConfig.listening``), None when stopped."""
        return self._where if self._sock is not None else None

    def _listening(self) -> _socket.socket:
        if self._sock is None:
            raise GplException(SOCKET_NOT_OPEN, detail="TcpListener not started")
        return self._sock

    def Pending(self) -> Boolean:
        """True if a connection request waits, so ``AcceptSocket`` will not block."""
        sock = self._listening()
        ready = _ready(sock, 0.0)
        self._listening()  # stopped by another thread meanwhile: -1707, not a Python error
        return Boolean(ready)

    def AcceptSocket(self) -> Socket:
        """Wait for a connection and return a new Socket for it."""
        sock = self._listening()

        def check() -> None:
            if self._sock is not sock:
                raise GplException(SOCKET_NOT_OPEN, detail="the TcpListener was stopped while waiting")

        def accept() -> _socket.socket:
            while True:
                wait_ready(lambda step: _ready(sock, step), None, check)
                check()
                try:  # another thread may have accepted the connection since select saw it
                    conn, _ = sock.accept()
                    return conn
                except BlockingIOError:
                    continue

        try:
            conn = blocking_call(accept, None)
        except OSError as exc:
            raise _os_error(exc, "accept") from None
        conn.setblocking(True)
        return Socket(_sock=conn, _kind=_socket.SOCK_STREAM)

    def LocalEndPoint(self) -> IPEndPoint:
        """[P] The bound endpoint (.NET ``LocalEndpoint``; tells the port chosen for port 0)."""
        return _endpoint(self._listening().getsockname())

    def Stop(self) -> None:
        """Stop listening and close the listener socket (accepted Sockets stay open)."""
        with self._stop_lock:  # two threads stopping at once release the real-time hold once
            sock, self._sock = self._sock, None
        if sock is not None:
            self._freed.detach()
            sock.close()
            self._release()

    def Close(self) -> None:
        self.Stop()


def listening_ports() -> set[int]:
    """The TCP ports the current session's program listens on now
    (:meth:`NetworkConfig.listening_ports`)."""
    return current_session().network.listening_ports()


class UdpClient:
    """``New UdpClient([local_ep])``: a UDP endpoint, bound to ``local_ep`` if given (port 0 = any)."""

    def __init__(self, local_endpoint: IPEndPoint | None = None) -> None:
        self._socket = Socket(_kind=_socket.SOCK_DGRAM)
        self._where: Listening | None = None
        if local_endpoint is not None:
            try:
                _bind(self._socket._sock, local_endpoint, "bind")
            except GplException:
                self._socket.Close()
                raise
            self._where = _announce(self, self._socket._sock, "UDP")

    def _open_at(self) -> Listening | None:
        """Where it receives now (``NetworkConfig.listening``): bound to a local endpoint, not closed."""
        return self._where if not self._socket._closed else None

    def Client(self) -> Socket:
        """The embedded Socket used for I/O."""
        return self._socket

    def Close(self) -> None:
        self._socket.Close()


__all__ = [
    "IPEndPoint", "Socket", "TcpClient", "TcpListener", "UdpClient", "Listening", "NetworkConfig",
    "configure_network", "listen_address", "listening_ports",
]
