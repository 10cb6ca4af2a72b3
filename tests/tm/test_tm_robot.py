"""The TM models and TM's pose convention, checked against Pinocchio and the manual's matrix."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

from gpl2py.tmscript.semantics.library import BUILTINS
from gplrt.tm import library
from gplrt.tm.robot import MODELS, arm, pose_to_se3, rotation, se3_to_pose


def manual_matrix(rx: float, ry: float, rz: float) -> np.ndarray:
    """The rotation printed at L9438 of the manual, element by element."""
    sx, cx = math.sin(math.radians(rx)), math.cos(math.radians(rx))
    sy, cy = math.sin(math.radians(ry)), math.cos(math.radians(ry))
    sz, cz = math.sin(math.radians(rz)), math.cos(math.radians(rz))
    return np.array([[cz * cy, -sz * cx + cz * sy * sx, sz * sx + cz * sy * cx],
                     [sz * cy, cz * cx + sz * sy * sx, -cz * sx + sz * sy * cx],
                     [-sy, cy * sx, cy * cx]])


@pytest.mark.parametrize("angles", [(0, 0, 0), (180, 0, 90), (30, -45, 120), (-170, 89, -10), (10, 20, 30)])
def test_pose_convention_is_the_manuals_and_pinocchios(angles: tuple[float, float, float]) -> None:
    assert np.allclose(rotation(*angles), manual_matrix(*angles), atol=1e-12)
    pose = [100.0, -200.0, 300.0, *angles]
    back = se3_to_pose(pose_to_se3(pose))
    m = pose_to_se3(pose)
    assert np.allclose(back[3:], np.degrees(pin.rpy.matrixToRpy(m.rotation)), atol=1e-9)
    assert np.allclose(rotation(*back[3:]), rotation(*angles), atol=1e-12)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_models_from_their_urdf_fk_and_ik_round_trip(name: str) -> None:
    a = arm(name)
    assert len(a.lower) == 6 and all(s > 0 for s in a.speed)
    q = [12.0, -30.0, 95.0, 20.0, 70.0, -40.0]
    pose = a.fk(q)
    back = a.ik(pose, [0.0, 0.0, 90.0, 0.0, 90.0, 0.0])
    assert np.allclose(a.fk(back), pose, atol=1e-7)


def test_every_catalogued_builtin_is_in_the_runtime() -> None:
    missing = [name for name in BUILTINS if not callable(getattr(library, name, None))]
    assert missing == []
