"""The language server's workspace: which project each file belongs to, and each project's warm state.

A file belongs to the project of its folder: the folder's ``Project.gpr`` when there is one and it
lists the file (a controller's project is one flat folder), else the folder's sources, as
``gpl2py check FOLDER`` reads them; a file its folder's ``Project.gpr`` does not list is checked
alone, as ``gpl2py check FILE`` would.  Several projects in one workspace are each their own
:class:`ProjectState`.

Checking is ``gpl2py check``'s own pipeline, through the one door (``gpl2py.transpile``), with
two additions the door offers every front end: the editor's unsaved texts in place of the files'
(``texts``), and a ``memo`` the front end keeps its per-file work in between checks.  So the
diagnostics are exactly ``check``'s for the same text, whatever the language, and an edit
re-parses only the file that changed (docs/design/lsp.md: why the semantic pass is run whole).
``[tool.gpl2py]`` applies as in ``check``: the table is found from the workspace folder the server
was started for (an editor starts it there, as a user runs ``check`` there), and its ``select``,
``ignore``, ``stubs``, ``strict`` and ``max-source-mb`` are used.
"""

from __future__ import annotations

import os
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py.config import Config, discover
from gpl2py.diagnostics import Diagnostic, DiagnosticSink
from gpl2py.languages import Frontend, frontend_for
from gpl2py.project import PROJECT_FILE, Limits, Project
from gpl2py.selection import Selection, parse_codes


@dataclass
class CheckResult:
    """One check of a project: the diagnostics of each of its files (every file of the project is
    a key, an empty list clearing what was published before), and how long it took."""

    by_file: dict[str, list[Diagnostic]]
    files: dict[str, str]  # absolute path -> the text that was checked
    seconds: float


@dataclass
class ProjectState:
    """One project held in memory: where it is, its language, and the front end's memo (for GPL
    the parsed tree of every file and the last analysis: ``gpl2py.gpl.pipeline.MODEL_KEY``)."""

    path: str  # what ``gpl2py check`` is given: the folder, or one file
    frontend: Frontend
    memo: dict[object, object] = field(default_factory=dict)
    last: CheckResult | None = None

    def check(self, texts: Mapping[str, str], config: Config) -> CheckResult:
        """Check the project with ``texts`` (absolute path -> text) in place of those files."""
        from gpl2py.transpile import transpile

        started = time.perf_counter()
        select = parse_codes(config.select, "select") if config.select is not None else None
        ignore = parse_codes(config.ignore, "ignore") if config.ignore is not None else ()
        sink = DiagnosticSink(Selection(select, ignore))
        files: dict[str, str] = {}
        anchor: list[str] = []

        def loaded(project: Project) -> None:
            if sink.filter is not None:
                sink.filter.add_sources(project.sources, sink)  # their ' gpl2py: ignore comments
            for f in project.files():
                files[os.path.abspath(f.path)] = f.text
            anchor.append(os.path.abspath(project.files()[0].path) if project.files() else self.path)

        limits = Limits.of_mb(config.max_source_mb) if config.max_source_mb is not None else None
        transpile(self.path, sink, stubs_dir=config.stubs, strict=bool(config.strict), loaded=loaded,
                  limits=limits, keep_modules=False, language=self.frontend.name, texts=texts, memo=self.memo)
        by_file: dict[str, list[Diagnostic]] = {p: [] for p in files}
        for d in sink.sorted():
            where = os.path.abspath(d.span.file) if d.span is not None else (anchor[0] if anchor else self.path)
            by_file.setdefault(where, []).append(d)
        self.last = CheckResult(by_file, files, time.perf_counter() - started)
        return self.last


class Workspace:
    """Every project the editor has opened a file of, keyed by what ``check`` is given."""

    def __init__(self, root: str | None = None) -> None:
        self.root = root
        self.projects: dict[str, ProjectState] = {}
        self.texts: dict[str, str] = {}  # the open documents: absolute path -> the editor's text

    def config(self) -> Config:
        """``[tool.gpl2py]`` as ``gpl2py check`` run in the workspace folder finds it (raises
        ConfigError, which the server reports to the client and then checks with none)."""
        return discover(None, False, cwd=Path(self.root) if self.root else None)

    def project_of(self, path: str) -> ProjectState:
        """The project ``path`` (an absolute file path) belongs to, made on first use."""
        key = project_path(path)
        state = self.projects.get(key)
        if state is None:
            state = self.projects[key] = ProjectState(key, frontend_for(key))
        return state


def project_path(path: str) -> str:
    """What ``gpl2py check`` is given for the project of the file ``path``: its folder, unless the
    folder's ``Project.gpr`` does not list the file (then the file alone)."""
    folder = os.path.dirname(path)
    gpr = _project_file(folder)
    if gpr is None:
        return folder
    name = os.path.basename(path).lower()
    try:
        text = Path(gpr).read_text(encoding="utf-8", errors="replace")[:2**20]
    except OSError:
        return folder
    listed = {line.split("=", 1)[1].strip().strip('"').lower() for line in text.splitlines()
              if line.strip().lower().startswith("projectsource") and "=" in line}
    return folder if name in listed or name == PROJECT_FILE.lower() else path


def _project_file(folder: str) -> str | None:
    try:
        return next((os.path.join(folder, n) for n in os.listdir(folder) if n.lower() == PROJECT_FILE.lower()), None)
    except OSError:
        return None


__all__ = ["CheckResult", "ProjectState", "Workspace", "project_path"]
