"""Blending into straight lines (InRange < 0): corners rounded within |InRange|, the robot never stops."""

from __future__ import annotations

import numpy as np

from gplrt.geometry.location import Location
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.queue import BlendedPathSegment
from gplrt.sim import Simulation


def xyz(x: float, y: float, z: float, yaw: float = 0.0) -> Location:
    loc = Location()
    loc.XYZ(x, y, z, yaw, 90.0, 180.0)
    loc.Config = 2  # GPL_Lefty: these points are reachable in that branch
    return loc


def profile(**kw: float | bool) -> Profile:
    p = Profile()
    for k, v in kw.items():
        setattr(p, k, v)
    return p


def tool(sim: Simulation, t: float) -> np.ndarray:
    robot = sim.robots[1]
    return robot.forward(robot.joints_at(t))


def slowest(sim: Simulation, t0: float, t1: float, margin: float, n: int) -> float:
    """The lowest joint speed (norm over the four arm axes) sampled at ``n`` instants inside
    [t0 + margin, t1 - margin]: above zero means the robot did not stop in between (the margin
    skips the jerk-limited start and stop)."""
    robot = sim.robots[1]
    return min(float(np.linalg.norm(robot.state_at(float(t))[1][:4]))
               for t in np.linspace(t0 + margin, t1 - margin, n))


def distance_to_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    d = b - a
    s = float(np.clip(np.dot(p - a, d) / np.dot(d, d), 0.0, 1.0))
    return float(np.linalg.norm(p - (a + s * d)))


def run_corner(sim: Simulation, inrange: float) -> tuple[float, float, np.ndarray]:
    """Tool path of P0 -> P1 -> P2 in straight lines, blended at P1 with ``inrange``."""
    Move.Loc(xyz(350.0, -150.0, 250.0), profile())
    Move.WaitForEOM()
    t0 = sim.now()
    Move.Loc(xyz(450.0, 0.0, 250.0, 20.0), profile(Straight=True, InRange=inrange))
    Move.Loc(xyz(350.0, 150.0, 300.0, 40.0), profile(Straight=True))
    Move.WaitForEOM()
    t1 = sim.now()
    path = np.array([tool(sim, float(t))[:3, 3] for t in np.linspace(t0, t1, 1500)])
    return t0, t1, path


def test_straight_to_straight_rounds_the_corner_within_inrange_without_stopping(sim: Simulation) -> None:
    p0, p1, p2 = np.array([350.0, -150.0, 250.0]), np.array([450.0, 0.0, 250.0]), np.array([350.0, 150.0, 300.0])
    t0, t1, path = run_corner(sim, -10.0)
    assert isinstance(sim.robots[1].queue.last, BlendedPathSegment)
    # every point is within 10 mm of the corner polyline, and the corner itself is cut
    off = [min(distance_to_segment(p, p0, p1), distance_to_segment(p, p1, p2)) for p in path]
    assert max(off) <= 10.0 + 1e-6
    near = float(np.min(np.linalg.norm(path - p1, axis=1)))
    assert 0.5 < near <= 10.0 + 1e-6
    # the tool keeps moving between the two ends (the jerk-limited start and stop are slow: look inside them)
    assert slowest(sim, t0, t1, margin=0.1, n=600) > 1.0  # never stops
    # it ends exactly on P2, orientation included
    end = xyz(350.0, 150.0, 300.0, 40.0).matrix()
    assert np.max(np.abs(tool(sim, t1) - end)) < 1e-9
    # and the blended corner is faster than stopping at P1
    stop_t0, stop_t1, _ = run_corner(sim, 0.0)
    assert (stop_t1 - stop_t0) > (t1 - t0) + 0.05


def test_blend_is_continuous_in_velocity_where_the_line_starts(sim: Simulation) -> None:
    run_corner(sim, -10.0)
    seg = sim.robots[1].queue.last
    assert isinstance(seg, BlendedPathSegment) and seg.prev_end > seg.t0
    robot = sim.robots[1]
    _, v_before, _ = robot.state_at(seg.t0 - 1e-6)
    _, v_after, _ = robot.state_at(seg.t0 + 1e-6)
    assert np.max(np.abs(v_after - v_before)) < 1e-2 * max(1.0, float(np.max(np.abs(v_before))))
    _, v_end_before, _ = robot.state_at(seg.prev_end - 1e-6)
    _, v_end_after, _ = robot.state_at(seg.prev_end + 1e-6)
    assert np.max(np.abs(v_end_after - v_end_before)) < 1e-2 * max(1.0, float(np.max(np.abs(v_end_before))))


