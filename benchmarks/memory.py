"""Memory per byte of source: ``gpl2py check`` and ``gpl2py PROJECT -o OUT`` on ~8 MB projects.

Run::

    python benchmarks/memory.py [--mb 8] [--runs 3] [--input corpus,dense] [--command check,translate]
    python benchmarks/memory.py --input shapes --mb 1,2

The measure (docs/security.md, "Input size") is the memory the *source* costs, as a multiple of
the size of the source files the project parses (``.gpl``/``.gpo``; Project.gpr and ``.gpp`` files
excluded).  Three figures, each the median of ``--runs`` runs (min-max in brackets):

* **rss**: ``ru_maxrss`` of the command run in a fresh interpreter (``python -m gpl2py ...``),
  minus the median ``ru_maxrss`` of the same command on a one-module project: the interpreter,
  gpl2py and the runtime the catalogue imports (the baseline) are not the source's cost;
* **traced**: the ``tracemalloc`` peak of the command run in-process after the same command has
  run once on the one-module project (so imports and caches are already paid);
* **cpu**: the CPU time (user + system) of the fresh-interpreter run, and per MB of source (less
  the median time of the same command on the one-module project: the start-up).  With several
  sizes (``--mb 1,2``) it shows whether the time grows with the source or faster (CPU time, not
  wall time: the machine is shared, and what grows faster than the source is work).

Two inputs of ordinary code: ``corpus``, the TCS project of the corpus (``tcs-3.0C1-pa``: real
code, comments, long lines) copied until it reaches the size, copy *k* with every module, top-level class and
module member renamed ``<name>_k`` so that the copies form one project without errors (a
project with errors is not lowered, and ``check`` lowers); ``dense``, the generator of
``benchmarks/transpile_speed.py`` (short statements, an expression every few characters).
And one-module projects whose one statement is one kind of token or shape made as long as the
size (issue 20, item 3; ``--input shapes`` selects them all): ``string``, a string literal;
``comment``, a comment; ``ident``, an identifier (an error: GPL names have at most 128 characters); ``number``,
a Real literal ``1.000...`` (an Integer literal of 4,301 digits or more is another matter: Python's
``int()`` refuses it); ``sum``, one expression ``1+1+...``; ``dim``, one ``Dim v0, v1, ... As
Integer``.  Target: at most 30x for both memory figures, every input, both commands, and a time
per MB that does not grow with the size.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import statistics
import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

#: The real code (``$GPL_CORPUS``, else ``../shared/corpus`` beside the repository), as the tests
#: and the other benchmarks find it.
CORPUS = Path(os.environ.get("GPL_CORPUS") or ROOT.parent / "shared" / "corpus")
TARGET = 30.0


def _corpus_dir() -> Path:
    if (CORPUS / "tcs-3.0C1-pa").is_dir():
        return CORPUS / "tcs-3.0C1-pa"
    raise SystemExit(f"corpus not found at {CORPUS}: set GPL_CORPUS to the folder holding tcs-3.0C1-pa")


# ------------------------------------------------------------------------------------ inputs


def _write_project(folder: Path, name: str, start: str, files: dict[str, str | bytes]) -> int:
    """Write a project; returns the bytes of its parsed sources (.gpl/.gpo)."""
    folder.mkdir(parents=True)
    gpr = ["ProjectBegin", f'ProjectName="{name}"', f'ProjectStart="{start}"']
    size = 0
    for fname, text in files.items():
        data = text.encode("latin-1") if isinstance(text, str) else text
        (folder / fname).write_bytes(data)
        gpr.append(f'ProjectSource="{fname}"')
        if fname.lower().endswith((".gpl", ".gpo")):
            size += len(data)
    (folder / "Project.gpr").write_text("\n".join(gpr + ["ProjectEnd"]) + "\n")
    return size


def tiny_project(folder: Path) -> int:
    text = "Module Main\n    Public Sub Run()\n        Console.WriteLine(\"hi\")\n    End Sub\nEnd Module\n"
    return _write_project(folder, "Tiny", "Main.Run", {"Main.gpl": text})


#: The one-statement shapes: name -> (the statement for about ``n`` bytes, whether it is an error).
SHAPES: dict[str, tuple[Callable[[int], str], bool]] = {
    "string": (lambda n: 'Dim s As String = "' + "x" * n + '"', False),
    "comment": (lambda n: "' " + "x" * n, False),
    "ident": (lambda n: "Dim a" + "x" * n + " As Integer", True),
    "number": (lambda n: "Dim d As Double = 1." + "0" * n, False),
    "sum": (lambda n: "Dim d As Integer = 1" + "+1" * (n // 2), False),
    "dim": (lambda n: "Dim " + ", ".join(f"v{i}" for i in range(_names_in(n))) + " As Integer", False),
}


def _names_in(n: int) -> int:
    """How many names ``v0, v1, ...`` fill about ``n`` bytes."""
    count, size = 0, 0
    while size < n:
        size += len(f"v{count}, ")
        count += 1
    return count


def shape_project(folder: Path, mb: float, shape: str) -> int:
    """A one-module project whose Sub holds one statement of ``shape`` (:data:`SHAPES`)."""
    statement = SHAPES[shape][0](int(mb * 1e6))
    text = f"Module Main\n    Public Sub Run()\n        {statement}\n    End Sub\nEnd Module\n"
    return _write_project(folder, "Shape", "Main.Run", {"Main.gpl": text})


def dense_project(folder: Path, mb: float) -> int:
    from transpile_speed import generate

    lines = int(mb * 1e6 / 27.8)  # the generator writes ~27.8 bytes a line
    return _write_project(folder, "Dense", "Mod0.Run", dict(generate(lines)))


def corpus_project(folder: Path, mb: float) -> int:
    """Copies of tcs-3.0C1-pa up to ``mb`` MB of source, names renamed per copy (module doc)."""
    src = _corpus_dir()
    gpr = (src / "Project.gpr").read_text(encoding="latin-1")
    names = [line.split('"')[1] for line in gpr.splitlines() if line.startswith("ProjectSource=")]
    texts = {n: (src / n).read_text(encoding="latin-1") for n in names if not n.lower().endswith(".gpp")}
    protected = {n: (src / n).read_bytes() for n in names if n.lower().endswith(".gpp")}
    renamed = _declared_names(texts)
    one = sum(len(t.encode("latin-1")) for t in texts.values())
    files: dict[str, str | bytes] = {}
    for k in range(max(1, round(mb * 1e6 / one))):
        for n, text in texts.items():
            stem, dot, ext = n.rpartition(".")
            files[f"{stem}_{k}{dot}{ext}" if k else n] = _rename(text, renamed, k) if k else text
    files.update(protected)
    return _write_project(folder, "Corpus", "startmain", files)


def _declared_names(texts: dict[str, str]) -> tuple[set[str], set[str]]:
    """(modules and top-level classes, every name to rename): those, module members, and the
    Consts and Shared fields of top-level classes (visible without qualification too)."""
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.source import SourceFile
    from gpl2py.gpl.syntax import ast as A
    from gpl2py.gpl.syntax.parser import parse

    modules: set[str] = set()
    names: set[str] = set()
    for n, text in texts.items():
        unit = parse(SourceFile(n, text), DiagnosticSink())
        for m in unit.members:
            if isinstance(m, A.ModuleDecl):
                modules.add(m.name.lower())
                for member in m.members:
                    if isinstance(member, A.VarDecl):
                        names.update(d.name.lower() for d in member.declarators)
                    elif hasattr(member, "name"):
                        names.add(member.name.lower())  # type: ignore[attr-defined]
            elif isinstance(m, A.ClassDecl):  # its Consts and Shared fields are seen like a module's
                modules.add(m.name.lower())
                for member in m.members:
                    if isinstance(member, A.VarDecl) and (member.is_const or "Shared" in member.modifiers):
                        names.update(d.name.lower() for d in member.declarators)
    names.discard("init")  # each module's Init is its own (called by the package, never by name)
    return modules, names | modules


def _rename(text: str, renamed: tuple[set[str], set[str]], k: int) -> str:
    """``text`` with every renamed name spelled ``<name>_k``: a name not after ``.``, or after
    ``Module.`` / ``Class.`` (a member reached through its module or class)."""
    from gpl2py.diagnostics import DiagnosticSink
    from gpl2py.source import SourceFile
    from gpl2py.gpl.syntax.lexer import tokenize
    from gpl2py.gpl.syntax.tokens import TokenKind as K

    modules, names = renamed
    lines = text.split("\n")
    edits: dict[int, list[tuple[int, int]]] = {}
    toks = [t for t in tokenize(SourceFile("x", text), DiagnosticSink()) if t.kind is not K.COMMENT]
    for i, tok in enumerate(toks):
        if tok.kind is not K.IDENT or tok.text.lower() not in names:
            continue
        if i > 0 and toks[i - 1].kind is K.DOT:
            if i < 2 or toks[i - 2].text.lower() not in modules:
                continue
        edits.setdefault(tok.span.line, []).append((tok.span.col, tok.span.end_col))
    for line, cols in edits.items():
        s = lines[line - 1]
        for col, end in sorted(cols, reverse=True):
            s = s[:end - 1] + f"_{k}" + s[end - 1:]
        lines[line - 1] = s
    return "\n".join(lines)


# ------------------------------------------------------------------------------- measuring


def _argv(command: str, project: Path, out: Path) -> list[str]:
    return ["check", str(project)] if command == "check" else [str(project), "-o", str(out), "--quiet"]


def rss_kb(command: str, project: Path, out: Path, errors: bool = False) -> tuple[int, float]:
    """``ru_maxrss`` (KB) and CPU seconds of the command in a fresh interpreter.  ``errors``: the
    input is meant to have errors (exit status 1 is what it should give)."""
    argv = [sys.executable, "-m", "gpl2py", *_argv(command, project, out)]
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=ROOT)
    assert proc.stderr is not None
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != (1 if errors else 0):
        raise SystemExit(f"{' '.join(argv)} failed ({proc.returncode}):\n{err.decode()[-2000:]}")
    return usage.ru_maxrss, usage.ru_utime + usage.ru_stime


def traced_bytes(command: str, project: Path, tiny: Path, out: Path, errors: bool = False) -> int:
    """The tracemalloc peak of the command, in a fresh interpreter, after a run on ``tiny``."""
    argv = [sys.executable, __file__, "--traced", command, str(project), str(tiny), str(out), str(int(errors))]
    res = subprocess.run(argv, capture_output=True, text=True, cwd=ROOT)
    if res.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed:\n{res.stderr[-2000:]}")
    return int(res.stdout.split()[-1])


def _traced_main(command: str, project: str, tiny: str, out: str, errors: str) -> int:
    import tracemalloc

    from gpl2py.cli import main

    sink = io.StringIO()
    with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
        if main(_argv(command, Path(tiny), Path(out) / "tiny")) != 0:
            raise SystemExit(sink.getvalue())
        tracemalloc.start()
        status = main(_argv(command, Path(project), Path(out) / "big"))
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    if status != int(errors):
        raise SystemExit(sink.getvalue()[-2000:])
    print(peak)
    return 0


def _spread(values: list[float], digits: int = 1) -> str:
    return f"{statistics.median(values):.{digits}f} [{min(values):.{digits}f}-{max(values):.{digits}f}]"


def main() -> int:
    if len(sys.argv) > 1 and sys.argv[1] == "--traced":
        return _traced_main(*sys.argv[2:7])
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mb", default="8", help="source size of each input (MB); several: 1,2")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--input", default="corpus,dense", help=f"corpus, dense, {', '.join(SHAPES)} or shapes")
    ap.add_argument("--command", default="check,translate")
    ap.add_argument("--no-traced", action="store_true", help="only the rss figure")
    args = ap.parse_args()
    names = [n for name in args.input.split(",") for n in (SHAPES if name == "shapes" else [name])]
    if unknown := [n for n in names if n not in SHAPES and n not in ("corpus", "dense")]:
        ap.error(f"unknown input {', '.join(unknown)}")
    sizes = [float(mb) for mb in args.mb.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        base = Path(tmp)
        tiny = base / "tiny"
        tiny_project(tiny)
        makers: dict[str, Callable[[Path, float], int]] = {"corpus": corpus_project, "dense": dense_project}
        for shape in SHAPES:
            makers[shape] = lambda folder, mb, shape=shape: shape_project(folder, mb, shape)
        inputs = {(name, mb): makers[name](base / f"{name}-{mb}", mb) for name in names for mb in sizes}
        print(f"python {sys.version.split()[0]}; runs: {args.runs}; median [min-max]")
        print(f"{'input':8} {'command':10} {'source MB':>9}  {'rss MB':>20} {'base MB':>8} "
              f"{'rss x':>20}  {'cpu s':>20} {'cpu s/MB':>8}  {'traced MB':>20} {'traced x':>20}")
        for command in args.command.split(","):
            out = base / "out"
            base_runs = [rss_kb(command, tiny, out) for _ in range(args.runs)]
            baseline = statistics.median(r for r, _ in base_runs) / 1024
            base_cpu = statistics.median(c for _, c in base_runs)
            for (name, mb_asked), size in inputs.items():
                folder = base / f"{name}-{mb_asked}"
                errors = name in SHAPES and SHAPES[name][1]
                mb = size / 2**20
                runs = [rss_kb(command, folder, out, errors) for _ in range(args.runs)]
                rss = [r / 1024 for r, _ in runs]
                cpu = [c for _, c in runs]
                above = [r - baseline for r in rss]
                row = (f"{name:8} {command:10} {mb:9.2f}  {_spread(rss):>20} {baseline:8.1f} "
                       f"{_spread([a / mb for a in above]):>20}  {_spread(cpu, 2):>20} "
                       f"{(statistics.median(cpu) - base_cpu) / mb:8.2f}")
                if not args.no_traced:
                    traced = [traced_bytes(command, folder, tiny, out, errors) / 2**20 for _ in range(args.runs)]
                    row += f"  {_spread(traced):>20} {_spread([x / mb for x in traced]):>20}"
                print(row, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
