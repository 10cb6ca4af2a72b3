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

Ruckig instances are cached per degree-of-freedom count and per thread: a fresh ``Trajectory`` per segment is
all that has to be allocated, which keeps ``Move.Loc`` planning cost close to a bare
``Ruckig.calculate`` (benchmarks/motion_speed.py measures the ratio).
"""

from __future__ import annotations

import math
import threading
from collections.abc import Sequence

import numpy as np
from ruckig import ControlInterface, InputParameter, Result, Ruckig, RuckigError, Synchronization, Trajectory

from gplrt.lang.errors import ASYNCHRONOUS_SOFT_ERROR, GplException
from gplrt.motion.limits import AxisLimits, Vec

#: GPL *Invalid Cartesian value*-family errors do not fit a planner failure; -1043 *Asynchronous
#: soft error* (ASYNCHRONOUS_SOFT_ERROR) is what the controller reports when its trajectory generator
#: cannot proceed.
PLANNING_FAILED = ASYNCHRONOUS_SOFT_ERROR

class _Cache(threading.local):
    """Per Python thread (so per GPL thread): under the real clock threads plan preemptively, and
    one shared InputParameter would hand a plan another thread's start, target or limits."""

    def __init__(self) -> None:
        #: n -> (Ruckig, InputParameter, what the input was last given: unchanged inputs are not
        #: converted again)
        self.solvers: dict[int, tuple[Ruckig, InputParameter, dict[str, object]]] = {}


_cache = _Cache()


_AXES = "axes"


def _solver(n: int) -> tuple[Ruckig, InputParameter, dict[str, object]]:
    """This thread's Ruckig, InputParameter and record of what the input was last given."""
    solver = _cache.solvers.get(n)
    if solver is None:
        solver = _cache.solvers[n] = (Ruckig(n), InputParameter(n), {})
    return solver


def _set(given: dict[str, object], inp: InputParameter, name: str, value: object) -> None:
    if given.get(name) != value:
        setattr(inp, name, value)
        given[name] = value


