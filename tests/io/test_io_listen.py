"""Issue 12, item 12: a GPL program's servers listen on loopback unless the user opens the network.

What a user checks: the address a socket is really bound to, whether a client on another interface
reaches it, and what the GPL program reads back from its own endpoint.  The tests that need an
address of this computer other than loopback find one through the routing table and are skipped
(with the reason) on a machine that has none.
"""

from __future__ import annotations

import socket
import sys
from pathlib import Path

import pytest

from gplrt.io.sockets import IPEndPoint, TcpListener, UdpClient
from gplrt.lang.errors import GplException
from gplrt.sim import Simulation

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from gpltest import gpl2py, write_project  # noqa: E402

FOREIGN = "192.0.2.17"  # TEST-NET: the IP of the controller a program was written for


def lan_address() -> str | None:
    """A non-loopback IPv4 address of this computer (the one that routes outwards), or None."""
    for target in ("192.0.2.1", "10.255.255.254", "198.51.100.1"):
        probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            probe.connect((target, 9))  # no packet is sent: the routing table picks the address
            address = probe.getsockname()[0]
        except OSError:
            continue
        finally:
            probe.close()
        if not address.startswith("127.") and address != FOREIGN:
            return address
    return None


LAN = lan_address()
needs_lan = pytest.mark.skipif(LAN is None, reason="this computer has no network interface besides loopback")


def bound(listener: TcpListener) -> str:
    return listener._listening().getsockname()[0]


def reachable(address: str, port: int) -> bool:
    try:
        socket.create_connection((address, port), timeout=5).close()
        return True
    except OSError:
        return False


@needs_lan
def test_a_server_bound_to_the_computers_own_lan_address_listens_on_loopback() -> None:
    assert LAN is not None
    endpoint = IPEndPoint(LAN, 0)
    listener = TcpListener(endpoint)
    listener.Start()
    try:
        port = listener.LocalEndPoint().Port
        assert bound(listener) == "127.0.0.1"
        assert not reachable(LAN, port)
        assert reachable("127.0.0.1", port)
        assert endpoint.IPAddress == LAN  # the program's own endpoint still says what it asked for
    finally:
        listener.Stop()


@needs_lan
def test_a_udp_endpoint_bound_to_the_lan_address_listens_on_loopback() -> None:
    assert LAN is not None
    udp = UdpClient(IPEndPoint(LAN, 0))
    try:
        assert udp.Client()._sock.getsockname()[0] == "127.0.0.1"
    finally:
        udp.Close()


def test_a_udp_socket_that_sends_before_binding_is_bound_to_loopback() -> None:
    """Left to the kernel, the first SendTo binds every interface: a port open to the network."""
    peer = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    peer.bind(("127.0.0.1", 0))
    udp = UdpClient()
    try:
        udp.Client().SendTo("ping", 0, IPEndPoint("127.0.0.1", peer.getsockname()[1]))
        data, sender = peer.recvfrom(100)
        assert data == b"ping"
        assert udp.Client()._sock.getsockname()[0] == "127.0.0.1" == sender[0]
    finally:
        udp.Close()
        peer.close()


@needs_lan
def test_listen_on_one_address_opens_that_interface_only() -> None:
    assert LAN is not None
    Simulation(listen=LAN).activate()
    for asked in ("", "0.0.0.0", LAN, FOREIGN):
        listener = TcpListener(IPEndPoint(asked, 0))
        listener.Start()
        try:
            assert bound(listener) == LAN, asked
        finally:
            listener.Stop()
    loop = TcpListener(IPEndPoint("127.0.0.1", 0))
    loop.Start()
    try:
        assert bound(loop) == "127.0.0.1"  # a program that asks for loopback keeps it
    finally:
        loop.Stop()


@needs_lan
def test_listen_on_every_interface_keeps_the_programs_own_choice() -> None:
    assert LAN is not None
    Simulation(listen="0.0.0.0").activate()
    for asked, where in (("", "0.0.0.0"), ("0.0.0.0", "0.0.0.0"), (LAN, LAN), (FOREIGN, "0.0.0.0")):
        listener = TcpListener(IPEndPoint(asked, 0))
        listener.Start()
        try:
            assert bound(listener) == where, asked
        finally:
            listener.Stop()


