"""Move.*: trajectories respect limits and end on target, straight lines stay straight, blends do not stop."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.lang.errors import GplException
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.queue import PathSegment
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.threads.thread import Thread


def angles(*v: float) -> Location:
    return Location.from_angles(v)


def profile(**kw: float | bool) -> Profile:
    p = Profile()
    for k, v in kw.items():
        setattr(p, k, v)
    return p


def check_limits(sim: Simulation, prof: Profile, t0: float, t1: float, n: int = 600, margin: float = 1e-9) -> None:
    """Joint velocities/accelerations read off the queue stay within the profile's limits."""
    robot = sim.robots[1]
    lim = robot.limits.joint_limits(prof, sim.controller.system_speed)
    amax = np.maximum(lim.accel, lim.decel)
    for t in np.linspace(t0, t1, n):
        q, v, a = robot.state_at(float(t))
        assert np.all(np.abs(v) <= lim.velocity * (1 + margin) + 1e-9), (t, v, lim.velocity)
        assert np.all(np.abs(a) <= amax * (1 + margin) + 1e-6), (t, a, amax)
        robot.check_joint_limits(q)


def test_joint_move_ends_exactly_on_target_and_wait_advances_virtual_time(sim: Simulation) -> None:
    target = (300.0, 10.0, 90.0, -100.0, 100.0)
    prof = profile(Speed=80.0)
    t_start = sim.now()
    Move.Loc(angles(*target), prof)
    assert sim.now() == t_start  # Move returns once the motion is queued
    seg = sim.robots[1].queue.last
    Move.WaitForEOM()
    assert math.isclose(sim.now(), seg.t0 + seg.duration, abs_tol=1e-9)
    assert Robot.WhereAngles().axis_values() == target
    check_limits(sim, prof, seg.t0, seg.end)


def test_waitforeom_before_any_motion_returns_at_once(sim: Simulation) -> None:
    # (an empty queue ends at -inf: the virtual clock's nanoseconds overflowed on it)
    t_start = sim.now()
    Move.WaitForEOM()
    assert sim.now() == t_start
    assert Robot.TrajState() == 1  # idle (TCS's label; 0 is "halted", power off)


def test_cartesian_joint_move_reaches_the_pose(sim: Simulation) -> None:
    goal = Location()
    goal.XYZ(400.0, 200.0, 300.0, 30.0, 90.0, 180.0)
    Move.Loc(goal, Profile())
    Move.WaitForEOM()
    where = Robot.Where()
    assert np.max(np.abs(where.matrix() - goal.matrix())) < 1e-9


def test_straight_move_stays_on_the_line_and_within_joint_limits(sim: Simulation) -> None:
    Move.Loc(angles(300.0, 10.0, 90.0, -100.0, 100.0), Profile())
    Move.WaitForEOM()
    start = Robot.Where()
    goal = start.Clone()
    goal.XYZ(start.X + 250.0, start.Y - 200.0, start.Z - 100.0, start.Yaw + 40.0, 90.0, 180.0)
    prof = profile(Straight=True, Speed=100.0, Accel=200.0, Decel=200.0)
    Move.Loc(goal, prof)
    seg = sim.robots[1].queue.last
    assert isinstance(seg, PathSegment)
    Move.WaitForEOM()
    p0, p1 = start.matrix()[:3, 3], goal.matrix()[:3, 3]
    d = (p1 - p0) / np.linalg.norm(p1 - p0)
    robot = sim.robots[1]
    for t in np.linspace(seg.t0, seg.end, 300):
        p = robot.forward(robot.joints_at(float(t)))[:3, 3]
        off = (p - p0) - np.dot(p - p0, d) * d
        assert np.linalg.norm(off) < 1e-6
        assert -1e-6 <= np.dot(p - p0, d) <= np.linalg.norm(p1 - p0) + 1e-6
    assert np.max(np.abs(Robot.Where().matrix() - goal.matrix())) < 1e-9
    check_limits(sim, prof, seg.t0, seg.end, margin=1e-3)


