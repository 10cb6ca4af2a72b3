"""The door to every translation: a project of any supported language -> diagnostics -> files.

``transpile(path, sink)`` picks the front end for ``path`` (:mod:`gpl2py.languages`; GPL today, V+
and TMscript as they land: docs/design/frontends.md) and runs its pipeline, which loads the
project, parses every source, analyses and lowers it; the result is the generated package's files
(:class:`gpl2py.output.Output`) or ``None`` when there were errors (unless ``keep_going``).
``write_package`` writes them below an output folder.  Output is deterministic: identical input
gives byte-identical files.

A library caller (a notebook, the test harness) gets the promise the command line gives: an
unexpected exception in any phase -- loading, parsing, semantics or lowering -- is a GPL9000
internal-error diagnostic and ``None``, never a traceback.  Each pipeline contains it to the file or
module where it happened (``diagnostics.contained``), so the other files' diagnostics are all
reported; this door contains whatever escapes the pipeline.  ``GPL2PY_TRACEBACK=1`` re-raises it,
as it does for the CLI, so a gpl2py developer can still see where it came from.

``gpl2py check`` runs this same pipeline without keeping the generated text (``keep_modules``),
so it reports exactly what ``translate`` reports, in every case.
"""

from __future__ import annotations

import gc
import inspect
import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager

from gpl2py.diagnostics import DiagnosticSink, contained
from gpl2py.languages import frontend_for
from gpl2py.messages import USAGE_ERROR
from gpl2py.output import DATA_FOLDER, Output, Progress, write_package
from gpl2py.project import Limits, Project


def transpile(path: str | os.PathLike[str], sink: DiagnosticSink, keep_going: bool = False,
              progress: Progress | None = None, *, stubs_dir: str | os.PathLike[str] | None = None,
              strict: bool = False, loaded: Callable[[Project], None] | None = None,
              limits: Limits | None = None, keep_modules: bool = True,
              language: str | None = None, start: str | None = None) -> Output | None:
    """``progress(phase, done, total)``, when given, is called per file parsed and module written
    (``gpl2py.progress.ProgressBar`` draws it).  ``stubs_dir``: user implementations of stubs
    (``gpl2py.gpl.lower.user_stubs``); ``strict``: every stub is an error (``gpl2py.gpl.semantics.stubs``).
    ``loaded(project)`` is called once the project is loaded, so a caller can count its files even
    when the translation fails.  ``limits``: how much input may be read (``project.Limits``;
    default from the environment).  ``keep_modules=False`` (``gpl2py check``): the diagnostics
    only, each module's text dropped once made and no project files read.  ``language``: the
    front end's name (``--language``); by default recognised from the files.  ``start``: the
    program to run (``--start``), given to the pipeline only when set.

    The cyclic garbage collector is paused meanwhile (:func:`collector_paused`), and the pipeline
    has the same stack whoever calls it (:func:`recursion_budget`).
    """
    with collector_paused(), recursion_budget(PIPELINE_FRAMES), contained(sink, None):  # never a traceback
        frontend = frontend_for(path, language)
        pipeline = frontend.pipeline()
        extra = {"start": start} if start is not None else {}
        if extra and "start" not in inspect.signature(pipeline).parameters:  # (a language without it)
            sink.report(USAGE_ERROR, None, detail=f"--start: a {frontend.title} project has no start to choose")
            return None
        return pipeline(path, sink, keep_going, progress, stubs_dir, strict, loaded, limits, keep_modules, **extra)
    return None


#: The Python frames a translation may use below its entry: what one from the command line had
#: under Python's default recursion limit of 1,000 (the CLI calls the pipeline 7 to 9 frames deep).
PIPELINE_FRAMES = 990


@contextmanager
def recursion_budget(frames: int) -> Iterator[None]:
    """Python's recursion limit is the current depth plus ``frames`` meanwhile (restored after).

    The analysis reports an expression nested past its recursion as GPL3005, and the limit is
    global, counted from the bottom of the stack: without a budget of its own, the same project
    gave GPL3005 from ``gpl2py check`` (one frame deeper) and nothing from ``translate``, and an
    internal error when a library caller (a test, a notebook) called it a few hundred frames deep.
    """
    depth = 0
    frame = sys._getframe()
    while frame is not None:
        depth += 1
        frame = frame.f_back
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(depth + frames)
    try:
        yield
    finally:
        sys.setrecursionlimit(limit)


@contextmanager
def collector_paused() -> Iterator[None]:
    """The collector policy of a translation and of ``gpl2py check``: the cyclic garbage
    collector is off from loading the project to the end of lowering, and back on (if it was)
    once the pipeline's locals -- sources, trees, symbols, the model -- are out of scope.

    The pipeline allocates millions of small token, tree and symbol objects that all live to the
    end; with the collector on, their allocation triggers collections that walk everything built
    so far, again and again, which cost more than the semantic pass itself.  Reference counting
    frees what can be freed meanwhile; the first collection after the pause walks what is left
    once (benchmarks/transpile_speed.py times it as part of the pipeline)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


__all__ = ["DATA_FOLDER", "PIPELINE_FRAMES", "Output", "Progress", "collector_paused", "recursion_budget",
           "transpile", "write_package"]
