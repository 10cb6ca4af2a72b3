"""The runtime half of the notebook: what a notebook shows of a running session.

The notebook API itself is ``gpl2py.notebook.Cell`` (``from gpl2py.notebook import Cell``): it
translates a project, so it belongs to gpl2py, and gplrt never imports gpl2py (issue 13: the
runtime runs without the transpiler).  What is pure runtime lives here, for ``Cell`` and for
anyone who drives a ``gplrt.sim.Simulation`` by hand:

* :class:`RobotPose` and :func:`robot_pose` -- where a robot is, with a short repr and a table;
* :func:`save_motion_plot` -- joints and tool path in one image (also ``gpl2py run --plot``);
* :func:`io_state` and :func:`variables` -- the I/O and the module variables as tables
  (``gplrt.display.Table``);
* :class:`GplError` -- a GPL error that reached the notebook, reported by its GPL file, line and
  source text first; :func:`show_gpl_errors_in_ipython` makes IPython print every GPL error so;
* :func:`drive` -- runs a call into the session on a helper thread and shows progress when it
  takes more than a few seconds of wall time;
* :class:`EchoConsole` -- a console sink that keeps the program's output and prints it as it comes.

``from gplrt.notebook import Cell`` raises an ImportError that names ``gpl2py.notebook``.
"""

from __future__ import annotations

import ast
import html
import sys
import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType, TracebackType
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray

from gplrt.controller.console import ConsoleSink
from gplrt.controller.signals import IoMap
from gplrt.display import Table, fixed, html_table, short
from gplrt.geometry.transforms import matrix_to_xyzypr
from gplrt.lang.errors import INTERNAL_ERROR, GplException
from gplrt.lang.sourcemap import GplFrame, format_gpl_report, gpl_source_line, gpl_traceback
from gplrt.motion.plot import plot_joints, plot_path_xy
from gplrt.session import Session

__all__ = ["RobotPose", "robot_pose", "save_motion_plot", "io_state", "variables", "GplError", "EchoConsole",
           "show_gpl_errors_in_ipython", "drive", "PLOT_SAMPLES", "PROGRESS_AFTER"]

PLOT_SAMPLES = 3000  # samples per plotted trace at most (see save_motion_plot)
PROGRESS_AFTER = 3.0  # wall seconds a run takes before it shows its progress
PROGRESS_EVERY = 1.0  # wall seconds between two progress updates

#: What moved to gpl2py.notebook (the loader translates, so it is the transpiler's).
_MOVED = ("Cell", "ProjectError", "Serving", "TranslationWarning")

T = TypeVar("T")


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        raise ImportError(f"gplrt.notebook.{name} is now gpl2py.notebook.{name}: "
                          f"from gpl2py.notebook import {name} (the runtime does not translate)")
    raise AttributeError(f"module 'gplrt.notebook' has no attribute {name!r}")


# -- where a robot is ------------------------------------------------------------------------------


@dataclass(frozen=True, repr=False)
class RobotPose:
    """Where a robot is at controller time ``time``: joints (mm/deg) and the tool pose.

    ``cartesian`` is GPL's (X, Y, Z, Yaw, Pitch, Roll) in mm and degrees, Base and Tool included
    (what ``Robot.Where`` reports); None for a robot without kinematics.  ``matrix`` is the same
    pose as a 4x4 homogeneous matrix (never shown by the reprs).
    """

    time: float
    joints: tuple[float, ...]
    cartesian: tuple[float, float, float, float, float, float] | None
    matrix: NDArray[np.float64] | None

    @property
    def xyz(self) -> tuple[float, float, float] | None:
        return None if self.cartesian is None else self.cartesian[:3]

    def __repr__(self) -> str:
        joints = ", ".join(fixed(j) for j in self.joints)
        cart = "" if self.cartesian is None else f", XYZ({', '.join(fixed(v) for v in self.cartesian)})"
        return f"RobotPose(t={fixed(self.time)} s, joints=({joints}){cart})"

    def _repr_html_(self) -> str:
        names = tuple(f"J{i + 1}" for i in range(len(self.joints)))
        out = html_table(names, [tuple(fixed(j) for j in self.joints)], f"robot at t = {fixed(self.time)} s: joints")
        if self.cartesian is not None:
            out += html_table(("X", "Y", "Z", "Yaw", "Pitch", "Roll"), [tuple(fixed(v) for v in self.cartesian)],
                              "tool (mm, deg)")
        return out


