"""ZYZ transforms: the manual's worked example, exact trig, singular poses, hypothesis round trips."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from gplrt.geometry.transforms import (
    matrix_to_xyzypr,
    normalize_angle,
    pose_from_xyzypr,
    pose_mul,
    pose_orthonormalize,
    pose_to_xyzypr,
    sincos_deg,
    xyzypr_to_matrix,
)
from gplrt.lang.errors import GplException

HYP = settings(max_examples=300, deadline=None)

mm = st.floats(min_value=-5000.0, max_value=5000.0, allow_nan=False)
angle = st.floats(min_value=-179.999, max_value=180.0, allow_nan=False)
regular_pitch = st.floats(min_value=0.01, max_value=179.99, allow_nan=False)


def test_manual_worked_example_without_rotation() -> None:
    """D0:2040-2042: (10,25,-40) combined with (0,5,0) is (10,30,-40)."""
    a = pose_from_xyzypr(10, 25, -40, 0, 0, 0)
    b = pose_from_xyzypr(0, 5, 0, 0, 0, 0)
    assert pose_to_xyzypr(pose_mul(a, b)) == (10.0, 30.0, -40.0, 0.0, 0.0, 0.0)


def test_manual_worked_example_with_rotation_is_exact() -> None:
    """D0:2043-2046: (10,25,-40,0,0,90) combined with (0,5,0) prints exactly (5,25,-40,0,0,90)."""
    a = pose_from_xyzypr(10, 25, -40, 0, 0, 90)
    b = pose_from_xyzypr(0, 5, 0, 0, 0, 0)
    assert pose_to_xyzypr(pose_mul(a, b)) == (5.0, 25.0, -40.0, 0.0, 0.0, 90.0)


@pytest.mark.parametrize("deg", [-720, -450, -360, -270, -180, -90, 0, 90, 180, 270, 360, 450, 1080])
def test_quarter_turns_have_exact_sin_cos(deg: int) -> None:
    s, c = sincos_deg(float(deg))
    assert (s, c) == (round(math.sin(math.radians(deg))), round(math.cos(math.radians(deg))))
    assert s in (-1.0, 0.0, 1.0) and c in (-1.0, 0.0, 1.0)


def test_matrix_matches_the_documented_formula() -> None:
    """gpl-classes.md §22.1 item 3, element by element, against scipy's intrinsic ZYZ."""
    m = xyzypr_to_matrix(1.5, -2.0, 3.25, 30.0, 45.0, -60.0)
    want = Rotation.from_euler("ZYZ", [30.0, 45.0, -60.0], degrees=True).as_matrix()
    assert np.max(np.abs(m[:3, :3] - want)) <= 1e-15
    assert m[:3, 3].tolist() == [1.5, -2.0, 3.25]
    assert m[3].tolist() == [0.0, 0.0, 0.0, 1.0]


def test_inverse_example_from_the_dictionary() -> None:
    """GD inverse.htm: XYZ(11,-23,45,0,180,42) read back unchanged, including the pitch-180 pose."""
    assert matrix_to_xyzypr(xyzypr_to_matrix(11, -23, 45, 0, 180, 42)) == (11.0, -23.0, 45.0, 0.0, 180.0, 42.0)


def test_pitch_zero_puts_the_whole_rotation_in_roll() -> None:
    assert matrix_to_xyzypr(xyzypr_to_matrix(0, 0, 0, 30, 0, 60)) == (0.0, 0.0, 0.0, 0.0, 0.0, 90.0)
    assert matrix_to_xyzypr(xyzypr_to_matrix(0, 0, 0, 170, 0, 20)) == (0.0, 0.0, 0.0, 0.0, 0.0, -170.0)


def test_pitch_180_puts_the_rotation_in_roll() -> None:
    """Rz(y)·Ry(180)·Rz(r) = Ry(180)·Rz(r - y): yaw 0, roll r - y."""
    assert matrix_to_xyzypr(xyzypr_to_matrix(0, 0, 0, 30, 180, -60)) == (0.0, 0.0, 0.0, 0.0, 180.0, -90.0)
    assert matrix_to_xyzypr(xyzypr_to_matrix(0, 0, 0, -100, 180, 100)) == (0.0, 0.0, 0.0, 0.0, 180.0, -160.0)


