"""Run-time speed of transpiled code: ten GPL kernels vs idiomatic hand-written Python.

Run::

    python benchmarks/runtime_speed.py [--n 200000] [--runs 7] [--show] [--cpu] [--on thread|direct|both]

Each kernel is written once in GPL (transpiled here, in the same process, with the real pipeline)
and once as the Python a programmer would write for the same algorithm.  Both run in this process
on the same input, in turns, after one untimed run of each, with the garbage collector in its
default state on both sides.  Printed per kernel: the median of ``--runs`` runs of each with the
spread (lowest-highest), and the median of the per-turn ratios ``transpiled / python`` with its
spread.  Both versions must return the same value (checked), so the comparison is honest; the GPL
side keeps GPL's semantics (Integer overflow is error -710, conversions to Integer round), the
Python side is what a programmer would write without them.

The first five kernels are the ones lowering was tuned on; the last five are the everyday shapes
whose checks cannot be dropped: a plain Integer sum, a ByVal Function call in a loop, a While loop
with a condition, string building with CStr, and a method call on an object of a GPL class.
Target: ratio <= 1.5 on every kernel.  ``--show`` prints the generated Python of the kernels.

Where the kernels run (``--on``, both by default): on a GPL thread of a simulated controller, as
``gpl2py run`` runs a program (its loops take checkpoints of the thread's slice, and a used-up
slice is a scheduling point), and called directly from Python, as a notebook or a test calls a
transpiled procedure (no scheduler: checkpoints cost nothing).  The hand-written side runs in the
same place as the transpiled one.

The reference workload R (``_reference``) runs in every turn too, on the same clock, and each
median is printed once more in R (each time divided by R of its turn): the figures to compare
between machines.
"""

from __future__ import annotations

import argparse
import importlib
import math
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "runtime")]  # this checkout's gpl2py and gplrt

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _reference import HOW_TO_COMPARE, Reference  # noqa: E402
from _sidebyside import side_by_side  # noqa: E402

from gpl2py.diagnostics import DiagnosticSink  # noqa: E402
from gpl2py.transpile import transpile, write_package  # noqa: E402
from gplrt.sim import Simulation  # noqa: E402

GPL_KERNELS = """Module Kernels
    ' 1. integer arithmetic: a linear congruential mix kept in 31 bits
    Public Function IntLoop(ByVal n As Integer) As Integer
        Dim i, acc As Integer
        acc = 1
        For i = 1 To n
            acc = ((acc * 75 + i) And &H7FFF) + (i \\ 3) - (i >> 2)
        Next
        Return acc
    End Function

    ' 2. Double math
    Public Function DoubleMath(ByVal n As Integer) As Double
        Dim i As Integer
        Dim x, s As Double
        s = 0
        For i = 1 To n
            x = i * 0.001
            s = s + Math.Sqrt(x) * Math.Sin(x) + x * x / 2.0
        Next
        Return s
    End Function

    ' 3. string building
    Public Function StringBuild(ByVal n As Integer) As Integer
        Dim i, total As Integer
        Dim s As String
        s = ""
        total = 0
        For i = 1 To n
            s = s & Chr(65 + (i And 15))
            If s.Length >= 64 Then
                total = total + s.IndexOf("P")
                s = ""
            End If
        Next
        Return total
    End Function

    ' 4. array fill and sum
    Public Function ArraySum(ByVal n As Integer) As Double
        Dim a(n) As Double
        Dim i As Integer
        Dim s As Double
        For i = 0 To n
            a(i) = i * 0.5
        Next
        s = 0
        For i = 0 To n
            s = s + a(i)
        Next
        Return s
    End Function

    ' 5. procedure calls with ByRef arguments
    Sub Accumulate(ByRef total As Integer, ByRef count As Integer, ByVal v As Integer)
        total = total + v
        count = count + 1
    End Sub

    Public Function ByRefCalls(ByVal n As Integer) As Integer
        Dim i, total, count As Integer
        For i = 1 To n
            Accumulate(total, count, i And 7)
        Next
        Return total + count
    End Function

    ' 6. a plain Integer sum (n is kept below 65,536 so that it fits an Integer)
    Public Function IntSum(ByVal n As Integer) As Integer
        Dim i, total As Integer
        total = 0
        For i = 1 To n
            total = total + i
        Next
        Return total
    End Function

    ' 7. a ByVal Function call in a loop
    Function Scale(ByVal v As Integer) As Integer
        Return v * 2 + 1
    End Function

    Public Function ByValCalls(ByVal n As Integer) As Integer
        Dim i, total As Integer
        For i = 1 To n
            total = total + Scale(i And 1023)
        Next
        Return total
    End Function

    ' 8. a While loop with a condition
    Public Function WhileLoop(ByVal n As Integer) As Integer
        Dim i, count As Integer
        i = 0
        count = 0
        While i < n
            i = i + 1
            If i Mod 3 = 0 Then
                count = count + 1
            End If
        End While
        Return count
    End Function

    ' 9. string building with numbers
    Public Function StringNumbers(ByVal n As Integer) As Integer
        Dim i, total As Integer
        Dim s As String
        s = ""
        total = 0
        For i = 1 To n
            s = s & CStr(i) & ","
            If Len(s) > 200 Then
                total = total + Len(s)
                s = ""
            End If
        Next
        Return total + Len(s)
    End Function

    ' 10. a method call on an object of a GPL class
    Public Class Counter
        Private total_in As Integer
        Public Sub Add(ByVal v As Integer)
            total_in = total_in + v
        End Sub
        Public Function Total() As Integer
            Return total_in
        End Function
    End Class

    Public Function MethodCalls(ByVal n As Integer) As Integer
        Dim c As New Counter()
        Dim i As Integer
        For i = 1 To n
            c.Add(i And 7)
        Next
        Return c.Total()
    End Function
End Module
"""


