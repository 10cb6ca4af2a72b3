"""The compiler the simulated controller's console uses: a loaded project, translated and imported.

The runtime keeps the projects in the controller's memory (``gplrt.controller.projects``) and
reads their files from its flash disk, but cannot translate GPL: ``gplrt`` never imports
``gpl2py``.  ``gpl2py run`` hands its session :func:`compiler` (``Simulation(compiler=...)``), giving it its
own ``build`` and ``import_built`` (this module cannot import ``gpl2py.run``, which imports it);
the console's ``Compile`` (and ``Controller.Load``) then calls it with the project's name and
files, and gets a ``gplrt.controller.projects.Program`` to start.

The files arrive as bytes, read from ``/flash/projects/<name>/`` through the flash sandbox: they
are written into a fresh temporary folder (their names are controller file names already, plain
and checked) and translated from there through the cache like any ``gpl2py run``, so the
translation never reads a host path the program chose.  Diagnostics name the controller's files
(``/flash/projects/Cell/Main.gpl:3:5: error GPL2001: ...``).
"""

from __future__ import annotations

import tempfile
from collections.abc import Callable
from pathlib import Path
from types import ModuleType
from typing import Any

from gplrt.controller.projects import Program
from gplrt.io.project_files import PROJECTS
from gplrt.lang.errors import COMPILATION_ERRORS, INVALID_PROJECT_FILE, GplException
from gplrt.lang.exceptions import gpl_entry
from gplrt.lang.procedures import registry_for

from gpl2py.diagnostics import Diagnostic, DiagnosticSink
from gpl2py.source import make_span

#: ``gpl2py.run.build`` and ``gpl2py.run.import_built``, handed in by ``run`` (which imports this
#: module): how a project folder is translated through the cache, and how its package is imported.
Build = Callable[..., Any]
Import = Callable[[Any], ModuleType]

__all__ = ["compiler", "program_of"]

#: At most this many diagnostics are quoted in a -742 reply; the rest are counted.
MAX_QUOTED = 20


def compiler(build: Build, import_built: Import,
             cache_dir: str | Path | None = None) -> Callable[[str, dict[str, bytes]], Program]:
    """A compiler for ``Simulation(compiler=...)`` that translates with ``build`` through the
    cache in ``cache_dir`` (the run's) and imports with ``import_built``."""

    def compile_project(name: str, files: dict[str, bytes]) -> Program:
        return compile_files(name, files, build, import_built, cache_dir=cache_dir)

    return compile_project


def compile_files(name: str, files: dict[str, bytes], build: Build, import_built: Import, *,
                  cache_dir: str | Path | None = None) -> Program:
    """Translate the project ``name`` made of ``files`` and import it; -742 *Compilation errors*
    when it has errors (the detail quotes them), -743 when it has no Project.gpr."""
    if not any(n.lower() == "project.gpr" for n in files):
        raise GplException(INVALID_PROJECT_FILE, detail=f"project {name} has no Project.gpr")
    shown = f"{PROJECTS}/{name}"
    with tempfile.TemporaryDirectory(prefix="gpl2py-load-") as tmp:
        folder = Path(tmp) / name
        folder.mkdir()
        for file, data in files.items():
            (folder / file).write_bytes(data)
        sink = DiagnosticSink()
        built = build(folder, sink, cache_dir=cache_dir)
        messages = [_shown(d, folder, shown) for d in sink.sorted()]
        if built is None:
            errors = [m for m, d in zip(messages, sink.sorted()) if d in sink.errors] or messages
            quoted = errors[:MAX_QUOTED]
            if len(errors) > MAX_QUOTED:
                quoted.append(f"... and {len(errors) - MAX_QUOTED} more")
            raise GplException(COMPILATION_ERRORS, detail="\n".join(quoted))
        package = import_built(built)
    return program_of(package, tuple(messages))


def program_of(package: ModuleType, warnings: tuple[str, ...] = ()) -> Program:
    """What ``Start`` runs of a generated package: its ``init()`` then its start procedure, on
    the thread ``Start`` makes (named after the procedure, as ProjectStart's thread is)."""
    start = package.PROJECT.get("start")
    if not start:
        return Program(None, "", warnings)
    if package.PROJECT.get("language", "gpl") != "gpl":  # another front end's package names its
        procedure = package.start_program  # start itself (V+: the start program, as task 0)
    else:  # (a GPL module may be called start_program: GPL's start is found by its name)
        procedure = registry_for(package.__name__).find(start).func
    init = package.init

    def run_project() -> None:
        init()
        procedure()

    thread_name = start.rpartition(".")[2]
    run_project.__gpl_name__ = thread_name  # type: ignore[attr-defined]
    return Program(gpl_entry(run_project), thread_name, warnings)


def _shown(diag: Diagnostic, folder: Path, shown: str) -> str:
    """The diagnostic's line, naming the file as the controller has it."""
    span = diag.span
    if span is not None:
        file = Path(span.file)
        name = file.name if file.parent == folder else span.file
        span = make_span(f"{shown}/{name}", span.line, span.col, span.end_line, span.end_col)
    return Diagnostic(diag.severity, diag.code, diag.message, span).header()