def test_roll_minus_180_reads_plus_180() -> None:
    """robot-models.md §5.1: PF400 programs write roll -180; the controller reports +180."""
    x = matrix_to_xyzypr(xyzypr_to_matrix(100, 200, 300, -83.036521, 90, -180))
    assert x[3:] == pytest.approx((-83.036521, 90.0, 180.0), abs=1e-12)
    assert x[5] == 180.0


def test_normalize_angle_range_and_negative_zero() -> None:
    assert normalize_angle(-180.0) == 180.0
    assert normalize_angle(540.0) == 180.0
    assert normalize_angle(-190.0) == 170.0
    assert math.copysign(1.0, normalize_angle(-0.0)) == 1.0
    assert normalize_angle(29.999999999999996) == 30.0


def test_matrix_shape_is_checked() -> None:
    """A matrix of another shape, or not numeric, is the GPL error -202 (never a ValueError)."""
    with pytest.raises(GplException) as caught:
        matrix_to_xyzypr(np.eye(3))
    assert caught.value.ErrorCode == -202
    with pytest.raises(GplException) as caught:
        matrix_to_xyzypr([["a"] * 4] * 4)  # type: ignore[arg-type]
    assert caught.value.ErrorCode == -202


def test_orthonormalize_removes_drift_and_keeps_position() -> None:
    p = pose_from_xyzypr(1, 2, 3, 20, 70, -30)
    drifted = tuple(v * (1 + 1e-6 * (i % 3)) for i, v in enumerate(p[:9])) + p[9:]
    q = pose_orthonormalize(drifted)  # type: ignore[arg-type]
    r = np.array(q[:9]).reshape(3, 3)
    assert np.max(np.abs(r @ r.T - np.eye(3))) < 1e-15
    assert np.linalg.det(r) == pytest.approx(1.0, abs=1e-15)
    assert q[9:] == p[9:]
    assert pose_to_xyzypr(q)[3:] == pytest.approx((20, 70, -30), abs=1e-3)


@HYP
@given(mm, mm, mm, angle, regular_pitch, angle)
def test_xyz_matrix_xyz_round_trip(x: float, y: float, z: float, yaw: float, pitch: float, roll: float) -> None:
    got = matrix_to_xyzypr(xyzypr_to_matrix(x, y, z, yaw, pitch, roll))
    assert got[:3] == (x + 0.0, y + 0.0, z + 0.0)
    assert got[4] == pytest.approx(pitch, abs=1e-9)
    # yaw and roll are determined to ~eps/sin(pitch); compare on the circle
    tol = 1e-9 if math.sin(math.radians(pitch)) > 1e-3 else 1e-6
    for want, have in ((yaw, got[3]), (roll, got[5])):
        assert abs(math.remainder(have - want, 360.0)) <= tol
        assert -180.0 < have <= 180.0


@HYP
@given(angle, st.sampled_from([0.0, 180.0]), angle)
def test_singular_round_trip_keeps_the_rotation(yaw: float, pitch: float, roll: float) -> None:
    m = xyzypr_to_matrix(0, 0, 0, yaw, pitch, roll)
    got = matrix_to_xyzypr(m)
    assert got[3] == 0.0 and got[4] == pitch
    assert np.max(np.abs(xyzypr_to_matrix(*got) - m)) <= 1e-12


@HYP
@given(mm, mm, mm, angle, st.floats(min_value=0.0, max_value=180.0), angle)
def test_matrix_xyz_matrix_round_trip_everywhere(x: float, y: float, z: float, yaw: float, pitch: float, roll: float) -> None:
    """Whatever the decomposition picks, it describes the same transform."""
    m = xyzypr_to_matrix(x, y, z, yaw, pitch, roll)
    assert np.max(np.abs(xyzypr_to_matrix(*matrix_to_xyzypr(m)) - m)) <= 1e-9
