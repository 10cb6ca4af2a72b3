"""Run-time speed of transpiled code: five GPL kernels vs idiomatic hand-written Python.

Run::

    python benchmarks/runtime_speed.py [--n 200000] [--repeat 9] [--show]

Each kernel is written once in GPL (transpiled here, in the same process, with the real pipeline)
and once as the Python a programmer would write for the same algorithm.  Both run in this process
on the same input, interleaved; the best of ``--repeat`` runs of each is kept and the ratio
``transpiled / python`` is printed.  Both versions must return the same value (checked), so the comparison is honest.
Target: ratio <= 1.5 on every kernel.  ``--show`` prints the generated Python of the kernels.
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

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from gpl2py.diagnostics import DiagnosticSink  # noqa: E402
from gpl2py.transpile import transpile, write_package  # noqa: E402

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


KERNELS: list[tuple[str, str, Callable[[int], object]]] = [
    ("integer arithmetic loop", "IntLoop", int_loop),
    ("Double math", "DoubleMath", double_math),
    ("string building", "StringBuild", string_build),
    ("array fill and sum", "ArraySum", array_sum),
    ("procedure calls with ByRef", "ByRefCalls", byref_calls),
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


def once(func: Callable[[int], object], n: int) -> tuple[float, object]:
    t0 = time.perf_counter()
    result = func(n)
    return time.perf_counter() - t0, result


def best_pair(a: Callable[[int], object], b: Callable[[int], object], n: int,
              repeat: int) -> tuple[float, object, float, object]:
    """Best time of each, the two runs interleaved so that load from other processes on a shared
    machine hits both sides alike."""
    ta, tb = [], []
    ra: object = None
    rb: object = None
    for _ in range(repeat):
        t, ra = once(a, n)
        ta.append(t)
        t, rb = once(b, n)
        tb.append(t)
    return min(ta), ra, min(tb), rb


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200_000)
    ap.add_argument("--repeat", type=int, default=9)
    ap.add_argument("--show", action="store_true")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        mod, text = build(Path(tmp))
        if args.show:
            print(text)
        worst = 0.0
        print(f"{'kernel':32} {'transpiled':>11} {'python':>9} {'ratio':>6}")
        for label, gpl_name, py_func in KERNELS:
            t_gpl, r_gpl, t_py, r_py = best_pair(getattr(mod, gpl_name), py_func, args.n, args.repeat)
            if isinstance(r_py, float):
                assert math.isclose(r_gpl, r_py, rel_tol=1e-12), (label, r_gpl, r_py)  # type: ignore[arg-type]
            else:
                assert r_gpl == r_py, (label, r_gpl, r_py)
            ratio = t_gpl / t_py
            worst = max(worst, ratio)
            print(f"{label:32} {t_gpl * 1e3:9.1f}ms {t_py * 1e3:7.1f}ms {ratio:6.2f}")
        print(f"worst ratio {worst:.2f} (target <= 1.5)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
