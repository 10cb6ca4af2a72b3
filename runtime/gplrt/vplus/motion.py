"""V+ motion instructions on the shared planner, with V+'s per-task modal state (spec §3.10).

Each motion builds a core ``Profile`` from the task's ``MotionState`` and calls the core's ``Move``
(Ruckig on the robot's Pinocchio kinematics), then returns **when its segment begins**: at once
when the robot was still, at the blend point of the running motion under CP.  That is V+'s
forward processing (L6309-6325): ``MOVE a; SIGNAL 1; MOVE b; SIGNAL 2`` turns 1 on as the robot
leaves for a and 2 as it leaves for b.  CP (the CP switch, CPON/CPOFF) is the core's blend
(``Profile.InRange = -1``); BREAK, OPENI, CLOSEI, RELAXI, TOOL, BASE and DETACH (0) wait for the
robot to stop (L6454-6459).

Modal vs one-shot (L6638-6652, L6586-6589, L6732-6734): ``SPEED``, ``DURATION`` and the tolerance
modifiers without ALWAYS, the configuration requests, CPON/CPOFF without ALWAYS and OPEN/CLOSE/
RELAX apply to the next motion only and are consumed by it.

[D] The simulated robot is powered and calibrated when a task first attaches it (V+ calibrates
at start-up; a program cannot press the power button).  Task 0 attaches robot 1 by itself
(L719-751).  ``READY`` is every joint at 0.  The hand is two digital outputs (``HAND_SIGNALS``:
open, close), changed when the next motion starts (OPEN/CLOSE) or at once (OPENI/CLOSEI, which
then wait HAND.TIME).  DURATION stretches motions (``_stretch``).  Not yet honoured: COARSE/FINE,
SINGLE/MULTIPLE, OVERLAP.  ``SPEED v MMPS|IPS`` is the
percent of the robot's nominal Cartesian speed that gives v on straight lines.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from gplrt.controller.services import Controller
from gplrt.geometry.location import Location
from gplrt.geometry.transforms import matrix_to_pose
from gplrt.lang.errors import GplException
from gplrt.motion import registry
from gplrt.motion.kinematics.config import GPL_ABOVE, GPL_BELOW, GPL_FLIP, GPL_LEFTY, GPL_NOFLIP, GPL_RIGHTY
from gplrt.motion.move import Move
from gplrt.motion.path_run import path_limits
from gplrt.motion.planner import plan_axes, plan_scalar
from gplrt.motion.profile import Profile
from gplrt.motion.robot_class import Robot
from gplrt.motion.straight import LinePath
from gplrt.session import current_session
from gplrt.threads.scheduler import controller_wait
from gplrt.vplus.errors import ILLEGAL_VALUE, VError, from_core
from gplrt.vplus.operators import to_int
from gplrt.vplus.signals import signal
from gplrt.vplus.system import parameter, switch, switch_set
from gplrt.vplus.taskstate import _sleep, current_task, safepoint
from gplrt.vplus.transforms import compose, inverse, trans
from gplrt.vplus.values import session_data

#: LEFTY, RIGHTY, ... -> the core's configuration bits (``Location.Config``), which the robots'
#: kinematics interpret (the Cobra's elbow by Righty/Lefty, the Viper's wrist by Flip/NoFlip).
CONFIG_BITS = {"RIGHTY": GPL_RIGHTY, "LEFTY": GPL_LEFTY, "ABOVE": GPL_ABOVE, "BELOW": GPL_BELOW,
               "NOFLIP": GPL_NOFLIP, "FLIP": GPL_FLIP}
HAND_SIGNALS = (1, 2)  # (open, close) [D]


@dataclass
class MotionState:
    speed: float = 100.0  # program speed, 100 when the program starts (L6565-6581)
    accel: float = 100.0
    decel: float = 100.0
    duration: float = 0.0
    speed_once: float | None = None
    duration_once: float | None = None
    cp_once: bool | None = None
    config_once: int = 0
    hand_once: str | None = None
    modifiers: dict[str, bool] = field(default_factory=dict)


def _state() -> MotionState:
    task = current_task()
    if task.motion is None:
        task.motion = MotionState()
    return task.motion


def _core(call: Callable[[], Any]) -> Any:
    try:
        return call()
    except VError:
        raise
    except GplException as exc:
        raise from_core(exc) from None


# -- the robot ---------------------------------------------------------------------------------------

def attach_robot(number: int = 1) -> None:
    """``ATTACH (0)`` / ``ATTACH ()``: this task gets the robot, powered and calibrated [D]."""
    s = current_session()
    _core(lambda: setattr(Robot, "Attached", number))
    robot = s.robot(number)
    if not registry.power_on(s):
        _core(lambda: setattr(Controller, "PowerEnabled", True))
    robot.homed = True


def detach_robot() -> None:
    s = current_session()
    if registry.attached_robot(s, registry.thread_key()) is not None:
        break_()
        _core(lambda: setattr(Robot, "Attached", 0))


def select_robot(number: Any) -> None:
    """``SELECT ROBOT = n``: [D] the simulation has one robot: only 1 is accepted."""
    if to_int(number) != 1:
        raise VError(ILLEGAL_VALUE, detail=f"robot {to_int(number)}")


def _number() -> int:
    """The robot HERE/DEST read: the task's own, else robot 1 (any task may read where it is)."""
    robot = registry.attached_robot(current_session(), registry.thread_key())
    return robot.number if robot is not None else 1


