"""Front-end speed: lex+parse of a 20,000-line GPL project vs CPython's ``ast.parse`` on Python.

Run::

    python benchmarks/parse_speed.py [--lines 20000] [--module-lines 150] [--runs 7] [--profile] [--out DIR] [--cpu]

One deterministic generator emits the GPL project and a Python program *line for line*.  The GPL
side is a real project: ``Project.gpr`` and one ``.gpl`` file per module, written to a temporary
folder (or ``--out DIR``) and read back with :func:`gpl2py.project.load_project`, so the timed
sources are exactly what ``gpl2py check`` would parse.  It uses what vendor code uses: modules with
classes and properties inside ``#Region`` lines, Functions with ByVal/ByRef, block Ifs with ElseIf,
For/Step, While, Do/Loop Until, Select Case, Try/Catch/Finally with a ``GoTo retry`` from the Catch
back into the Try, trailing comments and messages continued with `` _``.  Every GPL line has a
Python counterpart with the same job (``Dim`` -> assignment, ``If … Then`` -> ``if …:``,
``Select Case`` -> ``match``, ``Try/Catch`` -> ``try/except`` …).  GPL's ``End …``/``Next``/label
lines have no Python statement; they become Python comment lines, so both sides have exactly the
same number of lines (this favours Python slightly).

Modules are about ``--module-lines`` long (real projects average about 110 lines a file; the
default 150 sits in the 100-200 range of real code), and the Python twin is split into the same
modules, one ``ast.parse`` per module, as the GPL side parses one file at a time.

Only lex+parse is timed (the files are read once, before timing).  Both sides run in this process,
in turns, under the same garbage-collector state: off, the state gpl2py parses in
(``gpl2py.gpl.syntax.lexer.gc_paused``), so ``ast.parse`` does not pay for collections the GPL side
skips.  Printed: the median of ``--runs`` runs of each with the spread, and the median of the
per-turn ratios ``gpl / python``.  Target: <= 3x.  The reference workload R (``_reference``) runs
in every turn too, under the same collector state and clock, and each time is printed once more
in R and each rate in lines per R (against R of its turn): the figures to compare between
machines.
"""

from __future__ import annotations

import argparse
import ast
import cProfile
import pstats
import random
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "runtime")]  # this checkout's gpl2py and gplrt

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _reference import HOW_TO_COMPARE, Reference, times_r  # noqa: E402
from _sidebyside import side_by_side  # noqa: E402

