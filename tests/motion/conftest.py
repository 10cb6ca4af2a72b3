"""Fixtures shared by the motion tests."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from gplrt.controller.services import Controller
from gplrt.motion.robot_class import Robot
from gplrt.sim import Simulation


@pytest.fixture
def sim(request: pytest.FixtureRequest) -> Iterator[Simulation]:
    """A captured simulation whose robot 1 is attached, powered and homed, ready for Move.*.

    The robot model is the PF400SX unless a test names another through indirect
    parametrisation: ``@pytest.mark.parametrize("sim", ["XYZT-GCU"], indirect=True)``.
    Test modules that need the robot *not* ready (e.g. to check the errors before Attach/Home)
    define their own ``sim`` fixture, which takes precedence over this one.
    """
    s = Simulation(robot=getattr(request, "param", "PF400SX"), capture=True)
    with s:
        Robot.Attached = 1
        Controller.PowerEnabled = True
        Robot.Home()
        yield s
