"""``gpl2py run PROJECT``: translate through the cache, then run ProjectStart on a simulated controller.

Two halves, usable separately:

* :func:`build` — load the project, look its key up in the cache (``gpl2py.cache``), translate only
  on a miss; returns a :class:`Built` (the cache entry, the project, counts, whether it was a hit).
  :func:`import_built` imports the package under a private module name, so a project called
  ``json`` or ``test`` cannot shadow anything and two projects with one name can live side by side
  (the notebook API uses both).
* :func:`run_command` — the command: prints diagnostics and a summary, runs the package's
  ``main(sim)`` with console output streaming to stdout and controller reports to stderr, then
  reports every unhandled GPL error as ``File.gpl:line: error <code> in thread <name>: <message>``.

Exit status of ``run`` (also in ``gpl2py run --help`` and docs/cli.md):

====  ==========================================================================================
0     the program ended and no GPL thread ended with an unhandled error
1     the project has errors (nothing ran)
2     the command line is wrong, or gpl2py failed internally (GPL9000)
3     the program ran, and at least one GPL thread ended with an unhandled error
4     virtual clock only: the program stalled — every remaining thread waits for something
      that no thread, timer or I/O rule can ever provide (a controller would wait forever)
130   interrupted with Ctrl-C (SIGINT): every GPL thread was stopped first
143   terminated by SIGTERM (``docker stop``, systemd, a CI time-out): stopped as on Ctrl-C
141   the output was closed by its reader (``gpl2py run X | head``): every GPL thread was stopped
      and nothing more is printed, as a program that SIGPIPE stops
====  ==========================================================================================

A closed output (decision): the console sink drops what the program writes after its reader went
away (``gplrt.sim.ConsoleSink.closed``), so the GPL program never sees an error for it (it was
error -201 at the user's line); :func:`_drive` notices and the run ends like a Ctrl-C, quietly.

Ctrl-C (decision): the GPL threads are aborted the way ``Thread.Abort`` does it (at their next
scheduling point), the command waits up to ``STOP_GRACE`` real seconds for them to end, then exits
with 130 — without a Python traceback.  A thread stuck in a blocking host call (a socket read) is a
daemon thread and ends with the process.  The program is driven from a helper thread while the main
thread only waits for it (:func:`_drive`): Python raises KeyboardInterrupt in the main thread at
whatever bytecode it is running, and were that the scheduler's own code (a dispatch half done under
its lock), the threads could be left in a state no abort reaches.  A run started with SIGINT
ignored (``nohup``, a background job of a shell script) keeps ignoring it, as POSIX programs do.
SIGTERM is stopped the same way (``gpl2py.interrupts.Terminated`` is a KeyboardInterrupt), with 143.

Where the program listens (decision): each time one of its servers starts listening
(``gplrt.io.sockets.NetworkConfig.on_listen``), stderr gets ``note: listening on 127.0.0.1:10100
(thread TcpCom1)`` -- the address a client must use, once it may connect -- unless ``--quiet`` or
``--json`` (whose stderr stays clean).  TCS serves one client per port and stops listening while it
has one, so a user who probed the port to find out would take the real client's turn.
"""

from __future__ import annotations

import argparse
import importlib.util
import itertools
import json
import math
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any, Callable, TextIO

from gpl2py import messages as msg
from gpl2py import serve
from gpl2py.cache import Cache, Entry, cache_key
from gpl2py.diagnostics import Diagnostic, DiagnosticSink, Severity, plural
from gpl2py.formats import github_annotation, github_annotations, json_document
from gpl2py.interrupts import EXIT_INTERRUPTED, stop_status
from gpl2py.outcome import Display, Outcome, add_project_options, emit, limits_of, new_sink, remember
from gpl2py.progress import ProgressBar
from gpl2py.languages import frontend_for
from gpl2py.project import Limits, Project

if TYPE_CHECKING:
    from gplrt.io.sockets import Listening

    from gpl2py.transpile import Progress

EXIT_OK = 0
EXIT_ERRORS = 1
EXIT_USAGE = 2
EXIT_GPL_ERROR = 3
EXIT_STALLED = 4
EXIT_OUTPUT_CLOSED = 141  # 128 + SIGPIPE: what a shell reports for a program a closed pipe stopped
STOP_GRACE = 2.0  # real seconds the threads get to end after Ctrl-C

