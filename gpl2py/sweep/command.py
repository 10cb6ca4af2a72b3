"""``gpl2py sweep PROJECT --params FILE --setup FILE.py -o results.parquet``: the command.

Translates the project once (diagnostics and summary as ``gpl2py run`` prints them), runs every
parameter set on a Dask cluster (a local one of ``--workers`` processes, started and closed here,
or ``--scheduler ADDRESS``), shows a progress bar on a terminal, writes the rows as they arrive
(``gpl2py.sweep.results``) and ends with a summary: how many runs ended how.  Exit status 0 once
every set has its row (runs that failed are rows, not a failure of the sweep), 1 when the project
has errors, 2 for a wrong command line, parameter file or setup file.  Ctrl-C keeps the rows
written so far; ``--resume`` continues.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from typing import Any

from gpl2py import messages as msg
from gpl2py.diagnostics import plural
from gpl2py.outcome import Outcome, add_project_options, new_sink
from gpl2py.run import _positive_float  # (--speed's: a finite number > 0)

#: What ``gpl2py sweep`` needs beyond gpl2py's own dependencies (the ``sweep`` extra).
NEEDS = ("distributed", "pandas", "pyarrow")


def configure(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``gpl2py sweep``."""
    parser.add_argument("path", metavar="PROJECT",
                        help="a project folder (with or without Project.gpr), a Project.gpr file, or one .gpl file")
    parser.add_argument("--params", metavar="FILE", required=True,
                        help="the parameter sets: a .toml file ([grid], [[run]] or [random], and optionally "
                        "[metrics] and [plot]) or a .csv file (a header of names, one set per row)")
    parser.add_argument("--setup", metavar="FILE.py", default=None,
                        help="Python file whose setup(sim, params) is called before each run's ProjectStart "
                        "(after the modules' Init); setup(sim, params, cell) also gets the run's notebook Cell")
    parser.add_argument("-o", "--output", metavar="FILE.parquet", required=True,
                        help="the results: one row per parameter set (its parameters and metrics), written "
                        "as the runs end (FILE.parquet.parts/ until the sweep is done)")
    parser.add_argument("--scheduler", metavar="ADDRESS", default=None,
                        help="run on this existing Dask cluster (tcp://host:8786) instead of a local one")
    parser.add_argument("--workers", metavar="N", type=_whole, default=None,
                        help="processes of the local cluster (default: one per core)")
    parser.add_argument("--timeout", metavar="S", type=_positive_float, default=None,
                        help="stop a run after S seconds of controller time (the same on any machine); "
                        "its row says timeout")
    parser.add_argument("--resume", action="store_true",
                        help="skip the parameter sets already in the output (or its parts, after a crash)")
    parser.add_argument("--plot", metavar="FILE.png", default=None,
                        help="save a metric against one or two parameters (the parameter file's [plot], "
                        "else end_time against the first one or two)")
    parser.add_argument("--cache-dir", metavar="DIR", default=None,
                        help="where translations are cached (as gpl2py run)")
    add_project_options(parser)


def _whole(text: str) -> int:
    from gpl2py.run import whole_number  # (run's own check: the same words for the same mistake)

    return whole_number(text)


