"""V+ check and translate per line, side by side with GPL's on projects of the same size (issue 21).

Run::

    python benchmarks/vplus_speed.py [--lines 10000] [--runs 5]

A deterministic generator writes a V+ project the way the corpus is written: files of 100-200
lines, each a few programs with AUTO declarations, arithmetic, strings, FOR/WHILE/IF/CASE blocks,
transformations (SET, SHIFT, ``:``), TYPE, and CALLs of programs of other files by reference and by
value; the GPL project of the same number of lines is ``transpile_speed.generate``'s.  Both go
through :func:`gpl2py.transpile.transpile` in this process, alternately, ``--runs`` times after
one untimed run of each: **translate** (everything but writing files) and **check**
(``keep_modules=False``, as ``gpl2py check``).  Printed: CPU microseconds per source line, median
and spread (min-max) of the runs, for each language and command, and the ratio V+/GPL.  CPU time
because the machine is shared.
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from transpile_speed import generate, write_project  # noqa: E402

from gpl2py.diagnostics import DiagnosticSink  # noqa: E402
from gpl2py.transpile import transpile  # noqa: E402


def _program(r: random.Random, f: int, k: int, files: int) -> list[str]:
    other = r.randrange(files)
    lines = [
        f".PROGRAM work{f}.{k}(count, $name, pose)",
        f"    ; program {k} of file {f}: arithmetic, strings, locations and calls",
        "    AUTO i, j, total, $text, step.size, place",
        "    total = 0",
        f"    step.size = {r.randint(1, 9)}",
        "    $text = \"\"",
        "    FOR i = 1 TO count",
        "        total = total + i * step.size MOD 7",
        "        IF (total > 100) AND (i < count) THEN",
        "            total = total - 50",
        "        ELSE",
        "            total = total + 1",
        "        END",
        "        CASE i MOD 3 OF",
        "        VALUE 0:",
        "            $text = $text + \"a\"",
        "        VALUE 1, 2:",
        "            $text = $name + $CHR(65 + i MOD 26)",
        "        ANY",
        "            TYPE \"none\"",
        "        END",
        "    END",
        "    j = 0",
        "    WHILE j < 10 DO",
        "        j = j + 1",
        f"        counter.{f} = counter.{f} + SQRT(j) * COS(j * 10)",
        "    END",
        f"    SET place = SHIFT(pose BY {r.randint(1, 90)}, total, j):RZ(i)",
        "    SET pose = place",
        f"    CALL work{other}.{r.randrange(3)}(j, $text, pose)",
        "    TYPE $name, \": \", total, \" \", LEN($text), /S",
        "    TYPE \" done\"",
        ".END",
        "",
    ]
    return lines


def generate_vplus(lines: int, seed: int = 7) -> dict[str, str]:
    r = random.Random(seed)
    files: dict[str, str] = {}
    total = 0
    n_files = max(1, lines // 150)
    f = 0
    while total < lines:
        body = [f"; file {f}", ""]
        for k in range(3):
            body += _program(r, f, k, n_files)
        body += [f".REALS", f"counter.{f} 0", ".END", ""]
        files[f"file{f:05d}.v2"] = "\n".join(body)
        total += len(body)
        f += 1
    return files


def _cpu(path: Path, keep: bool) -> float:
    sink = DiagnosticSink()
    t0 = time.process_time()
    out = transpile(path, sink, keep_modules=keep)
    spent = time.process_time() - t0
    if sink.has_errors() or (keep and out is None):
        raise SystemExit("\n".join(d.header() for d in sink.errors[:10]))
    return spent


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lines", type=int, default=10000)
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        vdir, gdir = Path(tmp, "vplus"), Path(tmp, "gpl")
        vdir.mkdir()
        vfiles = generate_vplus(args.lines)
        for name, text in vfiles.items():
            (vdir / name).write_text(text)
        write_project(gdir, generate(args.lines))
        vlines = sum(t.count("\n") + 1 for t in vfiles.values())
        glines = sum(len(p.read_text().splitlines()) for p in gdir.glob("*.gpl"))
        samples: dict[tuple[str, str], list[float]] = {}
        for run in range(args.runs + 1):
            for lang, path, n in (("V+", vdir, vlines), ("GPL", gdir, glines)):
                for command, keep in (("translate", True), ("check", False)):
                    per_line = _cpu(path, keep) / n * 1e6
                    if run:  # (the first run of each is untimed: imports, caches)
                        samples.setdefault((lang, command), []).append(per_line)
        print(f"V+ {vlines} lines in {len(vfiles)} files, GPL {glines} lines; {args.runs} runs each, "
              "CPU us per line: median (min-max)")
        for command in ("translate", "check"):
            med = {}
            for lang in ("V+", "GPL"):
                s = samples[(lang, command)]
                med[lang] = statistics.median(s)
                print(f"  {command:9} {lang:3}: {med[lang]:7.1f} ({min(s):.1f}-{max(s):.1f})")
            print(f"  {command:9} V+/GPL: {med['V+'] / med['GPL']:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