def test_joint_move_blends_into_a_straight_line(sim: Simulation) -> None:
    """The pick-and-place idiom: joint to the approach point, blended into the straight descent."""
    robot = sim.robots[1]
    Move.Loc(xyz(300.0, -250.0, 300.0), profile())
    Move.WaitForEOM()
    above, grip = xyz(450.0, 100.0, 330.0, 30.0), xyz(450.0, 100.0, 250.0, 30.0)
    t0 = sim.now()
    Move.Loc(above, profile(InRange=-5.0))
    Move.Loc(grip, profile(Straight=True, Speed=50.0))
    seg = robot.queue.last
    Move.WaitForEOM()
    t1 = sim.now()
    assert isinstance(seg, BlendedPathSegment)
    assert slowest(sim, t0, t1, margin=0.02, n=600) > 1.0  # never stops
    path = np.array([tool(sim, float(t))[:3, 3] for t in np.linspace(t0, t1, 2000)])
    assert float(np.min(np.linalg.norm(path - above.matrix()[:3, 3], axis=1))) <= 5.0 + 1e-6
    # once the joint move has run out, the tool is exactly on the line down to the grip point
    a, b = above.matrix()[:3, 3], grip.matrix()[:3, 3]
    for t in np.linspace(seg.prev_end, t1, 200):
        assert distance_to_segment(tool(sim, float(t))[:3, 3], a, b) < 1e-6
    assert np.max(np.abs(tool(sim, t1) - grip.matrix())) < 1e-9


def test_a_short_line_after_a_long_blend_still_ends_on_target(sim: Simulation) -> None:
    Move.Loc(xyz(300.0, -250.0, 300.0), profile())
    Move.WaitForEOM()
    t0 = sim.now()
    Move.Loc(xyz(450.0, 100.0, 300.0), profile(InRange=-50.0))
    Move.Loc(xyz(452.0, 100.0, 300.0), profile(Straight=True))  # 2 mm: shorter than the run-out
    Move.WaitForEOM()
    t1 = sim.now()
    assert np.max(np.abs(tool(sim, t1) - xyz(452.0, 100.0, 300.0).matrix())) < 1e-9
    assert slowest(sim, t0, t1, margin=0.02, n=400) > 0.1  # never stops (a stop samples < 1e-3)