def _robot() -> Any:
    safepoint()
    s = current_session()
    robot = registry.attached_robot(s, registry.thread_key())
    if robot is None and current_task().number == 0:
        attach_robot()
        robot = registry.attached_robot(s, registry.thread_key())
    return robot


# -- modal state -------------------------------------------------------------------------------------

def speed(value: Any, rotation: Any = None, unit: str | None = None, always: bool = False) -> None:
    """``SPEED v [, r] [MMPS|IPS|MONITOR] [ALWAYS]``."""
    v = float(value)
    if v <= 0:
        raise VError(ILLEGAL_VALUE, detail=f"SPEED {v}")
    u = (unit or "").upper()
    if u == "MONITOR":
        Controller.SystemSpeed = min(v, 100.0)  # (the core's property: kept when its database boots)
        return
    if u in ("MMPS", "IPS"):
        # an absolute tool speed (L6583-6594): the percent of the robot's nominal Cartesian speed
        # (DataID 2701) that gives it; like V+, it assumes monitor speed 100
        mm_per_s = v * 25.4 if u == "IPS" else v
        v = 100.0 * mm_per_s / current_session().robot(_number()).limits.cart_speed[0]
    st = _state()
    if always:
        st.speed, st.speed_once = v, None
    else:
        st.speed_once = v


def speed_value(which: Any = 1) -> float:
    """``SPEED(n)``: 1 monitor speed, 2 program speed [D]."""
    if to_int(which) == 1:
        return float(Controller.SystemSpeed)
    return _state().speed


def accel_value(which: Any = 1) -> float:
    """``ACCEL(n)`` (function): 1 the program's acceleration, 2 its deceleration, in percent [D]."""
    st = _state()
    return st.decel if to_int(which) == 2 else st.accel


def duration_value(which: Any = 0) -> float:
    """``DURATION(n)`` (function): the minimum motion time in force (the ALWAYS one) [D]."""
    return _state().duration


def config_value(which: Any = 0) -> float:
    """``CONFIG(n)`` (function): [D] the robot's present configuration as the core's bits
    (Righty 1, Lefty 2, Above 4, Below 8, Flip 16, NoFlip 32)."""
    return float(here().Config)


def select_value(name: str = "ROBOT") -> float:
    """``SELECT(ROBOT)`` (function): the selected robot; the simulation has robot 1."""
    return 1.0


