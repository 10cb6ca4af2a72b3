"""Reading a V+ project: one ``.v2``/``.pg`` file, or every one of a folder (sorted by name).

V+ loads programs by name into one namespace (spec §1.1), so a folder of files is one project;
the files are read with the safety every front end shares (``gpl2py.project.load_sources``: size
limits, no links out of the folder, lenient decoding).  The program to run is ``--start``, else
the first program of the first file (:func:`gpl2py.vplus.semantics.check.analyze`).
"""

from __future__ import annotations

import os

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.project import Limits, Project, load_sources
from gpl2py.vplus import messages as M

#: The extensions of V+ sources: .V2 (a V+ disk module) and .PG (a program file).
SUFFIXES = (".v2", ".pg")


def load_project(path: str | os.PathLike[str], sink: DiagnosticSink, limits: Limits | None = None) -> Project | None:
    """The V+ project at ``path``; problems are diagnostics in ``sink``, never an exception."""
    project = load_sources(path, sink, limits, SUFFIXES)
    if project is not None and not project.sources and not sink.has_errors() and os.path.isdir(path):
        sink.report(M.NO_SOURCES, None, path=str(path))
    return project
