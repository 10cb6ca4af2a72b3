"""The session: one simulated controller, and the one way every part of the runtime finds it.

A :class:`Session` holds everything a running GPL program reads and changes, each part typed:

==================  ===========================================================================
``scheduler``       who runs and how controller time moves (``gplrt.threads.scheduler``); its
                    ``clock`` is the controller's clock (virtual, fast or real)
``controller``      power, homing, system speed, the power sequencer, E-stop, the error and
                    system-message logs (``gplrt.controller.state.ControllerState``)
``pdb``             the parameter database with the controller's live DataIDs, booted on first
                    use by :meth:`database` (``gplrt.controller.pdb.ParameterDatabase``)
``robots``          robot number -> ``gplrt.motion.robot.RobotState`` (homed, attached, Tool,
                    Base, the motion queue), built on first use by :meth:`robot`
``selected``        the robot each thread has Selected (``Robot.Selected``)
``io``              digital and analog signals, their rules, latches and the change trace
                    (``gplrt.controller.signals.IoMap``)
``files``           the controller's disks: its flash root and the folder relative file names
                    resolve in (``gplrt.io.flashroot.Disks``)
``network``         where its servers listen, the connect time-out, its listening sockets
                    (``gplrt.io.sockets.NetworkConfig``)
``procedures``      the registry procedure names resolve in (``Thread("Module.Proc")``,
                    String delegates: ``gplrt.lang.procedures.ProcedureRegistry``)
``console``         program output and controller reports (``gplrt.controller.console.ConsoleSink``)
``threads``         every GPL ``Thread`` started in it, and the hooks run as each one ends
``projects``        the projects in its memory, loaded and started by the console
                    (``gplrt.controller.projects.ProjectTable``; ``Controller.Command``, Telnet)
``history``         how many motions each robot's history keeps (None: all; :attr:`history`)
==================  ===========================================================================

What happened in a session is kept by its parts: the motion each robot was given (its queue's
history, which ``Simulation.trace`` samples), every signal change (``io.trace``), the error log
and system messages (``controller``), the console text (``console``).  The motion history and the
signal trace keep a bounded window of the most recent entries (``history``, ``io.trace_window``),
so that a long run's memory does not grow with its length; what was dropped is counted
(``queue.dropped``, ``io.trace_dropped``, ``Trace.dropped``).

:func:`current_session` is how the runtime finds the session: code on a GPL thread gets the
session of that thread's scheduler, any other Python thread (a notebook, a test) the *active*
session (:func:`set_active_session`, ``with sim:``), made by the default factory on first use.
Two sessions in one process share nothing: each has its own parts, and a GPL thread only ever
sees its own.

This module is the bottom of the simulated controller: it imports only ``gplrt.thread_binding``
(which GPL thread is calling); the parts' modules import it, and ``gplrt.sim.Simulation``, the one
composer, builds the parts and hands them over.  The parts' types are imported for annotations
only.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING

from gplrt.thread_binding import current_ctx

if TYPE_CHECKING:
    from gplrt.controller.console import ConsoleSink
    from gplrt.controller.projects import ProjectTable
    from gplrt.controller.pdb import ParameterDatabase
    from gplrt.controller.signals import IoMap
    from gplrt.controller.state import ControllerState
    from gplrt.io.flashroot import Disks
    from gplrt.io.sockets import NetworkConfig
    from gplrt.lang.procedures import ProcedureRegistry
    from gplrt.motion.robot import RobotState
    from gplrt.threads.scheduler import Scheduler, ThreadKey
    from gplrt.threads.thread import Thread

__all__ = [
    "ProjectScope", "Session", "check_window", "current_scope", "current_session", "active_session", "set_active_session", "set_default_factory",
]


class ProjectScope:
    """The project a GPL thread belongs to, when a session holds several (the console's ``Load``).

    A controller keeps several projects in memory at once, each with its own threads
    (D1 §18: "these threads allow simultaneous execution of multiple projects"); two of them may
    both have a ``Main.Worker`` or a relative file name ``Tcs.gpo``.  A thread started for a loaded
    project carries its scope, and the threads it starts inherit it: procedures named in a String
    (``New Thread("Worker")``) resolve in ``procedures``, relative file names in ``folder``, and
    ``Thread.Project`` reads ``name``.  A thread without a scope belongs to the session's own
    project (``Session.project``, its ``procedures`` and ``files.working_folder``).
    """

    __slots__ = ("name", "folder", "procedures")

    def __init__(self, name: str, folder: str | None, procedures: ProcedureRegistry | None = None) -> None:
        self.name = name
        #: The project's folder on the controller (``/flash/projects/X``): relative names resolve here.
        self.folder = folder
        #: Its procedure registry; None until its package's ``init()`` names it (``use_procedures``).
        self.procedures = procedures

    def __repr__(self) -> str:
        return f"<ProjectScope {self.name!r} in {self.folder!r}>"


def current_scope() -> ProjectScope | None:
    """The project scope of the calling GPL thread (None: the session's own project, or not a
    GPL thread)."""
    ctx = current_ctx()
    if ctx is None or ctx.owner is None:
        return None
    scope: ProjectScope | None = getattr(ctx.owner, "_project", None)
    return scope


class Session:
    """One simulated controller (see the module docstring for its parts).

    The composer (``gplrt.sim.Simulation``) builds every part and passes it in, and builds the
    two parts made on first use: the parameter database (:meth:`database`) and each robot
    (:meth:`robot`).
    """

    def __init__(
        self,
        *,
        scheduler: Scheduler,
        controller: ControllerState,
        io: IoMap,
        files: Disks,
        network: NetworkConfig,
        procedures: ProcedureRegistry,
        console: ConsoleSink,
        robot_model: str,
        project: str = "",
        max_threads: int = 32,
        history: int | None = None,
    ) -> None:
        self.scheduler = scheduler
        self.controller = controller
        self.io = io
        self.files = files
        self.network = network
        self.procedures = procedures
        self.console = console
        #: The robot model whose shipped database :meth:`database` loads unless ``pdb`` is set.
        self.robot_model = robot_model
        self.pdb: ParameterDatabase | None = None
        self.robots: dict[int, RobotState] = {}
        self.selected: dict[ThreadKey, int] = {}
        self.project = project
        self.max_threads = max_threads
        self._history = check_window(history, "motions")
        #: Every GPL Thread started in this session.
        self.threads: list[Thread] = []
        #: Called with each GPL Thread as it ends, on that thread (robots are released there).
        self.thread_exit_hooks: list[Callable[[Thread], None]] = []
        #: Called when the session stops (``Simulation.stop``): a language layer releases there
        #: what it keeps past a thread's end (V+ keeps an error-stopped task's devices attached).
        self.stop_hooks: list[Callable[[], None]] = []
        self._booted: ParameterDatabase | None = None
        #: The projects in the controller's memory (the composer sets it: ``gplrt.sim``).
        self.projects: ProjectTable | None = None
        scheduler.session = self

    # -- what the session keeps ----------------------------------------------------------------

    @property
    def history(self) -> int | None:
        """How many motions each robot's history keeps (``gplrt.motion.queue``; None: every one).
        Setting it applies to the robots built already and to those built later."""
        return self._history

    @history.setter
    def history(self, window: int | None) -> None:
        window = check_window(window, "motions")
        for robot in self.robots.values():
            robot.queue.set_window(window)
        self._history = window

    # -- the parts made on first use ---------------------------------------------------------------

    def database(self) -> ParameterDatabase:
        """The parameter database, booted on first use: the robot model's shipped one unless
        ``pdb`` was set, with the controller's live DataIDs, and the robots' limits following
        its writes.  A database set later (``sim.pdb = db``) is booted at its first use."""
        pdb = self.pdb
        if pdb is None or pdb is not self._booted:
            pdb = self._booted = self._boot_database()
        return pdb

    def robot(self, number: int) -> RobotState:
        """Robot ``number`` (1-based), built from the database on first use (-1001 when the
        database does not define it)."""
        robot = self.robots.get(number)
        if robot is None:
            robot = self._build_robot(number)
        return robot

    def _boot_database(self) -> ParameterDatabase:
        """Load or adopt ``pdb`` and make it the controller's (the composer's job)."""
        raise NotImplementedError("a Session is composed by gplrt.sim.Simulation")

    def _build_robot(self, number: int) -> RobotState:
        """Build robot ``number`` into ``robots`` (the composer's job)."""
        raise NotImplementedError("a Session is composed by gplrt.sim.Simulation")

    # -- time and reports ------------------------------------------------------------------------

    def now(self) -> float:
        """Controller time, in seconds since the simulated boot."""
        return float(self.scheduler.clock.now())

    def report(self, thread_name: str, text: str, code: int = 0) -> None:
        """Record a controller-level error: the error log, and the console's log channel."""
        entry = self.controller.log_error(self.now(), thread_name, text, code)
        self.console.log(f"[{entry.time:.6f}] thread {thread_name}: {text}")


def check_window(window: int | None, what: str) -> int | None:
    """``window`` if it is a history window (a whole number >= 1 of ``what``, or None for all),
    else a ValueError that says so: a Python caller's mistake gets Python's error at once."""
    if window is not None and (isinstance(window, bool) or not isinstance(window, int) or window < 1):
        raise ValueError(f"a history window is a whole number of {what} >= 1, or None for all, not {window!r}")
    return window


# -- finding the session ----------------------------------------------------------------------------


class _Active:
    """The process's active session (the one threads outside every scheduler use)."""

    session: Session | None = None
    factory: Callable[[], Session] | None = None


_active = _Active()
_create_lock = threading.Lock()


def current_session() -> Session:
    """The session the calling code runs in.

    On a GPL thread: the session of its scheduler, always (sessions made one after another, or
    side by side, never see each other's threads).  Elsewhere: the active session, or a default
    one made by the factory ``gplrt.sim`` registers (a virtual-clock ``Simulation``).
    """
    ctx = current_ctx()
    if ctx is not None:
        session = ctx.sched.session
        if session is not None:
            return session
    session = _active.session
    if session is None:
        session = _make_default()
    return session


def session_of_caller() -> Session | None:
    """Like :func:`current_session`, but None where it would make a default session."""
    ctx = current_ctx()
    if ctx is not None and ctx.sched.session is not None:
        return ctx.sched.session
    return _active.session


def active_session() -> Session | None:
    """The active session (None before any)."""
    return _active.session


def set_active_session(session: Session | None) -> None:
    """Make ``session`` the one that code outside GPL threads uses (None: none)."""
    _active.session = session


def set_default_factory(factory: Callable[[], Session]) -> None:
    """What makes the default session when code needs one and none is active (``gplrt.sim``)."""
    _active.factory = factory


def _make_default() -> Session:
    with _create_lock:
        if _active.session is None:
            if _active.factory is None:
                raise RuntimeError("no simulation session: make one with gplrt.sim.Simulation() "
                                   "(importing gplrt.sim also makes a default one on first use)")
            _active.session = _active.factory()
        return _active.session
