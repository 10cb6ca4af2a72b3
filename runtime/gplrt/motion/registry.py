"""Where the motion runtime finds its robots, the calling thread and the controller state.

* ``robot_of(sim, n)`` — the :class:`RobotState` of robot ``n`` in ``sim.robots``, built on first
  use from the session's parameter database (``sim.pdb``; when the session has none yet, the
  shipped database of ``sim.robot_model``, default PF400SX, is loaded into ``sim.pdb``).  A robot
  number the database does not define raises -1001 *Undefined robot*.
* ``thread_key()`` — the identity used for ``Robot.Attached``/``Selected``: the GPL thread's
  scheduler record, or the Python thread for code outside the scheduler (a notebook).
* Thread end releases the robots the thread had attached (gpl-classes §22.3 item 4), through the
  session's ``thread_exit_hooks``.
* Parameter-database writes: the session's database tells ``_pdb_written`` of every change
  (through a listener that holds the session weakly, ``_listen``); a
  change to one of the DataIDs the limits come from (``limits.LIMIT_DATA_IDS``) reloads that
  robot's :class:`RobotLimits` (with the hard maxima derived from them), so later
  motions use the new values; motions already queued keep the plan they were given.
* Power: ``power_dropped(sim)`` is called by ``Controller.PowerEnabled = False`` / ``SoftEStop``
  (controller/services.py) and stops every robot at once.  ``PowerState`` reads 21 while a robot
  is attached and 28 while homing (gpl-dictionary §13.3).
"""

from __future__ import annotations

import threading
import weakref
from typing import Any

from gplrt.controller.services import POWER_ON_STATES
from gplrt.lang.errors import INVALID_ROBOT_NUMBER, POWER_NOT_ENABLED, GplException
from gplrt.threads.scheduler import WaitQueue, current_ctx

POWER_READY = 20
POWER_ATTACHED = 21
POWER_HOMING = 28


def sim() -> Any:
    """The active Simulation: the calling GPL thread's, else ``gplrt.sim.current()``."""
    ctx = current_ctx()
    if ctx is not None:
        return ctx.sched.sim
    from gplrt.sim import current

    return current()


def now() -> float:
    return float(sim().scheduler.clock.now())


def thread_key() -> Any:
    ctx = current_ctx()
    return ctx if ctx is not None else threading.current_thread()


def _motion(s: Any) -> dict[str, Any]:
    """Per-session motion bookkeeping kept on the Simulation (selected robot per thread)."""
    state = s.__dict__.get("_motion")
    if state is None:
        state = s.__dict__["_motion"] = {"selected": {}, "hooked": False}
    if not state["hooked"]:
        s.thread_exit_hooks.append(_release_on_exit)
        state["hooked"] = True
    return state  # type: ignore[no-any-return]


def pdb_of(s: Any) -> Any:
    if s.pdb is None:
        from gplrt.controller.pdb import default_database

        s.pdb = default_database(getattr(s, "robot_model", "PF400SX"))
        if not s.controller.system_speed_set:
            # DataID 601 "System wide test speed in %" is the SystemSpeed a controller boots with
            # (robot-models.md §2.4: a real PF400 reports 50); a program's own setting wins.
            s.controller.system_speed = s.pdb.get_num(601, default=100.0)
    if not s.pdb.live:
        from gplrt.controller.live_pdb import install

        install(s.pdb)  # the controller's own DataIDs (power state, version, torques, ...)
    return s.pdb


def robot_numbers(s: Any) -> list[int]:
    return [int(n) for n in pdb_of(s).robots()]


