"""The GPL front end's pipeline: a GPL project -> diagnostics -> the generated package's files.

Loads the project (``Project.gpr``, a folder of ``.gpl`` files or one file), parses every source,
runs the semantic analysis and lowers each module.  :func:`gpl2py.transpile.transpile` is the
door every caller uses: it picks the front end (docs/design/frontends.md), pauses the collector,
gives the pipeline its recursion budget and contains an internal error; this module is what it
calls for GPL.  Each file is parsed and each module analysed and lowered inside
``diagnostics.contained``, so a bug in one file leaves the other files' diagnostics reported.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink, contained
from gpl2py.gpl.lower.context import ProjectNames
from gpl2py.gpl.lower.module import lower_module
from gpl2py.gpl.lower.names import package_name
from gpl2py.gpl.lower.package import package_init, package_main
from gpl2py.gpl.lower.stubs import stub_files
from gpl2py.gpl.lower.user_stubs import (
    SHIPPED_PREFIX,
    USER_PREFIX,
    UserStubs,
    load_user_stubs,
    with_shipped_standins,
)
from gpl2py.gpl.semantics.catalogue import load_catalogue
from gpl2py.gpl.semantics.check import Model, analyze
from gpl2py.gpl.semantics.resolve import TOP_MODULE
from gpl2py.gpl.syntax.parser import parse
from gpl2py.output import Output, Progress
from gpl2py.project import Limits, Project, load_project, read_data_files
from gpl2py.pywriter.sourcemap import runs_json, sourcemap_json
from gpl2py.source import make_span


def transpile_project(path: str | os.PathLike[str], sink: DiagnosticSink, keep_going: bool,
                      progress: Progress | None, stubs_dir: str | os.PathLike[str] | None = None,
                      strict: bool = False, loaded: Callable[[Project], None] | None = None,
                      limits: Limits | None = None, keep_modules: bool = True,
                      start: str | None = None) -> Output | None:
    """The GPL translation of ``path``; the arguments are :func:`gpl2py.transpile.transpile`'s
    (``start``, from ``--start``, replaces Project.gpr's ProjectStart)."""
    loading = DiagnosticSink()  # unfiltered: whether a file failed to load, reported or ignored
    project = load_project(path, loading, limits)
    if project is not None and start is not None:
        project.start, project.start_span = start, None
    if project is not None and loaded is not None:
        loaded(project)  # (before the loading's diagnostics pass the sink's filter: its comments)
    sink.extend(loading)
    if project is None:
        return None
    user = load_user_stubs(stubs_dir, sink) if stubs_dir is not None else None
    if stubs_dir is None or user is not None:  # (a bad --stubs folder is already an error)
        user = with_shipped_standins(user, sink)
    protected = bool(project.protected)
    units = []
    for i, src in enumerate(project.sources):
        with contained(sink, make_span(src.path, 1, 1, 1, 1)):  # a bug in one file: the others go on
            units.append(parse(src, sink))
        if progress is not None:
            progress("parsing", i + 1, len(project.sources))
    # the semantic pass runs even after syntax errors, so every error is reported in one run; a
    # file that failed to load (or to parse) may declare the start procedure, not looked for then
    missing = loading.has_errors() or len(units) < len(project.sources)
    model = analyze(units, sink, load_catalogue(), project.name, project.start, protected=protected,
                    strict=strict, stub_provider=user.provider if user is not None else None,
                    start_span=project.start_span, sources_missing=missing)
    if sink.has_errors() and not keep_going:
        return None
    output = lower(project, model, sink, progress, user, keep_modules=keep_modules)
    if sink.has_errors() and not keep_going:  # lowering errors (illegal GoTo ...)
        return None
    if keep_modules:
        output.data_files = _project_data(Path(path), project)
    return output


def _project_data(given: Path, project: Project) -> dict[str, bytes]:
    """The files the controller's project folder holds: every regular file of a project folder
    (read without following links: ``project.read_data_files``); for one source file, that file."""
    if given.is_dir() or given.name.lower() == "project.gpr":
        return read_data_files(project.root)
    return {k: v for k, v in read_data_files(given.parent).items() if k == given.name}


def lower(project: Project, model: Model, sink: DiagnosticSink,
          progress: Progress | None = None, user: UserStubs | None = None, *,
          keep_modules: bool = True) -> Output:
    """The generated files of an analysed project.  ``gpl2py check`` runs it for the lowering's
    diagnostics only, with ``keep_modules=False``: each module's text is dropped as soon as it is
    made (with the whole analysis alive, holding every module's text was a tenth of the memory)."""
    start = model.start
    if project.start is None and start is not None and start.module is not None:
        # no ProjectStart: the package will run the only Public Sub Main (semantics/check.py)
        sink.report(M.START_ASSUMED_MAIN, start.span, name=f"{start.module.name}.{start.name}")
    names = ProjectNames.build(model)
    package = package_name(project.name)
    out = Output(package, project=project)
    smap: dict[str, tuple[str, str]] = {}
    modules = list(model.project.module_list)
    extra = []
    top = model.project.modules.get(TOP_MODULE.lower())
    if top is not None:
        extra.append(top)
    entries: dict[str, frozenset[str]] = {}
    for i, mod in enumerate(extra + modules):
        with contained(sink, mod.span):  # a bug in one module: the others are still lowered
            text, gmap, entries[mod.py_name] = lower_module(model, names, mod, sink)
            if keep_modules:
                fname = f"{mod.py_name}.py"
                out.files[f"{package}/{fname}"] = text
                smap[fname] = (mod.path, runs_json(gmap))
            del text, gmap
        if progress is not None:
            progress("writing", i + 1, len(extra) + len(modules))
    stub_texts, records = stub_files(model.stubs, names.stub_module_py, names.stub_attr_py, package, user) \
        if model.stubs is not None and model.stubs.stubs else ({}, [])
    out.files.update(stub_texts)
    stub_modules = sorted({Path(rel).stem for rel in stub_texts
                           if not Path(rel).stem.startswith((USER_PREFIX, SHIPPED_PREFIX))})
    out.files[f"{package}/__init__.py"] = package_init(model, project.name, project.start, modules, extra,
                                                       records, stub_modules, names.proc_name, entries)
    out.files[f"{package}/__main__.py"] = package_main()
    out.files[f"{package}/_sourcemap.json"] = sourcemap_json(smap)
    return out
