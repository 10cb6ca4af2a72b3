"""The TM motion queue on the shared planner (Ruckig, ``gplrt.motion.planner``) and the robot's state.

TMscript's motion calls only *queue* a command and return ``true`` (manual L15519, L14655): one
FIFO holds motions, ``ChangeBase``/``ChangeTCP``/``ChangeLoad``, queued I/O writes and queue tags,
and one executor thread runs it in order.  A motion is planned when it starts, from where the
robot is: ``PTP`` joint-interpolated (``plan_axes``), ``Line``/``Circle``/``PLine`` along their path
(``plan_scalar`` on the path length).  Units are the manual's (spec §4.4): speed % of the joints'
URDF speeds (or mm/s for ``A``/``D`` formats), acceleration as the time in ms to reach top speed.

Time is the controller time of the robot's session (``gplrt.sim.Simulation``: the shared
scheduler's ``virtual``, ``fast`` or ``real`` clock, docs/design/clock.md).  The executor is a
thread of that scheduler: a motion starts at the clock's now and ends ``duration`` later, the
executor waiting for that deadline as a GPL ``WaitForEOM`` would; states read during a motion are
sampled from its plan at the clock's now.  A script that waits for the robot (``QueueTag(n, 1)``,
``WaitQueueTag``, the end of a project, ``Exit``) waits *for the controller*
(``controller_wait``): on the ``fast`` clock time then jumps to the end of the motion in
progress, while a motion nobody waits for keeps real-time pace (its client watches it move).
A motion with a blend value hands over, at its blend zone, to the next motion queued by then:
a PTP is planned by Ruckig from the moving state there, a path motion is superposed on the end of
the blending one (``_superpose``); docs/design/tmscript.md says how.
"""

from __future__ import annotations

import math
import sys
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pinocchio as pin

from gplrt.lang.sourcemap import gpl_line_of
from gplrt.motion.limits import AxisLimits
from gplrt.motion.planner import plan_axes, plan_scalar
from gplrt.sim import Simulation
from gplrt.threads.scheduler import Scheduler, ThreadAbort, WaitQueue, controller_wait
from gplrt.tm.manager import TMManager
from gplrt.tm.vision import Vision
from gplrt.tm.robot import TMArm, pose_to_se3, se3_to_pose
from gplrt.tm.values import TMError

#: 100 % Cartesian speed (mm/s) of a ``P`` format Line (ours: the manual gives none; the same
#: figure as the shared URDF catalogue's).
CARTESIAN_SPEED = 1000.0
#: Samples of a blending motion searched for the start of its blend zone.
BLEND_SAMPLES = 200
#: Time step (s) of the differences that give a blend's hand-over velocity and acceleration.
BLEND_DT = 1e-4
#: Motions kept in ``Robot.history``.
HISTORY = 64
#: Blend into a path (``_blend_within_limits``): start candidates tried, samples of the overlap
#: checked per candidate, and the share of the joint speeds the sum may use where it is faster
#: than either motion alone (the samples are discrete: a margin for the moments between them).
BLEND_START_STEPS = 8
BLEND_CHECK_SAMPLES = 48
BLEND_LIMIT_SAFETY = 0.98
#: Steps of the grid each motion's joint rates are sampled on for that check.
BLEND_GRID = 24
#: Queue tags that are remembered (TMSTA 01 answers for the last 4, manual L17930).
TAGS_KEPT = 4


def start_thread(sched: Scheduler, name: str, body: Callable[[], None]) -> None:
    """Run ``body`` as a thread of ``sched`` (the robot's executor, the servers' loops, the
    Listen node's scripts, ``ThreadRun``): as a GPL thread, it ends by handing the token on
    (``finish``); an Abort (the session closing) ends it quietly."""
    ctx = sched.new_ctx(name)

    def run() -> None:
        try:
            body()
        except ThreadAbort:
            pass
        finally:
            sched.finish(ctx)
    sched.spawn(ctx, run)


