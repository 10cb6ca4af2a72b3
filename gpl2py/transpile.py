"""The pipeline: project -> diagnostics -> files (issue "Core language", part 1).

``transpile(path, sink)`` loads the project, parses every source, runs the semantic analysis and
lowers each module; it returns the generated files (relative path -> text) or ``None`` when there
were errors (unless ``keep_going``).  ``write_package`` writes them below an output folder.  Output
is deterministic: identical input gives byte-identical files.

A library caller (a notebook, the test harness) gets the promise the command line gives: an
unexpected exception in any phase -- loading, parsing, semantics or lowering -- is a GPL9000
internal-error diagnostic and ``None``, never a traceback.  It is contained to the file or module
where it happened (``diagnostics.contained``): each file is parsed, each module analysed and
lowered on its own, so the other files' diagnostics are all reported.  ``GPL2PY_TRACEBACK=1``
re-raises it, as it does for the CLI, so a gpl2py developer can still see where it came from.

``gpl2py check`` runs this same pipeline without keeping the generated text (``keep_modules``),
so it reports exactly what ``translate`` reports, in every case.
"""

from __future__ import annotations

import gc
import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink, contained
from gpl2py.lower.context import ProjectNames
from gpl2py.lower.module import lower_module
from gpl2py.lower.names import package_name
from gpl2py.lower.package import package_init, package_main
from gpl2py.lower.sourcemap import runs_json, sourcemap_json
from gpl2py.lower.stubs import stub_files
from gpl2py.lower.user_stubs import (
    SHIPPED_PREFIX,
    USER_PREFIX,
    UserStubs,
    load_user_stubs,
    with_shipped_standins,
)
from gpl2py.project import Limits, Project, load_project, read_data_files
from gpl2py.semantics.catalogue import load_catalogue
from gpl2py.semantics.check import Model, analyze
from gpl2py.semantics.resolve import TOP_MODULE
from gpl2py.source import make_span
from gpl2py.syntax.parser import parse


@dataclass
class Output:
    """The generated package: ``files`` maps paths relative to the output folder to their text."""

    package: str
    files: dict[str, str] = field(default_factory=dict)
    project: Project | None = None
    #: The project's own files (name -> bytes), written to ``<package>/_project_files/`` so that
    #: ``python -m <package>`` installs them where the controller has them (package_main)
    data_files: dict[str, bytes] = field(default_factory=dict)


Progress = Callable[[str, int, int], None]
#: Where a written package keeps the project's own files (``Output.data_files``).
DATA_FOLDER = "_project_files"


def transpile(path: str | os.PathLike[str], sink: DiagnosticSink, keep_going: bool = False,
              progress: Progress | None = None, *, stubs_dir: str | os.PathLike[str] | None = None,
              strict: bool = False, loaded: Callable[[Project], None] | None = None,
              limits: Limits | None = None, keep_modules: bool = True) -> Output | None:
    """``progress(phase, done, total)``, when given, is called per file parsed and module written
    (``gpl2py.progress.ProgressBar`` draws it).  ``stubs_dir``: user implementations of stubs
    (``gpl2py.lower.user_stubs``); ``strict``: every stub is an error (``gpl2py.semantics.stubs``).
    ``loaded(project)`` is called once the project is loaded, so a caller can count its files even
    when the translation fails.  ``limits``: how much input may be read (``project.Limits``;
    default from the environment).  ``keep_modules=False`` (``gpl2py check``): the diagnostics
    only, each module's text dropped once made (:func:`lower`) and no project files read.

    The cyclic garbage collector is paused meanwhile (:func:`collector_paused`), and the pipeline
    has the same stack whoever calls it (:func:`recursion_budget`).
    """
    with collector_paused(), recursion_budget(PIPELINE_FRAMES), contained(sink, None):  # never a traceback
        return _transpile(path, sink, keep_going, progress, stubs_dir, strict, loaded, limits, keep_modules)
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


def _transpile(path: str | os.PathLike[str], sink: DiagnosticSink, keep_going: bool,
               progress: Progress | None, stubs_dir: str | os.PathLike[str] | None = None,
               strict: bool = False, loaded: Callable[[Project], None] | None = None,
               limits: Limits | None = None, keep_modules: bool = True) -> Output | None:
    loading = DiagnosticSink()  # unfiltered: whether a file failed to load, reported or ignored
    project = load_project(path, loading, limits)
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


def write_package(output: Output, out_dir: str | os.PathLike[str], sink: DiagnosticSink) -> bool:
    """Write the files below ``out_dir`` (a previous package of the same name is replaced file by
    file; stale modules of an earlier run are removed)."""
    root = Path(out_dir)
    pkg = root / output.package
    try:
        pkg.mkdir(parents=True, exist_ok=True)
        wanted = {Path(rel).name for rel in output.files}
        for old in pkg.glob("*.py"):
            if old.name not in wanted:
                old.unlink()
        for rel, text in sorted(output.files.items()):
            target = root / rel
            target.write_text(text, encoding="utf-8", newline="\n")
        data = pkg / DATA_FOLDER
        if data.is_dir():
            import shutil  # (here: only writing needs it, check does not)

            shutil.rmtree(data)
        if output.data_files:
            data.mkdir()
            for name, blob in sorted(output.data_files.items()):
                (data / name).write_bytes(blob)
    except OSError as exc:
        sink.report(M.OUTPUT_ERROR, None, path=str(pkg), detail=exc.strerror or str(exc))
        return False
    return True
