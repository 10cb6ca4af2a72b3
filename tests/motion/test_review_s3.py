"""Review of the straight-line redesign (issue 5): behaviours a user hits, each test failing
before its fix.  The robot is the conftest's PF400SX, attached, powered and homed."""

from __future__ import annotations

import numpy as np
import pytest

from gplrt.geometry.location import Location
from gplrt.lang.errors import GplException
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.threads.thread import Thread

#: A line between these two postures bulges J2 past its +93° limit (test_midpath_transpiled).
BULGE_START = (359.0, 77.02, 269.19, 84.96, 109.06)
BULGE_GOAL = (378.07, 87.16, 269.19, -25.54, 101.24)


def angles(*v: float) -> Location:
    return Location.from_angles(v)


def ready_at(joints: tuple[float, ...]) -> None:
    """Attach robot 1, power it, home it and bring it to ``joints`` (a session of one's own)."""
    from gplrt.controller.services import Controller

    Robot.Attached = 1
    Controller.PowerEnabled = True
    Robot.Home()
    Move.Loc(angles(*joints), Profile())
    Move.WaitForEOM()


def straight(**kw: float) -> Profile:
    p = Profile()
    p.Straight = True
    for k, v in kw.items():
        setattr(p, k, v)
    return p


def queue_bulging_line(sim: Simulation) -> float:
    """Rest at BULGE_START, queue the line to BULGE_GOAL (accepted: both ends are fine); return
    the line's planned end.  It stops with -1012 (axis 2) about 1.0 s into its 1.67 s."""
    Move.Loc(angles(*BULGE_START), Profile())
    Move.WaitForEOM()
    goal = Location.from_matrix(sim.robots[1].forward(np.array(BULGE_GOAL)))
    Move.Loc(goal, straight())
    seg = sim.robots[1].queue.last
    return seg.t0 + seg.duration


def test_trajstate_and_dest_after_a_mid_path_stop_agree_with_where(sim: Simulation) -> None:
    """A program that polls TrajState (not Where) while a line runs: once the line has stopped
    on its fault, TrajState says idle and Dest is where the robot stopped — as they would had
    the program read Where first.  TrajState and Dest did not run the path's cycles: they said
    "executing" toward the planned goal until the planned end, so the answer depended on
    whether anything else had read the robot."""
    planned_end = queue_bulging_line(sim)
    Thread.Sleep(int((planned_end - sim.now() - 0.2) * 1000))  # past the stop, short of the planned end
    assert sim.now() < planned_end
    state, dest = Robot.TrajState(), Robot.DestAngles().axis_values()
    here = Robot.WhereAngles().axis_values()
    assert here[1] <= 93.0 and here != BULGE_GOAL  # stopped on the line, short of the goal
    assert state == 1  # idle
    assert dest == here
    assert Robot.TrajState() == 1
    with pytest.raises(GplException) as exc:
        Move.WaitForEOM()
    assert exc.value.ErrorCode == -1012 and exc.value.Axis == 2


def test_straight_move_to_angles_in_the_other_elbow_branch_is_refused(sim: Simulation) -> None:
    """A straight line keeps the arm's branch (-1042 for a Cartesian Location whose Config asks
    for the other one).  An Angles Location names its branch through its joints: a straight move
    to Lefty angles from a Righty arm was accepted and ended on the Righty mirror posture (same
    tool pose, other joints), so WhereAngles did not report the angles the program moved to.
    In the arm's own branch the line ends on the angles exactly."""
    start = (300.0, 10.0, 90.0, -100.0, 100.0)
    Move.Loc(angles(*start), Profile())
    Move.WaitForEOM()
    with pytest.raises(GplException) as exc:
        Move.Loc(angles(300.0, 60.0, 300.0, 0.0, 90.0), straight())  # Lefty: J3 in [180°, 360°)
    assert exc.value.ErrorCode == -1042
    Move.WaitForEOM()
    assert Robot.WhereAngles().axis_values() == start  # nothing moved
    same_branch = (350.0, 20.0, 80.0, -90.0, 90.0)
    Move.Loc(angles(*same_branch), straight())
    Move.WaitForEOM()
    assert np.allclose(Robot.WhereAngles().axis_values(), same_branch, rtol=0.0, atol=1e-9)


