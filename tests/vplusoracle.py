"""An oracle for V+ transformations, independent of gplrt: TRANS(x, y, z, yaw, pitch, roll) is
the translation then Rz(yaw) Ry(pitch) Rz(roll), in mm and degrees, as the V+ Language User's
Guide defines it.  The V+ tests check the poses the robot reaches against it."""

from __future__ import annotations

import math

import numpy as np


def trans(x: float, y: float, z: float, yaw: float = 0, pitch: float = 0, roll: float = 0) -> np.ndarray:
    def rz(a: float) -> np.ndarray:
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])

    def ry(a: float) -> np.ndarray:
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]])

    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t @ rz(yaw) @ ry(pitch) @ rz(roll)
