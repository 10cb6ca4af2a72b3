"""The simulation: composes a session (``gplrt.session.Session``) for a notebook, a test or ``python -m``.

:class:`Simulation` is the one place that builds a session's parts; everything else in the runtime
reads them through ``gplrt.session.current_session()``.  A notebook, a test or ``python -m
out.project`` makes a :class:`Simulation` (or lets :func:`current` make a default one) and chooses:

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
  parameter database is loaded into ``pdb`` on first use unless ``pdb`` was set), the robots
  (``robots``: ``gplrt.motion.robot.RobotState`` per robot number, built on first use) and the
  parameter database (``pdb``; ``Controller.PDb`` reads it);
* how much of the past it keeps (``history``: the motions each robot's history keeps, default
  ``gplrt.motion.queue.DEFAULT_HISTORY``; ``signal_history``: the signal changes of ``io.trace``,
  default ``gplrt.controller.signals.DEFAULT_SIGNAL_HISTORY``; None keeps everything, for a notebook
  that wants the whole run);
* ``trace(robot)``: the sampled motion of a robot (``gplrt.motion.trace``);
* the projects in the controller's memory (``projects``, ``gplrt.controller.projects``), which the
  console loads and starts (``Controller.Command``; ``gplrt.controller.telnet`` and
  ``gplrt.io.ftp`` serve the console and the disks to clients);
  ``compiler`` is what translates a project the console loads (``gpl2py run`` gives
  ``gpl2py.deploy.compile_project``: the runtime cannot translate GPL itself).

Two Simulations in one process are independent: each has its own clock, controller, robots,
database, I/O, disks, network, procedure registry and console, and a GPL thread only ever sees the
session it was started in.

Program lifetime (decision; D0:1493 and D0 §17): a thread ends when its top-level procedure
returns, and the other threads keep running — the main procedure (ProjectStart) returning does not
stop the threads it started.  :meth:`Simulation.run_main` therefore returns when *every* GPL
thread has ended, or, in virtual mode, when the program has stalled (all remaining threads wait
for something no GPL thread or timer can ever provide — on a controller they would wait forever).
"""

from __future__ import annotations

import atexit
import numbers
import sys
import weakref
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, ContextManager, Literal

from gplrt.controller import live_pdb
from gplrt.controller.clock import RealClock, VirtualClock
from gplrt.controller.console import ConsoleSink
from gplrt.controller.pdb import ParameterDatabase, default_database
from gplrt.controller.projects import Compiler, ProjectTable
from gplrt.controller.signals import DEFAULT_SIGNAL_HISTORY, IoMap
from gplrt.controller.state import ControllerState, LogEntry
from gplrt.io.flashroot import Disks
from gplrt.io.project_files import install_project, read_project_files
from gplrt.io.sockets import LOOPBACK, NetworkConfig, listen_address
from gplrt.lang.console import get_console_sink, set_console_sink
from gplrt.lang.procedures import default_registry
from gplrt.motion import registry
from gplrt.motion.queue import DEFAULT_HISTORY
from gplrt.motion.robot import RobotState
from gplrt.motion.trace import Trace, trace
from gplrt.session import (
    Session,
    active_session,
    check_window,
    current_session,
    session_of_caller,
    set_active_session,
    set_default_factory,
)
from gplrt.threads.scheduler import RealScheduler, Scheduler, ThreadCtx, VirtualScheduler
from gplrt.threads.thread import Thread

__all__ = [
    "CLOCKS", "ConsoleSink", "ControllerState", "LogEntry", "Simulation", "SimulationStalled", "StopReport",
    "current", "set_current",
]

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


@dataclass(frozen=True)
class StopReport:
    """What :meth:`Simulation.stop` did: the threads it aborted, and those still running after it."""

    aborted: list[str]
    still_alive: list[str]


