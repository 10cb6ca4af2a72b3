"""The controller's console commands: what Telnet and ``Controller.Command`` reach.

A controller has one command console, reached over Telnet, the serial port, the web page and
from GPL by ``Controller.Command`` (D0:2580, "Executes a console command and returns any output
as a String value").  :class:`ConsoleCommands` is that console for one session: it parses a
command line and runs it on the session's project table (``gplrt.controller.projects``) and
disks.  The Telnet server (``gplrt.controller.telnet``) and ``Controller.Command``
(``gplrt.controller.services``) both call :meth:`ConsoleCommands.execute`.

The commands a deploying client needs (docs/design/console.md has each reply and error)::

    Load path              read /flash/projects/<name> (or a bare name) into memory
    Compile project        translate a loaded project
    Start [-event] project run its start procedure in a new thread
    Stop project | -all    abort the project's threads
    Unload project | -all  remove an idle project from memory
    Show Thread            every thread of the projects in memory, and its state
    Show Project           every project in memory, and its state
    Dir [-stat] [path]     the files and folders of a controller folder (default /flash)
    Del path               delete a file
    Help                   this list

Command and switch names are case-insensitive and may be shortened to any unique prefix
(``sh th``); an ambiguous one is -716 *Ambiguous abbreviation*, an unknown one -714 *Unknown
command*.  A command that succeeds and has nothing to show returns "" (the console prints only its
prompt); a failure raises the GplException with the controller's code, which the Telnet server
prints as ``-745 *Project already exists*`` and ``Controller.Command`` raises to the program.
"""

from __future__ import annotations

import shlex
from collections.abc import Callable
from dataclasses import dataclass

from gplrt.controller.projects import LoadedProject, ProjectTable
from gplrt.io.files import _file_error, folder_entries
from gplrt.io.sandbox import Kind
from gplrt.lang.errors import (
    AMBIGUOUS_ABBREVIATION,
    INVALID_ARGUMENT,
    INVALID_FILE_TYPE,
    MISSING_ARGUMENT,
    MISSING_QUOTE_MARK,
    UNKNOWN_COMMAND,
    WRITE_ERROR,
    GplException,
)
from gplrt.threads.thread import Thread, ThreadStateValue

__all__ = ["ConsoleCommands"]

#: Width of the name columns of ``Show Thread`` and ``Show Project``.
_COLUMN = 20


@dataclass(frozen=True)
class _Command:
    name: str
    usage: str
    run: Callable[[list[str]], str]


def _pick(word: str, choices: list[str], what: str) -> str:
    """The one of ``choices`` that ``word`` names, whole or as a unique prefix (case-insensitive)."""
    low = word.lower()
    exact = [c for c in choices if c.lower() == low]
    if exact:
        return exact[0]
    found = [c for c in choices if c.lower().startswith(low)]
    if len(found) == 1:
        return found[0]
    if found:
        raise GplException(AMBIGUOUS_ABBREVIATION, detail=f"{word!r} could be {', '.join(found)}")
    raise GplException(UNKNOWN_COMMAND, detail=f"{what} {word!r}")