def run_command(args: argparse.Namespace) -> Outcome:
    """The ``sweep`` command (``gpl2py.cli`` calls it)."""
    from gpl2py.progress import ProgressBar, wants_progress
    from gpl2py.run import missing_extra, transpile_summary

    out = Outcome(sink=new_sink(args))
    stderr = sys.stderr
    problem = None
    if args.display.format != "text":
        problem = "gpl2py sweep writes its table to -o FILE; its messages are text only"
    for module in NEEDS + (("matplotlib",) if args.plot else ()):
        problem = problem or missing_extra(module, "sweep" if module != "matplotlib" else "plot", "gpl2py sweep")
    if problem is not None:
        return _usage(out, problem)
    from gpl2py.sweep import Sweep, SweepError, default_workers
    from gpl2py.sweep.params import ParamsError

    started = time.perf_counter()
    try:
        sweep = Sweep.from_file(args.path, args.params, args.setup, timeout=args.timeout, cache_dir=args.cache_dir,
                                stubs=args.stubs, sink=out.sink)
    except (ParamsError, SweepError) as exc:
        if out.sink.has_errors():
            return out  # the project's own errors: cli prints them, status 1
        return _usage(out, str(exc))
    built = sweep.built
    out.summary = transpile_summary(built.files, built.lines, out.sink, built.seconds, built.cached)
    out.checked = built.files
    from gpl2py.outcome import emit, remember

    remember(out, built.project)
    emit(out, args.display, sys.stdout, stderr)
    out.emitted = True
    plot = _plot_choice(sweep, args.plot) if args.plot else None
    if isinstance(plot, str):
        return _usage(out, plot)

    where = f"the Dask cluster at {args.scheduler}" if args.scheduler else \
        f"a local cluster of {plural(args.workers or default_workers(), 'worker')}"
    if not args.quiet:
        total = plural(len(sweep.sets), "parameter set")
        kept = sweep.already_done(args.output) if args.resume else 0
        what = f"{len(sweep.sets) - kept} of {total} ({kept} already in {args.output})" if kept else total
        stderr.write(f"sweeping {what} on {where}\n")
    bar = ProgressBar(stderr, wants_progress(stderr, args.quiet, False), min_files=0)
    try:
        table = sweep.run(scheduler=args.scheduler, workers=args.workers, output=args.output, resume=args.resume,
                          progress=lambda done, total: bar("sweep", done, total))
    except OSError as exc:  # the scheduler cannot be reached, the output cannot be written
        return _usage(out, f"{args.scheduler or args.output}: {exc.strerror or exc}")
    finally:
        bar.close()
    if not args.quiet:
        stderr.write(summary(table, time.perf_counter() - started, args.output) + "\n")
    out.exit_status = 0
    if plot is not None:
        from gpl2py.sweep.plot import save_plot

        try:
            save_plot(table, args.plot, *plot)
        except KeyError as exc:
            return _usage(out, f"--plot: {exc.args[0]}")
        except OSError as exc:
            return _usage(out, f"--plot {args.plot}: {exc.strerror or exc}")
        if not args.quiet:
            stderr.write(f"plot of {plot[0]} against {' and '.join(p for p in plot[1:] if p)} saved to {args.plot}\n")
    return out


def summary(table: Any, seconds: float, output: str) -> str:
    """``swept 40 parameter sets in 9.8 s: 35 ok, 5 timeout; results in results.parquet``."""
    counts = Counter(table["status"])
    order = ["ok", "error", "stalled", "timeout", "setup error", "crashed", "lost"]
    parts = [f"{counts[s]} {s}" for s in order if counts[s]] + [f"{n} {s}" for s, n in counts.items() if s not in order]
    return (f"swept {plural(len(table), 'parameter set')} in {seconds:.1f} s: {', '.join(parts) or 'no runs'}; "
            f"results in {output}")


def _plot_choice(sweep: Any, path: str) -> tuple[str, str, str | None] | str:
    """(metric, x, y) for ``--plot``: the parameter file's ``[plot]``, else end_time against the
    first one or two parameters; a string says why it cannot be drawn."""
    from gpl2py.run import _plot_problem

    problem = _plot_problem(path)
    if problem is not None:
        return problem
    spec = sweep.plot_spec
    names = sweep.names
    x = spec.get("x", names[0] if names else None)
    y = spec.get("y", names[1] if len(names) > 1 and "x" not in spec else None)
    metric = spec.get("metric", "end_time")
    for name in (x, y):
        if name is not None and name not in names:
            return f"--plot: {name!r} is not a parameter (the parameters: {', '.join(names)})"
    if x is None:
        return "--plot: the sweep has no parameters to plot against"
    return metric, x, y


def _usage(out: Outcome, detail: str) -> Outcome:
    """A wrong command line, parameter or setup file: GPL9001, printed now if the translation's
    diagnostics already were (then status 2 is set here), else by the CLI with the others."""
    diag = out.sink.report(msg.USAGE_ERROR, None, detail=detail)
    if out.emitted:
        sys.stderr.write(diag.render(None) + "\n")
        out.exit_status = 2
    else:
        out.usage_error = True
    return out