@pytest.mark.parametrize("sim", ["PF400SXL"], indirect=True)
def test_extra_waits_for_the_next_cartesian_motion_past_a_straight_move_to_angles(sim: Simulation) -> None:
    """Move.Extra sets the rail for the next motion to a Cartesian Location (move.py): an Angles
    Location carries its own rail value.  A joint move to Angles left the Extra pending, but a
    straight one consumed it and ignored it, so the Cartesian move after it left the rail where
    it was."""
    Move.Loc(angles(200.0, 10.0, 90.0, 0.0, 100.0, 0.0), Profile())
    Move.WaitForEOM()
    goal = Robot.Where()
    Move.Extra(250.0)
    Move.Loc(angles(220.0, 20.0, 80.0, 0.0, 100.0, 0.0), straight())  # the rail stays at 0 (its angle)
    Move.WaitForEOM()
    assert Robot.WhereAngles().axis_values()[5] == 0.0
    Move.Loc(goal, Profile())  # the motion to a Cartesian Location the Extra was for
    Move.WaitForEOM()
    assert Robot.WhereAngles().axis_values()[5] == pytest.approx(250.0, abs=1e-9)
    assert np.allclose(Robot.Where().matrix(), goal.matrix(), atol=1e-9)


def test_source_after_a_mid_path_stop_is_the_start_of_the_motion_that_ran(sim: Simulation) -> None:
    """A line stopped mid-path drops the motion queued behind it.  Source ("start of the last
    queued motion") went on reporting that dropped motion's start — the line's planned goal,
    where the robot never was — instead of the start of the line that ran."""
    planned_end = queue_bulging_line(sim)
    Move.Loc(angles(*BULGE_START), Profile())  # queued behind the line; dropped by its stop
    Thread.Sleep(int((planned_end - sim.now() + 0.5) * 1000))
    here = Robot.WhereAngles().axis_values()
    assert here[1] <= 93.0 and Robot.DestAngles().axis_values() == here  # stopped, the rest dropped
    assert Robot.SourceAngles().axis_values() == BULGE_START
    with pytest.raises(GplException) as exc:
        Move.WaitForEOM()
    assert exc.value.ErrorCode == -1012


def off_line(p: np.ndarray, p0: np.ndarray, p1: np.ndarray) -> float:
    """Distance of ``p`` from the line through ``p0`` and ``p1``."""
    d = (p1 - p0) / np.linalg.norm(p1 - p0)
    return float(np.linalg.norm((p - p0) - np.dot(p - p0, d) * d))


@pytest.mark.parametrize("change", ["Tool", "Base"])
@pytest.mark.parametrize("inrange", [0.0, -10.0])
def test_tool_or_base_set_after_queueing_lines_does_not_change_them(sim: Simulation, change: str,
                                                                    inrange: float) -> None:
    """Robot.Tool/Base apply to later motions (robot_class): a program that queues a line and
    then sets the Tool for the next pick (a second gripper) must see the line run as queued.
    The line's cycles, solved as it runs, took the new Tool: the flange jumped by the offset and
    the line stopped at its first cycle with -3122."""
    robot = sim.robots[1]
    Move.Loc(angles(300.0, 10.0, 90.0, -100.0, 100.0), Profile())
    Move.WaitForEOM()
    here = Robot.Where()
    first, second = here.Clone(), here.Clone()
    first.XYZ(here.X + 80.0, here.Y - 40.0, here.Z, here.Yaw + 20.0, here.Pitch, here.Roll)
    second.XYZ(first.X + 60.0, first.Y + 30.0, first.Z + 20.0, first.Yaw, first.Pitch, first.Roll)
    Move.Loc(first, straight(InRange=inrange))
    Move.Loc(second, straight())
    segs = robot.queue.history[-2:]
    tool, base = robot.model.tool, robot.model.base
    offset = Location()
    offset.XYZ(5.0, -10.0, 200.0 if change == "Tool" else 30.0, 15.0, 0.0, 0.0)
    getattr(Robot, f"set_{change}")(offset)
    Move.WaitForEOM()  # no error: the lines run as they were queued
    p = [here.matrix()[:3, 3], first.matrix()[:3, 3], second.matrix()[:3, 3]]
    for k, seg in enumerate(segs):
        if inrange == 0.0:  # (a blend leaves the lines at the corner)
            for t in np.linspace(seg.t0, seg.end, 50):
                tip = base @ robot.model.flange(robot.joints_at(float(t))) @ tool  # the Tool it was queued with
                assert off_line(tip[:3, 3], p[k], p[k + 1]) < 1e-6
    end = base @ robot.model.flange(robot.joints_at(sim.now())) @ tool
    assert np.max(np.abs(end - second.matrix())) < 1e-9


