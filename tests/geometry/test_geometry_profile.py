"""Profile: controller defaults from the parameter files, every property, range checks, Clone."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from gplrt.lang.errors import GplException
from gplrt.motion.profile import Profile, set_profile_defaults

import gplrt

# The PF400 parameter file shipped with the runtime (a byte-identical copy of the controller's).
PF400_PAC = Path(gplrt.__file__).parent / "data" / "robots" / "pf400sx" / "robot01.pac"


def _pdb_value(text: str, data_id: int) -> float:
    m = re.search(rf"^DI: {data_id},.*= *([-0-9.Ee+]+)", text, re.MULTILINE)
    assert m, data_id
    return float(m.group(1))


def test_defaults_are_the_pf400_parameter_database_defaults() -> None:
    p = Profile()
    text = PF400_PAC.read_text()
    want = [_pdb_value(text, i) for i in (2708, 2709, 2710, 2711, 2712, 2713)]
    assert want == [50, 0, 100, 100, 0.1, 0.1]  # as robot-models.md §2.4 records for the PF400 sets
    assert [p.Speed, p.Speed2, p.Accel, p.Decel, p.AccelRamp, p.DecelRamp] == want
    assert p.Straight is False and p.InRange == 0.0 and p.Text == ""


def test_every_property_round_trips() -> None:
    p = Profile()
    p.Speed, p.Speed2, p.Accel, p.Decel = 75, 20, 150, 120
    p.AccelRamp, p.DecelRamp, p.Straight, p.InRange, p.Text = 0.25, 0, True, -1, "fast"
    assert [p.Speed, p.Speed2, p.Accel, p.Decel, p.AccelRamp, p.DecelRamp] == [75, 20, 150, 120, 0.25, 0]
    assert (p.Straight, p.InRange, p.Text, p.blends) == (True, -1, "fast", True)


def test_ex10_speed_reduction() -> None:
    """EX-10: ``profile1.Speed *= .9`` on retry."""
    p = Profile()
    p.Speed *= 0.9
    assert p.Speed == pytest.approx(45.0)


def test_clone_is_independent() -> None:
    p = Profile()
    p.Speed = 10
    q = p.Clone()
    p.Speed = 20
    assert (q.Speed, p.Speed) == (10, 20)
    assert q is not p


@pytest.mark.parametrize(
    "name, value, code",
    [
        ("Speed", 0, -705), ("Speed", -5, -705), ("Accel", 0, -705), ("Decel", -1, -705),
        ("Speed2", -1, -705), ("AccelRamp", -0.1, -705), ("DecelRamp", -1, -705),
        ("Speed", float("nan"), -708), ("InRange", float("inf"), -708), ("AccelRamp", float("inf"), -708),
    ],
)  # fmt: skip
def test_range_checks(name: str, value: float, code: int) -> None:
    p = Profile()
    before = getattr(p, name)
    with pytest.raises(GplException) as info:
        setattr(p, name, value)
    assert info.value.ErrorCode == code
    assert getattr(p, name) == before


def test_robot_specific_defaults() -> None:
    set_profile_defaults(speed=100)
    try:
        assert Profile().Speed == 100
    finally:
        set_profile_defaults()
    assert Profile().Speed == 50
