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
from collections.abc import Callable, Mapping, MutableMapping
from pathlib import Path

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink, contained
from gpl2py.gpl.lower.context import LocalsTaken, ProjectNames
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
from gpl2py.gpl.semantics.symbols import ClassSym, ModuleSym
from gpl2py.gpl.semantics.warm import WarmAnalysis, analyze_warm, shift_analysis
from gpl2py.gpl.syntax.parser import parse
from gpl2py.gpl.syntax.reparse import reparse_procedure
from gpl2py.gpl.syntax.shift import Moves, Shift
from gpl2py.output import Output, Progress
from gpl2py.project import Limits, Project, load_project, read_data_files, swap_texts
from gpl2py.pywriter.sourcemap import runs_json, sourcemap_json
from gpl2py.gpl.syntax import ast as A
from gpl2py.source import SourceFile, make_span


#: Where :func:`transpile_project` leaves the analysed project in ``memo``: (project, units, model).
MODEL_KEY = "gpl-model"
#: Where it keeps the analysis it checks again after an edit (``semantics.warm.WarmAnalysis``).
WARM_KEY = "gpl-warm"
#: Where the lowering keeps which locals' names each procedure keeps from the package's names.
LOCALS_KEY = "gpl-locals"


def transpile_project(path: str | os.PathLike[str], sink: DiagnosticSink, keep_going: bool,
                      progress: Progress | None, stubs_dir: str | os.PathLike[str] | None = None,
                      strict: bool = False, loaded: Callable[[Project], None] | None = None,
                      limits: Limits | None = None, keep_modules: bool = True,
                      start: str | None = None, *,
                      texts: Mapping[str, str] | None = None,
                      memo: MutableMapping[object, object] | None = None) -> Output | None:
    """The GPL translation of ``path``; the arguments are :func:`gpl2py.transpile.transpile`'s
    (``start``, from ``--start``, replaces Project.gpr's ProjectStart).

    ``texts``: the text of some sources by absolute path, in place of what the files hold (an
    editor's unsaved buffers); ``memo``: where the parsed tree of each source is kept between
    calls, keyed by its path and text, so that a caller checking again after an edit (the
    language server) parses only the files that changed.  A tree is reused with the diagnostics
    its parse reported, replayed into ``sink``: the result is the same as a cold run's."""
    loading = DiagnosticSink()  # unfiltered: whether a file failed to load, reported or ignored
    project = load_project(path, loading, limits)
    if project is not None and texts:
        swap_texts(project, texts)
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
            units.append(parse(src, sink) if memo is None else _parse_memo(src, sink, memo))
        if progress is not None:
            progress("parsing", i + 1, len(project.sources))
    # the semantic pass runs even after syntax errors, so every error is reported in one run; a
    # file that failed to load (or to parse) may declare the start procedure, not looked for then
    missing = loading.has_errors() or len(units) < len(project.sources)
    provider = user.provider if user is not None else None
    if memo is None:
        model = analyze(units, sink, load_catalogue(), project.name, project.start, protected=protected,
                        strict=strict, stub_provider=provider, start_span=project.start_span,
                        sources_missing=missing)
    else:  # checked again: only the files that changed, when their declarations did not (warm.py)
        kept = memo.get(WARM_KEY)
        warm = analyze_warm(units, load_catalogue(), project.name, project.start, protected=protected,
                            strict=strict, stub_provider=provider, start_span=project.start_span,
                            sources_missing=missing, kept=kept if isinstance(kept, WarmAnalysis) else None,
                            texts={src.path: src.text for src in project.sources})
        memo[WARM_KEY] = warm
        sink.extend(warm.diagnostics())
        model = warm.model
        model.errors_reported = sink.found_errors()  # (as analyze's: the parse's errors count too)
        memo[MODEL_KEY] = (project, units, model)  # what the language server's navigation reads (gpl2py/lsp/gpl/)
    if sink.has_errors() and not keep_going:
        return None
    output = lower(project, model, sink, progress, user, keep_modules=keep_modules, memo=memo)
    if sink.has_errors() and not keep_going:  # lowering errors (illegal GoTo ...)
        return None
    if keep_modules:
        output.data_files = _project_data(Path(path), project)
    return output


def _parse_memo(src: SourceFile, sink: DiagnosticSink, memo: MutableMapping[object, object]) -> A.SourceUnit:
    """``parse(src, sink)``, or the tree an earlier call parsed from the same path and text, its
    diagnostics reported again, or that tree with the one procedure an edit changed parsed again
    (``syntax/reparse.py``).  Only the last text of each path is kept."""
    key = ("gpl-parse", src.path)
    kept = memo.get(key)
    if isinstance(kept, tuple) and kept[0] == src.text:
        unit, diags = kept[1], kept[2]
    else:
        # (one procedure changed; the Moves keep the walks of what edits adding lines moved)
        again = reparse_procedure(kept[0], kept[1], kept[2], src, kept[3]) if isinstance(kept, tuple) else None
        if again is None:
            parsed = DiagnosticSink()  # unfiltered: the caller's filter applies when they are replayed
            unit, diags, moves = parse(src, parsed), list(parsed), Moves()
        else:
            (unit, diags, shift), moves = again, kept[3]  # type: ignore[index]
            if shift is not None:  # (lines added or removed: the nodes below moved, kept/old_unit too)
                _shift_memo(memo, kept[1], shift)  # type: ignore[index]
        memo[key] = (src.text, unit, diags, moves)
    sink.extend(diags)
    return unit


