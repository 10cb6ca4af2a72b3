"""A Cartesian path motion as the controller runs it: planned once, its joints solved each cycle.

The controller's trajectory planner plans a straight line (or arc) as a profile of the path
parameter only; the kinematics run every trajectory cycle while the robot moves (gpl-classes
§22.4: "1-DOF Ruckig on the path parameter ..., limits from the nominal Cartesian speed; IK each
cycle").  So queueing a straight move costs one IK (the destination, refused at once with its
code when unreachable or out of range) and one 1-DOF Ruckig plan; :class:`PathRun` then solves
the joints lazily, cycle by cycle, only as far as the robot's state is actually read (Where,
the trace, WaitForEOM's end, a blend's start).

Decisions [P] (the manuals are silent on what happens mid-path; documented here):

* **Cycle**: ``CYCLE`` = 16 ms, the standard trajectory generation period ("62.5 Hz", seed
  002_222113dd5a155b3a.txt:6551).  Each cycle's pose is solved with the full checks of
  ``RobotModel.inverse`` (soft limits -1012 with the axis, -1039/-1040 too close/far, -1033).
* **A mid-path error stops the robot at the last good cycle** (its joints, at that cycle's
  time) and is delivered as the asynchronous motion error of the robot: the next ``Move`` or
  ``WaitForEOM`` of the attached thread raises it (catchable by the program's Try/Catch).
* **Joint speed along the path**: the profile is planned from the Cartesian limits, and from
  the joints' *chord* (``|q1 − q0|`` against the Profile's joint speed and acceleration): any
  joint path between the two ends needs at least that much, so the bound never slows a line
  more than the exact joint analysis would, and it alone governs the axes that move linearly
  along the path (rail, grippers).  The controller does not re-plan a queued motion: where the
  geometry makes a joint faster than its maximum (``2700 × 2704 %``, e.g. a line grazing the
  PF400's column) the servo reports -3106 *Axis over-speed* with the axis; where it asks a joint
  for more than its maximum acceleration (``2702 ×`` the larger of 2705 %/2706 %) the servo
  cannot follow and reports -3122 *Soft envelope error*.  Either stops the robot at the last
  good cycle (``PathRun._check_rates``: both are checked on the cycles, as the servos see them).
  Below those maxima a joint may run faster than the Profile's percentage of its speed: a
  straight line's speed is the Cartesian one.
* Soft-limit bulges between two cycles (16 ms apart) are not searched for.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from gplrt.lang.errors import AXIS_OVER_SPEED, SOFT_ENVELOPE_ERROR, GplException
from gplrt.motion.limits import MIN_RAMP, LineLimits, Vec
from gplrt.motion.planner import Plan
from gplrt.motion.straight import Path, PathIK, PathJoints

#: Trajectory cycle (s): the standard 62.5 Hz of the trajectory generator.
CYCLE = 0.016
#: The last cycle before a motion's end is at least this far (s) from it (``run_to``).
END_GAP = CYCLE / 4
#: Relative tolerance on the over-speed check (finite differences over one cycle).
OVER_SPEED_TOLERANCE = 1e-6
#: Cycles solved per batch (``RobotModel.inverse_path``) when the state is read far ahead
#: (8 s of motion: a line is solved in one batch as a rule; a longer one in a few).
BATCH = 512


@dataclass(frozen=True)
class Fault:
    """Where a path motion stopped: the last good cycle (local time, path parameter, joints) and
    the error that stopped it."""

    t: float
    u: float
    q: Vec
    error: GplException


def path_limits(length: float, turn: float, q0: list[float], q1: list[float],
                lim: LineLimits) -> tuple[float, float, float, float]:
    """(u̇_max, ü_max accel, ü_max decel, jerk) of the 1-D plan: the Cartesian limits over the
    path's ``length`` and ``turn``, and the joints' chord from ``q0`` to ``q1`` (see the module
    docstring).

    Each bound is ``limit / extent`` (u runs 0 → 1 over the extent) and the smallest wins;
    written as plain comparisons on Python floats, as every straight ``Move.Loc`` runs it: the
    Cartesian extents first, then a loop over the joints' chords (``zip`` rather than indexing,
    about 40 % less time than one loop over all the extents)."""
    inf = math.inf
    v = acc = dec = inf
    vel, accel, decel = lim.velocity, lim.accel, lim.decel
    if length > 1e-12:  # the path's length ...
        v, acc, dec = vel[0] / length, accel[0] / length, decel[0] / length
    if turn > 1e-12:  # ... and its turn
        x = vel[1] / turn
        if x < v:
            v = x
        x = accel[1] / turn
        if x < acc:
            acc = x
        x = decel[1] / turn
        if x < dec:
            dec = x
    # then each joint's chord |q1 − q0|
    for e1, e0, vi, ai, di in zip(q1, q0, lim.joint_velocity, lim.joint_accel, lim.joint_decel):
        extent = abs(e1 - e0)
        if extent > 1e-12:
            x = vi / extent
            if x < v:
                v = x
            x = ai / extent
            if x < acc:
                acc = x
            x = di / extent
            if x < dec:
                dec = x
    if v == inf:  # nothing moves (the caller queues a dwell instead)
        v, acc, dec = 1.0, 1.0, 1.0
    accel_ramp, decel_ramp = lim.accel_ramp, lim.decel_ramp
    ja = acc / accel_ramp if accel_ramp >= MIN_RAMP else inf
    jd = dec / decel_ramp if decel_ramp >= MIN_RAMP else inf
    return v, acc, dec, ja if ja < jd else jd


class PathRun:
    """The joints of one planned path motion, solved cycle by cycle as far as they are read.

    ``us``/``qs`` are the solved cycles (u = 0 is the start joints, never solved again);
    ``done`` is the local time up to which every cycle has been solved and checked.  A plain
    class rather than a dataclass: one is made per straight ``Move.Loc``, on its hot path."""

    __slots__ = ("path", "plan", "ik", "ik_between", "extra_start", "extra_end", "extra_mask", "q_end",
                 "max_speed", "max_accel", "ik_path", "us", "qs", "ts", "done", "fault", "final", "_grid",
                 "_v_last", "_m_last")

    def __init__(self, path: Path, plan: Plan, ik: Callable[[np.ndarray, Vec], Vec],
                 ik_between: Callable[[np.ndarray, Vec], Vec], extra_start: Vec, extra_end: Vec,
                 extra_mask: np.ndarray, q_end: Vec, max_speed: Vec, max_accel: Vec,
                 ik_path: PathIK | None = None) -> None:
        self.path = path
        self.plan = plan
        self.ik = ik  # checked (raises the controller's codes)
        self.ik_between = ik_between  # unchecked: reading between checked cycles
        self.extra_start = extra_start  # the start joints (never changed in place, so not copied)
        self.extra_end = extra_end
        self.extra_mask = extra_mask
        self.q_end = q_end  # the destination's joints, solved (and checked) when the motion was queued
        self.max_speed = max_speed  # per joint: the hard maximum (2700 × 2704 %)
        self.max_accel = max_accel  # per joint: the hard maximum (2702 × 2705/2706 %)
        self.ik_path = ik_path
        self.us: list[float] = [0.0]
        self.qs: list[Vec] = [extra_start]
        self.ts: list[float] = [0.0]  # local times of the solved cycles
        self.done = 0.0
        self.fault: Fault | None = None
        #: The joints the path ended on when they differ from ``q_end`` by whole turns (``_final``).
        self.final: Vec | None = None
        self._grid: PathJoints | None = None
        # The joint velocity of the last solved interval and the time it holds at (its middle):
        # the path starts at rest, so at first zero at the start (``_solve``'s acceleration check).
        self._v_last: Vec | None = None  # None: zero (made when first needed)
        self._m_last = 0.0

    @property
    def q(self) -> np.ndarray:
        """Start and destination joints (``q[-1]``: the destination)."""
        return np.array([self.qs[0], self.q_end])

    @property
    def duration(self) -> float:
        return self.plan.duration

    def _seed(self, seed: Vec, u: float) -> Vec:
        s = np.array(seed, float)
        m = self.extra_mask
        s[m] = self.extra_start[m] + (self.extra_end[m] - self.extra_start[m]) * u
        return s

    def run_to(self, t: float) -> Fault | None:
        """Solve and check every cycle up to local time ``t`` (the motion's end included when
        ``t`` reaches it); the fault that stopped the motion, if any, at or before ``t``."""
        if self.fault is not None:
            return self.fault if self.fault.t <= t else None
        end = self.plan.duration
        if t <= self.done or self.done >= end:
            return None
        k0 = int(math.floor(self.done / CYCLE + 1e-9)) + 1
        k1 = int(math.floor(min(t, end) / CYCLE + 1e-9))
        # a cycle closer than END_GAP to the end is left to the end itself: a sliver of an interval
        # there turns rounding into speeds and accelerations (``_check_rates``)
        times = (np.arange(k0, k1 + 1) * CYCLE).tolist()  # k · CYCLE, as Python floats multiply
        while times and times[-1] >= end - END_GAP:
            times.pop()
        if t >= end - 1e-12:
            times.append(end)
        i = 0
        while i < len(times):
            chunk = times[i:i + BATCH]
            if self._solve(chunk) is not None:
                return self.fault
            i += BATCH
        self.done = max(self.done, min(t, end))
        return None

    def _solve(self, times: list[float]) -> Fault | None:
        """Solve the cycles at local ``times`` (in order, after ``ts[-1]``) and check them.

        The poses are solved in one pass (``ik_path``) where the model can, else one by one up
        to the first that fails; then the joint speeds of all the cycles are checked at once.
        The first cycle that fails either way stops the motion at the one before it — the same
        cycle a check of each cycle in turn would stop at."""
        us = np.clip(self.plan.sample(np.array(times))[0][:, 0], 0.0, 1.0).tolist()
        last_is_end = times[-1] >= self.plan.duration
        inner = us[:-1] if last_is_end else us
        prev = self.qs[-1]
        rows: list[Vec] = []
        error: GplException | None = None
        solved = None
        if self.ik_path is not None and len(inner) > 1:
            solved = self.ik_path(self.path.poses(np.array(inner)), self._seeds(prev, inner))
        if solved is not None:
            rows = list(solved)
        else:
            seed = prev
            for u in inner:
                try:
                    seed = np.asarray(self.ik(self.path.pose(u), self._seed(seed, u)), float)
                except GplException as exc:
                    error = exc
                    break
                rows.append(seed)
        if error is None and last_is_end:
            try:
                rows.append(self._final(us[-1]))
            except GplException as exc:
                error = exc
        ok = len(rows)
        if ok:
            stop = self._check_rates(prev, np.array(rows), times[:ok], ended=error is None and last_is_end)
            if stop is not None:
                ok, error = stop
            self.us.extend(us[:ok])
            self.ts.extend(times[:ok])
            self.qs.extend(rows[:ok])
            if ok:
                self.done = times[ok - 1]
        if error is not None:
            self.fault = Fault(self.ts[-1], self.us[-1], self.qs[-1].copy(), error)
            return self.fault
        return None

    def _check_rates(self, prev: Vec, q: np.ndarray, times: list[float],
                     ended: bool) -> tuple[int, GplException] | None:
        """Joint speeds and accelerations of the cycles ``q`` (at ``times``, after ``prev``)
        against the hard maxima; ``ended``: the last cycle is the motion's end, at rest.

        Each interval's mean velocity holds at its middle; the difference of two neighbours
        over the time between their middles is a weighted mean of the acceleration in between
        (a hat-shaped weight), so neither check fires on a motion within its limits, whatever
        the cycle.  Returns (index of the first cycle that fails, the error) or None.

        Decision [P] (the manuals do not say what a servo does when the geometry asks more of a
        joint than it can give): over its maximum speed the servo reports -3106 *Axis
        over-speed*; over its maximum acceleration it cannot follow the set-points, and the
        following error trips -3122 *Soft envelope error*.  Either stops the robot at the last
        good cycle."""
        t_prev = self.ts[-1]
        t = np.array([t_prev, *times])
        dts = np.diff(t)
        steps = np.diff(np.vstack((prev, q)), axis=0)
        vel = steps / np.where(dts > 0.0, dts, np.inf)[:, None]
        mids = 0.5 * (t[:-1] + t[1:])
        v_last = np.zeros(len(prev)) if self._v_last is None else self._v_last
        v_all, m_all = np.vstack((v_last, vel)), np.concatenate(((self._m_last,), mids))
        if ended:  # at rest at the end
            v_all = np.vstack((v_all, np.zeros(len(prev))))
            m_all = np.concatenate((m_all, (t[-1],)))
        gaps = np.diff(m_all)
        acc = np.diff(v_all, axis=0) / np.where(gaps > 0.0, gaps, np.inf)[:, None]
        # acc[k] ends at interval k (the last one, when ended, at the end: the last cycle)
        fast = np.abs(vel) > self.max_speed * (1.0 + OVER_SPEED_TOLERANCE)
        hard = np.abs(acc) > self.max_accel * (1.0 + OVER_SPEED_TOLERANCE)
        k_fast = int(np.argmax(fast.any(axis=1))) if fast.any() else len(times)
        row = int(np.argmax(hard.any(axis=1))) if hard.any() else len(acc)
        k_hard = min(row, len(times) - 1) if hard.any() else len(times)  # (row N: the stop at the end)
        if k_fast == k_hard == len(times):
            self._v_last, self._m_last = vel[-1], float(mids[-1])
            return None
        if k_fast <= k_hard:
            j = int(np.argmax(fast[k_fast]))
            return k_fast, GplException(AXIS_OVER_SPEED, axis=j + 1,
                                        detail=f"axis {j + 1} would reach {abs(vel[k_fast, j]):.6g}/s on the path "
                                               f"(maximum {self.max_speed[j]:.6g}/s)")
        j = int(np.argmax(hard[row]))
        return k_hard, GplException(SOFT_ENVELOPE_ERROR, axis=j + 1,
                                    detail=f"axis {j + 1} would need {abs(acc[row, j]):.6g}/s² on the path "
                                           f"(maximum {self.max_accel[j]:.6g}/s²)")

    def _seeds(self, seed: Vec, us: list[float]) -> np.ndarray:
        """``_seed(seed, u)`` for every u (N×n), in one numpy pass."""
        out = np.broadcast_to(seed, (len(us), len(seed))).copy()
        m = self.extra_mask
        if m.any():
            out[:, m] = self.extra_start[m] + (self.extra_end[m] - self.extra_start[m]) * np.array(us)[:, None]
        return out

    def _final(self, u: float) -> Vec:
        """The joints the cycles arrive at: the destination solved when queued, unless the path
        reaches the same pose with a multi-turn joint a whole number of turns away (a wrist that
        unwinds more than half a turn along the line, which the destination's "nearest to the
        start" rule cannot know): then the path's own, recorded in ``final`` for the queue."""
        q_c = np.asarray(self.ik(self.path.pose(u), self._seed(self.qs[-1], u)), float)
        diff = q_c - self.q_end
        turns = np.round(diff / 360.0)
        if np.any(turns != 0.0) and np.allclose(diff, turns * 360.0, atol=1e-6):
            self.final = q_c
            return q_c
        return self.q_end

    def joints(self, u: float) -> Vec:
        """Joints at ``u`` (solved from the nearest checked cycle; the exact ends)."""
        if u <= 0.0:
            return self.qs[0].copy()
        if u >= 1.0 and self.fault is None:
            return (self.q_end if self.final is None else self.final).copy()
        if self.fault is not None and u >= self.fault.u:
            return self.fault.q.copy()
        k = bisect.bisect_left(self.us, u)
        if k >= len(self.us) or (k > 0 and u - self.us[k - 1] <= self.us[k] - u):
            k -= 1
        return np.asarray(self.ik_between(self.path.pose(u), self._seed(self.qs[k], u)), float)

    def rates(self, u: np.ndarray, ud: np.ndarray, udd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The blend planner's estimate of joint rates (``PathJoints.rates``) on a coarse grid of
        the path, solved the first time a blend asks (a blend overlaps two motions' rates)."""
        if self._grid is None:
            self._grid = PathJoints.sample(self.path, self.ik_between, self.qs[0], self.extra_end, self.extra_mask,
                                           self.ik_path)
        return self._grid.rates(u, ud, udd)
