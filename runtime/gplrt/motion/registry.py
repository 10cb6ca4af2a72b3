"""The session's robots: how one is built, who holds it, and what power changes do to them.

The robots live in the session (``Session.robots``, ``Session.selected``: ``gplrt.session``); this
module is what the motion runtime does with them:

* ``build_robot(session, n)`` — the :class:`RobotState` of robot ``n``, built from the session's
  parameter database (``session.database()``) into ``session.robots``; ``Session.robot(n)``
  calls it on first use (the composer, ``gplrt.sim.Simulation``, wires it).  A robot number
  the database does not define raises -1001 *Undefined robot*.
* ``thread_key()`` — the identity used for ``Robot.Attached``/``Selected``: the GPL thread's
  scheduler record, or the Python thread for code outside the scheduler (a notebook).
* Thread end releases the robots the thread had attached (gpl-classes §22.3 item 4):
  ``release_on_exit``, one of the session's ``thread_exit_hooks``.
* Parameter-database writes: ``listen(session, pdb)`` has the database tell ``_pdb_written`` of
  every change (through a listener that holds the session weakly); a change to one of the
  DataIDs the limits come from (``limits.LIMIT_DATA_IDS``) reloads that robot's
  :class:`RobotLimits` (with the hard maxima derived from them), so later motions use the new
  values; motions already queued keep the plan they were given.
* Power: ``power_dropped(session)`` is called by ``Controller.PowerEnabled = False`` /
  ``SoftEStop`` (controller/services.py) and stops every robot at once.  ``PowerState`` reads 21
  while a robot is attached and 28 while homing (gpl-dictionary §13.3).
"""

from __future__ import annotations

import threading
import weakref
from typing import TYPE_CHECKING

import numpy as np

from gplrt.controller.pdb import ParameterDatabase
from gplrt.controller.state import POWER_ATTACHED, POWER_HOMING, POWER_ON_STATES, POWER_READY
from gplrt.lang.errors import INVALID_ROBOT_NUMBER, POWER_NOT_ENABLED, GplException
from gplrt.motion.kinematics import build_model
from gplrt.motion.limits import LIMIT_DATA_IDS, RobotLimits
from gplrt.motion.queue import MotionQueue
from gplrt.motion.robot import RobotState
from gplrt.motion.servo import joint_to_motor_scale, make_gripper
from gplrt.session import Session
from gplrt.threads.scheduler import ThreadKey, WaitQueue, current_ctx

if TYPE_CHECKING:
    from gplrt.threads.thread import Thread

__all__ = [
    "POWER_ATTACHED", "POWER_HOMING", "POWER_READY", "attached_robot", "build_robot", "listen", "pdb_of",
    "power_dropped", "power_on", "refresh_power_state", "release_on_exit", "robot_moving", "robot_numbers",
    "robot_of", "selected", "set_selected", "thread_key",
]


def thread_key() -> ThreadKey:
    ctx = current_ctx()
    return ctx if ctx is not None else threading.current_thread()


def pdb_of(s: Session) -> ParameterDatabase:
    """The session's parameter database, booted on first use (``Session.database``)."""
    return s.database()


def robot_numbers(s: Session) -> list[int]:
    return [int(n) for n in s.database().robots()]


def robot_of(s: Session, n: int) -> RobotState:
    """The RobotState of robot ``n`` (1-based), built on first use (``Session.robot``)."""
    return s.robot(int(n))


def build_robot(s: Session, n: int) -> RobotState:
    """Build robot ``n`` of ``s`` from its parameter database into ``s.robots`` (once)."""
    n = int(n)
    robot = s.robots.get(n)
    if robot is not None:
        return robot
    if n < 1:
        raise GplException(INVALID_ROBOT_NUMBER, detail=f"robot {n}")
    pdb = s.database()
    model = build_model(pdb, n)  # -1001 when the PDb does not define robot n
    limits = RobotLimits.from_pdb(pdb, n, model.axis_count)
    rest = np.array(model.ready_joints(), dtype=float)
    gripper = make_gripper(model)
    if gripper is not None:  # the fingers rest closed, on their stop (not beyond it)
        rest[gripper.axis] = max(rest[gripper.axis], gripper.closed_stop)
    robot = RobotState(n, model, limits, model.tool.copy(), model.base.copy(),
                       MotionQueue(rest, window=s.history, clock=s.scheduler.clock.now),
                       eom_waiters=WaitQueue(f"robot {n} end of motion"), gripper=gripper,
                       motor_scale=joint_to_motor_scale(pdb, n, model.axis_count))
    s.robots[n] = robot
    return robot


