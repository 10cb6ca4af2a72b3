"""Per-robot state of the simulated controller: homed, attached, Tool/Base, and the motion queue.

A :class:`RobotState` lives in ``Session.robots[n]`` (built on first use by ``Session.robot``,
:func:`gplrt.motion.registry.build_robot`).  ``Move.*`` calls end up in :meth:`RobotState.queue_joint`,
:meth:`queue_path` or :meth:`queue_delay`, which plan a segment at once and append it with an
absolute start time; the call returns as soon as the segment is queued (as on the controller).

Decisions where the manuals are silent (documented per gpl-classes §22.3 [P]):

* **Start of a segment**: when the queue is idle the segment starts *now* from rest; otherwise it
  starts when the last queued segment ends.  The queue holds at most ``QUEUE_DEPTH`` unfinished
  segments; a further ``Move`` waits (on the controller clock) for room, as the controller's
  bounded motion queue makes a program wait.
* **Blending (InRange < 0)**: when the next motion is joint-interpolated and is queued before the
  previous (blending) motion has finished, the previous motion is cut at the first moment the
  tool tip is within ``|InRange|`` mm of its target (robots without kinematics: the joint-space
  distance), but never before *now*, and the new motion is planned by Ruckig from the full state
  (position, velocity, acceleration) at that moment — the robot never stops at the via point and
  passes within ``|InRange|`` mm of it.  A Cartesian path (straight line, arc or circle) queued
  after a blending motion (joint or path) is planned from rest at the via point and starts when the
  tool comes within ``|InRange|`` of it (but no earlier than its own duration before the previous
  motion's end, and never before *now*); the two are superimposed in Cartesian space until the
  previous motion ends (``queue.BlendedPathSegment``): the corner is rounded within ``|InRange|``,
  the robot does not stop, and after the overlap the tool is exactly on the line or circle.  The
  start is delayed further where the two motions' joint rates would add up beyond the joint
  limits in the overlap (``_blend_within_limits``).
* **Settling (InRange > 0)**: the robot stops on target and the segment is held for the
  in-range settling time (DataID 2601, 0.05 s on a PF400); InRange = 0 ends at the last set-point.
* **Cartesian paths** (``queue_path``): planned as the controller plans them — the destination's
  IK (refused at once with its code) and a 1-D profile of the path parameter; the joints along
  the way are solved cycle by cycle as the motion runs, and an error found there stops the robot
  at the last good cycle (``path_run``; reported by ``raise_async_error``).
* **Power loss / RapidDecel**: power off stops the robot where it is at once (the brakes) and the
  next ``Move`` or ``WaitForEOM`` of the attached thread raises -1046; RapidDecel plans a
  Ruckig stop with the RapidDecel deceleration (DataID 2101 %) and discards the queue.
"""

from __future__ import annotations

import functools
import math
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from gplrt.geometry.transforms import Pose, matrix_to_pose
from gplrt.lang.errors import (
    CANT_CHANGE_CONFIG,
    NOT_IN_POSITION_MODE,
    NO_ROBOT_ATTACHED,
    POWER_NOT_ENABLED,
    ROBOT_NOT_HOMED,
    GplException,
)
from gplrt.motion.kinematics import GPL_ABOVE, GPL_BELOW, GPL_FLIP, GPL_LEFTY, GPL_NOFLIP, GPL_RIGHTY, RobotModel
from gplrt.motion.limits import AxisLimits, RobotLimits, Vec, jerk_of
from gplrt.motion.planner import Plan, plan_axes, plan_scalar, plan_stop
from gplrt.motion.profile import Profile
from gplrt.motion.queue import (
    CLOCK_RESOLUTION,
    BlendedPathSegment,
    DwellSegment,
    JointSegment,
    MotionQueue,
    PathSegment,
    Segment,
    profile_from_values,
)
from gplrt.motion.path_run import PathRun, path_limits
from gplrt.motion.servo import ServoGripper
from gplrt.motion.special import OverlapSegment, SpecialMode, Trigger, fire_triggers
from gplrt.motion.straight import Path
from gplrt.session import current_session
from gplrt.threads.scheduler import ThreadKey, WaitQueue

QUEUE_DEPTH = 8
#: Homing duration (s) [P]: PF400 axes have absolute encoders and do not move; the gripper homes.
HOMING_TIME = 1.0
#: The blend starts when the tool is within |InRange| of the via point and no more than this
#: (mm) inside it: a micrometre is far below anything a trace or a test of the corner can see.
BLEND_DISTANCE_TOLERANCE = 1e-3

