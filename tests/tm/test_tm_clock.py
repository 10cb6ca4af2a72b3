"""The simulated TM robot runs on the runtime's shared scheduler and clock (issue 22): the Listen
node's and the Ethernet Slave's threads are threads of the robot's session, their sockets the
runtime's (``gplrt.io.sockets``), and controller time is that session's clock -- a script's
``Sleep`` takes controller time, a motion nobody waits for keeps real-time pace (a client watches
it move, docs/design/clock.md), one waited for costs no wall time on the fast clock; blending
hands a motion over to the next one on the shared Ruckig planner."""

from __future__ import annotations

import re

import pytest
from tmpacket import NodeClient

from gplrt.tm.packets import encode


def script(ident: str, text: str) -> bytes:
    return encode("TMSCT", f"{ident},{text}".encode())


def joints(svr: NodeClient) -> list[float]:
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
    c = NodeClient(node.port)
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
    c, svr = NodeClient(node.port), NodeClient(slave.port)
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
    c = NodeClient(node.port)
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


# --- blending (L15747, L15990): a motion blends into the next one, on the shared Ruckig planner ---
A = "0,0,90,0,90,0"
B = "60,-20,110,0,60,0"
C = "0,30,60,10,90,40"


_sessions = iter(range(1, 1000))


def session_time(port: int, motions: str) -> int:
    """Controller ms that ``motions`` (script lines) take, waited for with a queue tag."""
    c = NodeClient(port)
    t = f"t{next(_sessions)}"  # (a Listen node's variables outlive their packet, L17838)
    try:
        text = f"int {t} = GetNowStamp()\r\n{motions}\r\nQueueTag(1, 1)\r\nListenSend(90, \"\" + GetNowStamp({t}))"
        c.sock.sendall(script("1", text))
        frames = [c.reply() for _ in range(3)]
        assert encode("TMSCT", b"1,OK") in frames, frames
        return int(next(f for f in frames if b",90," in f).split(b",")[3])
    finally:
        c.close()


def test_a_blended_ptp_hands_over_moving_and_ends_on_its_target(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, _ = tm_robot

    def through_b(blend: int) -> int:
        robot.wait_idle()
        return session_time(node.port, f'PTP("JPP",{B},50,200,{blend},false)\r\nPTP("JPP",{C},50,200,0,false)\r\n'
                                       f'PTP("JPP",{A},100,200,0,false)')
    stopping, blended = through_b(0), through_b(50)
    assert blended < stopping  # the robot does not stop at B
    assert robot.joints == [0.0, 0.0, 90.0, 0.0, 90.0, 0.0]
    # from a fast motion into a slow one: Ruckig brakes from the hand-over state
    session_time(node.port, f'PTP("JPP",{B},100,200,80,false)\r\nPTP("JPP",{C},2,200,0,false)')
    assert robot.joints == [0.0, 30.0, 60.0, 10.0, 90.0, 40.0]


def test_a_line_blends_by_radius_into_a_ptp_and_a_ptp_into_a_line(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, _ = tm_robot
    line = 'Line("CAR",400,-100,500,180,0,90,300,200,{},false)'
    ptp = f'PTP("JPP",{A},50,200,{{}},false)'
    start = f'PTP("JPP",{A},100,200,0,false)'

    def timed(motions: str) -> tuple[float, list[float]]:
        """Seconds of motion (the robot's, not the script's own turns) of ``motions`` from A, and
        where the robot ends."""
        session_time(node.port, start)
        before = robot.sim_time
        session_time(node.port, motions)
        return robot.sim_time - before, list(robot.joints)
    blended, stopping = timed(line.format(50) + "\r\n" + ptp.format(0)), timed(line.format(0) + "\r\n" + ptp.format(0))
    assert blended[0] < stopping[0] and blended[1] == stopping[1] == [0.0, 0.0, 90.0, 0.0, 90.0, 0.0]
    # into a path motion: superposed until the PTP's end, then exactly on the line (the core's way)
    to_b = f'PTP("JPP",{B},50,200,{{}},false)'
    blended, stopping = timed(to_b.format(50) + "\r\n" + line.format(0)), timed(to_b.format(0) + "\r\n" + line.format(0))
    assert blended[0] < stopping[0]
    assert blended[1] == pytest.approx(stopping[1], abs=1e-9)
    flange = robot.arm.fk(blended[1])
    assert flange[:3] == pytest.approx([400, -100, 500], abs=1e-6)


def test_blending_values_out_of_range_are_script_errors(tm_robot) -> None:  # type: ignore[no-untyped-def]
    _, node, _ = tm_robot
    c = NodeClient(node.port)
    try:
        assert c.ask(script("1", f'PTP("JPP",{B},50,200,101,false)')) == encode("TMSCT", b"1,ERROR;1")
        assert c.ask(script("2", 'Line("CAR",400,-100,500,180,0,90,300,200,-5,false)')) == encode("TMSCT", b"2,ERROR;1")
    finally:
        c.close()


SPINNER = """define
{
    int flag = 0
}

void Waiter()
{
    while (flag == 0)
    {
    }
    Display("seen")
}

main
{
    ThreadRun(Waiter())
    PTP("JPP",0,0,90,0,90,10,50,200,0,false)
    QueueTag(1,1)
    flag = 1
    Sleep(100)
    Display("done")
}
"""


def test_a_thread_that_spins_leaves_the_robot_its_turns(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """TM threads run one at a time on the shared scheduler: a loop's turn is a scheduling point
    (``tm.tick()``), so a thread polling a variable without a wait does not starve the motion
    executor that ``main`` waits for (the run would hang)."""
    import subprocess
    import sys

    src = tmp_path / "spin.tms"
    src.write_text(SPINNER)
    run = subprocess.run([sys.executable, "-m", "gpl2py", "run", str(src)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == ["seen", "done"]
