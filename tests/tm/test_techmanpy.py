"""techmanpy 1.2 (PyPI), unchanged, drives the simulated TM5-900 over loopback (issue 22).

The client's classes take fixed ports (5890, 5891); the test points them at the fixture's free
ports by setting the class attribute they read, nothing else of the client is touched.  After
each motion the joints and the flange pose read back through the Ethernet Slave match the URDF's
forward kinematics (Pinocchio on the URDF, independently of the runtime) to 1e-6.
"""

from __future__ import annotations

import asyncio
import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

techmanpy = pytest.importorskip("techmanpy")

URDF = Path(__file__).resolve().parents[2] / "runtime" / "gplrt" / "data" / "robots" / "urdf" / "tm5-900-nominal.urdf"


def urdf_flange(joints_deg: list[float]) -> list[float]:
    """The flange pose of the URDF at ``joints_deg``, as X Y Z (mm) and R = Rz·Ry·Rx (deg)."""
    model = pin.buildModelFromUrdf(str(URDF))
    data = model.createData()
    pin.framesForwardKinematics(model, data, np.radians(joints_deg))
    m = data.oMf[model.getFrameId("flange")]
    rpy = np.degrees(pin.rpy.matrixToRpy(m.rotation))
    return [*(m.translation * 1000.0), *rpy]


def near(a: list[float], b: list[float], tol: float = 1e-6) -> bool:
    return len(a) == len(b) and all(math.isclose(x, y, abs_tol=tol) for x, y in zip(a, b))


