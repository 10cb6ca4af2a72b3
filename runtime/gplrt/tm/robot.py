"""A TM robot's kinematics in TM's units: joints in degrees, poses ``{X, Y, Z, RX, RY, RZ}`` in mm
and degrees with R = Rz(RZ)·Ry(RY)·Rx(RX) (spec §4.1, manual L9438), on the shared core's model.

The models (``TM5-700``, ``TM5-900``, ``TM12``, ``TM14``) are the core's URDF robots
(``gplrt.motion.kinematics.robot_model``, docs/design/robots.md): forward kinematics, the
closed-form inverse with configuration bits, the joint limits and speeds of Techman's nominal
URDFs.  This module only adds what is TM's business: the pose convention (R = Rz·Ry·Rx is what
Pinocchio calls roll-pitch-yaw, ``pin.rpy``, checked in tests/tm/test_tm_robot.py) and TM's pose
configuration triplet ``{Config1, Config2, Config3}`` (L17206–L17227) as the core's bits.

**The triplet.**  Config1 ∈ {0, 1} is the shoulder side, Config2 ∈ {2, 3} the elbow (the sign of
J3), Config3 ∈ {4, 5} the wrist (the sign of J5), each with the manual's wrist mode M = 0 (the
manual does not define M nor draw its vectors A–D in the text we have).  On the core's geometric
bits: Config3 4 (J5 positive) is NoFlip, 5 is Flip, exactly.  Config2: the elbow's J3 sign is the
core's Above/Below read for the shoulder side asked for (the core measures "above" with the reach
pointing forward, so a Lefty arm's J3 > 0 is Below where a Righty's is Above).  Config1 0 is the
side of TM's home ``{0, 0, 90, 0, 90, 0}`` with the reach forward (TMflow's points at home show
``{0, 2, 4}``): the core's Righty; 1 is Lefty.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Sequence

import numpy as np
import pinocchio as pin

from gplrt.lang.errors import GplException
from gplrt.motion.kinematics import (
    GPL_ABOVE,
    GPL_BELOW,
    GPL_FLIP,
    GPL_LEFTY,
    GPL_NOFLIP,
    GPL_RIGHTY,
    robot_model,
)
from gplrt.motion.kinematics.base import RobotModel
from gplrt.tm.values import TMError

#: The TM robots of the core's catalogue (``--robot`` names).
MODELS = ("TM5-700", "TM5-900", "TM12", "TM14")


def rotation(rx: float, ry: float, rz: float) -> np.ndarray:
    """R = Rz·Ry·Rx of angles in degrees (manual L9438)."""
    return pin.rpy.rpyToMatrix(math.radians(rx), math.radians(ry), math.radians(rz))


def pose_to_se3(pose: list[float] | np.ndarray) -> pin.SE3:
    """A TM pose (mm, deg) as a rigid transform in metres."""
    x, y, z, rx, ry, rz = (float(v) for v in pose)
    return pin.SE3(rotation(rx, ry, rz), np.array([x, y, z]) / 1000.0)


def se3_to_pose(m: pin.SE3) -> list[float]:
    """A rigid transform as a TM pose: RY = asin(-R31), RX = atan2(R32, R33), RZ = atan2(R21, R11)."""
    r = m.rotation
    ry = math.asin(max(-1.0, min(1.0, -r[2, 0])))
    rx = math.atan2(r[2, 1], r[2, 2])
    rz = math.atan2(r[1, 0], r[0, 0])
    t = m.translation * 1000.0
    return [float(t[0]), float(t[1]), float(t[2]), math.degrees(rx), math.degrees(ry), math.degrees(rz)]


def config_bits(triplet: Sequence[int] | None) -> int:
    """The core's configuration bits for TM's ``{Config1, Config2, Config3}`` (module docstring);
    0 (keep the branch the robot is in) for None.  TMError for a value outside the manual's."""
    if triplet is None:
        return 0
    c = [int(v) for v in triplet]
    if len(c) != 3 or c[0] not in (0, 1) or c[1] not in (2, 3) or c[2] not in (4, 5):
        raise TMError(f"the pose configuration {{{', '.join(map(str, c))}}} is not {{0|1, 2|3, 4|5}}")
    righty = c[0] == 0
    j3_positive = c[1] == 2
    bits = GPL_RIGHTY if righty else GPL_LEFTY
    bits |= GPL_ABOVE if j3_positive == righty else GPL_BELOW
    bits |= GPL_NOFLIP if c[2] == 4 else GPL_FLIP
    return bits


def triplet_of(bits: int, joints: Sequence[float]) -> list[int]:
    """TM's ``{Config1, Config2, Config3}`` of a joint vector (deg) whose core bits are ``bits``:
    what ``Point[...].Pose`` reads."""
    return [0 if bits & GPL_RIGHTY else 1, 2 if float(joints[2]) >= 0.0 else 3,
            4 if float(joints[4]) >= 0.0 else 5]


def _to_matrix(m: pin.SE3) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = m.rotation
    T[:3, 3] = m.translation * 1000.0
    return T


@dataclass
class TMArm:
    """One TM model on the core: ``fk(joints) -> flange pose``, ``ik(pose, seed) -> joints``."""

    name: str
    model: RobotModel
    lower: list[float]  # deg
    upper: list[float]
    speed: list[float]  # deg/s at 100 %

    def fk_se3(self, joints: Sequence[float]) -> pin.SE3:
        """The flange in RobotBase, metres (the core model has no Base nor Tool: the TM layer's
        base and TCP are its own, queued with the motions)."""
        T = self.model.forward([float(v) for v in joints])
        return pin.SE3(np.array(T[:3, :3], dtype=float), np.array(T[:3, 3], dtype=float) / 1000.0)

    def fk(self, joints: Sequence[float]) -> list[float]:
        """The flange pose in RobotBase (mm, deg)."""
        return se3_to_pose(self.fk_se3(joints))

    def ik_se3(self, target: pin.SE3, seed: Sequence[float], config: Sequence[int] | None = None) -> list[float]:
        """Joints (deg) that put the flange at ``target``: the core's closed form, in the
        configuration ``config`` (TM's triplet) or, without one, the branch the robot is in.
        TMError with the core's reason (too far, out of limits, no such configuration) if none."""
        try:
            q = self.model.inverse(_to_matrix(target), config_bits(config), [float(v) for v in seed])
        except GplException as exc:
            raise TMError(f"the point is out of reach ({exc})") from exc
        return [float(v) for v in q]

    def ik(self, pose: Sequence[float], seed: Sequence[float], config: Sequence[int] | None = None) -> list[float]:
        return self.ik_se3(pose_to_se3(list(pose)), seed, config)

    def config(self, joints: Sequence[float]) -> list[int]:
        """TM's pose configuration triplet of a joint vector."""
        return triplet_of(self.model.config_of([float(v) for v in joints]), joints)


@cache
def arm(name: str) -> TMArm:
    """The model called ``name`` (``TM5-900``, ...); ValueError for another name."""
    key = name.upper()
    if key not in MODELS:
        raise ValueError(f"unknown TM robot {name!r}: one of {', '.join(MODELS)}")
    model = robot_model(key)
    spec = model.chain  # type: ignore[attr-defined]
    speed = [j.to_units(j.velocity) for j in spec.axes]
    return TMArm(key, model, [j.lower for j in model.joints], [j.upper for j in model.joints], speed)
