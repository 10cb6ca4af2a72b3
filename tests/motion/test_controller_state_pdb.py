"""``Controller.PDb``/``PDbNum`` writes to the motion DataIDs reach the limits later motions use.

The reference for every check is a robot *built* from a database that already had the new value
(``RobotLimits.from_pdb`` at boot): a motion after a run-time write must plan exactly like it.
2700-2703 need power off (-1522 *Cannot write value when power on*, the value unchanged);
2704-2706, 2101 and 2601 may change with power on (gplrt.controller.services.NEEDS_POWER_OFF).
"""

from __future__ import annotations

import gc
import weakref
from collections.abc import Callable

import numpy as np
import pytest

from gplrt.controller.pdb import default_database
from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.lang.errors import GplException
from gplrt.motion import registry
from gplrt.session import current_session
from gplrt.motion.limits import RobotLimits
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation

START = Location.from_angles((300.0, 10.0, 90.0, 0.0, 100.0))
GOAL = Location.from_angles((900.0, 60.0, 150.0, 30.0, 100.0))


def fast() -> Profile:
    prof = Profile()
    prof.Speed, prof.Accel, prof.Decel = 150.0, 300.0, 300.0  # at the 2704-2706 caps
    return prof


def ready() -> None:
    Robot.Attached = 1
    Controller.PowerEnabled = True
    Robot.Home()
    Move.Loc(START, Profile())
    Move.WaitForEOM()


def move_duration(prof: Profile, goal: Location = GOAL) -> float:
    """Queue one joint move from rest and return its planned duration (settling included)."""
    Move.Loc(goal, prof)
    seg = current_session().robots[1].queue.last
    duration = float(seg.end - seg.t0)
    Move.WaitForEOM()
    return duration


def reference(edit: Callable[[object], None], prof: Profile, goal: Location = GOAL) -> float:
    """The same move on a robot built from a database that had ``edit`` applied at boot."""
    s = Simulation(capture=True)
    with s:
        edit(registry.pdb_of(s))  # before the robot is built: RobotLimits.from_pdb reads it
        ready()
        return move_duration(prof, goal)


def test_cap_writes_with_power_on_apply_to_the_next_motion() -> None:
    s = Simulation(capture=True)
    with s:
        ready()
        before = move_duration(fast(), GOAL)
        Move.Loc(START, fast())
        Move.WaitForEOM()
        Controller.set_PDbNum(2704, 40.0)  # Max %speed allowed: 150 -> 40
        Controller.set_PDbNum(2705, 1, 1, 1, 50.0)  # Max %accel (unit, unit2, index given)
        Controller.set_PDb(2706, "60")  # Max %decel, as text
        assert Controller.PDbNum(2704) == 40.0
        after = move_duration(fast(), GOAL)

    def edit(db: object) -> None:
        db.set(2704, 40.0, index=1)  # type: ignore[attr-defined]
        db.set(2705, 50.0, index=1)  # type: ignore[attr-defined]
        db.set(2706, 60.0, index=1)  # type: ignore[attr-defined]

    expected = reference(edit, fast())
    assert after > before * 1.5
    assert after == pytest.approx(expected, abs=1e-9)


def _line_there_and_back(prof: Profile) -> float:
    """A straight line out and back from a Cartesian start: the planned duration of the return."""
    start, goal = Location(), Location()
    start.XYZ(400.0, 0.0, 300.0, 0.0, 90.0, 180.0)
    goal.XYZ(450.0, 100.0, 250.0, 0.0, 90.0, 180.0)
    Move.Loc(start, Profile())
    Move.Loc(goal, prof)
    Move.Loc(start, prof)
    seg = current_session().robots[1].queue.last
    Move.WaitForEOM()
    return float(seg.end - seg.t0)


def test_cap_writes_with_power_on_apply_to_the_next_straight_line() -> None:
    """A straight line's limits are memoised per Profile (``RobotLimits.line_limits``): a write
    must reach the next line as it reaches the next joint move."""
    line = fast()
    line.Straight = True
    s = Simulation(capture=True)
    with s:
        ready()
        before = _line_there_and_back(line)
        Controller.set_PDbNum(2704, 40.0)  # Max %speed allowed: 150 -> 40
        after = _line_there_and_back(line)

    def edit(db: object) -> None:
        db.set(2704, 40.0, index=1)  # type: ignore[attr-defined]

    s = Simulation(capture=True)
    with s:
        edit(registry.pdb_of(s))
        ready()
        expected = _line_there_and_back(line)
    assert after > before * 1.5
    assert after == pytest.approx(expected, abs=1e-9)


def test_the_hard_speed_cap_used_along_paths_follows_2704() -> None:
    s = Simulation(capture=True)
    with s:
        ready()
        robot = s.robots[1]
        assert np.allclose(robot.max_joint_speed, robot.limits.joint_speed * 1.5)
        Controller.set_PDbNum(2704, 80.0)
        assert np.allclose(robot.max_joint_speed, robot.limits.joint_speed * 0.8)


