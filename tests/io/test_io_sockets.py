"""Networking on real loopback sockets: EX-18/19 echo, UDP (EX-20 shape), timeouts and error codes."""

from __future__ import annotations

import contextlib
import socket
import struct
import threading
import time
from collections.abc import Iterator

import pytest

from gpltest import free_port
from gplrt.io import _blocking
from gplrt.io.sockets import IPEndPoint, Socket, TcpClient, TcpListener, UdpClient
from gplrt.lang.errors import GplException


WAIT = 5.0  # seconds: upper bound for any thread join in these tests


def run(target: object) -> threading.Thread:
    thread = threading.Thread(target=target, daemon=True)  # type: ignore[arg-type]
    thread.start()
    return thread


@contextlib.contextmanager
def connected_pair() -> Iterator[tuple[Socket, Socket]]:
    """(server-side Socket, client-side Socket) over loopback, both GPL objects."""
    tl = TcpListener(IPEndPoint("", 0))
    tl.Start()
    port = tl.LocalEndPoint().Port
    tc = TcpClient(IPEndPoint("127.0.0.1", port))
    ts = tl.AcceptSocket()
    tl.Stop()
    try:
        yield ts, tc.Client()
    finally:
        ts.Close()
        tc.Close()


def test_ex18_ex19_echo_server_and_client(cell: type) -> None:
    port = free_port()
    log: list[str] = []
    tl = TcpListener(IPEndPoint("", port))  # EX-18: blank IP = accept from any address
    tl.Start()
    assert tl.Pending() is False

    def telnet() -> None:  # EX-18, with a bounded poll instead of Sleep(5000)
        deadline = time.monotonic() + WAIT
        while not tl.Pending() and time.monotonic() < deadline:
            time.sleep(0.005)
        ts = tl.AcceptSocket()
        tl.Stop()
        ts.ReceiveTimeout = int(WAIT * 1000)
        recv = cell("")
        while True:
            ii = ts.Receive(recv, 1000)
            log.append(f"Receive count: {ii}")
            if ii == 0:
                break
            ts.Send("Received: " + recv.get())
        log.append("Connection closed")
        ts.Close()

    server = run(telnet)
    tc = TcpClient(IPEndPoint("127.0.0.1", port))  # EX-19
    ts = tc.Client()
    ts.ReceiveTimeout = int(WAIT * 1000)
    message = "Test message" + chr(13) + chr(10)
    replies = []
    for _ in range(5):
        ts.Send(message)
        reply = cell()
        n = ts.Receive(reply, 1000)
        replies.append(reply.get())
        assert n == len("Received: " + message)
    ts.Close()
    server.join(WAIT)
    assert not server.is_alive()
    assert replies == ["Received: Test message\r\n"] * 5
    assert log == [f"Receive count: {len(message)}"] * 5 + ["Receive count: 0", "Connection closed"]


def test_binary_bytes_pass_unchanged_and_remote_endpoint(cell: type) -> None:
    with connected_pair() as (server, client):
        payload = "".join(chr(c) for c in range(256))
        assert client.Send(payload) == 256
        got = ""
        server.ReceiveTimeout = 2000
        while len(got) < 256:
            part = cell()
            server.Receive(part, 1000)
            got += part.get()
        assert got == payload
        ep = server.RemoteEndPoint
        assert ep.IPAddress == "127.0.0.1" and ep.Port == client._sock.getsockname()[1]
        assert client.Send("abc", 2) == 2  # max_length truncates
        buf = cell()
        deadline = time.monotonic() + WAIT
        while server.Available < 2 and time.monotonic() < deadline:
            time.sleep(0.001)
        assert server.Available == 2
        assert server.Receive(buf, 10) == 2 and buf.get() == "ab"


def test_receive_timeout_raises_network_timeout(cell: type) -> None:
    with connected_pair() as (_server, client):
        assert client.ReceiveTimeout == 0  # default: wait forever
        client.ReceiveTimeout = 100
        start = time.monotonic()
        with pytest.raises(GplException) as exc:
            client.Receive(cell(), 100)
        elapsed = time.monotonic() - start
        assert exc.value.ErrorCode == -1705
        assert 0.09 <= elapsed < 2.0