def robot_pose(sim: Session, robot: int = 1) -> RobotPose:
    """Where ``robot`` of ``sim`` is now (``Robot.WhereAngles`` and ``Robot.Where`` in one)."""
    state = sim.robot(int(robot))
    now = sim.now()
    q = np.asarray(state.joints_at(now), dtype=float)
    matrix = cart = None
    if state.model.has_kinematics:
        matrix = np.asarray(state.forward(q), dtype=float)
        cart = tuple(float(v) for v in matrix_to_xyzypr(matrix))
    return RobotPose(now, tuple(float(v) for v in q), cart, matrix)  # type: ignore[arg-type]


def save_motion_plot(sim: Session, path: str | Path, robot: int = 1) -> Path:
    """Robot ``robot``'s joints against time and its tool path from above, side by side, in one file.

    Used by ``Cell.save_plot`` and ``gpl2py run --plot``.  Works without a display (the figure is
    drawn off-screen and closed, so a long batch run does not accumulate figures).
    """
    from matplotlib.figure import Figure  # an optional dependency (the "plot" extra)

    # A plot needs no more than a few thousand samples; the trace's default (the 4 ms servo
    # period) would sample an hour-long run 900 000 times.
    tr = sim.trace(robot, max(0.004, sim.now() / PLOT_SAMPLES))
    fig = Figure(figsize=(12, 4.5))
    left, right = fig.subplots(1, 2)
    plot_joints(tr, ax=left)
    plot_path_xy(tr, ax=right)
    left.set_title(f"robot {robot}: joints")
    right.set_title(f"robot {robot}: tool path seen from above")
    fig.tight_layout()
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100)
    return out


# -- tables ----------------------------------------------------------------------------------------


def _signal_kind(io: IoMap, kind: str, n: int) -> str:
    m = io.map
    if kind == "AIO":
        return "analog input" if n in m.analog_inputs else "analog output"
    if n in m.digital_inputs:
        return "digital input"
    return "soft signal" if n in m.soft_signals else "digital output"


def io_state(io: IoMap) -> Table:
    """Every signal that is on or was ever changed: its kind, value, changes and the last one.

    A signal nobody touched is off (analog: 0) and is not listed.  ``by`` is ``program`` for a
    change the GPL program made and ``outside`` for an input driven from the notebook or a rule.
    ``changes`` counts what ``io.trace`` still holds (it keeps a window: ``io.trace_window``).
    """
    last: dict[tuple[str, int], tuple[float, str, int]] = {}
    for change in io.trace:
        key = (change.kind, change.signal)
        count = last.get(key, (0.0, "", 0))[2]
        last[key] = (change.time, "program" if change.source == "gpl" else "outside", count + 1)
    digital, analog = io.snapshot()
    values: dict[tuple[str, int], Any] = {("DIO", n): v for n, v in digital.items()}
    values.update({("AIO", n): v for n, v in analog.items()})
    rows = []
    for kind, n in sorted(set(values) | set(last), key=lambda k: (k[0] != "DIO", k[1])):
        value = values.get((kind, n), False if kind == "DIO" else 0.0)
        when, by, count = last.get((kind, n), (None, "", 0))
        shown = ("on" if value else "off") if kind == "DIO" else short(value)
        rows.append((n, _signal_kind(io, kind, n), shown, count, "" if when is None else fixed(when), by))
    return Table(("signal", "kind", "value", "changes", "last change (s)", "by"), rows, "I/O state")


def _gpl_type(value: Any) -> str:
    """The GPL type a person recognises for a variable's value."""
    names = {bool: "Boolean", int: "Integer", float: "Double", str: "String"}
    if value is None:
        return "Nothing"
    return names.get(type(value), type(value).__name__)


def _declared_names(module: ModuleType) -> list[str]:
    """The names a generated module assigns at its top level: its GPL variables and constants, in
    the order the module declares them (what it imports, such as ``Console``, is not one)."""
    try:
        with open(str(module.__file__), encoding="utf-8") as f:
            tree = ast.parse(f.read())
    except (OSError, SyntaxError, TypeError):
        return []
    names: list[str] = []
    for node in tree.body:
        if isinstance(node, ast.Assign):
            targets = node.targets
        elif isinstance(node, ast.AnnAssign):
            targets = [node.target]
        else:
            continue
        names.extend(t.id for t in targets if isinstance(t, ast.Name) and not t.id.startswith("_"))
    return list(dict.fromkeys(names))


