"""GPL's global ``Move`` class (gpl-classes §7, gpl-dictionary §4): queue motions of the attached robot.

Every method acts on the robot attached to the calling thread and returns as soon as the motion
is planned and queued (``Move.WaitForEOM`` waits for the end).  Refusals, in this order:
-1009 *No robot attached*, -1046 *Power not enabled*, -1021 *Robot not homed*; then the target's
own errors (-1012 joint out of range, -1039/-1040 too close/far, -1033 invalid Cartesian value,
-1042 configuration change in a straight line, -1036 no kinematics for Cartesian targets).  A
straight line or arc is refused for its destination only: its joints along the way are solved
cycle by cycle as it runs, and an error there (a soft limit between the ends, -3106 / -3122 where
a joint would pass its maximum speed or acceleration) stops the robot mid-path and is raised by
the thread's next ``Move`` or ``WaitForEOM`` (``path_run``).

Decisions [P] where the Dictionary gives only a name:

* ``Rel(loc, prof)``: Cartesian ``loc`` — destination of the previous motion · loc (offset in the
  tool frame); Angles — axis-wise sum.
* ``Approach`` of an Angles Location: its Cartesian pose (forward kinematics), then the clearance
  rule of ``Location.approach_location``; ZClearance not set (1.0e32) raises -794 *ZClearance
  property not set*.
* ``OneAxis(axis, position, relative, prof)``: a joint move of one axis (1-based); bad axis -1002.
* ``Circle(loc1, loc2, prof)``: the full circle through the previous destination, loc1 and loc2,
  back to the start, orientation held.  ``Arc``: the arc from the previous destination through
  loc1 to loc2, orientation slerped to loc2's.
* ``Extra(a1[, a2, a3, a4])``: the robot's extra axes (the linear rail of a PF400 SXL) go to these
  values during the next motion to a Cartesian Location; values beyond the robot's extra axes are
  ignored (extra.htm).
* Jog mode (``StartJogMode``, ``SetJogCommand``), torque mode (``StartTorqueCntrl``,
  ``SetTorques``), ``StopSpecialModes``, ``Trigger`` and ``ForceOverlap``: see
  ``gplrt.motion.special`` for what the simulation does with them.
* Velocity and real-time-modification modes and ``StartSpeedDAC`` are not simulated: they have
  their real signatures (``@not_simulated``, CATALOGUE.md) and raise -204 *Not implemented* with
  the member named (gpl-classes §22.5).
"""

from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np

from gplrt.geometry._checks import wrong_object
from gplrt.geometry.location import Location
from gplrt.geometry.transforms import matrix_to_pose
from gplrt.lang.errors import (
    INCONSISTENT_TRIGGER_MODE,
    INVALID_AXIS,
    NO_ROBOT_ATTACHED,
    VALUE_INFINITE_OR_NAN,
    VALUE_OUT_OF_RANGE,
    ZCLEARANCE_NOT_SET,
    GplException,
)
from gplrt.lang.arrays import GplArray
from gplrt.lang.conversions import to_double, to_int32
from gplrt.lang.exceptions import not_simulated
from gplrt.lang.gpltypes import Boolean, Double, Integer
from gplrt.motion import registry, special
from gplrt.motion.profile import Profile
from gplrt.motion.robot import QUEUE_DEPTH, RobotState
from gplrt.motion.straight import ArcPath, LinePath
from gplrt.session import Session, current_session
from gplrt.threads.scheduler import ThreadKey, controller_wait, current_ctx

NO_CLEARANCE = 1.0e32
#: The longest Move.Delay, in seconds (see ``Delay``).
MAX_DELAY = (2**31 - 1) / 1000.0


def _attached(s: Session, key: ThreadKey | None = None) -> RobotState:
    robot = registry.attached_robot(s, registry.thread_key() if key is None else key)
    if robot is None:
        raise GplException(NO_ROBOT_ATTACHED, detail="this thread has no robot attached (Robot.Attached)")
    return robot


def _ready(s: Session, key: ThreadKey | None = None) -> RobotState:
    """The attached robot, checked for motion, once the queue has room (waits on the clock).
    ``key``: the calling thread's ``registry.thread_key()`` when the caller has it already."""
    if key is None:
        key = registry.thread_key()
    robot = _attached(s, key)
    robot.check_can_move(key, registry.power_on(s))
    queue = robot.queue
    if len(queue.history) < QUEUE_DEPTH:
        return robot  # room whatever has finished
    sched = s.scheduler
    while queue.pending(sched.clock.now()) >= QUEUE_DEPTH:
        # the oldest unfinished segment is QUEUE_DEPTH from the end: wait until it has run
        end = queue.history[-QUEUE_DEPTH].end
        with controller_wait(end):
            sched.sleep_until(end)
        robot.check_can_move(key, registry.power_on(s))
    return robot


