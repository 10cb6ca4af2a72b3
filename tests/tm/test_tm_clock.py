"""The simulated TM robot runs on the runtime's shared scheduler and clock (issue 22): the Listen
node's and the Ethernet Slave's threads are threads of the robot's session, their sockets the
runtime's (``gplrt.io.sockets``), and controller time is that session's clock -- a script's
``Sleep`` takes controller time, a motion nobody waits for keeps real-time pace (a client watches
it move, docs/design/clock.md), one waited for costs no wall time on the fast clock."""

from __future__ import annotations

import re
import socket

from gplrt.tm.packets import encode


class Client:
    """A raw TCP client reading the replies frame by frame."""

    def __init__(self, port: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=30)
        self.buf = b""

    def ask(self, raw: bytes) -> bytes:
        self.sock.sendall(raw)
        return self.reply()

    def reply(self) -> bytes:
        while b"\r\n" not in self.buf:
            chunk = self.sock.recv(65536)
            assert chunk, "the robot closed the connection"
            self.buf += chunk
        frame, _, self.buf = self.buf.partition(b"\r\n")
        return frame + b"\r\n"

    def close(self) -> None:
        self.sock.close()


def script(ident: str, text: str) -> bytes:
    return encode("TMSCT", f"{ident},{text}".encode())


def joints(svr: Client) -> list[float]:
    """``Joint_Angle`` read through the Ethernet Slave (mode 12, as techmanpy reads it)."""
    reply = svr.ask(encode("TMSVR", b"q,12,Joint_Angle")).decode()
    found = re.search(r"Joint_Angle=\{([^}]*)\}", reply)
    assert found, reply
    return [float(x) for x in found.group(1).split(",")]


def test_the_servers_are_threads_and_sockets_of_the_robots_session(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, slave = tm_robot
    names = {ctx.name for ctx in robot.sim.scheduler.live}
    assert {"tm-motion", "tm-listen", "tm-listen-executor", "tm-svr"} <= names
    # the runtime's socket layer knows the ports, as it knows a GPL server's (docs/security.md)
    assert {node.port, slave.port} <= robot.sim.network.listening_ports()


def test_sleep_in_a_script_takes_controller_time(tm_robot) -> None:  # type: ignore[no-untyped-def]
    _, node, _ = tm_robot
    c = Client(node.port)
    try:
        text = ("int t0 = GetNowStamp()\r\nSleep(200)\r\nint t1 = GetNowStamp()\r\n"
                'ListenSend(90, "" + (t1 - t0))')
        c.sock.sendall(script("1", text))
        pushed = c.reply()
        assert c.reply() == encode("TMSCT", b"1,OK")
        elapsed = int(pushed.split(b",")[3])
        assert 200 <= elapsed <= 205, pushed  # (the clock charges the script's own turns too)
    finally:
        c.close()


def test_a_motion_nobody_waits_for_is_watched_moving_and_stops_where_caught(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, slave = tm_robot
    c, svr = Client(node.port), Client(slave.port)
    start = [0.0, 0.0, 90.0, 0.0, 90.0, 0.0]
    try:
        # J1 by 90 degrees at 1 % of its speed: about a minute of motion, in real-time pace
        assert c.ask(script("1", 'PTP("JPP",90,0,90,0,90,0,1,200,0,false)')) == encode("TMSCT", b"1,OK")
        moving = joints(svr)
        assert moving[0] < 90.0 and moving[1:] == start[1:]  # not at its target: it is moving
        assert c.ask(script("2", "StopAndClearBuffer(0)")) == encode("TMSCT", b"2,OK")
        stopped = joints(svr)
        assert moving[0] <= stopped[0] < 90.0
        assert joints(svr) == stopped  # it stays where the stop caught it
        assert robot.idle()
    finally:
        c.close()
        svr.close()


def test_a_waited_motion_moves_the_controller_clock_by_its_duration(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, _ = tm_robot
    c = Client(node.port)
    try:
        text = ('int t0 = GetNowStamp()\r\nPTP("JPP",90,0,90,0,90,0,20,200,0,false)\r\nQueueTag(1, 1)\r\n'
                'ListenSend(90, "" + GetNowStamp(t0))')
        c.sock.sendall(script("1", text))
        frames = [c.reply() for _ in range(3)]
        pushed = next(f for f in frames if f.startswith(b"$TMSTA,") and b",90," in f)
        assert encode("TMSCT", b"1,OK") in frames
        elapsed = int(pushed.split(b",")[3])
        assert abs(elapsed - robot.sim_time * 1000) <= 5, (elapsed, robot.sim_time)
        assert robot.sim_time > 2.0  # (90 degrees at 20 %: seconds of motion)
    finally:
        c.close()
