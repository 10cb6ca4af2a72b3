"""GPL's global ``Robot`` class (gpl-classes §10, gpl-dictionary §5) and the geometry kinematics hook.

Members that take an optional robot number (``Where(robot)``, ``Dest(robot)``, ...) are methods
whose ``Robot`` argument defaults to 0 = the thread's Selected robot.  Assignable members with
arguments follow CATALOGUE.md rule 5 (``Base``/``set_Base``; the value comes last).

Decisions [P] where the manuals are silent:

* ``Attached = n`` works with power off (a program attaches, then enables power and homes, as the
  GDE start-up code does); a robot held by another thread refuses with -1006; ``0`` releases;
  attaching sets ``Selected``.  A thread holds one robot at a time: attaching another releases
  the first.  The robot is released when the thread ends.
* Detaching a *moving* robot (a motion queued and not finished at the controller clock's now —
  Move.Delay dwells and InRange settling included, as ``TrajState`` <> 0 shows) raises -1008
  *Can't detached a moving robot* (gpl-dictionary.md error table; the GPL manual only says the
  robot is "un-Attached when the program is terminated or pauses", D0:2659-2662, and is silent on
  a detach in mid-motion).  The robot stays attached, so the thread can ``Move.WaitForEOM`` and
  detach again.  Attaching another robot while the first still moves is the same detach and
  refuses the same way.  The release at thread end or Abort (``registry._release_on_exit``)
  is the controller's own clean-up, not a GPL detach, and still releases a moving robot.
* ``Home`` needs the attached robot (-1009) and power (-1046) and takes ``HOMING_TIME`` (1 s) of
  controller time with ``PowerState`` 28; ``HomeAll`` needs power only and homes every robot.
  Joints do not move (absolute encoders, robot-models §2.5).
* ``TrajState(robot, mode)``: the codes TCS labels (Globals.gpl:118-132; docs/design/real-code.md,
  "TrajState codes"): 0 halted (high power off), 1 idle, 2 accelerating, 3 constant speed,
  4 blending into the next motion, 5 decelerating (rapid deceleration included), 6 a motion
  overlapped by ``Move.ForceOverlap``, 8 torque mode [P: no label for it], 9 homing, 10 jog
  mode, 15 nulling (InRange > 0 settling at the end).  A ``Move.Delay`` reads 3 [P: the
  set-point holds, at constant zero speed].  ``mode`` is ignored.  A path motion stopped by a
  mid-path error (``path_run``) is over at its stop: TrajState then says idle and ``Dest`` is
  where it stopped [P] (the queue was flushed; both run the path's cycles up to now first, as
  ``Where`` does, so the answer does not depend on earlier reads).
* ``Tool``/``Base`` assignments apply to later motions and to ``Where``; queued motions are not
  changed (a line's or arc's cycles, solved as it runs, keep the Tool and Base it was queued
  with: ``robot.QueuedFrames``).  ``RestartTool``/``RestartBase`` are DataIDs 16051/16052.
* Writing DataID 213 homes every robot as the controller's own action (``start_homing_all``):
  the writer does not wait; PowerState reads 28 for ``HOMING_TIME``.
* ``JointToMotor(robot, joints, motors)`` / ``MotorToJoint(robot, motors, joints)``: motor
  position = joint position × DataID 2300's scale for that axis (``gplrt.motion.servo``; motor
  counts per mm or degree), element by element for the robot's axes; the output array is
  filled in place (arrays are references); elements beyond either array are left alone.
* ``DefLinComp``: -204 (no encoder linearity model in the simulation).
"""

from __future__ import annotations

from typing import Any, overload

import numpy as np

