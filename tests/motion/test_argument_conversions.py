"""Move, Robot and PDb arguments convert by GPL's rules, as a transpiled call would.

Hand-written Python (a notebook, a --setup file) can pass any value: it must get the controller's
codes (-717 bad numeric text, -708 a NaN/infinite value, -202 another object than a Location or
Profile), never a bare ValueError or AttributeError, and Integer arguments round as CInt does
instead of truncating.
"""

from __future__ import annotations

import math

import pytest

from gplrt.controller.pdb import default_database
from gplrt.geometry.location import Location
from gplrt.lang.errors import INVALID_ARGUMENT, INVALID_NUMBER_FORMAT, VALUE_INFINITE_OR_NAN, VALUE_OUT_OF_RANGE
from gplrt.motion.move import MAX_DELAY, Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation
from gpltest import code_of


@pytest.mark.parametrize(("call", "code"), [
    (lambda: Move.OneAxis(1, "fast", False, Profile()), INVALID_NUMBER_FORMAT),
    (lambda: Move.OneAxis(1, math.nan, False, Profile()), VALUE_INFINITE_OR_NAN),
    (lambda: Move.OneAxis("one", 300.0, False, Profile()), INVALID_NUMBER_FORMAT),
    (lambda: Move.Delay("long"), INVALID_NUMBER_FORMAT),
    (lambda: Move.Delay(math.nan), VALUE_INFINITE_OR_NAN),
    (lambda: Move.Delay(1e300), VALUE_OUT_OF_RANGE),  # was queued, then overflowed at WaitForEOM
    (lambda: Move.Delay(MAX_DELAY + 0.001), VALUE_OUT_OF_RANGE),
    (lambda: Move.Extra("x"), INVALID_NUMBER_FORMAT),
    (lambda: Move.Extra(100.0, math.inf), VALUE_INFINITE_OR_NAN),
    (lambda: setattr(Robot, "Attached", "robot one"), INVALID_NUMBER_FORMAT),
    (lambda: setattr(Robot, "Selected", "x"), INVALID_NUMBER_FORMAT),
    (lambda: Robot.set_Payload("heavy"), INVALID_NUMBER_FORMAT),
    # another object than the Location/Profile asked for (was an AttributeError)
    (lambda: Move.Loc(3.0, Profile()), INVALID_ARGUMENT),
    (lambda: Move.Loc(Location.from_angles([300.0, 0.0, 90.0, 0.0, 100.0]), "fast"), INVALID_ARGUMENT),
    (lambda: Move.Loc(Location.XYZValue(300.0, 0.0, 200.0, 0.0, 90.0, 180.0), 1), INVALID_ARGUMENT),
    (lambda: Move.Rel("x", Profile()), INVALID_ARGUMENT),
    (lambda: Move.Approach(1, Profile()), INVALID_ARGUMENT),
    (lambda: Move.Arc(Location(), 2.0, Profile()), INVALID_ARGUMENT),
    (lambda: Move.OneAxis(1, 300.0, False, "p"), INVALID_ARGUMENT),
    (lambda: Robot.set_Tool("flange"), INVALID_ARGUMENT),
    (lambda: Robot.set_Base(0), INVALID_ARGUMENT),
])
def test_bad_values_get_gpl_codes_and_queue_nothing(sim: Simulation, call: object, code: int) -> None:
    before = len(sim.robots[1].queue.history)
    assert code_of(call) == code
    assert len(sim.robots[1].queue.history) == before


def test_numeric_text_and_real_axis_numbers_convert_as_cint_and_cdbl(sim: Simulation) -> None:
    Move.Loc(Location.from_angles([300.0, 0.0, 90.0, 0.0, 100.0]), Profile())
    Move.OneAxis(0.6, "350", False, Profile())  # axis 0.6 rounds to 1 (int() would give 0: -1002)
    Move.OneAxis("3", 10.0, True, Profile())
    Move.Delay("0.25")
    Move.WaitForEOM()
    assert Robot.WhereAngles().axis_values() == (350.0, 0.0, 100.0, 0.0, 100.0)
    Robot.set_Payload("12.5")
    assert Robot.Payload() == 12.5


def test_pdbnum_write_converts_text_and_refuses_bad_text() -> None:
    db = default_database("PF400SX")
    db.set_pdb_num("75", 601)
    assert db.pdb_num(601) == 75.0
    assert code_of(db.set_pdb_num, "fast", 601) == INVALID_NUMBER_FORMAT
    assert db.pdb_num(601) == 75.0


def test_the_longest_delay_is_queued_and_waited_for(sim: Simulation) -> None:
    t0 = sim.now()
    Move.Delay(MAX_DELAY)
    Move.WaitForEOM()
    assert sim.now() - t0 == pytest.approx(MAX_DELAY, abs=1e-6)
