"""Helpers for end-to-end tests: transpile GPL text to a temporary package, run it on gplrt.sim.

``run_gpl(source)`` writes the GPL modules into a fresh project folder, runs the transpiler (as
the ``gpl2py`` command does), imports the generated package and runs ``main(sim)`` on a
virtual-clock simulation with captured console; it returns what the user would look at: console
output, the controller log, the exit status, and the generated files.
"""

from __future__ import annotations

import importlib
import itertools
import sys
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType

from gpl2py.diagnostics import DiagnosticSink
from gpl2py.transpile import transpile, write_package
from gplrt.sim import Simulation

_counter = itertools.count()


@dataclass
class RunResult:
    output: str
    log: str
    status: int
    files: dict[str, str]
    package: ModuleType
    sim: Simulation


class TranspileFailed(AssertionError):
    pass


def write_project(root: Path, sources: dict[str, str], start: str = "Main", name: str | None = None) -> str:
    name = name or f"E2e{next(_counter)}"
    proj = root / name
    proj.mkdir(parents=True)
    lines = ["ProjectBegin", f'ProjectName="{name}"', f'ProjectStart="{start}"']
    for fname, text in sources.items():
        (proj / fname).write_text(text)
        lines.append(f'ProjectSource="{fname}"')
    lines.append("ProjectEnd")
    (proj / "Project.gpr").write_text("\n".join(lines) + "\n")
    return str(proj)


def transpile_to(root: Path, sources: dict[str, str] | str, start: str = "Main") -> tuple[str, dict[str, str], DiagnosticSink]:
    if isinstance(sources, str):
        sources = {"Main.gpl": sources}
    proj = write_project(root, sources, start)
    sink = DiagnosticSink()
    out = transpile(proj, sink)
    if out is None:
        raise TranspileFailed("\n".join(f"{d.header()}" for d in sink.sorted()))
    out_dir = root / "out"
    write_package(out, out_dir, sink)
    return out.package, out.files, sink


def run_gpl(root: Path, sources: dict[str, str] | str, start: str = "Main") -> RunResult:
    package, files, _ = transpile_to(root, sources, start)
    out_dir = str(root / "out")
    sys.path.insert(0, out_dir)
    try:
        pkg = importlib.import_module(package)
        sim = Simulation(capture=True, project=package)
        status = pkg.main(sim)
    finally:
        sys.path.remove(out_dir)
    return RunResult(sim.console.output, sim.console.log_text, status, files, pkg, sim)


def module_src(body: str, name: str = "Main") -> str:
    """Wrap procedure text in ``Module <name>``."""
    return f"Module {name}\n{body}\nEnd Module\n"
