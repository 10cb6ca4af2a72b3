"""The FAST virtual clock: a client that waits for the controller does not wait in wall time.

On the ``virtual`` clock an open socket holds virtual time to real-time pace (a server's
timeouts must mean something to its real clients), so a client waits out every motion in wall
time.  ``clock="fast"`` lets time jump while a GPL thread waits for the controller — the end of
a motion, homing, a power-up — and nothing else can run; everything else stays paced.  These
tests drive a small line server (Python procedures on GPL threads, shaped like TCS's
``TcpComMain``: a ``Pending()`` poll with ``Thread.Sleep(500)``, then one connection) from a
real socket client, and assert on controller times and on the order of events.  Wall time is
bounded only through time-outs (the client's socket, ``run_main``): each waited motion is
minutes of controller time, which a paced run could not finish within them.
"""

from __future__ import annotations

import socket
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import pytest

from gplrt.controller.services import Controller
from gplrt.io.sockets import IPEndPoint, TcpListener
from gplrt.lang.byref import Box
from gplrt.lang.errors import NETWORK_TIMEOUT, GplException
from gplrt.motion.move import Move
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.threads import Thread

RUN_TIMEOUT = 60.0  # wall seconds: a hang guard for the whole run, never a measurement
REPLY_TIMEOUT = 30.0  # wall seconds the client waits for one reply (a paced run needs 300+)
POWER_UP = 300.0  # controller seconds a power-up takes in these tests
MOTION = 600.0  # controller seconds of the waited motion (Move.Delay)


def timer() -> float:
    return float(Controller.Timer())


def prepare() -> str:
    """Power (a POWER_UP-second power-up), attach and home: TCS's hp / attach / home."""
    Controller.PowerEnabled = True
    Robot.Attached = 1
    Robot.Home()
    return f"{timer():.4f}"


def queue_motion() -> str:
    """Queue MOTION seconds of motion and return at once (TCS's moveJ does not wait)."""
    Move.Delay(MOTION)
    return f"{timer():.4f}"


def wait_for_eom() -> str:
    Move.WaitForEOM()
    return f"{timer():.4f}"


COMMANDS: dict[str, Callable[[], str]] = {
    "prepare": prepare,
    "move": queue_motion,
    "wait": wait_for_eom,
    "time": lambda: f"{timer():.4f}",
}


@dataclass
class LineServer:
    """One connection, one command per line, one reply line each (TCS's TcpComMain shape)."""

    poll_ms: int = 500
    port: int = 0
    listening: threading.Event = field(default_factory=threading.Event)
    done: bool = False
    log: list[str] = field(default_factory=list)

    def serve(self) -> None:
        listener = TcpListener(IPEndPoint("127.0.0.1", 0))
        listener.Start()
        self.port = int(listener.LocalEndPoint().Port)
        self.listening.set()
        while not listener.Pending():  # Main.gpl:75-77
            Thread.Sleep(self.poll_ms)
        sock = listener.AcceptSocket()
        listener.Stop()  # "Only service one"
        received, pending = Box(""), ""
        while sock.Receive(received, 1000) > 0:
            pending += received.get()
            while "\n" in pending:
                line, pending = pending.split("\n", 1)
                self.log.append(line)
                sock.Send(COMMANDS[line]() + "\n")
        sock.Close()
        self.done = True


class Client:
    """A socket client on a plain Python thread: sends each request once the last reply came."""

    def __init__(self, server: LineServer, requests: list[str], delay: float = 0.0) -> None:
        self.server, self.requests, self.delay = server, requests, delay
        self.replies: list[str] = []
        self.error: BaseException | None = None
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self) -> None:
        try:
            assert self.server.listening.wait(REPLY_TIMEOUT)
            time.sleep(self.delay)
            with socket.create_connection(("127.0.0.1", self.server.port), timeout=REPLY_TIMEOUT) as conn:
                lines = conn.makefile("r", encoding="latin-1", newline="\n")
                for request in self.requests:
                    conn.sendall(request.encode() + b"\n")
                    self.replies.append(lines.readline().strip())
        except BaseException as exc:  # reported by the test, not lost on this thread
            self.error = exc

    def join(self) -> list[float]:
        self.thread.join(REPLY_TIMEOUT)
        assert self.error is None, f"client failed: {self.error!r}"
        return [float(r) for r in self.replies]


def fast_sim() -> Simulation:
    sim = Simulation(clock="fast", capture=True)
    sim.controller.power_up_time = POWER_UP
    return sim


def test_fast_is_a_clock_of_its_own() -> None:
    sim = Simulation(clock="fast")
    assert sim.mode == "fast" and sim.scheduler.run_ahead
    assert not Simulation(clock="virtual").scheduler.run_ahead
    with pytest.raises(ValueError, match="'virtual', 'fast', 'real'"):
        Simulation(clock="quick")  # type: ignore[arg-type]


