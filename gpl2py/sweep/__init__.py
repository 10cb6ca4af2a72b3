"""Cell studies at scale: many runs of one project with different parameters, on Dask.

::

    from gpl2py.sweep import Sweep, grid, Count

    def setup(sim, params, cell):           # before each run's ProjectStart (cell is optional)
        sim.io.when_output(2).set_input(10001, after=params["interval"])
        cell.module("GPO").prof_fast.Speed = params["speed"]

    sweep = Sweep("samples/pick_and_place", setup, grid(interval=[0.2, 1.0], speed=[20, 80]),
                  metrics=[Count("parts", "^placed part")])
    df = sweep.run(workers=2)               # a pandas DataFrame, one row per parameter set
    sweep.run(scheduler="tcp://host:8786", output="results.parquet")  # an existing cluster
    sweep.plot(df, "end_time", "interval", "speed")                    # a heat map

The project is translated once, here (through the cache, as ``gpl2py run``); its package is
shipped to the workers as bytes (``gpl2py.sweep.worker``), never translated there.  Each run is
deterministic on the virtual clock, so a parameter set gives the same row on one worker, on many,
and in :meth:`Sweep.run_in_process` (a plain loop here, no Dask).  The parts: ``params`` (the
sets and their files), ``metrics`` (the columns), ``worker`` (one run), ``cluster`` (Dask),
``engine`` (the loop), ``results`` (the table, written as the rows arrive) and ``plot``; docs/sweep.md is the
user's guide and ``gpl2py sweep`` the command (``gpl2py.sweep.command``).
"""

from __future__ import annotations

import tempfile
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.run import Built, build, project_files
from gpl2py.sweep.metrics import OUTCOME, Count, EndTime, EventTime, Metric, MotionTime, PeakJointSpeeds, default_metrics
from gpl2py.sweep.params import ParamsError, ParamSet, draws, grid, read_params, run_id, unique
from gpl2py.sweep.worker import Setup, SetupSource, Shipment, pack, robot_models

__all__ = ["Count", "EndTime", "EventTime", "Metric", "MotionTime", "PeakJointSpeeds", "ParamsError", "Sweep",
           "SweepError", "default_metrics", "default_workers", "draws", "grid", "read_params", "run_id"]


class SweepError(Exception):
    """The sweep cannot start: the project has errors, or the setup file cannot be read."""


