"""Location and RefFrame called from hand-written Python (setup files, notebooks).

Generated code passes GPL-typed values; Python callers can pass a String, a Boolean or the wrong
object.  Those calls must follow GPL's conversion rules or raise a GplException with the
controller's code — never a bare ValueError/AttributeError/TypeError.
"""

from __future__ import annotations

from typing import Any, Callable

import pytest

from gplrt.geometry import Conveyor, Location, RefFrame, register_conveyor
from geomtest import cartesian as _loc, conveyor_frame, xyz as _xyz
from gpltest import code_of as _code


def test_numeric_strings_are_converted_like_gpl() -> None:
    loc = Location()
    loc.X = "12.5"  # type: ignore[assignment]
    loc.XYZInc(" 1", "-2", "1E1")  # type: ignore[arg-type]
    assert (loc.X, loc.Y, loc.Z) == (13.5, -2.0, 10.0)
    loc.Yaw = "90"  # type: ignore[assignment]
    assert loc.Yaw == 90.0
    loc.Config = "&H1001"  # type: ignore[assignment]
    assert loc.Config == 0x1001
    a = Location()
    a.Angles("1.5", 2)  # type: ignore[arg-type]
    assert a.Angle("2") == 2.0  # type: ignore[arg-type]


def test_booleans_are_minus_one_and_zero() -> None:
    """GPL's True is -1: Angles(True) stores -1, a Boolean axis number True is axis -1 (-707)."""
    a = Location()
    a.Angles(True, False)  # type: ignore[arg-type]
    assert (a.Angle(1), a.Angle(2)) == (-1.0, 0.0)
    assert _code(a.Angle, True) == -707


def test_zworld_and_text_follow_the_gpl_conversions() -> None:
    loc = Location()
    loc.ZWorld = "False"  # type: ignore[assignment]
    assert loc.ZWorld is False  # bool("False") would be True
    loc.ZWorld = 1  # type: ignore[assignment]
    assert loc.ZWorld is True
    loc.Text = 2.0  # type: ignore[assignment]
    assert loc.Text == "2"  # CStr(2.0), not Python's "2.0"
    rf = RefFrame()
    rf.Text = 1.5  # type: ignore[assignment]
    assert rf.Text == "1.5"


@pytest.mark.parametrize("bad, code", [("abc", -717), ("", -717), (object(), -202), (None, -782)])
def test_bad_numbers_raise_gpl_errors(bad: Any, code: int) -> None:
    loc = Location()
    rf = RefFrame()
    rf.Type = 1
    calls: list[Callable[[], object]] = [
        lambda: setattr(loc, "X", bad),
        lambda: setattr(loc, "Roll", bad),
        lambda: setattr(loc, "ZClearance", bad),
        lambda: setattr(loc, "Config", bad),
        lambda: setattr(loc, "Type", bad),
        lambda: loc.XYZ(1, bad),
        lambda: loc.XYZInc(bad),
        lambda: Location.XYZValue(bad),
        lambda: rf.PalletIndex(bad),
        lambda: rf.set_PalletPitch(1, bad),
        lambda: rf.set_PalletMaxIndex(1, bad),
        lambda: rf.PalletRowColLay(1, bad, 1),
        lambda: setattr(rf, "PalletOrder", bad),
        lambda: setattr(rf, "Type", bad),
    ]
    for fn in calls:
        assert _code(fn) == code
    assert _xyz(loc) == (0, 0, 0, 0, 0, 0)  # nothing was half-written


def test_an_integer_beyond_32_bits_overflows() -> None:
    rf = RefFrame()
    rf.Type = 1
    assert _code(rf.set_PalletMaxIndex, 1, 1e12) == -710
    assert _code(rf.PalletIndex, float("nan")) == -708


@pytest.mark.parametrize("bad", [5, "loc", RefFrame()])
def test_a_wrong_object_where_a_location_is_needed_is_202(bad: object) -> None:
    loc = _loc(1, 2, 3)
    a = Location()
    a.Angles(1, 2)
    for fn in (
        lambda: loc.Mul(bad), lambda: setattr(loc, "Pos", bad), lambda: setattr(loc, "PosWrtRef", bad),
        lambda: Location.Distance(loc, bad), lambda: Location.Distance(bad, loc),
        lambda: loc.Here3(loc, bad, loc), lambda: setattr(RefFrame(), "Loc", bad),
    ):  # fmt: skip
        assert _code(fn) == -202
    assert _xyz(loc) == (1, 2, 3, 0, 0, 0)


def test_a_wrong_object_as_kinesol_reference_is_202() -> None:
    class _Arm:
        def inverse(self, loc: Location, config: int, current: Location | None) -> Location:
            raise AssertionError("must not be reached")

    from gplrt.geometry import set_kinematics_provider

    set_kinematics_provider(_Arm())  # type: ignore[arg-type]  # tests/conftest.py restores it
    assert _code(_loc(1, 2, 3).KineSol, 0, "home") == -202


@pytest.mark.parametrize("bad", [_loc(1, 2, 3), 7, "frame"])
def test_refframe_property_takes_only_a_refframe(bad: object) -> None:
    """A Location is not a frame: without the check its _total_pose would silently act as one."""
    loc = Location()
    assert _code(setattr, loc, "RefFrame", bad) == -202
    assert loc.RefFrame is None


def test_nothing_stays_782() -> None:
    loc = Location()
    assert _code(loc.Mul, None) == -782
    assert _code(Location.Distance, None, loc) == -782
    assert _code(loc.Here3, loc, loc, None) == -782
    loc.RefFrame = None  # Nothing is a valid frame: no frame
    assert loc.RefFrame is None


def test_set_encoder_converts_and_checks() -> None:
    register_conveyor(4, Conveyor())
    rf = conveyor_frame(4)
    rf.set_encoder("250")  # type: ignore[arg-type]
    assert rf.Pos().X == 250.0
    assert _code(rf.set_encoder, float("inf")) == -708
    assert _code(rf.set_encoder, "fast") == -717


@pytest.mark.parametrize(
    ("make", "code"),
    [
        (lambda: Location.from_pose(None), -782),  # type: ignore[arg-type]
        (lambda: Location.from_pose((1.0, 2.0)), -202),  # type: ignore[arg-type]
        (lambda: Location.from_pose(("a",) * 12), -202),  # type: ignore[arg-type]
        (lambda: Location.from_matrix([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), -202),  # type: ignore[arg-type]
        (lambda: Location.from_matrix("eye"), -202),  # type: ignore[arg-type]
        (lambda: Location.from_angles(None), -782),
        (lambda: Location.from_angles(5), -202),
    ],
)
def test_python_constructors_reject_what_is_not_a_pose(make: Callable[[], Location], code: int) -> None:
    """Python-side constructors get GPL codes too, not a TypeError/ValueError from deep inside."""
    assert _code(make) == code


def test_from_pose_takes_any_sequence_of_12_numbers() -> None:
    loc = Location.from_pose([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 5.0, 6.0, 7.0])  # type: ignore[arg-type]
    assert (loc.X, loc.Y, loc.Z) == (5.0, 6.0, 7.0)
    loc.XYZInc(1, 0, 0)  # a list stored as is breaks the tuple arithmetic here (TypeError)
    assert (loc.X, loc.Y, loc.Z) == (6.0, 6.0, 7.0)
