"""One run of a sweep, where it runs (a Dask worker or the sweep's own process): never translates.

The sweep translates the project once, on the machine that starts it, and ships a
:class:`Shipment`: the generated package's files and the project's own files as bytes (workers
may be other machines: no shared file system is assumed).  A worker unpacks it into a folder of
its own once per process (:func:`install`) and imports it under a private name; this module
imports only the runtime and ``gpl2py.run`` (which does not import the translator: a test checks
that ``gpl2py.transpile`` never loads on a worker).

A run (:func:`run_one`):

1. a fresh virtual-clock ``Simulation`` (parameter ``robot``, if the set has one, is its model);
2. the project's modules initialised (their variables and ``Init`` procedures);
3. the user's ``setup(sim, params)`` -- I/O rules, inputs, Profile or database changes; a
   setup that takes a third parameter also gets the run's ``gpl2py.notebook.Cell``
   (``cell.module("GPO").prof_fast.Speed = 50``: the modules' variables, as Init left them);
4. ProjectStart, as ``gpl2py run`` runs it (``gpl2py.run.execute``): an unhandled GPL error,
   a stall (exit 4's condition) or ``timeout`` controller seconds (every thread aborted then)
   ends it with that status.

Why the time-out is in controller seconds: every run is deterministic on the virtual clock, so
the same parameter set gives the same row on any worker, machine or load (a wall-clock limit
would make the row depend on how busy the worker was).  Compute time is charged to the virtual
clock too (``gplrt.threads.scheduler``), so a busy loop reaches the limit as a sleeping one does.

Nothing a run does escapes as an exception: a failing setup, a GPL error or a fault of gpl2py
itself becomes the row's ``status`` and ``error_*`` columns.
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import io
import itertools
import os
import shutil
import tempfile
import traceback
import zipfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import CodeType, ModuleType
from typing import Any

import numpy as np
from gplrt.controller.console import ConsoleSink

from gpl2py.sweep.metrics import OUTCOME, Metric, MotionSummary, RunRecord

__all__ = ["Installed", "Shipment", "SetupSource", "install", "installed", "robot_models", "run_one", "pack"]

#: A run's setup: the user's function, or the text of a setup file (the CLI's ``--setup``).
Setup = Callable[..., Any]


@dataclass(frozen=True)
class SetupSource:
    """A setup file's text, shipped as data and compiled on the worker under its own file name
    (tracebacks and error rows point at the user's file and line)."""

    path: str
    text: str

    def load(self) -> Setup:
        """A fresh module of the file's code (compiled once per process), and its ``setup``."""
        module = ModuleType(f"_gpl2py_sweep_setup_{hashlib.sha256(self.text.encode()).hexdigest()[:12]}")
        module.__file__ = self.path
        exec(_compiled(self.path, self.text), module.__dict__)  # the user's own code (like --setup)
        setup = getattr(module, "setup", None)
        if not callable(setup):
            raise AttributeError(f"{self.path} defines no setup(sim, params) function")
        return setup


@functools.lru_cache(maxsize=8)
def _compiled(path: str, text: str) -> CodeType:
    """A setup file's code: compiled once, executed afresh for each run (``_start``)."""
    return compile(text, path, "exec")


@dataclass(frozen=True)
class Shipment:
    """What a worker needs to run the project: bytes only (module docstring)."""

    project: str  # the project's name (the controller folder its files go to)
    package: str  # the generated package's folder name
    archive: bytes  # the package's files, zipped
    files: dict[str, bytes]  # the project's own files (Project.gpr, data files), by name
    gpl2py: str  # the gpl2py version that translated it
    digest: str = field(default="")

    def __post_init__(self) -> None:
        if not self.digest:
            object.__setattr__(self, "digest", hashlib.sha256(self.archive).hexdigest()[:16])


def pack(package_dir: Path, project: str, files: dict[str, bytes]) -> Shipment:
    """Zip a generated package (a folder of Python files) into a :class:`Shipment`."""
    from gpl2py import __version__

    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for path in sorted(package_dir.rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                archive.write(path, path.relative_to(package_dir).as_posix())
    return Shipment(project, package_dir.name, buffer.getvalue(), dict(files), __version__)


@dataclass(frozen=True)
class Installed:
    """A shipment unpacked and imported in this process: what a run needs of it."""

    package: ModuleType
    project: str
    files: dict[str, bytes]


#: Shipments this process has unpacked and imported, by digest.
_installed: dict[str, Installed] = {}
_serial = itertools.count()


def installed(digest: str) -> Installed:
    """The shipment :func:`install` unpacked in this process (LookupError if none was)."""
    try:
        return _installed[digest]
    except KeyError:
        raise LookupError(f"no project package {digest} was installed in this process") from None


def install(shipment: Shipment, folder: str | Path | None = None) -> Installed:
    """Unpack ``shipment`` under ``folder`` (default: a temporary folder) and import it, once per
    process; later calls return the same one.  Each run's ``init`` resets the modules."""
    found = _installed.get(shipment.digest)
    if found is not None:
        return found
    from gpl2py import __version__
    from gpl2py.run import import_package

    if shipment.gpl2py != __version__:
        raise RuntimeError(f"the project was translated by gpl2py {shipment.gpl2py}, this worker has "
                           f"{__version__}: install the same gpl2py on every worker")
    base = Path(folder) if folder is not None else Path(tempfile.gettempdir())
    target = base / f"gpl2py-sweep-{shipment.digest}-{os.getpid()}-{next(_serial)}" / shipment.package
    if target.parent.exists():
        shutil.rmtree(target.parent)
    with zipfile.ZipFile(io.BytesIO(shipment.archive)) as archive:
        archive.extractall(target)
    module = import_package(target, f"_gpl2py_sweep_{shipment.package}_{shipment.digest[:8]}")
    found = _installed[shipment.digest] = Installed(module, shipment.project, dict(shipment.files))
    return found


def robot_models() -> list[str]:
    """The robot models a parameter ``robot`` may name (the runtime's; the sweep checks the sets
    against them before any run, through this module: the one that runs programs)."""
    from gplrt.controller.pdb import model_names

    return list(model_names())


def run_one(project: Installed, setup: Setup | SetupSource | None, params: Mapping[str, Any],
            metrics: list[Metric], timeout: float | None = None) -> dict[str, Any]:
    """Run the project once with ``params`` and return what it measured (module docstring).

    A program that stalls before ``timeout`` is stalled, not timed out: the time-out's timer is
    the only thing that moved the clock on, so the run is made again without it, to give the row
    a run without a time-out gives (each run is deterministic: it stalls at the same moment).
    """
    row = _run(project, setup, params, metrics, timeout)
    if row is None:
        row = _run(project, setup, params, metrics, None)
    assert row is not None
    return row


def _run(project: Installed, setup: Setup | SetupSource | None, params: Mapping[str, Any],
         metrics: list[Metric], timeout: float | None) -> dict[str, Any] | None:
    """One run; None when it stalled before ``timeout`` (see :func:`run_one`)."""
    from gplrt.sim import Simulation

    package = project.package
    console = _TimedConsole()
    robot = params.get("robot")
    outcome: dict[str, Any] = dict.fromkeys(OUTCOME)
    record = RunRecord()
    sim = Simulation(clock="virtual", console=console, project=project.project, history=None,
                     signal_history=1, **({"robot": str(robot).upper()} if robot is not None else {}))
    console.sim = sim
    sim.io.on_change(lambda c: record.signals.append((round(c.time, 9), c.signal, bool(c.value)))
                     if c.kind == "DIO" else None)
    try:
        sim.install_project_files(dict(project.files), project.project)
        outcome.update(_start(package, sim, setup, params))
        if outcome["status"] is None:
            ended = _main(package, sim, timeout, record)
            if ended is None:
                return None
            outcome.update(ended)
    except Exception as exc:  # a fault of gpl2py or the runtime: the row says so, the sweep goes on
        frames = traceback.extract_tb(exc.__traceback__)
        where = f" (at {Path(frames[-1].filename).name}:{frames[-1].lineno})" if frames else ""
        outcome.update(status="crashed", error_message=f"{type(exc).__name__}: {exc}{where}")
        sim.close(0.0)
    record.end_time = round(sim.now(), 9)
    record.console = console.lines()
    row: dict[str, Any] = {}
    for metric in metrics:
        row.update(metric.columns(record))
    return {**outcome, **row}


def _start(package: ModuleType, sim: Any, setup: Setup | SetupSource | None,
           params: Mapping[str, Any]) -> dict[str, Any]:
    """Initialise the modules, then the user's setup; the outcome of a failure, else {}."""
    try:
        sim.call(package.init)
    except Exception as exc:  # a GPL error in an Init (GplException), or one of Python in it
        sim.close(0.0)
        return {"status": "error", **_error_columns(exc, "Init")}
    if setup is None:
        return {}
    try:
        # A setup file is executed afresh for each run: nothing it keeps at module level (a
        # random generator, a counter) carries over from one run to the next, whichever runs a
        # worker happened to get before.
        function = setup.load() if isinstance(setup, SetupSource) else setup
        if _takes_cell(function):
            from gpl2py.notebook import Cell

            function(sim, dict(params), Cell(package, sim))
        else:
            function(sim, dict(params))
    except Exception as exc:  # the user's setup code: its file and line
        sim.close(0.0)
        mine = setup.path if isinstance(setup, SetupSource) else getattr(getattr(setup, "__code__", None),
                                                                         "co_filename", None)
        frames = traceback.extract_tb(exc.__traceback__)
        last = next((f for f in reversed(frames) if f.filename == mine), frames[-1] if frames else None)
        return {"status": "setup error", "error_message": f"setup raised {type(exc).__name__}: {exc}",
                "error_file": Path(last.filename).name if last else None, "error_line": last.lineno if last else None}
    return {}


def _takes_cell(function: Setup) -> bool:
    try:
        positional = [p for p in inspect.signature(function).parameters.values()
                      if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    except (TypeError, ValueError):
        return False
    return len(positional) >= 3


def _main(package: ModuleType, sim: Any, timeout: float | None, record: RunRecord) -> dict[str, Any] | None:
    """ProjectStart through ``gpl2py.run.execute``; the robots' motion is summarised before
    ``execute`` closes the session (which lets go of the trajectories).  None: the program
    stalled before the time-out (:func:`run_one`)."""
    from gpl2py.run import EXIT_GPL_ERROR, EXIT_STALLED, execute

    timed_out: list[float] = []
    stalled_before: list[bool] = []
    if timeout is not None:
        def abort_all() -> None:
            # Called by the scheduler (its lock held): with every thread blocked for good, the
            # clock only moved on to reach this timer, and the program had stalled before it.
            if sim.scheduler.is_stalled():
                stalled_before.append(True)
                return
            timed_out.append(sim.now())
            for ctx in list(sim.scheduler.live):
                if ctx.phase != "done":
                    sim.scheduler.request_abort(ctx)

        sim.scheduler.call_at(float(timeout), abort_all)

    def main(s: Any) -> None:
        try:
            package.main(s)
        finally:
            record.motion = {n: _motion_summary(s, n) for n in sorted(s.robots)}

    report = execute(package, sim, main=main)
    if stalled_before:
        return None
    if timed_out:
        return {"status": "timeout", "error_message": f"stopped at the time-out, {timeout:g} s of controller time"}
    if report.status == EXIT_GPL_ERROR and report.errors:
        first = report.errors[0]
        return {"status": "error", "error_code": first["code"], "error_message": first["message"],
                "error_file": first["file"], "error_line": first["line"], "error_thread": first["thread"]}
    if report.status == EXIT_STALLED:
        return {"status": "stalled", "stalled_threads": ", ".join(report.stalled)}
    return {"status": "ok"}


def _error_columns(exc: BaseException, thread: str) -> dict[str, Any]:
    """Code, message and GPL file:line of an error raised out of GPL code (``Init``)."""
    from gplrt.lang.errors import GplException
    from gplrt.lang.sourcemap import locate

    where = getattr(exc, "gpl_location", None) or locate(exc)
    file, _, line = (where or "").rpartition(":")
    if isinstance(exc, GplException):
        code, message = exc.ErrorCode, exc.Message() + (f" - {exc.detail}" if exc.detail else "")
    else:
        code, message = -201, f"Python error {type(exc).__name__}: {exc}"
    return {"error_code": code, "error_message": message, "error_file": file or None,
            "error_line": int(line) if line.isdigit() else None, "error_thread": thread}


def _motion_summary(sim: Any, number: int) -> MotionSummary:
    """How long robot ``number`` moved (the union of its motions) and each joint's peak speed,
    sampled at the trajectory generator's period (every motion is kept: ``history=None``)."""
    from gplrt.motion.queue import DwellSegment
    from gplrt.motion.trace import _default_dt

    state = sim.robots[number]
    step = _default_dt(sim, number)
    peaks = np.zeros(state.axis_count)
    moving, last_end = 0.0, -np.inf
    for seg in state.queue.history:
        start, end = seg.t0, min(seg.motion_end, sim.now())
        if isinstance(seg, DwellSegment) or end <= start:
            continue
        moving += end - max(start, last_end) if end > last_end else 0.0
        last_end = max(last_end, end)
        ts = np.append(np.arange(start, end, step), end)
        with state.lock:
            velocities, _ = seg.rates(ts)
        peaks = np.maximum(peaks, np.abs(np.asarray(velocities)).max(axis=0))
    return MotionSummary(tuple(state.model.joint_names), round(moving, 9),
                         tuple(round(float(p), 6) for p in peaks))


class _TimedConsole(ConsoleSink):
    """The run's console, kept in memory (never printed): also each complete line of the program's
    output with the controller time it was completed at, for the console metrics."""

    def __init__(self) -> None:
        super().__init__(capture=True)
        self.sim: Any = None
        self._lines: list[tuple[float, str]] = []
        self._partial = ""

    def write(self, text: str) -> None:
        super().write(text)
        now = round(self.sim.now(), 9) if self.sim is not None else 0.0
        *complete, self._partial = (self._partial + text).split("\n")
        self._lines.extend((now, line) for line in complete)

    def lines(self) -> list[tuple[float, str]]:
        """Every line written, the last one even when it was never ended."""
        return self._lines + ([(round(self.sim.now(), 9), self._partial)] if self._partial else [])