def test_a_move_queued_as_another_thread_finds_the_stop_raises_it(monkeypatch: pytest.MonkeyPatch) -> None:
    """Real clock: a thread queues a line and then the next motion, while another thread reads
    Robot.Where.  If the reader's read finds the line's mid-path stop between the mover's
    checks and its queueing (forced here: the mover's checks wait for it), the next motion was
    queued after the stop as if nothing had happened — the robot moved on, and the error came
    one Move late.  The queueing itself must refuse it, as a Move after the stop does."""
    import threading

    from gplrt.motion.robot import RobotState

    sim = Simulation(clock="real", speed=4.0, capture=True)
    found = threading.Event()
    outcome: list[object] = []
    armed: list[bool] = []
    check = RobotState.check_can_move

    def check_then_wait(self: RobotState, key: object, power_on: bool) -> None:
        check(self, key, power_on)
        if armed:  # the move after the line
            assert found.wait(10.0)  # the reader has found the stop meanwhile

    def reader() -> None:
        robot = sim.robots[1]
        while robot.queue.fault is None:
            Robot.Where(1)
            Thread.Sleep(5)
        found.set()

    def main() -> None:
        ready_at(BULGE_START)
        goal = Location.from_matrix(sim.robots[1].forward(np.array(BULGE_GOAL)))
        monkeypatch.setattr(RobotState, "check_can_move", check_then_wait)
        Move.Loc(goal, straight())
        armed.append(True)
        watcher = Thread(reader, 0, "reader")
        watcher.Start()
        try:
            Move.Loc(angles(*BULGE_START), Profile())
            outcome.append("queued")
        except GplException as exc:
            outcome.append(exc.ErrorCode)
        watcher.Join()

    sim.run_main(main)
    assert outcome == [-1012]


def test_a_trace_taken_before_a_mid_path_stop_does_not_bring_it_forward() -> None:
    """A program (or a notebook) that takes a trace while a line runs must not learn of a stop
    that has not happened yet: the next Move before it is queued as usual, and the error comes
    at WaitForEOM when the robot stops — exactly as without the trace."""

    def run(with_trace: bool) -> tuple[float, int, tuple[float, ...]]:
        s = Simulation(capture=True)
        with s:
            ready_at(BULGE_START)
            goal = Location.from_matrix(s.robots[1].forward(np.array(BULGE_GOAL)))
            Move.Loc(goal, straight())
            Thread.Sleep(10)  # the line is under way; its stop is later
            if with_trace:
                tr = s.trace(1)
                assert tr.times[-1] <= s.now() + 1e-9  # what has happened, not what will
            Move.Loc(angles(*BULGE_START), Profile())  # queued behind the line: no error yet
            with pytest.raises(GplException) as exc:
                Move.WaitForEOM()
            return s.now(), exc.value.ErrorCode, Robot.WhereAngles().axis_values()

    assert run(with_trace=True) == run(with_trace=False)
