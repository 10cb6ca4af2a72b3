"""A GPL thread blocked on the outside world can still be stopped.

On a controller ``Thread.Abort`` ends a thread wherever it is, and a server that stops its
listener or closes a connection wakes the thread blocked on it.  Python cannot kill a thread or
wake a blocked ``accept``/``select`` by closing the socket, so these waits poll in short slices;
without that, each of these tests hangs until its bound and fails.
"""

from __future__ import annotations

import gc
import socket
import threading
import time

import pytest

from gplrt.io.modbus import Modbus
from gplrt.io.serial import LoopbackPort
from gplrt.io.sockets import IPEndPoint, Socket, TcpClient, TcpListener, UdpClient
from gplrt.lang.byref import Box
from gplrt.lang.errors import SOCKET_NOT_OPEN, GplException
from gplrt.sim import Simulation
from gplrt.threads import Thread

BOUND = 5.0  # real seconds any of these runs may take at most


def _abort_while_blocked(clock: str, blocked: object) -> Simulation:
    """Start ``blocked`` in a GPL thread, abort it 200 ms later; check that the Abort ended it.

    ``Thread.Abort`` waits one controller second for its target to unwind (paced to real time
    while the target waits on the outside world), so "joined True" and ThreadState 0 right after
    it prove the blocked call noticed the Abort within that second, without a wall-time
    assertion; ``run_main``'s bound only keeps a hang from stalling the suite.
    """
    sim = Simulation(clock=clock, capture=True)
    events: list[str] = []
    state: dict[str, int] = {}

    def worker() -> None:
        try:
            blocked()  # type: ignore[operator]
            events.append("returned")
        except GplException as exc:
            events.append(f"caught {exc.ErrorCode}")
        finally:
            events.append("finally")

    def main() -> None:
        t = Thread(worker, 0, "worker")
        t.Start()
        Thread.Sleep(200)
        t.Abort()
        state["after"] = t.ThreadState
        events.append(f"joined {t.Join(0)}")

    assert sim.run_main(main, timeout=BOUND) == []
    events.append(f"state {state['after']}")
    assert events == ["finally", "joined True", "state 0"]  # Catch does not see an Abort
    return sim


@pytest.mark.parametrize("clock", ["virtual", "real"])
def test_abort_a_thread_blocked_in_accept_socket(clock: str) -> None:
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    try:
        sim = _abort_while_blocked(clock, listener.AcceptSocket)
    finally:
        listener.Stop()
    assert sim.controller.error_log == []


@pytest.mark.parametrize("clock", ["virtual", "real"])
def test_abort_a_thread_blocked_in_receive(clock: str) -> None:
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    client = TcpClient(IPEndPoint("127.0.0.1", listener.LocalEndPoint().Port))
    server_side = listener.AcceptSocket()
    try:
        _abort_while_blocked(clock, lambda: server_side.Receive(Box(""), 100))
    finally:
        client.Close()
        server_side.Close()
        listener.Stop()


def test_abort_a_thread_blocked_on_a_silent_modbus_slave() -> None:
    silent = socket.socket()
    silent.bind(("127.0.0.1", 0))
    silent.listen(1)  # accepts the connection (in the backlog) but never answers
    mb = Modbus(IPEndPoint("127.0.0.1", silent.getsockname()[1]))  # Timeout 0: wait forever
    try:
        _abort_while_blocked("virtual", lambda: mb.ReadHoldingRegisters(0, 1, Box(None)))
    finally:
        mb.Close()
        silent.close()


def test_abort_a_thread_blocked_reading_a_serial_port() -> None:
    port = LoopbackPort()
    _abort_while_blocked("virtual", port.read)


def _wait_in_thread(fn: object) -> tuple[threading.Thread, list[object]]:
    result: list[object] = []

    def run() -> None:
        try:
            result.append(fn())  # type: ignore[operator]
        except GplException as exc:
            result.append(exc.ErrorCode)

    t = threading.Thread(target=run, daemon=True)
    t.start()
    time.sleep(0.2)
    return t, result


def test_stopping_the_listener_ends_a_pending_accept_socket_with_1707() -> None:
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    t, result = _wait_in_thread(listener.AcceptSocket)
    assert result == []  # really blocked
    listener.Stop()
    t.join(BOUND)
    assert result == [SOCKET_NOT_OPEN]


def test_closing_a_socket_ends_a_pending_receive_with_1707() -> None:
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    client = TcpClient(IPEndPoint("127.0.0.1", listener.LocalEndPoint().Port))
    server_side = listener.AcceptSocket()
    listener.Stop()
    try:
        t, result = _wait_in_thread(lambda: server_side.Receive(Box(""), 100))
        assert result == []
        server_side.Close()
        t.join(BOUND)
        assert result == [SOCKET_NOT_OPEN]
    finally:
        client.Close()


def test_closing_a_udp_socket_ends_a_pending_receive_from_with_1707() -> None:
    udp = UdpClient(IPEndPoint("127.0.0.1", 0))
    sock: Socket = udp.Client()
    t, result = _wait_in_thread(lambda: sock.ReceiveFrom(Box(""), 100, Box(None)))
    assert result == []
    udp.Close()
    t.join(BOUND)
    assert result == [SOCKET_NOT_OPEN]