def test_non_blocking_receive_without_data(cell: type) -> None:
    with connected_pair() as (_server, client):
        client.Blocking = False
        with pytest.raises(GplException) as exc:
            client.Receive(cell(), 100)
        assert exc.value.ErrorCode == -523


def test_orderly_peer_close_reads_zero_then_send_is_connection_closed(cell: type) -> None:
    with connected_pair() as (server, client):
        server.Close()
        buf = cell("stale")
        client.ReceiveTimeout = 2000
        assert client.Receive(buf, 100) == 0
        assert buf.get() == ""
        assert client.Connected is False
        with pytest.raises(GplException) as exc:
            client.Send("anyone there?")
        assert exc.value.ErrorCode == -1708


def test_peer_reset_is_connection_closed(cell: type) -> None:
    with connected_pair() as (server, client):
        server._sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        server.Close()  # linger 0: the peer sees a reset, not an orderly close
        client.ReceiveTimeout = 2000
        with pytest.raises(GplException) as exc:
            client.Receive(cell(), 100)
        assert exc.value.ErrorCode == -1708


def test_port_in_use() -> None:
    first = TcpListener(IPEndPoint("", 0))
    first.Start()
    port = first.LocalEndPoint().Port
    second = TcpListener(IPEndPoint("", port))
    with pytest.raises(GplException) as exc:
        second.Start()
    assert exc.value.ErrorCode == -304
    first.Stop()
    udp = UdpClient(IPEndPoint("", 0))
    udp_port = udp.Client()._sock.getsockname()[1]
    with pytest.raises(GplException) as exc:
        UdpClient(IPEndPoint("", udp_port))
    assert exc.value.ErrorCode == -304
    udp.Close()


def test_connection_refused_and_closed_socket(cell: type) -> None:
    port = free_port()
    with pytest.raises(GplException) as exc:
        TcpClient(IPEndPoint("127.0.0.1", port))
    assert exc.value.ErrorCode == -1702
    tc = TcpClient()
    with pytest.raises(GplException) as exc:
        tc.Client().Send("not connected")
    assert exc.value.ErrorCode == -1707
    tc.Close()
    with pytest.raises(GplException) as exc:
        tc.Client().Receive(cell(), 10)
    assert exc.value.ErrorCode == -1707
    tl = TcpListener(IPEndPoint("", 0))
    with pytest.raises(GplException) as exc:
        tl.AcceptSocket()  # not started
    assert exc.value.ErrorCode == -1707


def test_already_connected() -> None:
    with connected_pair() as (server, client):
        with pytest.raises(GplException) as exc:
            client.Connect(IPEndPoint("127.0.0.1", server._sock.getsockname()[1]))
        assert exc.value.ErrorCode == -1706


def test_endpoint_validation_and_blank_address_binds_loopback() -> None:
    with pytest.raises(GplException) as exc:
        IPEndPoint("300.1.2.3", 10)
    assert exc.value.ErrorCode == -1704
    with pytest.raises(GplException) as exc:
        IPEndPoint("10.0.0.1", 70000)
    assert exc.value.ErrorCode == -707
    ep = IPEndPoint("192.168.0.150")
    assert (ep.IPAddress, ep.Port) == ("192.168.0.150", 0)
    tl = TcpListener(IPEndPoint("", 0))
    tl.Start()
    assert tl.LocalEndPoint().IPAddress == "127.0.0.1"
    tl.Stop()