def test_straight_move_speed_is_the_cartesian_reference(sim: Simulation) -> None:
    """A long straight line away from singularities cruises at 2701[1] × Speed % (× SystemSpeed)."""
    Controller.SystemSpeed = 100.0  # it boots at DataID 601 (50 on this robot)
    Move.Loc(angles(300.0, 0.0, 90.0, 0.0, 100.0), Profile())
    Move.WaitForEOM()
    goal = Robot.Where()
    goal.Z = goal.Z + 600.0  # vertical: only the Z column moves
    Move.Loc(goal, profile(Straight=True, Speed=50.0))
    seg = sim.robots[1].queue.last
    Move.WaitForEOM()
    peak = max(abs(sim.robots[1].state_at(float(t))[1][0]) for t in np.linspace(seg.t0, seg.end, 400))
    assert math.isclose(peak, 250.0, rel_tol=1e-6)


def test_blended_sequence_never_stops_and_passes_within_tolerance(sim: Simulation) -> None:
    robot = sim.robots[1]
    Move.Loc(angles(300.0, -30.0, 90.0, 0.0, 100.0), Profile())
    Move.WaitForEOM()
    blend = profile(InRange=-5.0, Speed=100.0)
    vias = [angles(500.0, 0.0, 60.0, 20.0, 100.0), angles(500.0, 30.0, 100.0, 40.0, 100.0)]
    via_xyz = [robot.forward(np.array(v.axis_values()))[:3, 3] for v in vias]
    t_begin = sim.now()
    for v in vias:
        Move.Loc(v, blend)
    final = angles(300.0, 40.0, 120.0, 0.0, 100.0)
    Move.Loc(final, profile(Speed=100.0))
    Move.WaitForEOM()
    t_end = sim.now()
    times = np.linspace(t_begin + 0.02, t_end - 0.02, 800)
    speeds = [np.linalg.norm(robot.state_at(float(t))[1][:4]) for t in times]
    assert min(speeds) > 1.0  # joint-space speed never reaches zero between start and end
    xyz = np.array([robot.forward(robot.joints_at(float(t)))[:3, 3] for t in np.linspace(t_begin, t_end, 3000)])
    for p in via_xyz:
        assert np.min(np.linalg.norm(xyz - p, axis=1)) <= 5.0 + 1e-6
    assert Robot.WhereAngles().axis_values() == final.axis_values()
    check_limits(sim, blend, t_begin, t_end)
    # Without blending the same sequence stops at each via point and takes longer.
    stop = profile(InRange=0.0, Speed=100.0)
    Move.Loc(angles(300.0, -30.0, 90.0, 0.0, 100.0), Profile())
    Move.WaitForEOM()
    t0 = sim.now()
    for v in vias:
        Move.Loc(v, stop)
    Move.Loc(final, profile(Speed=100.0))
    Move.WaitForEOM()
    assert sim.now() - t0 > (t_end - t_begin) + 0.05


def test_inrange_positive_settles(sim: Simulation) -> None:
    q = angles(300.0, 10.0, 90.0, 0.0, 100.0)
    Move.Loc(q, profile(InRange=10.0))
    seg = sim.robots[1].queue.last
    Move.WaitForEOM()
    assert math.isclose(sim.now(), seg.t0 + seg.duration + 0.05, abs_tol=1e-9)  # DataID 2601


def test_system_speed_scales_joint_speed(sim: Simulation) -> None:
    Controller.SystemSpeed = 100.0  # it boots at DataID 601 (50 on this robot)
    target = angles(900.0, 0.0, 12.0, 0.0, 69.0)
    Move.Loc(target, profile(Speed=100.0, AccelRamp=0.0, DecelRamp=0.0))
    fast = sim.robots[1].queue.last
    Move.WaitForEOM()
    Controller.SystemSpeed = 50.0
    Move.Loc(angles(1.5, 0.0, 12.0, 0.0, 69.0), profile(Speed=100.0, AccelRamp=0.0, DecelRamp=0.0))
    slow = sim.robots[1].queue.last
    Move.WaitForEOM()
    peak = max(abs(sim.robots[1].state_at(float(t))[1][0]) for t in np.linspace(slow.t0, slow.end, 500))
    assert math.isclose(peak, 250.0, rel_tol=1e-6)
    assert slow.duration > fast.duration * 1.5


