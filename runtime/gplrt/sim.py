"""The simulation session: one simulated controller that GPL code (generated or hand-written) runs on.

A notebook, a test or ``python -m out.project`` makes a :class:`Simulation` (or lets
:func:`current` make a default one) and chooses:

* the clock — ``clock="virtual"`` (default: deterministic, waits cost no wall time; paced to
  real time while a socket is open), ``clock="fast"`` (virtual, and a client that waits for a
  motion, homing or power-up does not wait for it in wall time: docs/design/clock.md) or
  ``clock="real"`` with a ``speed`` factor (servers talking to real clients);
* the I/O map (``io``: digital/analog signals, scripted input rules, output trace);
* the console sink (``console``: stdout, or ``capture=True`` to collect the text);
* the flash root (``flash_root``: folder standing in for ``/flash``);
* where the program's servers may listen (``listen``: loopback unless the user names an address of
  this computer or ``"0.0.0.0"``; ``gplrt.io.sockets`` and docs/security.md say what each means);
* the robot (``robot="PF400SX"``: any name of ``gplrt.controller.pdb.model_names()``; its shipped
  parameter database is loaded into ``pdb`` on first motion use unless ``pdb`` was set), the
  robots registry (``robots``: ``gplrt.motion.robot.RobotState`` per robot number, built on first
  use) and the parameter database (``pdb``; ``Controller.PDb`` reads it);
* ``trace(robot)``: the sampled motion of a robot (``gplrt.motion.trace``).

Program lifetime (decision; D0:1493 and D0 §17): a thread ends when its top-level procedure
returns, and the other threads keep running — the main procedure (ProjectStart) returning does not
stop the threads it started.  :meth:`Simulation.run_main` therefore returns when *every* GPL
thread has ended, or, in virtual mode, when the program has stalled (all remaining threads wait
for something no GPL thread or timer can ever provide — on a controller they would wait forever).
"""

from __future__ import annotations

import atexit
import numbers
import io as _io
import sys
import threading
import weakref
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Literal, TextIO

from gplrt.controller.clock import RealClock, VirtualClock
from gplrt.threads.scheduler import RealScheduler, Scheduler, VirtualScheduler, current_ctx

#: The clocks a Simulation can run on (``gpl2py run --clock``): the two virtual ones, then the real one.
CLOCKS = ("virtual", "fast", "real")


def _seconds(value: Any, what: str) -> Any:
    """A duration argument of the Python API (``run_for``, ``timeout=``): None or a finite number
    >= 0, else a ValueError that names it.  (Python callers get Python's error for a Python
    argument; a NaN or a string would otherwise fail deep inside the scheduler.)"""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not 0 <= value < float("inf"):
        raise ValueError(f"{what} must be a finite number of seconds >= 0, not {value!r}")
    return value


class SimulationStalled(RuntimeError):
    """``Simulation.call`` cannot finish: every GPL thread waits for something that never comes.

    This is a fault of the *session* (a notebook waiting on a deadlocked program), not a GPL error,
    so it is a Python exception rather than a GplException.
    """


class ConsoleSink:
    """Where the program's console output and the controller's log lines go.

    ``write`` carries program output (``Console.WriteLine``); ``log`` carries controller reports
    (unhandled thread errors, system messages).  With ``capture=True`` both are kept in memory
    (``output``, ``log_text``) instead of being printed — tests compare them byte for byte.
    """

    def __init__(self, capture: bool = False, stream: TextIO | None = None, log_stream: TextIO | None = None) -> None:
        self.capture = capture
        self._out: TextIO = _io.StringIO() if capture else (stream or sys.stdout)
        self._log: TextIO = _io.StringIO() if capture else (log_stream or sys.stderr)
        self._lock = threading.Lock()
        #: Set when a stream was closed by its reader (``gpl2py run | head``): the console output
        #: is then dropped, never an error of the GPL program that wrote it, and ``gpl2py run``
        #: ends the run quietly.
        self.closed = threading.Event()

    def write(self, text: str) -> None:
        self._put(self._out, text)

    def log(self, line: str) -> None:
        self._put(self._log, line + "\n")

    def _put(self, stream: TextIO, text: str) -> None:
        with self._lock:
            if self.closed.is_set():
                return
            try:
                stream.write(text)
                if not self.capture:
                    stream.flush()
            except (BrokenPipeError, ValueError):  # the reader went away / the stream was closed
                self.closed.set()

    @property
    def output(self) -> str:
        return self._out.getvalue() if isinstance(self._out, _io.StringIO) else ""

    @property
    def log_text(self) -> str:
        return self._log.getvalue() if isinstance(self._log, _io.StringIO) else ""