#: Blend start search (``_blend_within_limits``): candidates tried, samples of the overlap
#: checked per candidate, and the share of the joint limits the summed rates may use.
BLEND_START_STEPS = 8
BLEND_CHECK_SAMPLES = 24
BLEND_LIMIT_SAFETY = 0.97
#: A Cartesian path shorter than this (mm, and degrees of turn) does not move the tool.
ZERO_PATH = 1e-9

EXTRA_ROLES = ("rail",)
PASSIVE_ROLES = ("rail", "gripper", "gripper2")
#: The Config bits that name an arm branch (a straight line must keep its branch: -1042).
_BRANCH_BITS = GPL_RIGHTY | GPL_LEFTY | GPL_ABOVE | GPL_BELOW | GPL_FLIP | GPL_NOFLIP


def _seed_at(q0: Vec, q_extra: Vec, mask: np.ndarray, u: float) -> Vec:
    """IK seed at path parameter ``u``: the start joints with the linearly moving axes set."""
    s = np.array(q0, float)
    s[mask] = q0[mask] + (q_extra[mask] - q0[mask]) * u
    return s


class QueuedFrames:
    """The IK (checked, unchecked, batch) and forward kinematics a path motion's cycles use,
    bound to the Tool and Base the motion was queued with.

    Why: the cycles are solved as the motion runs, and ``Robot.Tool``/``Base`` assigned after a
    line was queued apply to later motions only (robot_class); the line's poses are tool-tip
    poses in that Tool and Base.  While they are unchanged (the rule) the model's own calls
    are used as they are; after a change a pose ``T`` is handed to the model as
    ``Base_now · Base⁻¹ · T · Tool⁻¹ · Tool_now``, which is the same flange target.  One is
    made per Tool/Base pair and shared by the lines queued with it (``RobotState.frames``)."""

    __slots__ = ("model", "tool", "base", "tool_inv", "base_inv")

    def __init__(self, model: RobotModel) -> None:
        self.model = model
        self.tool, self.base = model.tool, model.base
        self.tool_inv, self.base_inv = model._tool_inv, model._base_inv

    def _now(self, T: np.ndarray) -> np.ndarray:
        model = self.model
        if model.tool is self.tool and model.base is self.base:
            return T
        return (model.base @ self.base_inv) @ T @ (self.tool_inv @ model.tool)

    def ik(self, T: np.ndarray, seed: Vec) -> Vec:
        return np.array(self.model.inverse(self._now(T), 0, seed.tolist()))

    def ik_between(self, T: np.ndarray, seed: Vec) -> Vec:
        return np.array(self.model.inverse(self._now(T), 0, seed.tolist(), False))

    def ik_path(self, Ts: np.ndarray, seeds: np.ndarray) -> np.ndarray | None:
        return self.model.inverse_path(self._now(Ts), seeds)

    def forward(self, q: Vec) -> np.ndarray:
        return self.base @ self.model.flange(q) @ self.tool


