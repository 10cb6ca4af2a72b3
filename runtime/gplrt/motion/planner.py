"""Ruckig planning: time-optimal, jerk-limited trajectories for joint moves and path parameters.

Two entry points, both returning a :class:`Plan` (a Ruckig ``Trajectory`` with its duration):

* :func:`plan_axes` — all axes of a joint-interpolated move, time-synchronised
  (``Synchronization.Time``: every axis starts and ends together), from any current state
  (position, velocity, acceleration: the start of a blended motion moves) to a target at rest;
* :func:`plan_scalar` — one degree of freedom, the path parameter of a straight line or an arc.

Ruckig has symmetric-looking limits but separate ``max_acceleration`` / ``min_acceleration``;
Profile.Accel and Profile.Decel are mapped onto them by direction of travel: an axis moving in +
accelerates with ``max_acceleration`` and brakes with ``min_acceleration``, so Accel applies while
speeding up and Decel while slowing down (for an axis moving in − the two swap).  Units are GPL
units (mm, deg, s); see limits.py.

Ruckig instances are cached per degree-of-freedom count: a fresh ``Trajectory`` per segment is
all that has to be allocated, which keeps ``Move.Loc`` planning cost close to a bare
``Ruckig.calculate`` (benchmarks/motion_speed.py measures the ratio).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from ruckig import ControlInterface, InputParameter, Result, Ruckig, RuckigError, Synchronization, Trajectory

from gplrt.lang.errors import GplException
from gplrt.motion.limits import AxisLimits, Vec

#: GPL *Invalid Cartesian value*-family errors do not fit a planner failure; -1043 *Asynchronous
#: soft error* is what the controller reports when its trajectory generator cannot proceed.
PLANNING_FAILED = -1043

_ruckig: dict[int, tuple[Ruckig, InputParameter]] = {}


def _solver(n: int) -> tuple[Ruckig, InputParameter]:
    pair = _ruckig.get(n)
    if pair is None:
        pair = _ruckig[n] = (Ruckig(n), InputParameter(n))
    return pair


@dataclass(frozen=True)
class Plan:
    """A planned Ruckig trajectory; ``at(t)`` gives (position, velocity, acceleration) lists."""

    traj: Trajectory
    duration: float

    def at(self, t: float) -> tuple[list[float], list[float], list[float]]:
        return self.traj.at_time(min(max(t, 0.0), self.duration))  # type: ignore[no-any-return]


#: Ruckig occasionally fails on inputs that sit exactly on a profile boundary (for instance a
#: jerk that reaches peak acceleration exactly at peak velocity); shaving the jerk and velocity
#: limits by these factors moves the input off the boundary without a visible change.
_RETRY_FACTORS = (1.0 - 1e-9, 1.0 - 1e-6, 1.0 - 1e-4)


def _calculate(inp: InputParameter, n: int, what: str) -> Plan:
    otg = _ruckig[n][0]
    jerk, vel = list(inp.max_jerk), list(inp.max_velocity)
    detail = ""
    for factor in (1.0, *_RETRY_FACTORS):
        if factor != 1.0:
            inp.max_jerk = [j * factor for j in jerk]
            inp.max_velocity = [v * factor for v in vel]
        traj = Trajectory(n)
        try:
            result = otg.calculate(inp, traj)
        except RuckigError as exc:
            detail = str(exc).strip().splitlines()[0] if str(exc).strip() else "RuckigError"
            continue
        if result in (Result.Working, Result.Finished):
            return Plan(traj, float(traj.duration))
        detail = f"Ruckig {result.name}"
    raise GplException(PLANNING_FAILED, detail=f"{what}: {detail}")


def _finite(values: Vec) -> list[float]:
    return [float(v) if math.isfinite(v) else math.inf for v in values]


def plan_axes(q0: Vec, v0: Vec, a0: Vec, q1: Vec, lim: AxisLimits) -> Plan:
    """Synchronised joint trajectory from state (q0, v0, a0) to q1 at rest."""
    n = len(q0)
    _, inp = _solver(n)
    inp.control_interface = ControlInterface.Position
    inp.synchronization = Synchronization.Time
    inp.current_position = [float(x) for x in q0]
    inp.current_velocity = [float(x) for x in v0]
    inp.current_acceleration = [float(x) for x in a0]
    inp.target_position = [float(x) for x in q1]
    inp.target_velocity = [0.0] * n
    inp.target_acceleration = [0.0] * n
    up = np.asarray(q1) >= np.asarray(q0)
    inp.max_velocity = [float(x) for x in lim.velocity]
    inp.max_acceleration = [float(x) for x in np.where(up, lim.accel, lim.decel)]
    inp.min_acceleration = [float(-x) for x in np.where(up, lim.decel, lim.accel)]
    inp.max_jerk = _finite(lim.jerk)
    return _calculate(inp, n, "joint move")


def plan_scalar(s0: float, v0: float, a0: float, s1: float, vmax: float, amax: float, dmax: float,
                jerk: float) -> Plan:
    """One-DOF trajectory of a path parameter from (s0, v0, a0) to s1 at rest (s1 ≥ s0)."""
    _, inp = _solver(1)
    inp.control_interface = ControlInterface.Position
    inp.synchronization = Synchronization.Time
    inp.current_position = [s0]
    inp.current_velocity = [v0]
    inp.current_acceleration = [a0]
    inp.target_position = [s1]
    inp.target_velocity = [0.0]
    inp.target_acceleration = [0.0]
    inp.max_velocity = [vmax]
    inp.max_acceleration = [amax]
    inp.min_acceleration = [-dmax]
    inp.max_jerk = [jerk if math.isfinite(jerk) else math.inf]
    return _calculate(inp, 1, "path move")


def plan_stop(q0: Vec, v0: Vec, a0: Vec, decel: Vec, jerk: Vec) -> Plan:
    """Bring every axis to rest as fast as ``decel``/``jerk`` allow (``Robot.RapidDecel``)."""
    n = len(q0)
    _, inp = _solver(n)
    inp.control_interface = ControlInterface.Velocity
    inp.synchronization = Synchronization.No
    inp.current_position = [float(x) for x in q0]
    inp.current_velocity = [float(x) for x in v0]
    inp.current_acceleration = [float(x) for x in a0]
    inp.target_velocity = [0.0] * n
    inp.target_acceleration = [0.0] * n
    inp.max_velocity = [math.inf] * n
    inp.max_acceleration = [float(x) for x in decel]
    inp.min_acceleration = [float(-x) for x in decel]
    inp.max_jerk = _finite(jerk)
    try:
        return _calculate(inp, n, "rapid deceleration")
    finally:
        inp.control_interface = ControlInterface.Position
