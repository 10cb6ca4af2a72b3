"""PyLabRobot drives the vendor's TCP Command Server on the simulated PF400 (issue "Real GPL code").

The corpus's TCS 3.0C1 with the PARobot plug-in is copied unchanged (not one .gpl line differs)
to a temporary folder, loaded as a notebook ``Cell`` on the FAST clock with ``robot="PF400SX"``
and served in this process (``Cell.serve``: ProjectStart in the background, back once TCS
listens on 10100, robot 1, and 10000, status).  TCS fixes those ports in Startup.gpl, so the
test runs in a network namespace of its own (``gpltest.private_network``) rather than editing
them.  The client is PyLabRobot's real ``PreciseFlex400Backend``; every reply is asserted, and
the robot's state is read off the simulated robot itself: joints to 1e-6 of what was commanded,
the Cartesian pose to 1e-6 mm of the PF400 kinematics, and the client's read-backs (TCS prints
three decimals) against it.  Wall time is bounded only by PyLabRobot's own 30 s read time-out.
"""

from __future__ import annotations

import asyncio
import os
import socket
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from gpltest import PRIVATE_NETWORK, copy_project, corpus_dir, private_network
from gplrt.controller.services import POWER_ON_STATES
from gpl2py.notebook import Cell

ROBOT_PORT, STATUS_PORT = 10100, 10000  # Startup.gpl: Robot1Port, Status1Port
READ_BACK = 5e-4  # TCS replies with three decimals (Functions.gpl sFormat(value, 3))
JOINTS_A = (300.0, 10.0, 90.0, -100.0, 90.0)  # Z mm, shoulder, elbow, wrist deg, gripper mm
JOINTS_B = (250.0, -20.0, 110.0, -80.0, 90.0)
SAFE = (170.0, 0.0, 180.0, -180.0, 75.5)  # PARobot.gpl:243, GRIP_CLOSE 75.5 (PARobot.gpl:230)

def tcs_cell(corpus: Path, tmp_path: Path) -> Cell:
    """TCS with the PARobot plug-in, copied as it is, on a simulated PF400SX with the fast clock."""
    project = copy_project(corpus, tmp_path / "tcs-3.0C1-pa")
    return Cell.load(project, robot="PF400SX", clock="fast", echo=False, cache_dir=tmp_path / "cache")


def joints(cell: Cell) -> np.ndarray:
    return np.array(cell.where().joints)


def assert_joints(cell: Cell, expected: tuple[float, ...] | np.ndarray, read_back: dict[int, float]) -> None:
    """The simulated robot is at ``expected`` (1e-6), and the client read the same (3 decimals)."""
    here = joints(cell)
    assert here == pytest.approx(np.array(expected), abs=1e-6)
    assert [read_back[axis] for axis in range(1, 6)] == pytest.approx(here, abs=READ_BACK)