class Simulation(Session):
    """One simulated controller session, composed here (see the module docstring)."""

    def __init__(
        self,
        *,
        clock: Literal["virtual", "fast", "real"] = "virtual",
        speed: float = 1.0,
        io: IoMap | None = None,
        console: ConsoleSink | None = None,
        capture: bool = False,
        flash_root: str | Path | None = None,
        project: str = "",
        max_threads: int = 32,
        slice_checkpoints: int = 1000,
        robot: str = "PF400SX",
        listen: str | None = None,
        history: int | None = DEFAULT_HISTORY,
        signal_history: int | None = DEFAULT_SIGNAL_HISTORY,
        compiler: Compiler | None = None,
    ) -> None:
        # Checked first, before anything starts: a typo must not expose or break a run halfway.
        network = NetworkConfig(listen=listen_address(listen) if listen is not None else LOOPBACK)
        check_window(history, "motions")
        check_window(signal_history, "signal changes")
        scheduler: Scheduler
        if clock in CLOCKS[:2]:
            scheduler = VirtualScheduler(VirtualClock(), slice_checkpoints=slice_checkpoints,
                                         run_ahead=clock == "fast")
        elif clock == "real":
            scheduler = RealScheduler(RealClock(speed), slice_checkpoints=slice_checkpoints)
        else:
            raise ValueError(f"clock must be one of {', '.join(map(repr, CLOCKS))}, not {clock!r}")
        super().__init__(
            scheduler=scheduler,
            controller=ControllerState(),
            io=io if io is not None else IoMap(),
            files=Disks(flash_root),
            network=network,
            procedures=default_registry(),  # until a generated package's init() gives its own
            console=console if console is not None else ConsoleSink(capture=capture),
            robot_model=robot,  # its shipped database is loaded into ``pdb`` on first use
            project=project,
            max_threads=max_threads,
            history=history,
        )
        self.mode = clock
        if io is None or signal_history != DEFAULT_SIGNAL_HISTORY:  # (a given IoMap keeps its own unless asked)
            self.io.trace_window = signal_history
        self.io.bind(self)
        self.flash_root = Path(flash_root) if flash_root is not None else None
        self.thread_exit_hooks.append(registry.release_on_exit)  # a thread's robots are freed as it ends
        self.projects: ProjectTable = ProjectTable(self, compiler)
        self._previous: Session | None = None
        _sessions.add(self)

    # -- the parts made on first use ----------------------------------------------------------------

    def _boot_database(self) -> ParameterDatabase:
        """``pdb``, or the robot model's shipped database, made the controller's: its live DataIDs
        installed and the robots' limits following its writes."""
        pdb = self.pdb
        if pdb is None:
            pdb = self.pdb = default_database(self.robot_model)
            if not self.controller.system_speed_set:
                # DataID 601 "System wide test speed in %" is the SystemSpeed a controller boots
                # with (robot-models.md §2.4: a real PF400 reports 50); a program's own setting wins.
                self.controller.system_speed = pdb.get_num(601, default=100.0)
        live_pdb.install(pdb)  # the controller's own DataIDs (power state, version, torques, ...)
        registry.listen(self, pdb)
        return pdb

    def _build_robot(self, number: int) -> RobotState:
        return registry.build_robot(self, number)

    # -- what it was made with ------------------------------------------------------------------------

    @property
    def listen(self) -> str:
        """Where the program's servers may listen (``gplrt.io.sockets``)."""
        return self.network.listen

    @property
    def project_folder(self) -> str | None:
        """The running project's folder on the flash disk (``install_project_files``), or None."""
        return self.files.working_folder

    # -- activation --------------------------------------------------------------------------------

    def activate(self) -> Simulation:
        """Make this the session that code outside GPL threads uses (``current()``), and route
        ``Console`` output to the sessions' consoles."""
        set_active_session(self)
        _install_console()
        return self

    def __enter__(self) -> Simulation:
        self._previous = active_session()
        self.activate()
        return self

    def __exit__(self, *exc: object) -> None:
        # With no session before, this one stays active: a notebook's later direct calls
        # (``Controller.Timer``) should see the session it just used, not a fresh default one.
        if self._previous is not None:
            set_active_session(self._previous)

    def install_project_files(self, files: dict[str, bytes] | str | Path, name: str | None = None) -> str | None:
        """Put the project's own files where the controller has them, ``/flash/projects/<name>/``
        (``name`` defaults to ``project``), and resolve relative file names there
        (``gplrt.io.project_files``: only regular files, never through a link).  ``files`` is
        a host project folder or a name -> bytes map.  Returns the controller folder, or None
        when ``name`` cannot be one.  The session becomes the active one."""
        data = files if isinstance(files, dict) else read_project_files(files)
        folder = install_project(data, name if name is not None else self.project, self.files)
        self.activate()
        return folder

    # -- running GPL code ----------------------------------------------------------------------------

    def run_main(self, proc: Callable[[], Any] | str, *, name: str | None = None, timeout: float | None = None) -> list[str]:
        """Run ``proc`` as the main GPL thread (ProjectStart) and wait for the program to end.

        Returns the names of threads still alive when it returned (empty when all ended; in
        virtual mode non-empty means the program stalled; ``timeout`` is in real seconds).
        """
        timeout = _seconds(timeout, "timeout")  # (before anything starts)
        with self:
            main = Thread(proc, 0, name or "", _session=self)
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
        timeout = _seconds(timeout, "timeout")  # (before anything starts)
        with self:
            t = Thread(proc, 0, "", _session=self, _args=args, _propagate=True)
            t.Start()
            assert t._ctx is not None
            ended = self.scheduler.wait_until_quiet([t._ctx], timeout)
            if not ended:
                raise SimulationStalled(f"{t.Name} did not finish: {'stalled' if timeout is None else 'timeout'}")
            if t._error is not None:
                raise t._error
            return t._result

    def start(self, proc: Callable[..., Any] | str, *args: Any, name: str = "") -> Thread:
        """Start ``proc`` as a background GPL thread (e.g. a server) and return its Thread object."""
        self.activate()
        t = Thread(proc, 0, name, _session=self, _args=args)
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
        for hook in list(self.stop_hooks):
            hook()
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
        self._release_motion()
        return report

    def _release_motion(self) -> None:
        """Let go of every robot's planned motion: the robots, and the frames of the threads'
        unhandled errors, which hold the robot the failing Move was using
        (``Thread.release_frames``).  The errors' codes and lines stay readable."""
        self.robots.clear()
        for thread in list(self.threads):
            thread.release_frames()

    def run_for(self, seconds: float) -> None:
        """Let the session's GPL threads run for ``seconds`` of controller time, then return."""
        seconds = _seconds(seconds, "seconds")
        self.activate()
        self.scheduler.sleep(seconds)

    def as_gpl_thread(self) -> ContextManager[ThreadCtx]:
        """Context manager: run the ``with`` body on the calling Python thread as a GPL thread.

        While inside, the body holds the virtual scheduler's token: other GPL threads run only at
        its scheduling points (sleeps, waits, checkpoints).
        """
        self.activate()
        return self.scheduler.adopted()

    def trace(self, robot: int = 1, dt: float | None = None) -> Trace:
        """Sampled joint and tool trajectories of ``robot`` (``gplrt.motion.trace.Trace``)."""
        return trace(self, robot, dt)