RUN_EPILOG = """\
exit status:
  0    the program ended; no GPL thread ended with an unhandled error
  1    errors in the GPL input (nothing ran)
  2    the command line is wrong, or gpl2py failed internally (GPL9000)
  3    the program ran and a GPL thread ended with an unhandled error; each one is
       reported as "File.gpl:LINE: error CODE in thread NAME: MESSAGE"
  4    virtual clock: the program stalled (every thread waits for something that
       can never happen; a real controller would wait forever)
  130  interrupted with Ctrl-C; every GPL thread was stopped first
  143  terminated by SIGTERM (docker stop, systemd, a CI time-out): stopped as
       on Ctrl-C, and the temporary flash folder removed
  141  the output was closed (gpl2py run ... | head): stopped quietly

The translation is cached (see --cache-dir): a second run of unchanged sources
starts at once. docs/cli.md has the details.
"""


@dataclass
class Built:
    """A project translated (or found in the cache): import it with :func:`import_built`."""

    entry: Entry
    project: Project
    cached: bool
    files: int
    lines: int
    seconds: float

    @property
    def package_dir(self) -> Path:
        return self.entry.package_dir


def count_lines(project: Project) -> int:
    return sum(len(src.text.splitlines()) for src in project.sources)


def build(path: str | Path, sink: DiagnosticSink, *, cache_dir: str | Path | None = None,
          keep_going: bool = False, rebuild: bool = False, progress: Progress | None = None,
          stubs_dir: str | Path | None = None, strict: bool = False,
          loaded: Callable[[Project], None] | None = None, limits: Limits | None = None,
          language: str | None = None, start: str | None = None) -> Built | None:
    """Translate ``path`` into the cache (or reuse the entry); diagnostics go to ``sink``.

    Returns None when the project has errors (unless ``keep_going``) or the cache cannot be
    written (reported as GPL3001-style output errors).  A cache hit replays the diagnostics of the
    translation that made the entry, so warnings are never lost by caching.  ``loaded(project)``
    is called once the project is loaded, so a caller can count its files even when the
    translation then fails (the summary says "checked 3 files: 1 error", not "checked 0 files").
    """
    started = time.perf_counter()
    probe = sink.child()  # the caller's filter (--select, --ignore) decides what stops the build
    frontend = frontend_for(path, language)
    project = frontend.load_project(path, probe, limits)
    if project is not None and sink.filter is not None:
        sink.filter.add_sources(project.sources, sink)  # its gpl2py: ignore comments
    if project is not None and loaded is not None:
        loaded(project)
    if project is None or probe.has_errors():
        sink.extend(probe)
        return None
    cache = Cache(cache_dir)
    key = cache_key(project, {"language": frontend.name, **({"start": start} if start else {}), "keep_going": keep_going, "strict": strict, "stubs": _stubs_fingerprint(stubs_dir),
                              "selection": sink.filter.fingerprint() if sink.filter is not None else None})
    entry = None if rebuild else cache.lookup(key)
    if entry is not None:
        sink.extend(entry.diagnostics)
        return Built(entry, project, True, entry.files, entry.lines, time.perf_counter() - started)
    from gpl2py.transpile import transpile  # the whole pipeline: only on a cache miss

    local = sink.child()
    output = transpile(path, local, keep_going=keep_going, progress=progress, stubs_dir=stubs_dir, strict=strict,
                       limits=limits, language=frontend.name, start=start)
    sink.extend(local)
    if output is None:
        return None
    counts = (len(project.sources), count_lines(project))
    try:
        entry = cache.store(key, output.package, output.files, local.sorted(), counts)
    except OSError as exc:
        sink.report(msg.OUTPUT_ERROR, None, path=str(cache.root), detail=getattr(exc, "strerror", None) or str(exc))
        return None
    return Built(entry, project, False, counts[0], counts[1], time.perf_counter() - started)


def _stubs_fingerprint(stubs_dir: str | Path | None) -> list[list[str]] | None:
    """The --stubs files (name and text) for the cache key: editing a user stub re-translates."""
    if stubs_dir is None:
        return None
    root = Path(stubs_dir)
    files = sorted(root.glob("*.py")) if root.is_dir() else []
    out = [[str(root.resolve())]]
    for f in files:
        try:
            out.append([f.name, f.read_text(encoding="utf-8", errors="replace")])
        except OSError:
            out.append([f.name, ""])
    return out


_serial = itertools.count()


def import_built(built: Built) -> ModuleType:
    """Import the generated package under a unique private name (see module docstring)."""
    return import_package(built.package_dir, f"_gpl2py_{built.entry.package}_{built.entry.key[:8]}_{next(_serial)}")


