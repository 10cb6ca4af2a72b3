"""Location/RefFrame arithmetic that leaves the Double range is GPL's -710, not an inf/NaN pose.

Ordinary Double arithmetic raises -710 *Arithmetic overflow* for an infinite result
(``gplrt.lang.operators``); a pose computed from finite Locations must do the same, whichever member
computed it.  Every operand here is finite and legal on input (the setters accept it); only the
result is out of range.  A NaN/inf operand can only be built from Python, and is -708 there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gplrt.geometry import Conveyor, Location, RefFrame, register_conveyor
from gplrt.lang.errors import ARITHMETIC_OVERFLOW, VALUE_INFINITE_OR_NAN, VALUE_OUT_OF_RANGE
from geomtest import conveyor_frame
from gpltest import code_of

BIG = 1.0e308  # finite; twice it is not


def _framed(frame_x: float, x: float) -> Location:
    """A Location at X = ``x`` in a basic frame at X = ``frame_x``."""
    frame = RefFrame()
    frame.Loc.XYZ(frame_x)
    loc = Location.XYZValue(x)
    loc.RefFrame = frame
    return loc


def test_mul_whose_translation_overflows_is_710() -> None:
    a = Location.XYZValue(BIG)
    assert code_of(a.Mul, Location.XYZValue(BIG)) == ARITHMETIC_OVERFLOW
    # Rotated: the overflow is in Y (Rz(90) turns b's X into Y) - every component is checked.
    r = Location.XYZValue(0, BIG, 0, 90)
    assert code_of(r.Mul, Location.XYZValue(BIG)) == ARITHMETIC_OVERFLOW


def test_mul_near_the_limit_still_succeeds() -> None:
    """The check rejects only what overflows: 1e308 + 7e307 is finite and exact enough."""
    res = Location.XYZValue(BIG).Mul(Location.XYZValue(7.0e307))
    assert res.X == pytest.approx(1.7e308, rel=1e-15)
    # The sum of the components overflows (X + Y) although each component is finite.
    res = Location.XYZValue(BIG, 0).Mul(Location.XYZValue(0, BIG))
    assert (res.X, res.Y, res.Z) == (BIG, BIG, 0.0)


def test_mul_through_the_argument_frame_is_710() -> None:
    """Mul uses Total(Location2): the frame chain's overflow is found there."""
    assert code_of(Location().Mul, _framed(BIG, BIG)) == ARITHMETIC_OVERFLOW


def test_inverse_whose_translation_overflows_is_710() -> None:
    # Rz(45): the inverse's X is -(cos45 * x + sin45 * y) = -0.707 * 3e308 -> -inf.
    loc = Location.XYZValue(1.5e308, 1.5e308, 0, 45)
    assert code_of(loc.Inverse) == ARITHMETIC_OVERFLOW
    # Without the rotation the same translation inverts exactly.
    inv = Location.XYZValue(1.2e308, 1.2e308).Inverse()
    assert (inv.X, inv.Y) == (-1.2e308, -1.2e308)


def test_pos_through_a_frame_that_overflows_is_710() -> None:
    loc = _framed(BIG, BIG)
    assert code_of(lambda: loc.Pos) == ARITHMETIC_OVERFLOW
    assert code_of(loc.total_pose) == ARITHMETIC_OVERFLOW
    assert code_of(Location.Distance, loc, Location()) == ARITHMETIC_OVERFLOW
    # PosWrtRef is what was stored, finite: still readable.
    assert loc.PosWrtRef.X == BIG


def test_setting_pos_in_a_frame_that_overflows_is_710_and_keeps_the_old_pose() -> None:
    loc = _framed(-BIG, 5.0)
    assert code_of(setattr, loc, "Pos", Location.XYZValue(BIG)) == ARITHMETIC_OVERFLOW
    assert loc.X == 5.0


def test_setting_poswrtref_from_an_overflowing_location_is_710() -> None:
    loc = Location()
    assert code_of(setattr, loc, "PosWrtRef", _framed(BIG, BIG)) == ARITHMETIC_OVERFLOW
    assert loc.X == 0.0


def test_xyzinc_that_overflows_is_710_and_keeps_the_old_pose() -> None:
    loc = Location.XYZValue(BIG, 1, 2)
    assert code_of(loc.XYZInc, BIG) == ARITHMETIC_OVERFLOW
    assert (loc.X, loc.Y, loc.Z) == (BIG, 1.0, 2.0)
    loc.XYZInc(-BIG)  # a legal step still works
    assert loc.X == 0.0