def accel(a: Any, d: Any = None) -> None:
    st = _state()
    st.accel = float(a)
    st.decel = float(d) if d is not None else st.decel


def duration(t: Any, always: bool = False) -> None:
    st = _state()
    if always:
        st.duration = float(t)
    else:
        st.duration_once = float(t)


def modifier(name: str, always: bool = False) -> None:
    """COARSE/FINE/NULL/NONULL/SINGLE/MULTIPLE/OVERLAP/NOOVERLAP (kept, see the module docstring)."""
    _state().modifiers[name.upper()] = always


def config(name: str) -> None:
    """LEFTY/RIGHTY/ABOVE/BELOW/FLIP/NOFLIP for the next motion."""
    key = name.upper()
    if key not in CONFIG_BITS:
        raise VError(ILLEGAL_VALUE, detail=name)
    _state().config_once |= CONFIG_BITS[key]


def lefty() -> None:
    config("LEFTY")


def righty() -> None:
    config("RIGHTY")


def above() -> None:
    config("ABOVE")


def below() -> None:
    config("BELOW")


def flip() -> None:
    config("FLIP")


def noflip() -> None:
    config("NOFLIP")


def cp(on: bool, always: bool = False) -> None:
    """CPON/CPOFF: for the next motion, or the CP switch with ``always``; CPOFF breaks CP."""
    if always:
        switch_set("CP", -1.0 if on else 0.0)
    else:
        _state().cp_once = on
    if not on:
        break_()


def _profile(straight: bool, speed_override: float | None = None) -> Profile:
    st = _state()
    prof = Profile()
    prof.Speed = speed_override if speed_override is not None else (st.speed_once or st.speed)
    prof.Accel = st.accel
    prof.Decel = st.decel
    prof.Straight = straight
    cp_on = st.cp_once if st.cp_once is not None else bool(switch("CP"))
    prof.InRange = -1.0 if cp_on else 0.0
    return prof


def _consume() -> tuple[int, str | None]:
    st = _state()
    cfg, hand = st.config_once, st.hand_once
    st.speed_once = st.duration_once = st.cp_once = None
    st.config_once, st.hand_once = 0, None
    return cfg, hand


def _begin(robot: Any, hand: str | None) -> None:
    """Wait until the segment just queued starts (forward processing), then the hand change."""
    seg = robot.queue.last
    if seg is not None:
        sched = current_session().scheduler
        if not sched.clock.reached(seg.t0):
            with controller_wait(seg.t0):
                sched.sleep_until(seg.t0)
    if hand is not None:
        _hand_now(hand)


# -- motions -----------------------------------------------------------------------------------------

def _go(target: Location, straight: bool) -> None:
    if not isinstance(target, Location):
        raise VError(ILLEGAL_VALUE, detail="motion target is not a location")
    robot = _robot()
    prof = _profile(straight)
    st = _state()
    minimum = st.duration_once if st.duration_once is not None else st.duration
    cfg, hand = _consume()
    if cfg and target._type == 0:
        target = target._copy()
        target._config = cfg
    if minimum > 0.0:
        _core(lambda: _stretch(robot, prof, target, minimum, straight))
    _core(lambda: Move.Loc(target, prof))
    _begin(robot, hand)


