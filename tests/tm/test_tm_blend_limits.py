"""A blend into a path motion (``Line``, ``Circle``, ``PLine``) keeps every joint within its speed
(issue 22, item 1).  In the overlap the robot's joint rates are the sum of the two motions' (the
superposition is in joint space), so a Line that drives a joint the same way a fast PTP still
drives it would ask for more than the joint can do.  The manual names no error for a blend
(L15747, L15990), and a real robot does not exceed its joint speeds: the blend starts later (a
shorter overlap, the robot passing closer to the via point), as the core does for GPL.  A blend
that fits is not changed."""

from __future__ import annotations

import numpy as np
import pytest
from tmpacket import NodeClient

from gplrt.tm import motion
from gplrt.tm.packets import encode

HOME = [0.0, 0.0, 90.0, 0.0, 90.0, 0.0]
#: Controller seconds between the samples of the trajectory (a path's joints cost an inverse each).
STEP = 4e-3


def run(robot, port: int, text: str) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """Run ``text`` as one packet, waited for; (controller time before, after)."""
    c = NodeClient(port)
    try:
        robot.wait_idle()
        t0 = robot.clock.now()
        c.sock.sendall(encode("TMSCT", f"1,{text}\r\nQueueTag(1, 1)".encode()))
        frames = [c.reply(), c.reply()]
        assert encode("TMSCT", b"1,OK") in frames, frames
        return t0, robot.clock.now()
    finally:
        c.close()


def fastest(robot, t0: float, t1: float) -> np.ndarray:  # type: ignore[no-untyped-def]
    """Each joint's highest speed between controller times t0 and t1, as a share of its limit,
    from the robot's trajectory sampled every 4 ms."""
    ts = np.arange(t0, t1, STEP)
    q = np.array([robot.trajectory(float(t)) for t in ts])
    v = np.abs(np.diff(q, axis=0)) / STEP
    return np.max(v, axis=0) / np.array(robot.arm.speed)


def blend_into_line(robot, port: int, ptp_speed: int, blend: int) -> tuple[float, np.ndarray]:  # type: ignore[no-untyped-def]
    """From J1 = -150, a PTP home at ``ptp_speed`` % blending ``blend`` % into a Line that turns
    J1 the same way: (seconds of motion, fastest joint speeds); the Line's target is checked."""
    run(robot, port, 'PTP("JPP",-150,0,90,0,90,0,100,200,0,false)')
    home = robot.arm.fk(HOME)
    goal = [home[0] - 300.0, home[1] + 300.0, *home[2:]]
    before = robot.sim_time
    t0, t1 = run(robot, port, f'PTP("JPP",0,0,90,0,90,0,{ptp_speed},100,{blend},false)\r\n'
                              f'Line("CDP",{",".join(f"{x:.6f}" for x in goal)},400,100,0,false)')
    assert robot.arm.fk(robot.joints) == pytest.approx(goal, abs=1e-6)  # it ends on the line's target
    return robot.sim_time - before, fastest(robot, t0, t1)


def test_a_blend_that_would_overspeed_a_joint_starts_later_and_keeps_within_the_limits(tm_robot) -> None:  # type: ignore[no-untyped-def]
    robot, node, _ = tm_robot
    blended, speeds = blend_into_line(robot, node.port, 100, 100)
    assert np.all(speeds <= 1.0 + 1e-3), speeds  # (before: J1 at 1.24 times its speed)
    stopping, _ = blend_into_line(robot, node.port, 100, 0)
    assert blended < stopping  # still a blend: the robot does not stop at the via point


def test_a_blend_within_the_limits_is_not_delayed(tm_robot, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    robot, node, _ = tm_robot
    checked, speeds = blend_into_line(robot, node.port, 30, 100)
    assert np.all(speeds <= 1.0 + 1e-3), speeds
    monkeypatch.setattr(motion, "BLEND_LIMIT_SAFETY", np.inf)  # (no limit: the overlap as it was)
    unchecked, _ = blend_into_line(robot, node.port, 30, 100)
    assert checked == pytest.approx(unchecked, abs=1e-9)
    stopping, _ = blend_into_line(robot, node.port, 30, 0)
    assert checked < stopping
