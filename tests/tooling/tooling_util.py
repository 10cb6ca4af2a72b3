"""Helpers for the tooling tests: write small GPL projects, run the ``gpl2py`` command.

Every test gets its own translation cache (``GPL2PY_CACHE_DIR`` in a temporary folder, see
``conftest.py``), so no test sees entries another test made and the user's cache is never touched.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def write_project(root: Path, sources: dict[str, str], start: str = "Main", name: str = "Proj") -> Path:
    """A project folder with a Project.gpr listing ``sources`` in order."""
    proj = root / name
    proj.mkdir(parents=True)
    lines = ["ProjectBegin", f'ProjectName="{name}"', f'ProjectStart="{start}"']
    for fname, text in sources.items():
        (proj / fname).write_text(text)
        lines.append(f'ProjectSource="{fname}"')
    lines.append("ProjectEnd")
    (proj / "Project.gpr").write_text("\n".join(lines) + "\n")
    return proj


def module(body: str, name: str = "Main") -> str:
    return f"Module {name}\n{body}\nEnd Module\n"


def gpl2py(*args: str, cwd: Path | None = None, timeout: float = 180, env: dict[str, str] | None = None
           ) -> subprocess.CompletedProcess[str]:
    """``python -m gpl2py ARGS`` in a subprocess (stdout and stderr are pipes, not a TTY)."""
    return subprocess.run([sys.executable, "-m", "gpl2py", *args], capture_output=True, text=True,
                          cwd=cwd or REPO, timeout=timeout, env={**os.environ, **(env or {})})