def _route_console(text: str) -> None:
    """The Console sink every session installs: the calling code's own session gets the text.

    Console output belongs to a session, but ``gplrt.lang.console`` has one process-wide sink (the
    language runtime knows nothing of sessions).  Routing per call keeps two sessions that run side
    by side (a test's server in the background, a notebook's cell) from taking each other's output.
    Outside any GPL thread the active session gets it, and with no session the text goes to stdout.
    """
    session = session_of_caller()
    if session is None:
        sys.stdout.write(text)
        sys.stdout.flush()
    else:
        session.console.write(text)


def _install_console() -> None:
    """Route GPL ``Console`` output (gplrt.lang.console) into the sessions' console sinks."""
    if get_console_sink() is not _route_console:
        set_console_sink(_route_console)


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
        sim._release_motion()


def current() -> Simulation:
    """The active simulation (``gplrt.session.current_session``: the calling GPL thread's own, else
    the active one, a default virtual-clock one made on first use).  Generated packages call it."""
    session = current_session()
    if not isinstance(session, Simulation):
        raise TypeError(f"the current session is a {type(session).__name__}, not a gplrt.sim.Simulation")
    return session


def set_current(sim: Simulation | None) -> None:
    """Make ``sim`` the active session (``gplrt.session.set_active_session``)."""
    set_active_session(sim)


set_default_factory(Simulation)