def test_delay_and_approach_and_rel_and_oneaxis(sim: Simulation) -> None:
    Move.Loc(angles(300.0, 10.0, 90.0, 0.0, 100.0), Profile())
    Move.Delay(0.5)
    t_queued_end = sim.robots[1].queue.end_time
    Move.WaitForEOM()
    assert sim.now() == pytest.approx(t_queued_end)
    assert sim.robots[1].queue.last.duration == 0.5
    place = Robot.Where()
    place.ZClearance, place.ZWorld = 450.0, True
    Move.Approach(place, Profile())
    Move.WaitForEOM()
    w = Robot.Where()
    assert (w.X, w.Y) == pytest.approx((place.X, place.Y), abs=1e-9) and w.Z == pytest.approx(450.0, abs=1e-9)
    place.ZWorld = False
    place.ZClearance = 50.0  # along the tool's -Z (a PF400 tool Z is horizontal, along the hand)
    Move.Approach(place, profile(Straight=True))
    Move.WaitForEOM()
    expected = place.matrix()[:3, 3] - 50.0 * place.matrix()[:3, 2]
    assert np.allclose(Robot.Where().matrix()[:3, 3], expected, atol=1e-9)
    before = Robot.WhereAngles().axis_values()
    Move.Rel(angles(10.0, 0.0, 0.0, 5.0), Profile())
    Move.WaitForEOM()
    after = Robot.WhereAngles().axis_values()
    assert np.allclose(np.subtract(after, before), [10.0, 0.0, 0.0, 5.0, 0.0], atol=1e-12)
    offset = Location()
    offset.XYZ(0.0, 0.0, 20.0)
    start = Robot.Where().matrix()
    Move.Rel(offset, profile(Straight=True))
    Move.WaitForEOM()
    assert np.allclose(Robot.Where().matrix(), start @ offset.matrix(), atol=1e-9)
    Move.OneAxis(5, 120.0, False, Profile())
    Move.OneAxis(1, -50.0, True, Profile())
    Move.WaitForEOM()
    q = Robot.WhereAngles().axis_values()
    assert q[4] == 120.0 and q[0] == pytest.approx(after[0] - 50.0, abs=1e-12)


def test_arc_and_circle_stay_on_the_circle(sim: Simulation) -> None:
    Move.Loc(angles(300.0, 0.0, 90.0, 0.0, 100.0), Profile())
    Move.WaitForEOM()
    robot = sim.robots[1]
    start = Robot.Where()
    centre = start.matrix()[:3, 3] + np.array([-60.0, 0.0, 0.0])
    mid, end = start.Clone(), start.Clone()
    mid.XYZ(centre[0], centre[1] + 60.0, centre[2], start.Yaw, 90.0, 180.0)
    end.XYZ(centre[0] - 60.0, centre[1], centre[2], start.Yaw + 30.0, 90.0, 180.0)
    # the arc start → mid → end, then the full circle end → start → mid → back to end
    for move, a, b in (("Arc", mid, end), ("Circle", start, mid)):
        getattr(Move, move)(a, b, profile(Speed=30.0))
        seg = robot.queue.last
        Move.WaitForEOM()
        for t in np.linspace(seg.t0, seg.end, 200):
            p = robot.forward(robot.joints_at(float(t)))[:3, 3]
            assert abs(np.linalg.norm(p - centre) - 60.0) < 1e-6 and abs(p[2] - centre[2]) < 1e-6
    # The arc ends at ``end``; the circle comes back to where it started (the arc's end).
    assert np.allclose(Robot.Where().matrix(), end.matrix(), atol=1e-9)


