"""How fast ``gpl2py lsp`` answers on the 12,000-line TCS project, against a cold ``gpl2py check``.

    python benchmarks/lsp_latency.py [--edits 52] [--requests 30] [--checks 5]

One server (``gpl2py lsp`` in a subprocess, driven over stdio by the tests' pygls client, with the
debounce off: ``debounceMs`` 0, so what is timed is gpl2py's work and the protocol's round trip)
holds a copy of ``../shared/corpus/tcs-3.0C1-pa`` (or ``$GPL_CORPUS``).  Timed, in one run:

* **edit -> diagnostics**: from sending a ``didChange`` to receiving the edited file's
  ``publishDiagnostics`` for that version, over ``--edits`` edits taking four kinds by turns: a
  statement changed inside a procedure body (``Cmd.gpl``'s ``Cmd_Version``, ``Main.gpl``'s
  ``TcpComMain``: the first edit of each adds a line, the next ones change it), an edit that
  changes the number of lines of the largest file, in its first procedure (``PARobot.gpl``'s
  ``Init``, 44 procedures below it: the most lines to move): Enter, a pasted block of 5 lines,
  a deleted line, by turns; and two edits of a
  Public declaration other modules use: the value of
  ``Globals.gpl``'s ``Public Const EcUnknown`` (read by ``Cmd.gpl`` and ``Class_command.gpl``;
  what other files see of it, its name and type, stays) and the type of a parameter of
  ``Functions.gpl``'s ``Public Sub Backspace`` (called by ``Main.gpl``, which is checked again);
* **hover** and **completion** round trips (a field reached through ``Cmd.``, the members after
  ``Cmd.``) once the index is built;
* **cold check**: ``gpl2py check`` of the same project in a subprocess, ``--checks`` times, in
  turns with the rest;
* **memory**: the server's resident set holding the project (VmRSS, and VmHWM its peak) against
  the peak resident set of one ``gpl2py check`` (``ru_maxrss`` of the waited children).

Medians with their spread (min-max), each also in R (``_reference``: the time divided by R of its
turn), to compare between machines.  Targets (issue 23): body edit <= 50 ms median, public
declaration <= 200 ms, hover and completion <= 20 ms.  Not a timed test: it only prints.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tests"))
from _reference import HOW_TO_COMPARE, Reference, per_r  # noqa: E402

from lspclient import Session  # noqa: E402  (the tests' client: pygls's, over stdio)


#: The kinds of edit, taken by turns (``Edits``' methods).
KINDS = ("body", "newline", "public", "signature")


def corpus() -> Path:
    """The TCS project of the real code (``$GPL_CORPUS``, else ``../shared/corpus`` beside the
    repository), as the tests find it."""
    base = Path(os.environ.get("GPL_CORPUS") or HERE.parent.parent / "shared" / "corpus")
    found = base / "tcs-3.0C1-pa"
    if not found.is_dir():
        raise SystemExit(f"lsp_latency.py: {found} not found: set GPL_CORPUS to the folder holding tcs-3.0C1-pa")
    return found


def spread(values: list[float], unit: float = 1e3, suffix: str = "ms") -> str:
    med = statistics.median(values) * unit
    return f"{med:7.1f} {suffix} (spread {min(values) * unit:.1f}-{max(values) * unit:.1f}, n={len(values)})"


def in_r(values: list[float], refs: list[float]) -> str:
    v = per_r(values, refs)
    return f"{statistics.median(v):.3f} R (spread {min(v):.3f}-{max(v):.3f})"


class Edits:
    """The texts of the edits: a body statement or a Public Const's value, a new one each time."""

    def __init__(self, folder: Path) -> None:
        self.files = {n: (folder / n).read_text(errors="replace")
                      for n in ("Cmd.gpl", "Main.gpl", "Globals.gpl", "Functions.gpl", "PARobot.gpl")}
        self.anchor = {"Cmd.gpl": "        Dim ii As Integer\n        If bTelnetMode Then\n",
                       "Main.gpl": "        Dim cCount As Integer = 0\n"}
        for name, anchor in self.anchor.items():
            assert anchor in self.files[name], (name, anchor)
        self.const = '    Public Const EcUnknown As String = "-2805 *Unknown command*"'
        assert self.const in self.files["Globals.gpl"]
        self.sub = "    Public Sub Backspace(ByVal index As Integer, ByRef msg As String)"
        assert self.sub in self.files["Functions.gpl"]
        self.init = "       Dim inti As Integer\n\n"
        assert self.init in self.files["PARobot.gpl"]

    def body(self, n: int) -> tuple[str, str]:
        name = "Cmd.gpl" if n // len(KINDS) % 2 else "Main.gpl"
        anchor = self.anchor[name]
        stmt = f"        ii = {n}\n" if name == "Cmd.gpl" else f"        cCount = {n}\n"
        return name, self.files[name].replace(anchor, anchor + stmt, 1)

    def public(self, n: int) -> tuple[str, str]:
        return "Globals.gpl", self.files["Globals.gpl"].replace(
            self.const, f'    Public Const EcUnknown As String = "-2805 *Unknown command {n}*"', 1)

    def newline(self, n: int) -> tuple[str, str]:
        """In the first procedure of the largest file (3,534 lines), by turns: Enter (a blank
        line), a pasted block of 5 lines, a deleted line; each changes the file's number of lines
        from the last edit's."""
        turn = n // len(KINDS) % 3
        init = self.init
        new = (init + "\n", init + "       inti = 1\n       inti = inti + 2\n       If inti > 2 Then\n"
               "           inti = 0\n       End If\n", init.replace("\n\n", "\n", 1))[turn]
        return "PARobot.gpl", self.files["PARobot.gpl"].replace(init, new, 1)

    def signature(self, n: int) -> tuple[str, str]:
        """A parameter's type, Integer or Double by turns: the procedure's signature changes."""
        typ = "Double" if n % 2 else "Integer"
        return "Functions.gpl", self.files["Functions.gpl"].replace(
            self.sub, self.sub.replace("index As Integer", f"index As {typ}"), 1)


