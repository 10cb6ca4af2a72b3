"""While a GPL program holds a socket open, virtual time keeps to real time.

A server that polls ``listener.Pending()`` between ``Thread.Sleep`` calls blocks in no call, so
without this rule the virtual clock would jump from sleep to sleep and the server's own timeout
would expire long before a real client (here: 0.3 s of wall time later) could connect.
"""

from __future__ import annotations

import gc
import socket
import threading
import time

from gplrt.controller.services import Controller
from gplrt.io.sockets import IPEndPoint, TcpClient, TcpListener
from gplrt.sim import Simulation
from gplrt.threads import Thread


def test_a_polling_server_waits_in_real_time_for_its_client() -> None:
    sim = Simulation(capture=True)  # virtual clock
    result: list[str] = []
    ports: list[int] = []
    listening = threading.Event()

    def server() -> None:
        listener = TcpListener(IPEndPoint("127.0.0.1", 0))
        listener.Start()
        ports.append(listener.LocalEndPoint().Port)
        listening.set()
        t0 = Controller.Timer()
        while not listener.Pending():
            if Controller.Timer() - t0 > 2.0:  # two controller seconds
                result.append("timeout")
                break
            Thread.Sleep(20)
        else:
            result.append("client arrived")
            listener.AcceptSocket().Close()
        listener.Stop()
        # With the listener closed, time jumps again: an hour passes at once.
        t1 = Controller.Timer()
        Thread.Sleep(3_600_000)
        result.append(f"slept {Controller.Timer() - t1:.0f} s")

    def client() -> None:
        listening.wait(5)
        time.sleep(0.3)
        with socket.create_connection(("127.0.0.1", ports[0]), timeout=5):
            pass

    helper = threading.Thread(target=client, daemon=True)
    helper.start()
    assert sim.run_main(server, timeout=30) == []
    helper.join(5)
    assert result == ["client arrived", "slept 3600 s"]


def _connected_client_dropped_without_close(port: int) -> None:
    """A GPL procedure whose local TcpClient goes out of scope unclosed (the object is freed)."""
    tc = TcpClient(IPEndPoint("127.0.0.1", port))
    tc.Client().Send("hi")


def test_sockets_freed_without_close_stop_pacing_virtual_time() -> None:
    """Programs often let a connection's object go instead of closing it; when the object is
    freed, so is its connection, and virtual time may jump again (before: paced forever, so this
    hour of controller time would take an hour)."""
    sim = Simulation(capture=True)  # virtual clock
    result: list[str] = []
    outside = socket.socket()
    outside.bind(("127.0.0.1", 0))
    outside.listen(4)

    def program() -> None:
        _connected_client_dropped_without_close(outside.getsockname()[1])
        listener = TcpListener(IPEndPoint("127.0.0.1", 0))
        listener.Start()
        del listener  # a module variable reassigned, a local at the end of its procedure
        gc.collect()
        t1 = Controller.Timer()
        Thread.Sleep(3_600_000)
        result.append(f"slept {Controller.Timer() - t1:.0f} s")

    try:
        # Paced, the hour would take an hour: the bound (a hang guard) fails it; no wall-time assert.
        assert sim.run_main(program, timeout=10) == []
    finally:
        outside.close()
    assert result == ["slept 3600 s"]