def _stretch(robot: Any, prof: Profile, target: Location, minimum: float, straight: bool) -> None:
    """``DURATION t``: a motion that would take less than t seconds is slowed to take t, by scaling
    its profile in time (speed × k, accelerations × k², ramps ÷ k, k = planned / t), which scales a
    Ruckig trajectory's duration by exactly 1/k.  The planned time is the core's own plan of the
    motion (``plan_axes`` for a joint motion, the path's 1-D plan for a straight line), [D] from
    rest at the previous destination: a blend may shorten the motion slightly."""
    system_speed = current_session().controller.system_speed
    q0 = robot.queue.final_joints()
    if target._type == 1:
        q1 = [float(v) for v in target.axis_values()[:robot.axis_count]]
        end_pose = matrix_to_pose(robot.forward(q1))
    else:
        end_pose = target.total_pose()
        q1 = robot.inverse(target.matrix(), int(target._config), q0).tolist()
    if straight:
        path = LinePath(robot.pose_of(q0), end_pose)
        v, acc, dec, jerk = path_limits(path.length, path.turn, q0.tolist(), q1,
                                        robot.limits.line_limits(prof, system_speed))
        planned = plan_scalar(0.0, 0.0, 0.0, 1.0, v, acc, dec, jerk).duration
    else:
        planned = plan_axes(q0, None, None, q1, robot.limits.joint_limits(prof, system_speed)).duration
    if 0.0 < planned < minimum:
        k = planned / minimum
        prof.Speed = prof.Speed * k
        prof.Accel = prof.Accel * k * k
        prof.Decel = prof.Decel * k * k
        prof.AccelRamp = prof.AccelRamp / k
        prof.DecelRamp = prof.DecelRamp / k


def move(target: Location) -> None:
    """``MOVE t``: joint-interpolated."""
    _go(target, False)


def moves(target: Location) -> None:
    """``MOVES t``: straight line."""
    _go(target, True)


def movet(target: Location, hand_open: Any) -> None:
    """``MOVET t, hand``: MOVE with the hand opened (nonzero) or closed (0) as the motion starts
    [D: the Guide gives MOVET's name only; the corpus writes ``MOVET #safe, TRUE``]."""
    _state().hand_once = "OPEN" if hand_open != 0 else "CLOSE"
    _go(target, False)


def movest(target: Location, hand_open: Any) -> None:
    """``MOVEST t, hand``: MOVES with the hand change of MOVET."""
    _state().hand_once = "OPEN" if hand_open != 0 else "CLOSE"
    _go(target, True)


def _cartesian_target(t: Location) -> Location:
    if t._type == 1:
        robot = _robot()
        q = np.array(t.axis_values()[:robot.axis_count], dtype=float)
        return Location.from_pose(matrix_to_pose(robot.forward(q)))
    return t


def appro(target: Location, d: Any) -> None:
    """``APPRO t, d``: to ``t:TRANS(0,0,-d)``, d mm back along the tool Z axis (L6359-6372)."""
    _go(compose(_cartesian_target(target), trans(0, 0, -float(d))), False)


def appros(target: Location, d: Any) -> None:
    _go(compose(_cartesian_target(target), trans(0, 0, -float(d))), True)


def depart(d: Any) -> None:
    """``DEPART d``: from the destination of the last motion, d mm back along tool Z."""
    _robot()
    _go(compose(dest(), trans(0, 0, -float(d))), False)


def departs(d: Any) -> None:
    _robot()
    _go(compose(dest(), trans(0, 0, -float(d))), True)


def drive(joint: Any, delta: Any, spd: Any) -> None:
    """``DRIVE j, delta, speed``: joint j by delta (deg or mm) at speed % (L6376-6382)."""
    robot = _robot()
    prof = _profile(False, speed_override=float(spd) * (_state().speed_once or _state().speed) / 100.0)
    _, hand = _consume()
    _core(lambda: Move.OneAxis(to_int(joint), float(delta), True, prof))
    _begin(robot, hand)


def ready() -> None:
    """``READY``: every joint to 0 [D]."""
    robot = _robot()
    _go(Location.from_angles([0.0] * robot.axis_count), False)


def delay(seconds: Any) -> None:
    """``DELAY t``: a motion of t seconds during which the robot stays put."""
    robot = _robot()
    _core(lambda: Move.Delay(float(seconds)))
    _begin(robot, None)


def break_() -> None:
    """``BREAK``: wait until the robot has stopped."""
    s = current_session()
    if registry.attached_robot(s, registry.thread_key()) is not None:
        _core(Move.WaitForEOM)