def ports(node, slave, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.setattr(techmanpy.TMSCT_client, "PORT", node.port)
    monkeypatch.setattr(techmanpy.TMSTA_client, "PORT", node.port)
    monkeypatch.setattr(techmanpy.TMSVR_client, "PORT", slave.port)


def test_techmanpy_session(tm_robot, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    robot, node, slave = tm_robot
    ports(node, slave, monkeypatch)

    async def session() -> None:
        async with techmanpy.connect_svr(robot_ip="127.0.0.1") as svr:
            assert await svr.get_value("Robot_Model") == "TM5-900"
            async with techmanpy.connect_sct(robot_ip="127.0.0.1") as sct:
                target = [10.0, -20.0, 100.0, 5.0, 80.0, 30.0]
                await sct.move_to_joint_angles_ptp(target, 0.5, 200)
                await sct.set_queue_tag(1, wait_for_completion=True)
                joints = await svr.get_value("Joint_Angle")
                assert near(joints, target)
                flange = await svr.get_value("Coord_Robot_Flange")
                assert near(flange, urdf_flange(target))

                goal = list(flange)
                goal[0] += 40.0
                goal[2] -= 25.0
                await sct.move_to_point_line(goal, 0.5, 200)
                await sct.set_queue_tag(2, wait_for_completion=True)
                flange = await svr.get_value("Coord_Robot_Flange")
                assert near(flange, goal)
                joints = await svr.get_value("Joint_Angle")
                assert near(urdf_flange(joints), goal)

                via, end = list(goal), list(goal)
                via[0] += 30.0
                via[1] += 30.0
                end[1] += 60.0
                await sct.move_on_circle(via, end, 0.5, 200)
                await sct.set_queue_tag(3, wait_for_completion=True)
                joints = await svr.get_value("Joint_Angle")
                assert near(urdf_flange(joints), end)
                assert near(await svr.get_value("Coord_Robot_Flange"), end)

                async with techmanpy.connect_sta(robot_ip="127.0.0.1") as sta:
                    assert await sta.is_listen_node_active() is True
                    assert await sta.get_queue_tag_status(3) is True
                    assert await sta.get_queue_tag_status(9) is None

                await svr.set_value("Ctrl_DO3", 1)
                assert await svr.get_value("Ctrl_DO3") == 1
                assert robot.ctrl_do[3] == 1

                await sct.exit_listen()
                with pytest.raises(techmanpy.TechmanException, match="Listen Node is not active"):
                    await sct.move_to_joint_angles_ptp(target, 0.5, 200)
            async with techmanpy.connect_sta(robot_ip="127.0.0.1") as sta:
                assert await sta.is_listen_node_active() is False

    asyncio.run(asyncio.wait_for(session(), 60))


def test_serve_from_a_notebook(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """``gpl2py.tmscript.node.serve()``: the notebook's way to what ``gpl2py run --listen-node`` starts."""
    from gpl2py.tmscript.node import serve

    node, slave = serve("TM12", port=0, svr_port=0)
    try:
        ports(node, slave, monkeypatch)

        async def session() -> None:
            async with techmanpy.connect_svr(robot_ip="127.0.0.1") as svr:
                assert await svr.get_value("Robot_Model") == "TM12"
            async with techmanpy.connect_sct(robot_ip="127.0.0.1") as sct:
                await sct.move_to_joint_angles_ptp([5, 5, 80, 5, 85, 5], 1.0, 100)
                await sct.set_queue_tag(1, wait_for_completion=True)
            async with techmanpy.connect_svr(robot_ip="127.0.0.1") as svr:
                assert near(await svr.get_value("Joint_Angle"), [5, 5, 80, 5, 85, 5])
        asyncio.run(asyncio.wait_for(session(), 60))
    finally:
        node.close()
        slave.close()


def test_declared_base_tcp_and_point_in_listen_node_scripts(tm_robot, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """TBase/TTCP/TPoint declared in one packet are used by name in the next (L15065, L16706)."""
    robot, node, slave = tm_robot
    ports(node, slave, monkeypatch)
    base = [100.0, 50.0, 20.0, 0.0, 0.0, 30.0]
    tool = [0.0, 0.0, 120.0, 0.0, 0.0, 0.0]

    async def session() -> None:
        async with techmanpy.connect_sct(robot_ip="127.0.0.1") as sct:
            tx = sct.start_transaction()
            tx.move_to_joint_angles_ptp([0, 10, 80, 0, 90, 0], 0.5, 200)
            tx.set_queue_tag(1, wait_for_completion=True)
            await tx.submit()
        # techmanpy sends only calls: the declarations go as a raw packet of the manual's form
        from gplrt.tm.packets import encode
        reader, writer = await asyncio.open_connection("127.0.0.1", node.port)
        script = ("TBase b1 = {" + ",".join(map(str, base)) + "}\r\nTTCP t1 = {" + ",".join(map(str, tool))
                  + "}, 1.5\r\nChangeBase(\"b1\")\r\nChangeTCP(\"t1\")\r\nTPoint p1 = 400, 0, 300, 180, 0, 90\r\n"
                  "Line(\"CAP\", Point[\"p1\"].Value, 200, 100, 0, false)\r\nQueueTag(2, 1)")
        writer.write(encode("TMSCT", b"7," + script.encode()))
        await writer.drain()
        reply = b""
        while b"7,OK" not in reply:
            reply += await asyncio.wait_for(reader.read(1000), 10)
        writer.close()
        async with techmanpy.connect_svr(robot_ip="127.0.0.1") as svr:
            assert near(await svr.get_value("Coord_Base_Tool"), [400, 0, 300, 180, 0, 90])
            joints = await svr.get_value("Joint_Angle")
            flange = pin.SE3(*_se3(urdf_flange(joints)))
            want = _pose_se3(base) * _pose_se3([400, 0, 300, 180, 0, 90]) * _pose_se3(tool).inverse()
            assert np.allclose(flange.homogeneous, want.homogeneous, atol=1e-8)
            assert await svr.get_value("TCP_Mass") == 1.5
    asyncio.run(asyncio.wait_for(session(), 60))


def _pose_se3(p: list[float]) -> pin.SE3:
    r = pin.rpy.rpyToMatrix(*np.radians(p[3:]))
    return pin.SE3(r, np.array(p[:3]) / 1000.0)


def _se3(p: list[float]) -> tuple[np.ndarray, np.ndarray]:
    m = _pose_se3(p)
    return m.rotation, m.translation