@dataclass(frozen=True)
class StopReport:
    """What :meth:`Simulation.stop` did: the threads it aborted, and those still running after it."""

    aborted: list[str]
    still_alive: list[str]


@dataclass
class LogEntry:
    """One line of the system-message log or of the error log."""

    time: float
    thread: str
    text: str
    code: int = 0


@dataclass
class ControllerState:
    """The controller's non-motion state (read by motion checks: power, speed, E-stop)."""

    power_state: int = 7  # off, waiting for the power request (gpl-dictionary §13.3)
    system_speed: float = 100.0  # until the parameter database loads: then its DataID 601
    system_speed_set: bool = False  # the program (or a test) set SystemSpeed itself
    soft_estop: bool = False
    record_button: bool = False
    tick: float = 0.001  # trajectory-generator period (gpl-classes §22.3 item 8)
    power_up_time: float = 0.3  # virtual seconds from the power request to "on"
    homings: int = 0  # Robot.Home calls in progress (they share PowerState 28, see Robot._home)
    power_before_homing: int = 0  # the power state the last of them restores
    time_of_day_origin: float = 1135641600.0  # Timer(0) at boot: 2024-01-01 UTC in s since 1988
    system_messages: list[LogEntry] = field(default_factory=list)
    error_log: list[LogEntry] = field(default_factory=list)
    dialog_handler: Callable[[list[str], str], int] | None = None
    dialog_answers: list[int] = field(default_factory=list)