# -- the same algorithms, written the way a Python programmer would -----------------------------


def int_loop(n: int) -> int:
    acc = 1
    for i in range(1, n + 1):
        acc = ((acc * 75 + i) & 0x7FFF) + (i // 3) - (i >> 2)
    return acc


def double_math(n: int) -> float:
    s = 0.0
    for i in range(1, n + 1):
        x = i * 0.001
        s = s + math.sqrt(x) * math.sin(x) + x * x / 2.0
    return s


def string_build(n: int) -> int:
    s = ""
    total = 0
    for i in range(1, n + 1):
        s = s + chr(65 + (i & 15))
        if len(s) >= 64:
            total = total + s.find("P")
            s = ""
    return total


def array_sum(n: int) -> float:
    a = [0.0] * (n + 1)
    for i in range(n + 1):
        a[i] = i * 0.5
    s = 0.0
    for i in range(n + 1):
        s = s + a[i]
    return s


def accumulate(total: int, count: int, v: int) -> tuple[int, int]:
    return total + v, count + 1


def byref_calls(n: int) -> int:
    total = count = 0
    for i in range(1, n + 1):
        total, count = accumulate(total, count, i & 7)
    return total + count


def int_sum(n: int) -> int:
    total = 0
    for i in range(1, n + 1):
        total = total + i
    return total


def scale(v: int) -> int:
    return v * 2 + 1


def byval_calls(n: int) -> int:
    total = 0
    for i in range(1, n + 1):
        total = total + scale(i & 1023)
    return total


def while_loop(n: int) -> int:
    i = 0
    count = 0
    while i < n:
        i = i + 1
        if i % 3 == 0:
            count = count + 1
    return count


def string_numbers(n: int) -> int:
    s = ""
    total = 0
    for i in range(1, n + 1):
        s = s + str(i) + ","
        if len(s) > 200:
            total = total + len(s)
            s = ""
    return total + len(s)


class Counter:
    def __init__(self) -> None:
        self.total = 0

    def add(self, v: int) -> None:
        self.total = self.total + v


def method_calls(n: int) -> int:
    c = Counter()
    for i in range(1, n + 1):
        c.add(i & 7)
    return c.total


def _below_integer_sum_limit(n: int) -> int:
    return min(n, 65_535)


# (label, GPL function, Python function, the argument a run gets from --n)
KERNELS: list[tuple[str, str, Callable[[int], object], Callable[[int], int]]] = [
    ("integer arithmetic loop", "IntLoop", int_loop, int),
    ("Double math", "DoubleMath", double_math, int),
    ("string building", "StringBuild", string_build, int),
    ("array fill and sum", "ArraySum", array_sum, int),
    ("procedure calls with ByRef", "ByRefCalls", byref_calls, int),
    ("plain Integer sum", "IntSum", int_sum, _below_integer_sum_limit),
    ("ByVal Function call", "ByValCalls", byval_calls, int),
    ("While loop with a condition", "WhileLoop", while_loop, int),
    ("string building with CStr", "StringNumbers", string_numbers, int),
    ("class method call", "MethodCalls", method_calls, int),
]


def build(tmp: Path):  # type: ignore[no-untyped-def]
    proj = tmp / "Kernels"
    proj.mkdir()
    (proj / "Kernels.gpl").write_text(GPL_KERNELS)
    (proj / "Project.gpr").write_text(
        'ProjectBegin\nProjectName="Bench Kernels"\nProjectSource="Kernels.gpl"\nProjectEnd\n')
    sink = DiagnosticSink()
    out = transpile(str(proj), sink)
    if out is None:
        raise SystemExit("\n".join(d.header() for d in sink.sorted()))
    write_package(out, tmp / "out", sink)
    sys.path.insert(0, str(tmp / "out"))
    pkg = importlib.import_module(out.package)
    return pkg.kernels, out.files[f"{out.package}/kernels.py"]


def run_kernels(mod, args: argparse.Namespace, ref: Reference) -> float:  # type: ignore[no-untyped-def]
    """Time every kernel side by side (R in every turn), print a line each; the worst median ratio."""
    worst = 0.0
    print(f"{'kernel':30} {'transpiled (median, spread)':>31} {'python (median, spread)':>31}  ratio (spread)")
    for label, gpl_name, py_func, arg in KERNELS:
        n = arg(args.n)
        gpl_func = getattr(mod, gpl_name)
        results: dict[str, object] = {}
        pair = side_by_side(lambda: results.__setitem__("gpl", gpl_func(n)),
                            lambda: results.__setitem__("py", py_func(n)), args.runs,
                            clock=time.process_time if args.cpu else time.perf_counter, reference=ref)
        r_gpl, r_py = results["gpl"], results["py"]
        if isinstance(r_py, float):
            assert math.isclose(r_gpl, r_py, rel_tol=1e-12), (label, r_gpl, r_py)  # type: ignore[arg-type]
        else:
            assert r_gpl == r_py, (label, r_gpl, r_py)
        worst = max(worst, pair.ratio)
        print(f"{label:30} {pair.a.text()} {pair.b.text()}  {pair.ratio_text()}")
        print(f"{'  in R':30} {pair.a_in_r.text(1, 'R', 3)}  {pair.b_in_r.text(1, 'R', 3)}")
    return worst


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200_000)
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--show", action="store_true")
    ap.add_argument("--on", choices=("thread", "direct", "both"), default="both",
                    help="run the kernels on a GPL thread of a simulated controller, directly, or both")
    ap.add_argument("--cpu", action="store_true",
                    help="time with the process's CPU time instead of the wall clock: steadier on a "
                    "machine shared with other work (both sides alike)")
    args = ap.parse_args()
    if args.runs < 5:
        ap.error("--runs must be at least 5 (a median of fewer says little on a shared machine)")
    with tempfile.TemporaryDirectory() as tmp:
        mod, text = build(Path(tmp))
        if args.show:
            print(text)
        worst = 0.0
        ref = Reference()
        for where in (["thread", "direct"] if args.on == "both" else [args.on]):
            if where == "thread":
                print("on a GPL thread (as `gpl2py run` runs a program):")
                with Simulation(capture=True) as sim, sim.as_gpl_thread():
                    worst = max(worst, run_kernels(mod, args, ref))
            else:
                print("called directly (as a notebook or a test calls a procedure):")
                worst = max(worst, run_kernels(mod, args, ref))
        print(f"worst median ratio {worst:.2f} (target <= 1.5)")
        print(ref.line())
        print(HOW_TO_COMPARE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