def variables(modules: Iterable[tuple[str, ModuleType]]) -> Table:
    """The module-level variables and constants of generated modules, given as (GPL name, module):
    module, name, GPL type and value (numbers rounded, objects by their short repr)."""
    rows = []
    for module_name, module in modules:
        for name in _declared_names(module):
            if hasattr(module, name):
                value = getattr(module, name)
                rows.append((module_name, name.removesuffix("_"), _gpl_type(value), short(value)))
    return Table(("module", "name", "type", "value"), rows, "module variables")


# -- errors ------------------------------------------------------------------------------------------


class GplError(GplException):
    """A GPL error the notebook's call did not handle, told in GPL terms.

    ``str(err)`` starts with ``File.gpl:42: error -709 in thread Main: *Division by 0*``, then
    the GPL line itself, then the GPL frames it came through (runtime and scheduler frames left
    out).  It is a ``GplException`` with the same ``ErrorCode``, ``Message()`` and robot data, so
    ``except GplException`` still catches it; ``error`` is the exception the program raised (its
    Python traceback has every frame) and ``frames`` the GPL frames (``gplrt.lang.sourcemap``).
    A Python exception in generated code (a fault of gpl2py or of a stub) is error -201.
    """

    def __init__(self, error: BaseException, thread: str = "", package_folder: str | None = None) -> None:
        if isinstance(error, GplException):
            super().__init__(error.ErrorCode, error.Qualifier, detail=error.detail, subject=error.subject)
            self._robot_error, self._robot_num, self._axis = error._robot_error, error._robot_num, error._axis
        else:
            super().__init__(INTERNAL_ERROR, detail=f"Python error {type(error).__name__}: {error}")
        self.error = error
        self.thread = thread
        self.others: list[str] = []  # headlines of further threads that ended unhandled (run_main)
        self.frames: list[GplFrame] = gpl_traceback(error)
        self.gpl_location = self.frames[-1].location if self.frames else getattr(error, "gpl_location", None)
        if not self.frames and self.gpl_location and package_folder is not None:
            # The runtime turned a Python error (in a stub, say) into this one where it caught it:
            # the traceback lost the GPL frame, the location it recorded did not.
            file, _, line = self.gpl_location.rpartition(":")
            if line.isdigit():
                text = gpl_source_line(file, int(line), package_folder)
                self.frames = [GplFrame(file, int(line), "", text)]

    def Message(self) -> str:  # noqa: N802 - the core's member name
        """The raised error's own text: a language layer's error (V+'s ``VError``) numbers and
        words its errors itself, and ``*Error -401*`` would hide V+'s *Undefined value*."""
        if isinstance(self.error, GplException):
            return self.error.Message()
        return super().Message()

    @property
    def source_line(self) -> str:
        """The GPL line that raised it (``""`` when unknown)."""
        return self.frames[-1].text if self.frames else ""

    def headline(self) -> str:
        where = f"{self.gpl_location}: " if self.gpl_location else ""
        thread = f" in thread {self.thread}" if self.thread else ""
        text = self.Message() + (f" - {self.detail}" if self.detail else "")
        return f"{where}error {self.ErrorCode}{thread}: {text}"

    def __str__(self) -> str:
        text = format_gpl_report(self.error, self.headline(), self.frames)
        if self.others:
            text += "\nalso ended with an unhandled error:\n" + "\n".join(f"  {h}" for h in self.others)
        return text

    def _repr_html_(self) -> str:
        return f"<pre>{html.escape(str(self))}</pre>"


def _show_gpl_error(shell: Any, etype: type[BaseException], value: BaseException, tb: TracebackType | None,
                    tb_offset: int | None = None) -> None:
    """IPython's handler for GplException: the GPL report, not the runtime's frames.

    An error raised by the notebook API is already a :class:`GplError`; a GplException that came
    straight out of generated code (a procedure called as a Python function) is reported as one.
    One that passed through no GPL code (a notebook typo) keeps IPython's usual traceback.
    """
    error = value if isinstance(value, GplError) else GplError(value)
    if not error.frames and not isinstance(value, GplError):
        shell.showtraceback((etype, value, tb), tb_offset=tb_offset)
        return
    lines = str(error).splitlines()
    shell._showtraceback(etype, error.headline(), [f"{type(value).__name__}: {lines[0]}", *lines[1:]])


