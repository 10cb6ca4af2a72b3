"""The front ends gpl2py has, and which one a project is written in (docs/design/frontends.md).

A :class:`Frontend` names a source language and where its pipeline lives; the pipeline is
imported only when a project of that language is translated, so nothing of one front end is loaded
on another's path (``gpl2py check`` of a GPL project never imports V+).  :func:`frontend_for`
recognises the language from the files: the extensions first, then -- for a file whose extension
says nothing -- its first significant line.  ``--language NAME`` overrides the guess.

A new front end adds one entry to :data:`FRONTENDS` and a package ``gpl2py/<name>/`` with its
``syntax``, ``semantics`` and ``lower`` layers and a ``pipeline`` module whose
``transpile_project`` has the signature of :func:`gpl2py.gpl.pipeline.transpile_project`.
"""

from __future__ import annotations

import importlib
import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.output import Output
    from gpl2py.project import Limits, Project

#: A front end's pipeline: ``transpile_project(path, sink, keep_going, progress, stubs_dir, strict,
#: loaded, limits, keep_modules) -> Output | None`` (the arguments of ``gpl2py.transpile.transpile``).
Pipeline = Callable[..., "Output | None"]


@dataclass(frozen=True)
class Frontend:
    """One source language: its ``--language`` name, the name users know it by, the file
    extensions that are its sources (lower case, with the dot), its pipeline's module (which has
    ``transpile_project``) and its loader's module (which has ``load_project(path, sink, limits)
    -> Project | None``, what ``gpl2py run`` reads to key its cache before it translates);
    ``first_line``, a pattern that claims a file whose extension says nothing by its start."""

    name: str
    title: str
    extensions: tuple[str, ...]
    module: str
    loader: str
    first_line: str = ""

    def pipeline(self) -> Pipeline:
        """The pipeline's ``transpile_project``, imported on first use."""
        return importlib.import_module(self.module).transpile_project  # type: ignore[no-any-return]

    def load_project(self, path: str | os.PathLike[str], sink: DiagnosticSink,
                     limits: Limits | None = None) -> Project | None:
        """The project at ``path`` as this front end reads it (diagnostics in ``sink``)."""
        load = importlib.import_module(self.loader).load_project
        return load(path, sink, limits)  # type: ignore[no-any-return]


GPL = Frontend("gpl", "GPL", (".gpl", ".gpo", ".gpr"), "gpl2py.gpl.pipeline", "gpl2py.project")
#: V+ (Adept): .V2 modules and .PG program files; any file whose first line that is neither blank
#: nor a ``;`` comment is ``.PROGRAM`` (a V+ program, whatever the extension).
VPLUS = Frontend("vplus", "V+", (".v2", ".pg"), "gpl2py.vplus.pipeline", "gpl2py.vplus.loader",
                 first_line=r"(?:[ \t\x1a]*(?:;[^\r\n]*)?(?:\r\n|\r|\n))*[ \t]*\.PROGRAM\b")
TMSCRIPT = Frontend("tmscript", "TMscript", (".tms", ".tmscript"), "gpl2py.tmscript.pipeline",
                    "gpl2py.tmscript.pipeline")

#: Every front end, GPL first: a folder or file no other front end claims is GPL (its loader
#: reports what it cannot read in the project's form).
FRONTENDS: tuple[Frontend, ...] = (GPL, VPLUS, TMSCRIPT)

#: How much of a file is read to recognise its first line.
_HEAD = 4096


def names() -> list[str]:
    """The ``--language`` choices."""
    return [f.name for f in FRONTENDS]


def by_name(name: str) -> Frontend:
    """The front end called ``name`` (a ``--language`` value; case-insensitive)."""
    for f in FRONTENDS:
        if f.name == name.lower():
            return f
    raise ValueError(f"unknown language {name!r}: one of {', '.join(names())}")


def frontend_for(path: str | os.PathLike[str], language: str | None = None) -> Frontend:
    """The front end that translates ``path``: ``language`` when given, else the one whose
    extensions the file (or most of the folder's source files) has; GPL when none claims it."""
    if language is not None:
        return by_name(language)
    p = Path(path)
    if p.is_dir():
        try:
            suffixes = [c.suffix.lower() for c in p.iterdir() if c.is_file()]
        except OSError:  # (the loader reports an unreadable folder in the project's form)
            return GPL
        counts = {f: sum(s in f.extensions for s in suffixes) for f in FRONTENDS}
        best = max(FRONTENDS, key=lambda f: counts[f])  # (ties: the first, GPL)
        return best if counts[best] else GPL
    suffix = p.suffix.lower()
    by_suffix = next((f for f in FRONTENDS if suffix in f.extensions), None)
    if by_suffix is not None:
        return by_suffix
    return _by_first_line(p) or GPL


def _by_first_line(p: Path) -> Frontend | None:
    """The front end whose ``first_line`` the start of the file ``p`` matches (the first 4 KB,
    read without following a link; an unreadable file is the loader's to report)."""
    try:
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0))
    except OSError:
        return None
    try:
        head = os.read(fd, _HEAD).removeprefix(b"\xef\xbb\xbf").decode("latin-1")
    except OSError:
        return None
    finally:
        os.close(fd)
    return next((f for f in FRONTENDS if f.first_line and re.match(f.first_line, head, re.IGNORECASE)), None)


__all__ = ["FRONTENDS", "GPL", "TMSCRIPT", "VPLUS", "Frontend", "Pipeline", "by_name", "frontend_for", "names"]
