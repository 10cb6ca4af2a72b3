"""A V+ program on the SCARA, ``--robot COBRA-S600`` (issue 21): MOVE, MOVES, APPRO, APPROS,
DEPART, DEPARTS with LEFTY and RIGHTY, through the front end onto the same runtime.

The poses the robot stops at are checked against the URDF itself, read here with Pinocchio
(``adept_cobra_s600.urdf``, its mimic joint given the value of the joint it follows): the joints
at the end of each motion, put through the file's forward kinematics, must be the transformations
the program names, composed as the Guide defines them (``TRANS(x,y,z,yaw,pitch,roll)`` =
``Trans * Rz(yaw) * Ry(pitch) * Rz(roll)``, L5987-6053; APPRO/DEPART along the tool's -Z), to
1e-6 mm.  A goal beyond the arm's 600 mm is V+'s error, which the program's REACTE trap reports.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from gpl2py.notebook import Cell, GplError
from gplrt.vplus import errors
from gpltest import REPO
from vplusoracle import trans

URDF = REPO / "runtime" / "gplrt" / "data" / "robots" / "urdf" / "adept_cobra_s600.urdf"

PROGRAM = """\
.PROGRAM cobra.cell()
; A SCARA cell on the Cobra s600: approach, place and depart, with each arm
        REACTE cobra.trap
        SPEED 50 ALWAYS
        MOVE #park
        BREAK
        RIGHTY
        APPRO pick, 60
        BREAK
        MOVES pick
        BREAK
        DEPART 60
        BREAK
        LEFTY
        APPRO place, 40
        BREAK
        MOVES place
        BREAK
        DEPARTS 40
        BREAK
        RIGHTY
        MOVE place
        BREAK
        APPROS pick, 60
        BREAK
        TYPE "placed"
        MOVE far            ; beyond the arm's 600 mm
        BREAK
        TYPE "after far"
        MOVE #park
        BREAK
.END
.PROGRAM cobra.trap()
; The error trap: say what stopped the motion, and go on after it
        TYPE "error ", ERROR(-1), ": ", $ERROR(ERROR(-1))
        RETURNE
.END
.LOCATIONS
pick    350 -200 250 30 180 0
place   300 250 220 -45 180 0
far     700 0 250 0 180 0
#park   0 90 -50 0
.END
"""




class UrdfArm:
    """The Cobra's forward kinematics straight from its URDF (joints in degrees, J3 in mm)."""

    def __init__(self) -> None:
        self.model = pin.buildModelFromUrdf(str(URDF))
        self.data = self.model.createData()
        self.flange = self.model.getFrameId("tool0")

    def forward(self, joints: list[float]) -> np.ndarray:
        j1, j2, j3, j4 = joints
        q = np.zeros(self.model.nq)
        for name, value in (("inner_joint", math.radians(j1)), ("flyover_cable_joint", math.radians(j1)),
                            ("outer_joint", math.radians(j2)), ("quill_prismatic_joint", j3 / 1000),
                            ("quill_rotation_joint", math.radians(j4))):
            q[self.model.joints[self.model.getJointId(name)].idx_q] = value
        pin.framesForwardKinematics(self.model, self.data, q)
        pose = self.data.oMf[self.flange].homogeneous.copy()
        pose[:3, 3] *= 1000
        return pose


def test_a_scara_program_reaches_what_it_names_by_the_urdf_and_traps_a_goal_too_far(
        tmp_path: Path) -> None:
    (tmp_path / "cobra.v2").write_text(PROGRAM)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cell = Cell.load(tmp_path, robot="COBRA-S600", echo=False, cache_dir=tmp_path / "cache")
    assert cell.run_main() == 0, cell.sim.console.log_text
    assert cell.sim.console.output.splitlines() == [
        "placed", f"error {errors.TOO_FAR}: *Location too far*", "after far"]

    arm = UrdfArm()
    state = cell.sim.robot(1)
    stops = [[float(j) for j in state.queue.joints_at(float(seg.end))] for seg in state.queue.history]
    reached = [arm.forward(joints) for joints in stops]

    def above(pose: np.ndarray, d: float) -> np.ndarray:  # APPRO/DEPART: along the tool's -Z
        return pose @ trans(0, 0, -d)

    park = arm.forward([0, 90, -50, 0])
    pick, place = trans(350, -200, 250, 30, 180, 0), trans(300, 250, 220, -45, 180, 0)
    expected = [park, above(pick, 60), pick, above(pick, 60),
                above(place, 40), place, above(place, 40), place, above(pick, 60), park]
    assert len(reached) == len(expected)  # (MOVE far never started)
    for n, (got, want) in enumerate(zip(reached, expected, strict=True)):
        assert np.abs(got - want).max() < 1e-6, (n, got.round(6), want.round(6))
    assert np.abs(np.array(stops[0]) - [0, 90, -50, 0]).max() < 1e-9
    # RIGHTY: the outer link turns counter-clockwise from the inner one (J2 > 0); LEFTY the other way
    righty_pick, lefty_place, righty_place = stops[2], stops[5], stops[7]
    assert righty_pick[1] > 0 and lefty_place[1] < 0 and righty_place[1] > 0


def test_without_a_trap_the_goal_too_far_stops_the_program_at_its_line(tmp_path: Path) -> None:
    (tmp_path / "far.v2").write_text(".PROGRAM far()\n        MOVE #park\n        MOVE far\n"
                                     "        TYPE \"never\"\n.END\n"
                                     ".LOCATIONS\nfar 0 -620 250 0 180 0\n#park 0 90 -50 0\n.END\n")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cell = Cell.load(tmp_path, robot="COBRA-S600", echo=False, cache_dir=tmp_path / "cache")
    with pytest.raises(GplError) as info:
        cell.run_main()
    error = info.value
    assert (error.ErrorCode, error.Message(), error.gpl_location) == (
        errors.TOO_FAR, "*Location too far*", "far.v2:3")
    assert "never" not in cell.sim.console.output
