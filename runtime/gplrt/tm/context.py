"""Which simulated robot (and Listen node) the running TMscript talks to.

Generated code calls ``tm.PTP(...)`` without naming a robot, as a TM robot runs one project; the
session that starts the code (``gpl2py run``, the Listen node, a test) sets the current one here.
"""

from __future__ import annotations

import math
from typing import Any

from gplrt.sim import Simulation
from gplrt.tm.motion import Robot
from gplrt.tm.robot import arm

_current: dict[str, Any] = {"robot": None, "node": None, "display": None}


def robot() -> Robot:
    """The current robot (a TM5-900 on the fast clock when nothing chose one)."""
    r = _current["robot"]
    if r is None:
        r = use_robot("TM5-900")
    return r  # type: ignore[no-any-return]


def use_robot(name: str = "TM5-900", speed: float = math.inf, clock: str | None = None) -> Robot:
    """Make a new simulated robot ``name`` the current one, in a session of its own
    (``gplrt.sim.Simulation``) on ``clock``: ``fast`` (the default), ``virtual`` or ``real``
    (``speed`` controller seconds per wall second); a finite ``speed`` alone means ``real``."""
    if clock is None:
        clock = "fast" if math.isinf(speed) else "real"
    sim = Simulation(clock=clock, speed=1.0 if math.isinf(speed) else speed)  # type: ignore[arg-type]
    previous = _current["robot"]
    r = Robot(arm(name), sim=sim)
    _current["robot"] = r
    if previous is not None and not previous.servers:
        previous.close()  # (one still serving clients, a notebook's first robot, runs on)
    return r


def node() -> Any:
    """The Listen node running the current script, or None."""
    return _current["node"]


def set_node(n: object) -> None:
    _current["node"] = n


def set_display(callback: object) -> None:
    """Where ``Display()`` text goes (default: standard output)."""
    _current["display"] = callback


def display_callback() -> Any:
    return _current["display"]