def test_extra_moves_the_rail_during_the_next_cartesian_motion() -> None:
    s = Simulation(robot="PF400SXL", capture=True)
    with s:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        Move.Loc(angles(200.0, 10.0, 90.0, 0.0, 100.0, 0.0), Profile())
        Move.WaitForEOM()
        goal = Robot.Where()
        Move.Extra(250.0)
        Move.Loc(goal, profile(Straight=True))
        Move.WaitForEOM()
        assert Robot.WhereAngles().axis_values()[5] == pytest.approx(250.0, abs=1e-9)
        assert np.allclose(Robot.Where().matrix(), goal.matrix(), atol=1e-9)


@pytest.mark.parametrize("model", ["PF400S", "PF3400SX", "GANTRY4", "ARM6"])
def test_other_robots_move_joint_and_straight(model: str) -> None:
    s = Simulation(robot=model, capture=True)
    with s:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.HomeAll()
        robot = s.robots[1]
        lo, hi = np.array(robot.model.lower_limits), np.array(robot.model.upper_limits)
        lo, hi = np.where(np.isfinite(lo), lo, -90.0), np.where(np.isfinite(hi), hi, 90.0)
        q = lo + 0.5 * (hi - lo)
        if model == "ARM6":
            q[1], q[2], q[4] = 20.0, 60.0, 40.0
        elif model.startswith("PF"):
            # mid-range is the folded arm (elbow 180°), the wrist next to the column: a line from
            # there asks the shoulder for more than it has (-3122; test_straight_line_past_the_column)
            q[2] = 90.0
        Move.Loc(angles(*q), Profile())
        Move.WaitForEOM()
        assert np.array_equal(robot.joints_at(s.now()), q)
        start = Robot.Where()
        goal = start.Clone()
        goal.XYZ(start.X + 20.0, start.Y + 10.0, start.Z - 15.0, start.Yaw, start.Pitch, start.Roll)
        Move.Loc(goal, profile(Straight=True))
        seg = robot.queue.last
        Move.WaitForEOM()
        assert np.max(np.abs(Robot.Where().matrix() - goal.matrix())) < 1e-9
        p0, p1 = start.matrix()[:3, 3], goal.matrix()[:3, 3]
        d = (p1 - p0) / np.linalg.norm(p1 - p0)
        for t in np.linspace(seg.t0, seg.end, 50):
            p = robot.forward(robot.joints_at(float(t)))[:3, 3]
            assert np.linalg.norm((p - p0) - np.dot(p - p0, d) * d) < 1e-6
        check_cycles_within_hard_limits(s, seg.t0, seg.t0 + seg.duration)


def test_real_clock_wait_sleeps_for_the_scaled_motion_time() -> None:
    import time

    s = Simulation(clock="real", speed=10.0, capture=True)
    with s:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        Move.Loc(angles(300.0, 10.0, 90.0, 0.0, 100.0), profile(Speed=100.0))
        seg = s.robots[1].queue.last
        t = time.perf_counter()
        Move.WaitForEOM()
        wall = time.perf_counter() - t
        assert s.now() >= seg.end
        assert 0.8 * (seg.end - seg.t0) / 10.0 < wall < (seg.end - seg.t0) / 10.0 + 0.5
        assert Robot.WhereAngles().axis_values() == (300.0, 10.0, 90.0, 0.0, 100.0)


def test_a_full_queue_makes_move_wait_for_room(sim: Simulation) -> None:
    """More motions than the queue holds: Move waits on the clock; mixed straight/joint blends run."""
    from gplrt.motion.robot import QUEUE_DEPTH

    a, b = Location(), Location()
    a.XYZ(400.0, 0.0, 300.0, 0.0, 90.0, 180.0)
    b.XYZ(400.0, 150.0, 300.0, 0.0, 90.0, 180.0)
    Move.Loc(a, Profile())
    Move.WaitForEOM()
    straight, joint = profile(Straight=True, InRange=-3.0), profile(InRange=-3.0)
    t0 = sim.now()
    for i in range(3 * QUEUE_DEPTH):
        Move.Loc(b if i % 2 == 0 else a, straight if i % 2 == 0 else joint)
        assert sim.robots[1].queue.pending(sim.now()) <= QUEUE_DEPTH
    assert sim.now() > t0  # some Move calls had to wait
    Move.WaitForEOM()
    assert np.max(np.abs(Robot.Where().matrix() - a.matrix())) < 1e-9
    cut = [seg.cut is not None for seg in sim.robots[1].queue.history[1:-1]]
    assert cut[0::2] == [True] * len(cut[0::2])  # every straight move blended into the joint move after it