@dataclass(eq=False)
class RobotState:
    """One robot of the simulated controller (see the module docstring)."""

    number: int
    model: RobotModel
    limits: RobotLimits
    restart_tool: np.ndarray
    restart_base: np.ndarray
    queue: MotionQueue
    homed: bool = False
    homing: int = 0  # homings of this robot in progress (TrajState 9)
    owner: ThreadKey | None = None  # the thread that has it attached (None = free)
    last_profile: tuple[object, ...] | None = None  # queue.profile_values of the last motion
    pending_extra: list[float] = field(default_factory=list)
    async_error: int = 0
    payload: float = 0.0
    custom: dict[int, float] = field(default_factory=dict)
    rapid_decel_until: float = -math.inf
    lock: threading.RLock = field(default_factory=threading.RLock)
    #: Threads waiting for the end of its motion (``Move.WaitForEOM``)
    eom_waiters: WaitQueue = field(default_factory=lambda: WaitQueue("end of motion"))
    _bounds: tuple[list[float], list[float]] | None = None
    #: (end joints, Tool, Base, tool pose) of the last Cartesian destination (``pose_of``)
    _known_pose: tuple[Vec, np.ndarray, np.ndarray, Pose] | None = None
    #: The path motions' kinematics for the present Tool and Base (``QueuedFrames``)
    _frames: QueuedFrames | None = None
    #: The servo gripper (``gplrt.motion.servo``), None for a robot without one
    gripper: ServoGripper | None = None
    #: Motor counts per mm or degree of each joint (DataID 2300; ``Robot.JointToMotor``)
    motor_scale: list[float] = field(default_factory=list)
    #: Brake control (DataIDs 14500/14002): the chosen axis, and the axes whose brake is released
    brake_axis: int = 0
    brakes_released: set[int] = field(default_factory=set)
    #: The special trajectory mode in force (jog, torque: ``gplrt.motion.special``), or None
    special: SpecialMode | None = None
    #: ``Move.Trigger`` actions armed for the next motion (``gplrt.motion.special``)
    pending_triggers: list[Trigger] = field(default_factory=list)
    #: ``Move.ForceOverlap`` percentage for the next motion, or None
    pending_overlap: float | None = None

    def __post_init__(self) -> None:
        self._axis_count = self.model.axis_count  # fixed for the model's lifetime; read per Move

    @property
    def axis_count(self) -> int:
        return self._axis_count

    @property
    def max_joint_speed(self) -> np.ndarray:
        """Each joint's hard maximum speed: 2700 × 2704 % (the fastest any Profile may ask)."""
        return self.limits.max_joint_speed

    @functools.cached_property
    def extra_mask(self) -> np.ndarray:
        """Axes ``Move.Extra`` sets (the rail)."""
        return np.array([j.role in EXTRA_ROLES for j in self.model.joints], dtype=bool)

    @functools.cached_property
    def passive_mask(self) -> np.ndarray:
        """Axes the inverse kinematics keeps at their current values (rail, grippers): a straight
        move to an Angles Location interpolates them to their target values instead."""
        return np.array([j.role in PASSIVE_ROLES for j in self.model.joints], dtype=bool)

    # -- reading the state --------------------------------------------------------------------

    # Reading the state runs the path motions' cycles up to ``t`` (``MotionQueue.advance``), which
    # changes the queue: under the real clock another thread may be reading the same robot, or
    # queueing on it, at the same moment — hence the robot's lock.

    def joints_at(self, t: float) -> Vec:
        """Where the joints are at ``t``: the command, except where the gripper's fingers are
        held back by a plate or their stop (``gplrt.motion.servo``)."""
        with self.lock:
            q = self.queue.joints_at(t)
        gripper = self.gripper
        if gripper is not None:
            i = gripper.axis
            held = gripper.actual(float(q[i]))
            if held != q[i]:
                q = q.copy()
                q[i] = held
        return q

    def state_at(self, t: float) -> tuple[Vec, Vec, Vec]:
        with self.lock:
            q, v, a = self.queue.state_at(t)
        gripper = self.gripper
        if gripper is not None:
            i = gripper.axis
            held = gripper.actual(float(q[i]))
            if held != q[i]:  # the fingers rest on the plate or their stop
                q, v, a = q.copy(), v.copy(), a.copy()
                q[i], v[i], a[i] = held, 0.0, 0.0
        return q, v, a

    def commanded_torques(self) -> dict[int, float]:
        """Axis (0-based) -> torque (tcnt) of the axes in torque mode (``gplrt.motion.special``)."""
        special = self.special
        return special.torques if special is not None and special.kind == "torque" else {}

    def run_cycles(self, t: float) -> None:
        """Run the path motions' cycles up to ``t`` (``MotionQueue.advance``): whatever reads the
        queue's plan rather than the joints (TrajState, Dest) must see a mid-path stop that has
        happened by ``t`` exactly as ``Where`` would, whether or not anything read the robot
        before."""
        if self.queue.paths_pending:
            with self.lock:
                self.queue.advance(t)

    def source_joints(self) -> Vec | None:
        """Where the last queued motion that is still in the queue started (``Robot.Source``);
        None before any.  Read off the queue rather than kept when a motion is queued: a stop
        (a mid-path error, power off) drops the motions queued after it, and the source is then
        that of the motion that ran.  ``Move.Delay`` and RapidDecel's stop are not motions of
        the program's and do not count."""
        for seg in reversed(self.queue.history):
            if seg.kind not in ("delay", "rapid_decel"):
                return seg.q_start
        return None

    def latch_angles(self) -> list[float]:
        """Present joints (used by the latch emulation in controller/signals.py)."""
        return [float(v) for v in self.joints_at(current_session().now())]

    def latch_pose(self, angles: tuple[float, ...]) -> tuple[np.ndarray, int] | None:
        """Tool pose (4×4 mm) and Config bits of latched joints; None without kinematics."""
        if not self.model.has_kinematics or len(angles) != self.axis_count:
            return None
        return self.model.forward(angles), self.model.config_of(angles)

    def forward(self, joints: Vec) -> np.ndarray:
        return self.model.forward(joints)  # (an array, a list or a tuple: the model takes each)

    def inverse(self, T: np.ndarray, config: int, current: Vec, check: bool = True) -> Vec:
        seed = current.tolist() if type(current) is np.ndarray else [float(v) for v in current]
        return np.array(self.model.inverse(T, int(config), seed, check))

    # -- checks --------------------------------------------------------------------------------

    def free_to_move(self, key: ThreadKey, power_on: bool) -> bool:
        """Whether nothing :meth:`check_can_move` tests stands in the way: attached to ``key``,
        powered, homed, in position mode, no stop to report and no path cycles still to run.
        One look, for the case nearly every Move is (``move._ready_now``); a precondition added
        to ``check_can_move`` belongs here too."""
        queue = self.queue
        return (self.owner is key and key is not None and power_on and self.homed and self.special is None
                and not self.async_error and queue.fault is None and not queue.paths_pending)

    def check_can_move(self, key: ThreadKey, power_on: bool) -> None:
        """The controller's motion preconditions (gpl-classes §7), raised in the controller's
        order: attached, a stop to report, power, position mode, homed (:meth:`free_to_move` is
        the same test as one question)."""
        if self.free_to_move(key, power_on):
            return
        if self.owner is None or self.owner is not key:
            raise GplException(NO_ROBOT_ATTACHED, robot_num=self.number,
                               detail=f"robot {self.number} is not attached to this thread")
        if self.queue.paths_pending:  # the path motions' cycles up to now (path_run)
            with self.lock:
                self.queue.advance(current_session().now())
        if self.async_error or self.queue.fault is not None:
            self.raise_async_error()
        if not power_on:
            raise GplException(POWER_NOT_ENABLED, robot_num=self.number, detail="high power is off")
        if self.special is not None:
            raise GplException(NOT_IN_POSITION_MODE, robot_num=self.number,
                               detail=f"robot {self.number} is in {self.special.kind} mode (Move.StopSpecialModes)")
        if not self.homed:
            raise GplException(ROBOT_NOT_HOMED, robot_num=self.number, detail=f"robot {self.number}")

    def _check_stopped(self) -> None:
        """Raise the error of a stop found since ``check_can_move`` (under the real clock another
        thread's read can run the cycles that find it in between): a motion queued after the
        stop would run as if nothing had happened, and the error would come one Move late."""
        if self.async_error or self.queue.fault is not None:
            self.raise_async_error()

    def raise_async_error(self) -> None:
        """An error that stopped a queued motion, reported once to the attached thread."""
        code, self.async_error = self.async_error, 0
        fault, self.queue.fault = self.queue.fault, None
        if code:
            raise GplException(code, robot_num=self.number, detail="motion stopped")
        if fault is not None:  # a path motion stopped mid-way (path_run): its own code and axis
            raise GplException(fault.ErrorCode, robot_num=self.number, axis=getattr(fault, "Axis", 0) or 0,
                               detail=f"motion stopped on its path: {fault.detail}")

    def check_joint_limits(self, q: Vec) -> None:
        """-1012 for an axis outside its soft limits (the model's check, on a fast path first)."""
        bounds = self._bounds
        if bounds is None:
            slack = [1e-9 if j.linear else 1e-9 for j in self.model.joints]
            bounds = self._bounds = ([j.lower - e for j, e in zip(self.model.joints, slack)],
                                     [j.upper + e for j, e in zip(self.model.joints, slack)])
        lows, highs = bounds
        values = q.tolist() if type(q) is np.ndarray else q
        if len(values) == len(lows):
            for i, v in enumerate(values):
                if not lows[i] <= v <= highs[i]:
                    break
            else:
                return
        self.model.check_limits([float(x) for x in q])  # raises with the model's detail

    # -- queueing ------------------------------------------------------------------------------

    def _start(self, now: float, can_blend: bool) -> tuple[float, Vec, Vec | None, Vec | None]:
        """Start time and state of the next segment (velocity/acceleration None = at rest;
        see the module docstring on blending)."""
        queue = self.queue
        last = queue.history[-1] if queue.history else None
        # (no copies: segments' joint arrays are replaced, never changed in place)
        if last is None:
            return now, queue.rest, None, None
        if last.end <= now + CLOCK_RESOLUTION:  # idle: at rest where the last segment left it
            return now, last.q_end, None, None
        if can_blend and last.blend and last.cut is None and not isinstance(last, DwellSegment):
            t_b = max(now, self._blend_time(last))
            if t_b < last.motion_end:
                q, v, a = last.state(t_b)
                last.cut = t_b
                return t_b, q, v, a
        return last.end, last.q_end, None, None

    def _blend_time(self, seg: Segment) -> float:
        """First time the tool is within the blend tolerance of the segment's target.

        Near the end of a motion the remaining distance falls roughly as the square of the time
        left (constant deceleration), so ``√distance − √tolerance`` is close to linear in time:
        its root is found by regula falsi with the Illinois modification in a handful of forward
        kinematics (bisection needs ~20).  The result is always a time at which the tool is
        within the tolerance, and at most ``BLEND_DISTANCE_TOLERANCE`` inside it."""
        tol = seg.blend_tolerance
        lo, hi = seg.t0, seg.t0 + seg.duration
        if tol <= 0.0:
            return hi
        if self.model.has_kinematics:
            goal = self.forward(seg.q_end)[:3, 3]

            def distance(t: float) -> float:
                d = self.forward(seg.joints(t))[:3, 3] - goal
                return math.sqrt(float(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]))
        else:
            def distance(t: float) -> float:
                return float(np.linalg.norm(seg.joints(t) - seg.q_end))
        root_tol = math.sqrt(tol)
        d_lo = distance(lo)
        if d_lo <= tol:
            return lo
        g_lo, g_hi = math.sqrt(d_lo) - root_tol, -root_tol  # on target at the end
        side = 0
        for _ in range(60):
            t = hi - g_hi * (hi - lo) / (g_hi - g_lo)
            if not lo < t < hi:
                t = 0.5 * (lo + hi)
            d = distance(t)
            g = math.sqrt(d) - root_tol
            if d > tol:
                lo, g_lo = t, g
                if side == -1:
                    g_hi *= 0.5  # Illinois: a stale end must not hold the estimate back
                side = -1
            else:
                hi, g_hi = t, g
                if side == 1:
                    g_lo *= 0.5
                side = 1
                if d > tol - BLEND_DISTANCE_TOLERANCE:
                    break
            if hi - lo < 1e-7:
                break
        return hi

    def queue_joint(self, now: float, target: Vec | Sequence[float], prof: Profile, system_speed: float) -> Segment:
        """Plan and queue a joint-interpolated motion to ``target`` (joints, GPL units)."""
        values = target.tolist() if type(target) is np.ndarray else [float(v) for v in target]
        return self.queue_joint_values(now, values, prof, system_speed)

    def queue_joint_values(self, now: float, values: Sequence[float], prof: Profile, system_speed: float) -> Segment:
        """``queue_joint`` for a list or tuple of Python floats, the forms Ruckig takes: ``Move.Loc``
        to an Angles Location (the commonest motion of all) converts nothing on its way here."""
        if self.async_error or self.queue.fault is not None:
            self.raise_async_error()  # (see ``_check_stopped``; inlined on this hot path)
        self.check_joint_limits(values)
        lim = self.limits.joint_limits(prof, system_speed)
        # ``_start``'s two commonest cases inlined, without its copy: the new segment's q_start may
        # be the very array of the previous q_end (or ``rest``): segments' joint arrays are only
        # ever replaced, never changed in place.
        queue = self.queue
        history = queue.history
        if not history:
            t0, q0, v0, a0 = now, queue.rest, None, None
        elif history[-1].end <= now + CLOCK_RESOLUTION:
            t0, q0, v0, a0 = now, history[-1].q_end, None, None
        elif self.pending_overlap is not None:
            return self._queue_overlapped(now, values, lim, prof)
        else:
            t0, q0, v0, a0 = self._start(now, can_blend=True)
        self.pending_overlap = None
        plan = plan_axes(q0, v0, a0, values, lim)
        return self._append(JointSegment(t0, plan.duration, q0, np.array(values), None, 0.0, False, 0.0, None,
                                         "joint", plan), prof)

    def _queue_overlapped(self, now: float, values: Sequence[float], lim: AxisLimits, prof: Profile) -> Segment:
        """A joint motion that ``Move.ForceOverlap`` overlaps with the running one
        (``gplrt.motion.special``): planned from rest at its target, started when it has the
        overlap percentage of its duration left, and superimposed on it until it ends."""
        prev = self.queue.history[-1]
        pct, self.pending_overlap = float(self.pending_overlap or 0.0), None
        prev_end = prev.motion_end
        t_b = max(now, prev_end - prev.duration * pct / 100.0, prev.t0)
        q0 = prev.q_end
        plan = plan_axes(q0, None, None, values, lim)
        if t_b >= prev_end:
            t_b = prev.end
        else:
            prev.cut = t_b  # the overlap segment covers the rest of it
        seg = OverlapSegment(t_b, plan.duration, q0, np.array(values), kind="overlap", plan=plan, prev=prev,
                             prev_end=prev_end)
        return self._append(seg, prof)

    def queue_pose(self, now: float, pose: Pose, config: int, prof: Profile, system_speed: float,
                   seed: Vec | None = None) -> Segment:
        """Plan and queue a joint-interpolated motion to a tool pose: its IK with ``config``,
        unwound toward ``seed`` (default: the previous destination).  The pose is remembered as
        where the robot will be (``pose_of``): a straight line from there starts on it."""
        if seed is None:
            queue = self.queue
            seed = queue.history[-1].q_end if queue.history else queue.rest
        seg = self.queue_joint_values(now, self.model.inverse_pose(pose, config, seed.tolist()), prof, system_speed)
        self.remember_pose(seg.q_end, pose)
        return seg

    def queue_path(self, now: float, make_path: Callable[[Pose], Path], config: int, prof: Profile,
                   system_speed: float, extra_end: Vec | None = None, kind: str = "straight",
                   extra_mask: np.ndarray | None = None, angles_end: Vec | None = None) -> Segment:
        """Plan and queue a Cartesian path motion; ``make_path(start_pose)`` builds the Path.

        The axes in ``extra_mask`` (default: the rail) move linearly along the path to their
        values in ``extra_end``; the IK solves the others.  ``angles_end``: the joints of an
        Angles Location the line goes to.  They name the arm's branch, and a line keeps the
        branch, so a destination the line reaches only on the other branch is refused with
        -1042, like a Cartesian Location whose Config asks for it.  Decision [P] (the manuals
        are silent): a multi-turn axis (the wrist) turns the short way, as for the Location's
        Cartesian pose, so it may end a whole turn away from the Angles' value.

        This is the controller's planning of a path (gpl-classes §22.4), and all of it happens
        here: the destination's joints (refused at once with their code), then the 1-D profile of
        the path parameter.  The joints along the way are solved cycle by cycle as the motion
        runs (``path_run.PathRun``, ``MotionQueue.advance``).  ``benchmarks/motion_speed.py``
        times this against a bare Ruckig call, so it keeps to Python floats where it can."""
        if self.async_error or self.queue.fault is not None:
            self.raise_async_error()  # (``_check_stopped``, inlined on this hot path)
        history = self.queue.history
        if not history:  # (``_blend_source`` and ``_start``'s commonest cases first)
            blend_from, t0, q0 = None, now, self.queue.rest
        elif history[-1].end <= now + CLOCK_RESOLUTION:  # idle: at rest where the last motion left it
            blend_from, t0, q0 = None, now, history[-1].q_end
        elif (blend_from := self._blend_source(now)) is not None:
            t0, q0 = blend_from.end, blend_from.q_end  # the line starts at the via point
        else:
            t0, q0, _, _ = self._start(now, can_blend=False)
        frames, model = self._frames, self.model
        # (the model's frames themselves, not its ``tool``/``base`` properties: a hot path)
        if frames is None or frames.tool is not model._tool or frames.base is not model._base:
            frames = self._frames = QueuedFrames(model)
        known = self._known_pose  # (``pose_of``, its commonest case inlined)
        if known is not None and known[0] is q0 and known[1] is frames.tool and known[2] is frames.base:
            path = make_path(known[3])
        else:
            path = make_path(self.pose_of(q0, frames))
        mask = self.extra_mask if extra_mask is None else extra_mask
        q_extra = q0 if extra_end is None else np.where(mask, extra_end, q0)
        start = q0.tolist()  # (Python floats: the seed, the Config and the chord read them)
        if config & _BRANCH_BITS:
            self._check_config_kept(config, model.config_of(start))
        if path.length < ZERO_PATH and path.turn < ZERO_PATH and (q_extra is q0 or np.array_equal(q_extra, q0)):
            # Nothing moves (``Move.Rel`` by nothing, a line to where the tool is): the motion is
            # done at once, exactly where it started; a blending motion before it runs to its end.
            seg = DwellSegment(t0, 0.0, q0, q0, kind=kind)
            return self._append(seg, prof)
        seed = start if q_extra is q0 else _seed_at(q0, q_extra, mask, 1.0).tolist()
        end = model.inverse_pose(path.end_pose, 0, seed)  # the destination's joints, Python floats
        if angles_end is not None:
            if (model.config_of(end) ^ model.config_of(angles_end.tolist())) & _BRANCH_BITS:
                raise GplException(CANT_CHANGE_CONFIG, robot_num=self.number,
                                   detail="a straight-line motion cannot reach these angles' arm configuration")
        limits = self.limits
        v, acc, dec, jerk = path_limits(path.length, path.turn, start, end, limits.line_limits(prof, system_speed))
        plan = plan_scalar(0.0, 0.0, 0.0, 1.0, v, acc, dec, jerk)
        q1 = np.array(end)
        max_speed, max_accel = limits._hard or limits.hard_limits()
        pj: PathRun | None = None
        if blend_from is not None:
            pj = PathRun(path, plan, frames.ik, frames.ik_between, q0, q_extra, mask, q1, max_speed, max_accel,
                         frames.ik_path)
            # The line must not end before the motion it blends out of: start no earlier than
            # its duration before that motion's end (a shorter overlap), never before now.
            prev_end = blend_from.motion_end
            t_b = max(now, self._blend_time(blend_from), prev_end - plan.duration)
            t_b = self._blend_within_limits(blend_from, t_b, prev_end, plan, pj, prof, system_speed)
            if t_b < prev_end:
                blend_from.cut = t_b
                seg: Segment = BlendedPathSegment(
                    t_b, plan.duration, blend_from.joints(t_b), q1, plan=plan, run=pj,
                    kind=kind, prev=blend_from, prev_end=prev_end, via=path.pose(0.0), forward=frames.forward)
                self.remember_pose(q1, path.end_pose, frames)
                return self._append(seg, prof)
        # (positional: t0, duration, q_start, q_end, profile, settle, blend, blend_tolerance, cut,
        # kind, plan, run, run_inputs; keywords cost a third of the call on this hot path)
        # The PathRun is built when the cycles are first read (``PathSegment.path_joints``).
        seg = PathSegment(t0, plan.duration, q0, q1, None, 0.0, False, 0.0, None, kind, plan, pj,
                          (path, frames, q0, q_extra, mask, q1, max_speed, max_accel) if pj is None else None)
        self._known_pose = (q1, frames.tool, frames.base, path.end_pose)  # (``remember_pose``, inlined)
        return self._append(seg, prof)

    def pose_of(self, q: Vec, frames: QueuedFrames | None = None) -> Pose:
        """The tool pose (a pose tuple) of the joints ``q``.

        A path starts where the previous motion ended, and when that motion went to a Cartesian
        destination the controller knows its pose already: ``remember_pose`` keeps it, keyed by
        the very array of the motion's end joints (segments' joint arrays are replaced, never
        changed in place) and by the Tool and Base it was reached with.  Anything else — a
        motion cut short, a new Tool — is a different key, and gets the forward kinematics.
        ``frames``: the path kinematics of the present Tool and Base, when the caller has them
        (their Tool and Base are the model's, without a property call each)."""
        known = self._known_pose
        tool, base = (self.model.tool, self.model.base) if frames is None else (frames.tool, frames.base)
        if known is not None and known[0] is q and known[1] is tool and known[2] is base:
            return known[3]
        pose = matrix_to_pose(self.forward(q))
        self._known_pose = (q, tool, base, pose)
        return pose

    def remember_pose(self, q: Vec, pose: Pose, frames: QueuedFrames | None = None) -> None:
        """``q`` (an array no one changes in place) puts the tool at ``pose`` (see ``pose_of``)."""
        if frames is None:
            self._known_pose = (q, self.model.tool, self.model.base, pose)
        else:
            self._known_pose = (q, frames.tool, frames.base, pose)

    def _blend_within_limits(self, prev: Segment, t_b: float, prev_end: float, plan: Plan, pj: PathRun,
                             prof: Profile, system_speed: float) -> float:
        """The earliest blend start from ``t_b`` on at which the overlap keeps every joint within
        its speed and acceleration limits (``prev_end``: no overlap at all).

        In the overlap the two motions add up: a joint the previous motion is still braking and
        the new path already accelerates (a corner that reverses it) can see up to twice its
        limit.  The bound checked is the sum of the two motions' own joint rates (their
        estimates, ``Segment.rates``), against the larger of the two Profiles' limits with
        ``BLEND_LIMIT_SAFETY`` for what the sum leaves out (the IK of the superposition is not
        the sum of the IKs).  A later start overlaps less of the braking (and the path has
        accelerated less): the candidates close in on ``prev_end`` geometrically.

        Out of a path (line, arc) the tool's speed is bounded the same way: the two paths' tool
        speeds (mm/s and deg/s, exact: length · u̇) may add up to the larger Cartesian limit."""
        lim = self.limits.joint_limits(prof, system_speed)
        v_lim, a_lim = lim.velocity, np.maximum(lim.accel, lim.decel)
        cart = self.limits.path_limits(prof, system_speed)
        lin_lim, rot_lim = cart.linear_velocity, cart.rotation_velocity
        if prev.profile is not None:
            prev_prof = profile_from_values(prev.profile)
            other = self.limits.joint_limits(prev_prof, system_speed)
            v_lim = np.maximum(v_lim, other.velocity)
            a_lim = np.maximum(a_lim, np.maximum(other.accel, other.decel))
            other_cart = self.limits.path_limits(prev_prof, system_speed)
            lin_lim = max(lin_lim, other_cart.linear_velocity)
            rot_lim = max(rot_lim, other_cart.rotation_velocity)
        v_lim, a_lim = v_lim * BLEND_LIMIT_SAFETY, a_lim * BLEND_LIMIT_SAFETY
        prev_path = prev.path_joints.path if isinstance(prev, PathSegment) and prev.path_joints else None
        span = prev_end - t_b
        for k in range(BLEND_START_STEPS):
            start = prev_end - span * 0.5 ** k
            ts = np.linspace(start, prev_end, BLEND_CHECK_SAMPLES)
            v_prev, a_prev = prev.rates(ts)
            u, ud, udd = plan.sample(ts - start)
            u_line, ud_line, udd_line = u[:, 0], ud[:, 0], udd[:, 0]
            v_line, a_line = pj.rates(u_line, ud_line, udd_line)
            if not (np.all(np.abs(v_prev) + np.abs(v_line) <= v_lim) and np.all(np.abs(a_prev) + np.abs(a_line) <= a_lim)):
                continue
            if prev_path is not None:
                assert isinstance(prev, PathSegment)
                ud_prev = np.abs(prev.parameters(ts)[1])
                ud_line = np.abs(ud_line)
                if (np.any(prev_path.length * ud_prev + pj.path.length * ud_line > lin_lim * (1.0 + 1e-9))
                        or np.any(prev_path.turn * ud_prev + pj.path.turn * ud_line > rot_lim * (1.0 + 1e-9))):
                    continue
            return start
        return prev_end

    def _blend_source(self, now: float) -> Segment | None:
        """The queued motion a new straight line may blend out of (see the module docstring)."""
        last = self.queue.last
        if last is None or last.end <= now + CLOCK_RESOLUTION or isinstance(last, DwellSegment):
            return None
        return last if last.blend and last.cut is None else None

    def _check_config_kept(self, config: int, start_config: int) -> None:
        """-1042 when ``config`` asks for a branch other than the one the arm is in: a straight
        line (or arc) keeps its configuration.  Only the bit pairs the robot reports count."""
        for yes, no in ((GPL_RIGHTY, GPL_LEFTY), (GPL_ABOVE, GPL_BELOW), (GPL_NOFLIP, GPL_FLIP)):
            if not start_config & (yes | no):
                continue  # this robot has no such branch
            asked = config & (yes | no)
            if asked in (yes, no) and not start_config & asked:
                raise GplException(CANT_CHANGE_CONFIG, robot_num=self.number,
                                   detail="a straight-line motion cannot change the arm configuration")

    def queue_delay(self, now: float, seconds: float) -> Segment:
        self._check_stopped()
        t0, q0, _, _ = self._start(now, can_blend=False)
        seg = DwellSegment(t0, max(0.0, float(seconds)), q0.copy(), q0.copy())
        self.queue.append(seg)
        return seg

    def _append(self, seg: Segment, prof: Profile) -> Segment:
        """Queue ``seg`` with the Profile's end-of-motion rule (blend, settle or stop)."""
        inrange = prof._inrange  # a float, validated by the Profile.InRange setter
        if inrange:  # InRange = 0 keeps the segment's defaults: no blend, no settling
            seg.blend = inrange < 0.0
            seg.blend_tolerance = abs(inrange)
            seg.settle = self.limits.settle_time if inrange > 0.0 else 0.0
        # the program may change its Profile after the Move
        seg.profile = self.last_profile = prof._values or prof.values()  # (``profile_values``, inline)
        queue = self.queue
        queue.history.append(seg)  # MotionQueue.append, inlined on this hot path
        queue._starts.append(seg.t0)
        if isinstance(seg, PathSegment):
            queue.paths_pending = True
        if len(queue.history) > queue.trim_at:
            queue.trim()
        if self.pending_triggers:  # Move.Trigger armed for this motion
            triggers, self.pending_triggers = self.pending_triggers, []
            fire_triggers(current_session(), seg, triggers)
        return seg

    # -- stopping ------------------------------------------------------------------------------

    def stop_now(self, t: float, error: int = 0) -> None:
        """Power loss: the robot stops where it is at ``t``; the queue is discarded."""
        if self.queue.end_time > t:
            self.queue.cut_at(t, self.joints_at(t))
            if error:
                self.async_error = error

    def rapid_decel(self, t: float) -> None:
        """Decelerate to rest as fast as DataID 2101 allows and discard the rest of the queue."""
        if self.queue.end_time <= t:
            return
        q, v, a = self.state_at(t)
        if not np.any(np.abs(v) > 0.0):
            self.queue.cut_at(t, q)
            return
        decel = self.limits.joint_accel * self.limits.rapid_decel_pct / 100.0
        plan = plan_stop(q, v, a, decel, jerk_of(decel, decel, 0.05, 0.05))
        q_end = np.array(plan.at(plan.duration)[0])
        self.queue.cut_at(t, q)
        seg = JointSegment(t, plan.duration, q.copy(), q_end, plan=plan, kind="rapid_decel")
        self.queue.append(seg)
        self.rapid_decel_until = t + plan.duration
