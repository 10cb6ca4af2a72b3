"""Special trajectory modes and motion events: jog mode, torque mode, ``Move.Trigger`` and
``Move.ForceOverlap`` (``Move`` calls these; gpl-dictionary §4 gives only the names).

Decisions [P] where the manuals are silent (docs/design/real-code.md records where real code,
TCS and PARobot, shows how they are used):

* **Jog mode**: ``Move.StartJogMode`` (attached robot, power on; it waits for the queued motions
  to end) puts the robot in jog mode (``Robot.TrajState`` 10) holding where it is.
  ``Move.SetJogCommand(mode, axis, speed)`` then sets what moves: mode 0 stops jogging (hold);
  1 jogs joint ``axis`` at ``speed`` % (signed) of its jog speed, DataID 2820 (max joint jog
  speed, % of the 100 % speed 2700); 4 makes joint ``axis`` free (0 or -1: every joint, until
  the jog mode is left: real lab code frees them all with -1, docs/design/real-code.md; PARobot's
  FreeMode uses mode 4 one axis at a time): a free joint follows whoever pushes it — nobody in a
  simulation, so it holds, gravity compensated, until :func:`push` moves it (a notebook's hand).
  Modes 2 and 3 (world and tool jog) raise -204: their Cartesian set-up is not simulated.  A
  jogging joint moves at constant speed on the controller clock and stops at its soft limit.
* **Torque mode**: ``Move.StartTorqueCntrl(motor_mask, adc_mask, torques)`` puts the masked
  axes (bit 0 = axis 1) in torque control, the others keep servoing where they are
  (TrajState 8); ``Move.SetTorques(torques)`` changes the torques.  A torque is a percentage of
  the motor's peak torque on top of the torque that held the axis when the mode started (TCS's
  zeroTorque: "balance the axes against any gravity loading"), so 0 holds the axis where it is;
  a non-zero torque makes it drift at that percentage of its maximum speed (2700 × 2704 %), a
  damped first-order model, until its soft limit.  DataID 12304 reports the torque.
  Analog-input torque (``adc_mask`` <> 0) raises -204.
* ``Move.StopSpecialModes`` ends either mode where the robot is (and does nothing in position
  mode).  While a special mode is on, a ``Move`` motion raises -1017 *Not in position control
  mode*, and ``Move.WaitForEOM`` waits until the mode ends (the controller's hang that TCS
  avoids by testing TrajState = 10 first).
* ``Move.Trigger(mode, point, target[, event_mask])``: at ``point`` % (0-100) of the distance of
  the next motion the robot's thread queues, the controller sends ``event_mask`` to the GPL
  Thread ``target`` (``Thread.SendEvent``) or, for a signal number, turns that digital output on
  (a negative number: off).  The distance is the joint-space distance of a joint move and the path
  length of a straight line or arc.  Only mode 0 (percent of distance) is simulated: another mode
  raises -788 *Inconsistent MOVE.TRIGGER mode*.  A motion stopped before the point (power off,
  RapidDecel) fires nothing.
* ``Move.ForceOverlap(mode, percent)``: the next joint motion starts when the previous one has
  ``percent`` % of its duration left and the two are superimposed until the previous one ends
  (TrajState 6), so two moves of different axes run side by side (PARobot moves J4 during the J3
  move of a configuration change).  Only mode 0 is simulated; another raises -788.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from gplrt.lang.errors import (
    INCONSISTENT_TRIGGER_MODE,
    INVALID_ARGUMENT,
    INVALID_AXIS,
    NOT_IMPLEMENTED,
    TORQUE_MODE_INCORRECT,
    GplException,
)
from gplrt.lang.arrays import GplArray
from gplrt.lang.conversions import to_double
from gplrt.motion.limits import Vec
from gplrt.motion.queue import JointSegment, PathSegment, Segment
from gplrt.motion.servo import PEAK_TCNT

if TYPE_CHECKING:
    from gplrt.motion.robot import RobotState
    from gplrt.session import Session
    from gplrt.threads.thread import Thread

JOG_STOP, JOG_JOINT, JOG_WORLD, JOG_TOOL, JOG_FREE = 0, 1, 2, 3, 4
TRAJ_TORQUE, TRAJ_JOG = 8, 10
_JOG_SPEED_PCT = 2820
#: Bisection steps that find a trigger's time (1e-6 of the motion's duration).
_TRIGGER_STEPS = 20


@dataclass
class SpecialMode:
    """The special trajectory mode a robot is in (``RobotState.special``)."""

    kind: str  # "jog" or "torque"
    traj_state: int
    velocity: np.ndarray
    torques: dict[int, float] = field(default_factory=dict)  # axis (0-based) -> tcnt
    free: set[int] = field(default_factory=set)  # axes (0-based) in free mode


@dataclass(eq=False, slots=True)
class ManualSegment(Segment):
    """Open-ended motion of a special mode: each axis at its constant ``velocity`` from
    ``q_start`` (0: held), stopping at its soft limits ``lower``/``upper``."""

    velocity: np.ndarray | None = None
    lower: np.ndarray | None = None
    upper: np.ndarray | None = None

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        assert self.velocity is not None and self.lower is not None and self.upper is not None
        dt = max(0.0, min(t, self.motion_end) - self.t0)
        free = self.q_start + self.velocity * dt
        q = np.clip(free, self.lower, self.upper)
        v = np.where(q == free, self.velocity, 0.0) if t < self.motion_end else np.zeros_like(q)
        return q, v, np.zeros_like(q)


@dataclass(eq=False, slots=True)
class OverlapSegment(JointSegment):
    """A joint motion started by ``Move.ForceOverlap`` while the previous one runs out: until
    ``prev_end`` the two displacements add up (the new one planned from the previous target)."""

    prev: Segment | None = None
    prev_end: float = 0.0

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        q, v, a = JointSegment.state(self, t)  # (a slotted dataclass: no bare super())
        if t >= self.prev_end or self.prev is None:
            return q, v, a
        qp, vp, ap = self.prev.state(t)
        return qp + q - self.q_start, vp + v, ap + a


# -- special modes --------------------------------------------------------------------------


def _start_mode(s: Session, robot: RobotState, mode: SpecialMode) -> None:
    now = s.scheduler.clock.now()
    with robot.lock:
        q = robot.joints_at(now)
        robot.queue.cut_at(now, q)
        robot.special = mode
        _queue_manual(robot, now, q, mode.velocity)


def _queue_manual(robot: RobotState, now: float, q: Vec, velocity: np.ndarray) -> None:
    model = robot.model
    lower = np.array([j.lower for j in model.joints], dtype=float)
    upper = np.array([j.upper for j in model.joints], dtype=float)
    seg = ManualSegment(now, math.inf, np.array(q, dtype=float), np.array(q, dtype=float), kind="manual",
                        velocity=velocity, lower=lower, upper=upper)
    robot.queue.append(seg)


def _replan(s: Session, robot: RobotState) -> None:
    """The special mode's velocities changed: the manual motion goes on from where it is now."""
    now = s.scheduler.clock.now()
    with robot.lock:
        q = robot.queue.joints_at(now)
        robot.queue.cut_at(now, q)
        assert robot.special is not None  # (a special mode is on: its velocities changed)
        _queue_manual(robot, now, q, robot.special.velocity)


