"""Front-end speed: lex+parse of a 20,000-line GPL project vs CPython's ``ast.parse`` on Python.

Run::

    python benchmarks/parse_speed.py [--lines 20000] [--repeat 5] [--profile]

One deterministic generator emits the GPL project and a Python program *line for line*: every GPL
line has a Python counterpart with the same job (``Dim`` -> annotated assignment, ``If … Then`` ->
``if …:``, ``Select Case`` -> ``match``, ``Try/Catch`` -> ``try/except`` …).  GPL's ``End …``/``Next``
lines have no Python statement; they become Python comment lines, so both files have exactly the
same number of lines (this favours Python slightly).  Both are timed in the same process, best of
``--repeat`` runs each, and the ratio ``gpl / python`` is printed.  Target: under 5x.
"""

from __future__ import annotations

import argparse
import ast
import cProfile
import pstats
import random
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from gpl2py.diagnostics import DiagnosticSink  # noqa: E402
from gpl2py.source import SourceFile  # noqa: E402
from gpl2py.syntax.parser import parse  # noqa: E402

Pair = tuple[str, str]  # (GPL line, Python line), without indentation


class Generator:
    """Emits matching GPL and Python lines until the line budget is used."""

    def __init__(self, seed: int) -> None:
        self.r = random.Random(seed)
        self.gpl: list[str] = []
        self.py: list[str] = []
        self.depth = 0

    def emit(self, g: str, p: str, extra_py_indent: int = 0) -> None:
        self.gpl.append("    " * self.depth + g)
        self.py.append("    " * (self.depth + extra_py_indent) + p)

    # -- expressions ------------------------------------------------------------------------
    def operand(self) -> Pair:
        r = self.r
        c = r.randrange(7)
        if c == 0:
            n = r.randrange(1000)
            return str(n), str(n)
        if c == 1:
            v = f"{r.randrange(100)}.{r.randrange(100)}"
            return v, v
        if c == 2:
            v = r.choice(["x", "y", "count", "total", "speed"])
            return v, v
        if c == 3:
            a = r.choice(["i", "j", "k"])
            return f"grid({a}, {a} + 1)", f"grid[{a}][{a} + 1]"
        if c == 4:
            return "loc1.X", "loc1.x"
        if c == 5:
            return "Math.Sqrt(y * y + 1)", "math.sqrt(y * y + 1)"
        return "Robot.Where.Z", "robot.where.z"

    def expr(self, depth: int = 0) -> Pair:
        r = self.r
        if depth > 2 or r.random() < 0.3:
            return self.operand()
        lg, lp = self.expr(depth + 1)
        rg, rp = self.expr(depth + 1)
        op = r.choice(["+", "-", "*", "/", "^", "Mod", "\\"])
        pop = {"^": "**", "Mod": "%", "\\": "//"}.get(op, op)
        if r.random() < 0.3:
            return f"({lg} {op} {rg})", f"({lp} {pop} {rp})"
        return f"{lg} {op} {rg}", f"{lp} {pop} {rp}"

    def cond(self) -> Pair:
        r = self.r
        lg, lp = self.expr(2)
        rg, rp = self.expr(2)
        op = r.choice(["<", ">", "<=", ">=", "=", "<>"])
        pop = {"=": "==", "<>": "!="}.get(op, op)
        g, p = f"{lg} {op} {rg}", f"{lp} {pop} {rp}"
        if r.random() < 0.4:
            g, p = f"{g} AndAlso Not done", f"{p} and not done"
        return g, p

    # -- statements -------------------------------------------------------------------------
    def simple(self) -> None:
        r = self.r
        c = r.randrange(6)
        if c == 0:
            eg, ep = self.expr()
            self.emit(f"x = {eg}", f"x = {ep}")
        elif c == 1:
            self.emit('msg = "Count: " & CStr(i) & " of " & CStr(total)', 'msg = "Count: " + str(i) + " of " + str(total)')
        elif c == 2:
            self.emit("Move.Loc(loc1, prof1)", "move.loc(loc1, prof1)")
        elif c == 3:
            eg, ep = self.expr(1)
            self.emit(f"total += {eg} ' accumulate", f"total += {ep}  # accumulate")
        elif c == 4:
            self.emit("Console.WriteLine(msg)", "print(msg)")
        else:
            self.emit("done = False ' keep the gripper closed while moving", "done = False  # keep the gripper closed while moving")

    def block(self, budget: int) -> None:
        self.depth += 1
        n = 0
        while n < budget:
            before = len(self.gpl)
            self.statement(budget - n)
            n += len(self.gpl) - before
        self.depth -= 1

    def statement(self, budget: int) -> None:
        r = self.r
        if budget < 6 or self.depth > 5 or r.random() < 0.55:
            self.simple()
            return
        c = r.randrange(6)
        inner = min(budget - 3, r.randrange(2, 6))
        if c == 0:
            cg, cp = self.cond()
            self.emit(f"If {cg} Then", f"if {cp}:")
            self.block(inner)
            cg, cp = self.cond()
            self.emit(f"ElseIf {cg} Then", f"elif {cp}:")
            self.block(1)
            self.emit("Else", "else:")
            self.block(1)
            self.emit("End If", "# end if")
        elif c == 1:
            self.emit("For i = 1 To count Step 2", "for i in range(1, count, 2):")
            self.block(inner)
            self.emit("Next i", "# next i")
        elif c == 2:
            cg, cp = self.cond()
            self.emit(f"While {cg}", f"while {cp}:")
            self.block(inner)
            self.emit("End While", "# end while")
        elif c == 3:
            self.emit("Select Case mode", "match mode:")
            self.depth += 1
            self.emit("Case 1, 2, 3", "case 1 | 2 | 3:")
            self.block(1)
            self.emit('Case "home"', 'case "home":')
            self.block(1)
            self.emit("Case Else", "case _:")
            self.block(1)
            self.depth -= 1
            self.emit("End Select", "# end select")
        elif c == 4:
            self.emit("Try", "try:")
            self.block(inner)
            self.emit("Catch ex", "except Exception as ex:")
            self.emit("    If ex.ErrorCode = -153 Then prof1.Speed *= .9", "    if ex.error_code == -153: prof1.speed *= .9")
            self.emit("Finally", "finally:")
            self.block(1)
            self.emit("End Try", "# end try")
        else:
            cg, cp = self.cond()
            self.emit("Do", "while True:")
            self.block(inner)
            self.emit(f"Loop Until {cg}", f"    if {cp}: break")

    def procedure(self, name: str, budget: int) -> None:
        if self.r.random() < 0.5:
            self.emit(f"Public Function {name}(ByVal a As Double, ByRef b As Integer) As Double", f"def {name}(a: float, b: int) -> float:")
            self.depth += 1
            self.emit("Dim i, j, k As Integer", "i = j = k = 0")
            self.emit("Dim x, y, total As Double", "x = y = total = 0.0")
            self.depth -= 1
            self.block(budget)
            self.depth += 1
            self.emit("Return total", "return total")
            self.depth -= 1
            self.emit("End Function", "# end function")
        else:
            self.emit(f"Public Sub {name}()", f"def {name}() -> None:")
            self.depth += 1
            self.emit("Dim i, j, k As Integer", "i = j = k = 0")
            self.emit("Dim x, y, total As Double", "x = y = total = 0.0")
            self.emit("' move to the station, then report", "# move to the station, then report")
            self.depth -= 1
            self.block(budget)
            self.emit("End Sub", "# end sub")

    def module(self, index: int, budget: int) -> None:
        start = len(self.gpl)
        self.emit(f"Module Cell{index}", f"class Cell{index}:")
        self.depth += 1
        self.emit("Public count As Integer = 10", "count: int = 10")
        self.emit("Private grid(20, 20) As Double", "grid = [[0.0] * 21 for _ in range(21)]")
        self.emit("Dim msg As String, mode As Integer, done As Boolean", "msg = ''; mode = 0; done = False")
        self.emit("Public Class Station", "class Station:")
        self.depth += 1
        self.emit("Private size_in As Integer", "size_in: int = 0")
        self.emit("Public Property Size As Integer", "@property")
        self.emit("    Get", "def size(self) -> int:")
        self.emit("        Return size_in", "    return self.size_in")
        self.emit("    End Get", "# end get")
        self.emit("End Property", "# end property")
        self.depth -= 1
        self.emit("End Class", "# end class")
        p = 0
        while len(self.gpl) - start < budget - 2:
            self.procedure(f"Proc{index}_{p}", self.r.randrange(15, 60))
            p += 1
        self.depth -= 1
        self.emit("End Module", "# end module")

    def project(self, lines: int) -> tuple[str, str]:
        self.gpl.append("' generated GPL benchmark project")
        self.py.append("import math")
        m = 0
        while len(self.gpl) < lines - 400:
            self.module(m, min(900, lines - 400 - len(self.gpl) + 50))
            m += 1
        while len(self.gpl) < lines:
            self.gpl.append("' padding")
            self.py.append("# padding")
        del self.gpl[lines:]
        del self.py[lines:]
        return "\n".join(self.gpl) + "\n", "\n".join(self.py) + "\n"