def listen(s: Session, pdb: ParameterDatabase) -> None:
    """Have ``pdb`` (the database the session's robots are built from) tell ``_pdb_written`` of
    its changes (the composer calls this once per session and database, when it boots one).

    The listener holds the session weakly: a database can outlive its session (a notebook puts
    one database on each new Simulation), and a strong reference from it would keep every
    finished session alive, robots and planned motion included.  A listener whose session is
    gone removes itself at the next write."""
    session = weakref.ref(s)

    def written(data_id: int, unit: int, unit2: int) -> None:
        live = session()
        if live is None:
            pdb.listeners.remove(written)  # ParameterDatabase calls a copy of its list: safe
            return
        _pdb_written(live, pdb, data_id, unit, unit2)

    pdb.listeners.append(written)


def _pdb_written(s: Session, pdb: ParameterDatabase, data_id: int, unit: int, unit2: int) -> None:
    """A parameter-database value changed: reload the limits of robot ``unit`` when it is one
    they come from.  Nothing is done per Move: the memo of ``joint_limits`` is dropped here."""
    if data_id not in LIMIT_DATA_IDS:
        return
    robot = s.robots.get(int(unit))
    if robot is None:
        return  # not built yet: it reads the database as it is when it is built
    with robot.lock:
        robot.limits.reload(pdb, robot.number, robot.axis_count)


def selected(s: Session) -> int:
    return s.selected.get(thread_key(), 1)


def set_selected(s: Session, n: int) -> None:
    s.selected[thread_key()] = int(n)


def attached_robot(s: Session, key: ThreadKey) -> RobotState | None:
    for robot in s.robots.values():
        if robot.owner is key:
            return robot
    return None


def robot_moving(robot: RobotState, t: float) -> bool:
    """Whether ``robot`` has motion queued and not finished at controller time ``t`` (a motion,
    its InRange settling or a Move.Delay dwell: what ``Robot.TrajState`` reports as non-zero).

    Path motions run their cycles up to ``t`` first, so one that stopped on a mid-path fault
    counts as stopped where it stopped.  That changes the queue, so it holds the robot's lock as
    the state readers do (RobotState.joints_at): under the real clock another thread may be
    reading or queueing on the same robot."""
    queue = robot.queue
    with robot.lock:
        if queue.paths_pending:
            queue.advance(t)
        return bool(queue.pending(t))


def power_on(s: Session) -> bool:
    """High power is on (PowerState in the controller's power-on states): the one test Move and
    Robot both make before a motion or a homing."""
    return s.controller.power_state in POWER_ON_STATES


def refresh_power_state(s: Session) -> None:
    """21 while some robot is attached, 20 otherwise (only while power is on and idle)."""
    state = s.controller
    if state.power_state in (POWER_READY, POWER_ATTACHED):
        busy = any(r.owner is not None for r in s.robots.values())
        state.power_state = POWER_ATTACHED if busy else POWER_READY


def release_on_exit(thread: Thread) -> None:
    """A GPL thread ended: the robots it had attached are free (a thread-exit hook)."""
    s = thread._session
    key = thread._ctx
    for robot in list(s.robots.values()):
        if robot.owner is not None and robot.owner is key:
            robot.owner = None
    refresh_power_state(s)


def power_dropped(s: Session, code: int = POWER_NOT_ENABLED) -> None:
    """High power went off: every robot stops where it is; moving ones report ``code`` (-1046,
    or -1045 *Soft E-STOP* when a soft E-stop dropped it)."""
    t = s.now()
    for robot in s.robots.values():
        robot.stop_now(t, code)
        s.scheduler.notify_all(robot.eom_waiters)