def brake() -> None:
    """``BRAKE``: stop the robot now (any task may)."""
    _core(lambda: Robot.do_RapidDecel(1))


# -- where the robot is ------------------------------------------------------------------------------

def here() -> Location:
    """``HERE``: where the tool is now (world)."""
    safepoint()
    return _core(lambda: Robot.Where(_number()))


def dest() -> Location:
    """``DEST``: the destination of the last motion."""
    safepoint()
    return _core(lambda: Robot.Dest(_number()))


def p_phere() -> Location:
    safepoint()
    return _core(lambda: Robot.WhereAngles(_number()))


def p_pdest() -> Location:
    safepoint()
    return _core(lambda: Robot.DestAngles(_number()))


def here_into(target: Any, *prefix: Location) -> None:
    """``HERE x`` / ``HERE #x`` / ``HERE a:b:x``: x such that a:b:x is where the tool is now."""
    name = getattr(target, "name", "")
    if name.startswith("#"):
        target.v = p_phere()
        return
    now = here()
    if prefix:
        now = compose(inverse(compose(*prefix)), now)
    target.v = Location.from_pose(now.total_pose())


def inrange(t: Location) -> float:
    """``INRANGE(t)``: 0 when the robot can reach t, else the V+ error code."""
    robot = _robot()
    try:
        if t._type == 1:
            robot.check_joint_limits([float(v) for v in t.axis_values()[:robot.axis_count]])
        else:
            robot.inverse(t.matrix(), int(t._config), robot.queue.final_joints(), True)
    except GplException as exc:
        return float(from_core(exc).ErrorCode)
    return 0.0


def tool(t: Location) -> None:
    """``TOOL t``: breaks CP, then the tool transformation."""
    break_()
    _robot()
    _core(lambda: Robot.set_Tool(t))


def tool_value() -> Location:
    _robot()
    return _core(lambda: Robot.Tool())


def base(dx: Any = 0.0, dy: Any = 0.0, dz: Any = 0.0, rz: Any = 0.0) -> None:
    """``BASE dx, dy, dz, rz``: breaks CP, then "translate and rotate the world reference frame
    relative to the robot" (L6764-6765): the world frame sits at TRANS(dx,dy,dz,rz) in the robot's
    frame, so the robot's base in the world (the core's ``Robot.Base``) is its inverse [D: the
    literal reading of L6764; BASE 0,0,300 makes HERE read 300 mm lower]."""
    break_()
    _robot()
    _core(lambda: Robot.set_Base(inverse(trans(float(dx), float(dy), float(dz), float(rz)))))


def base_value() -> Location:
    """``BASE`` (function): the transformation the last BASE set (L6768-6769)."""
    safepoint()
    return inverse(_core(lambda: Robot.Base(_number())))


# -- the hand ----------------------------------------------------------------------------------------

def _hand_now(kind: str) -> None:
    open_sig, close_sig = HAND_SIGNALS
    if kind == "OPEN":
        signal(open_sig, -close_sig)
    elif kind == "CLOSE":
        signal(-open_sig, close_sig)
    else:
        signal(-open_sig, -close_sig)
    session_data().extra["hand"] = kind


def _hand_immediate(kind: str) -> None:
    break_()
    _hand_now(kind)
    _sleep(parameter("HAND.TIME"))


def open_() -> None:
    _state().hand_once = "OPEN"


def close() -> None:
    _state().hand_once = "CLOSE"


def relax() -> None:
    _state().hand_once = "RELAX"


def openi() -> None:
    _hand_immediate("OPEN")


def closei() -> None:
    _hand_immediate("CLOSE")


def relaxi() -> None:
    _hand_immediate("RELAX")


def hand() -> float:
    """``HAND``: -1 when the hand is open [D], else 0."""
    return -1.0 if session_data().extra.get("hand", "OPEN") == "OPEN" else 0.0