def test_a_second_acceptor_does_not_hang_when_the_first_takes_the_connection() -> None:
    """Two threads accept on one listener; one client: one gets it, the other keeps waiting and
    can still be woken by Stop (a select-then-blocking-accept would hang in accept)."""
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    t1, r1 = _wait_in_thread(listener.AcceptSocket)
    t2, r2 = _wait_in_thread(listener.AcceptSocket)
    client = socket.create_connection(("127.0.0.1", listener.LocalEndPoint().Port), timeout=BOUND)
    deadline = time.monotonic() + BOUND
    while not (r1 or r2) and time.monotonic() < deadline:
        time.sleep(0.01)
    listener.Stop()
    t1.join(BOUND)
    t2.join(BOUND)
    client.close()
    results = r1 + r2
    assert len(results) == 2 and SOCKET_NOT_OPEN in results
    accepted = [r for r in results if isinstance(r, Socket)]
    assert len(accepted) == 1
    accepted[0].Close()


def test_send_to_a_peer_that_never_reads_is_abortable() -> None:
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    peer = socket.create_connection(("127.0.0.1", listener.LocalEndPoint().Port), timeout=BOUND)
    server_side = listener.AcceptSocket()
    listener.Stop()
    big = "x" * (64 * 1024)

    def flood() -> None:
        while True:  # fills both socket buffers, then blocks in Send
            server_side.Send(big)

    try:
        _abort_while_blocked("virtual", flood)
    finally:
        server_side.Close()
        peer.close()


def _unanswered_endpoint() -> tuple[socket.socket, socket.socket, int]:
    """A listener whose accept queue is full: the kernel drops further SYNs, a connect hangs."""
    full = socket.socket()
    full.bind(("127.0.0.1", 0))
    full.listen(0)
    port = full.getsockname()[1]
    first = socket.create_connection(("127.0.0.1", port), timeout=BOUND)  # fills the queue
    return full, first, port


def test_abort_a_thread_blocked_in_connect() -> None:
    full, first, port = _unanswered_endpoint()
    client = TcpClient()
    try:
        _abort_while_blocked(
            "virtual", lambda: client.Client().Connect(IPEndPoint("127.0.0.1", port)))
    finally:
        client.Close()
        first.close()
        full.close()


def test_closing_a_socket_ends_a_pending_connect_with_1707() -> None:
    full, first, port = _unanswered_endpoint()
    client = TcpClient()
    try:
        t, result = _wait_in_thread(lambda: client.Client().Connect(IPEndPoint("127.0.0.1", port)))
        assert result == []
        client.Close()
        t.join(BOUND)
        assert result == [SOCKET_NOT_OPEN]
    finally:
        first.close()
        full.close()


@pytest.mark.parametrize("clock", ["virtual", "real"])
def test_simulation_stop_ends_a_server_blocked_in_accept_and_a_client_in_receive(clock: str) -> None:
    """What ``gpl2py run`` does on Ctrl-C: every thread ends, none is left in ``still_alive``."""
    sim = Simulation(clock=clock, capture=True)
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    peer = TcpClient(IPEndPoint("127.0.0.1", listener.LocalEndPoint().Port))
    connected = listener.AcceptSocket()
    try:
        sim.start(listener.AcceptSocket, name="server")
        sim.start(lambda: connected.Receive(Box(""), 10), name="reader")
        time.sleep(0.2)
        report = sim.stop(grace=BOUND)
    finally:
        peer.Close()
        connected.Close()
        listener.Stop()
    assert sorted(report.aborted) == ["reader", "server"]
    assert report.still_alive == []


def test_an_aborted_thread_frees_a_socket_held_in_a_reference_cycle() -> None:
    """Abort frees what the thread held at once, as a controller frees a stopped thread's
    objects, even when they sit in a reference cycle: the client of the connection sees it
    close.  (TCS's ``reset`` relies on it: "Any TCP/IP connections made by these threads are
    broken"; there a caught exception's traceback ties the server's frame into a cycle.)
    Python frees a cycle only when its cyclic collector runs, which it does whenever allocations
    add up, so the collector is off here: the test does not depend on when it would run."""
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    client = socket.create_connection(("127.0.0.1", listener.LocalEndPoint().Port), timeout=BOUND)
    sim = Simulation(clock="virtual", capture=True)
    accepted: list[bool] = []

    def server() -> None:
        held: list[object] = [listener.AcceptSocket()]
        held.append(held)  # the cycle: nothing but itself keeps the socket alive once the frame goes
        accepted.append(True)
        held[0].Receive(Box(""), 600_000)  # type: ignore[attr-defined]

    def main() -> None:
        t = Thread(server, 0, "server")
        t.Start()
        while not accepted:
            Thread.Sleep(10)
        t.Abort()

    enabled = gc.isenabled()
    gc.disable()
    try:
        assert sim.run_main(main, timeout=BOUND) == []
        assert client.recv(16) == b""  # closed by the controller (a time-out raises instead)
    finally:
        if enabled:
            gc.enable()
        client.close()
        listener.Stop()