def test_zero_length_straight_moves_finish_at_once_without_numeric_warnings(sim: Simulation) -> None:
    """Move.Rel by nothing in a straight line (a common "settle here" idiom) plans a motion of zero
    length: no NaN may enter the planner (it used to compute inf · 0 for the joints that do not move)."""
    import warnings

    Move.Loc(angles(300.0, 10.0, 90.0, -100.0, 100.0), Profile())
    Move.WaitForEOM()
    before = Robot.Where().matrix()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Move.Rel(Location.XYZValue(0.0, 0.0, 0.0, 0.0, 0.0, 0.0), profile(Straight=True))
        seg = sim.robots[1].queue.last
        Move.WaitForEOM()
    assert math.isfinite(seg.duration) and seg.duration < 1e-3
    assert np.max(np.abs(Robot.Where().matrix() - before)) < 1e-9


def off_line(p: np.ndarray, p0: np.ndarray, p1: np.ndarray) -> float:
    """Distance of ``p`` from the line through ``p0`` and ``p1``."""
    d = (p1 - p0) / np.linalg.norm(p1 - p0)
    return float(np.linalg.norm((p - p0) - np.dot(p - p0, d) * d))


def check_max_joint_speed(sim: Simulation, t0: float, t1: float, n: int = 600) -> None:
    """Joint speeds read off the queue stay within each joint's hard maximum (2700 × 2704 %):
    a straight line runs at its Cartesian speed, and a joint that would pass the maximum stops
    the motion with -3106 (path_run's decision)."""
    robot = sim.robots[1]
    for t in np.linspace(t0, t1, n):
        q, v, _ = robot.state_at(float(t))
        assert np.all(np.abs(v) <= robot.max_joint_speed * (1 + 1e-3)), (t, v)
        robot.check_joint_limits(q)


def check_cycles_within_hard_limits(sim: Simulation, t0: float, t1: float, at_rest_at_end: bool = True) -> None:
    """The joints read off the queue at the trajectory generator's 16 ms cycles from ``t0`` (a
    path motion's start, at rest) to ``t1``: every interval's mean speed within each joint's hard
    maximum (2700 × 2704 %) and every change of it within the hard maximum acceleration
    (2702 × 2705 %) — what the servos are asked for.  ``at_rest_at_end``: the motion ends at rest
    at ``t1`` (a motion a fault stopped is not: the stop itself is not a planned trajectory)."""
    from gplrt.motion.path_run import CYCLE

    robot = sim.robots[1]
    ts = [t0 + k * CYCLE for k in range(int((t1 - t0) / CYCLE) + 1) if t0 + k * CYCLE < t1 - CYCLE / 4] + [t1]
    q = np.array([robot.joints_at(t) for t in ts])
    dt = np.diff(ts)
    v = np.diff(q, axis=0) / dt[:, None]
    mids = np.concatenate(([t0], 0.5 * (np.array(ts[:-1]) + np.array(ts[1:]))))
    v_all = np.vstack((np.zeros(q.shape[1]), v))
    if at_rest_at_end:
        v_all, mids = np.vstack((v_all, np.zeros(q.shape[1]))), np.concatenate((mids, [t1]))
    a = np.diff(v_all, axis=0) / np.diff(mids)[:, None]
    assert np.all(np.abs(v) <= robot.limits.max_joint_speed * (1 + 1e-6)), np.abs(v).max(axis=0)
    assert np.all(np.abs(a) <= robot.limits.max_joint_accel * (1 + 1e-6)), np.abs(a).max(axis=0)