from gpl2py.diagnostics import DiagnosticSink  # noqa: E402
from gpl2py.project import load_project  # noqa: E402
from gpl2py.gpl.syntax.parser import parse  # noqa: E402

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
        c = r.randrange(7)
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
        elif c == 5:
            self.emit("done = False ' keep the gripper closed while moving", "done = False  # keep the gripper closed while moving")
        else:  # a message built over a ' _' continuation, as vendor code writes long replies
            self.emit('msg = "Station " & CStr(i) _', 'msg = ("Station " + str(i)')
            self.emit('    & " at " & CStr(loc1.X) & ", " & CStr(loc1.Y) _', '    + " at " + str(loc1.x) + ", " + str(loc1.y)')
            self.emit('    & " mm"', '    + " mm")')

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
            self.emit("retry:", "# retry:")
            self.block(inner)
            self.emit("Catch ex", "except Exception as ex:")
            self.emit("    If ex.ErrorCode = -1012 Then GoTo retry", "    if ex.error_code == -1012: pass")
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
        short = budget < 300  # a realistic module: two or three procedures
        self.emit(f"Module Cell{index}", f"class Cell{index}:")
        self.depth += 1
        self.emit("Public count As Integer = 10", "count: int = 10")
        self.emit("Private grid(20, 20) As Double", "grid = [[0.0] * 21 for _ in range(21)]")
        self.emit("Dim msg As String, mode As Integer, done As Boolean", "msg = ''; mode = 0; done = False")
        self.emit('#Region "Station"', "# region Station")
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
        self.emit("#End Region", "# end region")
        p = 0
        while len(self.gpl) - start < budget - 2:
            left = budget - 2 - (len(self.gpl) - start)
            size = self.r.randrange(15, 60) if not short else max(5, min(left - 8, self.r.randrange(25, 60)))
            self.procedure(f"Proc{index}_{p}", size)
            p += 1
        self.depth -= 1
        self.emit("End Module", "# end module")

    def project(self, lines: int, module_lines: int) -> tuple[dict[str, str], dict[str, str]]:
        """``({file name: GPL text}, {file name: Python text})``: one file per module on each side,
        ``lines`` lines in all, modules of about ``module_lines`` lines."""
        self.gpl.append("' generated GPL benchmark project")
        self.py.append("import math")
        starts: list[int] = []
        m = 0
        while len(self.gpl) < lines - 400:
            starts.append(0 if m == 0 else len(self.gpl))
            size = self.r.randrange(module_lines * 2 // 3, module_lines * 4 // 3 + 1)
            self.module(m, min(size, lines - 400 - len(self.gpl) + 50))
            m += 1
        while len(self.gpl) < lines:
            self.gpl.append("' padding")
            self.py.append("# padding")
        del self.gpl[lines:]
        del self.py[lines:]
        bounds = starts + [lines]
        files = {
            f"Cell{i}.gpl": "\n".join(self.gpl[bounds[i]:bounds[i + 1]]) + "\n" for i in range(len(starts))
        }
        py = {
            f"cell{i}.py": "\n".join(self.py[bounds[i]:bounds[i + 1]]) + "\n" for i in range(len(starts))
        }
        return files, py


def write_project(folder: Path, files: dict[str, str]) -> None:
    """The benchmark project on disk, as a controller would hold it: Project.gpr plus sources."""
    folder.mkdir(parents=True, exist_ok=True)
    gpr = ["' Project file, generated by benchmarks/parse_speed.py", "ProjectBegin",
           'ProjectName="ParseBench"', 'ProjectStart="Cell0.Proc0_0"']
    gpr += [f'ProjectSource="{name}"' for name in files] + ["ProjectEnd"]
    (folder / "Project.gpr").write_text("\r\n".join(gpr) + "\r\n")
    for name, text in files.items():
        (folder / name).write_text(text)


def main() -> None:
    ap = argparse.ArgumentParser(description="GPL lex+parse speed vs ast.parse")
    ap.add_argument("--lines", type=int, default=20000)
    ap.add_argument("--module-lines", type=int, default=150,
                    help="about this many lines per module (900: the large modules of earlier runs)")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--profile", action="store_true", help="print a cProfile of one GPL parse")
    ap.add_argument("--out", type=Path, help="keep the generated project in this folder")
    ap.add_argument("--cpu", action="store_true",
                    help="time with the process's CPU time instead of the wall clock: steadier on a "
                    "machine shared with other work (both sides alike)")
    args = ap.parse_args()

    files, py = Generator(seed=20240521).project(args.lines, args.module_lines)
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.out or Path(tmp) / "ParseBench"
        write_project(folder, files)
        sink = DiagnosticSink()
        project = load_project(folder, sink)
        assert project is not None
        sources = project.sources
        for source in sources:
            parse(source, sink)
        if len(sink):
            for d in sink.sorted()[:10]:
                print(d.render(project.source(d.span.file) if d.span else None))
            raise SystemExit("the generated GPL project must load and parse without diagnostics")
    gpl_lines = sum(s.text.count("\n") for s in sources)
    assert gpl_lines == sum(text.count("\n") for text in py.values()) == args.lines
    texts = list(py.items())
    for name, text in texts:
        ast.parse(text, name)  # the Python twin must be valid too

    def parse_gpl() -> None:
        for source in sources:
            parse(source, DiagnosticSink())

    def parse_python() -> None:
        for name, text in texts:
            ast.parse(text, name)

    if args.profile:
        prof = cProfile.Profile()
        prof.enable()
        parse_gpl()
        prof.disable()
        pstats.Stats(prof).sort_stats("tottime").print_stats(15)

    ref = Reference()
    pair = side_by_side(parse_gpl, parse_python, args.runs, gc_enabled=False,
                        clock=time.process_time if args.cpu else time.perf_counter, reference=ref)
    assert pair.ref is not None
    gpl_rate = statistics.median(times_r([args.lines / t for t in pair.a.values], pair.ref.values))
    py_rate = statistics.median(times_r([args.lines / t for t in pair.b.values], pair.ref.values))
    print(f"lines:            {args.lines} GPL and {args.lines} Python, in {len(sources)} modules each "
          f"(about {args.lines // len(sources)} lines a module)")
    print("collector:        off on both sides (gpl2py parses with it paused)")
    print(f"gpl2py lex+parse: {pair.a.text()}  ({args.lines / pair.a.median:,.0f} GPL lines/s)")
    print(f"ast.parse:        {pair.b.text()}  ({args.lines / pair.b.median:,.0f} Python lines/s)")
    print(f"ratio gpl/python: {pair.ratio_text()}  (target <= 3x)")
    print(f"in R:             gpl2py {pair.a_in_r.text(1, 'R', 3)}  ({gpl_rate:,.0f} GPL lines per R); "
          f"ast.parse {pair.b_in_r.text(1, 'R', 3)}  ({py_rate:,.0f} Python lines per R)")
    print(ref.line())
    print(HOW_TO_COMPARE)


if __name__ == "__main__":
    main()
