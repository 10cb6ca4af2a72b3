"""TM motion on the shared core: PTP's pose configuration triplet (L17206–L17227) chooses the
core's closed-form branch; an out-of-reach target stops the project (L1095)."""

from __future__ import annotations

import numpy as np
import pytest

from gplrt.motion.kinematics import robot_model
from gpl2py.tmscript.pipeline import translate_packet
from gplrt.tm import context
from gplrt.tm.listen import Vars
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
