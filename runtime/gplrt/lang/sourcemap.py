"""GPL file:line for frames of transpiled code (docs/design/lowering.md, "Traceability").

gpl2py writes ``_sourcemap.json`` next to a generated package: for every generated module, the
GPL source file and the runs of Python lines that came from each GPL line.  The package registers
it on import (``register_package``), which costs nothing at run time; only when an error is
reported are frames translated:

* ``locate(exc)`` -- "Startup.gpl:42" for the innermost transpiled frame of ``exc``'s traceback
  (``GplException.__str__`` uses it, so an unhandled error names the GPL line);
* ``gpl_frames(tb)`` / ``format_gpl_traceback(exc)`` -- every frame, each with its GPL location;
* ``install_excepthook()`` -- called by ``register_package``: an exception that nobody catches and
  whose traceback passes through transpiled code prints as ``format_gpl_traceback`` does, so a
  script that imports a generated package and calls a Public procedure sees the GPL file and line
  of every frame, not only the generated Python lines.  Other exceptions print as before (the hook
  chains to the one it replaced).  IPython/Jupyter does not use ``sys.excepthook``; there,
  ``format_gpl_traceback(exc)`` on a caught exception gives the same text, and the notebook
  registers its own hook (``gplrt.notebook``);
* ``register_source_text(init_file, texts)`` -- the GPL text of a package's sources, given by
  whoever has it (the notebook loader); ``gpl_traceback(exc)`` then gives each GPL frame with its
  source line, and ``format_gpl_report(exc)`` the report that shows them first.
"""

from __future__ import annotations

import bisect
import json
import os
import sys
import threading
import traceback
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import TracebackType

__all__ = ["register_package", "register_module_map", "locate", "gpl_frames", "format_gpl_traceback", "gpl_line_of",
           "install_excepthook", "register_source_text", "GplFrame", "gpl_traceback", "format_gpl_report",
           "gpl_source_line"]

ExceptHook = Callable[[type[BaseException], BaseException, TracebackType | None], object]

_lock = threading.Lock()
# absolute path of a generated .py -> (GPL file, python line starts, GPL lines)
_maps: dict[str, tuple[str, list[int], list[int]]] = {}
# generated package folder -> {GPL file name: its lines}, for reports only (register_source_text)
_texts: dict[str, dict[str, list[str]]] = {}


def register_module_map(py_file: str, gpl_file: str, runs: list[list[int]]) -> None:
    """``runs`` is ``[[first_python_line, gpl_line], ...]`` in increasing Python line order."""
    starts = [r[0] for r in runs]
    lines = [r[1] for r in runs]
    with _lock:
        _maps[os.path.normcase(os.path.abspath(py_file))] = (gpl_file, starts, lines)


def register_package(init_file: str) -> None:
    """Load the ``_sourcemap.json`` of the generated package whose ``__init__.py`` is ``init_file``."""
    folder = os.path.dirname(os.path.abspath(init_file))
    path = os.path.join(folder, "_sourcemap.json")
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError):
        return
    for module, entry in data.get("modules", {}).items():
        register_module_map(os.path.join(folder, module), entry["source"], entry["runs"])
    install_excepthook()


def gpl_line_of(py_file: str, py_line: int) -> tuple[str, int] | None:
    entry = _maps.get(os.path.normcase(os.path.abspath(py_file)))
    if entry is None:
        return None
    gpl_file, starts, lines = entry
    i = bisect.bisect_right(starts, py_line) - 1
    if i < 0 or lines[i] <= 0:
        return None
    return gpl_file, lines[i]


def gpl_frames(tb: TracebackType | None) -> list[tuple[str, int, str, tuple[str, int] | None]]:
    """(python file, python line, function, (GPL file, GPL line) or None) for every frame."""
    out = []
    while tb is not None:
        code = tb.tb_frame.f_code
        out.append((code.co_filename, tb.tb_lineno, code.co_name, gpl_line_of(code.co_filename, tb.tb_lineno)))
        tb = tb.tb_next
    return out


def locate(exc: BaseException) -> str | None:
    """``"File.gpl:line"`` of the innermost transpiled frame that ``exc`` passed through."""
    if not _maps:
        return None
    found = None
    for _, _, _, gpl in gpl_frames(exc.__traceback__):
        if gpl is not None:
            found = gpl
    return f"{found[0]}:{found[1]}" if found else None


