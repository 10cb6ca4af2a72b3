"""A TM robot's kinematics in TM's units: joints in degrees, poses ``{X, Y, Z, RX, RY, RZ}`` in mm
and degrees with R = Rz(RZ)·Ry(RY)·Rx(RX) (spec §4.1, manual L9438), from the URDF (Pinocchio).

The models (``TM5-700``, ``TM5-900``, ``TM12``, ``TM14``) are Techman's nominal URDFs
(``data/robots/urdf/``, BSD-3-Clause, LICENSES/), kinematics only: joint limits and speeds are the
URDF's.  R = Rz·Ry·Rx is what Pinocchio calls roll-pitch-yaw (``pin.rpy``), so the pose
convention is checked against Pinocchio's own conversion (tests/tm/test_robot.py).

This is the TM layer's view of the shared Pinocchio model; the inverse is damped least squares on
the flange Jacobian, seeded with the current joints (the TM arm has no spherical wrist: J4-J6 do
not meet in one point, so no closed form is used).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np
import pinocchio as pin

from gplrt.tm.values import TMError

URDF_DIR = Path(__file__).resolve().parent.parent / "data" / "robots" / "urdf"
MODELS = {"TM5-700": "tm5-700-nominal.urdf", "TM5-900": "tm5-900-nominal.urdf",
          "TM12": "tm12-nominal.urdf", "TM14": "tm14-nominal.urdf"}
FLANGE = "flange"


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


@dataclass
class TMArm:
    """One TM model: ``fk(joints) -> flange pose``, ``ik(pose, seed) -> joints``, its limits."""

    name: str
    model: pin.Model
    frame: int
    lower: list[float]  # deg
    upper: list[float]
    speed: list[float]  # deg/s at 100 %

    def fk_se3(self, joints: list[float]) -> pin.SE3:
        data = self.model.createData()
        q = np.radians(np.asarray(joints, dtype=float))
        pin.framesForwardKinematics(self.model, data, q)
        return data.oMf[self.frame].copy()

    def fk(self, joints: list[float]) -> list[float]:
        """The flange pose in RobotBase (mm, deg)."""
        return se3_to_pose(self.fk_se3(joints))

    def ik_se3(self, target: pin.SE3, seed: list[float]) -> list[float]:
        """Joints (deg) that put the flange at ``target``, nearest ``seed``; TMError if none."""
        data = self.model.createData()
        q = np.radians(np.asarray(seed, dtype=float))
        lo, hi = np.radians(self.lower), np.radians(self.upper)
        damping = 1e-6
        for _ in range(200):
            pin.framesForwardKinematics(self.model, data, q)
            err = pin.log6(data.oMf[self.frame].actInv(target)).vector
            if np.linalg.norm(err) < 1e-12:
                break
            j = pin.computeFrameJacobian(self.model, data, q, self.frame, pin.LOCAL)
            dq = j.T @ np.linalg.solve(j @ j.T + damping * np.eye(6), err)
            q = pin.integrate(self.model, q, dq)
        pin.framesForwardKinematics(self.model, data, q)
        err = pin.log6(data.oMf[self.frame].actInv(target)).vector
        if np.linalg.norm(err) > 1e-9 or np.any(q < lo - 1e-9) or np.any(q > hi + 1e-9):
            raise TMError("the point is out of reach")
        return [math.degrees(v) for v in q]

    def ik(self, pose: list[float], seed: list[float]) -> list[float]:
        return self.ik_se3(pose_to_se3(pose), seed)


@cache
def arm(name: str) -> TMArm:
    """The model called ``name`` (``TM5-900``, ...); ValueError for another name."""
    key = name.upper()
    if key not in MODELS:
        raise ValueError(f"unknown TM robot {name!r}: one of {', '.join(MODELS)}")
    model = pin.buildModelFromUrdf(str(URDF_DIR / MODELS[key]))
    frame = model.getFrameId(FLANGE)
    lower = [math.degrees(v) for v in model.lowerPositionLimit]
    upper = [math.degrees(v) for v in model.upperPositionLimit]
    speed = [math.degrees(v) for v in model.velocityLimit]
    return TMArm(key, model, frame, lower, upper, speed)
