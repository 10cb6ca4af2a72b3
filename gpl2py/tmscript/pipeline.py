"""The TMscript front end's pipeline: files -> diagnostics -> a Python package; and, for the
Listen node, one packet's script -> Python at run time (:func:`translate_packet`).

A TMscript project on disk is one script file (``.tms`` / ``.tmscript``: TMflow keeps a script
project as one script) or a folder of them; each file becomes one module of the package, with a
``run()`` that runs its ``main`` then ``closestop``/``errorstop``.  ``gpl2py.transpile`` is the
door that calls :func:`transpile_project`; the Listen node (``gplrt.tm.listen``) calls
:func:`translate_packet` on every ``$TMSCT`` script: the same lexer, parser, checks and lowering,
no second interpreter (issue 22).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, MutableMapping
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py import messages as GM
from gpl2py.diagnostics import Diagnostic, DiagnosticSink, contained
from gpl2py.gpl.lower.names import package_name
from gpl2py.output import Output, Progress
from gpl2py.project import Limits, Project, _add_source, swap_texts
from gpl2py.pywriter.sourcemap import runs_json, sourcemap_json
from gpl2py.pywriter.text import escape
from gpl2py.source import make_span
from gpl2py.tmscript import messages as M
from gpl2py.tmscript.lower.lower import Unsupported, lower_packet, lower_script
from gpl2py.tmscript.semantics.check import Var, check_packet, check_script
from gpl2py.tmscript.syntax.parser import parse_packet, parse_script

SUFFIXES = (".tms", ".tmscript")
#: Where :func:`transpile_project` leaves the parsed scripts in ``memo``.
SCRIPTS_KEY = "tmscript-scripts"


def load_project(path: str | os.PathLike[str], sink: DiagnosticSink, limits: Limits | None = None) -> Project | None:
    """The TMscript files at ``path`` (one file, or a folder's ``.tms``/``.tmscript`` files sorted by
    name), read with gpl2py's safe reader (size limits, no links out: docs/security.md)."""
    limits = limits if limits is not None else Limits.from_env()
    try:
        p = Path(path)
        exists, is_dir = p.exists(), p.is_dir()
    except (TypeError, OSError):
        sink.report(GM.NOT_A_PROJECT, None, path=str(path)[:200])
        return None
    if not exists:
        sink.report(GM.PATH_NOT_FOUND, None, path=str(p))
        return None
    project = Project(name=p.stem if not is_dir else p.resolve().name, start="main",
                      root=p if is_dir else p.parent, limits=limits)
    files = sorted((e for e in p.iterdir() if e.suffix.lower() in SUFFIXES and e.is_file()),
                   key=lambda e: e.name.lower()) if is_dir else [p]
    if not files:
        sink.report(M.TM_NO_SOURCES, None, path=str(p))
        return None
    for f in files:
        if is_dir and (f.is_symlink() or not f.resolve().is_relative_to(p.resolve())):
            continue  # (a link out of the folder is not read)
        _add_source(project, f, str(f), None, sink)
    return project


def transpile_project(path: str | os.PathLike[str], sink: DiagnosticSink, keep_going: bool,
                      progress: Progress | None, stubs_dir: str | os.PathLike[str] | None = None,
                      strict: bool = False, loaded: Callable[[Project], None] | None = None,
                      limits: Limits | None = None, keep_modules: bool = True, *,
                      texts: Mapping[str, str] | None = None,
                      memo: MutableMapping[object, object] | None = None) -> Output | None:
    """The TMscript translation of ``path``; the arguments are :func:`gpl2py.transpile.transpile`'s
    (``stubs_dir`` and ``strict`` concern GPL's stubs and are not used).  ``texts`` and ``memo``
    serve the language server (docs/design/frontends.md): the editor's text of some files in place
    of theirs, and where the parsed scripts are left (:data:`SCRIPTS_KEY`, path -> tree)."""
    project = load_project(path, sink, limits)
    if project is None:
        return None
    if texts:
        swap_texts(project, texts)
    trees: dict[str, object] = {}
    if memo is not None:
        memo[SCRIPTS_KEY] = trees  # (the language server's outline reads them: gpl2py/lsp/tmscript.py)
    if loaded is not None:
        loaded(project)
    package = package_name(project.name)
    out = Output(package, project=project)
    smap: dict[str, tuple[str, str]] = {}
    modules: list[str] = []
    for i, src in enumerate(project.sources):
        with contained(sink, make_span(src.path, 1, 1, 1, 1)):
            tree = parse_script(src.text, src.path, sink)
            trees[os.path.abspath(src.path)] = tree
            info = check_script(tree, sink)
            try:
                text, gmap = lower_script(tree, info, Path(src.path).name)
            except Unsupported as exc:
                exc.report(sink)
                continue
            mod = package_name(Path(src.path).stem)
            modules.append(mod)
            if keep_modules:
                out.files[f"{package}/{mod}.py"] = text
                smap[f"{mod}.py"] = (src.path, runs_json(gmap))
        if progress is not None:
            progress("parsing", i + 1, len(project.sources))
    if sink.has_errors() and not keep_going:
        return None
    title = escape(project.name, "docstring")
    imports = "".join(f"from . import {m}\n" for m in modules)
    first = modules[0] if modules else None
    out.files[f"{package}/__init__.py"] = (
        f'"""TMscript project {title}, translated by gpl2py.\n\n``main()`` runs it on a simulated TM robot.\n"""\n\n'
        "from gplrt.lang.sourcemap import register_package\n\n"
        f"{imports}\n"
        "register_package(__file__)  # (a run-time error names the script's file and line)\n\n\n"
        "def main(sim: object = None) -> int:\n"
        '    """Run the project\'s (first) script; 0 when it ended without error."""\n'
        + (f"    from gplrt import tm\n\n    return tm.run_module({first}, sim)\n"
           if first else "    return 0\n")
    )
    out.files[f"{package}/__main__.py"] = (
        '"""``python -m <package>``: run the project."""\n\nfrom . import main\n\nraise SystemExit(main())\n')
    out.files[f"{package}/_sourcemap.json"] = sourcemap_json(smap)
    return out


@dataclass
class Packet:
    """One packet's script translated: ``python`` (``def script(v):``) and, per Python line, the
    script line it came from; ``errors``/``warnings`` (their script lines give ``ERROR;l`` and
    ``OK;l``); ``declared``: the node variables it adds."""

    python: str = ""
    lines: list[int] = field(default_factory=list)
    errors: list[Diagnostic] = field(default_factory=list)
    warnings: list[Diagnostic] = field(default_factory=list)
    declared: dict[str, Var] = field(default_factory=dict)


def translate_packet(script: str, known: dict[str, Var] | None = None, name: str = "packet") -> Packet:
    """Translate one Listen-node script (lines separated by CRLF, L17828); ``known``: the node's
    variables declared by earlier packets.  Never raises on bad input: errors are in the result."""
    from gpl2py.transpile import PIPELINE_FRAMES, recursion_budget

    sink = DiagnosticSink()
    out = Packet()
    with recursion_budget(PIPELINE_FRAMES), contained(sink, make_span(name, 1, 1, 1, 1)):
        tree = parse_packet(script, name, sink)
        info = check_packet(tree, sink, known)
        if not sink.has_errors():
            try:
                out.python, out.lines = lower_packet(tree, info)
            except Unsupported as exc:
                exc.report(sink)
        out.declared = info.declared
    out.errors = list(sink.errors)
    out.warnings = list(sink.warnings)
    return out
