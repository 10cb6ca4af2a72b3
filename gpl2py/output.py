"""What a translation produces, whatever its source language: the files of a Python package.

:class:`Output` is the package a front end's pipeline returns (docs/design/frontends.md);
:func:`write_package` writes it below an output folder.  Output is deterministic: identical input
gives byte-identical files.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from gpl2py import messages as M
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.project import Project


@dataclass
class Output:
    """The generated package: ``files`` maps paths relative to the output folder to their text."""

    package: str
    files: dict[str, str] = field(default_factory=dict)
    project: Project | None = None
    #: The project's own files (name -> bytes), written to ``<package>/_project_files/`` so that
    #: ``python -m <package>`` installs them where the controller has them (package_main)
    data_files: dict[str, bytes] = field(default_factory=dict)


#: ``progress(phase, done, total)``: called per file parsed and module written
#: (``gpl2py.progress.ProgressBar`` draws it).
Progress = Callable[[str, int, int], None]
#: Where a written package keeps the project's own files (``Output.data_files``).
DATA_FOLDER = "_project_files"


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
