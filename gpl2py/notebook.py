"""The notebook API: one object for "translate my GPL project, run bits of it, look at the robot".

::

    from gpl2py.notebook import Cell

    cell = Cell.load("samples/pick_and_place", robot="PF400SX", clock="virtual")
    cell.io.when_output(2, True).set_input(10001, True, after=0.2)   # a scripted conveyor
    cell.init()                                   # module variables and each module's Init
    cell.call("Gripper.Open")                     # any Public procedure, with arguments
    cell.set_input(10002, True)                   # drive an input
    cell.output(1)                                # read an output -> bool
    cell.run_main()                               # or run ProjectStart, as `gpl2py run` does
    cell.where()                                  # robot 1 now: joints, X Y Z yaw pitch roll
    cell.variables(); cell.io_state()             # tables of the module variables and the I/O
    cell.plot_joints(); cell.plot_path()          # matplotlib figures of the motion so far
    cell.save_plot("cell.png")

Design: :class:`Cell` is thin.  Everything it does is one call into ``gplrt.sim.Simulation``
(``cell.sim``), the session's ``IoMap`` (``cell.io``), the runtime's notebook helpers
(``gplrt.notebook``: poses, tables, plots, GPL error reports, progress), or the generated package
(``cell.package``) -- reach for those directly for anything not covered here.  The Cell is on
gpl2py's side because it translates (issue 13: gplrt never imports gpl2py); loading goes through
the same translation cache as ``gpl2py run`` (``gpl2py.run.build``), so re-running a notebook cell
does not re-translate unchanged sources; the package is imported under a private name, so loading
two projects (or one twice) never mixes their module state.

What a notebook shows (issue 15):

* a GPL error that ``call`` or ``run_main`` does not handle is raised as ``gplrt.notebook.GplError``
  whose text starts with the GPL file, line and source line; in IPython every GplException is
  reported by its GPL frames (``gplrt.notebook.show_gpl_errors_in_ipython``);
* the translation's warnings (GPL3501 stubs, ...) are Python warnings of category
  :class:`TranslationWarning`, so the notebook shows them under the loading cell;
* a call that takes more than a few seconds of wall time shows its progress (``gplrt.notebook.drive``).

Console output is kept (``cell.console``) and, with ``echo=True`` (default), also printed as it
happens, so a notebook shows it under the cell that produced it.

Procedures are looked up by their GPL names, case-insensitively, among *this* project's procedures
(``"Module.Proc"``, or ``"Proc"`` when exactly one Public procedure has that name).  Only Public
procedures can be called, as from another GPL module (§12): a Private one raises -729 with a hint.
"""

from __future__ import annotations

import os
import threading
import time
import warnings
from collections.abc import Iterable
from pathlib import Path
from types import ModuleType
from typing import Any, Literal

from gpl2py.diagnostics import DiagnosticSink, Severity
from gpl2py.run import Built, build, import_built, install_project_files, listening_place
from gplrt.controller.pdb import default_database
from gplrt.controller.signals import DEFAULT_SIGNAL_HISTORY, IoMap
from gplrt.display import Table
from gplrt.io.sockets import Listening, listen_address
from gplrt.lang.errors import (
    AMBIGUOUS_PUBLIC_REFERENCE,
    INVALID_ARGUMENT,
    NO_MODULE_DEFINED,
    NOTHING_VALUE,
    UNDEFINED_SYMBOL,
    GplException,
)
from gplrt.lang.procedures import ProcedureEntry, choose_overload, registered_procedures
from gplrt.lang.sourcemap import gpl_traceback, register_source_text
from gplrt.motion.plot import plot_joints, plot_path_xy
from gplrt.motion.queue import DEFAULT_HISTORY
from gplrt.motion.trace import Trace
from gplrt.notebook import (
    PLOT_SAMPLES,
    EchoConsole,
    GplError,
    RobotPose,
    drive,
    io_state,
    robot_pose,
    save_motion_plot,
    show_gpl_errors_in_ipython,
    variables,
)
from gplrt.session import check_window
from gplrt.sim import Simulation, StopReport
from gplrt.threads.thread import Thread

__all__ = ["Cell", "RobotPose", "ProjectError", "Serving", "GplError", "TranslationWarning", "save_motion_plot"]


class ProjectError(Exception):
    """The project could not be translated; ``str()`` lists the diagnostics (file:line:col ...)."""


class TranslationWarning(UserWarning):
    """A warning of the translation (GPL3501 a stub for protected code, GPL2014, ...): ``Cell.load``
    issues one per diagnostic, its text as ``gpl2py check`` prints it, so a notebook shows them
    and ``warnings.simplefilter("error", TranslationWarning)`` makes them fatal."""


