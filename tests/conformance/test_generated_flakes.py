"""Every generated module compiles and passes pyflakes (issue "Core language", Must show).

The conformance cases cover every construct, so their output is the widest sample of what the
lowering emits; the samples add realistic multi-module projects.  Each is transpiled through the
library API and every ``.py`` file of the package is compiled and checked with pyflakes: no
undefined names, no unused imports, no redefinitions.  The only pyflakes message let through is
"local variable ... is assigned to but never used": a GPL local the program writes and never
reads is the program's own business, and dropping it would change the port.
"""

from __future__ import annotations

import io
import shutil
from pathlib import Path

import pytest
from pyflakes.api import check as pyflakes_check
from pyflakes.reporter import Reporter

from conformance_harness import Case, discover
from gpl2py.diagnostics import DiagnosticSink
from gpl2py.transpile import transpile

REPO = Path(__file__).resolve().parents[2]
CASES = discover()
# realistic projects: the samples, the TCS-like cell and the end-to-end I/O projects
PROJECTS = sorted(str(p.parent.relative_to(REPO)) for pattern in
                  ("samples/*/Project.gpr", "tests/realworld/*/Project.gpr", "tests/e2e_io/projects/*/Project.gpr")
                  for p in REPO.glob(pattern))


def flakes(text: str, name: str) -> list[str]:
    """pyflakes' complaints about ``text``, minus unused locals (see module docstring)."""
    out, err = io.StringIO(), io.StringIO()
    pyflakes_check(text, name, Reporter(out, err))
    return [line for line in (out.getvalue() + err.getvalue()).splitlines()
            if line and "is assigned to but never used" not in line]


def check_package(source: Path, tmp_path: Path) -> int:
    """Transpile ``source`` (a folder or one .gpl file) and check every module; returns how many."""
    if source.is_file():  # give the single file the Project.gpr the conformance worker gives it
        folder = tmp_path / source.stem
        folder.mkdir()
        shutil.copyfile(source, folder / source.name)
        (folder / "Project.gpr").write_text(
            f'ProjectBegin\nProjectName="Conf_{source.stem}"\nProjectStart="Main"\n'
            f'ProjectSource="{source.name}"\nProjectEnd\n', encoding="latin-1")
        source = folder
    sink = DiagnosticSink()
    out = transpile(str(source), sink)
    assert out is not None and not sink.errors, [d.header() for d in sink.sorted()]
    modules = {name: text for name, text in out.files.items() if name.endswith(".py")}
    for name, text in modules.items():
        compile(text, name, "exec")
        assert flakes(text, name) == [], f"{name}:\n{text}"
    return len(modules)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_generated_modules_pass_pyflakes(case: Case, tmp_path: Path) -> None:
    assert check_package(case.source, tmp_path) >= 3  # the module, __init__ and __main__


@pytest.mark.parametrize("project", PROJECTS)
def test_project_modules_pass_pyflakes(project: str, tmp_path: Path) -> None:
    assert check_package(REPO / project, tmp_path) >= 3


def test_there_are_projects_to_check() -> None:
    assert len(PROJECTS) >= 8, PROJECTS


def test_the_filter_still_sees_real_problems() -> None:
    """The check is not vacuous: an unused import and an undefined name are both reported."""
    assert len(flakes("import os\n\n\ndef f() -> None:\n    g()\n", "m.py")) == 2
