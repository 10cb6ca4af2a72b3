"""Homogeneous transforms and GPL's ZYZ Euler angles (mm, degrees) — the controller's exact math.

GPL stores every Cartesian pose as a 4x4 homogeneous transform and shows it as X, Y, Z (mm) and
Yaw, Pitch, Roll (degrees): rotate about Z, then about the *new* Y, then about the *new* Z
(gpl-classes.md §5.1, §22.1; D0:1996-2013), i.e.

    T(x, y, z, yaw, pitch, roll) = Trans(x, y, z) · Rz(yaw) · Ry(pitch) · Rz(roll)

with column vectors (``p_parent = R·p_child + t``).

Two representations live here:

* the public numpy form, ``xyzypr_to_matrix`` / ``matrix_to_xyzypr`` (a (4, 4) ``ndarray``), for
  the kinematics and anyone who wants matrices;
* a *pose tuple* of 12 Python floats ``(r11, r12, r13, r21, r22, r23, r31, r32, r33, x, y, z)``
  used internally by ``Location``.  Why: numpy's per-call overhead dominates on 4x4 arrays, and a
  hand-written 3x3+3 product on floats is as fast as ``a @ b`` while avoiding array allocation
  (see benchmarks/geometry_speed.py).  Tuples are immutable, so Locations can share them safely.

Exactness decisions (documented because the manual prints exact values, D0:2040-2046):

* ``sin``/``cos`` of an exact multiple of 90° are exactly 0/±1, so ``(10,25,-40,0,0,90)·(0,5,0)``
  gives exactly ``(5, 25, -40, 0, 0, 90)``.
* Extracted angles within ``_SNAP`` (1e-11°) of an integer are snapped to it, so writing Yaw = 30
  and reading it back gives exactly 30 (the float round trip through sin/cos/atan2 otherwise
  returns e.g. 29.999999999999996).  The change is far below any measurable difference.
* Angles are reported in (-180°, 180°]; -0.0 is reported as 0.0.

Singular orientations (pitch 0° or 180°, where the two Z rotations are about parallel axes and
only their sum/difference is defined): following the V+ rule that GPL inherits ("the yaw component
is forced to 0", D2:6033-6038) and the only worked example (D0:2044-2046, a pure Z rotation reads
as roll 90), the whole rotation goes into **roll** and yaw reads 0.  This also suits the PF400, whose
tool frames are all pitch 180 (robot-models.md §5): the gripper rotation reads back as roll.
A pitch is treated as singular when sin(pitch) <= ``SINGULAR_EPS``.
"""

from __future__ import annotations

import math
from typing import TypeAlias

import numpy as np
from numpy.typing import NDArray

from gplrt.lang.errors import INVALID_ARGUMENT, GplException

Pose: TypeAlias = tuple[float, float, float, float, float, float, float, float, float, float, float, float]

#: A pose is singular (pitch 0 or 180) when sin(pitch) is at most this.
SINGULAR_EPS = 1e-9
_SNAP = 1e-11

_FLOAT64 = np.dtype(np.float64)

IDENTITY: Pose = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)

_EXACT_QUARTER: dict[int, tuple[float, float]] = {0: (0.0, 1.0), 1: (1.0, 0.0), 2: (0.0, -1.0), 3: (-1.0, 0.0)}


def sincos_deg(angle: float) -> tuple[float, float]:
    """``(sin, cos)`` of ``angle`` degrees; exact for multiples of 90°.

    The angle is first reduced to [-180, 180) so that large inputs keep their precision.
    """
    q, r = divmod(angle, 90.0)
    if r == 0.0:
        return _EXACT_QUARTER[int(q) % 4]
    a = math.remainder(angle, 360.0)
    rad = math.radians(a)
    return math.sin(rad), math.cos(rad)


def wrap_angle(deg: float) -> float:
    """Wrap ``deg`` into (-180, 180] and turn -0.0 into 0.0 (no snapping: for values a user wrote)."""
    if not -180.0 < deg <= 180.0:
        deg = math.remainder(deg, 360.0)
        if deg == -180.0:
            deg = 180.0
    return deg + 0.0


def normalize_angle(deg: float) -> float:
    """Wrap ``deg`` into (-180, 180], snap near-integers, and turn -0.0 into 0.0 (computed angles)."""
    deg = wrap_angle(deg)
    n = round(deg)
    if abs(deg - n) <= _SNAP:
        deg = float(n)
        if deg == -180.0:
            deg = 180.0
    return deg + 0.0


