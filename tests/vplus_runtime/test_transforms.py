"""V+ transformations on the shared Location, checked against hand computation (spec §3.9)."""

from __future__ import annotations

import math

import pytest

from gplrt import vplus as vp
from gplrt.vplus.transforms import components

TOL = 1e-9


def close(loc: object, expected: tuple[float, ...]) -> None:
    got = components(loc)  # type: ignore[arg-type]
    assert len(got) == len(expected)
    for g, e in zip(got, expected):
        assert g == pytest.approx(e, abs=TOL), (got, expected)


def test_trans_defaults_and_composition_from_the_guide() -> None:
    loc_a = vp.trans(300, 50, 350, 0, 180, 0)
    close(vp.trans(0, 50), (0, 50, 0, 0, 0, 0))
    # L6134-6154: loc_a:TRANS(-50,20,30) = 350, 70, 320, 0, 180, 0
    close(vp.compose(loc_a, vp.trans(-50, 20, 30)), (350, 70, 320, 0, 180, 0))
    loc_b = vp.trans(-50, 20, 30)
    loc_c = vp.compose(loc_a, loc_b)
    # L6176-6185: loc_c:INVERSE(loc_b) = loc_a
    close(vp.compose(loc_c, vp.inverse(loc_b)), (300, 50, 350, 0, 180, 0))
    # L6162-6170: loc_a:loc_b:TRANS(0,50) in the world
    close(vp.compose(loc_a, loc_b, vp.trans(0, 50)), (350, 120, 320, 0, 180, 0))
    close(vp.inverse(loc_a), (300, -50, 350, 0, 180, 0))
    # GPL cross-check (seed000 L2040-2046)
    close(vp.compose(vp.trans(10, 25, -40, 0, 0, 90), vp.trans(0, 5, 0)), (5, 25, -40, 0, 0, 90))


def test_rotations_are_about_x_y_z() -> None:
    p = vp.trans(0, 0, 100)
    # RX(90) turns +Z into -Y
    close(vp.compose(vp.rx(90), p), (0, -100, 0, -90, 90, 90))
    t = vp.compose(vp.ry(90), p)
    assert (vp.dx(t), vp.dy(t), vp.dz(t)) == pytest.approx((100, 0, 0), abs=TOL)
    t = vp.compose(vp.rz(90), vp.trans(100))
    assert (vp.dx(t), vp.dy(t), vp.dz(t)) == pytest.approx((0, 100, 0), abs=TOL)
    # RZ(a) is TRANS(0,0,0,a,0,0): yaw/pitch/roll are Z, Y, Z rotations
    m1 = vp.compose(vp.rz(30), vp.ry(40), vp.rz(50))
    close(m1, components(vp.trans(0, 0, 0, 30, 40, 50)))


def test_shift_scale_distance_identical() -> None:
    t = vp.trans(1, 2, 3, 10, 20, 30)
    close(vp.shift(t, 5, 5, 5), (6, 7, 8, 10, 20, 30))
    close(vp.scale(t, 2), (2, 4, 6, 10, 20, 30))
    assert vp.distance(vp.trans(0, 0, 0), vp.trans(3, 4, 12)) == pytest.approx(13.0, abs=TOL)
    assert vp.identical(t, vp.trans(1, 2, 3, 10, 20, 30)) == -1.0
    assert vp.identical(t, vp.null()) == 0.0


def test_frame_from_three_points_and_a_position() -> None:
    o, x, y = vp.trans(100, 0, 0), vp.trans(200, 0, 0), vp.trans(100, 50, 0)
    f = vp.frame(o, x, y, vp.trans(10, 20, 30))
    close(f, (10, 20, 30, 0, 0, 0))
    # a frame whose X axis is world Y: yaw 90
    f = vp.frame(vp.null(), vp.trans(0, 10, 0), vp.trans(-5, 0, 0), vp.null())
    close(f, (0, 0, 0, 0, 0, 90))
    with pytest.raises(vp.VError):
        vp.frame(o, o, y, o)


def test_normal_restores_a_rotation() -> None:
    from gplrt.geometry.location import Location
    bent = Location.from_pose((1.0, 1e-6, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 3.0))
    close(vp.normal(bent), (1, 2, 3, 0, 0, 0))


def test_decompose_transformation_and_precision_point() -> None:
    arr = vp.VArray("arr")
    assert vp.decompose(arr, 0, vp.trans(1, 2, 3, 10, 20, 30)) == 6.0
    assert [arr[i] for i in range(6)] == pytest.approx([1, 2, 3, 10, 20, 30], abs=TOL)
    jts = vp.VArray("jts")
    vp.decompose(jts, 1, vp.p_ppoint(10, 20, 30, 40, 50, 60))  # ros.v2: DECOMPOSE jts[1] = #cur.loc
    assert [jts[i] for i in range(1, 7)] == [10, 20, 30, 40, 50, 60]


def test_precision_point_cannot_be_composed() -> None:
    with pytest.raises(vp.VError):
        vp.compose(vp.trans(1), vp.p_ppoint(1, 2, 3))


def test_scara_tool_down_reads_pitch_180() -> None:
    t = vp.trans(300, 0, 100, 0, 180, 45)
    y, p, r = components(t)[3:]
    assert (y, p) == (0.0, 180.0) and r == pytest.approx(45.0, abs=TOL)
    # the same pose computed (no written angles) decomposes with yaw 0
    c = vp.compose(vp.trans(300, 0, 100), vp.ry(180), vp.rz(45))
    close(c, (300, 0, 100, 0, 180, 45 + 0.0))
    assert math.isfinite(vp.dz(c))