class Simulation:
    """One simulated controller session (see module docstring)."""

    def __init__(
        self,
        *,
        clock: Literal["virtual", "fast", "real"] = "virtual",
        speed: float = 1.0,
        io: Any = None,
        console: ConsoleSink | None = None,
        capture: bool = False,
        flash_root: str | Path | None = None,
        project: str = "",
        max_threads: int = 32,
        slice_checkpoints: int = 1000,
        robot: str = "PF400SX",
        listen: str | None = None,
    ) -> None:
        from gplrt.io.sockets import LOOPBACK, listen_address

        # Checked first, before anything starts: a typo must not expose or break a run halfway.
        self.listen = listen_address(listen) if listen is not None else LOOPBACK
        self.scheduler: Scheduler
        if clock in CLOCKS[:2]:
            self.scheduler = VirtualScheduler(VirtualClock(), slice_checkpoints=slice_checkpoints,
                                              run_ahead=clock == "fast")
        elif clock == "real":
            self.scheduler = RealScheduler(RealClock(speed), slice_checkpoints=slice_checkpoints)
        else:
            raise ValueError(f"clock must be one of {', '.join(map(repr, CLOCKS))}, not {clock!r}")
        self.mode = clock
        self.scheduler.sim = self
        from gplrt.controller.signals import IoMap

        self.io: IoMap = io if io is not None else IoMap()
        self.io.bind(self)
        self.console = console if console is not None else ConsoleSink(capture=capture)
        self.flash_root = Path(flash_root) if flash_root is not None else None
        self.project = project
        #: The running project's folder on the flash disk (``install_project_files``), or None
        self.project_folder: str | None = None
        self.max_threads = max_threads
        self.controller = ControllerState()
        self.robots: dict[int, Any] = {}  # gplrt.motion.robot.RobotState, built on first use
        self.robot_model = robot  # shipped database loaded into ``pdb`` on first motion use
        self.pdb: Any = None
        self.thread_exit_hooks: list[Callable[[Any], None]] = []
        self.threads: list[Any] = []  # every GPL Thread object started in this session
        self._previous: Simulation | None = None
        _sessions.add(self)

    # -- activation --------------------------------------------------------------------------------

    def activate(self) -> Simulation:
        """Make this the session that ``current()`` returns, and send ``Console`` output to it.

        Also points the controller's file system (``/flash`` ...) at this session's flash root, and
        the network at this session's ``listen`` address (always: another session's opt-in to the
        network must not carry over to this one).
        """
        set_current(self)
        _install_console(self)
        from gplrt.io.flashroot import get_flash_root, set_flash_root, set_working_folder
        from gplrt.io.sockets import configure_network, network_config

        if network_config().listen != self.listen:
            configure_network(listen=self.listen)
        if self.flash_root is not None and get_flash_root().root != self.flash_root.resolve():
            set_flash_root(self.flash_root, clear_romdisk=False)
        set_working_folder(self.project_folder)  # relative file names: this session's project
        return self

    def __enter__(self) -> Simulation:
        self._previous = _state.sim
        self.activate()
        return self

    def __exit__(self, *exc: object) -> None:
        # With no session before, this one stays active: a notebook's later direct calls
        # (``Controller.Timer``) should see the session it just used, not a fresh default one.
        if self._previous is not None:
            set_current(self._previous)
            _install_console(self._previous)

    def install_project_files(self, files: dict[str, bytes] | str | Path, name: str | None = None) -> str | None:
        """Put the project's own files where the controller has them, ``/flash/projects/<name>/``
        (``name`` defaults to ``project``), and resolve relative file names there
        (``gplrt.io.project_files``: only regular files, never through a link).  ``files`` is
        a host project folder or a name -> bytes map.  Returns the controller folder, or None
        when ``name`` cannot be one."""
        from gplrt.io.project_files import install_project, read_project_files

        data = files if isinstance(files, dict) else read_project_files(files)
        self.activate()
        self.project_folder = install_project(data, name if name is not None else self.project)
        self.activate()
        return self.project_folder

    # -- time ------------------------------------------------------------------------------------

    def now(self) -> float:
        return float(self.scheduler.clock.now())

    # -- running GPL code ----------------------------------------------------------------------------

    def run_main(self, proc: Callable[[], Any] | str, *, name: str | None = None, timeout: float | None = None) -> list[str]:
        """Run ``proc`` as the main GPL thread (ProjectStart) and wait for the program to end.

        Returns the names of threads still alive when it returned (empty when all ended; in
        virtual mode non-empty means the program stalled; ``timeout`` is in real seconds).
        """
        from gplrt.threads.thread import Thread

        timeout = _seconds(timeout, "timeout")  # (before anything starts)
        with self:
            main = Thread(proc, 0, name or "", _sim=self)
            main.Start()
            self.scheduler.wait_until_quiet(None, timeout)
            alive = [c.name for c in list(self.scheduler.live) if c.phase != "done"]
            if alive:
                self.console.log(f"Program stalled; threads still waiting: {', '.join(alive)}")
            return alive

    def call(self, proc: Callable[..., Any] | str, *args: Any, timeout: float | None = None) -> Any:
        """Call a GPL procedure from outside (a notebook) as a GPL thread under the scheduler.

        Returns its result; a GPL exception it does not handle is raised here (not reported as an
        unhandled thread error, since the caller receives it).
        """
        from gplrt.threads.thread import Thread

        timeout = _seconds(timeout, "timeout")  # (before anything starts)
        with self:
            t = Thread(proc, 0, "", _sim=self, _args=args, _propagate=True)
            t.Start()
            ended = self.scheduler.wait_until_quiet([t._ctx], timeout)
            if not ended:
                raise SimulationStalled(f"{t.Name} did not finish: {'stalled' if timeout is None else 'timeout'}")
            if t._error is not None:
                raise t._error
            return t._result

    def start(self, proc: Callable[..., Any] | str, *args: Any, name: str = "") -> Any:
        """Start ``proc`` as a background GPL thread (e.g. a server) and return its Thread object."""
        from gplrt.threads.thread import Thread

        self.activate()
        t = Thread(proc, 0, name, _sim=self, _args=args)
        t.Start()
        return t

    def stop(self, grace: float = 2.0) -> StopReport:
        """Abort every live GPL thread and wait up to ``grace`` real seconds for them to end.

        Abort is cooperative (Python threads cannot be killed): a thread ends at its next
        scheduling point or checkpoint, running its ``Finally`` blocks; one blocked in Python code
        that never reaches one (a long computation outside the runtime) is reported in
        ``still_alive``.  An interrupt (Ctrl-C) while waiting ends the wait early, so a user who
        presses it twice is never stuck here.
        """
        sched = self.scheduler
        running = [ctx for ctx in list(sched.live) if ctx.phase != "done"]
        for ctx in running:
            sched.request_abort(ctx)
        try:
            sched.wait_until_quiet(None, grace)
        except KeyboardInterrupt:
            pass
        sched.release_timers()  # end the real-time timer thread unless an I/O rule still waits on it
        return StopReport([c.name for c in running], [c.name for c in running if c.phase != "done"])

    def close(self, grace: float = 2.0) -> StopReport:
        """End the session: stop its GPL threads (as :meth:`stop`) and release the robots' state.

        Why release: a session's robots hold their planned motion (Ruckig trajectories, the
        kinematic model), and the scheduler's real-time timer thread may still hold a pending
        callback (an I/O-rule action on the real clock) that refers back to this session; close
        drops those and ends that thread.  At interpreter exit such a timer is never collected, and everything reachable
        from it is reported by nanobind as "leaked" Ruckig objects on stderr — after a run that
        ended cleanly.  A closed session is done with: ``robots`` is emptied (a later
        ``Robot.Where`` would build a fresh robot at its ready position, not the old state).
        ``gpl2py run`` closes its session once everything about the run has been reported.
        """
        report = self.stop(grace)
        self.scheduler.release_timers(drop_pending=True)
        self.robots.clear()
        return report

    def run_for(self, seconds: float) -> None:
        """Let the session's GPL threads run for ``seconds`` of controller time, then return."""
        seconds = _seconds(seconds, "seconds")
        self.activate()
        self.scheduler.sleep(seconds)

    def as_gpl_thread(self) -> Any:
        """Context manager: run the ``with`` body on the calling Python thread as a GPL thread.

        While inside, the body holds the virtual scheduler's token: other GPL threads run only at
        its scheduling points (sleeps, waits, checkpoints).
        """
        self.activate()
        return self.scheduler.adopted()

    def trace(self, robot: int = 1, dt: float | None = None) -> Any:
        """Sampled joint and tool trajectories of ``robot`` (``gplrt.motion.trace.Trace``)."""
        from gplrt.motion.trace import trace

        return trace(self, robot, dt)

    def report(self, thread_name: str, text: str, code: int = 0) -> None:
        """Record a controller-level error (error log + console log)."""
        entry = LogEntry(self.now(), thread_name, text, code)
        self.controller.error_log.append(entry)
        self.console.log(f"[{entry.time:.6f}] thread {thread_name}: {text}")