def _atan2_deg(y: float, x: float) -> float:
    return normalize_angle(math.degrees(math.atan2(y, x)))


# -- pose tuples ---------------------------------------------------------------------------------


def pose_from_xyzypr(x: float, y: float, z: float, yaw: float, pitch: float, roll: float) -> Pose:
    """Pose tuple for X, Y, Z (mm), Yaw, Pitch, Roll (degrees)."""
    sy, cy = sincos_deg(yaw)
    sp, cp = sincos_deg(pitch)
    sr, cr = sincos_deg(roll)
    cycp = cy * cp
    sycp = sy * cp
    return (
        cycp * cr - sy * sr, -cycp * sr - sy * cr, cy * sp,
        sycp * cr + cy * sr, -sycp * sr + cy * cr, sy * sp,
        -sp * cr, sp * sr, cp,
        float(x), float(y), float(z),
    )  # fmt: skip


def pose_angles(p: Pose) -> tuple[float, float, float]:
    """(yaw, pitch, roll) in degrees of a pose's rotation; see the module docstring for singular rules."""
    r13, r23, r33 = p[2], p[5], p[8]
    s = math.sqrt(r13 * r13 + r23 * r23)
    if s > SINGULAR_EPS:
        return _atan2_deg(r23, r13), _atan2_deg(s, r33), _atan2_deg(p[7], -p[6])
    if r33 > 0.0:  # pitch 0: R = Rz(yaw + roll)
        return 0.0, 0.0, _atan2_deg(p[3], p[0])
    # pitch 180: R = Rz(yaw)·Ry(180)·Rz(roll) = Ry(180)·Rz(roll - yaw); with yaw 0, r21 = sin, r22 = cos
    return 0.0, 180.0, _atan2_deg(p[3], p[4])


def pose_to_xyzypr(p: Pose) -> tuple[float, float, float, float, float, float]:
    """X, Y, Z, Yaw, Pitch, Roll of a pose tuple."""
    yaw, pitch, roll = pose_angles(p)
    return p[9] + 0.0, p[10] + 0.0, p[11] + 0.0, yaw, pitch, roll


def pose_mul(a: Pose, b: Pose) -> Pose:
    """``a · b``: ``b`` interpreted in the coordinate system defined by ``a`` (D0:2030-2038)."""
    a11, a12, a13, a21, a22, a23, a31, a32, a33, ax, ay, az = a
    b11, b12, b13, b21, b22, b23, b31, b32, b33, bx, by, bz = b
    return (
        a11 * b11 + a12 * b21 + a13 * b31, a11 * b12 + a12 * b22 + a13 * b32, a11 * b13 + a12 * b23 + a13 * b33,
        a21 * b11 + a22 * b21 + a23 * b31, a21 * b12 + a22 * b22 + a23 * b32, a21 * b13 + a22 * b23 + a23 * b33,
        a31 * b11 + a32 * b21 + a33 * b31, a31 * b12 + a32 * b22 + a33 * b32, a31 * b13 + a32 * b23 + a33 * b33,
        a11 * bx + a12 * by + a13 * bz + ax, a21 * bx + a22 * by + a23 * bz + ay, a31 * bx + a32 * by + a33 * bz + az,
    )  # fmt: skip


def pose_inv(a: Pose) -> Pose:
    """Inverse of a rigid transform: ``[Rᵀ, -Rᵀ·t]`` (exact for orthonormal R)."""
    a11, a12, a13, a21, a22, a23, a31, a32, a33, x, y, z = a
    return (
        a11, a21, a31,
        a12, a22, a32,
        a13, a23, a33,
        -(a11 * x + a21 * y + a31 * z), -(a12 * x + a22 * y + a32 * z), -(a13 * x + a23 * y + a33 * z),
    )  # fmt: skip


def pose_translate(a: Pose, dx: float, dy: float, dz: float) -> Pose:
    """``a · Trans(dx, dy, dz)``: a step along ``a``'s own axes (pallet cells, tool retraction)."""
    return a[:9] + (
        a[0] * dx + a[1] * dy + a[2] * dz + a[9],
        a[3] * dx + a[4] * dy + a[5] * dz + a[10],
        a[6] * dx + a[7] * dy + a[8] * dz + a[11],
    )