def test_distance_of_far_apart_points() -> None:
    """The distance is exact up to the Double range (no Python OverflowError from squaring) and
    -710 beyond it."""
    assert Location.Distance(Location.XYZValue(3e200, 4e200), Location()) == pytest.approx(5e200, rel=1e-15)
    assert code_of(Location.Distance, Location.XYZValue(BIG), Location.XYZValue(-BIG)) == ARITHMETIC_OVERFLOW


def test_here3_with_far_apart_points() -> None:
    """Here3 normalises its axes without squaring overflow; points beyond the range are -710."""
    loc = Location()
    loc.Here3(Location.XYZValue(0, 0, 0), Location.XYZValue(1e200, 0, 0), Location.XYZValue(0, 1e200, 0))
    assert (loc.X, loc.Y, loc.Z, loc.Yaw, loc.Pitch, loc.Roll) == (0, 0, 0, 0, 0, 0)
    loc = Location()
    assert code_of(
        loc.Here3, Location.XYZValue(-BIG), Location.XYZValue(BIG), Location.XYZValue(0, 1, 0)
    ) == ARITHMETIC_OVERFLOW


def test_pallet_cell_that_overflows_is_710() -> None:
    pallet = RefFrame()
    pallet.Type = 1
    pallet.set_PalletMaxIndex(1, 3)
    pallet.set_PalletPitch(1, BIG)
    pallet.set_PalletIndex(1, 2)
    assert pallet.Pos().X == BIG  # cell 2 is (2-1) * pitch: in range
    pallet.set_PalletIndex(1, 3)
    assert code_of(pallet.Pos) == ARITHMETIC_OVERFLOW
    assert code_of(pallet.PosWrtRef) == ARITHMETIC_OVERFLOW
    part = Location()
    part.RefFrame = pallet
    assert code_of(lambda: part.Pos) == ARITHMETIC_OVERFLOW


@pytest.fixture
def runaway_belt() -> Conveyor:
    c = Conveyor(mm_per_count=BIG, encoder=2.0)  # belt travel 2 * 1e308 mm
    register_conveyor(7, c)  # conftest.py unregisters it
    return c


def test_conveyor_position_that_overflows_is_710(runaway_belt: Conveyor) -> None:
    frame = conveyor_frame(7)
    assert code_of(frame.Pos) == ARITHMETIC_OVERFLOW
    runaway_belt.set_count(1.0)
    assert frame.Pos().X == BIG


def test_a_non_finite_pose_from_python_is_708() -> None:
    """A NaN or infinite component can only come from Python (``from_pose``/``from_matrix``): it is
    rejected there as -708 *Value infinite or NAN*, a bad input like ``loc.X = NaN``."""
    for bad in (math.nan, math.inf):
        pose = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, bad, 0.0, 0.0)
        assert code_of(Location.from_pose, pose) == VALUE_INFINITE_OR_NAN
        assert code_of(Location.from_matrix, np.array([pose[0:3] + pose[9:10], pose[3:6] + (0.0,),
                                                       pose[6:9] + (0.0,), (0, 0, 0, 1)])) == VALUE_INFINITE_OR_NAN


def test_here3_far_apart_collinear_points_are_still_707() -> None:
    """Scaling far-apart points keeps the collinearity test: -707 as for near points."""
    loc = Location()
    far = (Location.XYZValue(0), Location.XYZValue(1e200), Location.XYZValue(2e200))
    assert code_of(loc.Here3, *far) == VALUE_OUT_OF_RANGE


def test_conveyor_limit_that_overflows_is_710(runaway_belt: Conveyor) -> None:
    """ConveyorLimit measures along the belt through Inverse(nominal), whose translation overflows
    for this (finite, rotated) nominal; the NaN that the overflow leaves in the result is -710 too."""
    runaway_belt.set_count(0.0)
    runaway_belt.nominal = Location.XYZValue(1.5e308, 1.5e308, 0, 45).pose_wrt_ref
    frame = conveyor_frame(7)
    part = Location()
    part.RefFrame = frame
    assert part.Pos.X == 1.5e308  # the part's own position is in range
    assert code_of(part.ConveyorLimit, 0) == ARITHMETIC_OVERFLOW