def robot_of(s: Any, n: int) -> Any:
    """The RobotState of robot ``n`` (1-based), built on first use."""
    from gplrt.motion.kinematics import build_model
    from gplrt.motion.limits import RobotLimits
    from gplrt.motion.queue import MotionQueue
    from gplrt.motion.robot import RobotState
    from gplrt.motion.servo import joint_to_motor_scale, make_gripper

    n = int(n)
    robot = s.robots.get(n)
    if robot is not None:
        return robot
    if n < 1:
        raise GplException(INVALID_ROBOT_NUMBER, detail=f"robot {n}")
    pdb = pdb_of(s)
    _listen(s, pdb)
    model = build_model(pdb, n)  # -1001 when the PDb does not define robot n
    limits = RobotLimits.from_pdb(pdb, n, model.axis_count)
    import numpy as np

    rest = np.array(model.ready_joints(), dtype=float)
    gripper = make_gripper(model)
    if gripper is not None:  # the fingers rest closed, on their stop (not beyond it)
        rest[gripper.axis] = max(rest[gripper.axis], gripper.closed_stop)
    robot = RobotState(n, model, limits, model.tool.copy(), model.base.copy(), MotionQueue(rest))
    robot.eom_waiters = WaitQueue(f"robot {n} end of motion")
    robot.gripper = gripper
    robot.motor_scale = joint_to_motor_scale(pdb, n, model.axis_count)
    s.robots[n] = robot
    return robot


def _listen(s: Any, pdb: Any) -> None:
    """Have ``pdb`` (the database the session's robots are built from) tell ``_pdb_written`` of
    its changes, once per session and database.

    The listener holds the session weakly: a database can outlive its session (a notebook puts
    one database on each new Simulation), and a strong reference from it would keep every
    finished session alive, robots and planned motion included.  A listener whose session is
    gone removes itself at the next write."""
    state = _motion(s)
    if state.get("pdb") is pdb:
        return
    session = weakref.ref(s)

    def written(data_id: int, unit: int, unit2: int) -> None:
        live = session()
        if live is None:
            pdb.listeners.remove(written)  # ParameterDatabase calls a copy of its list: safe
            return
        _pdb_written(live, pdb, data_id, unit, unit2)

    pdb.listeners.append(written)
    state["pdb"] = pdb


def _pdb_written(s: Any, pdb: Any, data_id: int, unit: int, unit2: int) -> None:
    """A parameter-database value changed: reload the limits of robot ``unit`` when it is one
    they come from.  Nothing is done per Move: the memo of ``joint_limits`` is dropped here."""
    from gplrt.motion.limits import LIMIT_DATA_IDS

    if data_id not in LIMIT_DATA_IDS:
        return
    robot = s.robots.get(int(unit))
    if robot is None:
        return  # not built yet: it reads the database as it is when it is built
    with robot.lock:
        robot.limits.reload(pdb, robot.number, robot.axis_count)


def selected(s: Any) -> int:
    return int(_motion(s)["selected"].get(thread_key(), 1))


def set_selected(s: Any, n: int) -> None:
    _motion(s)["selected"][thread_key()] = int(n)


def attached_robot(s: Any, key: Any) -> Any:
    for robot in s.robots.values():
        if robot.owner is key:
            return robot
    return None


def robot_moving(robot: Any, t: float) -> bool:
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


def power_on(s: Any) -> bool:
    """High power is on (PowerState in the controller's power-on states): the one test Move and
    Robot both make before a motion or a homing."""
    return s.controller.power_state in POWER_ON_STATES


def refresh_power_state(s: Any) -> None:
    """21 while some robot is attached, 20 otherwise (only while power is on and idle)."""
    state = s.controller
    if state.power_state in (POWER_READY, POWER_ATTACHED):
        busy = any(r.owner is not None for r in s.robots.values())
        state.power_state = POWER_ATTACHED if busy else POWER_READY


def _release_on_exit(thread: Any) -> None:
    s = sim()
    keys = {getattr(thread, "_ctx", None)}
    for robot in list(s.robots.values()):
        if robot.owner is not None and robot.owner in keys:
            robot.owner = None
    refresh_power_state(s)


def power_dropped(s: Any, code: int = POWER_NOT_ENABLED) -> None:
    """High power went off: every robot stops where it is; moving ones report ``code`` (-1046,
    or -1045 *Soft E-STOP* when a soft E-stop dropped it)."""
    t = float(s.scheduler.clock.now())
    for robot in s.robots.values():
        robot.stop_now(t, code)
        if robot.eom_waiters is not None:
            s.scheduler.notify_all(robot.eom_waiters)
