"""Location members: manual examples, reference semantics, Pos/PosWrtRef/Mul/Inverse rules, errors."""

from __future__ import annotations

from typing import Iterator

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gplrt.geometry import Location, RefFrame, set_kinematics_provider
from geomtest import angles as _angles, cartesian as _loc, in_a_frame_loop, xyz as _xyz
from gpltest import code_of as _code


# -- manual and Dictionary examples ------------------------------------------------------------


def test_new_location_is_cartesian_identity_with_documented_defaults() -> None:
    loc = Location()
    assert loc.Type == 0
    assert _xyz(loc) == (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    assert loc.RefFrame is None and loc.Config == 0 and loc.ZWorld is False and loc.Text == ""
    assert loc.ZClearance == 1.0e32


def test_mul_worked_examples() -> None:
    """GD mul.htm / D0:2040-2046."""
    assert _xyz(_loc(10, 25, -40).Mul(_loc(0, 5, 0))) == (10, 30, -40, 0, 0, 0)
    assert _xyz(_loc(10, 25, -40, 0, 0, 90).Mul(_loc(0, 5, 0))) == (5, 25, -40, 0, 0, 90)


def test_inverse_inverse_example() -> None:
    """GD inverse.htm: loc1.XYZ(11,-23,45,0,180,42); loc1.Inverse.Inverse.Y = -23."""
    loc1 = _loc(11, -23, 45, 0, 180, 42)
    assert loc1.Inverse().Inverse().Y == -23.0
    assert _xyz(loc1.Inverse().Inverse()) == pytest.approx((11, -23, 45, 0, 180, 42), abs=1e-12)


def test_z_example() -> None:
    """GD z.htm: after XYZ(10,20,30,0,180,25) Z = 30; loc.Z += 7 gives 37."""
    loc = _loc(10, 20, 30, 0, 180, 25)
    assert loc.Z == 30.0
    loc.Z += 7
    assert loc.Z == 37.0
    assert _xyz(loc) == (10, 20, 37, 0, 180, 25)


def test_copy_is_a_pointer_clone_is_a_copy() -> None:
    """EX-04 and EX-05 (D0:611-637)."""
    loc1 = Location()
    loc1.X = 10
    loc2 = loc1
    loc3 = loc1.Clone()
    loc1.X = 20
    assert loc2.X == 20.0
    assert loc3.X == 10.0


def test_clone_shares_the_frame_not_copies_it() -> None:
    f = RefFrame()
    loc = Location()
    loc.RefFrame = f
    assert loc.Clone().RefFrame is f


def test_zworld_approach_example() -> None:
    """GD zworld.htm: total (10,20,30), ZClearance 52.3, ZWorld True -> approach (10,20,52.3)."""
    loc = _loc(10, 20, 30)
    loc.ZClearance = 52.3
    loc.ZWorld = True
    app = loc.approach_location()
    assert app is not None and (app.X, app.Y, app.Z) == (10, 20, 52.3)
    loc.ZWorld = False  # retract along tool -Z; with pitch 180 tool Z points down, so up in world
    loc.XYZ(10, 20, 30, 0, 180, 0)
    app = loc.approach_location()
    assert app is not None and (app.X, app.Y, app.Z) == (10, 20, 82.3)
    assert Location().approach_location() is None


# -- reading back what was written ---------------------------------------------------------------


def test_angles_written_one_by_one_compose_as_intended() -> None:
    loc = Location()
    loc.Yaw = 30
    loc.Pitch = 90
    loc.Roll = 180
    assert _xyz(loc) == (0, 0, 0, 30, 90, 180)
    assert loc.Mul(Location()).Yaw == pytest.approx(30, abs=1e-12)  # the matrix agrees


def test_written_singular_angles_read_back_but_computed_ones_follow_the_rule() -> None:
    loc = _loc(0, 0, 0, 30, 0, 60)
    assert (loc.Yaw, loc.Pitch, loc.Roll) == (30, 0, 60)
    assert (loc.Pos.Yaw, loc.Mul(Location()).Roll) == (30, 90)  # Pos of a frameless loc keeps the values
    assert _xyz(loc.Mul(Location())) == (0, 0, 0, 0, 0, 90)


def test_x_write_keeps_the_orientation() -> None:
    loc = _loc(1, 2, 3, 10, 20, 30)
    loc.X = 5
    loc.Y = 6
    assert _xyz(loc) == (5, 6, 3, 10, 20, 30)


def test_xyzinc_moves_in_the_parent_axes() -> None:
    loc = _loc(1, 2, 3, 0, 0, 90)
    loc.XYZInc(10, 0, -1)
    assert _xyz(loc) == (11, 2, 2, 0, 0, 90)


def test_xyzvalue_is_shared() -> None:
    assert _xyz(Location.XYZValue(1, 2, 3, 4, 5, 6)) == (1, 2, 3, 4, 5, 6)
    assert _xyz(Location.XYZValue(7)) == (7, 0, 0, 0, 0, 0)


@settings(max_examples=200, deadline=None)
@given(
    st.lists(st.floats(min_value=-1e4, max_value=1e4, allow_nan=False), min_size=3, max_size=3),
    st.lists(st.floats(min_value=-179.9, max_value=180.0, allow_nan=False), min_size=3, max_size=3),
)
def test_location_xyz_round_trip(pos: list[float], ang: list[float]) -> None:
    loc = _loc(*pos, *ang)
    assert _xyz(loc) == tuple(pos + ang)


# -- Pos, PosWrtRef, Mul and Inverse storage rules ------------------------------------------------


def test_pos_wrt_ref_get_returns_a_bare_copy() -> None:
    f = RefFrame()
    f.Loc.XYZ(100, 0, 0)
    loc = _loc(1, 2, 3, 0, 90, 0)
    loc.RefFrame, loc.Config, loc.ZClearance, loc.Text = f, 1, 5.0, "t"
    w = loc.PosWrtRef
    assert _xyz(w) == (1, 2, 3, 0, 90, 0)
    assert (w.RefFrame, w.Config, w.ZClearance, w.Text) == (None, 0, 1.0e32, "")
    assert loc.Pos.X == 101.0


def test_pos_wrt_ref_set_takes_the_total_and_touches_nothing_else() -> None:
    f = RefFrame()
    f.Loc.XYZ(100, 0, 0)
    src = _loc(1, 2, 3)
    src.RefFrame = f
    loc = Location()
    loc.Config = 2
    loc.PosWrtRef = src
    assert (loc.X, loc.Y, loc.Z, loc.Config, loc.RefFrame) == (101, 2, 3, 2, None)


def test_pos_set_copies_values_not_the_pointer() -> None:
    a, b = Location(), _loc(1, 2, 3)
    a.Pos = b
    b.X = 9
    assert a.X == 1.0


def test_mul_keeps_the_left_frame_and_uses_the_right_total() -> None:
    fa, fb = RefFrame(), RefFrame()
    fa.Loc.XYZ(100, 0, 0)
    fb.Loc.XYZ(0, 100, 0)
    a, b = _loc(1, 0, 0), _loc(0, 1, 0)
    a.RefFrame, b.RefFrame = fa, fb
    c = a.Mul(b)
    assert c.RefFrame is fa
    assert (c.X, c.Y, c.Z) == (1, 101, 0)  # PosWrtRef(a)·Total(b)
    assert (c.Pos.X, c.Pos.Y) == (101, 101)  # Total(a)·Total(b)


def test_inverse_uses_the_total_and_drops_the_frame() -> None:
    f = RefFrame()
    f.Loc.XYZ(100, 0, 0)
    a = _loc(1, 2, 3)
    a.RefFrame, a.Config, a.Text = f, 1, "keep"
    inv = a.Inverse()
    assert (inv.X, inv.Y, inv.Z, inv.RefFrame, inv.Config, inv.Text) == (-101, -2, -3, None, 1, "keep")


def test_normalize_repairs_a_drifted_rotation() -> None:
    p = _loc(1, 2, 3, 10, 20, 30).pose_wrt_ref
    loc = Location.from_pose(tuple(v * 1.001 for v in p[:9]) + p[9:])  # type: ignore[arg-type]  # drifted
    loc.Normalize()
    assert _xyz(loc) == pytest.approx((1, 2, 3, 10, 20, 30), abs=0.2)
    r = loc.pose_wrt_ref
    assert sum(r[i] * r[i] for i in (0, 3, 6)) == pytest.approx(1.0, abs=1e-15)


def test_normalize_keeps_written_angles() -> None:
    """Normalize of a pose whose angles were written changes nothing, singular ones included."""
    for v in ((1, 2, 3, 45, 180, 30), (0, 0, 0, 30, 0, 60), (5, 6, 7, -100, 33, 170)):
        loc = _loc(*v)
        before = loc.pose_wrt_ref
        loc.Normalize()
        assert _xyz(loc) == v
        assert loc.pose_wrt_ref == before
    loc = _loc(1, 2, 3, 10, 20, 30).Mul(Location())  # computed: decomposed, then repaired
    loc.Normalize()
    assert _xyz(loc) == pytest.approx((1, 2, 3, 10, 20, 30), abs=1e-12)


def test_here3_builds_a_frame_from_three_points() -> None:
    loc = Location()
    loc.Here3(_loc(10, 20, 0), _loc(10, 30, 0), _loc(0, 25, 0))
    # X along +Y world, the third point on the -X world side -> Y axis = -X world, Z = +Z world
    assert _xyz(loc) == pytest.approx((10, 20, 0, 0, 0, 90), abs=1e-12)


def test_distance_uses_total_positions() -> None:
    f = RefFrame()
    f.Loc.XYZ(3, 0, 0)
    a, b = Location(), _loc(0, 4, 0)
    a.RefFrame = f
    assert Location.Distance(a, b) == 5.0


# -- Angles Locations --------------------------------------------------------------------------


def test_angles_location() -> None:
    loc = _angles(10, -20, 30.5, 40)
    assert loc.Type == 1
    assert [loc.Angle(i) for i in range(1, 6)] == [10, -20, 30.5, 40, 0]
    loc.set_Angle(12, 7)
    assert loc.Angle(12) == 7.0
    copy = Location()
    copy.Angles()
    copy.Pos = loc
    assert copy.Angle(3) == 30.5
    assert loc.Pos.Angle(1) == 10.0


def test_xyz_turns_an_angles_location_cartesian() -> None:
    loc = _angles(1, 2)
    loc.XYZ(1, 2, 3)
    assert loc.Type == 0 and loc.Z == 3.0


# -- errors ----------------------------------------------------------------------------------------


def test_cartesian_only_members_on_angles_raise_762() -> None:
    a = _angles(1, 2, 3)
    c = Location()
    for fn in (
        lambda: a.X, lambda: a.Yaw, lambda: a.Inverse(), lambda: a.Mul(c), lambda: c.Mul(a),
        lambda: a.PosWrtRef, lambda: a.XYZInc(1), lambda: a.Normalize(), lambda: Location.Distance(a, c),
        lambda: setattr(a, "X", 1), lambda: setattr(a, "Roll", 1), lambda: setattr(c, "Pos", a),
        lambda: setattr(a, "RefFrame", RefFrame()), lambda: setattr(c, "PosWrtRef", a),
    ):  # fmt: skip
        assert _code(fn) == -762


def test_angles_only_members_on_cartesian_raise_763() -> None:
    c = Location()
    assert _code(c.Angle, 1) == -763
    assert _code(c.set_Angle, 1, 5.0) == -763
    a = _angles(1)
    assert _code(setattr, a, "Pos", c) == -763


def test_nothing_arguments_raise_782() -> None:
    c = Location()
    assert _code(c.Mul, None) == -782
    assert _code(Location.Distance, c, None) == -782
    assert _code(setattr, c, "Pos", None) == -782
    assert _code(setattr, c, "PosWrtRef", None) == -782
    f = RefFrame()
    f.Loc = None
    c.RefFrame = f
    assert _code(lambda: c.Pos) == -782


@pytest.mark.parametrize("axis", [0, -1, 13])
def test_axis_out_of_range_raises_707(axis: int) -> None:
    a = _angles(1)
    assert _code(a.Angle, axis) == -707
    assert _code(a.set_Angle, axis, 1.0) == -707


def test_bad_type_and_values() -> None:
    loc = Location()
    assert _code(setattr, loc, "Type", 2) == -707
    assert _code(loc.XYZ, float("nan")) == -708
    assert _code(loc.Here3, _loc(0, 0, 0), _loc(1, 0, 0), _loc(2, 0, 0)) == -707


def test_frame_loop_raises_770() -> None:
    loc = in_a_frame_loop()
    assert _code(lambda: loc.Pos) == -770


# -- robot-dependent members ------------------------------------------------------------------------


class _FakeArm:
    """A 'robot' whose Cartesian pose is simply X=axis1, Y=axis2, Z=axis3 (enough to test delegation)."""

    def __init__(self) -> None:
        self.calls: list[tuple[object, ...]] = []

    def forward(self, angles: Location) -> Location:
        return Location.XYZValue(angles.Angle(1), angles.Angle(2), angles.Angle(3))

    def inverse(self, loc: Location, config: int, current: Location | None) -> Location:
        self.calls.append((config, current))
        t = loc.Pos
        out = Location()
        out.Angles(t.X, t.Y, t.Z)
        return out

    def where(self) -> Location:
        w = Location.XYZValue(5, 6, 7)
        w.Config = 1
        return w

    def where_angles(self) -> Location:
        out = Location()
        out.Angles(1, 2, 3)
        return out


@pytest.fixture
def arm() -> Iterator[_FakeArm]:
    a = _FakeArm()
    set_kinematics_provider(a)
    yield a  # tests/conftest.py puts the previous provider back


def test_kinesol_and_here_without_a_robot_raise_1036() -> None:
    set_kinematics_provider(None)  # as before any robot package registers one
    assert _code(Location().KineSol) == -1036
    assert _code(_angles(1).KineSol) == -1036
    assert _code(Location().Here) == -1036


def test_kinesol_delegates_with_config(arm: _FakeArm) -> None:
    assert _xyz(_angles(1, 2, 3).KineSol()) == (1, 2, 3, 0, 0, 0)
    target = _loc(4, 5, 6)
    target.Config = 2
    sol = target.KineSol()
    assert [sol.Angle(i) for i in (1, 2, 3)] == [4, 5, 6]
    assert arm.calls == [(2, None)]
    assert _code(target.KineSol, 0, Location()) == -763


def test_here_back_solves_through_the_frame(arm: _FakeArm) -> None:
    f = RefFrame()
    f.Loc.XYZ(1, 1, 1)
    loc = Location()
    loc.RefFrame = f
    loc.Here()
    assert (loc.X, loc.Y, loc.Z, loc.Config) == (4, 5, 6, 1)
    a = _angles(0)
    a.Here()
    assert a.Angle(2) == 2.0
