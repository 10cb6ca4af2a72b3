"""A motion plans with its Profile's values at the time of the Move, however the runtime memoises.

``Profile.values`` is one tuple per Profile state and the limits are memoised by its identity
(``RobotLimits.joint_limits``/``line_limits``): a member changed between two Moves, on the Profile
itself or on a Clone, must reach the next motion exactly as a fresh Profile with those values
would plan it, and a motion already queued keeps the values it was queued with.
"""

from __future__ import annotations

import pytest

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.motion.move import Move
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.session import current_session
from gplrt.sim import Simulation

START, GOAL = Location(), Location()
START.XYZ(400.0, 0.0, 300.0, 0.0, 90.0, 180.0)
GOAL.XYZ(450.0, 100.0, 250.0, 20.0, 90.0, 180.0)

#: (member, new value): each changes the plan of a joint move or a straight line
CHANGES = [("Speed", 20.0), ("Speed2", 5.0), ("Accel", 30.0), ("Decel", 25.0), ("AccelRamp", 0.4),
           ("DecelRamp", 0.5), ("InRange", 3.0), ("Straight", None)]  # (None: the other path type)


def _duration(prof: Profile) -> float:
    """The planned duration (settling included) of a move from START to GOAL, from rest."""
    Move.Loc(START, Profile())
    Move.WaitForEOM()
    Move.Loc(GOAL, prof)
    seg = current_session().robots[1].queue.last
    assert seg is not None
    Move.WaitForEOM()
    return float(seg.duration + seg.settle)  # (not end − t0: that rounds with the start time)


def _ready() -> None:
    Robot.Attached = 1
    Controller.PowerEnabled = True
    Robot.Home()


def _base(straight: bool) -> Profile:
    prof = Profile()
    prof.Straight = straight
    return prof


#: (path type, member, value); Speed2 bounds the rotation of Cartesian paths only
CASES = [pytest.param(straight, member, value, id=f"{'straight' if straight else 'joint'}-{member}")
         for straight in (False, True) for member, value in CHANGES if straight or member != "Speed2"]


@pytest.mark.parametrize("straight,member,value", CASES)
@pytest.mark.parametrize("clone", [False, True], ids=["same", "clone"])
def test_a_member_changed_between_moves_reaches_the_next_move(straight: bool, member: str, value: object,
                                                              clone: bool) -> None:
    if member == "Straight":
        value = not straight
    with Simulation(capture=True):
        _ready()
        prof = _base(straight)
        before = _duration(prof)
        changed = prof.Clone() if clone else prof
        assert _duration(changed) == before  # (the memo is warm for these values)
        setattr(changed, member, value)
        after = _duration(changed)
    fresh = _base(straight)
    setattr(fresh, member, value)
    with Simulation(capture=True):
        _ready()
        expected = _duration(fresh)
    assert after == expected
    assert after != before


def test_a_queued_motion_keeps_the_values_it_was_queued_with() -> None:
    with Simulation(capture=True) as s:
        _ready()
        prof = Profile()
        Move.Loc(GOAL, prof)
        seg = s.robots[1].queue.last
        prof.Speed = 10.0
        prof.InRange = -5.0
        Move.Loc(START, prof)
        later = s.robots[1].queue.last
        Move.WaitForEOM()
    assert seg is not None and later is not None
    assert Profile().values() == seg.profile
    assert later.profile is not None and later.profile[0] == 10.0 and later.profile[7] == -5.0
