"""The one place where GPL units (mm, degrees) meet the kinematics' SI units (m, radians).

GPL programs, the parameter database and ``RobotModel``'s public methods speak millimetres and
degrees; Pinocchio and the solvers inside this package speak metres and radians.  Every
conversion goes through these functions so that a unit slip can only happen here
(STYLE.md: "SI inside, explicit conversions at the boundary").  One conversion is done once per
robot rather than per call: the forward kinematics runs on a copy of the Pinocchio model with its
lengths in millimetres (``model_in_mm``, ``configuration_of``), so that ``forward`` converts only
its rotary axes to radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

MM_PER_M = 1000.0
Matrix = NDArray[np.float64]


def joints_to_si_list(joints: Sequence[float], linear: Sequence[bool]) -> list[float]:
    """GPL joint values (mm for linear axes, degrees for rotary) → SI (m, rad), as Python floats."""
    radians = math.radians
    return [j / MM_PER_M if lin else radians(j) for j, lin in zip(joints, linear)]


def q_to_joints(q: Sequence[float], linear: Sequence[bool]) -> list[float]:
    """SI joint vector (m, rad) → GPL joint values (mm, degrees), as Python floats."""
    # Python floats (faster below); a list from the scalar solvers is one already
    values = q if type(q) is list else q.tolist() if isinstance(q, np.ndarray) else [float(v) for v in q]
    degrees = math.degrees
    return [v * MM_PER_M if lin else degrees(v) for v, lin in zip(values, linear, strict=True)]


def configuration_of(linear: Sequence[bool], order: Sequence[int]) -> Callable[[Sequence[float]], NDArray[np.float64]]:
    """The function that turns a GPL joint vector (mm, degrees) into the configuration vector of
    ``model_in_mm``'s model: position ``p`` is GPL axis ``order[p]``, a linear axis as it is (mm), a
    rotary one through ``math.radians``.

    It is written out once per model, as ``dataclasses`` writes ``__init__``: for a PF400,
    ``lambda v: array([v[0], radians(v[1]), radians(v[2]), radians(v[3]), v[4]])``.  ``forward``
    runs for every ``Where`` and trace sample and the Pinocchio call it wraps takes half a
    microsecond; one ``np.array`` of an explicit list costs a third less than an array times a
    vector of factors, and puts the axes in Pinocchio's order on the way."""
    terms = [f"v[{int(i)}]" if linear[i] else f"radians(v[{int(i)}])" for i in order]
    convert: Callable[[Sequence[float]], NDArray[np.float64]] = eval(  # noqa: S307 (text made of integers above)
        f"lambda v: array([{', '.join(terms)}])", {"array": np.array, "radians": math.radians})
    return convert


def model_in_mm(model: pin.Model) -> pin.Model:
    """A copy of ``model`` with every length in millimetres: joint and frame placements scaled,
    so that its prismatic joints take mm and its placements come out in mm (revolute joints still
    take radians).

    Why: ``RobotModel.forward`` runs for every ``Where`` and trace sample, and the Pinocchio call
    it wraps takes well under a microsecond: converting its input and output (m ↔ mm) cost as
    much again.  The SI model stays the one the solvers use."""
    scaled = pin.Model(model)
    for i in range(1, scaled.njoints):
        placement = scaled.jointPlacements[i]
        scaled.jointPlacements[i] = pin.SE3(placement.rotation, placement.translation * MM_PER_M)
    for k in range(scaled.nframes):
        frame = scaled.frames[k]
        frame.placement = pin.SE3(frame.placement.rotation, frame.placement.translation * MM_PER_M)
    return scaled


def matrix_to_se3_mm(T: Matrix) -> pin.SE3:
    """4×4 homogeneous transform (mm) → ``pin.SE3`` with the translation still in mm (for
    ``model_in_mm``'s model)."""
    T = np.asarray(T, dtype=float)
    return pin.SE3(T[:3, :3].copy(), T[:3, 3].copy())


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
