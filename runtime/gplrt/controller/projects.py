"""The projects in a controller's memory: load, compile, start, stop, unload (``Session.projects``).

On a controller a project is deployed to ``/flash/projects/<name>/`` (by FTP), then loaded into
memory, compiled and started from the console (D1 §17 "Executing a Project": load, compile,
start).  Several projects may be in memory at once, each with its own threads (D1 §18).  This
module keeps that table for one session; the console's commands (``gplrt.controller.commands``)
and ``Controller.Load``/``Unload`` work on it.

The runtime cannot compile GPL: translating a project is the transpiler's business, and ``gplrt``
never imports ``gpl2py`` (tests/controller/test_import_graph.py).  So the table is handed a
:data:`Compiler` — a function from a project's name and files to a :class:`Program` — by whoever
composes the session (``gpl2py run`` gives ``gpl2py.deploy.compile_project``).  Without one,
``Compile`` is -204 *Not implemented*.  Loading (reading the files into memory) is the runtime's
own: it goes through the flash sandbox (``gplrt.io.project_files.read_controller_folder``), so the
compiler only ever sees bytes, never a host path.

Each loaded project has a :class:`~gplrt.session.ProjectScope`: its threads resolve procedure
names in its own registry and relative file names in its own folder, and ``Thread.Project``
reads its name.  The project the session was made for (``gpl2py run PROJECT``) is one of them,
with no scope: its threads are the session's own, as without a console.

The choices the manuals leave open are in docs/design/console.md.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from gplrt.io.project_files import PROJECTS, read_controller_folder
from gplrt.lang.errors import (
    FILE_NOT_FOUND,
    INVALID_PROJECT_FILE,
    INVALID_START_PROCEDURE,
    INVALID_WHEN_THREAD_ACTIVE,
    NOT_IMPLEMENTED,
    PROJECT_ALREADY_EXISTS,
    PROJECT_NOT_COMPILED,
    UNDEFINED_SYMBOL,
    GplException,
)
from gplrt.session import ProjectScope
from gplrt.threads.scheduler import current_ctx, external_wait
from gplrt.threads.thread import Thread

if TYPE_CHECKING:
    from gplrt.session import Session

__all__ = ["Compiler", "LoadedProject", "Program", "ProjectTable", "STOP_GRACE"]

#: Real seconds ``Stop`` waits for the threads of a project to end (they end at their next
#: scheduling point; a thread blocked in host code longer than this is reported still running).
STOP_GRACE = 2.0


@dataclass(frozen=True)
class Program:
    """A compiled project: what ``Start`` runs.

    ``start`` runs the project's module initialisation and its start procedure on the calling GPL
    thread (None: Project.gpr names no start procedure); ``thread_name`` is the name its thread
    gets (the start procedure's); ``warnings`` are the compiler's messages, shown by ``Compile``.
    """

    start: Callable[[], Any] | None
    thread_name: str
    warnings: tuple[str, ...] = ()


#: Translates a project (its name and its files, by name) into a :class:`Program`, or raises a
#: GplException: -742 *Compilation errors* (the detail says which), -743 *Invalid project file*.
Compiler = Callable[[str, dict[str, bytes]], Program]


@dataclass
class LoadedProject:
    """One project in memory: its files as they were when loaded, and its program once compiled."""

    name: str
    folder: str | None
    files: dict[str, bytes] = field(repr=False)
    #: None for the session's own project (its threads have no scope: ``gplrt.session``).
    scope: ProjectScope | None
    program: Program | None = None


class ProjectTable:
    """The projects in one session's memory, by name (case-insensitive, as GPL names are)."""

    def __init__(self, session: Session, compiler: Compiler | None = None) -> None:
        self.session = session
        self.compiler = compiler
        self._lock = threading.RLock()
        self._projects: dict[str, LoadedProject] = {}

    # -- what is in memory ---------------------------------------------------------------------------

    def names(self) -> list[str]:
        with self._lock:
            return [p.name for p in self._projects.values()]

    def get(self, name: str) -> LoadedProject:
        """The loaded project ``name``; -729 *Undefined symbol* when none has that name."""
        with self._lock:
            project = self._projects.get(name.lower())
        if project is None:
            raise GplException(UNDEFINED_SYMBOL, detail=f"no project {name!r} in memory")
        return project

    def threads(self, name: str | None = None) -> list[Thread]:
        """The session's GPL threads (all, or those of project ``name``), in start order."""
        threads = list(self.session.threads)
        if name is None:
            return threads
        return [t for t in threads if str(t.Project).lower() == name.lower()]

    def active_threads(self, name: str) -> list[Thread]:
        return [t for t in self.threads(name) if t._active]

    # -- load, compile, unload -------------------------------------------------------------------------

    def adopt(self, name: str, folder: str | None, program: Program) -> LoadedProject:
        """Put the session's own project (``gpl2py run PROJECT``, already compiled) in the table."""
        project = LoadedProject(name, folder, {}, None, program)
        with self._lock:
            self._projects[name.lower()] = project
        return project

    def load(self, path: str) -> LoadedProject:
        """``Load path``: read the project folder into memory (not compiled yet).

        ``path`` is a controller folder (``/flash/projects/Cell``) or a bare name, which means
        ``/flash/projects/<name>``.  The folder must hold a ``Project.gpr`` (-743 otherwise) and
        its name, the project's, must not be in memory already (-745)."""
        folder = controller_folder(path)
        name = folder.rstrip("/").rpartition("/")[2]
        with self._lock:
            if name.lower() in self._projects:
                raise GplException(PROJECT_ALREADY_EXISTS, detail=f"project {name!r} is in memory; Unload it first")
        with external_wait():  # on a GPL thread (Controller.Load): the others run meanwhile
            files = read_controller_folder(self.session.files, folder)
        if not any(n.lower() == "project.gpr" for n in files):
            raise GplException(INVALID_PROJECT_FILE, detail=f"{folder} has no Project.gpr")
        project = LoadedProject(name, folder, files, ProjectScope(name, folder))
        with self._lock:
            if name.lower() in self._projects:
                raise GplException(PROJECT_ALREADY_EXISTS, detail=f"project {name!r} is in memory; Unload it first")
            self._projects[name.lower()] = project
        return project

    def compile(self, name: str) -> Program:
        """``Compile name``: translate the files loaded; an idle project only (-750)."""
        project = self.get(name)
        self._check_idle(project)
        if self.compiler is None:
            raise GplException(NOT_IMPLEMENTED, detail="this session has no GPL compiler (gpl2py run gives it one)")
        if project.scope is None:
            assert project.program is not None
            return project.program  # the session's own project was compiled before it was adopted
        with external_wait():  # translating takes a while: a GPL caller's others run meanwhile
            program = self.compiler(project.name, dict(project.files))
        project.program = program
        return program

    def unload(self, name: str | None) -> list[str]:
        """``Unload name`` (None: every project): idle projects only (-750); returns the names."""
        with self._lock:
            chosen = list(self._projects.values()) if name is None else [self.get(name)]
            for project in chosen:
                self._check_idle(project)
            for project in chosen:
                del self._projects[project.name.lower()]
        return [p.name for p in chosen]

    def _check_idle(self, project: LoadedProject) -> None:
        busy = self.active_threads(project.name)
        if busy:
            raise GplException(INVALID_WHEN_THREAD_ACTIVE,
                               detail=f"project {project.name} has threads running: {', '.join(str(t.Name) for t in busy)}")

    # -- start, stop -----------------------------------------------------------------------------------

    def start(self, name: str) -> Thread:
        """``Start name``: run the compiled project's start procedure in a new thread.

        -753 *Project not compiled*; -744 *Invalid start procedure* when Project.gpr names none;
        -750 while the project has threads running; -749 when another thread has the name."""
        project = self.get(name)
        program = project.program
        if program is None:
            raise GplException(PROJECT_NOT_COMPILED, detail=f"Compile {project.name} first")
        if program.start is None:
            raise GplException(INVALID_START_PROCEDURE, detail=f"Project.gpr of {project.name} names no start procedure")
        self._check_idle(project)
        thread = Thread(program.start, 0, program.thread_name, _session=self.session, _project=project.scope)
        thread.Start()
        return thread

    def stop(self, name: str | None, grace: float = STOP_GRACE) -> list[str]:
        """``Stop name`` (None: every project): abort its threads and wait up to ``grace`` real
        seconds for them to end.  Returns the names of threads still running after that.

        Called from a GPL thread (``Controller.Command``) whose own project is stopped, the other
        threads are stopped first and the caller last, at its next scheduling point."""
        if name is not None:
            self.get(name)
        sched = self.session.scheduler
        me = current_ctx()
        targets = [t for t in self.threads(name) if t._active and t._ctx is not None]
        others = [t for t in targets if t._ctx is not me]
        for t in others:
            assert t._ctx is not None
            sched.request_abort(t._ctx)
        with external_wait():  # a GPL caller (Controller.Command) lets them run to their end
            sched.wait_until_quiet([t._ctx for t in others if t._ctx is not None], grace)
        if len(others) != len(targets):
            sched.request_abort(me)  # type: ignore[arg-type]
        return [str(t.Name) for t in others if t._active]


def controller_folder(path: str) -> str:
    """The controller folder a ``Load`` argument names: a path as given, a bare name below
    ``/flash/projects`` (-508 for an empty name)."""
    text = path.strip().rstrip("/")
    if not text:
        raise GplException(FILE_NOT_FOUND, detail="no project folder given")
    return text if text.startswith("/") else f"{PROJECTS}/{text}"