def _ready_now(s: Session, key: ThreadKey) -> RobotState:
    """``_ready(s, key)`` in one look at the per-robot state for the case nearly every Move is:
    the thread's robot is found, powered, homed, in position mode, with no stop to report, no
    path cycles to run and room in its queue.  Anything else takes ``_ready``, which raises the
    controller's code in its order (or waits for room).

    Why: ``Move.Loc`` runs this once per motion, and ``_ready``'s five calls cost about as much
    as a fifth of a bare Ruckig plan (``benchmarks/motion_speed.py``)."""
    robot = registry.attached_robot(s, key)
    if robot is not None and robot.free_to_move(key, registry.power_on(s)) and len(robot.queue.history) < QUEUE_DEPTH:
        return robot
    return _ready(s, key)


def _special_ready(s: Session) -> RobotState:
    """The attached robot, checked as for a motion, once its queued motions have ended: a
    special mode starts from rest (``gplrt.motion.special``)."""
    robot = _ready(s)
    sched = s.scheduler
    while not sched.clock.reached(robot.queue.end_time):
        with controller_wait(robot.queue.end_time):
            sched.sleep_until(robot.queue.end_time)
    robot.raise_async_error()
    return robot


def _need(obj: Any, cls: type, what: str) -> None:
    """-782 for Nothing, -202 for any other object than a ``cls`` (reached from Python only: the
    transpiler's type check stops it in GPL source)."""
    if not isinstance(obj, cls):
        raise wrong_object(obj, what, cls.__name__)


def _finite(value: Any, what: str) -> float:
    """A numeric argument as a Double by GPL's rules (numeric text parsed, -717 on bad text, -782
    for Nothing), -708 when it is not finite: hand-written Python may pass anything, and a NaN
    would otherwise slip through ``max(0, nan)`` into the queue or reach the planner."""
    v = to_double(value)
    if not math.isfinite(v):
        raise GplException(VALUE_INFINITE_OR_NAN, detail=f"{what} = {v}")
    return v


def _angles_of(robot: RobotState, loc: Location) -> np.ndarray:
    """Joint values of an Angles Location for ``robot``.

    An Angles Location holds "one axis position value for each degree-of-freedom of the robot"
    (D0:1958-1960), but ``loc.Angles(...)`` always stores 12 values (omitted ones 0) and one
    Location may serve robots of different axis counts.  Decision [P] (the manual is silent on
    values beyond the robot's axes): they do not belong to any degree of freedom of this robot and
    are ignored, so ``l.Angles(250, 0, 90, 0, 69)`` moves a 5-axis PF400.  An axis the Location
    holds no value for is 0, as ``loc.Angle(axis)`` reads it: a controller's Angles Location always
    holds 12 values (a real TCS writes an untaught station as ``Angles(0, 0, ...)``), so a Location
    made Angles without values moves to zeros -- or is refused there -- rather than nowhere.
    """
    vals = loc.axis_values()
    n = robot.axis_count
    if len(vals) >= n:
        return np.array(vals[:n], dtype=float)
    q = np.zeros(n)
    q[: len(vals)] = vals
    return q