def where(main: str) -> tuple[int, int]:
    """Where hover and completion are asked in Main.gpl's text: on ``NewRobNum`` after ``Cmd.``
    (0-based line and column)."""
    lines = main.splitlines()
    line = next(i for i, t in enumerate(lines) if "Cmd.NewRobNum = robNumArg" in t)
    return line, lines[line].index("Cmd.NewRobNum") + 4


def cold_check(folder: Path, cwd: Path) -> float:
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "gpl2py", "check", str(folder)], cwd=cwd, capture_output=True, check=False)
    return time.perf_counter() - start


def memory(pid: int) -> tuple[int, int]:
    """VmRSS and VmHWM of ``pid``, in kB."""
    fields = {}
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        key, _, value = line.partition(":")
        if key in ("VmRSS", "VmHWM"):
            fields[key] = int(value.split()[0])
    return fields["VmRSS"], fields["VmHWM"]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--edits", type=int, default=52)
    ap.add_argument("--requests", type=int, default=30)
    ap.add_argument("--checks", type=int, default=5)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        folder = Path(shutil.copytree(corpus(), work / "tcs"))
        edits = Edits(folder)
        ref = Reference()
        ref.run(record=False)
        started = time.perf_counter()
        session = Session(work, debounce_ms=0)
        try:
            for name in edits.files:
                session.open(folder / name)
            for name in edits.files:
                session.wait_diagnostics(folder / name, timeout=300)
            first = time.perf_counter() - started
            main_gpl = folder / "Main.gpl"
            line, col = where(edits.files["Main.gpl"])
            # warm-up: one edit of each kind, a hover (imports the runtime's descriptions) and a completion
            for kind in (edits.body, edits.newline, edits.public, edits.signature):
                name, text = kind(0)
                session.change(folder / name, text)
                session.wait_diagnostics(folder / name, timeout=300)
                session.change(folder / name, edits.files[name])
                session.wait_diagnostics(folder / name, timeout=300)
            session.hover(main_gpl, line, col)
            session.completion(main_gpl, line, col)
            times: dict[str, list[float]] = {k: [] for k in KINDS + ("hover", "completion", "check")}
            refs: dict[str, list[float]] = {k: [] for k in times}
            main_text = edits.files["Main.gpl"]
            for n in range(1, args.edits + 1):
                kind = KINDS[n % len(KINDS)]
                name, text = getattr(edits, kind)(n)
                main_text = text if name == "Main.gpl" else main_text
                t0 = time.perf_counter()
                session.change(folder / name, text)
                session.wait_diagnostics(folder / name, timeout=300)
                times[kind].append(time.perf_counter() - t0)
                ref.run(match=times[kind][-1])
                refs[kind].append(ref.wall[-1])
            session.settle()  # the index of the last check is built
            line, col = where(main_text)  # (the body edits add a line above it)
            for _ in range(args.requests):
                for kind, call in (("hover", session.hover), ("completion", session.completion)):
                    t0 = time.perf_counter()
                    call(main_gpl, line, col)
                    times[kind].append(time.perf_counter() - t0)
                    ref.run(match=times[kind][-1])
                    refs[kind].append(ref.wall[-1])
            rss, hwm = memory(session.client._server.pid)  # type: ignore[union-attr]
            for _ in range(args.checks):
                times["check"].append(cold_check(folder, work))
                ref.run(match=times["check"][-1])
                refs["check"].append(ref.wall[-1])
            check_peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss  # kB, the checks' peak
        finally:
            session.close()
    lines = sum(t.count("\n") for t in (p.read_text(errors="replace") for p in corpus().glob("*.gp[lo]")))
    print(f"TCS project ({lines} lines), gpl2py lsp over stdio, debounce off; first diagnostics "
          f"after open: {first * 1e3:.0f} ms (server start, cold parse and check)")
    rows = [("edit in a procedure body -> diagnostics", "body", "target <= 50 ms"),
            ("lines added/removed in a body (PARobot) -> diag.", "newline", "target <= 50 ms"),
            ("edit of a Public Const's value -> diagnostics", "public", "target <= 200 ms"),
            ("edit of a Public Sub's parameter type -> diag.", "signature", "target <= 200 ms"),
            ("hover", "hover", "target <= 20 ms"),
            ("completion after Cmd.", "completion", "target <= 20 ms"),
            ("cold gpl2py check of the project", "check", "")]
    for label, key, target in rows:
        if not times[key]:  # (fewer --edits than kinds)
            print(f"  {label:45s} not measured: no edit of this kind")
            continue
        print(f"  {label:45s} {spread(times[key])}  {in_r(times[key], refs[key])}  {target}")
    print(f"memory: the server holding the project {rss / 1024:.0f} MB resident (peak {hwm / 1024:.0f} MB); "
          f"one gpl2py check peaks at {check_peak / 1024:.0f} MB")
    print(ref.line())
    print(HOW_TO_COMPARE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
