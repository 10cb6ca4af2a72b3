"""V+ transformations and precision points as values of the shared ``Location`` (spec §3.9).

``T(x,y,z,yaw,pitch,roll) = Trans · Rz(yaw) · Ry(pitch) · Rz(roll)`` (L5987-6053) is the convention
``gplrt.geometry.transforms`` already implements for GPL, so every function here is a few lines
over ``Location``: ``a:b`` is ``Location.Mul``, ``INVERSE`` is ``Location.Inverse``.  The layer
treats Locations as immutable values: nothing here changes its argument.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from gplrt.geometry import transforms as tf
from gplrt.geometry.location import Location
from gplrt.lang.errors import GplException
from gplrt.vplus.errors import ILLEGAL_VALUE, NOT_PRECISION_POINT, VError, from_core
from gplrt.vplus.operators import to_int


def _cartesian(t: Any, what: str) -> Location:
    if not isinstance(t, Location):
        raise VError(ILLEGAL_VALUE, detail=f"{what}: not a transformation")
    if t._type != 0:
        raise VError(ILLEGAL_VALUE, detail=f"{what}: a precision point cannot be used here (L5944-5947)")
    return t


def _pose(t: Location) -> tf.Pose:
    try:
        return t.total_pose()
    except GplException as exc:
        raise from_core(exc) from None


def trans(x: Any = 0.0, y: Any = 0.0, z: Any = 0.0, yaw: Any = 0.0, pitch: Any = 0.0, roll: Any = 0.0) -> Location:
    """``TRANS(x, y, z, yaw, pitch, roll)``; omitted trailing values are 0 (L6162-6164)."""
    vals = [float(v) for v in (x, y, z, yaw, pitch, roll)]
    if not all(math.isfinite(v) for v in vals):
        raise VError(ILLEGAL_VALUE, detail="TRANS of a non-finite value")
    loc = Location.from_pose(tf.pose_from_xyzypr(*vals))
    loc._ypr = (tf.wrap_angle(vals[3]), tf.wrap_angle(vals[4]), tf.wrap_angle(vals[5]))
    return loc


def null() -> Location:
    """``NULL``: the identity transformation."""
    return Location()


def _rot(axis: int, deg: Any) -> Location:
    s, c = tf.sincos_deg(float(deg))
    m = np.eye(4)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m[i, i] = c
    m[j, j] = c
    m[i, j] = -s
    m[j, i] = s
    return Location.from_matrix(m)


def rx(deg: Any) -> Location:
    """``RX(a)``: rotation of ``a`` degrees about X."""
    return _rot(0, deg)


def ry(deg: Any) -> Location:
    return _rot(1, deg)


def rz(deg: Any) -> Location:
    return _rot(2, deg)


def compose(*parts: Location) -> Location:
    """``a:b:c``: left to right (L6116-6185)."""
    result = _cartesian(parts[0], ":")
    for p in parts[1:]:
        p = _cartesian(p, ":")
        result = Location.from_pose(tf.pose_mul(_pose(result), _pose(p)))
    return result


def inverse(t: Location) -> Location:
    t = _cartesian(t, "INVERSE")
    return Location.from_pose(tf.pose_inv(_pose(t)))


def shift(t: Location, dx: Any = 0.0, dy: Any = 0.0, dz: Any = 0.0) -> Location:
    """``SHIFT(t BY dx, dy, dz)``: world X/Y/Z added, orientation kept (L6111-6114)."""
    p = _pose(_cartesian(t, "SHIFT"))
    return Location.from_pose(p[:9] + (p[9] + float(dx), p[10] + float(dy), p[11] + float(dz)))  # type: ignore[arg-type]


def scale(t: Location, s: Any) -> Location:
    """``SCALE(t BY s)``: the position multiplied by s, orientation kept."""
    p = _pose(_cartesian(t, "SCALE"))
    k = float(s)
    return Location.from_pose(p[:9] + (p[9] * k, p[10] * k, p[11] * k))  # type: ignore[arg-type]


def normal(t: Location) -> Location:
    """``NORMAL(t)``: the rotation re-orthonormalised against round-off (the core's rule)."""
    return Location.from_pose(tf.pose_orthonormalize(_pose(_cartesian(t, "NORMAL"))))


def frame(origin: Location, x_point: Location, y_point: Location, position: Location) -> Location:
    """``FRAME(o, x, y, p)``: X axis from o toward x, Z = X × (y − o), Y = Z × X, origin at p's
    position (spec §3.9 [INF], L6215).  Coincident or collinear points are *Illegal value*."""
    o = np.array(_pose(_cartesian(origin, "FRAME"))[9:])
    px = np.array(_pose(_cartesian(x_point, "FRAME"))[9:])
    py = np.array(_pose(_cartesian(y_point, "FRAME"))[9:])
    pp = np.array(_pose(_cartesian(position, "FRAME"))[9:])
    x = px - o
    nx = np.linalg.norm(x)
    z = np.cross(x, py - o)
    nz = np.linalg.norm(z)
    if nx == 0.0 or nz <= 1e-12 * nx * max(1.0, np.linalg.norm(py - o)):
        raise VError(ILLEGAL_VALUE, detail="FRAME points coincide or are collinear")
    x /= nx
    z /= nz
    y = np.cross(z, x)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = x, y, z, pp
    return Location.from_matrix(m)


def dx(t: Location) -> float:
    return float(_pose(_cartesian(t, "DX"))[9])


def dy(t: Location) -> float:
    return float(_pose(_cartesian(t, "DY"))[10])


def dz(t: Location) -> float:
    return float(_pose(_cartesian(t, "DZ"))[11])


def distance(a: Location, b: Location) -> float:
    pa, pb = _pose(_cartesian(a, "DISTANCE")), _pose(_cartesian(b, "DISTANCE"))
    return math.dist(pa[9:], pb[9:])


def identical(a: Location, b: Location) -> float:
    if a._type != b._type:
        return 0.0
    same = a.axis_values() == b.axis_values() if a._type == 1 else _pose(a) == _pose(b)
    return -1.0 if same else 0.0


def components(t: Location) -> tuple[float, ...]:
    """x, y, z, yaw, pitch, roll of a transformation, or the joints of a precision point."""
    if t._type == 1:
        return tuple(float(v) for v in t.axis_values())
    p = _pose(t)
    y, pi, r = (t._ypr if t._ref is None and t._ypr is not None else tf.pose_angles(p))
    return (p[9], p[10], p[11], y, pi, r)


def decompose(array: Any, start: Any, t: Location) -> float:
    """``DECOMPOSE a[i] = t``: components into a[i], a[i+1], ...; returns how many."""
    i0 = to_int(start)
    values = components(t)
    for k, v in enumerate(values):
        array[i0 + k] = v
    return float(len(values))


def p_ppoint(*joints: Any) -> Location:
    """``#PPOINT(j1, j2, ...)``: a precision point."""
    return Location.from_angles([float(j) for j in joints])


def need_ppoint(t: Any) -> Location:
    if not isinstance(t, Location) or t._type != 1:
        raise VError(NOT_PRECISION_POINT)
    return t
