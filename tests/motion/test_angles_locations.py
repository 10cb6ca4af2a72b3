"""Angles Locations move robots with fewer axes than the Location holds (``loc.Angles`` stores 12)."""

from __future__ import annotations

from pathlib import Path

import pytest

from gplrt.geometry.location import Location
from gplrt.lang.errors import GplException
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gpltest import module_src, run_gpl


def test_angles_method_location_moves_a_five_axis_robot(sim: Simulation) -> None:
    loc = Location()
    loc.Angles(250.0, 10.0, 90.0, -20.0, 80.0)  # 12 values stored, the last 7 are 0
    Move.Loc(loc, Profile())
    Move.WaitForEOM()
    assert [float(v) for v in sim.robots[1].joints_at(sim.now())] == [250.0, 10.0, 90.0, -20.0, 80.0]


def test_values_beyond_the_robots_axes_are_ignored(sim: Simulation) -> None:
    loc = Location.from_angles([300.0, -5.0, 100.0, 15.0, 90.0, 7.0, -3.0])
    Move.Loc(loc, Profile())
    Move.WaitForEOM()
    assert [float(v) for v in sim.robots[1].joints_at(sim.now())] == [300.0, -5.0, 100.0, 15.0, 90.0]


def test_twelve_value_angles_location_works_for_straight_approach_and_rel(sim: Simulation) -> None:
    loc = Location()
    loc.Angles(250.0, 10.0, 90.0, -20.0, 80.0)
    straight = Profile()
    straight.Straight = True
    Move.Loc(loc, straight)
    Move.WaitForEOM()
    assert [round(float(v), 6) for v in sim.robots[1].joints_at(sim.now())] == [250.0, 10.0, 90.0, -20.0, 80.0]
    step = Location()
    step.Angles(5.0, 1.0)
    Move.Rel(step, Profile())
    Move.WaitForEOM()
    assert list(sim.robots[1].joints_at(sim.now())) == pytest.approx([255.0, 11.0, 90.0, -20.0, 80.0], abs=1e-9)
    loc.ZClearance = 50.0
    loc.ZWorld = True
    Move.Approach(loc, Profile())
    Move.WaitForEOM()
    assert Robot.Where().Z == pytest.approx(50.0, abs=1e-9)


def test_a_joint_beyond_the_robots_axes_still_out_of_range_on_its_own_axes(sim: Simulation) -> None:
    loc = Location()
    loc.Angles(250.0, 10.0, 90.0, -20.0, 10.0)  # gripper below its 69 mm limit
    with pytest.raises(GplException) as err:
        Move.Loc(loc, Profile())
    assert err.value.ErrorCode == -1012 and err.value.Axis == 5  # the gripper, not an axis the robot lacks


def test_where_angles_has_the_robots_axes(sim: Simulation) -> None:
    here = Robot.WhereAngles()
    assert here.Type == 1
    assert len(here.axis_values()) == 5
    assert here.Angle(6) == 0.0


def test_transpiled_gpl_moves_to_an_angles_location(tmp_path: Path) -> None:
    src = module_src("""
    Public Sub Main()
        Dim l As New Location
        Dim p As New Profile
        Dim w As Location
        l.Angles(250, 0, 90, 0, 100)
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        Move.Loc(l, p)
        Move.WaitForEOM
        w = Robot.WhereAngles
        Console.WriteLine(CStr(w.Angle(1)) & " " & CStr(w.Angle(3)) & " " & CStr(w.Angle(5)))
        Console.WriteLine(Format(Robot.Where.X, "0.000"))
    End Sub
    """)
    res = run_gpl(tmp_path, src)
    assert res.log == ""
    # PF400SX: l1 = 302 mm, l2 = 289 mm; J2 = 0, J3 = 90 -> X = 302
    assert res.output.splitlines()[0] == "250 90 100"
    assert res.output.splitlines()[1] == "302.000"
