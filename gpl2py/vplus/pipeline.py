"""The V+ front end's pipeline: a V+ project -> diagnostics -> the generated package's files.

Loads the files (:mod:`gpl2py.vplus.loader`), parses each (:mod:`gpl2py.vplus.syntax.parser`),
analyses them together (:mod:`gpl2py.vplus.semantics.check`: programs, scopes, types) and lowers
the project to Python on the V+ runtime layer (:mod:`gpl2py.vplus.lower`).  It is what
:func:`gpl2py.transpile.transpile` calls for ``--language vplus`` or for files it recognises as V+;
each file is parsed inside ``diagnostics.contained``, so a bug in one leaves the others reported.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, MutableMapping

from gpl2py.diagnostics import DiagnosticSink, contained
from gpl2py.output import Output, Progress
from gpl2py.project import Limits, Project, swap_texts
from gpl2py.source import make_span
from gpl2py.vplus.loader import load_project
from gpl2py.vplus.semantics.check import analyze
from gpl2py.vplus.syntax.parser import parse

#: Where :func:`transpile_project` leaves the parsed files in ``memo``.
MODULES_KEY = "vplus-modules"


def transpile_project(path: str | os.PathLike[str], sink: DiagnosticSink, keep_going: bool,
                      progress: Progress | None, stubs_dir: str | os.PathLike[str] | None = None,
                      strict: bool = False, loaded: Callable[[Project], None] | None = None,
                      limits: Limits | None = None, keep_modules: bool = True,
                      start: str | None = None, *, texts: Mapping[str, str] | None = None,
                      memo: MutableMapping[object, object] | None = None) -> Output | None:
    """The V+ translation of ``path``; the arguments are :func:`gpl2py.transpile.transpile`'s
    (``stubs_dir`` and ``strict`` concern GPL's protected code and mean nothing here), and
    ``start`` the program to run (``--start``; default the first program of the first file).
    ``texts`` and ``memo`` serve the language server (docs/design/frontends.md): the editor's text
    of some files in place of theirs, and where the parsed files are left (:data:`MODULES_KEY`)."""
    loading = DiagnosticSink()
    project = load_project(path, loading, limits)
    if project is not None and texts:
        swap_texts(project, texts)
    if project is not None and start is not None:
        project.start = start
    if project is not None and loaded is not None:
        loaded(project)
    sink.extend(loading)
    if project is None:
        return None
    modules = []
    for i, src in enumerate(project.sources):
        with contained(sink, make_span(src.path, 1, 1, 1, 1)):
            modules.append(parse(src, sink))
        if progress is not None:
            progress("parsing", i + 1, len(project.sources))
    if memo is not None:
        memo[MODULES_KEY] = modules  # (the language server's outline reads them: gpl2py/lsp/vplus.py)
    model = analyze(modules, sink, project.start)
    if sink.has_errors() and not keep_going:
        return None
    from gpl2py.vplus.lower.package import lower_project

    output = lower_project(project, modules, model, sink, keep_modules=keep_modules)
    if sink.has_errors() and not keep_going:
        return None
    return output
