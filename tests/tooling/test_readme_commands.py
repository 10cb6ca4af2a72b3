"""The README's commands work: the two first commands, every bash and Python block, CI's command.

The ``slow`` test runs ``bash scripts/demo.sh`` the way a newcomer would on a fresh machine: in a
copy of the repository's tracked files, with a new virtual environment (``GPL2PY_VENV``) that
``scripts/_venv.sh`` creates and fills from the package index (pip's cache makes that quick).
``scripts/test.sh`` in a fresh environment would run this very test again, so instead CI's entry
point must call exactly the README's test command.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from gpl2py.cli import build_parser
from gpltest import REPO

README = (REPO / "README.md").read_text()


def _blocks(lang: str) -> list[str]:
    return re.findall(rf"^```{lang}\n(.*?)^```", README, flags=re.S | re.M)


def _commands(block: str) -> list[str]:
    return [line.split("#", 1)[0].strip() for line in block.splitlines() if line.split("#", 1)[0].strip()]


def test_readme_starts_with_the_demo_and_test_commands() -> None:
    first_block = README.index("```")
    assert "##" not in README[:first_block]  # nothing but the title and one paragraph before them
    assert _commands(_blocks("bash")[0]) == ["bash scripts/demo.sh", "bash scripts/test.sh"]


def test_ci_runs_exactly_the_readme_test_command() -> None:
    """CI runs the README's test command, after the dependency floors' check (scripts/floors.sh),
    which the README names too; then it runs the same command again in a fresh clone with no
    ``../shared`` beside it (scripts/fresh_clone.sh), as a user who has only the repository."""
    readme_test = _commands(_blocks("bash")[0])[1]
    ci = [line for line in _commands((REPO / ".ci/run").read_text())
          if not line.startswith(("set ", "cd "))]
    assert ci == ["bash scripts/floors.sh", readme_test, "bash scripts/fresh_clone.sh"]
    assert "bash scripts/floors.sh" in README
    fresh = (REPO / "scripts/fresh_clone.sh").read_text()
    assert re.search(rf"^env -u CI -u GPL_CORPUS -u GPL_SPEC -u GPL2PY_VENV {re.escape(readme_test)} ", fresh, re.M)
    # the whole suite is collected there (a collection-time error once made it run 0 tests)
    assert re.search(rf"^env -u CI -u GPL_CORPUS -u GPL_SPEC -u GPL2PY_VENV {re.escape(readme_test)} "
                     r"--collect-only ", fresh, re.M)


def _sandbox(tmp_path: Path) -> tuple[Path, dict[str, str]]:
    """A working folder that looks like the repository root to the README's commands."""
    work = tmp_path / "work"
    work.mkdir()
    (work / "samples").symlink_to(REPO / "samples")
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
           "MPLBACKEND": "Agg"}
    return work, env


def test_every_bash_block_of_the_readme_runs(tmp_path: Path) -> None:
    work, env = _sandbox(tmp_path)
    for block in _blocks("bash")[1:]:
        r = subprocess.run(["bash", "-euo", "pipefail", "-c", block], cwd=work, env=env,
                           capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, f"{block}\n--- stdout\n{r.stdout}\n--- stderr\n{r.stderr}"
    assert (work / "build/cell.png").read_bytes()[:4] == b"\x89PNG"
    assert (work / "build/out/pick_and_place/__init__.py").is_file()


def test_every_python_block_of_the_readme_runs(tmp_path: Path) -> None:
    work, env = _sandbox(tmp_path)
    for block in _blocks("python"):
        r = subprocess.run([sys.executable, "-c", block], cwd=work, env=env, capture_output=True,
                           text=True, timeout=300)
        assert r.returncode == 0, f"{block}\n--- stderr\n{r.stderr}"
        assert "200 ms" in r.stdout  # the scripted conveyor answered after 0.2 s


def test_every_run_option_is_documented() -> None:
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    run = sub.choices["run"]  # type: ignore[attr-defined]
    options = [s for a in run._actions for s in a.option_strings if s.startswith("--") and s != "--help"]
    cli_md = (REPO / "docs/cli.md").read_text()
    for option in options:
        assert f"`{option}" in cli_md, option
        assert option in README, option
    robots = next(a for a in run._actions if "--robot" in a.option_strings).choices
    for model in robots:
        assert model in cli_md and model in README, model


def _tracked_files() -> list[str]:
    out = subprocess.run(["git", "ls-files", "-z"], cwd=REPO, capture_output=True, check=True).stdout
    return [p for p in out.decode().split("\0") if p]


@pytest.mark.slow
def test_demo_works_on_a_fresh_machine(tmp_path: Path) -> None:
    if shutil.which("git") is None or not (REPO / ".git").exists():
        pytest.skip("needs the git checkout to know which files a fresh clone has")
    repo = tmp_path / "repo"
    for rel in _tracked_files():
        src = REPO / rel
        if src.is_file():
            (repo / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, repo / rel)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("VIRTUAL_ENV", "PYTHONPATH"))}
    env.update(GPL2PY_VENV=str(tmp_path / "venv"), GPL2PY_CACHE_DIR=str(tmp_path / "cache"),
               PYTHON=shutil.which("python3") or sys.executable, MPLBACKEND="Agg")
    # The demo command exactly as the README gives it.
    command = shlex.split(_commands(_blocks("bash")[0])[0])
    r = subprocess.run(command, cwd=repo, env=env, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.splitlines()[0] == "palletising cell: 8 parts onto outfeed pallet"
    assert r.stdout.splitlines()[-1] == "cell done: 8 parts placed, 8 requested"
    assert (tmp_path / "venv/bin/gpl2py").exists()
    png = repo / "build/demo/pick_and_place.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
