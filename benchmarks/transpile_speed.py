"""Transpile speed: realistic GPL projects of 10k, 100k and 300k lines through the whole pipeline
vs ``compile()`` of the generated Python, and how the cost of ``check`` and translate grows.

Run::

    python benchmarks/transpile_speed.py [--lines 10000,100000,300000] [--runs 5] [--profile]

A deterministic generator writes a project the way real ones are written: thousands of files of
100-200 lines (real projects average about 110 lines a file), each module a Public variable, a
class with a constructor and a property, and a few procedures with declarations, arithmetic,
strings, arrays, If/Select/For/While/Do, Try/Catch, ByRef arguments and built-in calls, which call
Public procedures and variables of other modules, unqualified (the "unambiguous Public name" rule)
and qualified, and create another module's class.  ``Project.gpr`` lists every file.

For each size, in turns, ``--runs`` times (after one untimed run of each):

* **translate**: :func:`gpl2py.transpile.transpile` (load, lex, parse, semantic analysis, lowering,
  rendering; no disk writes), then ``compile()`` of every generated module;
* **check**: ``gpl2py check PROJECT --quiet`` through :func:`gpl2py.cli.main` (load, parse,
  analysis and the lowering's checks; nothing written).

Each run is a fresh process, as a user's command is: nothing one run leaves in the heap can slow
(or speed) the next.  The process imports gpl2py and reads the built-in catalogue before the clock
starts (a constant, measured by ``benchmarks/check_startup.py``, that would flatter the per-line
cost of the small sizes).  The cyclic garbage collector is on, as in any process; the pipelines
pause it while they build their trees and switch it back on at the end, where the first collection
walks what they allocated -- a cost of the pipeline, inside its time.  ``compile()`` runs in the same
process right after the translation, on its output; it builds its tree outside Python's heap and
pays no collection.

Printed per size: the medians with their spread (wall time), the median ratio
``transpile / compile()`` (target: <= 8 at 100k and 300k lines), and the per-line CPU time of
translate and check with its ratio to the smallest size (target: <= 1.2 at 300k lines against 10k).
CPU time, not wall time, for the growth: the machine is shared, and what grows faster than the code
is work, which CPU time measures without the neighbours' load.

The generator numbers modules and procedures (``Mod2378``, ``Work2378_0``), so names are two
digits longer at 300k lines than at 10k, and a few more generated lines (``register_procedure``
calls) are long enough to be wrapped: about 1.5% of the time at 300k lines, counted against the
larger sizes.

``--libcst`` also measures, at the first size, what emitting through libcst would cost on the same
output (docs/design/lowering.md, "Output text", explains why we emit text and keep libcst as the
checker): ``parse_module`` of the generated Python, rendering the trees with ``Module.code``, and
rebuilding every node with an identity ``CSTTransformer`` -- the nearest stand-in for constructing
the tree node by node -- each as a ratio to ``compile()`` (medians of three runs).

The reference workload R (``_reference``) runs in this process after each turn (a translate and
a check), and each median is printed once more in R: the wall times divided by R's wall time of
the turn, the per-line CPU times by its CPU time (in mR per line).  Those are the figures to
compare between machines.
"""

from __future__ import annotations

import argparse
import contextlib
import cProfile
import importlib
import io
import json
import pstats
import random
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "runtime")]  # this checkout's gpl2py and gplrt

from _reference import HOW_TO_COMPARE, Reference, per_r  # noqa: E402
from _sidebyside import Samples, timed  # noqa: E402

from gpl2py import cli  # noqa: E402
from gpl2py.diagnostics import DiagnosticSink  # noqa: E402
from gpl2py.transpile import transpile  # noqa: E402


def _proc(r: random.Random, m: int, k: int, other: int) -> list[str]:
    """A Function of module ``m`` that uses module ``other``'s Public names."""
    n = r.randint(0, 9)
    return [
        f"    ' Procedure {k} of module {m}: mixes the statements real cells use",
        f"    Public Function Work{m}_{k}(ByVal n As Integer, ByRef total As Double) As Integer",
        "        Dim i, j, count As Integer",
        "        Dim x As Double",
        "        Dim s As String",
        "        Dim buf(31) As Integer",
        "        Dim ex As Exception",
        "        count = 0",
        f"        x = {n}.5 + shared_total{other}",
        "        s = \"start\"",
        "        For i = 0 To 31",
        f"            buf(i) = (i * {n + 3}) Mod 17",
        "            If buf(i) > 8 Then",
        "                count += 1",
        "            ElseIf buf(i) = 3 Then",
        "                count -= 1",
        "            Else",
        "                x = x + Math.Sqrt(i) * 0.5",
        "            End If",
        "        Next i",
        "        Select Case count",
        "            Case 0, 1",
        "                s = s & \" low\"",
        "            Case 2 To 10",
        "                s = s & \" mid \" & CStr(count)",
        "            Case Else",
        "                s = s & \" high\"",
        "        End Select",
        "        j = 0",
        "        While j < n",
        "            j = j + 1",
        "            total = total + j / 2",
        "        End While",
        "        Do",
        "            j -= 1",
        "        Loop Until j <= 0",
        "        Try",
        "            x = x / (n - j + 1)",
        "        Catch ex",
        "            Console.WriteLine(\"error \" & ex.ErrorCode)",
        "        End Try",
        f"        If s.Length > {20 + n} Then s = s.Substring(0, 10)",
        f"        Return count + CInt(x) + s.Length + Helper{other}(n)",
        "    End Function",
        "",
    ]