def _with_extra(robot: RobotState, q: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    """``q`` with the pending ``Move.Extra`` values on the extra axes (consumed here)."""
    extra, robot.pending_extra = robot.pending_extra, []
    if not extra:
        return q, None
    idx = [i for i, m in enumerate(robot.extra_mask) if m]
    out = q.copy()
    for i, v in zip(idx, extra):
        out[i] = v
    return out, out


def _cartesian(robot: RobotState, loc: Location, base: np.ndarray) -> np.ndarray:
    """Total pose (4×4 mm) of a Location; Angles Locations through forward kinematics."""
    if loc.Type == 1:
        return robot.forward(_angles_of(robot, loc))
    return loc.matrix()


class _MoveClass:
    """GPL ``Move`` (global class: one instance; see the module docstring)."""

    # -- the motion itself -----------------------------------------------------------------------

    def _go(self, loc: Location, prof: Profile, pose: Callable[[RobotState, np.ndarray], np.ndarray] | None = None,
            joints: Callable[[RobotState, np.ndarray], np.ndarray] | None = None,
            angles: Callable[[RobotState, np.ndarray], np.ndarray] | None = None) -> None:
        """Queue one motion: ``joints`` gives a joint-interpolated target; ``pose`` a Cartesian one
        (straight or joint per the Profile); ``angles`` the joint target of a straight move to an
        Angles Location, whose axes that do not set the tool pose (rail, grippers) must also
        reach their values."""
        _need(loc, Location, "Location")
        _need(prof, Profile, "Profile")
        s = current_session()
        robot = _ready(s)
        t = s.scheduler.clock.now()
        speed = s.controller.system_speed
        last = robot.queue.last
        dest = last.q_end if last is not None else robot.queue.rest  # read only: never modified
        with robot.lock:
            if joints is not None:
                robot.queue_joint(t, joints(robot, dest), prof, speed)
                return
            if angles is not None and prof.Straight:
                # (an Angles Location carries its own extra axes: a pending Extra waits for the
                # next motion to a Cartesian Location, as after a joint move to Angles)
                q1 = angles(robot, dest)
                T1 = robot.forward(q1)
                robot.queue_path(t, lambda P0: LinePath(P0, T1), int(loc.Config), prof, speed, q1,
                                 extra_mask=robot.passive_mask, angles_end=q1)
                return
            assert pose is not None
            seed, extra_end = _with_extra(robot, dest)
            T1 = pose(robot, dest)
            if prof.Straight:
                robot.queue_path(t, lambda P0: LinePath(P0, T1), int(loc.Config), prof, speed, extra_end)
            else:
                robot.queue_pose(t, matrix_to_pose(T1), int(loc.Config), prof, speed, seed)

    def Loc(self, Location1: Location, Profile1: Profile) -> None:
        """Move to the total position of ``Location1`` (Cartesian or Angles)."""
        loc = Location1
        # (the runtime's own fields, not the GPL properties: this is the hot path)
        if isinstance(loc, Location) and loc._type == 1 and isinstance(Profile1, Profile) and not Profile1._straight:
            # the commonest move of all, kept short (benchmarks/motion_speed.py measures it):
            # current_session() and registry.thread_key() in one look at the calling thread
            ctx = current_ctx()
            s: Session | None
            if ctx is not None and (s := ctx.sched.session) is not None:
                key: ThreadKey = ctx
            else:
                s, key = current_session(), registry.thread_key()
            robot = _ready_now(s, key)
            vals = loc._angles  # Python floats (Location.from_angles / Angles store them so)
            n = robot._axis_count
            with robot.lock:
                if len(vals) >= n:
                    values = vals[:n]  # what _angles_of gives, as the tuple Ruckig takes (no copy when n)
                else:
                    values = _angles_of(robot, loc).tolist()
                robot.queue_joint_values(s.scheduler.clock.now(), values, Profile1, s.controller.system_speed)
        elif isinstance(loc, Location) and loc._type != 1 and isinstance(Profile1, Profile):
            # a Cartesian Location: what the controller plans when the move is queued is the
            # destination's joints and the profile — of the joints, or of a straight line's path
            # (kept short for the same benchmark); Move.Extra values take the general way
            ctx = current_ctx()
            if ctx is not None and (s := ctx.sched.session) is not None:
                key = ctx
            else:
                s, key = current_session(), registry.thread_key()
            robot = _ready_now(s, key)
            P1 = loc.total_pose()
            with robot.lock:
                if robot.pending_extra:
                    self._go(loc, Profile1, pose=lambda r, dest: _cartesian(r, loc, dest))
                elif Profile1._straight:
                    robot.queue_path(s.scheduler.clock.now(), lambda P0: LinePath(P0, P1), loc._config, Profile1,
                                     s.controller.system_speed)
                else:
                    robot.queue_pose(s.scheduler.clock.now(), P1, loc._config, Profile1, s.controller.system_speed)
        elif isinstance(loc, Location) and loc.Type == 1:
            self._go(loc, Profile1, angles=lambda r, dest: _angles_of(r, loc))
        else:
            self._go(loc, Profile1, pose=lambda r, dest: _cartesian(r, loc, dest))

    def Approach(self, Location1: Location, Profile1: Profile) -> None:
        """Move to the clearance position of ``Location1`` (ZClearance / ZWorld)."""
        loc = Location1

        def pose(r: RobotState, dest: np.ndarray) -> np.ndarray:
            zc = float(loc.ZClearance)
            if zc >= NO_CLEARANCE:
                raise GplException(ZCLEARANCE_NOT_SET, robot_num=r.number)
            T = _cartesian(r, loc, dest).copy()
            if loc.ZWorld:
                T[2, 3] = zc
            else:
                T[:3, 3] -= zc * T[:3, 2]
            return T

        self._go(loc, Profile1, pose=pose)

    def Rel(self, Location1: Location, Profile1: Profile) -> None:
        """Move relative to the destination of the previous motion (see the module docstring)."""
        loc = Location1
        # (the runtime's own fields, not the GPL properties: this is the hot path)
        if isinstance(loc, Location) and loc._type == 1 and isinstance(Profile1, Profile) and not Profile1._straight:
            self._go(loc, Profile1, joints=lambda r, dest: dest + _angles_of(r, loc))
        elif isinstance(loc, Location) and loc.Type == 1:
            self._go(loc, Profile1, pose=lambda r, dest: r.forward(dest + _angles_of(r, loc)))
        else:
            self._go(loc, Profile1, pose=lambda r, dest: r.forward(dest) @ loc.matrix())

    def OneAxis(self, Axis: Integer, Position: Double, RelativeFlag: Boolean, Profile1: Profile) -> None:
        """Move one axis (1-based) to ``Position`` (or by it, when ``RelativeFlag``)."""
        _need(Profile1, Profile, "Profile")
        s = current_session()
        robot = _ready(s)
        axis = to_int32(Axis)
        position = _finite(Position, "Move.OneAxis position")
        if not 1 <= axis <= robot.axis_count:
            raise GplException(INVALID_AXIS, robot_num=robot.number, axis=axis, detail=f"axis {axis}")
        with robot.lock:
            q = robot.queue.final_joints()
            q[axis - 1] = q[axis - 1] + position if RelativeFlag else position
            robot.queue_joint(s.scheduler.clock.now(), q, Profile1, s.controller.system_speed)

    def Arc(self, Location1: Location, Location2: Location, Profile1: Profile) -> None:
        """Circular arc from the previous destination through ``Location1`` to ``Location2``."""
        self._circular(Location1, Location2, Profile1, full=False)

    def Circle(self, Location1: Location, Location2: Location, Profile1: Profile) -> None:
        """Full circle through the previous destination, ``Location1`` and ``Location2``."""
        self._circular(Location1, Location2, Profile1, full=True)

    def _circular(self, loc1: Location, loc2: Location, prof: Profile, *, full: bool) -> None:
        _need(loc1, Location, "Location1")
        _need(loc2, Location, "Location2")
        _need(prof, Profile, "Profile")
        s = current_session()
        robot = _ready(s)
        with robot.lock:
            dest = robot.queue.final_joints()
            _, extra_end = _with_extra(robot, dest)
            p_mid = _cartesian(robot, loc1, dest)[:3, 3]
            T2 = _cartesian(robot, loc2, dest)
            robot.queue_path(s.scheduler.clock.now(), lambda P0: ArcPath(P0, p_mid, T2, full=full),
                             int(loc2.Config), prof, s.controller.system_speed, extra_end,
                             kind="circle" if full else "arc")

    def Delay(self, Seconds: Double) -> None:
        """Insert a pause of ``Seconds`` into the motion queue.

        Decision [P] (delay.htm gives no range): a pause longer than ``MAX_DELAY`` (the Int32
        milliseconds of ``Thread.Sleep``, about 24.8 days) is -707 *Value out of range*; a huge
        one would otherwise be queued and overflow the clock's nanoseconds at WaitForEOM.
        """
        seconds = _finite(Seconds, "Move.Delay seconds")
        if seconds > MAX_DELAY:
            raise GplException(VALUE_OUT_OF_RANGE, detail=f"Move.Delay {seconds} s (at most {MAX_DELAY} s)")
        s = current_session()
        robot = _ready(s)
        with robot.lock:
            robot.queue_delay(s.scheduler.clock.now(), seconds)

    def Extra(self, Axis1: Double, Axis2: Double | None = None, Axis3: Double | None = None,
              Axis4: Double | None = None) -> None:  # type: ignore[assignment]
        """Positions of the extra axes for the next motion to a Cartesian Location."""
        robot = _attached(current_session())
        n_extra = int(np.count_nonzero(robot.extra_mask))
        vals = [_finite(v, f"Move.Extra axis {i}") for i, v in enumerate((Axis1, Axis2, Axis3, Axis4), 1)
                if v is not None]
        robot.pending_extra = vals[:n_extra]

    def WaitForEOM(self) -> None:
        """Wait until the attached robot's queued motions have ended (and settled)."""
        s = current_session()
        robot = _attached(s)
        sched = s.scheduler
        while robot.special is not None:  # a special mode has no end of motion until it stops
            sched.wait(robot.eom_waiters, None, until=lambda: robot.special is None)
        while True:
            # the path motions' cycles up to the end: one may stop the robot (and the queue) early
            end = robot.queue.end_time
            if robot.queue.paths_pending:
                with robot.lock:
                    robot.queue.advance(end)
                    end = robot.queue.end_time
            if sched.clock.reached(end):
                break
            if sched.run_alone_until(end):  # one GPL thread, as a rule: nothing else can happen first
                continue
            with controller_wait(end):
                sched.wait(robot.eom_waiters, end, until=lambda: sched.clock.reached(robot.queue.end_time))
        robot.raise_async_error()

    # -- special modes and motion events (gplrt.motion.special) -----------------------------------

    def StopSpecialModes(self) -> None:
        """End jog or torque mode where the robot is (nothing to do in position mode)."""
        s = current_session()
        special.stop_special_modes(s, _attached(s))

    def StartJogMode(self) -> None:
        """Enter jog mode, holding where the queued motions end."""
        s = current_session()
        robot = _special_ready(s)
        special.start_jog_mode(s, robot)

    def SetJogCommand(self, JogMode: Integer, JogAxis: Integer, JogSpeed: Double) -> None:
        """Jog mode 0 (hold), 1 (joint ``JogAxis`` at ``JogSpeed`` %) or 4 (free ``JogAxis``)."""
        s = current_session()
        special.set_jog_command(s, _attached(s), to_int32(JogMode), to_int32(JogAxis),
                                _finite(JogSpeed, "Move.SetJogCommand speed"))

    def StartTorqueCntrl(self, MotorMask: Integer, AdcMask: Integer, Torques: GplArray[Double]) -> None:
        """Torque control of the axes in ``MotorMask`` with ``Torques`` (% of peak, per axis)."""
        s = current_session()
        _need(Torques, GplArray, "Torques array")
        special.start_torque_mode(s, _special_ready(s), to_int32(MotorMask), to_int32(AdcMask), Torques)

    def SetTorques(self, Torques: GplArray[Double]) -> None:
        """New torques for the axes in torque mode."""
        s = current_session()
        _need(Torques, GplArray, "Torques array")
        special.set_torques(s, _attached(s), Torques)

    def Trigger(self, Mode: Integer, TriggerPt: Double, Target: Any, EventMask: Integer = 0) -> None:  # type: ignore[assignment]
        """At ``TriggerPt`` % of the next motion, send ``EventMask`` to the Thread ``Target`` (or
        turn on output ``Target``).  The four-argument form is the one real code uses."""
        s = current_session()
        robot = _attached(s)
        target = Target if hasattr(Target, "SendEvent") else to_int32(Target)
        special.arm_trigger(robot, to_int32(Mode), _finite(TriggerPt, "Move.Trigger point"), target,
                            to_int32(EventMask))

    def ForceOverlap(self, Mode: Integer, Criterion: Double) -> None:
        """Overlap the next joint motion with the running one by ``Criterion`` % of its duration."""
        s = current_session()
        robot = _attached(s)
        if to_int32(Mode) != 0:
            raise GplException(INCONSISTENT_TRIGGER_MODE, robot_num=robot.number,
                               detail=f"Move.ForceOverlap mode {Mode}: only mode 0 is simulated")
        robot.pending_overlap = max(0.0, min(100.0, _finite(Criterion, "Move.ForceOverlap criterion")))

    # -- special trajectory modes, not simulated (gpl-classes §22.5) -------------------------------
    # Their real signatures (gpl-dictionary §4) let the transpiler check calls; each raises -204.

    @not_simulated
    def SetRealTimeMod(self, changes: GplArray[Double]) -> None:
        """Incremental path changes while real-time modification is on."""

    @not_simulated
    def StartRealTimeMod(self, coordinates: Integer, change_type: Integer) -> None:
        """Start real-time modification of the planned path."""

    @not_simulated
    def SetSpeeds(self, speeds: GplArray[Double], profile: Profile) -> None:
        """Target speed of every axis in velocity-control mode."""

    @not_simulated
    def StartSpeedDAC(self, mode: Integer, n_segments: Integer, speeds: GplArray[Double],
                      dacs: GplArray[Double]) -> None:
        """Drive an analog output from the tool-tip speed."""

    @not_simulated
    def StartVelocityCntrl(self, mode: Integer, adc_mask: Integer, speeds: GplArray[Double],
                           profile: Profile) -> None:
        """Switch every axis from position to velocity control."""


Move = _MoveClass()
