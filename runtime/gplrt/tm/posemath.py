"""Pose and frame math (manual L9393-L9900; spec §4.2): 4×4 algebra on ``{X,Y,Z,RX,RY,RZ}`` poses
(mm, deg, R = Rz·Ry·Rx), results as ``float[]`` (binary32, as the manual prints them:
``-44.999996``, L9608)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from gplrt.tm.robot import pose_to_se3, se3_to_pose
from gplrt.tm.values import Array, TMError, to_bool


def _se3(p: object, name: str) -> pin.SE3:
    if not isinstance(p, (list, tuple)) or len(p) != 6:
        raise TMError(f"{name}: a pose has 6 values")
    return pose_to_se3([float(x) for x in p])


def _out(m: pin.SE3) -> Array:
    return Array("float", se3_to_pose(m))


def _delta_world(p1: pin.SE3, p2: pin.SE3) -> pin.SE3:
    return pin.SE3(p2.rotation @ p1.rotation.T, p2.translation - p1.translation)


def trans(p1: object, p2: object, rel: object = False) -> Array:
    """rel: T1⁻¹·T2; else (P2 − P1, R2·R1⁻¹) (L9444-L9454)."""
    a, b = _se3(p1, "trans"), _se3(p2, "trans")
    return _out(a.inverse() * b if to_bool(rel) else _delta_world(a, b))


def inversetrans(d: object, rel: object = False) -> Array:
    """rel: T⁻¹; else (−P, R⁻¹) (L9510-L9520)."""
    m = _se3(d, "inversetrans")
    return _out(m.inverse() if to_bool(rel) else pin.SE3(m.rotation.T, -m.translation))


def applytrans(p: object, d: object, rel: object = False) -> Array:
    """rel: T·Td; else (P + Pd, Rd·R) (L9578-L9588)."""
    a, b = _se3(p, "applytrans"), _se3(d, "applytrans")
    return _out(a * b if to_bool(rel) else pin.SE3(b.rotation @ a.rotation, a.translation + b.translation))


def changeref(p: object, frm: object, to: object = None) -> Array:
    """``p`` given in frame ``frm`` re-expressed in ``to`` (default RobotBase): T_to⁻¹·T_from·T_p (L9661)."""
    target = pin.SE3.Identity() if to is None else _se3(to, "changeref")
    return _out(target.inverse() * _se3(frm, "changeref") * _se3(p, "changeref"))


def interpoint(p1: object, p2: object, ratio: object) -> Array:
    """Linear in XYZ, orientation by slerp (spec §4.2: the example at L9658 is slerp's)."""
    a, b = _se3(p1, "interpoint"), _se3(p2, "interpoint")
    r = float(ratio)  # type: ignore[arg-type]
    rot = a.rotation @ pin.exp3(r * pin.log3(a.rotation.T @ b.rotation))
    return _out(pin.SE3(rot, a.translation + r * (b.translation - a.translation)))


def _unit(v: np.ndarray, name: str) -> np.ndarray:
    n = float(np.linalg.norm(v))
    if n < 1e-9:
        raise TMError(f"{name}: the points do not define a frame (two coincide or all three are on a line)")
    return v / n


def _frame(origin: np.ndarray, x: np.ndarray, z: np.ndarray) -> Array:
    """The frame at ``origin`` with axes ``x``, ``z`` (unit, orthogonal) and y = z × x."""
    return _out(pin.SE3(np.column_stack([x, np.cross(z, x), z]), origin))


def points2coord(*args: object) -> Array:
    """The frame of three points (L9733): origin p1, x towards p2, z = x × (p3 − p1), y = z × x;
    three poses (their XYZ) or nine coordinates."""
    if len(args) == 9:
        pts = [np.array([float(v) for v in args[i:i + 3]]) / 1000.0 for i in (0, 3, 6)]  # type: ignore[arg-type]
    elif len(args) == 3:
        pts = [_se3(p, "points2coord").translation for p in args]
    else:
        raise TMError("points2coord: three poses or nine values")
    x = _unit(pts[1] - pts[0], "points2coord")
    return _frame(pts[0], x, _unit(np.cross(x, pts[2] - pts[0]), "points2coord"))


def intercoord(p1: object, p2: object) -> Array:
    """The frame between two frames (L9843): at their midpoint, i = p2 − p1, j = k1 × i, k = i × j."""
    a, b = _se3(p1, "intercoord"), _se3(p2, "intercoord")
    i = _unit(b.translation - a.translation, "intercoord")
    j = _unit(np.cross(a.rotation[:, 2], i), "intercoord")
    return _frame((a.translation + b.translation) / 2, i, np.cross(i, j))


__all__ = ["applytrans", "changeref", "interpoint", "intercoord", "inversetrans", "points2coord", "trans"]