def show_gpl_errors_in_ipython() -> bool:
    """In IPython (Jupyter, VS Code), report every GplException by its GPL frames; False elsewhere.

    IPython does not use ``sys.excepthook`` (where ``gplrt.lang.sourcemap`` installs the same
    idea for scripts), so the notebook loader calls this.  Calling it again changes nothing.
    IPython keeps one such handler: one the user set already is left alone (False).
    """
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None  # type: ignore[attr-defined]
    if shell is None:
        return False
    handled = tuple(getattr(shell, "custom_exceptions", ()))
    if handled == (GplException,):
        return True
    if handled:
        return False
    shell.set_custom_exc((GplException,), _show_gpl_error)
    return True


# -- running with progress -------------------------------------------------------------------------


class EchoConsole(ConsoleSink):
    """Captures like ``ConsoleSink(capture=True)`` and also prints program output as it comes."""

    def __init__(self, echo: bool) -> None:
        super().__init__(capture=True)
        self.echo = echo

    def write(self, text: str) -> None:
        super().write(text)
        if self.echo:
            sys.stdout.write(text)
            sys.stdout.flush()


class _Progress:
    """One line that says how far a long run is: in place under a notebook cell (an HTML display
    updated by id, no widgets), else a line on stderr each time it changes."""

    def __init__(self, sim: Session) -> None:
        self.sim = sim
        self.handle: Any = None
        self.shown = False

    def text(self, wall: float, done: bool = False) -> str:
        threads = sum(1 for c in list(self.sim.scheduler.live) if c.phase != "done")
        state = "done" if done else f"running, {threads} GPL thread{'s' if threads != 1 else ''}"
        return f"{state}: {fixed(self.sim.now(), 1)} s of controller time in {fixed(wall, 1)} s wall"

    def show(self, wall: float, done: bool = False) -> None:
        line = self.text(wall, done)
        if not self.shown:
            self.shown = True
            self.handle = _display_handle(line)
        if self.handle is not None:
            self.handle.update(_Html(f"<code>{html.escape(line)}</code>"))
        else:
            sys.stderr.write(line + "\n")
            sys.stderr.flush()


class _Html:
    def __init__(self, text: str) -> None:
        self.text = text

    def _repr_html_(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return html.unescape(self.text.removeprefix("<code>").removesuffix("</code>"))


def _display_handle(line: str) -> Any:
    """An updatable display under the running notebook cell, or None outside a kernel."""
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None  # type: ignore[attr-defined]
    if shell is None or not hasattr(shell, "kernel"):
        return None
    from IPython.display import display

    return display(_Html(f"<code>{html.escape(line)}</code>"), display_id=True)


def drive(sim: Session, call: Callable[..., T], *args: Any, progress_after: float = PROGRESS_AFTER,
          **kwargs: Any) -> T:
    """``call(*args, **kwargs)`` on a helper thread while this one waits, showing progress once the
    call has taken ``progress_after`` wall seconds; its result or exception is this function's.

    Why a helper thread: the caller (the notebook's main thread) stays free to report progress,
    and Ctrl-C (a kernel interrupt) lands here, never inside the scheduler: every GPL thread of
    ``sim`` is then stopped (``Simulation.stop``) before KeyboardInterrupt goes on.
    """
    result: list[Any] = []
    failure: list[BaseException] = []

    def target() -> None:
        try:
            result.append(call(*args, **kwargs))
        except BaseException as exc:  # noqa: BLE001 - handed to the caller below
            failure.append(exc)

    helper = threading.Thread(target=target, name="gplrt-notebook", daemon=True)
    started = time.monotonic()
    progress = _Progress(sim)
    next_update = started + progress_after
    helper.start()
    try:
        while helper.is_alive():
            helper.join(0.05)
            now = time.monotonic()
            if now >= next_update and helper.is_alive():
                progress.show(now - started)
                next_update = now + PROGRESS_EVERY
    except KeyboardInterrupt:
        stop = getattr(sim, "stop", None)
        if stop is not None:
            stop()
        helper.join(1.0)
        raise
    if progress.shown:
        progress.show(time.monotonic() - started, done=True)
    if failure:
        raise failure[0]
    return result[0]
