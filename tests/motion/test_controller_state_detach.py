"""``Robot.Attached = 0`` on a moving robot raises -1008 *Can't detached a moving robot*
(gpl-dictionary.md); an idle robot detaches; a thread that ends or is aborted while its robot
moves still releases it (the controller's clean-up, not a GPL detach)."""

from __future__ import annotations

import threading
from pathlib import Path

import numpy as np
import pytest

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.lang.errors import GplException
from gplrt.motion import registry
from gplrt.motion.move import Move
from gplrt.motion.path_run import PathRun
from gplrt.motion.profile import Profile
from gplrt.motion.robot import RobotState
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gplrt.threads.thread import Thread
from gpltest import code_of, module_src, run_gpl

FAR = Location.from_angles((1100.0, 10.0, 90.0, 0.0, 100.0))
NEAR = Location.from_angles((300.0, 10.0, 90.0, 0.0, 100.0))


def test_detach_while_moving_raises_1008_and_keeps_the_robot_attached(sim: Simulation) -> None:
    Move.Loc(FAR, Profile())
    err = pytest.raises(GplException, setattr, Robot, "Attached", 0).value
    assert (err.ErrorCode, err.RobotError, err.RobotNum) == (-1008, True, 1)
    assert Robot.Attached == 1
    assert Controller.PowerState() == 21  # still "robot attached by a GPL project"
    Move.WaitForEOM()
    Robot.Attached = 0
    assert Robot.Attached == 0 and Controller.PowerState() == 20
    assert Robot.WhereAngles().axis_values() == FAR.axis_values()


def test_detach_of_an_idle_robot_works(sim: Simulation) -> None:
    Robot.Attached = 0  # never moved
    assert Robot.Attached == 0
    Robot.Attached = 1
    Move.Loc(NEAR, Profile())
    Move.WaitForEOM()
    Robot.Attached = 0
    assert Robot.Attached == 0


def test_detach_during_a_dwell_or_settling_is_a_moving_robot(sim: Simulation) -> None:
    Move.Delay(0.5)
    assert Robot.TrajState() == 3  # a Move.Delay holds the set-point (module docstring of robot_class)
    assert code_of(setattr, Robot, "Attached", 0) == -1008
    sim.scheduler.sleep(0.5)
    assert Robot.TrajState() == 1  # idle
    Robot.Attached = 0
    Robot.Attached = 1
    prof = Profile()
    prof.InRange = 10.0  # settles for DataID 2601 (0.05 s) after the motion
    Move.Loc(NEAR, prof)
    sim.scheduler.sleep_until(sim.robots[1].queue.last.motion_end + 0.01)
    assert Robot.TrajState() == 15  # "Motion terminated nulling" (TCS's label): settling
    assert code_of(setattr, Robot, "Attached", 0) == -1008
    Move.WaitForEOM()
    Robot.Attached = 0


def test_detach_just_after_the_motion_ends_works(sim: Simulation) -> None:
    Move.Loc(NEAR, Profile())
    end = sim.robots[1].queue.end_time
    sim.scheduler.sleep_until(end)
    Robot.Attached = 0
    assert Robot.Attached == 0


@pytest.mark.parametrize("sim", ["XYZT-GCU"], indirect=True)  # a gantry and a second robot
def test_attaching_another_robot_while_the_first_moves_is_refused(sim: Simulation) -> None:
    vals = list(Robot.WhereAngles().axis_values())
    vals[0] += 200.0
    Move.Loc(Location.from_angles(vals), Profile())
    assert code_of(setattr, Robot, "Attached", 2) == -1008
    assert Robot.Attached == 1 and sim.robots[2].owner is None
    Move.WaitForEOM()
    Robot.Attached = 2
    assert Robot.Attached == 2 and sim.robots[1].owner is None


@pytest.mark.parametrize("abort", [False, True])
def test_thread_end_or_abort_releases_a_moving_robot(abort: bool) -> None:
    s = Simulation(capture=True)
    seen: list[object] = []

    def mover() -> None:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        Move.Loc(FAR, Profile())
        if abort:
            Thread.Sleep(60_000)

    def main() -> None:
        w = Thread(mover, 0, "mover")
        w.Start()
        while s.robots.get(1) is None or s.robots[1].queue.last is None:
            Thread.Sleep(10)
        if abort:
            w.Abort()
        w.Join()
        seen.append(Robot.TrajState(1) in (2, 3, 5))  # still moving: the release did not stop it
        Robot.Attached = 1  # the thread's robot was released when it ended
        seen.append(Robot.Attached)
        Move.WaitForEOM()
        seen.append(Robot.WhereAngles().axis_values() == FAR.axis_values())
        Robot.Attached = 0

    assert s.run_main(main) == []
    assert seen == [True, 1, True]


GPL_DETACH = """    Public Sub Main()
        Dim prof As New Profile
        Dim ex As Exception
        Dim target As New Location
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home
        target.Angles(1100, 10, 90, 0, 100)
        Move.Loc(target, prof)
        Try
            Robot.Attached = 0
            Console.WriteLine("detached while moving")
        Catch ex
            Console.WriteLine("refused: " & CStr(ex.ErrorCode) & " robot " & CStr(ex.RobotNum))
        End Try
        Move.WaitForEOM
        Robot.Attached = 0
        Console.WriteLine("attached now: " & CStr(Robot.Attached))
    End Sub"""


def test_a_transpiled_program_catches_1008(tmp_path: Path) -> None:
    result = run_gpl(tmp_path, module_src(GPL_DETACH))
    assert result.output == "refused: -1008 robot 1\nattached now: 0\n", result.output + result.log
    assert result.status == 0


def test_the_moving_check_and_a_reader_run_a_line_s_cycles_once(slow_line: tuple[RobotState, PathRun, float]) -> None:
    """The -1008 check runs the path cycles up to now (registry.robot_moving): under the real
    clock another thread may read the robot at that moment, so it takes the robot's lock as the
    readers do."""
    robot, run, t_end = slow_line
    workers = [threading.Thread(target=registry.robot_moving, args=(robot, t_end)),
               threading.Thread(target=robot.joints_at, args=(t_end,))]
    for w in workers:
        w.start()
    for w in workers:
        w.join(10.0)
    assert all(np.diff(run.ts) > 0.0), run.ts  # each cycle once, in order
    assert len(run.ts) == len(run.us) == len(run.qs)