def _install_blocking_hook() -> None:
    """Let every blocking I/O wait in ``gplrt.io`` release the scheduler (see io/_blocking.py).

    A GPL thread waiting on a socket must not hold the virtual scheduler's token, and must not count
    as waiting on virtual time; ``external_wait`` does both and is harmless outside GPL threads.
    While a socket is open, virtual time keeps to real time (``hold_real_time``).
    """
    from gplrt.io import _blocking
    from gplrt.threads.scheduler import external_wait, hold_real_time

    _blocking.set_blocking_hook(lambda timeout: external_wait())
    _blocking.set_open_hook(hold_real_time)


_install_blocking_hook()


def _route_console(text: str) -> None:
    """The Console sink every session installs: the calling GPL thread's own session gets the text.

    Console output belongs to a session, but ``gplrt.lang.console`` has one process-wide sink (the
    language runtime knows nothing of sessions).  Routing per call keeps two sessions that run side
    by side (a test's server in the background, a notebook's cell) from taking each other's output.
    Outside any GPL thread the active session gets it, and with no session the text goes to stdout.
    """
    ctx = current_ctx()
    sim = ctx.sched.sim if ctx is not None else _state.sim
    if sim is None:
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        sim.console.write(text)


def _install_console(sim: Simulation) -> None:
    """Route GPL ``Console`` output (gplrt.lang.console) into the sessions' console sinks."""
    try:
        from gplrt.lang.console import get_console_sink, set_console_sink
    except ImportError:  # the language runtime is not there: nothing to route
        return
    if get_console_sink() is not _route_console:
        set_console_sink(_route_console)


class _State:
    sim: Simulation | None = None


#: Every session not yet garbage-collected (see :func:`_release_robots_at_exit`).
_sessions: weakref.WeakSet[Simulation] = weakref.WeakSet()


@atexit.register
def _release_robots_at_exit() -> None:
    """Drop the motion state of sessions nobody closed, before the extension modules are torn down.

    A session can outlive its use: a notebook never closes it, a generated package keeps the one it
    was initialised for, a GPL thread left blocked keeps its frames.  Its robots hold Ruckig
    trajectories, and nanobind reports every one still alive when the ``ruckig`` module is
    finalised as "leaked" on stderr, after a run that ended cleanly.  Nothing can use a robot's
    planned motion after exit, so releasing it here is safe; :meth:`Simulation.close` does the same
    for a session that is done with earlier.
    """
    for sim in list(_sessions):
        sim.robots.clear()


_state = _State()
_create_lock = threading.Lock()


def current() -> Simulation:
    """The active simulation (a default virtual-clock one is created on first use).

    Code running on a GPL thread always gets the simulation that thread belongs to, so sessions
    made one after another (tests) never see each other's threads.
    """
    ctx = current_ctx()
    if ctx is not None:
        return ctx.sched.sim  # type: ignore[no-any-return]
    sim = _state.sim
    if sim is None:
        with _create_lock:
            if _state.sim is None:
                _state.sim = Simulation()
            sim = _state.sim
    return sim


def set_current(sim: Simulation | None) -> None:
    _state.sim = sim