def start_jog_mode(s: Session, robot: RobotState) -> None:
    if robot.special is not None and robot.special.kind == "jog":
        return
    _start_mode(s, robot, SpecialMode("jog", TRAJ_JOG, np.zeros(robot.axis_count)))


def set_jog_command(s: Session, robot: RobotState, mode: int, axis: int, speed: float) -> None:
    special = robot.special
    if special is None or special.kind != "jog":
        raise GplException(INVALID_ARGUMENT, robot_num=robot.number,
                           detail="the robot is not in jog mode (Move.StartJogMode first)")
    n = robot.axis_count
    if mode in (JOG_WORLD, JOG_TOOL):
        raise GplException(NOT_IMPLEMENTED, robot_num=robot.number,
                           detail="Move.SetJogCommand: world and tool jog are not simulated")
    if mode not in (JOG_STOP, JOG_JOINT, JOG_FREE):
        raise GplException(INVALID_ARGUMENT, robot_num=robot.number, detail=f"jog mode {mode}")
    every_axis = mode == JOG_FREE and axis in (0, -1)
    if mode != JOG_STOP and not (1 <= axis <= n or every_axis):
        raise GplException(INVALID_AXIS, robot_num=robot.number, axis=axis, detail=f"jog axis {axis}")
    velocity = np.zeros(n)
    if mode == JOG_JOINT:
        pct = _jog_percent(s, robot)
        velocity[axis - 1] = robot.limits.joint_speed[axis - 1] * pct / 100.0 * max(-100.0, min(100.0, speed)) / 100.0
        special.free.clear()
    elif mode == JOG_FREE:
        special.free.update(range(n) if every_axis else {axis - 1})
    else:
        special.free.clear()
    special.velocity = velocity
    _replan(s, robot)


def _jog_percent(s: Session, robot: RobotState) -> float:
    return float(s.database().get_num(_JOG_SPEED_PCT, robot.number, default=3.0))