def _class(m: int) -> list[str]:
    return [
        f"    Public Class Station{m}",
        "        Public name As String = \"st\"",
        "        Private count_in As Integer",
        "        Public Shared made As Integer",
        "        Public Sub New(ByVal n As String)",
        "            name = n",
        "            made += 1",
        "        End Sub",
        "        Public Property Count As Integer",
        "            Get",
        "                Return count_in",
        "            End Get",
        "            Set(ByVal value As Integer)",
        "                count_in = value",
        "            End Set",
        "        End Property",
        "    End Class",
        "",
    ]


def _module(r: random.Random, m: int, size: int) -> list[str]:
    other = r.randrange(m) if m else 0  # a module earlier in the project (module 0 uses itself)
    body = [f"Module Mod{m}", f"    Public shared_total{m} As Double", ""]
    body += _class(m)
    body += [
        f"    Public Function Helper{m}(ByVal v As Integer) As Integer",
        f"        Return (v * {m % 97 + 1}) Mod 13",
        "    End Function",
        "",
    ]
    k = 0
    while len(body) + 44 + 6 <= size or k == 0:
        body += _proc(r, m, k, other)
        k += 1
    body += [
        "    Public Sub Run()",
        f"        Dim st As New Mod{other}.Station{other}(\"a\")",
        f"        Console.WriteLine(Work{m}_0(3, shared_total{m}) + st.Count + Mod{other}.Helper{other}(2))",
        "    End Sub",
        "End Module",
    ]
    return body


def generate(lines: int, seed: int = 7, module_lines: tuple[int, int] = (100, 200)) -> dict[str, str]:
    """``{file name: GPL text}``, about ``lines`` lines in files of ``module_lines`` lines."""
    r = random.Random(seed)
    files: dict[str, str] = {}
    total = 0
    m = 0
    while total < lines:
        body = _module(r, m, r.randint(*module_lines))
        files[f"Mod{m}.gpl"] = "\n".join(body) + "\n"
        total += len(body)
        m += 1
    return files


def write_project(folder: Path, files: dict[str, str]) -> None:
    folder.mkdir(parents=True)
    gpr = ["ProjectBegin", 'ProjectName="Bench"', 'ProjectStart="Mod0.Run"']
    for name, text in files.items():
        (folder / name).write_text(text)
        gpr.append(f'ProjectSource="{name}"')
    (folder / "Project.gpr").write_text("\n".join(gpr + ["ProjectEnd"]) + "\n")


def translate(proj: Path) -> dict[str, str]:
    sink = DiagnosticSink()
    out = transpile(str(proj), sink)
    if out is None:
        raise SystemExit("\n".join(d.header() for d in sink.sorted()[:20]))
    return {k: v for k, v in out.files.items() if k.endswith(".py")}


def check(proj: Path) -> None:  # (returns nothing to compile)
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        status = cli.main(["check", str(proj), "--quiet"])
    if status != 0:
        raise SystemExit(f"gpl2py check exited with {status}:\n{err.getvalue()[:4000]}")


def compile_all(py: dict[str, str]) -> None:
    for name, text in py.items():
        compile(text, name, "exec")


def _child(what: str, proj: Path) -> None:
    """One timed run in this fresh process (``--child``): prints its times as JSON."""
    from gpl2py.gpl.semantics.catalogue import load_catalogue

    load_catalogue()
    for name in ("conversions", "operators", "strings", "mathlib"):  # what folding Consts imports
        importlib.import_module(f"gplrt.lang.{name}")
    t0, c0 = time.perf_counter(), time.process_time()
    py = translate(proj) if what == "translate" else check(proj)
    times = {"wall": time.perf_counter() - t0, "cpu": time.process_time() - c0}
    if py is not None:
        t0 = time.perf_counter()
        compile_all(py)
        times["compile"] = time.perf_counter() - t0
        times["py_lines"] = sum(v.count("\n") for v in py.values())
    print(json.dumps(times))


