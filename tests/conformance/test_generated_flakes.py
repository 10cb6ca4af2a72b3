"""Every generated module compiles, passes pyflakes and is PEP 8 (issue "Core language").

The conformance cases cover every construct, so their output is the widest sample of what the
lowering emits; the samples add realistic multi-module projects.  Each is transpiled through the
library API and every ``.py`` file of the package is compiled, parsed by libcst, checked with
pyflakes (no undefined names, no unused imports, no redefinitions), checked with pycodestyle
(the project's line length, 99) and searched for ``exec``/``eval``.  The only pyflakes message let through is
"local variable ... is assigned to but never used": a GPL local the program writes and never
reads is the program's own business, and dropping it would change the port.
"""

from __future__ import annotations

import io
import re
import shutil
from pathlib import Path

import libcst
import pycodestyle
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


def style_errors(text: str) -> list[str]:
    """pycodestyle's findings for ``text`` (max line length 99), as ``line:col: code`` strings."""
    found: list[str] = []

    class Report(pycodestyle.BaseReport):
        def error(self, line_number: int, offset: int, text: str, check: object) -> str | None:
            found.append(f"{line_number}:{offset + 1}: {text}")
            return None

    style = pycodestyle.StyleGuide(max_line_length=99, quiet=True, reporter=Report)
    checker = pycodestyle.Checker(lines=text.splitlines(keepends=True), options=style.options,
                                  report=style.options.report)
    checker.check_all()
    return found


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
        libcst.parse_module(text)
        assert flakes(text, name) == [], f"{name}:\n{text}"
        assert style_errors(text) == [], f"{name}:\n{text}"
        assert not re.search(r"\b(exec|eval)\(", text), name
    return len(modules)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_generated_modules_pass_pyflakes(case: Case, tmp_path: Path) -> None:
    assert check_package(case.source, tmp_path) >= 3  # the module, __init__ and __main__


@pytest.mark.parametrize("project", PROJECTS)
def test_project_modules_pass_pyflakes(project: str, tmp_path: Path) -> None:
    assert check_package(REPO / project, tmp_path) >= 3


def test_there_are_projects_to_check() -> None:
    assert len(PROJECTS) >= 8, PROJECTS


def test_the_checks_still_see_real_problems() -> None:
    """The checks are not vacuous: an unused import and an undefined name are both reported, and
    so are a long line and a missing blank line."""
    assert len(flakes("import os\n\n\ndef f() -> None:\n    g()\n", "m.py")) == 2
    assert len(style_errors("x = 1\ndef f() -> None:\n    return " + "1 + " * 30 + "1\n")) == 2
