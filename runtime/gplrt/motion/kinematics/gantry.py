"""Cartesian XYZ-Theta gantry (kinematic module 116 = 2, the generic "XYZTheta" module).

Module semantics from Brooks' Kinematic Library page for XYZTheta (robot-models.md §7 [EXT]):
1–4 optional axes; axis 1 moves +X, axis 2 +Y, **axis 3 positive moves toward −Z**, **axis 4
positive is a negative rotation about world Z**.  Which axes exist comes from the axis mask 2003
(&H1 X, &H2 Y, &H4 Z, &H8 theta, numbered consecutively; &H10 = servo gripper after them, as
TCS reads it for the PrecisePlace 100).  Our PP100-style default ``GANTRY4`` and the GCU default
set both use this module.  16050 carries no dimensions for this module.

Flange frame (our decision; the module page does not say): ``Trans(X, Y, −Z_axis) · Rz(−theta)``,
so the flange keeps world-Z up and yaw = −theta.  A Cartesian target must therefore be a pure
rotation about Z (else -1033, tolerance 1e-6°); a missing axis must have 0 in its coordinate
(else -1033).  Config bits have no branch to choose on a gantry: ``config_of`` reports 0,
``GPL_Single`` puts theta in (−180°, 180°], otherwise theta is unwound toward its current value
within the soft limits (multi-turn theta).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from gplrt.controller.pdb import ParameterDatabase
from gplrt.lang.errors import INVALID_AXIS_COUNT, INVALID_CARTESIAN, GplException
from gplrt.motion.kinematics.base import (
    RobotModel,
    axis_roles,
    read_joints,
    read_transform,
)
from gplrt.motion.kinematics.config import GPL_SINGLE

MODULE_XYZTHETA = 2
_AXES = ((0x01, "x"), (0x02, "y"), (0x04, "z"), (0x08, "theta"), (0x10, "gripper"))
_NAMES = {"x": "X", "y": "Y", "z": "Z", "theta": "Theta", "gripper": "Gripper"}
_LINEAR_ROLES = {"x", "y", "z", "gripper"}
_TOLERANCE = math.sin(math.radians(1e-6))
#: Allowed coordinate error (m) for a coordinate whose axis is missing.
_POSITION_TOLERANCE = 1e-9


class GantryModel(RobotModel):
    """An XYZ-Theta gantry; see the module docstring."""

    def __init__(self, pdb: ParameterDatabase, robot: int = 1) -> None:
        roles = axis_roles(int(pdb.get_num(2003, robot)), (), _AXES)
        name, joints = read_joints(pdb, robot, roles, _NAMES, _LINEAR_ROLES)
        super().__init__(name, robot, MODULE_XYZTHETA, joints,
                         read_transform(pdb, 16051, robot), read_transform(pdb, 16052, robot))
        self.roles = roles
        self._i = {role: roles.index(role) for role in roles}
        self.single_axis = self._i.get("theta")
        self._build_pin_model()

    def _build_pin_model(self) -> None:
        if not any(role in self._i for role in ("x", "y", "z", "theta")):
            # checked before building: a gripper alone would otherwise hang off the universe joint
            raise GplException(INVALID_AXIS_COUNT, detail=f"{self.name}: no X, Y, Z or theta axis in the axis mask")
        model = pin.Model()
        model.name = self.name
        ids: dict[str, int] = {}
        parent = 0
        kinds = {"x": pin.JointModelPX(), "y": pin.JointModelPY(),
                 "z": pin.JointModelPrismaticUnaligned(np.array([0.0, 0.0, -1.0])),
                 "theta": pin.JointModelRevoluteUnaligned(np.array([0.0, 0.0, -1.0]))}
        for role in ("x", "y", "z", "theta"):
            if role in self._i:
                parent = ids[role] = model.addJoint(parent, kinds[role], pin.SE3.Identity(), _NAMES[role])
        flange = model.addFrame(pin.Frame("flange", parent, pin.SE3.Identity(), pin.FrameType.OP_FRAME))
        if "gripper" in self._i:
            ids["gripper"] = model.addJoint(parent, pin.JointModelPY(), pin.SE3.Identity(), "Gripper")
        self._finish_pin_model(model, [ids[r] for r in self.roles], flange)

    def _solve_pose(self, rotation: Sequence[float], position: Sequence[float], bits: int,
                    current: list[float]) -> list[float]:
        r00, _, r02, r10, _, r12, _, _, r22 = rotation
        if math.hypot(r02, r12) > _TOLERANCE or r22 < 0.0:
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot, detail="a gantry tool stays vertical")
        yaw = math.atan2(r10, r00)
        q = list(current)
        x, y, z = position
        for role, value in (("x", x), ("y", y), ("z", -z)):
            k = self._i.get(role)
            if k is not None:
                q[k] = value
            elif abs(value) > _POSITION_TOLERANCE:
                raise GplException(INVALID_CARTESIAN, robot_num=self.robot, detail=f"no {_NAMES[role]} axis")
        k = self._i.get("theta")
        if k is not None:
            q[k] = self._unwind(k, -yaw, current, single=bool(bits & GPL_SINGLE))
        elif abs(yaw) > _TOLERANCE:
            raise GplException(INVALID_CARTESIAN, robot_num=self.robot, detail="no theta axis")
        return q