def stopped_on_the_line(sim: Simulation, start: Location, goal: Location, code: int, axis: int) -> float:
    """WaitForEOM reports the mid-path error (code, axis); the robot then rests on the line short
    of the goal, within its joint limits.  Returns the time it stopped at."""
    from gplrt.lang.errors import GplException

    robot = sim.robots[1]
    seg = robot.queue.last
    planned_end = seg.t0 + seg.duration
    with pytest.raises(GplException) as exc:
        Move.WaitForEOM()
    assert exc.value.ErrorCode == code and exc.value.Axis == axis
    assert sim.now() < planned_end  # it stopped before the planned end, and WaitForEOM returned there
    p0, p1 = start.matrix()[:3, 3], goal.matrix()[:3, 3]
    here = Robot.Where().matrix()[:3, 3]
    assert off_line(here, p0, p1) < 1e-6
    assert np.linalg.norm(here - p1) > 1e-3
    robot.check_joint_limits(robot.joints_at(sim.now()))
    later = robot.joints_at(sim.now() + 1.0)
    assert np.array_equal(later, robot.joints_at(sim.now()))  # at rest there
    for t in np.linspace(seg.t0, sim.now(), 200):
        assert off_line(robot.forward(robot.joints_at(float(t)))[:3, 3], p0, p1) < 1e-6
    check_max_joint_speed(sim, seg.t0, sim.now(), n=300)
    check_cycles_within_hard_limits(sim, seg.t0, sim.now(), at_rest_at_end=False)
    return sim.now()


def test_straight_line_past_the_column_stops_with_a_servo_error_or_runs_slower(sim: Simulation) -> None:
    """A line that passes close to the PF400's column makes the shoulder swing round in a few
    millimetres.  The controller plans the line's Cartesian profile and solves the joints each
    cycle: at full speed the shoulder would need more than its maximum acceleration there, and
    the motion stops on the line with -3122 *Soft envelope error* (axis 2) at WaitForEOM.
    (Before the cycle-by-cycle design this line was slowed at planning time by a joint analysis
    of the whole path.)  At a lower speed the same line runs through, on the line, within every
    joint's maximum speed and acceleration, exactly to the goal."""
    start_q = (552.002, 13.765, 306.24, -121.479, 80.431)
    Move.Loc(angles(*start_q), Profile())
    Move.WaitForEOM()
    start = Robot.Where()
    goal = start.Clone()
    goal.XYZ(-164.883, 44.756, start.Z - 34.81, start.Yaw - 39.469, 90.0, 180.0)
    p0, p1 = start.matrix()[:3, 3], goal.matrix()[:3, 3]
    closest = min(np.linalg.norm((p0 + s * (p1 - p0))[:2]) for s in np.linspace(0, 1, 2001))
    assert closest < 120.0  # the line really passes near the column (tool 162 mm: the wrist nearer)
    Move.Loc(goal, profile(Straight=True, Speed=100.0))  # accepted: both ends are fine
    stopped_on_the_line(sim, start, goal, -3122, 2)
    Move.Loc(angles(*start_q), Profile())  # reported once: the robot moves again
    Move.WaitForEOM()
    Move.Loc(goal, profile(Straight=True, Speed=20.0))
    seg = sim.robots[1].queue.last
    Move.WaitForEOM()
    robot = sim.robots[1]
    for t in np.linspace(seg.t0, seg.end, 400):
        assert off_line(robot.forward(robot.joints_at(float(t)))[:3, 3], p0, p1) < 1e-6
    check_max_joint_speed(sim, seg.t0, seg.end, n=1500)
    check_cycles_within_hard_limits(sim, seg.t0, seg.t0 + seg.duration)
    assert np.max(np.abs(Robot.Where().matrix() - goal.matrix())) < 1e-9