from gplrt.geometry._checks import wrong_object
from gplrt.geometry.kinematics_provider import set_kinematics_provider
from gplrt.geometry.location import Location
from gplrt.lang.errors import (
    CANT_DETACH_MOVING_ROBOT,
    NOT_CARTESIAN,
    NO_ROBOT_ATTACHED,
    POWER_NOT_ENABLED,
    ROBOT_ALREADY_ATTACHED,
    GplException,
)
from gplrt.lang.arrays import GplArray
from gplrt.lang.conversions import to_double, to_int32
from gplrt.lang.exceptions import not_simulated
from gplrt.lang.gpltypes import Boolean, Double, Integer
from gplrt.motion import registry, servo  # noqa: F401 - servo provides the gripper's inputs
from gplrt.motion.profile import Profile
from gplrt.motion.queue import BlendedPathSegment, DwellSegment, profile_from_values
from gplrt.motion.robot import HOMING_TIME, RobotState
from gplrt.session import Session, current_session
from gplrt.threads.scheduler import controller_wait

#: ``Robot.TrajState`` codes (module docstring).
TRAJ_HALTED, TRAJ_IDLE, TRAJ_ACCEL, TRAJ_CONSTANT, TRAJ_BLENDING, TRAJ_DECEL, TRAJ_OVERLAP = range(7)
TRAJ_TORQUE, TRAJ_HOMING, TRAJ_JOG, TRAJ_NULLING = 8, 9, 10, 15


def _robot(n: int = 0) -> RobotState:
    s = current_session()
    return s.robot(to_int32(n) or registry.selected(s))


def _now() -> float:
    return current_session().now()


def _check_not_moving(robot: RobotState) -> None:
    """-1008 when ``robot`` still has motion to run at the controller clock's now (see the
    module docstring: a GPL detach of a moving robot is refused, the thread-end release is not)."""
    if registry.robot_moving(robot, _now()):
        raise GplException(CANT_DETACH_MOVING_ROBOT, robot_num=robot.number,
                           detail=f"robot {robot.number} is still moving (Move.WaitForEOM first)")


def _source(robot: RobotState) -> np.ndarray:
    """Joints at the start of the last queued motion, or the present ones before any motion."""
    now = _now()
    robot.run_cycles(now)  # a stop by now has dropped the motions after it
    q = robot.source_joints()
    return q if q is not None else robot.joints_at(now)


def _cart(robot: RobotState, q: np.ndarray) -> Location:
    loc = Location.from_matrix(robot.forward(q))
    loc.Config = robot.model.config_of(q)
    return loc


def _angles(q: np.ndarray) -> Location:
    return Location.from_angles([float(v) for v in q])


def _matrix_of(value: Location) -> np.ndarray:
    if not isinstance(value, Location):  # -782 for Nothing, -202 for another object
        raise wrong_object(value, "Tool/Base", "Location")
    if value.Type != 0:
        raise GplException(NOT_CARTESIAN, detail="Tool/Base must be a Cartesian Location")
    return value.matrix()


