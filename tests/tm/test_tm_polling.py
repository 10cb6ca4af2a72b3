"""A client that does not wait for its motion but polls (issue 22, item 2): ``$TMSTA 01`` queue-tag
status and the Ethernet Slave's ``Joint_Angle`` show the motion progress at the clock's pace, on
every clock (docs/design/clock.md: a motion nobody waits for is not a controller wait, so even
the ``fast`` clock keeps it at real-time pace, as TCS's ``wherej`` pollers see a ``moveJ`` move).

Checked with a raw-socket client and with techmanpy's own polling calls
(``set_queue_tag(n, wait_for_completion=False)``, then ``get_queue_tag_status`` and
``get_value('Joint_Angle')``).  The motion lasts about a second of controller time; no
assertion is on wall time, only on what the poller sees in order."""

from __future__ import annotations

import asyncio
import re

import pytest
from tmpacket import NodeClient

from gplrt.tm import context
from gplrt.tm.listen import ListenNode
from gplrt.tm.packets import encode
from gplrt.tm.slave import EthernetSlave

from gpl2py.tmscript.pipeline import translate_packet

HOME = [0.0, 0.0, 90.0, 0.0, 90.0, 0.0]


def _joints(svr: NodeClient) -> list[float]:
    reply = svr.ask(encode("TMSVR", b"q,12,Joint_Angle")).decode()
    found = re.search(r"Joint_Angle=\{([^}]*)\}", reply)
    assert found, reply
    return [float(x) for x in found.group(1).split(",")]


def _poll_until_done(status, joints) -> list[tuple[str, float]]:  # type: ignore[no-untyped-def]
    """(tag status, J1) samples until the tag is done (at most 20000 polls)."""
    seen: list[tuple[str, float]] = []
    for _ in range(20000):
        st = status()
        seen.append((st, joints()[0]))
        if st == "true":
            return seen
    raise AssertionError(f"the tag never completed: {seen[-3:]}")


def _check_progress(seen: list[tuple[str, float]], target: float) -> None:
    words = [s for s, _ in seen]
    assert words[0] == "false" and words[-1] == "true" and words.count("true") == 1
    j1 = [q for _, q in seen]
    assert all(a <= b + 1e-9 for a, b in zip(j1, j1[1:]))  # the robot only moves on
    assert any(0.0 < q < target for s, q in seen if s == "false")  # seen on its way
    assert j1[-1] == pytest.approx(target, abs=1e-9)


@pytest.mark.parametrize("clock", ["fast", "virtual", "real"])
def test_a_raw_client_polling_tag_status_and_joints_sees_the_motion_progress(clock: str) -> None:
    robot = context.use_robot("TM5-900", clock=clock)
    node = ListenNode(robot, translate_packet, "127.0.0.1", 0).serve()
    slave = EthernetSlave(robot, "127.0.0.1", 0).serve()
    sct, sta, svr = NodeClient(node.port), NodeClient(node.port), NodeClient(slave.port)
    try:
        # J1 by 30 degrees at 20 % of its speed, a tag queued and not waited for
        t0 = robot.clock.now()
        ok = sct.ask(encode("TMSCT", b'1,PTP("JPP",30,0,90,0,90,0,20,200,0,false)\r\nQueueTag(1)'))
        assert ok == encode("TMSCT", b"1,OK")

        def status() -> str:
            reply = sta.ask(encode("TMSTA", b"01,01")).decode()
            return reply.split(",")[4]
        seen = _poll_until_done(status, lambda: _joints(svr))
        _check_progress(seen, 30.0)
        assert robot.clock.now() - t0 >= robot.sim_time - 1e-6  # controller time ran the whole motion
        assert sct.reply() == encode("TMSTA", b"01,01,true")  # the push to the connection that queued it
    finally:
        for c in (sct, sta, svr):
            c.close()
        node.close()
        slave.close()
        context.set_node(None)


def test_techmanpy_polling_without_waiting_sees_the_motion_progress(tm_robot, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    techmanpy = pytest.importorskip("techmanpy")
    robot, node, slave = tm_robot
    monkeypatch.setattr(techmanpy.TMSCT_client, "PORT", node.port)
    monkeypatch.setattr(techmanpy.TMSTA_client, "PORT", node.port)
    monkeypatch.setattr(techmanpy.TMSVR_client, "PORT", slave.port)

    async def session() -> list[tuple[str, float]]:
        async with techmanpy.connect_sct(robot_ip="127.0.0.1") as sct, \
                techmanpy.connect_sta(robot_ip="127.0.0.1") as sta, \
                techmanpy.connect_svr(robot_ip="127.0.0.1") as svr:
            await sct.move_to_joint_angles_ptp([30, 0, 90, 0, 90, 0], 0.2, 200)
            await sct.set_queue_tag(1, wait_for_completion=False)
            seen: list[tuple[str, float]] = []
            while not seen or seen[-1][0] != "true":
                done = await sta.get_queue_tag_status(1)
                seen.append(("true" if done else "false", (await svr.get_value("Joint_Angle"))[0]))
            # the session goes on: the next command is answered as usual
            await sct.move_to_joint_angles_ptp(HOME, 0.5, 200)
            await sct.set_queue_tag(2, wait_for_completion=True)
            assert await svr.get_value("Joint_Angle") == HOME
            return seen
    _check_progress(asyncio.run(asyncio.wait_for(session(), 60)), 30.0)