def test_random_straight_lines_run_on_the_line_or_stop_on_it_with_a_motion_error(sim: Simulation) -> None:
    """Seeded random lines across the PF400's workspace (many pass near the column, turn the tool
    and change height).  A line whose destination is unreachable is refused when queued; one
    accepted either runs to its goal exactly, on the line, within every joint's maximum speed and
    acceleration, or stops on the line with the mid-path error at WaitForEOM (the controller's IK
    each cycle).
    (This test asserted the Profile's joint speeds and accelerations along every line when the
    plan came from a joint analysis of the whole path; the straight-line speed is now the
    Cartesian one — path_run's module docstring.)"""
    from gplrt.lang.errors import GplException

    rng = np.random.default_rng(20261121)
    prof = profile(Straight=True, Speed=100.0)
    robot = sim.robots[1]
    completed = stopped = 0
    while completed < 16:
        q = rng.uniform([100, -90, 20, -300, 80], [900, 90, 340, 300, 120])
        Move.Loc(angles(*q), Profile())
        Move.WaitForEOM()
        start = Robot.Where()
        goal = start.Clone()
        r, a = rng.uniform(50.0, 600.0), rng.uniform(0.0, 2.0 * math.pi)
        goal.XYZ(r * math.cos(a), r * math.sin(a), start.Z + rng.uniform(-50, 50), start.Yaw + rng.uniform(-90, 90),
                 90.0, 180.0)
        try:
            Move.Loc(goal, prof)
        except GplException as exc:
            assert exc.ErrorCode in (-1012, -1039, -1040, -1033, -1042), (exc.ErrorCode, str(exc))
            assert Robot.WhereAngles().axis_values() == tuple(q)  # nothing was queued
            continue
        seg = robot.queue.last
        p0, p1 = start.matrix()[:3, 3], goal.matrix()[:3, 3]
        try:
            Move.WaitForEOM()
        except GplException as exc:
            assert exc.ErrorCode in (-1012, -1039, -1040, -1033, -3106, -3122)
            stopped += 1
            here = Robot.Where().matrix()[:3, 3]
            assert off_line(here, p0, p1) < 1e-6
            check_max_joint_speed(sim, seg.t0, sim.now(), n=100)
            check_cycles_within_hard_limits(sim, seg.t0, sim.now(), at_rest_at_end=False)
            continue
        completed += 1
        assert np.max(np.abs(Robot.Where().matrix() - goal.matrix())) < 1e-9
        check_max_joint_speed(sim, seg.t0, seg.end, n=250)
        check_cycles_within_hard_limits(sim, seg.t0, seg.t0 + seg.duration)
        for t in np.linspace(seg.t0, seg.end, 40):
            assert off_line(robot.forward(robot.joints_at(float(t)))[:3, 3], p0, p1) < 1e-6


def test_a_line_that_leaves_a_soft_limit_between_its_ends_stops_there_with_1012(sim: Simulation) -> None:
    """Both ends within J2's ±93°, but the shoulder bulges past +93° in between.  The controller
    plans the line (both ends are fine, so Move.Loc returns) and finds the limit in the cycle
    that would pass it: the robot stops on the line at the last good cycle, within the limit,
    and WaitForEOM raises -1012 with axis 2.  (This test asserted a refusal when queued, which
    needed the IK of the whole path at queue time.)"""
    q0 = (359.0, 77.02, 269.19, 84.96, 109.06)
    Move.Loc(angles(*q0), Profile())
    Move.WaitForEOM()
    start = Robot.Where()
    goal = Location.from_matrix(sim.robots[1].forward(np.array([378.07, 87.16, 269.19, -25.54, 101.24])))
    Move.Loc(goal, profile(Straight=True))
    t_stop = stopped_on_the_line(sim, start, goal, -1012, 2)
    assert Robot.WhereAngles().axis_values()[1] <= 93.0
    assert t_stop > sim.robots[1].queue.last.t0  # it did move first
    Move.Loc(angles(*q0), Profile())  # the error was reported once
    Move.WaitForEOM()
    assert Robot.WhereAngles().axis_values() == q0


