"""TM motion on the shared core: PTP's pose configuration triplet (L17206–L17227) chooses the
core's closed-form branch; an out-of-reach target stops the project (L1095)."""

from __future__ import annotations

import socket

import numpy as np
import pytest

from gplrt.motion.kinematics import robot_model
from gpl2py.tmscript.pipeline import translate_packet
from gplrt.tm import context
from gplrt.tm.listen import Vars
from gplrt.tm.packets import encode
from gplrt.tm.robot import arm, config_bits
from gplrt.tm.values import TMError

HOME = [0.0, 0.0, 90.0, 0.0, 90.0, 0.0]


def run(script: str) -> Vars:
    """Translate a Listen-node packet and run it on the current robot."""
    p = translate_packet(script)
    assert not p.errors, [d.header() for d in p.errors]
    import gplrt.tm as tm

    ns: dict[str, object] = {"tm": tm}
    exec(compile(p.python, "<packet>", "exec"), ns)  # noqa: S102
    v = Vars()
    ns["script"](v)  # type: ignore[operator]
    return v


def test_the_tm_arm_is_the_shared_cores_model() -> None:
    a = arm("TM5-900")
    q = [12.0, -30.0, 95.0, 20.0, 70.0, -40.0]
    assert np.allclose(a.model.forward(q), robot_model("TM5-900").forward(q), atol=1e-12)


@pytest.mark.parametrize("triplet", [[0, 2, 4], [0, 3, 4], [0, 2, 5], [0, 3, 5], [1, 2, 4], [1, 3, 4]])
def test_ptp_cpp_pose_configuration_picks_the_branch(triplet: list[int]) -> None:
    robot = context.use_robot("TM5-900")
    a = robot.arm
    pose = a.fk([10.0, -20.0, 100.0, 10.0, 80.0, 30.0])
    coords = ", ".join(f"{v!r}" for v in pose)
    run(f'PTP("CPP", {coords}, 50, 200, 0, false, {triplet[0]}, {triplet[1]}, {triplet[2]})')
    robot.wait_idle()
    assert robot.error_code == 0, getattr(robot, "last_error", "")
    q = robot.current_joints()
    assert np.allclose(a.fk(q), pose, atol=1e-6)
    assert a.config(q) == triplet
    assert (q[2] >= 0) == (triplet[1] == 2) and (q[4] >= 0) == (triplet[2] == 4)


def test_ptp_cpp_pose_configuration_as_an_array() -> None:
    robot = context.use_robot("TM5-900")
    pose = robot.arm.fk([0.0, 10.0, 80.0, 0.0, 60.0, 0.0])
    run("float[] p = {" + ", ".join(f"{v!r}" for v in pose) + "}\nint[] c = {0, 3, 5}\n"
        "PTP(\"CPP\", p, 50, 200, 0, false, c)")
    robot.wait_idle()
    q = robot.current_joints()
    assert q[2] < 0 and q[4] < 0 and np.allclose(robot.flange(), pose, atol=1e-6)


def test_home_is_config_0_2_4_and_a_bad_triplet_is_refused() -> None:
    assert arm("TM5-900").config(HOME) == [0, 2, 4]
    with pytest.raises(TMError):
        config_bits([0, 4, 4])
    context.use_robot("TM5-900")
    with pytest.raises(TMError):
        run('PTP("CPP", 400, 0, 500, 180, 0, 90, 50, 200, 0, false, 2, 2, 4)')


FAR = 'PTP("CPP", 3000, 0, 500, 180, 0, 90, 50, 200, 0, false)'  # 3 m: beyond a TM5-900's reach


def test_an_unreachable_target_stops_the_listen_node_project(tm_robot) -> None:  # type: ignore[no-untyped-def]
    """The script is answered OK (the motion is only queued), then the motion cannot start: the
    project stops by error -- Error_Code set, Project_Run false, the node left, so the next
    script draws CPERR F1 and the status says the node is not active; entering anew clears it."""
    robot, node, slave = tm_robot
    with socket.create_connection(("127.0.0.1", node.port)) as s:
        f = s.makefile("rb")
        s.sendall(encode("TMSCT", ("1," + FAR).encode()))
        assert f.readline() == encode("TMSCT", b"1,OK")
        robot.wait_idle()
        s.sendall(encode("TMSCT", b"2,int after = 1"))
        assert f.readline() == encode("CPERR", b"F1")
    assert robot.error_code != 0 and robot.project_running is False
    assert node.result == "fail" and not node.active
    with socket.create_connection(("127.0.0.1", node.port)) as s:
        f = s.makefile("rb")
        s.sendall(encode("TMSCT", b"3,int after = 1"))
        assert f.readline() == encode("CPERR", b"F1")
        s.sendall(encode("TMSTA", b"00"))
        assert f.readline() == encode("TMSTA", b"00,false,")
    node.enter()
    assert robot.error_code == 0 and robot.project_running
    with socket.create_connection(("127.0.0.1", node.port)) as s:
        f = s.makefile("rb")
        s.sendall(encode("TMSCT", b"4,int after = 1"))
        assert f.readline() == encode("TMSCT", b"4,OK")


def test_an_unreachable_target_stops_the_project_like_the_robot(tmp_path) -> None:  # type: ignore[no-untyped-def]
    import subprocess
    import sys

    src = tmp_path / "far.tms"
    src.write_text('main\n{\n  PTP("JPP",0,0,90,0,90,0,50,200,0,false)\n  ' + FAR + '\n'
                   '  QueueTag(1, 1)\n  WaitQueueTag(1)\n  Display("after")\n}\n'
                   'errorstop\n{\n  IO["ControlBox"].DO[3] = 1\n  QueueTag(2, 1)\n  Display("errorstop ran " + IO["ControlBox"].DO[3])\n}\n')
    r = subprocess.run([sys.executable, "-m", "gpl2py", "run", str(src), "--robot", "TM5-900"],
                       capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert r.returncode == 1
    assert r.stdout.splitlines() == ["errorstop ran 1"]  # (errorstop's queued I/O still runs)
    assert "far.tms:4: error:" in r.stderr and "out of reach" in r.stderr
    assert "Traceback" not in r.stderr


def test_a_points_pose_configuration_reads_and_chooses_its_joints() -> None:
    """``Point[...].Pose`` (L14419): the triplet of the point's joints; setting it recomputes them."""
    context.use_robot("TM5-900")
    v = run('TPoint p2 = 400, -120, 300, 180, 0, 90\r\nint[] c0 = Point["p2"].Pose\r\n'
            'Point["p2"].Pose = {0, 3, 5}\r\nfloat[] j = Point["p2"].Joint\r\nint[] c = Point["p2"].Pose')
    assert list(v.c0) == [0, 2, 4] and list(v.c) == [0, 3, 5]
    a = arm("TM5-900")
    assert v.j[2] < 0 and v.j[4] < 0
    # (a float[] holds binary32: 1e-5 degree of a joint is ~1e-2 mm at the flange)
    assert np.allclose(a.fk([float(x) for x in v.j])[:3], [400, -120, 300], atol=0.05)