def _shift_memo(memo: MutableMapping[object, object], old_unit: A.SourceUnit, shift: Shift) -> None:
    """Move what the later phases kept of ``old_unit``'s file below an edit that added or removed
    lines (``syntax/reparse.py`` moved the nodes): the warm analysis's symbols and diagnostics,
    the diagnostics of each declaration's last lowering.  A warm analysis of other trees than
    ``old_unit`` (its last check did not finish) is dropped: the next check is a cold one."""
    warm = memo.get(WARM_KEY)
    if isinstance(warm, WarmAnalysis) and not shift_analysis(warm, old_unit, shift):
        del memo[WARM_KEY]
    for key, kept in memo.items():
        if isinstance(key, tuple) and key[0] == "gpl-lower" and isinstance(kept, tuple):
            trees, diags, entries, decls = kept
            for node, lowered in decls.items():
                moved = shift.diagnostics(lowered.diags)
                if moved is not lowered.diags:
                    decls[node] = lowered._replace(diags=moved)
            memo[key] = (trees, shift.diagnostics(diags), entries, decls)


def _lower_memo(model: Model, names: ProjectNames, mod: ModuleSym, sink: DiagnosticSink,
                memo: MutableMapping[object, object], entries: dict[str, frozenset[str]]) -> None:
    """Lower ``mod`` for its diagnostics, or replay those of the last lowering of the same tree."""
    key = ("gpl-lower", mod.path, mod.name.lower())
    kept = memo.get(key)
    # the module's trees: its declaration, or the top-level classes of the synthetic module
    trees = (mod.decl,) if mod.decl is not None else tuple(
        c.decl for c in mod.members.values() if isinstance(c, ClassSym))
    if isinstance(kept, tuple) and len(kept[0]) == len(trees) and all(a is b for a, b in zip(kept[0], trees)):
        diags, entries[mod.py_name] = kept[1], kept[2]
    else:
        own = DiagnosticSink()  # unfiltered: the caller's filter applies when they are replayed
        entries[mod.py_name] = frozenset()
        # each procedure's last lowering, by its node: one whose node is shared with the last
        # tree (syntax/reparse.py parsed only another one again) is not lowered again
        decls = kept[3] if isinstance(kept, tuple) else {}
        with contained(own, mod.span):
            entries[mod.py_name] = lower_module(model, names, mod, own, text=False, reuse=decls)[2]
        diags = list(own)
        memo[key] = (trees, diags, entries[mod.py_name], decls)
    sink.extend(diags)


def _project_data(given: Path, project: Project) -> dict[str, bytes]:
    """The files the controller's project folder holds: every regular file of a project folder
    (read without following links: ``project.read_data_files``); for one source file, that file."""
    if given.is_dir() or given.name.lower() == "project.gpr":
        return read_data_files(project.root)
    return {k: v for k, v in read_data_files(given.parent).items() if k == given.name}


def lower(project: Project, model: Model, sink: DiagnosticSink,
          progress: Progress | None = None, user: UserStubs | None = None, *,
          keep_modules: bool = True, memo: MutableMapping[object, object] | None = None) -> Output:
    """The generated files of an analysed project.  ``gpl2py check`` runs it for the lowering's
    diagnostics only, with ``keep_modules=False``: each module's text is dropped as soon as it is
    made (with the whole analysis alive, holding every module's text was a tenth of the memory).

    With a ``memo`` (the language server) and no error reported or ignored so far, a module whose
    tree is the one lowered last time is not lowered again: its diagnostics are those it had.  The
    lowering's own diagnostics (a GoTo it cannot translate, nesting Python cannot compile) are
    about the module's own statements, and which errors a construct keeps matters only when some
    error was reported or ignored, when every module is lowered."""
    reuse = memo is not None and not keep_modules and not sink.has_errors() and not sink.ignored_errors
    start = model.start
    if project.start is None and start is not None and start.module is not None:
        # no ProjectStart: the package will run the only Public Sub Main (semantics/check.py)
        sink.report(M.START_ASSUMED_MAIN, start.span, name=f"{start.module.name}.{start.name}")
    warm = memo.get(WARM_KEY) if memo is not None else None
    taken = memo.setdefault(LOCALS_KEY, LocalsTaken()) if memo is not None else None
    names = ProjectNames.build(model, warm.dynamic_members()
                               if isinstance(warm, WarmAnalysis) and warm.model is model else None,
                               taken if isinstance(taken, LocalsTaken) else None)
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
        if reuse:
            _lower_memo(model, names, mod, sink, memo, entries)  # type: ignore[arg-type]
            continue
        with contained(sink, mod.span):  # a bug in one module: the others are still lowered
            text, gmap, entries[mod.py_name] = lower_module(model, names, mod, sink, text=keep_modules)
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