def test_a_bulge_past_a_limit_in_the_first_cycles_stops_the_robot_at_once(sim: Simulation) -> None:
    """From J2 = 92.98° the shoulder first rises past +93° (to 93.03°) and then falls: the robot
    stops in the first cycles of the line with -1012 (axis 2), within the limit, on the line.
    (This test asserted a refusal when queued.)"""
    q0 = (305.85, 92.98, 330.99, 80.63, 93.97)
    Move.Loc(angles(*q0), Profile())
    Move.WaitForEOM()
    start = Robot.Where()
    goal = Location.from_matrix(sim.robots[1].forward(np.array([330.0, 61.61, 330.99, 85.52, 100.85])))
    Move.Loc(goal, profile(Straight=True))
    stopped_on_the_line(sim, start, goal, -1012, 2)
    assert Robot.WhereAngles().axis_values()[1] <= 93.0


def test_a_mid_path_error_reaches_the_next_motion_and_not_before_it_happens(sim: Simulation) -> None:
    """Without WaitForEOM the error stops the robot when it happens and the next Move of the
    thread raises it; reading the robot before that moment shows it moving, with no error."""
    from gplrt.lang.errors import GplException

    q0 = (359.0, 77.02, 269.19, 84.96, 109.06)
    Move.Loc(angles(*q0), Profile())
    Move.WaitForEOM()
    goal = Location.from_matrix(sim.robots[1].forward(np.array([378.07, 87.16, 269.19, -25.54, 101.24])))
    Move.Loc(goal, profile(Straight=True))
    seg = sim.robots[1].queue.last
    Thread.Sleep(10)  # a cycle in: the robot moves, nothing to report yet
    assert Robot.WhereAngles().axis_values() != q0
    Move.Loc(angles(*q0), Profile())  # queued behind the line
    Thread.Sleep(int(seg.duration * 1000) + 1000)
    with pytest.raises(GplException) as exc:
        Move.Loc(angles(*q0), Profile())
    assert exc.value.ErrorCode == -1012 and exc.value.Axis == 2
    assert len(sim.robots[1].queue.history) and sim.robots[1].queue.last is seg  # the rest was dropped
    assert Robot.WhereAngles().axis_values()[1] <= 93.0


def test_queueing_a_straight_line_solves_only_its_destination(sim: Simulation, monkeypatch: pytest.MonkeyPatch) -> None:
    """The controller's planning of a line: the destination's IK and the path profile; the joints
    along the way are solved as the motion runs (benchmarks/motion_speed.py times this)."""
    Move.Loc(angles(300.0, 10.0, 90.0, -100.0, 100.0), Profile())
    Move.WaitForEOM()
    model = sim.robots[1].model
    # (``inverse`` of a matrix goes through ``inverse_pose``: counting the latter counts every IK)
    calls = {"inverse_pose": 0, "inverse_path": 0}
    inverse_pose, inverse_path = model.inverse_pose, model.inverse_path

    def counted(name: str, fn):  # type: ignore[no-untyped-def]
        def wrapper(*a, **k):  # type: ignore[no-untyped-def]
            calls[name] += 1
            return fn(*a, **k)
        return wrapper

    monkeypatch.setattr(model, "inverse_pose", counted("inverse_pose", inverse_pose))
    monkeypatch.setattr(model, "inverse_path", counted("inverse_path", inverse_path))
    goal = Robot.Where()
    goal.XYZ(goal.X + 200.0, goal.Y - 150.0, goal.Z - 80.0, goal.Yaw + 30.0, 90.0, 180.0)
    Move.Loc(goal, profile(Straight=True))
    assert calls == {"inverse_pose": 1, "inverse_path": 0}
    Move.WaitForEOM()  # the cycles run now
    assert calls["inverse_pose"] + calls["inverse_path"] > 1
    assert np.max(np.abs(Robot.Where().matrix() - goal.matrix())) < 1e-9