def _name(value: Any, what: str) -> str:
    """``value`` if it is a String; a GPL name looked up by the notebook must be one.

    Nothing is -782 and any other value -202, as for a GPL member given the wrong argument, so a
    notebook typo (``cell.get(None)``) reads like every other runtime error, not AttributeError.
    """
    if type(value) is str:
        return value
    code = NOTHING_VALUE if value is None else INVALID_ARGUMENT
    raise GplException(code, detail=f"{what} must be a String, not {value!r}")


class Serving:
    """A project's ProjectStart running in the background (:meth:`Cell.serve`)."""

    POLL = 0.01  # real seconds between looks at the listening ports

    def __init__(self, cell: Cell) -> None:
        self.cell = cell
        self.status: int | None = None  # run_main's result once the program has ended
        self._thread = threading.Thread(target=self._run, name=f"gplrt-serve:{cell.sim.project}", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        self.status = self.cell._main_status()

    @property
    def running(self) -> bool:
        return self._thread.is_alive()

    def wait_listening(self, ports: Iterable[int], timeout: float = 30.0) -> None:
        """Block until the program listens on every port of ``ports`` (see :meth:`Cell.serve`)."""
        listening_ports = self.cell.sim.network.listening_ports
        wanted = set(ports)
        end = time.monotonic() + timeout
        while not wanted <= listening_ports():
            if not self.running:
                raise RuntimeError(f"the program ended (status {self.status}) before listening on "
                                   f"{sorted(wanted - listening_ports())}:\n{self.cell.log}")
            if time.monotonic() > end:
                where = ", ".join(listening_place(w) for w in self.listening) or "nowhere"
                raise TimeoutError(f"ports {sorted(wanted - listening_ports())} not listening after "
                                   f"{timeout} s; it listens on {where}:\n{self.cell.log}")
            time.sleep(self.POLL)

    @property
    def listening(self) -> list[Listening]:
        """Where the program listens now, ordered by port: each server's address, port, protocol
        and GPL thread (``gplrt.io.sockets.Listening``; ``str()`` of one is ``127.0.0.1:10100``).
        The address is the one a client must use, which may differ from what the GPL code bound."""
        return self.cell.sim.network.listening()

    def stop(self, grace: float = 5.0) -> StopReport:
        """Abort every GPL thread (``Simulation.stop``) and wait for ProjectStart's runner."""
        report = self.cell.sim.stop(grace)
        self._thread.join(grace)
        return report

    def __enter__(self) -> Serving:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


class Cell:
    """A transpiled GPL project on its own simulated controller (see module docstring)."""

    def __init__(self, package: ModuleType, sim: Simulation, diagnostics: list[str] | None = None,
                 source: Path | None = None) -> None:
        self.package = package
        self.sim = sim
        self._procedures = _procedures_of(package)
        self.diagnostics = diagnostics or []  # warnings of the translation, rendered
        self.source = source

    # -- making one ----------------------------------------------------------------------------------

    @classmethod
    def load(
        cls,
        project: str | Path,
        *,
        robot: str = "PF400SX",
        clock: Literal["virtual", "fast", "real"] = "virtual",
        speed: float = 1.0,
        flash: str | Path | None = None,
        io: IoMap | None = None,
        echo: bool = True,
        cache_dir: str | Path | None = None,
        rebuild: bool = False,
        stubs: str | Path | None = None,
        listen: str | None = None,
        history: int | None = DEFAULT_HISTORY,
        signal_history: int | None = DEFAULT_SIGNAL_HISTORY,
        language: str | None = None,
        start: str | None = None,
    ) -> Cell:
        """Translate ``project`` (through the cache), import it and make its Simulation.

        ``robot`` is any name of ``gplrt.controller.pdb.model_names()``; ``flash`` is the folder
        that holds the controller's disks (``flash/`` in it is ``/flash``); ``io`` an ``IoMap``
        prepared beforehand (or use ``cell.io`` afterwards); ``stubs`` the folder of Python
        implementations for protected code, as ``gpl2py run --stubs DIR`` takes it (the same
        project is ported in a notebook and on the command line with the same stubs).  ``listen``
        opens the program's servers to the network as ``gpl2py run --listen`` does (an address of
        this computer, or ``"0.0.0.0"`` for every interface); by default they listen on loopback
        only, whatever address the GPL code binds.  ``history`` and ``signal_history`` are how
        many motions per robot and signal changes the session keeps for ``trace``, the plots and
        ``io.trace`` (None: the whole run; by default a bounded window, docs/notebook.md).  Raises
        :class:`ProjectError` when the project has errors, ValueError for a ``listen`` that is not
        an address of this computer or a history that is not a whole number >= 1 or None.  Each
        warning of the translation is issued as a :class:`TranslationWarning`.  ``language`` and
        ``start`` are ``gpl2py run``'s ``--language`` and ``--start`` (a V+ project's program to run).
        """
        default_database(robot)  # an unknown model fails here, with -221 and the known names
        if listen is not None:
            listen_address(listen)  # before the translation: a typo fails at once
        check_window(history, "motions")
        check_window(signal_history, "signal changes")
        if stubs is not None and not isinstance(stubs, (str, os.PathLike)):
            raise TypeError(f"stubs is the folder of Python stubs (a str or Path), not {stubs!r}")
        sink = DiagnosticSink()
        built = build(project, sink, cache_dir=cache_dir, rebuild=rebuild, stubs_dir=stubs, language=language,
                      start=start)
        files = {f.path: f for f in built.project.files()} if built is not None else {}
        rendered = [(d.severity, d.render(files.get(d.span.file) if d.span else None)) for d in sink.sorted()]
        if built is None:
            raise ProjectError(f"{project} could not be translated:\n" + "\n".join(text for _, text in rendered))
        for severity, text in rendered:
            if severity is not Severity.ERROR:  # (with errors, nothing was built: ProjectError above)
                warnings.warn(text, TranslationWarning, stacklevel=2)
        package = import_built(built)
        _register_sources(package, built)
        show_gpl_errors_in_ipython()  # in a notebook, GPL errors print as GPL frames
        sim = Simulation(clock=clock, speed=speed, io=io, console=EchoConsole(echo), flash_root=flash,
                         project=built.project.name, robot=robot, listen=listen, history=history,
                         signal_history=signal_history)
        install_project_files(sim, project, built.project)  # where the controller has them
        return cls(package, sim, [text for _, text in rendered], Path(project))

    # -- running GPL code ------------------------------------------------------------------------------

    def _drive(self, call: Any, *args: Any, **kwargs: Any) -> Any:
        """``call`` into the session with progress (``gplrt.notebook.drive``); a GPL error it does
        not handle, or a Python error raised in generated code, becomes a :class:`GplError`."""
        try:
            return drive(self.sim, call, *args, **kwargs)
        except GplError:
            raise
        except GplException as exc:
            raise GplError(exc, package_folder=self._folder) from None
        except Exception as exc:
            if not gpl_traceback(exc):
                raise  # not from GPL code: a fault of the session itself (SimulationStalled, ...)
            raise GplError(exc, package_folder=self._folder) from None

    def init(self) -> None:
        """Initialise the modules (variables in ProjectSource order, then each ``Init``), once.

        A GPL error an ``Init`` does not handle is raised as :class:`GplError`."""
        self._drive(self.sim.call, self.package.init)

    def call(self, procedure: str, *args: Any, timeout: float | None = None) -> Any:
        """Call a Public procedure by GPL name on a GPL thread; returns what a Function returns.

        Initialises the project first if that has not happened.  A GPL error the procedure does
        not handle is raised here as :class:`GplError` (a ``GplException``: ``ErrorCode``,
        ``Message()``), whose text starts with the GPL file, line and source line; ``timeout`` is
        in real seconds (``gplrt.sim.SimulationStalled`` when exceeded or when the program
        deadlocks).  A call longer than a few seconds of wall time shows its progress.
        """
        func = self.procedure(procedure, len(args))
        return self._drive(self._init_and_call, func, args, timeout)

    def _init_and_call(self, func: Any, args: tuple[Any, ...], timeout: float | None) -> Any:
        """``init()`` if needed, then the call: one trip through :meth:`_drive` for both."""
        self.sim.call(self.package.init)
        return self.sim.call(func, *args, timeout=timeout)

    def start(self, procedure: str, *args: Any, name: str = "") -> Thread:
        """Start a Public procedure as a background GPL thread (e.g. a server); returns the Thread."""
        func = self.procedure(procedure, len(args))
        self.init()
        return self.sim.start(func, *args, name=name or procedure.rpartition(".")[2])

    def run_main(self) -> int:
        """Run ProjectStart as ``gpl2py run`` does; returns 0 when no GPL thread ended with an
        unhandled error, and raises :class:`GplError` for the first one that did (its text names
        the others).

        Returns when every GPL thread has ended (or, virtual clock, when the program stalled).  A
        run longer than a few seconds of wall time shows its progress.
        """
        before = {id(t) for t in self._failed_threads()}  # an earlier run's errors are not this one's
        logged = len(self.sim.controller.error_log)
        self._drive(self._main_status)
        failed = [t for t in self._failed_threads() if id(t) not in before]
        if failed:
            first, *others = failed
            error = GplError(first.unhandled_error, first.Name, self._folder)  # type: ignore[arg-type]
            error.others = [GplError(t.unhandled_error, t.Name, self._folder).headline()  # type: ignore[arg-type]
                            for t in others]
            raise error
        return 1 if len(self.sim.controller.error_log) > logged else 0

    @property
    def _folder(self) -> str:
        """The generated package's folder (its GPL text is registered under it)."""
        return str(Path(str(self.package.__file__)).parent)

    def _failed_threads(self) -> list[Thread]:
        return [t for t in list(self.sim.threads) if t.unhandled_error is not None]

    def _main_status(self) -> int:
        """ProjectStart's run: 0, or 1 if a thread ended with an unhandled error (``main(sim)``)."""
        return int(self.package.main(self.sim))

    def serve(self, ports: Iterable[int] = (), timeout: float = 30.0) -> Serving:
        """Run ProjectStart in the background, for a server that Python clients talk to.

        Returns once the program listens on every TCP port of ``ports`` (a client may connect
        then) as a :class:`Serving` handle; use it in a ``with`` block, or call ``stop()``, to
        end the program.  Why not ``start``: ``serve`` drives the session as ``run_main`` does,
        so controller time moves while the notebook or test talks to the server instead of
        freezing between calls.  Raises ``TimeoutError`` (naming the ports still closed and the
        program's log) if the ports do not open within ``timeout`` real seconds, or
        ``RuntimeError`` if the program ends before they do.
        """
        serving = Serving(self)
        try:
            serving.wait_listening(ports, timeout)
        except BaseException:
            serving.stop()
            raise
        return serving

    def run_for(self, seconds: float) -> None:
        """Let the GPL threads run for ``seconds`` of controller time (virtual: takes no wall time;
        real clock: a run longer than a few seconds shows its progress)."""
        self._drive(self.sim.run_for, seconds)

    def procedure(self, name: str, nargs: int | None = None) -> Any:
        """The Python function of this project's procedure ``"Module.Proc"`` or ``"Proc"``;
        ``nargs`` (how many arguments it will get) chooses among overloads of the name."""
        mine = self._procedures
        want = _name(name, "procedure name").strip().lower()
        if "." in want:
            found = [e for e in mine if e.qualified_name.lower() == want]
        else:
            found = [e for e in mine if e.name.lower() == want]
        public = [e for e in found if e.public]
        if public and len({e.qualified_name.lower() for e in public}) == 1:
            return choose_overload(public, nargs, name).func  # one procedure, or its overloads
        if len(public) > 1:
            names = ", ".join(sorted(e.qualified_name for e in public))
            raise GplException(AMBIGUOUS_PUBLIC_REFERENCE, detail=f"{name!r} could be {names}: say which module")
        hint = ""
        if found:
            hint = f" ({', '.join(e.qualified_name for e in found)} is Private)"
        known = ", ".join(sorted(e.qualified_name for e in mine if e.public))
        raise GplException(UNDEFINED_SYMBOL, detail=f"no Public procedure {name!r}{hint}; known: {known}")

    # -- GPL variables -------------------------------------------------------------------------------

    def _modules(self) -> list[ModuleType]:
        """The generated module of each GPL module, in the package's order."""
        prefix = self.package.__name__ + "."
        return [value for value in vars(self.package).values()
                if isinstance(value, ModuleType) and value.__name__.startswith(prefix) and _gpl_module_name(value)]

    def module(self, name: str) -> ModuleType:
        """The generated Python module of GPL module ``name`` (case-insensitive)."""
        want = _name(name, "module name").strip().lower()
        for value in self._modules():
            if _gpl_module_name(value).lower() == want:
                return value
        raise GplException(NO_MODULE_DEFINED, detail=f"no module {name!r} in this project")

    def get(self, variable: str) -> Any:
        """The value of a module variable, ``"Module.name"`` (case-insensitive)."""
        module, _, name = _name(variable, "variable name").rpartition(".")
        if not module:
            raise GplException(NO_MODULE_DEFINED, detail=f"say which module: 'Module.{variable}'")
        mod = self.module(module)
        want = name.lower()
        for attr, value in vars(mod).items():
            if attr.lower() in (want, want + "_") and not isinstance(value, ModuleType) and not callable(value):
                return value
        raise GplException(UNDEFINED_SYMBOL, detail=f"no variable {variable!r}")

    # -- I/O ------------------------------------------------------------------------------------------

    @property
    def io(self) -> IoMap:
        """The session's ``gplrt.controller.signals.IoMap``: rules (``when_output``), trace, ..."""
        return self.sim.io

    def set_input(self, signal: int, value: bool = True) -> None:
        """Drive digital input (10001-10064) or soft signal (20001-...) ``signal``."""
        self.sim.io.set_input(signal, value)

    def set_analog_input(self, channel: int, value: float) -> None:
        self.sim.io.set_analog_input(channel, value)

    def output(self, signal: int) -> bool:
        """The state of digital signal ``signal`` (an output the program writes, or any other)."""
        return bool(self.sim.io.value(signal))

    def outputs_written(self) -> list[tuple[float, int, bool]]:
        """(controller time, signal, value) of every digital change the program made, in order."""
        return [(c.time, c.signal, c.value) for c in self.sim.io.output_trace()]

    def io_state(self) -> Table:
        """Every signal that is on or was ever changed, as a table (``gplrt.notebook.io_state``)."""
        return io_state(self.sim.io)

    def variables(self) -> Table:
        """Every module variable and constant of the project with its GPL type and value, as a
        table (``.to_pandas()`` when pandas is installed)."""
        return variables((_gpl_module_name(m), m) for m in self._modules())

    # -- what happened ---------------------------------------------------------------------------------

    @property
    def console(self) -> str:
        """Everything the program wrote with ``Console.Write``/``WriteLine`` so far."""
        return self.sim.console.output

    @property
    def log(self) -> str:
        """Controller reports (unhandled thread errors, stalls) so far."""
        return self.sim.console.log_text

    @property
    def time(self) -> float:
        """Controller time in seconds."""
        return self.sim.now()

    def where(self, robot: int = 1) -> RobotPose:
        """Where ``robot`` is now (``Robot.WhereAngles`` and ``Robot.Where`` in one)."""
        return robot_pose(self.sim, robot)

    def trace(self, robot: int = 1, dt: float | None = None) -> Trace:
        """The sampled motion so far (``gplrt.motion.trace.Trace``: times, joints, xyz).

        ``dt`` defaults to the servo period for short runs and to 1/``PLOT_SAMPLES`` of the run
        for long ones, so a plot of an hour of cell time stays quick.
        """
        if dt is None:
            dt = max(0.004, self.sim.now() / PLOT_SAMPLES)
        return self.sim.trace(robot, dt)

    def plot_joints(self, robot: int = 1, ax: Any = None) -> Any:
        """Every joint against controller time; returns the matplotlib Figure."""
        return plot_joints(self.trace(robot), ax)

    def plot_path(self, robot: int = 1, ax: Any = None) -> Any:
        """The tool-tip path seen from above (X-Y, mm); returns the matplotlib Figure."""
        return plot_path_xy(self.trace(robot), ax)

    def save_plot(self, path: str | Path, robot: int = 1) -> Path:
        """Joints and path side by side in one image file (PNG, SVG, PDF by extension)."""
        return save_motion_plot(self.sim, path, robot)

    def __repr__(self) -> str:
        return (f"<Cell {self.sim.project!r} robot={self.sim.robot_model} clock={self.sim.mode} "
                f"t={self.sim.now():.3f}s>")


def _gpl_module_name(module: ModuleType) -> str:
    """``Cell`` for the module whose docstring starts "Module Cell, transpiled by gpl2py ..."; ""
    for a module that is not a GPL module's."""
    head = (module.__doc__ or "").split(",", 1)[0]
    return head[len("Module "):] if head.startswith("Module ") else ""


def _register_sources(package: ModuleType, built: Built) -> None:
    """Hand the project's GPL text to the source map, so that a GplError can quote its line."""
    texts = {Path(src.path).name: src.text for src in built.project.sources}
    register_source_text(str(package.__file__), texts)


def _procedures_of(package: ModuleType) -> list[ProcedureEntry]:
    """The registry entries of ``package``'s procedures.

    Each generated package registers into its own registry (``gplrt.lang.procedures``), and its
    ``init()`` binds that registry to the Cell's simulation, so two Cells of projects with the same
    module names never see each other's procedures, not even for threads started by name.
    """
    return registered_procedures(package.__name__)
