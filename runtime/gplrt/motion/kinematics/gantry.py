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
from gplrt.geometry.transforms import Pose
from gplrt.lang.errors import INVALID_AXIS_COUNT, INVALID_CARTESIAN, GplException
from gplrt.motion.kinematics.base import (
    RobotModel,
    axis_roles,
    read_joints,
    read_transform,
)
from gplrt.motion.kinematics.config import GPL_SINGLE, TWO_PI
from gplrt.motion.kinematics.units import MM_PER_M

MODULE_XYZTHETA = 2
_AXES = ((0x01, "x"), (0x02, "y"), (0x04, "z"), (0x08, "theta"), (0x10, "gripper"))
_NAMES = {"x": "X", "y": "Y", "z": "Z", "theta": "Theta", "gripper": "Gripper"}
_LINEAR_ROLES = {"x", "y", "z", "gripper"}
_TOLERANCE = math.sin(math.radians(1e-6))
#: Allowed coordinate error (m) for a coordinate whose axis is missing.
_POSITION_TOLERANCE = 1e-9
# (``_plain_inverse``: module-level names save an attribute lookup each)
_atan2, _hypot, _radians, _degrees, _PI = math.atan2, math.hypot, math.radians, math.degrees, math.pi


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
        self._n_axes = len(roles)
        #: (x, y, z, theta) axis indices when the gantry has all four (``_plain_inverse``), else None
        self._plain_axes = (tuple(self._i[r] for r in ("x", "y", "z", "theta"))
                            if all(r in self._i for r in ("x", "y", "z", "theta")) else None)
        self._build_pin_model()
        #: ``check_limits``'s bounds of the four axes (lower, upper, ...) and of the others
        self._plain_bounds = tuple(b for k in self._plain_axes or () for b in self._joint_bounds[k])
        solved = self._plain_axes or ()
        self._plain_others = [(k, *self._joint_bounds[k]) for k in range(len(roles)) if k not in solved]

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

    def _plain_inverse(self, pose: Pose, bits: int, current: list[float], check: bool) -> list[float] | None:
        """The steps of ``RobotModel.inverse_pose`` and ``_solve_pose`` for the case nearly every
        call is — no Base or Tool, every axis X, Y, Z and theta present, the tool vertical, theta's
        nearest turn within its limits, no ``GPL_Single``, the result within the soft limits — in
        one method; None for anything else, which the general steps then solve (and refuse with
        their codes).  The arithmetic is theirs, operation for operation (metres and back
        included), so the two agree to the bit (tests/motion/test_kinematics_gantry.py), except
        that an axis the gantry does not solve (the gripper) keeps its value exactly.

        Why: the general steps cost twenty times the gantry's closed form, which is four
        assignments and an ``atan2`` (``benchmarks/kinematics_speed.py``)."""
        axes = self._plain_axes
        if axes is None or bits & GPL_SINGLE or len(current) != self._n_axes or not (
                self._base_is_identity and self._tool_is_identity):
            return None
        r11, _, r13, r21, _, r23, _, _, r33, x, y, z = pose
        if not (_hypot(r13, r23) <= _TOLERANCE and r33 >= 0.0):
            return None
        ix, iy, iz, it = axes
        theta = -_atan2(r21, r11)
        now = _radians(current[it])
        near = theta + round((now - theta) / TWO_PI) * TWO_PI  # ``_unwind``'s first case
        if not (abs(near - now) < _PI and self._slack_lower_si[it] <= near <= self._slack_upper_si[it]):
            return None
        mm = MM_PER_M
        qx, qy, qz, qt = x / mm * mm, y / mm * mm, -(z / mm) * mm, _degrees(near)
        if check:  # ``check_limits``: the four axes solved, then the others (the gripper) as they are
            xl, xh, yl, yh, zl, zh, tl, th = self._plain_bounds
            if not (xl <= qx <= xh and yl <= qy <= yh and zl <= qz <= zh and tl <= qt <= th):
                return None
            for k, lo, hi in self._plain_others:
                if not lo <= current[k] <= hi:
                    return None
        q = current.copy()
        q[ix], q[iy], q[iz], q[it] = qx, qy, qz, qt
        return q

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
