"""Profile members convert what they are given by GPL's rules, as a transpiled store would.

Hand-written Python (a notebook, a --setup file) can hand a Profile any value; it must get the
controller's error codes, never a bare Python ValueError or TypeError, and text must read as CBool
and CStr read it.
"""

from __future__ import annotations

import pytest

from gpltest import code_of
from gplrt.lang.errors import INVALID_NUMBER_FORMAT, NOTHING_VALUE
from gplrt.motion.profile import Profile


@pytest.mark.parametrize("member", ["Speed", "Speed2", "Accel", "Decel", "AccelRamp", "DecelRamp", "InRange"])
def test_numeric_members_parse_numeric_text_and_refuse_bad_values(member: str) -> None:
    prof = Profile()
    setattr(prof, member, "30")
    assert getattr(prof, member) == 30.0
    assert code_of(setattr, prof, member, "fast") == INVALID_NUMBER_FORMAT
    assert code_of(setattr, prof, member, None) == NOTHING_VALUE


def test_straight_reads_text_as_cbool_does() -> None:
    prof = Profile()
    prof.Straight = "True"
    assert prof.Straight is True
    prof.Straight = "False"
    assert prof.Straight is False  # bool("False") would be True
    prof.Straight = -1
    assert prof.Straight is True


def test_text_follows_cstr() -> None:
    prof = Profile()
    prof.Text = 2.0
    assert prof.Text == "2"
