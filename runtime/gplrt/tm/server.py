"""The TCP servers of a simulated TM robot (the Listen node, the Ethernet Slave) on the runtime's
socket layer and scheduler.

Why not ``socketserver``: the robot runs on the shared scheduler of its session
(``gplrt.sim.Simulation``, docs/design/clock.md), as GPL threads and V+ tasks do.  The accept loop
and each connection are threads of that scheduler, their sockets ``gplrt.io.sockets``'
``TcpListener``/``Socket`` (what GPL's own servers, TCS, use): a thread blocked receiving is an
``external_wait``, an open socket paces virtual time to real time while nothing waits for the
controller, and the listen address follows the session's network policy (docs/security.md).
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator

from gplrt.io._codec import from_bytes, to_bytes
from gplrt.io.sockets import IPEndPoint, Socket, TcpListener, listen_address
from gplrt.lang.byref import Box
from gplrt.lang.errors import GplException
from gplrt.sim import Simulation
from gplrt.threads.scheduler import ThreadAbort
from gplrt.tm.packets import Frame, split
from gplrt.tm.motion import start_thread

#: Bytes asked for per receive.
CHUNK = 65536


class Conn:
    """One client connection: ``recv()`` bytes (b"" when closed), ``send(frame)``.

    Frames go out in the order they were queued (``queue``) even when several threads send: a
    send may hand the scheduler's token to another thread while it waits for the socket, so
    each frame is put in an outbox first and one thread at a time empties it (``flush``).  A
    script's reply queued before the tag push that follows it is sent before it."""

    def __init__(self, sock: Socket) -> None:
        self.sock = sock
        self.closed = False
        self._out: list[bytes] = []
        self._lock = threading.Lock()  # (held only to touch the outbox, never across a send)
        self._sending = False

    def recv(self) -> bytes:
        box = Box()
        try:
            n = int(self.sock.Receive(box, CHUNK))  # type: ignore[arg-type]
        except GplException:
            return b""
        return to_bytes(box.value) if n > 0 else b""

    def queue(self, frame: bytes) -> None:
        """Put ``frame`` in the outbox (no I/O: callable under the caller's own locks)."""
        with self._lock:
            self._out.append(frame)

    def flush(self) -> None:
        """Send what the outbox holds, unless another thread is sending it already."""
        with self._lock:
            if self._sending:
                return
            self._sending = True
        try:
            while True:
                with self._lock:
                    if not self._out or self.closed:
                        self._out.clear()
                        return
                    data, self._out = b"".join(self._out), []
                try:
                    self.sock.Send(from_bytes(data))  # type: ignore[arg-type]
                except GplException:
                    self.closed = True
        finally:
            with self._lock:
                self._sending = False

    def send(self, frame: bytes) -> None:
        self.queue(frame)
        self.flush()

    def frames(self) -> Iterator[Frame]:
        """The frames the client sends, as they arrive (``packets.split``), until it closes."""
        buf = bytearray()
        while chunk := self.recv():
            buf += chunk
            yield from split(buf)

    def close(self) -> None:
        self.closed = True
        self.sock.Close()


class Server:
    """A TCP server on ``sim``'s scheduler that runs ``serve_conn(conn)`` on a thread per
    connection; ``port`` is the port bound (0 asks for a free one)."""

    def __init__(self, sim: Simulation, host: str, port: int, serve_conn: Callable[[Conn], None],
                 name: str) -> None:
        self.sim, self.host, self.name = sim, host, name
        self.serve_conn = serve_conn
        self.port = port
        self.conns: list[Conn] = []
        self._listener: TcpListener | None = None
        self._closed = False
        self._error: BaseException | None = None
        self._started = threading.Event()
        start_thread(sim.scheduler, name, self._accept_loop)
        self._started.wait()
        if self._error is not None:
            raise self._error

    def _accept_loop(self) -> None:
        try:
            if self.host not in ("127.0.0.1", "localhost", ""):
                self.sim.network.listen = listen_address(self.host)
            listener = TcpListener(IPEndPoint(self.host, self.port))  # type: ignore[arg-type]
            listener.Start()
            self.port = int(listener.LocalEndPoint().Port)
            self._listener = listener
        except BaseException as exc:  # (-304 port in use, a refused address): the caller's error
            self._error = OSError(f"{self.name}: cannot listen on {self.host}:{self.port}: {exc}")
            return
        finally:
            self._started.set()
        sched = self.sim.scheduler
        while not self._closed:
            try:
                sock = listener.AcceptSocket()
            except (GplException, ThreadAbort):
                return
            sock.NoDelay = True  # type: ignore[assignment]  # a push then a reply: no delayed-ACK wait
            conn = Conn(sock)
            self.conns.append(conn)
            start_thread(sched, f"{self.name}-conn", lambda c=conn: self._serve(c))

    def _serve(self, conn: Conn) -> None:
        try:
            self.serve_conn(conn)
        finally:
            if conn in self.conns:
                self.conns.remove(conn)
            try:
                conn.close()
            except GplException:
                pass

    def close(self) -> None:
        """Stop listening and close the connections (their threads end at their next receive)."""
        self._closed = True
        if self._listener is not None:
            self._listener.Stop()
        for conn in list(self.conns):
            try:
                conn.close()
            except GplException:
                pass