def test_a_client_waits_for_power_homing_and_a_motion_without_waiting_in_wall_time() -> None:
    sim = fast_sim()
    server = LineServer()
    client = Client(server, ["prepare", "move", "time", "wait", "time"])
    assert sim.run_main(server.serve, timeout=RUN_TIMEOUT) == []
    prepared, queued, between, ended, after = client.join()
    assert server.log == ["prepare", "move", "time", "wait", "time"] and server.done
    # the power-up and homing (1 s) were waited for: they took their controller time
    assert prepared >= POWER_UP + 1.0
    # a motion nobody waits for keeps real-time pace: a moment later it has barely begun
    assert queued <= between < queued + MOTION / 10
    # waited for, it ends exactly where the queue says (to the 125 us Timer tick)
    assert ended == pytest.approx(queued + MOTION, abs=2e-3)
    assert ended <= after < ended + MOTION / 10


def test_a_poller_with_no_client_does_not_race_the_clock_ahead() -> None:
    """TCS polls ``Pending()`` between sleeps while nobody has connected: with no controller
    wait in progress the clock stays paced, so a controller-time timeout of a minute does not
    expire before a client that connects 0.3 wall seconds later."""
    sim = fast_sim()
    result: list[str] = []
    port: list[int] = []
    listening = threading.Event()

    def server() -> None:
        listener = TcpListener(IPEndPoint("127.0.0.1", 0))
        listener.Start()
        port.append(int(listener.LocalEndPoint().Port))
        listening.set()
        t0 = timer()
        while not listener.Pending():
            if timer() - t0 > 60.0:
                result.append("timeout")
                break
            Thread.Sleep(10)
        else:
            result.append("client arrived")
            listener.AcceptSocket().Close()
        listener.Stop()

    def client() -> None:
        listening.wait(REPLY_TIMEOUT)
        time.sleep(0.3)
        with socket.create_connection(("127.0.0.1", port[0]), timeout=REPLY_TIMEOUT):
            pass

    helper = threading.Thread(target=client, daemon=True)
    helper.start()
    assert sim.run_main(server, timeout=RUN_TIMEOUT) == []
    helper.join(REPLY_TIMEOUT)
    assert result == ["client arrived"]


def test_sleeping_threads_wake_at_each_of_their_deadlines_on_the_way() -> None:
    """Time jumps deadline by deadline, never over one: a second server thread polling its
    own listener every 500 ms (TCS runs one per port) wakes 2 x MOTION times during the
    waited motion, each time exactly 0.5 s after the last."""
    sim = fast_sim()
    server = LineServer()
    wakes: list[float] = []

    def idle_port_poller() -> None:
        listener = TcpListener(IPEndPoint("127.0.0.1", 0))
        listener.Start()
        while not server.done and not listener.Pending():
            Thread.Sleep(500)
            wakes.append(timer())
        listener.Stop()

    def main() -> None:
        Thread(idle_port_poller, _session=sim).Start()
        server.serve()

    client = Client(server, ["prepare", "move", "wait"])
    assert sim.run_main(main, timeout=RUN_TIMEOUT) == []
    _, queued, ended = client.join()
    during = [t for t in wakes if queued < t <= ended]
    assert len(during) == pytest.approx(2 * MOTION, abs=2)
    assert all(b - a == pytest.approx(0.5, abs=2e-3) for a, b in zip(during, during[1:]))


def test_a_receive_time_out_stays_in_wall_time() -> None:
    """Socket time-outs are wall-clock (they are the client's): a Receive with a one-second
    ReceiveTimeout, begun before a waited motion of MOTION seconds, ends with -1705 after the
    motion's end in controller time — the jump did not expire it."""
    sim = fast_sim()
    events: list[tuple[str, float]] = []
    port: list[int] = []
    listening = threading.Event()

    def receiver(sock: object) -> None:
        sock.ReceiveTimeout = 1000  # type: ignore[attr-defined]
        try:
            sock.Receive(Box(""), 100)  # type: ignore[attr-defined]
            events.append(("received", timer()))
        except GplException as exc:
            events.append((f"error {exc.ErrorCode}", timer()))

    def server() -> None:
        listener = TcpListener(IPEndPoint("127.0.0.1", 0))
        listener.Start()
        port.append(int(listener.LocalEndPoint().Port))
        listening.set()
        sock = listener.AcceptSocket()
        listener.Stop()
        prepare()
        reader = Thread(receiver, _session=sim, _args=(sock,))
        reader.Start()
        Move.Delay(MOTION)
        Move.WaitForEOM()
        events.append(("motion ended", timer()))
        reader.Join()
        sock.Close()

    def client() -> None:
        listening.wait(REPLY_TIMEOUT)
        with socket.create_connection(("127.0.0.1", port[0]), timeout=REPLY_TIMEOUT) as conn:
            conn.recv(1)  # until the server closes: sends nothing

    helper = threading.Thread(target=client, daemon=True)
    helper.start()
    assert sim.run_main(server, timeout=RUN_TIMEOUT) == []
    helper.join(REPLY_TIMEOUT)
    assert [name for name, _ in events] == ["motion ended", f"error {NETWORK_TIMEOUT}"]
    assert events[1][1] > events[0][1] >= POWER_UP + 1.0 + MOTION