def format_gpl_traceback(exc: BaseException) -> str:
    """A Python traceback in which each transpiled frame also names its GPL file and line."""
    lines = ["Traceback (most recent call last):"]
    for py_file, py_line, func, gpl in gpl_frames(exc.__traceback__):
        where = f"  [GPL {gpl[0]}:{gpl[1]}]" if gpl else ""
        lines.append(f'  File "{py_file}", line {py_line}, in {func}{where}')
    lines.extend(traceback.format_exception_only(type(exc), exc))
    return "\n".join(line.rstrip("\n") for line in lines) + "\n"


def _maps_any(tb: TracebackType | None) -> bool:
    return any(gpl is not None for _, _, _, gpl in gpl_frames(tb))


def install_excepthook() -> None:
    """Make uncaught exceptions through transpiled code print their GPL frames (module docstring).

    Idempotent: the hook is installed once and remembers the hook it replaced."""
    current = sys.excepthook
    if getattr(current, "__gpl_sourcemap__", False):
        return
    previous: ExceptHook = current

    def hook(etype: type[BaseException], value: BaseException, tb: TracebackType | None) -> None:
        if value is None or not _maps_any(tb):
            previous(etype, value, tb)
            return
        parts: list[str] = []
        cause = value.__cause__
        if cause is not None and cause.__traceback__ is not None:
            parts.append(format_gpl_traceback(cause))
            parts.append("\nThe above exception was the direct cause of the following exception:\n\n")
        parts.append(format_gpl_traceback(value))
        sys.stderr.write("".join(parts))

    hook.__gpl_sourcemap__ = True  # type: ignore[attr-defined]
    sys.excepthook = hook


def register_source_text(init_file: str, texts: Mapping[str, str]) -> None:
    """Remember the GPL text of the package whose ``__init__.py`` is ``init_file``: ``texts`` maps
    each source's file name (as the source map names it, ``Cell.gpl``) to its text.

    A generated package does not carry its GPL sources; whoever loaded it from them (the notebook
    loader) hands them here so that an error report can quote the failing GPL line."""
    folder = os.path.normcase(os.path.dirname(os.path.abspath(init_file)))
    with _lock:
        _texts[folder] = {name: text.splitlines() for name, text in texts.items()}


@dataclass(frozen=True)
class GplFrame:
    """One frame of transpiled code, in GPL terms: file, line, procedure and the GPL source line
    (``""`` when the text was not registered)."""

    file: str
    line: int
    procedure: str
    text: str

    @property
    def location(self) -> str:
        return f"{self.file}:{self.line}"


def _source_line(py_file: str, gpl_file: str, line: int) -> str:
    return gpl_source_line(gpl_file, line, os.path.dirname(py_file))


def gpl_source_line(gpl_file: str, line: int, package_folder: str) -> str:
    """Line ``line`` of ``gpl_file`` of the package in ``package_folder``, stripped; ``""`` when
    its text was not registered (:func:`register_source_text`)."""
    lines = _texts.get(os.path.normcase(os.path.abspath(package_folder)), {}).get(gpl_file)
    if lines is None or not 0 < line <= len(lines):
        return ""
    return lines[line - 1].strip()


def gpl_traceback(exc: BaseException) -> list[GplFrame]:
    """The transpiled frames ``exc`` passed through, outermost first; runtime frames are left out."""
    frames = []
    for py_file, _, func, gpl in gpl_frames(exc.__traceback__):
        if gpl is not None:
            frames.append(GplFrame(gpl[0], gpl[1], func, _source_line(py_file, gpl[0], gpl[1])))
    return frames


def format_gpl_report(exc: BaseException, headline: str, frames: list[GplFrame] | None = None) -> str:
    """``headline`` (which names the error), then the failing GPL line, then the GPL traceback.

    ``File.gpl:42: error -709 in thread Main: *Division by 0*`` reads like ``gpl2py run``'s report;
    the runtime and scheduler frames in between are not shown (``format_gpl_traceback`` has them).
    """
    frames = gpl_traceback(exc) if frames is None else frames
    lines = [headline]
    if frames and frames[-1].text:
        lines.append(f"    {frames[-1].text}")
    if len(frames) > 1:
        lines.append("GPL traceback (most recent call last):")
        for frame in frames:
            lines.append(f"  {frame.location}, in {frame.procedure}")
            if frame.text:
                lines.append(f"    {frame.text}")
    return "\n".join(lines)