def _run_child(what: str, proj: Path) -> dict[str, float]:
    done = subprocess.run([sys.executable, __file__, "--child", what, str(proj)], capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{what} of {proj} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return json.loads(done.stdout.splitlines()[-1])  # type: ignore[no-any-return]


def measure(lines: int, runs: int, profile: bool, libcst: bool, ref: Reference) -> dict[str, object]:
    files = generate(lines)
    n_lines = sum(text.count("\n") for text in files.values())
    wall: dict[str, list[float]] = {"translate": [], "compile": [], "check": []}
    cpu: dict[str, list[float]] = {"translate": [], "check": []}
    with tempfile.TemporaryDirectory() as tmp:
        proj = Path(tmp) / "Bench"
        write_project(proj, files)
        if profile:
            cProfile.runctx("translate(proj)", globals(), locals(), "/tmp/transpile.prof")
            pstats.Stats("/tmp/transpile.prof").sort_stats("tottime").print_stats(25)
        py_lines = _run_child("translate", proj)["py_lines"]  # untimed runs: the file system's caches
        _run_child("check", proj)
        ref.run(record=False)
        for _ in range(runs):
            for what in ("translate", "check"):
                times = _run_child(what, proj)
                wall[what].append(times["wall"])
                cpu[what].append(times["cpu"])
                if "compile" in times:
                    wall["compile"].append(times["compile"])
            ref.run(match=wall["translate"][-1] + wall["compile"][-1] + wall["check"][-1])
        if libcst:
            _libcst_costs(translate(proj), statistics.median(wall["compile"]))
    ratios = [a / b for a, b in zip(wall["translate"], wall["compile"])]
    ref_wall, ref_cpu = ref.wall[-runs:], ref.cpu[-runs:]
    return {
        "lines": n_lines, "files": len(files), "py_lines": int(py_lines),
        "wall": {k: Samples(v) for k, v in wall.items()}, "ratios": ratios,
        "wall_in_r": {k: Samples(per_r(v, ref_wall)) for k, v in wall.items()},
        "cpu_per_line_in_r": {k: Samples([x / n_lines for x in per_r(v, ref_cpu)]) for k, v in cpu.items()},
        "cpu_per_line": {k: statistics.median(v) / n_lines for k, v in cpu.items()},
        "cpu_spread": {k: (min(v) / n_lines, max(v) / n_lines) for k, v in cpu.items()},
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", default="10000,100000,300000",
                    help="comma-separated project sizes in GPL lines (default: 10000,100000,300000)")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--profile", action="store_true", help="print a cProfile of one translation per size")
    ap.add_argument("--libcst", action="store_true", help="also time libcst parse/render/rebuild of the output")
    ap.add_argument("--child", nargs=2, metavar=("WHAT", "PROJECT"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        _child(args.child[0], Path(args.child[1]))
        return 0
    sizes = [int(s) for s in args.lines.split(",")]
    results = []
    ref = Reference()
    for i, lines in enumerate(sizes):
        res = measure(lines, args.runs, args.profile, args.libcst and i == 0, ref)
        results.append(res)
        w, w_r = res["wall"], res["wall_in_r"]
        r = res["ratios"]
        print(f"{res['lines']:,} GPL lines in {res['files']:,} files; {res['py_lines']:,} Python lines generated")
        for key, label in (("translate", "transpile:              "), ("compile", "compile() of the output:"),
                           ("check", "check:                  ")):
            print(f"  {label}{w[key].text()}  {w_r[key].text(1, 'R', 2)}")  # type: ignore[index]
        print(f"  ratio transpile / compile: {statistics.median(r):.2f}x "  # type: ignore[arg-type]
              f"(spread {min(r):.2f}-{max(r):.2f}, {args.runs} runs each; target <= 8 at 100k and 300k)", flush=True)
    base = results[0]
    print(f"per-line CPU time, median of {args.runs} runs (spread), and its ratio to {base['lines']:,} lines "
          "(target <= 1.2 at 300k lines):")
    for res in results:
        cells = []
        for k in ("translate", "check"):
            per = res["cpu_per_line"][k]  # type: ignore[index]
            lo, hi = res["cpu_spread"][k]  # type: ignore[index]
            cells.append(f"{k} {per * 1e6:6.1f} us/line ({lo * 1e6:.1f}-{hi * 1e6:.1f}) "
                         f"{res['cpu_per_line_in_r'][k].text(1e-3, 'mR/line', 2)} "  # type: ignore[index]
                         f"{per / base['cpu_per_line'][k]:5.2f}x")  # type: ignore[index]
        print(f"  {res['lines']:>9,} lines: " + "   ".join(cells))
    print(ref.line())
    print(HOW_TO_COMPARE)
    return 0


def _libcst_costs(py: dict[str, str], compile_s: float) -> None:
    """Time libcst on the generated modules (median of 3 each), as ratios to ``compile()``."""
    import libcst

    def median3(fn: Callable[[], object]) -> float:
        return statistics.median(timed(fn) for _ in range(3))

    trees = [libcst.parse_module(text) for text in py.values()]
    rows = [
        ("libcst parse_module", median3(lambda: [libcst.parse_module(text) for text in py.values()])),
        ("libcst Module.code (render)", median3(lambda: [tree.code for tree in trees])),
        ("libcst rebuild every node", median3(lambda: [tree.visit(libcst.CSTTransformer()) for tree in trees])),
    ]
    for label, seconds in rows:
        print(f"  {label}: {seconds * 1e3:.0f} ms ({seconds / compile_s:.1f}x compile)")


if __name__ == "__main__":
    raise SystemExit(main())
