"""Conformance harness: discover cases, transpile them with the real gpl2py, run them on gplrt.

A *case* is an expected-output file ``<name>.out`` next to its GPL source, which is either

* ``<name>.gpl`` -- one file holding one or more modules, started at ``Main`` (the harness writes a
  ``Project.gpr`` for it into a scratch folder: ``ProjectStart="Main"``), or
* ``<name>/`` -- a project folder with its own ``Project.gpr`` (multi-module cases).

Running a case (in the worker process, see ``conformance_worker.py``):

1. transpile with the documented command line contract ``gpl2py PROJECT -o OUT`` (called in-process
   through ``gpl2py.cli.main`` so that no interpreter start-up is paid per case);
2. import the generated package ``OUT/<package>`` and, inside a fresh virtual-clock
   ``gplrt.sim.Simulation(capture=True)``, call ``main(sim)``: the generated ``main`` runs ``init()``
   and then ProjectStart on the main GPL thread of that session (``__main__`` calls ``main()``,
   which makes its own session; a package whose ``main`` takes no session gets ``init()``, ``main()``);
3. the case's output is everything the program wrote to the Console (the session's captured console,
   plus anything that reached ``sys.stdout``), and its log is the controller's log (unhandled thread
   errors, stalls).

Why a worker process: a transpiler bug can turn a loop into an infinite one or leave GPL threads
blocked; the pytest process must survive that.  The client kills and restarts the worker when a case
exceeds its time limit.  Global runtime state (the procedure registry, the Rnd sequence, imported
generated modules) is reset between cases so that cases cannot see each other.
"""

from __future__ import annotations

import difflib
import json
import os
import queue
import subprocess
import sys
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import IO

HERE = Path(__file__).resolve().parent
SUITES = ("manual", "differential")
CASE_TIMEOUT_S = 30.0  # real seconds per case (transpile + run); generous: cases take well under 1 s


@dataclass(frozen=True)
class Case:
    """One conformance case: ``source`` is a .gpl file or a project folder."""

    id: str
    source: Path
    expected: Path

    @property
    def name(self) -> str:
        return self.expected.stem

    def expected_output(self) -> str:
        return self.expected.read_text(encoding="latin-1")


def discover(root: Path = HERE) -> list[Case]:
    """Every case under ``root/<suite>/``, sorted by id; a .out without a source is an error."""
    cases: list[Case] = []
    for suite in SUITES:
        folder = root / suite
        if not folder.is_dir():
            continue
        for out in sorted(folder.glob("*.out")):
            single = out.with_suffix(".gpl")
            project = out.with_suffix("")
            if single.is_file():
                source = single
            elif (project / "Project.gpr").is_file():
                source = project
            else:
                raise FileNotFoundError(f"{out}: no {single.name} and no {project.name}/Project.gpr")
            cases.append(Case(f"{suite}/{out.stem}", source, out))
    return cases


@dataclass
class Result:
    """What running a case produced (sent from the worker as JSON)."""

    status: str  # ok | transpile_error | import_error | run_error | stalled | timeout | worker_error
    output: str = ""
    log: str = ""
    detail: str = ""

    def to_json(self) -> str:
        return json.dumps(self.__dict__)

    @staticmethod
    def from_json(text: str) -> Result:
        return Result(**json.loads(text))


def explain(case: Case, result: Result) -> str:
    """The failure message: status, transpiler diagnostics or run error, log, and a unified diff."""
    expected = case.expected_output()
    parts = [f"case {case.id} ({case.source.name}): {result.status}"]
    if result.detail:
        parts.append(result.detail.rstrip())
    if result.log:
        parts.append("controller log:\n" + result.log.rstrip())
    if result.output != expected:
        diff = difflib.unified_diff(
            expected.splitlines(keepends=True),
            result.output.splitlines(keepends=True),
            fromfile=f"{case.expected.name} (expected)",
            tofile="actual console output",
        )
        parts.append("".join(diff).rstrip() or "(outputs differ only in line endings)")
    return "\n".join(parts)


# -- client side: a worker process that runs cases one at a time -----------------------------------


class Worker:
    """A ``conformance_worker.py`` subprocess; ``run`` sends one case and waits for its result."""

    def __init__(self) -> None:
        self._proc: subprocess.Popen[str] | None = None
        self._lines: queue.Queue[str | None] = queue.Queue()

    def _start(self) -> subprocess.Popen[str]:
        env = dict(os.environ)
        env.setdefault("PYTHONHASHSEED", "0")
        proc = subprocess.Popen(
            [sys.executable, str(HERE / "conformance_worker.py")],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            encoding="utf-8",
            env=env,
        )
        self._lines = queue.Queue()
        assert proc.stdout is not None
        threading.Thread(target=self._pump, args=(proc.stdout, self._lines), daemon=True).start()
        self._proc = proc
        return proc

    @staticmethod
    def _pump(stream: IO[str], lines: queue.Queue[str | None]) -> None:
        for line in stream:
            lines.put(line)
        lines.put(None)

    def run(self, case: Case, timeout: float = CASE_TIMEOUT_S) -> Result:
        proc = self._proc if self._proc is not None and self._proc.poll() is None else self._start()
        assert proc.stdin is not None
        request = {"id": case.id, "name": case.name, "source": str(case.source)}
        try:
            proc.stdin.write(json.dumps(request) + "\n")
            proc.stdin.flush()
            line = self._lines.get(timeout=timeout)
        except queue.Empty:
            self.close()
            return Result("timeout", detail=f"no result within {timeout:.0f} s (worker restarted)")
        except OSError as exc:
            self.close()
            return Result("worker_error", detail=f"worker pipe: {exc}")
        if line is None:
            self.close()
            return Result("worker_error", detail="the worker process died")
        result = Result.from_json(line)
        if result.status in ("stalled", "run_error"):
            self.close()  # threads may still be blocked in it: start clean for the next case
        return result

    def close(self) -> None:
        proc, self._proc = self._proc, None
        if proc is None:
            return
        if proc.poll() is None:
            proc.kill()
        proc.wait()