def push(sim: Session, robot_number: int, joints: dict[int, float]) -> None:
    """Move free-mode joints by hand (a notebook's or setup's stand-in for the operator):
    ``joints`` maps axis numbers (1-based) to positions; -202 for an axis that is not free."""
    robot = sim.robot(int(robot_number))
    special = robot.special
    for axis in joints:
        if special is None or special.kind != "jog" or axis - 1 not in special.free:
            raise GplException(INVALID_ARGUMENT, robot_num=robot.number, detail=f"axis {axis} is not in free mode")
    now = sim.scheduler.clock.now()
    with robot.lock:
        q = robot.queue.joints_at(now)
        for axis, value in joints.items():
            q[axis - 1] = float(value)
        robot.check_joint_limits(q)
        robot.queue.cut_at(now, robot.queue.joints_at(now))
        assert special is not None  # (checked above: the axes are free)
        _queue_manual(robot, now, q, special.velocity)


def start_torque_mode(s: Session, robot: RobotState, motor_mask: int, adc_mask: int, torques: GplArray) -> None:
    if adc_mask:
        raise GplException(NOT_IMPLEMENTED, robot_num=robot.number,
                           detail="Move.StartTorqueCntrl: analog-input torque is not simulated")
    axes = {i for i in range(robot.axis_count) if motor_mask >> i & 1}
    if not axes:
        raise GplException(INVALID_ARGUMENT, robot_num=robot.number, detail="no axis in the motor mask")
    _start_mode(s, robot, SpecialMode("torque", TRAJ_TORQUE, np.zeros(robot.axis_count),
                                      torques={i: 0.0 for i in axes}))
    set_torques(s, robot, torques)


def set_torques(s: Session, robot: RobotState, torques: GplArray) -> None:
    special = robot.special
    if special is None or special.kind != "torque":
        raise GplException(TORQUE_MODE_INCORRECT, robot_num=robot.number, detail="the robot is not in torque mode")
    velocity = np.zeros(robot.axis_count)
    for i in special.torques:
        pct = to_double(torques[i]) if i < torques.Length else 0.0
        pct = max(-100.0, min(100.0, pct))
        special.torques[i] = pct / 100.0 * PEAK_TCNT
        velocity[i] = robot.max_joint_speed[i] * pct / 100.0
    special.velocity = velocity
    _replan(s, robot)


def stop_special_modes(s: Session, robot: RobotState) -> None:
    if robot.special is None:
        return
    now = s.scheduler.clock.now()
    with robot.lock:
        robot.queue.cut_at(now, robot.queue.joints_at(now))
        robot.special = None
    s.scheduler.notify_all(robot.eom_waiters)


# -- motion events --------------------------------------------------------------------------


@dataclass
class Trigger:
    """A ``Move.Trigger`` armed for the next motion (module docstring)."""

    percent: float
    target: Thread | int  # a GPL Thread, or a signal number
    event_mask: int


def arm_trigger(robot: RobotState, mode: int, percent: float, target: Thread | int, event_mask: int) -> None:
    if mode != 0:
        raise GplException(INCONSISTENT_TRIGGER_MODE, robot_num=robot.number,
                           detail=f"Move.Trigger mode {mode}: only mode 0 (percent of the motion) is simulated")
    robot.pending_triggers.append(Trigger(max(0.0, min(100.0, percent)), target, event_mask))


def fire_triggers(s: Session, seg: Segment, triggers: list[Trigger]) -> None:
    """Schedule ``triggers`` on the motion ``seg`` just queued (module docstring)."""
    for trig in triggers:
        t = _time_at(seg, trig.percent / 100.0)
        s.scheduler.call_at(t, functools.partial(_fire, s, seg, trig, t))


def _fire(s: Session, seg: Segment, trig: Trigger, t: float) -> None:
    if seg.cut is not None and seg.cut < t - 1e-9 and seg.kind != "overlap":
        return  # stopped (or cut) before the point: nothing fires
    if isinstance(trig.target, int):
        s.io.write_dio(trig.target, True)
    else:
        trig.target.SendEvent(trig.event_mask)  # type: ignore[arg-type]


def _time_at(seg: Segment, fraction: float) -> float:
    """When ``seg`` has covered ``fraction`` of its distance (bisection on its own plan)."""
    if fraction <= 0.0 or seg.duration <= 0.0:
        return seg.t0
    if isinstance(seg, PathSegment):
        def progress(t: float) -> float:
            return seg.parameter(t)[0]
    else:
        total = float(np.linalg.norm(np.asarray(seg.q_end) - np.asarray(seg.q_start)))
        if total == 0.0:
            return seg.t0

        def progress(t: float) -> float:
            return float(np.linalg.norm(seg.state(t)[0] - np.asarray(seg.q_start))) / total
    lo, hi = seg.t0, seg.t0 + seg.duration
    if fraction >= 1.0:
        return hi
    for _ in range(_TRIGGER_STEPS):
        mid = (lo + hi) / 2.0
        if progress(mid) >= fraction:
            hi = mid
        else:
            lo = mid
    return hi