def test_a_port_in_use_names_the_address_this_computer_refused() -> None:
    """With every interface open, a server written for its controller's own IP (which this computer
    lacks) binds 0.0.0.0; when that port is taken, -304 named the controller's IP, where nothing
    was ever tried."""
    Simulation(listen="0.0.0.0").activate()
    with socket.socket() as taken:
        taken.bind(("0.0.0.0", 0))
        taken.listen()
        port = taken.getsockname()[1]
        with pytest.raises(GplException) as tcp:
            TcpListener(IPEndPoint(FOREIGN, port)).Start()
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as taken_udp:
            taken_udp.bind(("0.0.0.0", 0))
            udp_port = taken_udp.getsockname()[1]
            with pytest.raises(GplException) as udp:
                UdpClient(IPEndPoint(FOREIGN, udp_port))
    assert tcp.value.ErrorCode == udp.value.ErrorCode == -304
    assert tcp.value.detail == f"listen on 0.0.0.0:{port}: address already in use"
    assert udp.value.detail == f"bind 0.0.0.0:{udp_port}: address already in use"


def test_one_sessions_opt_in_does_not_carry_over_to_the_next() -> None:
    Simulation(listen="0.0.0.0").activate()
    Simulation().activate()
    listener = TcpListener(IPEndPoint("", 0))
    listener.Start()
    try:
        assert bound(listener) == "127.0.0.1"
    finally:
        listener.Stop()


@pytest.mark.parametrize("address", ["10.9.9.9x", "", "localhost", "192.0.2.17"])
def test_a_listen_address_this_computer_lacks_is_refused_at_once(address: str) -> None:
    with pytest.raises(ValueError):
        Simulation(listen=address)


def test_gpl2py_run_refuses_a_bad_listen_address_before_the_program_runs(tmp_path: Path) -> None:
    project = write_project(tmp_path, {"Main.gpl": 'Module Main\n    Public Sub Main()\n'
                                       '        Console.WriteLine("ran")\n    End Sub\nEnd Module\n'})
    r = gpl2py("run", project, "--listen", FOREIGN, "-q")
    assert r.returncode == 2
    assert f"error GPL9001: --listen {FOREIGN}: {FOREIGN} is not an address of this computer" in r.stderr
    assert "ran" not in r.stdout


SERVER = """Module Main
    Public Sub Main()
        Dim listener As New TcpListener(New IPEndPoint("{lan}", {port}))
        Dim client As TcpClient
        listener.Start()
        Try
            client = New TcpClient(New IPEndPoint("127.0.0.1", {port}))
            Console.WriteLine("loopback reaches it")
            client.Close()
        Catch ex As Exception
            Console.WriteLine("loopback " & CStr(ex.ErrorCode))
        End Try
        Try
            client = New TcpClient(New IPEndPoint("{lan}", {port}))
            Console.WriteLine("the network reaches it")
            client.Close()
        Catch ex As Exception
            Console.WriteLine("the network gets " & CStr(ex.ErrorCode))
        End Try
        listener.Stop()
    End Sub
End Module
"""


@needs_lan
@pytest.mark.parametrize("opt_in", [False, True])
def test_gpl2py_run_listens_on_the_lan_only_with_listen(tmp_path: Path, opt_in: bool) -> None:
    with socket.socket() as s:  # a port free on every interface
        s.bind(("0.0.0.0", 0))
        port = s.getsockname()[1]
    project = write_project(tmp_path, {"Main.gpl": SERVER.format(lan=LAN, port=port)})
    r = gpl2py("run", project, "-q", *(["--listen", str(LAN)] if opt_in else []))
    assert r.returncode == 0, r.stderr
    if opt_in:
        assert r.stdout.splitlines() == ["loopback -1702", "the network reaches it"]
    else:
        assert r.stdout.splitlines() == ["loopback reaches it", "the network gets -1702"]


def test_cell_load_refuses_a_bad_listen_address_before_translating(tmp_path: Path) -> None:
    from gpl2py.notebook import Cell

    with pytest.raises(ValueError, match="not an address of this computer"):
        Cell.load(tmp_path / "no such project", listen=FOREIGN)  # the address fails first