def _on_circle(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> tuple[float, float]:
    """(distance from the circle through a, b, c in its plane, distance from its plane)."""
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    centre = a + (np.dot(ac, ac) * np.cross(n, ab) + np.dot(ab, ab) * np.cross(ac, n)) / (2.0 * np.dot(n, n))
    r = float(np.linalg.norm(a - centre))
    nn = n / np.linalg.norm(n)
    off_plane = float(np.dot(p - centre, nn))
    in_plane = p - centre - off_plane * nn
    return abs(float(np.linalg.norm(in_plane)) - r), abs(off_plane)


def test_joint_move_blends_into_an_arc_and_a_line_into_a_circle(sim: Simulation) -> None:
    """InRange < 0 blends into *the next queued motion*, arcs and circles included: the robot does
    not stop at the via point, passes within |InRange| of it, and after the overlap the tool is on
    the circle through the three points and ends exactly on target."""
    robot = sim.robots[1]
    Move.Loc(xyz(300.0, -250.0, 300.0), profile())
    Move.WaitForEOM()
    via, mid, end = xyz(400.0, 0.0, 300.0), xyz(430.0, 30.0, 300.0), xyz(400.0, 60.0, 300.0)
    t0 = sim.now()
    Move.Loc(via, profile(InRange=-5.0))
    Move.Arc(mid, end, profile(Straight=True, Speed=50.0))
    seg = robot.queue.last
    Move.WaitForEOM()
    t1 = sim.now()
    assert isinstance(seg, BlendedPathSegment) and seg.kind == "arc"
    # (the jerk-limited start and stop are slow: look inside them)
    assert slowest(sim, t0, t1, margin=0.05, n=600) > 1.0  # never stops
    path = np.array([tool(sim, float(t))[:3, 3] for t in np.linspace(t0, t1, 2000)])
    assert float(np.min(np.linalg.norm(path - via.matrix()[:3, 3], axis=1))) <= 5.0 + 1e-6
    a, b, c = (loc.matrix()[:3, 3] for loc in (via, mid, end))
    for t in np.linspace(seg.prev_end, t1, 200):
        radial, normal = _on_circle(tool(sim, float(t))[:3, 3], a, b, c)
        assert radial < 1e-6 and normal < 1e-6
    assert np.max(np.abs(tool(sim, t1) - end.matrix())) < 1e-9

    # a straight line blended into a full circle: no stop, back on the start point at the end
    start = xyz(350.0, 0.0, 280.0)
    t0 = sim.now()
    Move.Loc(start, profile(Straight=True, InRange=-3.0))
    Move.Circle(xyz(380.0, 30.0, 280.0), xyz(350.0, 60.0, 280.0), profile(Straight=True))
    seg = robot.queue.last
    Move.WaitForEOM()
    t1 = sim.now()
    assert isinstance(seg, BlendedPathSegment) and seg.kind == "circle"
    assert slowest(sim, t0, t1, margin=0.05, n=600) > 1.0  # never stops
    assert np.max(np.abs(tool(sim, t1)[:3, 3] - start.matrix()[:3, 3])) < 1e-9


def test_blend_overlap_keeps_joint_accelerations_within_limits(sim: Simulation) -> None:
    """Two joint moves blended into a straight line whose corner reverses the shoulder: while the
    joint move still brakes, the line already accelerates, and the two add up (the shoulder used
    to reach 125 % of its acceleration limit in the overlap).  The blend starts late enough for
    the sum to fit, and the robot still does not stop."""
    robot = sim.robots[1]
    Move.Loc(Location.from_angles([400.0, 0.0, 90.0, 0.0, 100.0]), profile())
    Move.WaitForEOM()
    t0 = sim.now()
    for (x, y, z, yaw), straight, inrange in (((418.7, 105.1, 348.0, 14.7), False, -44.3),
                                              ((254.1, 221.6, 383.0, 6.4), False, -40.7),
                                              ((338.8, -222.8, 495.9, -48.5), True, -33.4)):
        loc = xyz(x, y, z, yaw)
        loc.Config = 0
        Move.Loc(loc, profile(Speed=100.0, Straight=straight, InRange=inrange))
    line = robot.queue.last
    Move.WaitForEOM()
    t1 = sim.now()
    assert isinstance(line, BlendedPathSegment) and line.prev_end > line.t0  # still blended
    lim = robot.limits.joint_limits(profile(Speed=100.0), 100.0)
    amax, vmax = np.maximum(lim.accel, lim.decel), lim.velocity
    for t in np.linspace(t0, t1, 2500):
        _, v, a = robot.state_at(float(t))
        assert np.all(np.abs(v) <= vmax * (1 + 1e-3)), (t, v)
        assert np.all(np.abs(a) <= amax * (1 + 1e-3)), (t, a / amax)
    assert slowest(sim, t0, t1, margin=0.05, n=600) > 1.0  # never stops


def test_wide_blend_between_lines_keeps_the_tool_within_its_cartesian_speed(sim: Simulation) -> None:
    """InRange = -50 starts the second line while the first still cruises: the two tool speeds
    add up in the overlap (the tool reached 252 mm/s of 250).  The overlap starts late enough
    for their sum to stay within 2701[1] × Speed %, and the robot still does not stop."""
    robot = sim.robots[1]
    t0, t1, _ = run_corner(sim, -50.0)
    seg = robot.queue.last
    assert isinstance(seg, BlendedPathSegment) and seg.prev_end > seg.t0
    ts = np.linspace(t0, t1, 6000)
    path = np.array([tool(sim, float(t))[:3, 3] for t in ts])
    speed = np.linalg.norm(np.diff(path, axis=0), axis=1) / np.diff(ts)
    limit = robot.limits.path_limits(profile(Straight=True), 100.0).linear_velocity
    assert limit == 250.0  # 2701[1] = 500 mm/s at the default Speed of 50 %
    assert float(np.max(speed)) <= limit * (1 + 1e-6)
    assert float(np.min(speed[300:-300])) > 1.0
