"""``gpl2py check`` and translate import no part of the simulator (issue 13, item 1).

They read the built-in catalogue from gpl2py's data module (``gpl2py/gpl/semantics/builtins_data.py``)
and the project's own files with gpl2py's reader, so a real project -- the vendor's TCP Command
Server from the corpus -- is checked and translated without numpy, Pinocchio, Coal or Ruckig, and
without the runtime's motion, geometry, I/O, threads or simulation packages.  What they may import
from the runtime is GPL's language semantics (``gplrt.lang``: constant folding computes a Const's
value with the operators the program would use)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from gpltest import REPO, corpus_dir

HEAVY = ("numpy", "pinocchio", "coal", "ruckig")
SIMULATOR = ("gplrt.builtins", "gplrt.motion", "gplrt.geometry", "gplrt.io", "gplrt.threads", "gplrt.sim",
             "gplrt.notebook")

SCRIPT = """
import contextlib, io, json, sys
from gpl2py import cli
before = set(sys.modules)
err = io.StringIO()
with contextlib.redirect_stderr(err):
    status = cli.main(sys.argv[1:])
print(json.dumps({"status": status, "stderr": err.getvalue()[-2000:],
                  "modules": sorted(set(sys.modules) - before)}))
"""


def _imports(*args: str) -> list[str]:
    done = subprocess.run([sys.executable, "-c", SCRIPT, *args], capture_output=True, text=True, cwd=REPO,
                          timeout=600)
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout.splitlines()[-1])
    assert result["status"] == 0, result["stderr"]
    return result["modules"]


def _simulator_modules(modules: list[str]) -> list[str]:
    return [m for m in modules if m.split(".")[0] in HEAVY or m.startswith(SIMULATOR)]


def test_check_of_a_real_project_imports_no_simulator() -> None:
    modules = _imports("check", str(corpus_dir() / "tcs-3.0C1-pa"), "--quiet")
    assert "gpl2py.gpl.semantics.check" in modules  # the check ran in this process
    assert _simulator_modules(modules) == []


def test_translate_of_a_real_project_imports_no_simulator(tmp_path: Path) -> None:
    modules = _imports(str(corpus_dir() / "tcs-3.0C1-pa"), "-o", str(tmp_path), "--quiet")
    assert "gpl2py.gpl.lower.module" in modules
    assert list(tmp_path.glob("*/_project_files/Tcs.gpo"))  # the project's files were packed too
    assert _simulator_modules(modules) == []