async def session(cell: Cell, tmp_path: Path) -> None:
    """One PyLabRobot session against TCS; every step checked against the simulated robot."""
    from pylabrobot.arms.precise_flex import PreciseFlex400Backend
    from pylabrobot.arms.precise_flex.coords import ElbowOrientation, PreciseFlexCartesianCoords
    from pylabrobot.arms.precise_flex.joints import PFAxis
    from pylabrobot.resources import Coordinate, Rotation

    sim = cell.sim
    arm = PreciseFlex400Backend("127.0.0.1", ROBOT_PORT)
    await arm.setup(skip_home=True)  # "mode 0", "hp 1 20", "attach 1": each reply "0"
    assert sim.controller.power_state in POWER_ON_STATES
    robot = sim.robots[1]
    assert robot.owner is not None and not robot.homed
    # A client learns whether the robot is homed from DataID 2800 ("pd 2800"), on connect and
    # after "home" (issue 20): 0, then 1
    assert await arm.get_parameter(2800) == "0"
    await arm.home()  # "home"
    assert robot.homed
    assert await arm.get_parameter(2800) == "1"
    assert await arm.get_parameter(2800, 1, 0, 1) == "1"  # "pd 2800 1 0 1": robot 1, element 1
    assert await arm.get_parameter(234) == "21"  # power on, robot attached by TCS
    assert await arm.get_parameter(2002) == "PreciseFlex 400SX"  # robot01.pac
    assert await arm.get_parameter(16050, 1, 0, 2) == "302"  # calib01.pac: the shoulder link

    version = await arm.get_version()  # "0 TCP Command Server 3.0C1 ..., PARobot Module 3.0C1 ..."
    assert version.startswith("TCP Command Server 3.0C1 05-27-2021"), version
    assert "PARobot Module 3.0C1 05-27-2021" in version

    await arm.set_speed(50)  # "Speed 1 50"
    assert await arm.get_speed() == 50.0  # "Speed 1" -> "0 1 50"

    await arm.move_j(1, dict(zip(PFAxis, JOINTS_A)))  # "moveJ 1 300.0 10.0 ..."
    assert_joints(cell, JOINTS_A, await arm.get_joint_position())  # "waitForEom", "wherej"

    # Teach: the Cartesian pose here, as TCS reports it ("wherec": X Y Z yaw pitch roll config)
    taught = await arm.get_cartesian_position()
    pose = cell.where().cartesian
    assert pose is not None
    read = (taught.location.x, taught.location.y, taught.location.z,
            taught.rotation.yaw, taught.rotation.pitch, taught.rotation.roll)
    assert read == pytest.approx(pose, abs=READ_BACK)
    assert taught.orientation == ElbowOrientation.RIGHT  # PF400 config 1 = Righty

    await arm.move_j(1, dict(zip(PFAxis, JOINTS_B)))
    assert_joints(cell, JOINTS_B, await arm.get_joint_position())

    # move_c back to the taught pose (the rounded numbers TCS printed): the PF400 kinematics
    # must put the tool exactly there
    back = PreciseFlexCartesianCoords(location=Coordinate(*read[:3]),
                                      rotation=Rotation(read[5], read[4], read[3]),
                                      orientation=ElbowOrientation.RIGHT)
    await arm.move_c(1, back)  # "moveC 1 x y z yaw pitch roll 4097"
    await arm.wait_for_eom()
    pose = cell.where().cartesian
    assert pose is not None and pose[:3] == pytest.approx(read[:3], abs=1e-6)
    assert pose[3:] == pytest.approx(read[3:], abs=1e-6)

    await arm.open_gripper(110.0)  # "GripOpenPos 110.0", "gripper 1"
    await arm.wait_for_eom()
    assert joints(cell)[4] == pytest.approx(110.0, abs=1e-6)
    await arm.close_gripper(80.0)  # "GripClosePos 80.0", "gripper 2"
    await arm.wait_for_eom()
    assert joints(cell)[4] == pytest.approx(80.0, abs=1e-6)

    # "movetosafe": closes the gripper, then goes to PARobot's SafeLoc, built when the connection
    # began with the PF400's default close position (PARobot.gpl:229-243), not the one set since
    await arm.move_to_safe()
    assert joints(cell) == pytest.approx(np.array(SAFE), abs=1e-6)

    # "halt" (Robot.RapidDecel(robot) alone, Cmd.gpl:1841) stops a motion on its way: a move of
    # tens of degrees, halted as soon as it is queued, ends far from its target; power stays on
    await arm.move_j(1, dict(zip(PFAxis, JOINTS_A)))
    await arm.halt()
    stopped = await arm.get_joint_position()  # "waitForEom", "wherej"
    here = joints(cell)
    assert np.max(np.abs(here - np.array(JOINTS_A))) > 10.0, here
    assert [stopped[axis] for axis in range(1, 6)] == pytest.approx(here, abs=READ_BACK)
    assert sim.controller.power_state in POWER_ON_STATES

    await arm.stop()  # "attach 0", "hp 0", "exit"
    assert robot.owner is None
    assert sim.controller.power_state not in POWER_ON_STATES


def test_pylabrobot_drives_tcs_on_the_simulated_pf400(tmp_path: Path, request: Any) -> None:
    corpus = corpus_dir() / "tcs-3.0C1-pa"  # skipped (failed under CI) here when missing
    if not private_network(request):
        return  # ran, and passed, in a network namespace of its own
    cell = tcs_cell(corpus, tmp_path)
    with cell.serve(ports=[ROBOT_PORT, STATUS_PORT], timeout=60.0) as serving:
        asyncio.run(session(cell, tmp_path))
        assert serving.running  # TCS serves on: it never ends by itself
    assert "error" not in cell.log.lower(), cell.log


def test_private_network_gives_a_test_the_fixed_ports_to_itself(request: Any) -> None:
    """The harness's isolation: while this process holds TCS's robot port, the same test run
    again by ``private_network`` binds it too — in a namespace of its own — and a failure there
    is this test's failure."""
    if os.environ.get(PRIVATE_NETWORK) == "1":
        with socket.create_server(("127.0.0.1", ROBOT_PORT)):
            return
    with socket.socket() as held:
        try:
            held.bind(("127.0.0.1", ROBOT_PORT))
        except OSError:
            pass  # someone else holds it: the inner run must bind it all the same
        if private_network(request):
            pytest.skip("no network namespace can be made here (needs root, unshare and ip)")
