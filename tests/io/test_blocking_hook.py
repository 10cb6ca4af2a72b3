"""A GPL thread blocked on a real socket must let the other GPL threads run (virtual clock)."""

from __future__ import annotations

from gplrt.io.sockets import IPEndPoint, TcpClient, TcpListener
from gplrt.lang.byref import Box
from gplrt.sim import Simulation
from gplrt.threads import Thread


def test_socket_wait_releases_the_virtual_scheduler() -> None:
    sim = Simulation(clock="virtual", capture=True)
    events: list[str] = []
    listener = TcpListener(IPEndPoint("127.0.0.1", 0))
    listener.Start()
    port = listener.LocalEndPoint().Port

    def server() -> None:
        sock = listener.AcceptSocket()
        sock.ReceiveTimeout = 5000
        buf = Box("")
        n = sock.Receive(buf, 100)
        events.append(f"server got {n}: {buf.get()}")
        sock.Close()

    def client() -> None:
        # Runs only if the server's blocking accept/receive released the token.
        for i in range(3):
            Thread.Sleep(10)
            events.append(f"client tick {i}")
        c = TcpClient()
        c.Connect(IPEndPoint("127.0.0.1", port))
        c.Client().Send("hello")
        Thread.Sleep(10)
        c.Close()

    def main() -> None:
        s = Thread(server)
        k = Thread(client)
        s.Start()
        k.Start()
        s.Join()
        k.Join()

    alive = sim.run_main(main, timeout=20)
    listener.Stop()
    assert alive == []
    assert events == ["client tick 0", "client tick 1", "client tick 2", "server got 5: hello"]