class ConsoleCommands:
    """The console of one session (module docstring)."""

    def __init__(self, projects: ProjectTable) -> None:
        self.projects = projects
        self.session = projects.session
        self._commands = {c.name: c for c in [
            _Command("Load", "Load path", self._load),
            _Command("Compile", "Compile project", self._compile),
            _Command("Start", "Start [-event] project", self._start),
            _Command("Stop", "Stop project | -all", self._stop),
            _Command("Unload", "Unload project | -all", self._unload),
            _Command("Show", "Show Thread | Project", self._show),
            _Command("Dir", "Dir [-stat] [path]", self._dir),
            _Command("Del", "Del path", self._del),
            _Command("Help", "Help", self._help),
        ]}

    def execute(self, line: str) -> str:
        """Run one command line; its output (lines separated by LF, no final LF), or a
        GplException.  An empty line does nothing."""
        try:
            words = shlex.split(line)
        except ValueError:
            raise GplException(MISSING_QUOTE_MARK, detail=line) from None
        if not words:
            return ""
        command = self._commands[_pick(words[0], list(self._commands), "command")]
        return command.run(words[1:])

    # -- projects -------------------------------------------------------------------------------------

    def _load(self, args: list[str]) -> str:
        path = _one(args, "a project folder")
        self.projects.load(path)
        return ""

    def _compile(self, args: list[str]) -> str:
        program = self.projects.compile(_one(args, "a project name"))
        return "\n".join(program.warnings)

    def _start(self, args: list[str]) -> str:
        switches, rest = _switches(args, ["event"])
        # -event sends the project's console output to GDE (D0:3972): here it always goes to the
        # run's own console, so the switch is accepted and changes nothing.
        del switches
        self.projects.start(_one(rest, "a project name"))
        return ""

    def _stop(self, args: list[str]) -> str:
        name = self._project_or_all(args)
        still = self.projects.stop(name)
        return f"still stopping: {', '.join(still)}" if still else ""

    def _unload(self, args: list[str]) -> str:
        self.projects.unload(self._project_or_all(args))
        return ""

    def _project_or_all(self, args: list[str]) -> str | None:
        switches, rest = _switches(args, ["all"])
        if "all" in switches:
            if rest:
                raise GplException(INVALID_ARGUMENT, detail="-all and a project name")
            return None
        return _one(rest, "a project name or -all")

    # -- show -------------------------------------------------------------------------------------------

    def _show(self, args: list[str]) -> str:
        what = _pick(_one(args, "Thread or Project"), ["Thread", "Project"], "Show")
        return self._show_threads() if what == "Thread" else self._show_projects()

    def _show_threads(self) -> str:
        """One line per thread: the latest thread of each name in each project in memory, and any
        other thread still running (a thread of the notebook, say)."""
        in_memory = {n.lower() for n in self.projects.names()}
        latest: dict[tuple[str, str], Thread] = {}
        for t in self.projects.threads():
            project = str(t.Project)
            if project.lower() in in_memory or t._active:
                latest[(project.lower(), str(t.Name).lower())] = t
        lines = [f"{'Project':<{_COLUMN}} {'Thread':<{_COLUMN}} State"]
        for t in latest.values():
            state = ThreadStateValue(t.ThreadState).name.capitalize()
            lines.append(f"{str(t.Project):<{_COLUMN}} {str(t.Name):<{_COLUMN}} {state}")
        return "\n".join(lines)

    def _show_projects(self) -> str:
        lines = [f"{'Project':<{_COLUMN}} {'State':<10} Folder"]
        for name in self.projects.names():
            project = self.projects.get(name)
            lines.append(f"{project.name:<{_COLUMN}} {self._state(project):<10} {project.folder or ''}")
        return "\n".join(lines)

    def _state(self, project: LoadedProject) -> str:
        if self.projects.active_threads(project.name):
            return "Running"
        return "Compiled" if project.program is not None else "Loaded"

    # -- files ------------------------------------------------------------------------------------------

    def _dir(self, args: list[str]) -> str:
        switches, rest = _switches(args, ["stat"])
        if len(rest) > 1:
            raise GplException(INVALID_ARGUMENT, detail=f"Dir takes one folder, not {len(rest)}")
        path = rest[0] if rest else "/flash"
        where = self.session.files.root().resolve(path)
        entries = folder_entries(where, path)
        assert where.file is not None
        lines = [f"Directory of {where.text.rstrip('/') or '/'}"]
        files = total = 0
        for name, kind in sorted(entries, key=lambda e: e[0].lower()):
            if name.startswith(".") or kind is Kind.OTHER:
                continue  # no controller name starts with "."; links and devices are not shown
            if kind is Kind.FOLDER:
                lines.append(f"{'<DIR>':>12}  {name}")
                continue
            found = where.file.box.path(*where.file.parts, name).lstat()
            size = found.st_size if found is not None else 0
            files, total = files + 1, total + size
            lines.append(f"{size:>12}  {name}")
        if "stat" in switches:
            lines.append(f"{files} file{'s' if files != 1 else ''}, {total} bytes")
        return "\n".join(lines)

    def _del(self, args: list[str]) -> str:
        path = _one(args, "a file")
        where = self.session.files.root().resolve(path)
        if where.file is None:
            raise GplException(INVALID_FILE_TYPE, detail=f"{path!r} is a device")
        try:
            where.file.unlink()
        except OSError as exc:
            raise _file_error(exc, path, WRITE_ERROR) from None
        return ""

    def _help(self, args: list[str]) -> str:
        return "\n".join(c.usage for c in self._commands.values())


def _one(args: list[str], what: str) -> str:
    """The one argument a command takes: -205 *Missing argument* without it, -202 with more."""
    if not args:
        raise GplException(MISSING_ARGUMENT, detail=f"expected {what}")
    if len(args) > 1:
        raise GplException(INVALID_ARGUMENT, detail=f"expected {what}, got {' '.join(args)}")
    return args[0]


def _switches(args: list[str], known: list[str]) -> tuple[set[str], list[str]]:
    """The ``-switch`` words of ``args`` (by unique prefix of ``known``) and the other words."""
    switches: set[str] = set()
    rest: list[str] = []
    for word in args:
        if word.startswith("-") and len(word) > 1:
            switches.add(_pick(word[1:], known, "switch").lower())
        else:
            rest.append(word)
    return switches, rest