class _RobotClass:
    """GPL ``Robot`` (global class: one instance; see the module docstring)."""

    # -- attachment and selection -------------------------------------------------------------

    @property
    def Attached(self) -> Integer:
        robot = registry.attached_robot(current_session(), registry.thread_key())
        return (robot.number if robot is not None else 0)  # type: ignore[return-value]

    @Attached.setter
    def Attached(self, value: Integer) -> None:
        s = current_session()
        key = registry.thread_key()
        n = to_int32(value)
        mine = registry.attached_robot(s, key)
        if n == 0:
            if mine is not None:
                with mine.lock:
                    _check_not_moving(mine)
                    mine.owner = None
            registry.refresh_power_state(s)
            return
        robot = s.robot(n)
        # The test of the owner and its setting are one step: under the real clock two threads
        # attaching a free robot at once would otherwise both get it.  (Only the thread that
        # owns ``mine`` takes its lock inside this one, so the nesting cannot deadlock.)
        with robot.lock:
            if robot.owner is not None and robot.owner is not key:
                raise GplException(ROBOT_ALREADY_ATTACHED, robot_num=n,
                                   detail=f"robot {n} is attached by another thread")
            if mine is not None and mine is not robot:
                with mine.lock:
                    _check_not_moving(mine)
                    mine.owner = None
            robot.owner = key
        registry.set_selected(s, n)
        registry.refresh_power_state(s)

    @property
    def Selected(self) -> Integer:
        return registry.selected(current_session())  # type: ignore[return-value]

    @Selected.setter
    def Selected(self, value: Integer) -> None:
        s = current_session()
        n = to_int32(value)
        s.robot(n)  # -1001 for a robot that does not exist
        mine = registry.attached_robot(s, registry.thread_key())
        if mine is not None and mine.number != n:
            return  # Selected is forced equal to Attached while attached (attached.htm)
        registry.set_selected(s, n)

    # -- homing -------------------------------------------------------------------------------

    def Home(self) -> None:
        """Home the attached robot (takes HOMING_TIME of controller time)."""
        s = current_session()
        robot = registry.attached_robot(s, registry.thread_key())
        if robot is None:
            raise GplException(NO_ROBOT_ATTACHED, detail="Robot.Home needs an attached robot")
        self._home(s, [robot])

    def HomeAll(self) -> None:
        """Home every robot of the controller."""
        s = current_session()
        self._home(s, [s.robot(n) for n in registry.robot_numbers(s)])

    def _home(self, s: Session, robots: list[RobotState]) -> None:
        """Home ``robots``: the controller shows PowerState 28 (homing) for ``HOMING_TIME``.

        Threads of a multi-robot cell may home their robots at the same time.  The controller's
        power state is one for all robots, so a homing that starts while another runs joins it
        (the state stays 28 until the last one ends) instead of reading 28 as "power not enabled";
        the state from before the first one is restored, unless power dropped meanwhile.
        """
        _begin_homing(s, robots)
        ok = False
        try:
            with controller_wait(s.scheduler.clock.now() + HOMING_TIME):
                s.scheduler.sleep(HOMING_TIME)
            ok = s.controller.power_state == registry.POWER_HOMING
            if not ok:  # power dropped meanwhile
                raise GplException(POWER_NOT_ENABLED, detail="power went off during homing")
        finally:
            _end_homing(s, robots, ok)

    # -- where the robot is -------------------------------------------------------------------

    def Where(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        """Present Cartesian pose (Base and Tool included; Config = present configuration)."""
        robot = _robot(Robot)
        return _cart(robot, robot.joints_at(_now()))

    def WhereAngles(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        robot = _robot(Robot)
        return _angles(robot.joints_at(_now()))

    def Dest(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        """Final destination of the last queued motion."""
        robot = _robot(Robot)
        robot.run_cycles(_now())  # a line stopped mid-way by now ends where it stopped
        return _cart(robot, robot.queue.final_joints())

    def DestAngles(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        robot = _robot(Robot)
        robot.run_cycles(_now())
        return _angles(robot.queue.final_joints())

    def Source(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        """Start of the last queued motion (the present pose before any motion)."""
        robot = _robot(Robot)
        return _cart(robot, _source(robot))

    def SourceAngles(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        return _angles(_source(_robot(Robot)))

    def SpeedAngles(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        """Present speed of every axis (mm/s or deg/s) as an Angles Location."""
        robot = _robot(Robot)
        return _angles(robot.state_at(_now())[1])

    def LastProfile(self, Robot: Integer = 0) -> Profile | None:  # type: ignore[assignment]
        robot = _robot(Robot)
        return profile_from_values(robot.last_profile) if robot.last_profile is not None else None

    def TrajState(self, Robot: Integer = 0, Mode: Integer = 0) -> Integer:  # type: ignore[assignment]
        return traj_state(_robot(Robot))  # type: ignore[return-value]

    # -- rapid deceleration ---------------------------------------------------------------------

    def RapidDecel(self, Robot: Integer = 0) -> Boolean:  # type: ignore[assignment]
        """True while a rapid deceleration is in progress."""
        return (_now() < _robot(Robot).rapid_decel_until)  # type: ignore[return-value]

    @overload
    def set_RapidDecel(self, value: Boolean) -> None: ...

    @overload
    def set_RapidDecel(self, Robot: Integer, value: Boolean) -> None: ...

    def set_RapidDecel(self, *args: Any) -> None:
        """``Robot.RapidDecel[(robot)] = True``: stop the robot's motion as fast as allowed."""
        if args[-1]:
            self.do_RapidDecel(args[0] if len(args) > 1 else 0)

    def do_RapidDecel(self, Robot: Integer = 0) -> None:
        """``Robot.RapidDecel(robot)`` as a statement: the same as assigning True.  The vendor's
        TCS stops a robot this way (its ``halt`` command, Cmd.gpl:1841); docs/design/real-code.md."""
        robot = _robot(Robot)
        s = current_session()
        with robot.lock:
            robot.rapid_decel(_now())
        s.scheduler.notify_all(robot.eom_waiters)

    # -- offsets -------------------------------------------------------------------------------

    def Tool(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        return Location.from_matrix(_robot(Robot).model.tool)

    @overload
    def set_Tool(self, value: Location) -> None: ...

    @overload
    def set_Tool(self, Robot: Integer, value: Location) -> None: ...

    def set_Tool(self, *args: Any) -> None:
        """``Robot.Tool = loc`` (attached/selected robot) or ``Robot.Tool(robot) = loc``."""
        robot = _robot(args[0] if len(args) > 1 else 0)
        robot.model.tool = _matrix_of(args[-1]).copy()

    def Base(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        return Location.from_matrix(_robot(Robot).model.base)

    @overload
    def set_Base(self, value: Location) -> None: ...

    @overload
    def set_Base(self, Robot: Integer, value: Location) -> None: ...

    def set_Base(self, *args: Any) -> None:
        robot = _robot(args[0] if len(args) > 1 else 0)
        robot.model.base = _matrix_of(args[-1]).copy()

    def RestartTool(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        return Location.from_matrix(_robot(Robot).restart_tool)

    def RestartBase(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        return Location.from_matrix(_robot(Robot).restart_base)

    # -- stored values -------------------------------------------------------------------------

    def Payload(self, Robot: Integer = 0) -> Double:  # type: ignore[assignment]
        return _robot(Robot).payload  # type: ignore[return-value]

    @overload
    def set_Payload(self, value: Double) -> None: ...

    @overload
    def set_Payload(self, Robot: Integer, value: Double) -> None: ...

    def set_Payload(self, *args: Any) -> None:
        _robot(args[0] if len(args) > 1 else 0).payload = to_double(args[-1])

    def Custom(self, Robot: Integer = 0, Index: Integer = 1) -> Double:  # type: ignore[assignment]
        return _robot(Robot).custom.get(to_int32(Index), 0.0)  # type: ignore[return-value]

    @overload
    def set_Custom(self, value: Double) -> None: ...

    @overload
    def set_Custom(self, Index: Integer, value: Double) -> None: ...

    def set_Custom(self, *args: Any) -> None:
        """``Robot.Custom(index) = v`` (custom.htm: the set form has only the index)."""
        index = to_int32(args[0]) if len(args) > 1 else 1
        _robot(0).custom[index] = to_double(args[-1])

    def CartMode(self, Robot: Integer = 0) -> Integer:  # type: ignore[assignment]
        _robot(Robot)
        return 0  # type: ignore[return-value]

    def MotorTempStatus(self, Robot: Integer = 0, Motor: Integer = 1) -> Integer:  # type: ignore[assignment]
        _robot(Robot)
        return 0  # type: ignore[return-value]

    def RealTimeModAcm(self, Robot: Integer = 0) -> Location:  # type: ignore[assignment]
        _robot(Robot)
        return Location()

    def JointToMotor(self, Robot: Integer, JointPos: GplArray[Double], MotorPos: GplArray[Double]) -> None:
        """Motor positions (motor counts) of joint positions (mm or degrees): see the module docstring."""
        _scale_into(_robot(Robot), JointPos, MotorPos, to_motor=True)

    def MotorToJoint(self, Robot: Integer, MotorPos: GplArray[Double], JointPos: GplArray[Double]) -> None:
        """Joint positions of motor positions: the inverse of ``JointToMotor``."""
        _scale_into(_robot(Robot), MotorPos, JointPos, to_motor=False)

    # -- linearity compensation: not simulated (no encoder model) ---------------------------------

    @not_simulated
    def DefLinComp(self, Robot: Integer, motor: Integer, enc_start: Integer, enc_step: Integer,
                   num_cor: Integer, cor: GplArray[Double]) -> None:
        """Define a motor's linearity-compensation table."""


Robot = _RobotClass()


def _scale_into(robot: RobotState, source: Any, target: Any, *, to_motor: bool) -> None:
    """``target(i) = source(i)`` × (or ÷) the joint-to-motor scale of axis i+1, for the robot's axes."""
    for arr, what in ((source, "input"), (target, "output")):
        if not isinstance(arr, GplArray):
            raise wrong_object(arr, f"{what} array", "array")
    count = min(robot.axis_count, source.Length, target.Length)
    for i in range(count):
        scale = robot.motor_scale[i]
        value = to_double(source[i])
        target[i] = value * scale if to_motor else (value / scale if scale else 0.0)


def traj_state(robot: RobotState) -> int:
    """``Robot.TrajState`` and DataID 3520 (see the module docstring for the codes)."""
    t = _now()
    if robot.special is not None:
        return robot.special.traj_state
    if robot.homing:
        return TRAJ_HOMING
    robot.run_cycles(t)  # a path motion stopped mid-way by now is no longer executing
    seg = robot.queue.segment_at(t)
    if seg is None:
        return TRAJ_IDLE if registry.power_on(current_session()) else TRAJ_HALTED
    if isinstance(seg, DwellSegment):
        return TRAJ_CONSTANT
    if t >= seg.motion_end:
        return TRAJ_NULLING
    if seg.kind == "rapid_decel":
        return TRAJ_DECEL
    if seg.kind == "overlap":
        return TRAJ_OVERLAP
    if isinstance(seg, BlendedPathSegment) and t < seg.prev_end:
        return TRAJ_BLENDING
    _, v, a = robot.queue.state_at(t)
    power = float(np.dot(v, a))
    if power > 1e-9:
        return TRAJ_ACCEL
    if power < -1e-9:
        return TRAJ_DECEL
    return TRAJ_CONSTANT


def _begin_homing(s: Session, robots: list[RobotState]) -> None:
    """PowerState 28 while the first of overlapping homings runs (see ``Robot._home``)."""
    state = s.controller
    joining = state.homings > 0 and state.power_state == registry.POWER_HOMING
    if not joining:
        if not registry.power_on(s):
            raise GplException(POWER_NOT_ENABLED, detail="homing needs high power")
        state.power_before_homing = state.power_state
        state.power_state = registry.POWER_HOMING
    state.homings += 1
    for robot in robots:
        robot.homing += 1


def _end_homing(s: Session, robots: list[RobotState], ok: bool) -> None:
    state = s.controller
    state.homings -= 1
    for robot in robots:
        robot.homing -= 1
    if state.homings == 0 and state.power_state == registry.POWER_HOMING:
        state.power_state = state.power_before_homing
        registry.refresh_power_state(s)
    if ok:
        for robot in robots:
            robot.homed = True


def start_homing_all(s: Session) -> None:
    """Home every robot as the controller's own action (DataID 213): PowerState 28 for
    ``HOMING_TIME`` on the controller clock, and the caller does not wait."""
    robots = [s.robot(n) for n in registry.robot_numbers(s)]
    _begin_homing(s, robots)

    def done() -> None:
        _end_homing(s, robots, s.controller.power_state == registry.POWER_HOMING)

    s.scheduler.call_at(s.scheduler.clock.now() + HOMING_TIME, done)


class SimulatedKinematics:
    """The ``KinematicsProvider`` for geometry: the Selected robot of the active session."""

    def forward(self, angles: Location) -> Location:
        robot = _robot(0)
        q = robot.joints_at(_now())
        vals = angles.axis_values()
        q[: min(len(vals), len(q))] = vals[: len(q)]
        return _cart(robot, q)

    def inverse(self, loc: Location, config: int, current: Location | None) -> Location:
        robot = _robot(0)
        ref = robot.joints_at(_now())
        if current is not None:
            vals = current.axis_values()
            ref[: min(len(vals), len(ref))] = vals[: len(ref)]
        return _angles(robot.inverse(loc.matrix(), int(config), ref))

    def where(self) -> Location:
        return Robot.Where(0)

    def where_angles(self) -> Location:
        return Robot.WhereAngles(0)


set_kinematics_provider(SimulatedKinematics())