def test_reference_speed_and_accel_need_power_off() -> None:
    s = Simulation(capture=True)
    with s:
        ready()
        for data_id in (2700, 2701, 2702, 2703):
            old = Controller.PDbNum(data_id)
            err = pytest.raises(GplException, Controller.set_PDbNum, data_id, old / 2).value
            assert err.ErrorCode == -1522
            assert Controller.PDbNum(data_id) == old  # not written
        before = move_duration(fast(), GOAL)
        Move.Loc(START, fast())
        Move.WaitForEOM()
        Controller.PowerEnabled = False
        Controller.set_PDb(2700, "250, 180, 360, 360, 200")  # half of the PF400SX's 100 % speeds
        Controller.set_PDbNum(2702, 1, 1, 2, 300.0)  # J2 acceleration halved
        Controller.PowerEnabled = True
        after = move_duration(fast(), GOAL)

    def edit(db: object) -> None:
        db.set(2700, [250.0, 180.0, 360.0, 360.0, 200.0])  # type: ignore[attr-defined]
        db.set(2702, 300.0, index=2)  # type: ignore[attr-defined]

    assert after > before * 1.2
    assert after == pytest.approx(reference(edit, fast()), abs=1e-9)


def test_settling_time_write_applies_to_inrange_motions() -> None:
    settle = Profile()
    settle.InRange = 10.0
    s = Simulation(capture=True)
    with s:
        ready()
        Controller.set_PDbNum(2601, 0.25)
        Move.Loc(GOAL, settle)
        assert s.robots[1].queue.last.settle == 0.25
        Move.WaitForEOM()


def test_rapid_decel_percent_write_applies_to_the_next_rapid_decel() -> None:
    def stop_time(at_run_time: float | None, at_boot: float | None) -> float:
        s = Simulation(capture=True)
        with s:
            if at_boot is not None:
                registry.pdb_of(s).set(2101, at_boot, index=1)
            ready()
            if at_run_time is not None:
                Controller.set_PDbNum(2101, at_run_time)
            Move.Loc(GOAL, Profile())
            s.scheduler.sleep(0.3)
            Robot.set_RapidDecel(True)
            return float(s.robots[1].rapid_decel_until - s.now())

    full, written = stop_time(None, None), stop_time(50.0, None)
    assert written > full * 1.2  # a gentler stop takes longer
    assert written == pytest.approx(stop_time(None, 50.0), abs=1e-9)


def test_a_motion_queued_before_the_write_keeps_its_plan() -> None:
    s = Simulation(capture=True)
    with s:
        ready()
        Move.Loc(GOAL, fast())
        seg = s.robots[1].queue.last
        end = seg.end
        Controller.set_PDbNum(2704, 20.0)
        assert s.robots[1].queue.last is seg and seg.end == end
        Move.WaitForEOM()
        assert Robot.WhereAngles().axis_values() == GOAL.axis_values()


def test_a_write_to_a_data_id_the_limits_do_not_read_keeps_their_memo() -> None:
    s = Simulation(capture=True)
    with s:
        ready()
        limits = s.robots[1].limits
        lim = limits.joint_limits(fast(), 100.0)
        Controller.set_PDbNum(601, 30.0)  # not a limit DataID: the memo stays
        assert limits.joint_limits(fast(), 100.0) is lim


def test_reload_drops_the_memo_and_updates_in_place() -> None:
    s = Simulation(capture=True)
    with s:
        db = registry.pdb_of(s)
        limits = RobotLimits.from_pdb(db, 1, 5)
        prof = fast()
        lim = limits.joint_limits(prof, 100.0)
        assert limits.joint_limits(prof, 100.0) is lim  # memoised
        db.set(2700, 100.0, index=1)
        limits.reload(db, 1, 5)
        new = limits.joint_limits(prof, 100.0)
        assert new is not lim
        assert new.velocity[0] == pytest.approx(100.0 * 1.5, abs=1e-12)
        assert new.velocity[1] == lim.velocity[1]


def test_a_database_shared_by_sessions_does_not_keep_a_finished_session_alive() -> None:
    """A program's database may outlive its session (a notebook sets one ``sim.pdb`` on each new
    Simulation).  The write listener a session registers on it must not keep that session — and
    its robots' planned motion — alive once it is closed and dropped, nor pile up per session."""
    db = default_database("PF400SX")
    with Simulation(capture=True):  # the session active around the others (a notebook's own)
        first = Simulation(capture=True)
        first.pdb = db
        with first:
            ready()  # builds robot 1: the session starts listening to ``db``
        first.close()
        gone = weakref.ref(first)
        del first
        gc.collect()
        assert gone() is None
        second = Simulation(capture=True)
        second.pdb = db
        with second:
            ready()
            Controller.set_PDbNum(2704, 40.0)  # still reaches the live session's robot
            assert second.robots[1].limits.max_speed_pct == 40.0
            assert len(db.listeners) == 1  # the dropped session's listener went with it


def test_a_write_for_one_robot_reloads_that_robot_only() -> None:
    s = Simulation(robot="XYZT-GCU", capture=True)  # robot 2 (the gripper) has no 2704 shipped
    with s:
        registry.pdb_of(s).define(2704, [150.0], unit=2)
        first, second = registry.robot_of(s, 1), registry.robot_of(s, 2)
        lim = first.limits.joint_limits(fast(), 100.0)
        Controller.set_PDbNum(2704, 2, 1, 1, 40.0)  # robot 2's Max %speed
        assert second.limits.max_speed_pct == 40.0
        assert first.limits.max_speed_pct != 40.0
        assert first.limits.joint_limits(fast(), 100.0) is lim