def best_of(repeat: int, fn) -> float:  # type: ignore[no-untyped-def]
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description="GPL lex+parse speed vs ast.parse")
    ap.add_argument("--lines", type=int, default=20000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--profile", action="store_true", help="print a cProfile of one GPL parse")
    args = ap.parse_args()

    gpl, py = Generator(seed=20240521).project(args.lines)
    assert gpl.count("\n") == py.count("\n") == args.lines

    sink = DiagnosticSink()
    parse(SourceFile("bench.gpl", gpl), sink)
    if len(sink):
        for d in sink.sorted()[:10]:
            print(d.render(SourceFile("bench.gpl", gpl)))
        raise SystemExit("the generated GPL project must parse without diagnostics")
    ast.parse(py)  # the Python twin must be valid too

    if args.profile:
        prof = cProfile.Profile()
        prof.enable()
        parse(SourceFile("bench.gpl", gpl), DiagnosticSink())
        prof.disable()
        pstats.Stats(prof).sort_stats("tottime").print_stats(15)

    t_gpl = best_of(args.repeat, lambda: parse(SourceFile("bench.gpl", gpl), DiagnosticSink()))
    t_py = best_of(args.repeat, lambda: ast.parse(py))
    print(f"lines:            {args.lines}")
    print(f"gpl2py lex+parse: {t_gpl * 1000:8.1f} ms  ({args.lines / t_gpl:,.0f} GPL lines/s)")
    print(f"ast.parse:        {t_py * 1000:8.1f} ms  ({args.lines / t_py:,.0f} Python lines/s)")
    print(f"ratio gpl/python: {t_gpl / t_py:.2f}x  (target < 5x)")


if __name__ == "__main__":
    main()