def import_package(folder: str | Path, name: str) -> ModuleType:
    """Import the package in ``folder`` as ``sys.modules[name]``, whatever the folder is called.

    The one way generated packages are imported (``run``, the notebook API, the tests): the name is
    the caller's, so it never collides with a standard module or another translation of the project.
    """
    folder = Path(folder)
    spec = importlib.util.spec_from_file_location(name, folder / "__init__.py",
                                                  submodule_search_locations=[str(folder)])
    if spec is None or spec.loader is None:
        raise ImportError(f"cannot import the generated package in {folder}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        sys.modules.pop(name, None)
        raise
    return module


# --- the command ------------------------------------------------------------------------------------


def _robot_names() -> list[str]:
    from gplrt.controller.pdb import model_names

    return model_names()


#: The TM robots (gplrt.tm.robot.MODELS; named here so that --help does not import the runtime).
TM_MODELS = ("TM5-700", "TM5-900", "TM12", "TM14")


def configure(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``gpl2py run``."""
    robots = sorted(set(_robot_names()) | set(TM_MODELS))
    parser.add_argument("path", metavar="PROJECT", nargs="?", default=None,
                        help="a project folder (with or without Project.gpr), a Project.gpr file, "
                        "or one .gpl file; a TMscript file or folder (.tms); none with --listen-node")
    parser.add_argument("--listen-node", action="store_true",
                        help="TM robots: serve the Listen node (TCP 5890: $TMSCT scripts, $TMSTA) and the "
                        "Ethernet Slave (TCP 5891: $TMSVR) on loopback (or --listen ADDRESS) for clients "
                        "such as techmanpy, until Ctrl-C (docs/tmscript.md)")
    parser.add_argument("--serial", action="append", default=[], type=_serial_link, metavar="PORT=URL",
                        help="TM robots: attach the simulated robot's virtual serial port PORT (COM1...) to "
                        "URL, a pyserial URL or device (loop://, socket://HOST:PORT, /dev/ttyUSB0); a "
                        "script's SerialPort/ModbusRTU opens only ports attached so (docs/tmscript.md)")
    parser.add_argument("--robot", default=None, type=str.upper, choices=robots, metavar="MODEL",
                        help="robot model of the simulated controller (default: robot in "
                        "[tool.gpl2py], else PF400SX); one of: "
                        + ", ".join(robots))
    parser.add_argument("--clock", choices=("virtual", "fast", "real"), default=None,
                        help="virtual (the default, unless clock in [tool.gpl2py]): waits and motions take no wall time and every run "
                        "is identical, but keep to real time while a socket is open; fast: virtual, "
                        "and a client that waits for a motion, homing or power-up does not wait "
                        "for it in wall time (see docs/design/clock.md); real: controller time "
                        "follows the wall clock (for servers that talk to real clients)")
    parser.add_argument("--speed", type=_positive_float, default=1.0, metavar="FACTOR",
                        help="real clock only: controller seconds per wall-clock second (default 1)")
    parser.add_argument("--flash", metavar="DIR", default=None,
                        help="folder that holds the controller's disks: DIR/flash is /flash, "
                        "DIR/ROMDISK is /ROMDISK (default: a temporary folder, removed at exit)")
    parser.add_argument("--listen", metavar="ADDRESS", default=None,
                        help="let the program's servers (TcpListener, UdpClient) be reached from the "
                        "network on ADDRESS, an IPv4 address of this computer, or 0.0.0.0 for every "
                        "interface; without it they listen on loopback (127.0.0.1) only, whatever "
                        "address the GPL code binds")
    parser.add_argument("--setup", metavar="FILE.py", default=None,
                        help="Python file whose setup(sim) is called before ProjectStart: wire "
                        "inputs to outputs (sim.io.when_output(2).set_input(10001, after=0.2)), "
                        "set inputs, load a parameter database")
    parser.add_argument("--plot", metavar="FILE.png", default=None,
                        help="after the run, save robot 1's joints against time and its tool path "
                        "(seen from above) to this image")
    parser.add_argument("--history", type=_history, default=DEFAULT_HISTORY, metavar="N|all",
                        help=f"how many motions each robot keeps for the plot (default {DEFAULT_HISTORY}: memory "
                        "stays bounded however long the run); all: every motion and every signal change")
    parser.add_argument("--cache-dir", metavar="DIR", default=None,
                        help="where translations are cached (default: $GPL2PY_CACHE_DIR, else "
                        "$XDG_CACHE_HOME/gpl2py or ~/.cache/gpl2py)")
    parser.add_argument("--rebuild", action="store_true",
                        help="translate again even when the cache has this project")
    serve.add_options(parser)
    add_project_options(parser)


#: ``--history``'s default: the motions each robot keeps (gplrt.motion.queue.DEFAULT_HISTORY; the
#: transpiler does not import the runtime to print its help, and a test checks the two agree).
DEFAULT_HISTORY = 1000


def whole_number(text: str, other: str = "") -> int:
    """An option's whole number >= 1 (``other``: what else the option takes, for the message)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number{other}: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1: {text!r}")
    return value


def _serial_link(text: str) -> tuple[str, str]:
    """``--serial COM2=socket://127.0.0.1:7000``: (port, URL)."""
    port, sep, url = text.partition("=")
    if not sep or not port.strip() or not url.strip():
        raise argparse.ArgumentTypeError(f"not PORT=URL: {text!r}")
    return port.strip(), url.strip()


def _attach_serial(args: argparse.Namespace) -> None:
    """The virtual serial ports the user attached with ``--serial``."""
    if args.serial:
        from gplrt.tm.serial import attach_serial

        for port, url in args.serial:
            attach_serial(port, url)


def _history(text: str) -> int | None:
    """``--history N|all``: a whole number >= 1, or None for ``all``."""
    if text.strip().lower() == "all":
        return None
    return whole_number(text, " or 'all'")


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be greater than 0: {text!r}")
    if value == math.inf:  # the real clock needs a finite factor (inf was internal error GPL9000)
        raise argparse.ArgumentTypeError(f"must be a finite number: {text!r}")
    return value


@dataclass
class RunReport:
    """What the program did: the exit status and what to tell the user about it."""

    status: int
    controller_time: float
    wall_time: float
    errors: list[dict[str, Any]] = field(default_factory=list)
    stalled: list[str] = field(default_factory=list)
    interrupted: bool = False  # by Ctrl-C or SIGTERM (``word`` says which)
    word: str = "interrupted"
    output_closed: bool = False  # the console's reader went away: nothing more is printed
    stopped: int = 0  # threads aborted after Ctrl-C
    still_alive: list[str] = field(default_factory=list)  # of those, still running after STOP_GRACE
    plot: str | None = None
    plot_requested: bool = False
    plot_error: str | None = None  # why the requested plot could not be written
    plot_note: str = ""  # what the plot leaves out (motions older than the history's window)

    def to_json(self) -> dict[str, Any]:
        return {
            "status": self.status,
            "controller_time": round(self.controller_time, 6),
            "errors": self.errors,
            "stalled": self.stalled,
            "interrupted": self.interrupted,
            "stopped_threads": self.stopped,
            "plot": self.plot,
            "plot_note": self.plot_note,
        }


def _unhandled_errors(sim: Any) -> list[dict[str, Any]]:
    """Every GPL thread that ended with an unhandled error: code, message, GPL file:line, thread.

    The Thread objects keep the exception (``Thread.unhandled_error``); the GPL location is the
    innermost transpiled frame the exception passed through (``gplrt.lang.sourcemap``).
    """
    from gplrt.lang.errors import GplException
    from gplrt.lang.sourcemap import locate

    found = []
    for t in list(sim.threads):
        exc = t.unhandled_error
        if exc is None:
            continue
        where = None
        if isinstance(exc, BaseException):
            where = getattr(exc, "gpl_location", None) or locate(exc)
        file, line = (where.rsplit(":", 1) + [""])[:2] if where else (None, "")
        if isinstance(exc, GplException):
            code, message = exc.ErrorCode, exc.Message()
            if exc.detail:
                message += f" - {exc.detail}"
        else:
            code, message = -201, f"Python error {type(exc).__name__}: {exc}"
        found.append({"thread": t.Name, "code": code, "message": message, "file": file,
                      "line": int(line) if line.isdigit() else None})
    return found


def _stop_all(sim: Any) -> tuple[int, list[str]]:
    """Abort every live GPL thread and give them ``STOP_GRACE`` seconds to end.

    Returns how many threads were running and the names of those still alive afterwards.
    """
    report = sim.stop(STOP_GRACE)  # a second Ctrl-C ends the wait early
    return len(report.aborted), report.still_alive


def _load_setup(path: str) -> Any:
    """The ``setup`` function of the --setup file; OSError/SyntaxError/... say what is wrong with it."""
    if not Path(path).is_file():
        what = "a folder, not a Python file" if Path(path).is_dir() else \
            "not a regular file" if Path(path).exists() else "no such file"
        raise FileNotFoundError(what)
    spec = importlib.util.spec_from_file_location(f"_gpl2py_setup_{next(_serial)}", path)
    if spec is None or spec.loader is None:
        raise ImportError("not a Python file (it must end in .py)")
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except (SyntaxError, ImportError):
        raise
    except Exception as exc:  # the user's module-level code failed, not gpl2py (so not GPL9000)
        raise ImportError(f"importing it raised {type(exc).__name__}: {exc}") from exc
    setup = getattr(module, "setup", None)
    if not callable(setup):
        raise AttributeError(f"{path} defines no setup(sim) function")
    return setup


def save_plot(sim: Any, path: str | Path, robot: int = 1) -> bool:
    """Save robot ``robot``'s joints and tool path to ``path``; False when the robot never existed."""
    if robot not in sim.robots:
        return False
    from gplrt.notebook import save_motion_plot

    save_motion_plot(sim, path, robot)
    return True


class OutputClosed(Exception):
    """The reader of the console output went away (:func:`_drive` stops the run)."""


def _drive(main: Callable[[Any], Any], sim: Any, closed: threading.Event | None = None) -> threading.Thread:
    """Run ``main(sim)`` (the package's ``main``) on a helper thread; the calling (main) thread only waits for it.

    A KeyboardInterrupt can then only arrive in this function's ``join`` (see module docstring),
    never inside the scheduler.  An exception of ``main`` itself is re-raised here, so a fault of
    gpl2py still reaches the command's GPL9000 report.  Returns the helper, still running when
    interrupted (it ends once :func:`_stop_all` has stopped the GPL threads it waits for).
    ``closed`` set (the console's reader went away) raises :class:`OutputClosed`.
    """
    failure: list[BaseException] = []

    def target() -> None:
        try:
            main(sim)
        except BaseException as exc:  # noqa: BLE001 - handed to the main thread below
            failure.append(exc)

    helper = threading.Thread(target=target, name="gpl2py run", daemon=True)
    helper.start()
    while helper.is_alive():
        helper.join(0.1)
        if closed is not None and closed.is_set():
            raise OutputClosed
    if failure:
        raise failure[0]
    return helper


def execute(package: ModuleType, sim: Any, *, plot: str | None = None,
            main: Callable[[Any], Any] | None = None) -> RunReport:
    """Run the package's ``main(sim)`` (or ``main(sim)``: ``gpl2py.serve.keep_running``); Ctrl-C
    stops every GPL thread (status 130)."""
    started = time.perf_counter()
    interrupted = closed = False
    stopped: tuple[int, list[str]] = (0, [])
    status, word = EXIT_INTERRUPTED, "interrupted"
    try:
        _drive(main or package.main, sim, getattr(sim.console, "closed", None))
    except KeyboardInterrupt as interrupt:  # Ctrl-C, or SIGTERM (gpl2py.entry)
        interrupted = True
        status, word = stop_status(interrupt)
        stopped = _stop_all(sim)
    except OutputClosed:
        closed = True
        stopped = _stop_all(sim)
    report = RunReport(EXIT_OK, sim.now(), time.perf_counter() - started, interrupted=interrupted,
                       word=word, output_closed=closed)
    report.stopped, report.still_alive = stopped
    report.errors = _unhandled_errors(sim)
    if not interrupted and not closed:
        report.stalled = [c.name for c in list(sim.scheduler.live) if c.phase != "done"]
    if closed:
        report.status = EXIT_OUTPUT_CLOSED
    elif interrupted:
        report.status = status
    elif report.errors:
        report.status = EXIT_GPL_ERROR
    elif report.stalled:
        report.status = EXIT_STALLED
    report.plot_requested = bool(plot)
    if plot and not interrupted and not closed:
        try:
            if save_plot(sim, plot):
                report.plot = str(plot)
                dropped = sim.robots[1].queue.dropped
                if dropped:  # the plot shows the history's window: say what it leaves out
                    report.plot_note = (f"the last {sim.history} motions; {dropped} earlier ones dropped "
                                        "(--history all keeps them)")
        except OSError as exc:
            report.plot_error = exc.strerror or str(exc)
    sim.close(0.0)  # everything is known: release the robots (Simulation.close says why)
    return report


def _plot_problem(path: str) -> str | None:
    """Why ``--plot path`` cannot be saved, checked before the program runs (a typo in the image
    type must not cost a whole run); None when matplotlib can write that type."""
    missing = missing_extra("matplotlib", "plot", "--plot")
    if missing is not None:
        return missing
    kind = Path(path).suffix.lstrip(".").lower()
    if not kind:
        return None  # matplotlib saves it as PNG, adding ".png"
    from matplotlib.figure import Figure

    kinds = Figure().canvas.get_supported_filetypes()
    if kind in kinds:
        return None
    return f"--plot {path}: cannot save a .{kind} image; the image types are: {', '.join(sorted(kinds))}"


def missing_extra(module: str, extra: str, needed_by: str) -> str | None:
    """One line naming the extra to install when ``module`` (an optional dependency) cannot be
    imported, or None: ``--plot needs matplotlib, which is not installed: pip install
    'gpl2py[plot]'`` rather than an internal error with an ImportError in it."""
    try:
        importlib.import_module(module)
    except ImportError as exc:
        why = "which is not installed" if isinstance(exc, ModuleNotFoundError) and exc.name == module \
            else f"which does not import ({exc})"
        return f"{needed_by} needs {module}, {why}: pip install 'gpl2py[{extra}]'"
    return None


def _flash_problem(path: str) -> str | None:
    """Why ``--flash path`` cannot hold the controller's disks, or None (the folder then exists).

    Checked here because the simulation only creates its disk folders when the program starts,
    where a failure would look like an error of gpl2py itself."""
    if Path(path).exists() and not Path(path).is_dir():
        return f"--flash {path}: not a folder (it holds the controller's disks: flash, ROMDISK, ...)"
    try:
        Path(path).mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        return f"--flash {path}: cannot hold the controller's disks: {exc.strerror or exc}"
    return None


def _listen_problem(address: str) -> str | None:
    """Why ``--listen address`` cannot be used (not IPv4, not an address of this computer), or None."""
    from gplrt.io.sockets import listen_address

    try:
        listen_address(address)
    except ValueError as exc:
        return f"--listen {address}: {exc}"
    return None


def run_command(args: argparse.Namespace) -> Outcome:
    """The ``run`` command (``gpl2py.cli`` calls it); prints everything itself."""
    from gpl2py.progress import wants_progress

    stdout, stderr = sys.stdout, sys.stderr
    display: Display = args.display
    out = Outcome(sink=new_sink(args), emitted=True)
    if args.listen_node or args.path is None:
        return _run_listen_node(args, out)
    bar = ProgressBar(stderr, wants_progress(stderr, args.quiet, not display.text))
    loaded: list[Project] = []
    try:
        built = build(args.path, out.sink, cache_dir=args.cache_dir, rebuild=args.rebuild, progress=bar,
                      stubs_dir=args.stubs, strict=args.strict, loaded=loaded.append,
                      limits=limits_of(args), language=args.language, start=args.start)
    finally:
        bar.close()
    project = built.project if built is not None else (loaded[0] if loaded else None)
    if project is not None:
        remember(out, project)  # diagnostics show their source lines, also on errors
        out.checked = len(project.sources)
    if built is not None:
        out.checked = built.files
        out.summary = transpile_summary(built.files, built.lines, out.sink, built.seconds, built.cached)
    if built is None:
        out.emitted = False  # cli prints the diagnostics; status 1
        return out
    package = import_built(built)
    if not hasattr(package, "PROJECT"):  # a TMscript project: its own runner (gplrt.tm.run_project)
        if not args.json:
            emit(out, display, stdout, stderr)
        from gplrt.tm import context

        _attach_serial(args)
        robot = context.use_robot(args.robot if args.robot in TM_MODELS else "TM5-900", clock=args.clock,
                                  speed=args.speed if args.clock == "real" else float("inf"))
        try:
            out.exit_status = int(package.main())
        finally:
            robot.close()  # (its session's threads and planned motions)
        return out
    if package.PROJECT.get("start") is None:
        needs = ("a .PROGRAM" if package.PROJECT.get("language") == "vplus" else
                 "a Project.gpr with ProjectStart=\"Module.Proc\", or a single Public Sub Main")
        out.sink.report(msg.USAGE_ERROR, None, detail=f"{args.path} has no start procedure: run needs {needs}")
        out.emitted, out.usage_error = False, True
        return out
    if not args.json:
        emit(out, display, stdout, stderr)

    problem = _plot_problem(args.plot) if args.plot else None
    problem = problem or (_flash_problem(args.flash) if args.flash else None)
    problem = problem or (_listen_problem(args.listen) if args.listen is not None else None)
    problem = problem or (missing_extra("pyftpdlib", "ftp", "--ftp") if args.ftp is not None else None)
    if problem is not None:
        return _usage_after_emit(out, problem, display, stdout, stderr)

    from gplrt.sim import ConsoleSink, Simulation

    from gpl2py.deploy import compiler, program_of

    console = ConsoleSink(capture=True) if args.json else ConsoleSink(stream=stdout, log_stream=stderr)
    sim = Simulation(clock=args.clock, speed=args.speed, console=console, flash_root=args.flash,
                     project=project.name if project else "", robot=args.robot, listen=args.listen,
                     history=args.history, **({"signal_history": None} if args.history is None else {}),
                     compiler=compiler(build, import_built, args.cache_dir))
    if not args.json and not args.quiet:
        sim.network.on_listen.append(lambda where: console.log(listening_note(where)))
    install_project_files(sim, args.path, project)
    sim.projects.adopt(sim.project, sim.project_folder, program_of(package))  # the console's Show, Stop ...
    if args.setup:
        try:
            setup = _load_setup(args.setup)
            problem = None
        except (OSError, AttributeError, SyntaxError, ImportError) as exc:
            problem = f"--setup {args.setup}: {exc}"
        if problem is None:
            try:
                setup(sim)
            except Exception as exc:  # the user's setup code, not gpl2py: say where, keep it short
                problem = f"--setup {args.setup}: setup(sim) raised {type(exc).__name__}: {exc}"
        if problem is not None:
            return _usage_after_emit(out, problem, display, stdout, stderr)
    note = stubs_note(package)
    if note and not args.json and not args.quiet:
        stderr.write(note + "\n")
    services = None
    if serve.wanted(args):
        try:
            services = serve.Services.start(sim, args, stderr)
        except OSError as exc:
            return _usage_after_emit(out, f"cannot serve the console or FTP: {exc.strerror or exc}", display,
                                     stdout, stderr)
    try:
        report = execute(package, sim, plot=args.plot,
                         main=serve.keep_running(sim.project) if services is not None else None)
    finally:
        if services is not None:
            services.close()
    out.exit_status = report.status
    if report.output_closed:  # a closed pipe ends quietly: whatever is printed now is lost or noise
        return out
    if report.plot_error is not None:  # the program's own status stands; the lost plot is said
        diag = out.sink.report(msg.OUTPUT_ERROR, None, path=str(args.plot), detail=report.plot_error)
        if not args.json:
            _say(diag, display, stdout, stderr)
    for e in report.errors:
        if e["file"]:
            e["file"] = _shown_path(built.project, e["file"])
    if args.json:
        doc = json_document(out.sink.sorted(), summary_json(built, out.sink),
                            run={**report.to_json(), "console": console.output, "log": console.log_text})
        stdout.write(json.dumps(doc, indent=2) + "\n")
        return out
    for e in report.errors:
        where = f"{e['file']}:{e['line']}: " if e["file"] else ""
        text = f"error {e['code']} in thread {e['thread']}: {e['message']}"
        stderr.write(f"{where}{text}\n")
        if display.format == "github":
            stdout.write(github_annotation(Severity.ERROR, text, e["file"], e["line"], f"GPL error {e['code']}"))
    if report.interrupted:
        text = f"gpl2py: {report.word}; stopped {plural(report.stopped, 'GPL thread')}"
        if report.still_alive:
            text += f" ({', '.join(report.still_alive)} did not stop within {STOP_GRACE:g} s)"
        stderr.write(text + "\n")
    elif not args.quiet:
        stderr.write(run_summary(report, args.clock) + "\n")
    return out


def _run_listen_node(args: argparse.Namespace, out: Outcome) -> Outcome:
    """``gpl2py run --robot TM5-900 --listen-node``: a simulated TM robot in a Listen node."""
    if not args.listen_node or (args.robot or "TM5-900") not in TM_MODELS:
        out.sink.report(msg.USAGE_ERROR, None, detail="run needs a PROJECT, or --listen-node with a TM "
                        f"robot (--robot {' | '.join(TM_MODELS)})")
        out.emitted, out.usage_error = False, True
        return out
    import math

    from gpl2py.tmscript.node import main as listen_main

    speed = args.speed if args.clock == "real" else math.inf
    _attach_serial(args)
    out.exit_status = listen_main(args.robot or "TM5-900", args.listen or "127.0.0.1", speed=speed, clock=args.clock)
    return out


def install_project_files(sim: Any, path: str | Path, project: Project | None) -> None:
    """Install the project's own files in its controller folder (``Simulation.install_project_files``)."""
    if project is None or not Path(path).exists():
        return
    sim.install_project_files(project_files(path, project), project.name)


def project_files(path: str | Path, project: Project) -> dict[str, bytes]:
    """The project's own files, by name: every regular file of a project folder; for a single
    source file, just that file (``gpl2py sweep`` ships them to its workers as bytes)."""
    from gplrt.io.project_files import read_project_files

    given = Path(path)
    if given.is_dir() or given.name.lower() == "project.gpr":
        return read_project_files(project.root)
    if given.is_file():
        return {k: v for k, v in read_project_files(given.parent).items() if k == given.name}
    return {}


def listening_note(where: Listening) -> str:
    """``note: listening on 127.0.0.1:10100 (thread TcpCom1)``: where a client reaches a server of
    the program, printed as it starts listening (module docstring)."""
    return f"note: listening on {listening_place(where)}"


def listening_place(where: Listening) -> str:
    """``127.0.0.1:10100 (thread TcpCom1)``: a server's address and port, and the GPL thread that
    opened it (none for Python code outside the GPL threads)."""
    return f"{where} (thread {where.thread})" if where.thread else str(where)


def stubs_note(package: ModuleType) -> str | None:
    """One line naming the package's stubs (PROJECT["stubs"]), or None when it has none."""
    stubs = getattr(package, "PROJECT", {}).get("stubs") or []
    if not stubs:
        return None
    names = [f"{s['name']} ({'gpl2py stand-in' if s.get('standin') else '--stubs'})" if s.get("provided")
             else str(s["name"]) for s in stubs]
    missing = sum(1 for s in stubs if not s.get("provided"))
    return (f"note: {plural(len(stubs), 'stub')} for protected or unsimulated code "
            f"({missing} {'raises' if missing == 1 else 'raise'} error -204 if used): {', '.join(names)}")


def _shown_path(project: Project, name: str) -> str:
    """The source path as diagnostics show it (the source map keeps only the file name)."""
    for src in project.sources:
        if Path(src.path).name.lower() == name.lower():
            return src.path
    return name


def _usage_after_emit(out: Outcome, detail: str, display: Display, stdout: TextIO, stderr: TextIO) -> Outcome:
    """A command-line problem found after the translation's diagnostics were printed (text mode):
    print only the new error; in JSON mode nothing was printed yet, so the CLI prints it all."""
    diag = out.sink.report(msg.USAGE_ERROR, None, detail=detail)
    if display.json:
        out.emitted, out.usage_error = False, True
    else:
        _say(diag, display, stdout, stderr)
        out.exit_status = EXIT_USAGE
    return out


def _say(diag: Diagnostic, display: Display, stdout: TextIO, stderr: TextIO) -> None:
    """One diagnostic found after the others were printed, in the display's format."""
    if display.format == "github":
        stdout.write(github_annotations([diag]))
    else:
        stderr.write(diag.render(None, display.colour) + "\n")


def transpile_summary(files: int, lines: int, sink: DiagnosticSink, seconds: float, cached: bool) -> str:
    errors, warnings = len(sink.errors), len(sink.warnings)
    how = "from the cache" if cached else f"in {seconds:.2f} s"
    return (f"transpiled {plural(files, 'file')} ({plural(lines, 'line')}) {how}: "
            f"{plural(errors, 'error')}, {plural(warnings, 'warning')}")


def summary_json(built: Built, sink: DiagnosticSink) -> dict[str, object]:
    return {"errors": len(sink.errors), "warnings": len(sink.warnings), "files": built.files,
            "lines": built.lines, "seconds": round(built.seconds, 3), "cached": built.cached}


def run_summary(report: RunReport, clock: str) -> str:
    text = (f"program ended after {report.controller_time:.3f} s of controller time ({clock} clock, "
            f"{report.wall_time:.2f} s wall): {plural(len(report.errors), 'unhandled error')}")
    if report.stalled:
        text += f"; stalled, threads still waiting: {', '.join(report.stalled)}"
    if report.plot:
        text += f"; plot saved to {report.plot}"
        if report.plot_note:
            text += f" ({report.plot_note})"
    elif report.plot_requested:
        text += "; no plot: robot 1 was never used"
    return text