@dataclass
class Command:
    """One queued item: ``kind`` is ``move``, ``tag``, ``call`` (base/TCP/load/IO)."""

    kind: str
    run: Callable[[], None] | None = None
    tag: int = 0
    #: ``plan(start, v0, a0)`` -> (duration, joints at t, end joints); ``v0``/``a0`` (deg/s,
    #: deg/s²) are given only to a motion that ``from_motion`` (a blend hands over to it moving).
    plan: Callable[..., tuple[float, Callable[[float], list[float]], list[float]]] | None = None
    #: Blending into the next motion (L15747, L15990): ``("P", percent)`` or ``("R", mm)``.
    blend: tuple[str, float] | None = None
    #: Whether it can start from a moving state (a joint-interpolated PTP, planned by Ruckig from
    #: the full state); a path motion starts at rest, so a blend into one is not made.
    from_motion: bool = False
    #: (file, line) of the frames that queued a motion, innermost first: the script line named
    #: when it fails (``Robot.fault``).
    origin: tuple[tuple[str, int], ...] = ()


@dataclass
class Motion:
    """The motion being executed: started at controller time ``t0``, lasting ``duration``."""

    t0: float
    duration: float
    at: Callable[[float], list[float]]
    end: list[float]


@dataclass
class Robot:
    """The simulated TM robot: joints, frames, load, I/O tables and the motion queue."""

    arm: TMArm
    #: The session whose scheduler and clock the robot runs on (default: the ``fast`` clock).
    sim: Simulation = field(default_factory=lambda: Simulation(clock="fast"))
    joints: list[float] = field(default_factory=lambda: [0.0, 0.0, 90.0, 0.0, 90.0, 0.0])
    base: pin.SE3 = field(default_factory=pin.SE3.Identity)
    base_name: str = "RobotBase"
    tcp: pin.SE3 = field(default_factory=pin.SE3.Identity)
    tcp_name: str = "NOTOOL"
    #: The base and TCP the script's next motions will use: set when ChangeBase/ChangeTCP is
    #: called (their frames change when the queue reaches them); what a TPoint declared with
    #: the name "" is recorded in ("by the current base1", L14978).
    script_base_name: str = "RobotBase"
    script_tcp_name: str = "NOTOOL"
    load: float = 0.0
    tool_mass: float = 0.0
    sim_time: float = 0.0  # seconds of motion executed (controller time spent moving)
    error_code: int = 0
    paused: bool = False
    project_running: bool = True
    on_tag: Callable[[int], None] | None = None
    #: Called (on the executor's thread) when a motion fails and the project stops by error.
    on_error: Callable[[TMError], None] | None = None

    def __post_init__(self) -> None:
        self.queue: deque[Command] = deque()
        #: Guards the state; never waited on (waits go through the scheduler: ``changed``).
        self.lock = threading.RLock()
        self.sched = self.sim.scheduler
        self.clock = self.sched.clock
        #: Notified whenever the queue, a motion, a tag, pause or stop changes.
        self.changed = WaitQueue("tm-robot")
        self.motion: Motion | None = None
        #: The last motions run, as they were set (a blend's merged motion after the one it cut
        #: short): ``trajectory(t)`` reads where the robot was at controller time ``t``.
        self.history: deque[Motion] = deque(maxlen=HISTORY)
        #: The simulated TMmanager ``VarSync`` sends to (``gplrt.tm.manager``).
        self.manager = TMManager()
        #: The vision backend the user fills (``gplrt.tm.vision``): jobs, outputs, images.
        self.vision = Vision()
        self.vision.on_change = self._notify
        self.tags: dict[int, bool] = {}  # tag -> done, the last TAGS_KEPT in order
        self.ctrl_do = [0] * 16
        self.ctrl_di = [0] * 16
        self.ctrl_ao = [0.0] * 2
        self.ctrl_ai = [0.0] * 2
        self.end_do = [0] * 4
        self.end_di = [0] * 3
        self.end_ao = [0.0]
        self.end_ai = [0.0]
        self.busy = False
        self.stopped = False
        #: Servers serving the robot (the Listen node, the Ethernet Slave): ``drive``/``undrive``.
        self.servers = 0
        #: (joints, velocities, accelerations) a blended motion hands over to the next one.
        self._handoff: tuple[list[float], list[float], list[float]] | None = None
        #: The error that stopped the project (a motion that could not start), until ``restart``.
        self.fault: TMError | None = None
        start_thread(self.sched, "tm-motion", self._execute)

    def close(self) -> None:
        """End the robot's session: its executor and threads (``use_robot`` closes the robot it
        replaces, unless a server still serves it)."""
        self.servers = 0
        self.close_devices()  # (the serial ports, sockets and Modbus links the scripts left open)
        self.sim.close(grace=1.0)

    def close_devices(self) -> None:
        """The project stops: every device its scripts declared closes and is forgotten (L12494;
        the tables are ``gplrt.tm.devices``': kind -> name -> device)."""
        for table in getattr(self, "_devices", {}).values():
            for dev in list(table.values()):
                try:
                    dev.close()
                except Exception:  # (one device failing to close does not keep the others open)
                    pass
            table.clear()

    def drive(self) -> None:
        """A server (the Listen node, the Ethernet Slave) starts serving: keep the robot's
        session driven while any does.  Virtual time moves only while someone outside waits on
        the run (``Scheduler.drivers``, as ``gpl2py run`` does for GPL's servers); clients over
        sockets are that someone.  ``undrive`` when the server closes."""
        self.servers += 1
        if self.servers > 1:
            return

        def driver() -> None:
            while self.servers > 0:
                t0 = time.monotonic()
                self.sched.wait_until_quiet(None, 0.5)
                if time.monotonic() - t0 < 0.05:  # (stalled: nothing runs until a client comes)
                    time.sleep(0.05)
        threading.Thread(target=driver, name="tm-driver", daemon=True).start()

    def undrive(self) -> None:
        """A server closed (the driver ends with the last)."""
        self.servers = max(0, self.servers - 1)

    @property
    def speed(self) -> float:
        """Controller seconds per wall second of a real clock (``math.inf`` on a virtual one)."""
        return float(getattr(self.clock, "speed", math.inf))

    def _notify(self) -> None:
        self.sched.notify_all(self.changed)

    def _horizon(self) -> float:
        """When the motion in progress ends (``math.inf``: none in progress)."""
        m = self.motion
        return math.inf if m is None else m.t0 + m.duration

    def _wait_for(self, done: Callable[[], bool], deadline: float | None,
                  cancelled: Callable[[], bool] = lambda: False, fault: bool = True) -> bool:
        """Wait for the controller until ``done()`` (True), or until controller time ``deadline``
        or ``cancelled()`` (False); the fault that stops the project is raised (if ``fault``).  The wait is a
        ``controller_wait`` to the end of the motion in progress, renewed as each one starts: on
        the ``fast`` clock a waited motion takes no wall time (docs/design/clock.md)."""
        with self.sched.adopted():
            while True:
                with self.lock:
                    if fault:
                        self._raise_fault()
                    if done():
                        return True
                if cancelled() or (deadline is not None and self.clock.reached(deadline)):
                    return False
                with controller_wait(self._horizon()):
                    self.sched.wait(self.changed, deadline)

    # --- state ----------------------------------------------------------------------------------
    def _elapsed(self, m: Motion) -> float:
        return min(m.duration, max(0.0, self.clock.now() - m.t0))

    def trajectory(self, t: float) -> list[float] | None:
        """Where the robot was (or will be) at controller time ``t`` by the motions in ``history``:
        the last one started by ``t``; None before the first.  (A blend's merged motion replaces the
        motion it cut from its own start on.)"""
        with self.lock:
            found = None
            for m in self.history:
                if m.t0 <= t + 1e-12:
                    found = m
            return None if found is None else found.at(min(found.duration, t - found.t0))

    def current_joints(self) -> list[float]:
        with self.lock:
            m = self.motion
            if m is None:
                return list(self.joints)
            return m.at(self._elapsed(m))

    def flange(self) -> list[float]:
        """The flange pose in RobotBase (mm, deg)."""
        return self.arm.fk(self.current_joints())

    def tool(self) -> list[float]:
        """The TCP in RobotBase (``Robot[0].CoordRobot``, L14714)."""
        return se3_to_pose(self.arm.fk_se3(self.current_joints()) * self.tcp)

    def tool_in_base(self) -> list[float]:
        """The TCP in the current base (``Robot[0].CoordBase``)."""
        return se3_to_pose(self.base.inverse() * self.arm.fk_se3(self.current_joints()) * self.tcp)

    def joint_speeds(self) -> list[float]:
        with self.lock:
            m = self.motion
            if m is None:
                return [0.0] * 6
            t = self._elapsed(m)
            dt = 1e-3
            a, b = m.at(max(0.0, t - dt)), m.at(min(m.duration, t + dt))
            return [(y - x) / (2 * dt) for x, y in zip(a, b)]

    # --- queue ----------------------------------------------------------------------------------
    def enqueue(self, cmd: Command) -> bool:
        if cmd.kind == "move":
            cmd.origin = _origin(sys._getframe(1))
        with self.lock:
            self._raise_fault()
            if cmd.kind == "tag":
                self.tags[cmd.tag] = False
                self.tags.pop(cmd.tag)
                self.tags[cmd.tag] = False
                while len(self.tags) > TAGS_KEPT:
                    self.tags.pop(next(iter(self.tags)))
            self.queue.append(cmd)
        self._notify()
        return True

    def _raise_fault(self) -> None:
        """The project has stopped by error: the script that goes on talking to the robot stops
        with that error (called with the lock held)."""
        if self.fault is not None:
            err = TMError(str(self.fault))
            err.where = self.fault.where
            raise err

    def check_fault(self) -> None:
        """TMError if a motion has stopped the project (``run_project`` after ``main``)."""
        with self.lock:
            self._raise_fault()

    def acknowledge_fault(self) -> None:
        """The project has been stopped by its error: ``errorstop`` may queue I/O again (L1097);
        ``Error_Code`` stays until ``restart``."""
        with self.lock:
            self.fault = None

    def restart(self) -> None:
        """The error is cleared and the project runs again (a Listen node entered anew)."""
        with self.lock:
            self.fault = None
            self.error_code = 0
            self.project_running = True

    def pause(self, paused: bool) -> None:
        """``Pause()`` / ``Resume()``: no queued command starts while paused."""
        with self.lock:
            self.paused = paused
        self._notify()

    def tag_status(self, tag: int) -> bool | None:
        with self.lock:
            return self.tags.get(tag)

    def wait_tag(self, tag: int, timeout_ms: float = -1, cancelled: Callable[[], bool] = lambda: False) -> int:
        """1 when ``tag`` is done, 0 at the timeout, -1 for a tag not among the last four (L15562)."""
        deadline = None if timeout_ms < 0 else self.clock.now() + timeout_ms / 1000.0
        with self.lock:
            if tag not in self.tags:
                return -1 if tag != 0 else 0
        done = self._wait_for(lambda: self.tags.get(tag, True), deadline, cancelled)
        with self.lock:
            if tag not in self.tags:  # (cleared by StopAndClearBuffer while waited for)
                return 0
            return 1 if done and self.tags[tag] else 0

    def run_queued(self, work: Callable[[], object], cancelled: Callable[[], bool] = lambda: False) -> tuple[bool, object]:
        """Queue ``work`` after what is queued (a vision job after its move, L17262), wait for it
        as for a queue tag: (True, what it returned), or (False, None) when it never ran (the
        queue cleared by ``StopAndClearBuffer``, the wait cancelled)."""
        box: list[object] = []

        def run() -> None:
            box.append(work())
        cmd = Command("call", run=run)
        self.enqueue(cmd)
        done = self._wait_for(lambda: bool(box) or (not any(c is cmd for c in self.queue) and not self.busy),
                              None, cancelled)
        return (True, box[0]) if done and box else (False, None)

    def idle(self) -> bool:
        with self.lock:
            return not self.queue and not self.busy

    def wait_idle(self, cancelled: Callable[[], bool] = lambda: False) -> None:
        self._wait_for(lambda: not self.queue and not self.busy, None, cancelled, fault=False)

    def stop_and_clear(self) -> None:
        """Stop at once and drop what is queued (``StopAndClearBuffer``, L15683); the robot stays
        where the stop caught it."""
        with self.lock:
            self.queue.clear()
            self.script_base_name, self.script_tcp_name = self.base_name, self.tcp_name  # (their changes dropped)
            for tag in [t for t, done in self.tags.items() if not done]:
                del self.tags[tag]  # (cleared with the queue: never reported, L18243)
            if self.motion is not None:
                self.stopped = True
            self._handoff = None
        self._notify()
        with self.sched.adopted():
            while self.busy:
                self.sched.wait(self.changed, None, until=lambda: not self.busy)
        with self.lock:
            self.stopped = False

    # --- the executor ---------------------------------------------------------------------------
    def _execute(self) -> None:
        """The executor, a thread of the robot's scheduler: runs the queue in order."""
        ready = lambda: bool(self.queue) and not self.paused  # noqa: E731
        while True:
            while not ready():
                self.sched.wait(self.changed, None, until=ready)
            with self.lock:
                if not ready():
                    continue
                cmd = self.queue.popleft()
                self.busy = True
            try:
                self._run(cmd)
            except TMError as exc:
                self._stop_by_error(cmd, exc)
            finally:
                with self.lock:
                    self.busy = False
                self._notify()

    def _stop_by_error(self, cmd: Command, exc: TMError) -> None:
        """A motion that cannot start (a Cartesian target out of reach, a joint beyond its limit)
        stops the project by error, as on the robot (L1095-L1148, L14427): the queue is cleared
        (its tags forgotten), ``Error_Code``/``Robot_Error`` are set and ``Project_Run`` is false;
        the script is stopped by this error at its next motion, wait or end."""
        exc.where = _where(cmd.origin)
        with self.lock:
            self.error_code = 1
            self.last_error = str(exc)
            self.fault = exc
            self.project_running = False
            self.queue.clear()
            for tag in [t for t, done in self.tags.items() if not done]:
                del self.tags[tag]
        self._notify()
        if self.on_error is not None:
            self.on_error(exc)

    def _run(self, cmd: Command) -> None:
        if cmd.kind == "tag":
            with self.lock:
                if cmd.tag in self.tags:
                    self.tags[cmd.tag] = True
            self._notify()
            if self.on_tag is not None:
                self.on_tag(cmd.tag)
            return
        if cmd.kind == "call":
            assert cmd.run is not None
            cmd.run()
            return
        assert cmd.plan is not None
        handoff, self._handoff = self._handoff, None
        if handoff is not None:
            start, v0, a0 = handoff
            duration, at, end = cmd.plan(start, v0, a0)
        else:
            start = list(self.joints)
            duration, at, end = cmd.plan(start)
        t0 = self.clock.now()
        blend = cmd.blend
        while True:
            with self.lock:
                self.motion = motion = Motion(t0, duration, at, end)
                self.history.append(motion)
            self._notify()  # the waiters renew their controller_wait to this motion's end
            cut = self._blend_start(blend, at, duration, start, end) if blend else None
            if cut is None or not self._wait_until(t0 + cut):
                break
            nxt = self._next_blendable()
            if nxt is None:
                break
            if nxt.from_motion:  # a PTP: planned by Ruckig from the state at the cut
                q, v, a = _state(at, cut, duration)
                with self.lock:
                    self.joints = q
                    self.sim_time += cut
                    self.motion = None
                    self._handoff = (q, v, a)
                return
            merged = self._superpose(nxt, t0, cut, duration, at, end)
            if merged is None:
                break
            t0, duration, at, start, end, blend = merged
        self._wait_until(t0 + duration)
        with self.lock:
            if not self.stopped:
                self.joints = list(end)
                self.sim_time += duration
            else:
                elapsed = self._elapsed(motion)
                self.joints = at(elapsed)
                self.sim_time += elapsed
            self.motion = None

    def _wait_until(self, t: float) -> bool:
        """Wait for controller time ``t``; False if a stop came first."""
        while not self.stopped and not self.clock.reached(t):
            self.sched.wait(self.changed, t, until=lambda: self.stopped)
        return not self.stopped

    def _superpose(self, nxt: Command, t0: float, cut: float, duration: float, at: Callable[[float], list[float]],
                   end: list[float]) -> tuple[float, float, Callable[[float], list[float]], list[float], list[float],
                                              tuple[str, float] | None] | None:
        """Blend into a path motion (``nxt``, taken off the queue): it is planned from rest at the
        current motion's target and starts at ``tb`` = the cut, but no earlier than its own
        duration before the current motion's end; until that end the two are added in joint space
        (the current motion's remaining way plus the path's progress), after it the robot is on the
        path exactly.  The core does the same in Cartesian space (``queue.BlendedPathSegment``).
        Returns the merged motion (t0, duration, at, start, end, its blend), or None when the path
        cannot be planned here (it then runs after the current motion, failing in its own name)."""
        with self.lock:
            if not self.queue or self.queue[0] is not nxt:
                return None
            self.queue.popleft()
        assert nxt.plan is not None
        try:
            d_b, at_b, end_b = nxt.plan(list(end))
        except TMError:
            with self.lock:
                self.queue.appendleft(nxt)
            return None
        tb = self._blend_within_limits(at, at_b, max(cut, duration - d_b), duration, d_b)
        if tb >= duration:  # no overlap keeps the joints within their speeds: run after it
            with self.lock:
                self.queue.appendleft(nxt)
            return None
        if not self._wait_until(t0 + tb):
            return None
        rest = duration - tb

        def merged(t: float, at_a: Callable[[float], list[float]] = at, a_end: list[float] = end) -> list[float]:
            q = at_b(t)
            if t >= rest:
                return q
            qa = at_a(tb + t)
            return [b + x - e for b, x, e in zip(q, qa, a_end)]
        with self.lock:
            self.sim_time += tb
            self.joints = merged(0.0)
        return t0 + tb, max(d_b, rest), merged, merged(0.0), end_b, nxt.blend

    def _blend_within_limits(self, at_a: Callable[[float], list[float]], at_b: Callable[[float], list[float]],
                             tb: float, duration: float, d_b: float) -> float:
        """The earliest start from ``tb`` on (s after the blending motion's start) at which the
        superposed motion keeps every joint within its speed (the URDF's, 100 %; where the sum is
        faster than either motion alone, within ``BLEND_LIMIT_SAFETY`` of it); ``duration`` (no
        overlap) if none does.  In joint space the blended rate is exactly the sum of the two
        motions' rates, so a path that moves a joint the same way the blending motion still
        drives it can ask for up to twice its speed: a real robot does not exceed its joint
        speeds, and the manual names no error for a blend (L15747, L15990), so the overlap is
        shortened (the robot passes closer to the via point), as the core does for GPL
        (``gplrt.motion.robot._blend_within_limits``).  Candidates close in on the end
        geometrically; each is checked at ``BLEND_CHECK_SAMPLES`` moments of its overlap.  Each
        motion's rates are sampled once on a grid of ``BLEND_GRID`` steps (a path's joints cost an
        inverse kinematics each) and interpolated for the candidates."""
        limit = np.array(self.arm.speed) * BLEND_LIMIT_SAFETY
        span = duration - tb
        if span <= 0:
            return duration
        ta, va = _grid_rates(at_a, tb, duration)
        tp, vp = _grid_rates(at_b, 0.0, min(d_b, span))
        for k in range(BLEND_START_STEPS):
            start = duration - span * 0.5 ** k
            ts = np.linspace(start, duration, BLEND_CHECK_SAMPLES)
            a = np.stack([np.interp(ts, ta, va[:, j]) for j in range(va.shape[1])], axis=1)
            b = np.stack([np.interp(ts - start, tp, vp[:, j], right=0.0) for j in range(vp.shape[1])], axis=1)
            if not np.any(np.abs(a + b) > np.maximum(limit, np.maximum(np.abs(a), np.abs(b)))):
                return start
        return duration

    def _next_blendable(self) -> Command | None:
        """The motion a blend hands over to: the next command, if it is a motion queued before
        the blend zone is reached (as the core's ``InRange < 0``) and the robot is not paused."""
        with self.lock:
            if not self.paused and self.queue and self.queue[0].kind == "move":
                return self.queue[0]
            return None

    def _blend_start(self, blend: tuple[str, float], at: Callable[[float], list[float]], duration: float,
                     start: list[float], end: list[float]) -> float | None:
        """When (s after its start) a blending motion may hand over to the next one: the first
        sampled moment the TCP is within ``R`` mm of the target, or (``P``) the joints have
        ``percent`` % of their way left, but never before half the motion (so 100 % still moves
        half-way); None for no blend."""
        kind, value = blend
        if value <= 0 or duration <= 0:
            return None
        n = BLEND_SAMPLES
        if kind == "R":
            goal = (self.arm.fk_se3(end) * self.tcp).translation
            def left(q: list[float]) -> float:
                return float(np.linalg.norm((self.arm.fk_se3(q) * self.tcp).translation - goal)) * 1000.0
            zone = value
        else:
            span = max(abs(b - a) for a, b in zip(start, end)) or 1.0
            def left(q: list[float]) -> float:
                return max(abs(b - a) for a, b in zip(q, end)) / span * 100.0
            zone = min(100.0, value)
        for i in range(n // 2, n):
            t = duration * i / n
            if left(at(t)) <= zone:
                return t
        return None

    # --- motions (the planning, run when a motion starts) ---------------------------------------
    def limits(self, speed_pct: float, accel_ms: float) -> AxisLimits:
        pct = max(1.0, min(100.0, float(speed_pct))) / 100.0
        vel = [s * pct for s in self.arm.speed]
        t = max(float(accel_ms), 1.0) / 1000.0
        acc = [v / t for v in vel]
        jerk = [a / 0.05 for a in acc]
        return AxisLimits(vel, acc, acc, jerk)

    def joint_move(self, target: list[float], speed_pct: float, accel_ms: float) -> Command:
        self._check_joints(target)
        lim = self.limits(speed_pct, accel_ms)

        def plan(start: list[float], v0: list[float] | None = None,
                 a0: list[float] | None = None) -> tuple[float, Callable[[float], list[float]], list[float]]:
            p = plan_axes(start, v0, a0, [float(x) for x in target], lim)
            return p.duration, (lambda t: [float(x) for x in p.at(t)[0]]), list(target)
        return Command("move", plan=plan, from_motion=True)

    def _check_joints(self, target: list[float]) -> None:
        for i, (q, lo, hi) in enumerate(zip(target, self.arm.lower, self.arm.upper)):
            if not lo - 1e-9 <= q <= hi + 1e-9:
                raise TMError(f"joint {i + 1} target {q:g} is beyond its limits [{lo:g}, {hi:g}]")

    def cartesian_target(self, pose: list[float]) -> pin.SE3:
        """The flange transform for a TCP ``pose`` given in the current base."""
        return self.base * pose_to_se3(pose) * self.tcp.inverse()

    def ptp_pose(self, pose: list[float], speed_pct: float, accel_ms: float,
                 config: list[int] | None = None) -> Command:
        """A PTP to a TCP pose in the base and with the TCP in effect when it starts: base and TCP
        changes are queued with the motions (L16706, L16814); ``config`` TM's pose configuration
        triplet (L17206), else the branch the robot is in."""
        lim = self.limits(speed_pct, accel_ms)

        def plan(start: list[float], v0: list[float] | None = None,
                 a0: list[float] | None = None) -> tuple[float, Callable[[float], list[float]], list[float]]:
            end = self.arm.ik_se3(self.cartesian_target(pose), start, config)
            p = plan_axes(start, v0, a0, end, lim)
            return p.duration, (lambda t: [float(x) for x in p.at(t)[0]]), end
        return Command("move", plan=plan, from_motion=True)

    def path_move(self, path: Callable[[pin.SE3], Callable[[float], pin.SE3]], speed_mm_s: float,
                  accel_ms: float) -> Command:
        """A Cartesian path: ``path(start)`` gives the flange transform at s in [0, 1]."""
        def plan(start: list[float]) -> tuple[float, Callable[[float], list[float]], list[float]]:
            begin = self.arm.fk_se3(start)
            f = path(begin)
            length = _path_length(f)
            v = max(1e-3, float(speed_mm_s))
            a = v / max(float(accel_ms), 1.0) * 1000.0
            end = self.arm.ik_se3(f(1.0), start)
            if length < 1e-9:
                return 0.0, (lambda t: list(end)), end
            p = plan_scalar(0.0, 0.0, 0.0, length, v, a, a, a / 0.05)
            seed = [list(start)]

            def at(t: float) -> list[float]:
                s = float(p.at(t)[0][0]) / length
                q = self.arm.ik_se3(f(min(1.0, max(0.0, s))), seed[0])
                seed[0] = q
                return q
            return p.duration, at, end
        return Command("move", plan=plan)


def _state(at: Callable[[float], list[float]], t: float, duration: float) -> tuple[list[float], list[float], list[float]]:
    """Joints, velocities and accelerations of a plan at ``t`` (central differences, as the
    core's blend, ``queue._BLEND_DT``)."""
    h = BLEND_DT
    q = at(t)
    before, after = at(max(0.0, t - h)), at(min(duration, t + h))
    v = [(b - a) / (2 * h) for a, b in zip(before, after)]
    acc = [(b - 2 * m + a) / (h * h) for a, m, b in zip(before, q, after)]
    return q, v, acc


def _grid_rates(f: Callable[[float], list[float]], lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """Joint rates of ``f`` on [lo, hi]: the moments (the grid's midpoints, and both ends) and
    the rates there, by differences between ``BLEND_GRID`` + 1 points."""
    ts = np.linspace(lo, hi, BLEND_GRID + 1)
    q = np.array([f(float(t)) for t in ts])
    v = np.diff(q, axis=0) / max(1e-12, (hi - lo) / BLEND_GRID)
    mids = (ts[:-1] + ts[1:]) / 2
    return np.concatenate(([lo], mids, [hi])), np.vstack((v[:1], v, v[-1:]))


def _origin(frame: object, depth: int = 8) -> tuple[tuple[str, int], ...]:
    """(file, line) of ``frame`` and its callers (a few: the script's line is near)."""
    out = []
    f = frame
    while f is not None and len(out) < depth:
        out.append((f.f_code.co_filename, f.f_lineno))
        f = f.f_back
    return tuple(out)


def _where(origin: tuple[tuple[str, int], ...]) -> str | None:
    """``"file.tms:line"`` of the innermost transpiled frame of ``origin`` (the source map)."""
    for file, line in origin:
        found = gpl_line_of(file, line)
        if found is not None:
            return f"{found[0]}:{found[1]}"
    return None


def _path_length(f: Callable[[float], pin.SE3], n: int = 32) -> float:
    """Length (mm) of a path, its rotation counted as 1 mm per degree where it turns more than it moves."""
    pts = [f(i / n) for i in range(n + 1)]
    lin = sum(float(np.linalg.norm(b.translation - a.translation)) for a, b in zip(pts, pts[1:])) * 1000.0
    rot = math.degrees(float(np.linalg.norm(pin.log3(pts[0].rotation.T @ pts[-1].rotation))))
    return max(lin, rot)


def line_path(goal: pin.SE3 | Callable[[], pin.SE3]) -> Callable[[pin.SE3], Callable[[float], pin.SE3]]:
    """A straight line to ``goal`` (or to what ``goal()`` gives when the motion starts: a pose in
    the base then in effect), orientation interpolated on the shortest rotation."""
    def path(start: pin.SE3) -> Callable[[float], pin.SE3]:
        target = goal() if callable(goal) else goal

        def at(s: float) -> pin.SE3:
            if s >= 1.0:
                return target
            return pin.SE3.Interpolate(start, target, s) if hasattr(pin.SE3, "Interpolate") else _interp(start, target, s)
        return at
    return path


def _interp(a: pin.SE3, b: pin.SE3, s: float) -> pin.SE3:
    rot = a.rotation @ pin.exp3(s * pin.log3(a.rotation.T @ b.rotation))
    return pin.SE3(rot, a.translation + s * (b.translation - a.translation))


def arc_path(points: Callable[[], tuple[pin.SE3, pin.SE3]], arc_deg: float) -> Callable[[pin.SE3], Callable[[float], pin.SE3]]:
    """A circular arc from the start through ``via`` to ``end`` (``points()`` when the motion
    starts, ``arc_deg`` = 0); with ``arc_deg`` ≠ 0, that many degrees along the same circle at
    constant orientation (L16114)."""
    def path(start: pin.SE3) -> Callable[[float], pin.SE3]:
        via, end = points()
        p0, p1, p2 = start.translation, via.translation, end.translation
        centre, normal, radius = _circle(p0, p1, p2)
        u = (p0 - centre) / radius
        w = np.cross(normal, u)

        def angle_of(p: np.ndarray) -> float:
            d = p - centre
            a = math.atan2(float(d @ w), float(d @ u))
            return a if a >= 0 else a + 2 * math.pi
        sweep = angle_of(p2) if arc_deg == 0 else math.radians(abs(arc_deg))
        if arc_deg < 0:
            w = -w

        def at(s: float) -> pin.SE3:
            if arc_deg == 0 and s >= 1.0:
                return end
            th = sweep * s
            p = centre + radius * (math.cos(th) * u + math.sin(th) * w)
            rot = start.rotation if arc_deg != 0 else _interp(start, end, s).rotation
            return pin.SE3(rot, p)
        return at
    return path


def _circle(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    nn = float(n @ n)
    if nn < 1e-18:
        raise TMError("the three points of the circle are on one line")
    centre = a + (np.cross(n, ab) * float(ac @ ac) + np.cross(ac, n) * float(ab @ ab)) / (2 * nn)
    return centre, n / math.sqrt(nn), float(np.linalg.norm(a - centre))