def pose_orthonormalize(a: Pose) -> Pose:
    """Remove numerical drift from the rotation (Gram-Schmidt on the Z then X columns).

    Why this order: the approach (Z) axis is the one a robot program cares most about, so it keeps
    its direction; X is made orthogonal to it and Y completes a right-handed frame.
    """
    zx, zy, zz = a[2], a[5], a[8]
    n = math.sqrt(zx * zx + zy * zy + zz * zz)
    if n == 0.0:
        return IDENTITY[:9] + a[9:]  # type: ignore[return-value]
    zx, zy, zz = zx / n, zy / n, zz / n
    xx, xy, xz = a[0], a[3], a[6]
    d = xx * zx + xy * zy + xz * zz
    xx, xy, xz = xx - d * zx, xy - d * zy, xz - d * zz
    n = math.sqrt(xx * xx + xy * xy + xz * xz)
    if n < 1e-12:  # X collapsed onto Z: pick any perpendicular
        xx, xy, xz = (1.0, 0.0, 0.0) if abs(zx) < 0.9 else (0.0, 1.0, 0.0)
        d = xx * zx + xy * zy + xz * zz
        xx, xy, xz = xx - d * zx, xy - d * zy, xz - d * zz
        n = math.sqrt(xx * xx + xy * xy + xz * xz)
    xx, xy, xz = xx / n, xy / n, xz / n
    yx, yy, yz = zy * xz - zz * xy, zz * xx - zx * xz, zx * xy - zy * xx
    return (xx, yx, zx, xy, yy, zy, xz, yz, zz, a[9], a[10], a[11])


def pose_to_matrix(p: Pose) -> NDArray[np.float64]:
    """(4, 4) homogeneous matrix of a pose tuple."""
    m = np.empty((4, 4))
    m[:3, :3] = np.asarray(p[:9], dtype=float).reshape(3, 3)
    m[:3, 3] = p[9:]
    m[3] = (0.0, 0.0, 0.0, 1.0)
    return m


def matrix_to_pose(m: NDArray[np.float64]) -> Pose:
    """Pose tuple of a (4, 4) (or (3, 4)) homogeneous matrix; the bottom row is ignored.

    Anything else (another shape, non-numeric entries) is -202 *Invalid argument*: it reaches
    here from Python callers (``Location.from_matrix``), who get GPL codes, not ValueError.
    One ``tolist`` and an unpacking: the inverse kinematics converts every target with it.
    """
    if type(m) is np.ndarray and m.shape == (4, 4) and m.dtype is _FLOAT64:  # (the usual case)
        (r11, r12, r13, x), (r21, r22, r23, y), (r31, r32, r33, z), _ = m.tolist()
        return (r11, r12, r13, r21, r22, r23, r31, r32, r33, x, y, z)
    if type(m) is not np.ndarray or m.dtype is not _FLOAT64:
        try:
            m = np.asarray(m, dtype=float)
        except (TypeError, ValueError):
            raise GplException(INVALID_ARGUMENT, detail=f"not a numeric matrix: {type(m).__name__}") from None
    shape = m.shape
    if shape != (4, 4) and shape != (3, 4):
        raise GplException(INVALID_ARGUMENT, detail=f"expected a (4, 4) matrix, got shape {shape}")
    (r11, r12, r13, x), (r21, r22, r23, y), (r31, r32, r33, z) = m.tolist()[:3]
    return (r11, r12, r13, r21, r22, r23, r31, r32, r33, x, y, z)


def xyzypr_to_matrix(x: float, y: float, z: float, yaw: float, pitch: float, roll: float) -> NDArray[np.float64]:
    """(4, 4) homogeneous transform for X, Y, Z (mm) and ZYZ Yaw, Pitch, Roll (degrees)."""
    return pose_to_matrix(pose_from_xyzypr(x, y, z, yaw, pitch, roll))


def matrix_to_xyzypr(m: NDArray[np.float64]) -> tuple[float, float, float, float, float, float]:
    """X, Y, Z (mm), Yaw, Pitch, Roll (degrees) of a (4, 4) homogeneous transform.

    Pitch is in [0, 180]; yaw and roll in (-180, 180]; at pitch 0 or 180 yaw reads 0 and the
    whole rotation is in roll (module docstring).
    """
    return pose_to_xyzypr(matrix_to_pose(m))
