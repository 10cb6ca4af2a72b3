"""Transpile a GPL project with the ``gpl2py`` command and import the package it writes.

Why through the command line: the samples are what a user ports, and a user runs
``gpl2py PROJECT -o OUT``.  Going through the CLI also checks its contract (exit status 0,
no error diagnostics) rather than an internal API that may change.

Each import gets a unique package name, so two tests that transpile projects with the same
ProjectName (or the same project twice) never share module state through ``sys.modules``.
"""

from __future__ import annotations

import importlib.util
import itertools
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType

REPO = Path(__file__).resolve().parents[2]
SAMPLES = REPO / "samples"
_serial = itertools.count()


class TranspileFailed(AssertionError):
    """gpl2py rejected the project: carries its diagnostics, which say which construct is missing."""


@dataclass
class Transpiled:
    """A transpiled project: its generated package (imported) and where it was written."""

    package: ModuleType
    folder: Path
    diagnostics: str


def transpile(project: Path, out_root: Path) -> Transpiled:
    """Run ``gpl2py project -o out_root``; import and return the generated package."""
    out_root.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run(
        [sys.executable, "-m", "gpl2py", str(project), "-o", str(out_root)],
        capture_output=True, text=True, timeout=120, cwd=REPO,
    )
    if proc.returncode != 0:
        raise TranspileFailed(f"gpl2py exit status {proc.returncode}:\n{proc.stderr}{proc.stdout}")
    packages = [p.parent for p in out_root.glob("*/__init__.py")]
    if len(packages) != 1:
        raise TranspileFailed(f"expected one package in {out_root}, found {packages}")
    folder = packages[0]
    name = f"_gpl_{folder.name}_{next(_serial)}"
    spec = importlib.util.spec_from_file_location(
        name, folder / "__init__.py", submodule_search_locations=[str(folder)])
    assert spec is not None and spec.loader is not None
    package = importlib.util.module_from_spec(spec)
    sys.modules[name] = package
    spec.loader.exec_module(package)
    return Transpiled(package, folder, proc.stderr)


def copy_project(project: Path, dest: Path, replace: dict[str, str] | None = None) -> Path:
    """Copy a project folder, replacing text in its sources (e.g. the server's port number).

    Each replacement must match exactly once, so a test never silently runs the unmodified text.
    """
    shutil.copytree(project, dest)
    for old, new in (replace or {}).items():
        hits = [f for f in dest.iterdir() if f.is_file() and old in f.read_text(encoding="latin-1")]
        if len(hits) != 1 or hits[0].read_text(encoding="latin-1").count(old) != 1:
            raise AssertionError(f"{old!r} must occur exactly once in {project}, found in {hits}")
        text = hits[0].read_text(encoding="latin-1")
        hits[0].write_text(text.replace(old, new), encoding="latin-1")
    return dest


def free_port() -> int:
    """A TCP port on loopback that nothing listens on right now."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])
