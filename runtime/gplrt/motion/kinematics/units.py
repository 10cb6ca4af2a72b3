"""The one place where GPL units (mm, degrees) meet the kinematics' SI units (m, radians).

GPL programs, the parameter database and ``RobotModel``'s public methods speak millimetres and
degrees; Pinocchio and the solvers inside this package speak metres and radians.  Every
conversion goes through these functions so that a unit slip can only happen here
(STYLE.md: "SI inside, explicit conversions at the boundary").
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

MM_PER_M = 1000.0
Matrix = NDArray[np.float64]


def joints_to_q(joints: Sequence[float], linear: Sequence[bool]) -> NDArray[np.float64]:
    """GPL joint values (mm for linear axes, degrees for rotary) → SI vector (m, rad)."""
    return np.array([j / MM_PER_M if lin else math.radians(j) for j, lin in zip(joints, linear, strict=True)])


def joints_to_si_list(joints: Sequence[float], linear: Sequence[bool]) -> list[float]:
    """``joints_to_q`` as a list of Python floats (for the scalar closed-form solvers)."""
    radians = math.radians
    return [j / MM_PER_M if lin else radians(j) for j, lin in zip(joints, linear)]


def q_to_joints(q: Sequence[float], linear: Sequence[bool]) -> list[float]:
    """SI joint vector (m, rad) → GPL joint values (mm, degrees), as Python floats."""
    # Python floats (faster below); a list from the scalar solvers is one already
    values = q if type(q) is list else q.tolist() if isinstance(q, np.ndarray) else [float(v) for v in q]
    degrees = math.degrees
    return [v * MM_PER_M if lin else degrees(v) for v, lin in zip(values, linear, strict=True)]


def joint_to_si(value: float, linear: bool) -> float:
    """One joint value or limit in GPL units → SI (infinite limits stay infinite)."""
    return value / MM_PER_M if linear else math.radians(value)


def matrix_to_se3(T: Matrix) -> pin.SE3:
    """4×4 homogeneous transform with translation in mm → ``pin.SE3`` in metres."""
    T = np.asarray(T, dtype=float)
    return pin.SE3(T[:3, :3].copy(), T[:3, 3] / MM_PER_M)


def se3_to_matrix(M: pin.SE3) -> Matrix:
    """``pin.SE3`` in metres → 4×4 homogeneous transform with translation in mm."""
    T: Matrix = M.homogeneous  # a fresh array (Pinocchio returns the 4×4 by value)
    T[:3, 3] *= MM_PER_M
    return T


def length_to_si(mm: float) -> float:
    """A length from the parameter database (mm) → metres."""
    return mm / MM_PER_M