class Sweep:
    """One project, a setup, the parameter sets and the metrics (module docstring)."""

    def __init__(self, project: str | Path, setup: Setup | str | Path | None,
                 params: Iterable[Mapping[str, Any]], *, metrics: Iterable[Metric] | None = None,
                 timeout: float | None = None, cache_dir: str | Path | None = None,
                 stubs: str | Path | None = None, sink: DiagnosticSink | None = None) -> None:
        """Translate ``project`` (through the cache) and prepare its shipment.

        ``setup`` is a function ``setup(sim, params)`` (or ``setup(sim, params, cell)``), or the
        path of a Python file defining one, shipped as text; ``params`` the parameter sets
        (``grid``, ``draws``, a list of dicts; a set given twice runs once; a parameter ``robot``
        is the robot model of its run); ``metrics`` the
        columns beyond the outcome (default: ``default_metrics()``, which a list given here
        replaces -- add them to it to keep them); ``timeout`` in controller seconds; ``sink``
        receives the translation's diagnostics.  Raises SweepError when the project has errors
        or the setup file cannot be read, ParamsError for unusable parameter sets.
        """
        self.metrics: list[Metric] = list(metrics) if metrics is not None else default_metrics()
        self.sets = params  # type: ignore[assignment]
        if timeout is not None and not timeout > 0:
            raise ValueError(f"timeout must be a number of controller seconds > 0, not {timeout!r}")
        self.timeout = timeout
        self.setup: Setup | SetupSource | None = _setup_of(setup)
        _check_language(project)
        self.built: Built = _translate(project, cache_dir, stubs, sink if sink is not None else DiagnosticSink())
        self.shipment: Shipment = pack(self.built.package_dir, self.built.project.name,
                                       project_files(project, self.built.project))
        #: What a parameter file's ``[plot]`` asks for (``metric``, ``x``, ``y``), else empty.
        self.plot_spec: dict[str, Any] = {}

    @property
    def sets(self) -> list[ParamSet]:
        """The parameter sets, each once; assigning checks them as the constructor does."""
        return self._sets

    @sets.setter
    def sets(self, sets: Iterable[Mapping[str, Any]]) -> None:
        found = unique(sets)
        for name in dict.fromkeys(n for params in found for n in params):
            if name in (*OUTCOME, "run_id") or any(m.claims(name) for m in getattr(self, "metrics", ())):
                raise ParamsError(f"parameter {name!r} has the name of a column of the results: rename it")
        for params in found:
            robot = params.get("robot")
            if robot is not None and str(robot).upper() not in robot_models():
                raise ParamsError(f"robot {robot!r} is not a robot model; one of {', '.join(robot_models())}")
        self._sets = found

    @property
    def names(self) -> list[str]:
        """The parameters' names, in the order the sets first give them: the table's first columns."""
        return list(dict.fromkeys(name for params in self.sets for name in params))

    @classmethod
    def from_file(cls, project: str | Path, params_file: str | Path, setup: Setup | str | Path | None = None,
                  **options: Any) -> Sweep:
        """A sweep of the sets, metrics (after the defaults) and plot a parameter file gives."""
        from gpl2py.sweep.metrics import from_table

        found = read_params(params_file)
        try:
            metrics = from_table(found.metrics)
        except ValueError as exc:
            raise ParamsError(f"{params_file}: {exc}") from None
        sweep = cls(project, setup, found.sets, metrics=metrics, **options)
        sweep.plot_spec = found.plot
        return sweep

    # -- running ---------------------------------------------------------------------------------------

    def run(self, *, client: Any = None, scheduler: str | None = None, workers: int | None = None,
            output: str | Path | None = None, resume: bool = False,
            progress: Callable[[int, int], None] | None = None, per_task: int | None = None) -> Any:
        """Run every set on Dask and return the table (a pandas DataFrame, in the sets' order).

        ``client`` (a ``distributed.Client``) or ``scheduler`` (an address) is an existing
        cluster; without either a local cluster of ``workers`` processes (default: one per core)
        is started and closed here.  ``output`` is a Parquet file written as the rows arrive
        (``gpl2py.sweep.results``); ``resume`` skips the sets already in it.  ``per_task`` is the
        most sets one Dask task runs (default ``gpl2py.sweep.cluster.MOST``; fewer towards the
        end of the sweep); each run's row still arrives as the run ends.
        """
        from gpl2py.sweep.cluster import MOST, Client, local_cluster, on_dask

        if per_task is not None and not (isinstance(per_task, int) and per_task >= 1):
            raise ValueError(f"per_task must be a whole number >= 1, not {per_task!r}")

        results, todo = self._open(output, resume)
        owned: list[Any] = []
        try:
            if client is None:
                if scheduler is None:
                    owned.append(local_cluster(workers or default_workers()))
                    client = Client(owned[0])
                else:
                    client = Client(scheduler)
                owned.insert(0, client)
            for row in on_dask(client, self.shipment, self.setup, todo, self.metrics, self.timeout, progress,
                               per_task or MOST):
                results.add(row)
        finally:
            results.flush()
            for thing in owned:
                thing.close()
        return results.finish()

    def run_in_process(self, *, output: str | Path | None = None, resume: bool = False,
                       progress: Callable[[int, int], None] | None = None) -> Any:
        """Run every set in turn in this process, without Dask: the same rows as :meth:`run`."""
        from gpl2py.sweep.engine import in_process

        results, todo = self._open(output, resume)
        with tempfile.TemporaryDirectory(prefix="gpl2py-sweep-") as folder:
            try:
                for row in in_process(self.shipment, self.setup, todo, self.metrics, self.timeout, folder, progress):
                    results.add(row)
            finally:
                results.flush()
        return results.finish()

    def already_done(self, output: str | Path) -> int:
        """How many of this sweep's sets have a row in ``output`` (or its parts): what ``resume``
        would skip."""
        from gpl2py.sweep.results import done

        found = done(Path(output))
        return sum(1 for p in self.sets if run_id(p) in found)

    def _open(self, output: str | Path | None, resume: bool) -> tuple[Any, list[ParamSet]]:
        from gpl2py.sweep.results import Results

        results = Results(output, self.names, [run_id(p) for p in self.sets])
        done = results.open(resume)
        return results, [p for p in self.sets if run_id(p) not in done]

    # -- looking at it ---------------------------------------------------------------------------------

    @staticmethod
    def plot(table: Any, metric: str, x: str, y: str | None = None) -> Any:
        """``metric`` against parameter ``x`` (a line) or ``x`` and ``y`` (a heat map): a
        matplotlib Figure, shown once by a notebook (``gpl2py.sweep.plot``)."""
        from gpl2py.sweep.plot import plot

        return plot(table, metric, x, y)


def default_workers() -> int:
    """The local cluster's processes by default: one per core this process may use."""
    import os

    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


def _setup_of(setup: Setup | str | Path | None) -> Setup | SetupSource | None:
    """A function stays one (Dask pickles it); a path becomes its text, shipped and compiled there."""
    if setup is None or callable(setup):
        return setup
    path = Path(setup)
    if path.suffix != ".py" or not path.is_file():
        raise SweepError(f"setup {path}: not a Python file")
    try:
        source = SetupSource(str(path), path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise SweepError(f"setup {path}: {exc.strerror or exc}") from None
    try:
        compile(source.text, source.path, "exec")
    except SyntaxError as exc:
        raise SweepError(f"setup {path}:{exc.lineno}: {exc.msg}") from None
    return source


def _check_language(project: str | Path) -> None:
    """GPL and V+ projects run on the simulation (``gplrt.sim``), as a sweep's runs do; a TMscript
    project has its own runner (``gplrt.tm.run_project``, not yet on the simulation's virtual
    clock), so a sweep of one is refused before any run rather than giving a row of errors each."""
    from gpl2py.languages import frontend_for

    frontend = frontend_for(project)
    if frontend.name == "tmscript":
        raise SweepError(f"{project}: a {frontend.title} project cannot be swept yet (its runtime does not run "
                         "on the simulation that a sweep's runs use); GPL and V+ projects can")


def _translate(project: str | Path, cache_dir: str | Path | None, stubs: str | Path | None,
               sink: DiagnosticSink) -> Built:
    """Translate once, here (through the cache, as ``gpl2py run``)."""
    built = build(project, sink, cache_dir=cache_dir, stubs_dir=stubs)
    if built is None:
        raise SweepError(f"{project} could not be translated:\n" + "\n".join(d.render(None) for d in sink.sorted()))
    return built