def test_udp_round_trip_ex20_shape(cell: type) -> None:
    server = UdpClient(IPEndPoint("", 0))
    server_sock = server.Client()
    server_port = server_sock._sock.getsockname()[1]
    server_sock.ReceiveTimeout = int(WAIT * 1000)

    def tftp_like_server() -> None:
        inp, rem_ep = cell(), cell(None)  # rem_ep declared without New: ReceiveFrom allocates it
        count = server_sock.ReceiveFrom(inp, 1500, rem_ep)
        assert count == len(inp.get())
        # Reply with DATA block 1: opcode 3, block 1, then data.
        server_sock.SendTo(chr(0) + chr(3) + chr(0) + chr(1) + "hello", 0, rem_ep.get())

    thread = run(tftp_like_server)
    uc = UdpClient()
    us = uc.Client()
    us.ReceiveTimeout = int(WAIT * 1000)
    srv_ep = IPEndPoint("127.0.0.1", server_port)
    out = chr(0) + chr(1) + "testfile.txt" + chr(0) + "octet" + chr(0)
    assert us.SendTo(out, 0, srv_ep) == len(out)
    inp, rem_ep = cell(), cell(None)
    count = us.ReceiveFrom(inp, 1500, rem_ep)
    thread.join(WAIT)
    assert count == 9
    data = inp.get()
    op = ord(data[0]) * 256 + ord(data[1])
    block = ord(data[2]) * 256 + ord(data[3])
    assert (op, block, data[4:]) == (3, 1, "hello")
    assert rem_ep.get().IPAddress == "127.0.0.1" and rem_ep.get().Port == server_port
    # An existing endpoint object is filled in place (EX-20 reuses `ep`).
    existing = IPEndPoint("10.1.1.1", 5)
    holder = cell(existing)
    us.SendTo("again", 0, srv_ep)
    server_sock.ReceiveFrom(cell(), 1500, holder)
    assert holder.get() is existing and existing.IPAddress == "127.0.0.1"
    us.Close()
    server.Close()


def test_udp_receive_timeout(cell: type) -> None:
    uc = UdpClient(IPEndPoint("", 0))
    s = uc.Client()
    s.ReceiveTimeout = 50
    with pytest.raises(GplException) as exc:
        s.ReceiveFrom(cell(), 100, cell())
    assert exc.value.ErrorCode == -1705
    uc.Close()


@pytest.mark.parametrize("max_length", [0, -1])
def test_receive_from_needs_a_positive_max_length(cell: type, max_length: int) -> None:
    uc = UdpClient(IPEndPoint("", 0))
    try:
        with pytest.raises(GplException) as exc:
            uc.Client().ReceiveFrom(cell(), max_length, cell())
        assert exc.value.ErrorCode == -707
    finally:
        uc.Close()


def test_blocking_waits_go_through_the_hook(cell: type) -> None:
    seen: list[float | None] = []

    @contextlib.contextmanager
    def hook(timeout: float | None) -> Iterator[None]:
        seen.append(timeout)
        yield

    previous = _blocking.set_blocking_hook(hook)
    try:
        with connected_pair() as (_server, client):
            client.ReceiveTimeout = 30
            with pytest.raises(GplException):
                client.Receive(cell(), 10)
    finally:  # the simulator's hook, not the no-op: later tests run GPL threads on sockets
        _blocking.set_blocking_hook(previous)
    assert 0.03 in seen  # the receive announced its bound
    assert None in seen  # the accept had none


@pytest.mark.parametrize("address", ["0.0.0.0", "192.0.2.17"])
def test_any_address_and_a_foreign_controller_address_bind_loopback(address: str) -> None:
    """0.0.0.0 means "any" like a blank; 192.0.2.17 (TEST-NET) stands for the controller's own IP
    in a program written for one cell: this PC does not have it, so the server binds loopback."""
    tl = TcpListener(IPEndPoint(address, 0))
    tl.Start()
    try:
        assert tl.LocalEndPoint().IPAddress == "127.0.0.1"
        with socket.create_connection(("127.0.0.1", tl.LocalEndPoint().Port), timeout=WAIT):
            accepted = tl.AcceptSocket()
            accepted.Close()
    finally:
        tl.Stop()
    udp = UdpClient(IPEndPoint(address, 0))
    try:
        assert udp.Client()._sock.getsockname()[0] == "127.0.0.1"
    finally:
        udp.Close()