class Plan:
    """A planned Ruckig trajectory; ``at(t)`` gives (position, velocity, acceleration) lists,
    ``sample(ts)`` the same at many times at once, as arrays."""

    __slots__ = ("traj", "duration", "_pieces")

    def __init__(self, traj: Trajectory, duration: float) -> None:
        self.traj = traj
        self.duration = duration
        self._pieces: _Pieces | None = None

    def at(self, t: float) -> tuple[list[float], list[float], list[float]]:
        return self.traj.at_time(min(max(t, 0.0), self.duration))  # type: ignore[no-any-return]

    def sample(self, ts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``at(t)`` for every ``t`` of ``ts``: positions, velocities, accelerations (N×dof).

        Why: a path motion's cycles and the blend planner read a plan at dozens of times, and
        one ``at_time`` call per time costs more than the arithmetic.  This is Ruckig's own
        evaluation (``Trajectory::at_time``: the phase whose cumulative end is the first past
        ``t``, then ``p + t·(v + t·(a/2 + t·j/6))``) in numpy, operation for operation, so the
        values are those ``at`` gives (tests/motion/test_planner.py checks them bit for bit)."""
        t = np.clip(np.asarray(ts, dtype=float), 0.0, self.duration)
        pieces = self._pieces
        if pieces is None:
            pieces = self._pieces = _pieces(self.traj)
        if pieces is _AT_TIME:  # a profile with a brake or accel pre-phase: Ruckig itself
            states = [self.traj.at_time(float(x)) for x in t]
            return tuple(np.array([st[i] for st in states]).reshape(len(t), -1) for i in range(3))  # type: ignore[return-value]
        starts, ends, p0, v0, a0, j = pieces
        T = t[:, None]
        # upper_bound over each DOF's cumulative phase ends (N×dof); past the last one, the final
        # state with no jerk (Ruckig's "t_diff >= t_sum.back()" case); phase 0 starts at 0.0,
        # and t − 0.0 is t, as Ruckig leaves it
        k = (T[:, :, None] >= ends[None, :, :]).sum(axis=2)
        rows = np.arange(len(ends))[None, :]
        dt = T - starts[rows, k]
        pk, vk, ak, jk = p0[rows, k], v0[rows, k], a0[rows, k], j[rows, k]
        P = pk + dt * (vk + dt * (ak / 2.0 + dt * jk / 6.0))
        V = vk + dt * (ak + dt * jk / 2.0)
        A = ak + dt * jk
        end = t >= self.duration  # Ruckig's "time >= duration": the final state itself
        if end.any():
            P[end], V[end], A[end] = p0[:, -1], v0[:, -1], a0[:, -1]
        return P, V, A


#: (phase starts, phase ends, start positions, velocities, accelerations, jerks): dof×8 arrays
#: (ends dof×7) for ``Plan.sample``
_Pieces = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
_AT_TIME: _Pieces = (np.empty(0),) * 6


def _pieces(traj: Trajectory) -> _Pieces:
    """The phases of a one-section trajectory's profiles, for ``Plan.sample``; ``_AT_TIME``
    when Ruckig's own evaluation must be used (a brake or accel pre-phase, several sections)."""
    sections = traj.profiles
    if len(sections) != 1:
        return _AT_TIME
    profiles = sections[0]
    for prof in profiles:
        if prof.brake.duration > 0.0 or prof.accel.duration > 0.0:
            return _AT_TIME
    ends = np.cumsum([prof.t for prof in profiles], axis=1)  # Ruckig's t_sum: the same running sums
    starts = np.concatenate((np.zeros((len(profiles), 1)), ends), axis=1)
    jerk = np.concatenate(([prof.j for prof in profiles], np.zeros((len(profiles), 1))), axis=1)  # past the end: none
    return (starts, ends, np.array([prof.p for prof in profiles]), np.array([prof.v for prof in profiles]),
            np.array([prof.a for prof in profiles]), jerk)


#: Ruckig occasionally fails on inputs that sit exactly on a profile boundary (for instance a
#: jerk that reaches peak acceleration exactly at peak velocity); shaving the jerk and velocity
#: limits by these factors moves the input off the boundary without a visible change.
_RETRY_FACTORS = (1.0 - 1e-9, 1.0 - 1e-6, 1.0 - 1e-4)


_WORKING, _FINISHED = Result.Working, Result.Finished


def _calculate(otg: Ruckig, inp: InputParameter, given: dict[str, object], n: int, what: str) -> Plan:
    traj = Trajectory(n)
    try:
        result = otg.calculate(inp, traj)
    except (RuckigError, ValueError):  # ValueError: a Result code the binding's enum lacks
        result = None
    if result is _WORKING or result is _FINISHED:
        return Plan(traj, traj.duration)
    return _retry(otg, inp, given, n, what)


def _retry(otg: Ruckig, inp: InputParameter, given: dict[str, object], n: int, what: str) -> Plan:
    """Shave the jerk and velocity limits off a profile boundary (see ``_RETRY_FACTORS``)."""
    jerk, vel = list(inp.max_jerk), list(inp.max_velocity)
    detail = ""
    for factor in _RETRY_FACTORS:
        inp.max_jerk = given["max_jerk"] = [j * factor for j in jerk]
        inp.max_velocity = given["max_velocity"] = [v * factor for v in vel]
        given["lim"] = given["limits"] = None  # the next plan must set its own limits again
        traj = Trajectory(n)
        try:
            result = otg.calculate(inp, traj)
        except RuckigError as exc:
            detail = str(exc).strip().splitlines()[0] if str(exc).strip() else "RuckigError"
            continue
        except ValueError as exc:
            # Ruckig returned a code its Python enum does not name, e.g. -101
            # ErrorTrajectoryDuration (a Speed so low the motion would outlast Ruckig's range)
            detail = f"Ruckig result {exc}"
            continue
        if result in (Result.Working, Result.Finished):
            return Plan(traj, float(traj.duration))
        detail = f"Ruckig {result.name}"
    raise GplException(PLANNING_FAILED, detail=f"{what}: {detail}")


def _finite(values: Vec) -> list[float]:
    return [float(v) if math.isfinite(v) else math.inf for v in values]


def plan_axes(q0: Sequence[float], v0: Sequence[float] | None, a0: Sequence[float] | None,
              q1: Sequence[float], lim: AxisLimits) -> Plan:
    """Synchronised joint trajectory from state (q0, v0, a0) to q1 at rest (None = 0); a ``list``
    or ``tuple`` ``q1`` must hold Python floats (it is handed to Ruckig as it is).

    Only what differs from the previous call is handed to Ruckig (the limits of a Profile
    repeat move after move), so the cost stays close to a bare ``Ruckig.calculate``."""
    n = len(q0)
    otg, inp, given = _cache.solvers.get(n) or _solver(n)
    p0 = q0.tolist() if type(q0) is np.ndarray else [float(x) for x in q0]
    p1 = (q1 if type(q1) is list or type(q1) is tuple else q1.tolist() if isinstance(q1, np.ndarray)
          else [float(x) for x in q1])
    if given.get("mode") is not _AXES:
        given.clear()  # another mode's memo says nothing of what the input holds now
        zero = [0.0] * n
        for name, value in (("control_interface", ControlInterface.Position),
                            ("synchronization", Synchronization.Time), ("target_velocity", zero),
                            ("target_acceleration", zero), ("current_velocity", zero),
                            ("current_acceleration", zero)):
            _set(given, inp, name, value)
        given["mode"], given["moving"], given["lim"] = _AXES, False, None
    if v0 is not None or given["moving"]:
        zero = [0.0] * n
        inp.current_velocity = zero if v0 is None else [float(x) for x in v0]
        inp.current_acceleration = zero if a0 is None else [float(x) for x in a0]
        given["moving"] = v0 is not None
    inp.current_position = p0
    inp.target_position = p1
    # With Accel = Decel the limits do not depend on the direction of travel: skip comparing it.
    if lim.symmetric:
        if given["lim"] is lim and given["up"] is None:  # the same limits as the last joint move
            return _calculate(otg, inp, given, n, "joint move")
        up = None
    else:
        up = [e >= s for s, e in zip(p0, p1)]
    if given["lim"] is not lim or given["up"] != up:
        vel, acc, dec, jerk = lim.lists
        inp.max_velocity = vel
        if up is None:
            inp.max_acceleration = acc
            inp.min_acceleration = [-a for a in acc]
        else:
            inp.max_acceleration = [a if u else d for a, d, u in zip(acc, dec, up)]
            inp.min_acceleration = [-d if u else -a for a, d, u in zip(acc, dec, up)]
        inp.max_jerk = jerk
        given["lim"], given["up"] = lim, up
    return _calculate(otg, inp, given, n, "joint move")


_SCALAR = "scalar"


def plan_scalar(s0: float, v0: float, a0: float, s1: float, vmax: float, amax: float, dmax: float,
                jerk: float) -> Plan:
    """One-DOF trajectory of a path parameter from (s0, v0, a0) to s1 at rest (s1 ≥ s0).

    A straight ``Move.Loc`` plans one of these when it is queued: the start (0 → 1 from rest,
    as a rule) repeats, so it is handed to Ruckig only when it changes."""
    otg, inp, given = _cache.solvers.get(1) or _solver(1)
    if given.get("mode") is not _SCALAR:
        given.clear()
        inp.control_interface = ControlInterface.Position
        inp.synchronization = Synchronization.Time
        inp.target_velocity = [0.0]
        inp.target_acceleration = [0.0]
        given["mode"] = _SCALAR
    start = (s0, v0, a0, s1)
    if given.get("start") != start:
        inp.current_position = [s0]
        inp.current_velocity = [v0]
        inp.current_acceleration = [a0]
        inp.target_position = [s1]
        given["start"] = start
    # (the limits are set every time: they follow each line's length and chord, so a memo of
    # them would cost more than it saves)
    inp.max_velocity = [vmax]
    inp.max_acceleration = [amax]
    inp.min_acceleration = [-dmax]
    inp.max_jerk = [jerk if math.isfinite(jerk) else math.inf]
    return _calculate(otg, inp, given, 1, "path move")


def plan_stop(q0: Vec, v0: Vec, a0: Vec, decel: Vec, jerk: Vec) -> Plan:
    """Bring every axis to rest as fast as ``decel``/``jerk`` allow (``Robot.RapidDecel``)."""
    n = len(q0)
    otg, inp, given = _solver(n)
    if given.get("mode") != "stop":
        given.clear()  # another mode's memo says nothing of what the input holds now
    for name, value in (("control_interface", ControlInterface.Velocity), ("synchronization", Synchronization.No),
                        ("current_position", [float(x) for x in q0]), ("current_velocity", [float(x) for x in v0]),
                        ("current_acceleration", [float(x) for x in a0]), ("target_velocity", [0.0] * n),
                        ("target_acceleration", [0.0] * n), ("max_velocity", [math.inf] * n),
                        ("max_acceleration", [float(x) for x in decel]),
                        ("min_acceleration", [float(-x) for x in decel]), ("max_jerk", _finite(jerk))):
        _set(given, inp, name, value)
    given["mode"] = "stop"
    return _calculate(otg, inp, given, n, "rapid deceleration")
