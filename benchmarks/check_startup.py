"""Edit-loop cost: ``gpl2py check`` of a 5-line GPL file vs ``python -m py_compile`` of a 5-line
Python file, both as fresh processes.

Run::

    python benchmarks/check_startup.py [--runs 21] [--importtime] [--no-bytecode-cache]

This is what a porting engineer pays per save: a new process that starts the interpreter, imports
gpl2py, loads the built-in catalogue, and checks one small file.  The baseline is the same for
Python: a new interpreter that byte-compiles one small file.  Interpreter start-up is in both.  The
two commands run in turns (after two untimed runs of each), and the medians of their wall times
are printed with the spread, then the median of the per-turn ratios.  Target: ratio <= 4.
The reference workload R (``_reference``) runs in this process after each turn, and both medians
are printed once more in R (each time divided by R of its turn), the figures to compare between
machines.

Both run with compiled bytecode cached, as an installed package and the standard library are (pip
compiles them at install): the environment's ``PYTHONDONTWRITEBYTECODE`` is dropped and
``PYTHONPYCACHEPREFIX`` points both commands at one fresh cache folder, which the untimed first
runs fill.  Without a cache every start would compile gpl2py from source, which no installed
gpl2py does.  ``PYTHONPATH`` makes the command run this checkout's gpl2py and gplrt.
``--no-bytecode-cache`` sets ``PYTHONDONTWRITEBYTECODE=1`` for both instead: every start then
compiles whatever has no bytecode cached beside its source (all of gpl2py in a fresh checkout).

``--importtime`` prints the slowest imports of one ``gpl2py check`` (``python -X importtime``) and
whether it imported numpy, pinocchio, coal or ruckig.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _reference import HOW_TO_COMPARE, Reference  # noqa: E402
from _sidebyside import Pair, Samples  # noqa: E402

GPL = """Module Hello
    Public Sub Main()
        Console.WriteLine("hello " & CStr(1 + 2))
    End Sub
End Module
"""

PY = """def main():
    print("hello " + str(1 + 2))


main()
"""

HEAVY = ("numpy", "pinocchio", "coal", "ruckig")


ROOT = Path(__file__).resolve().parents[1]


def gpl2py_command() -> list[str]:
    """The installed ``gpl2py`` script beside this interpreter, else ``python -m gpl2py``."""
    script = Path(sys.executable).with_name("gpl2py")
    return [str(script)] if script.exists() else [sys.executable, "-m", "gpl2py"]


def environment(cache: Path, bytecode: bool) -> dict[str, str]:
    """This environment with bytecode cached in ``cache``, or never written (module docstring)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "PYTHONPYCACHEPREFIX")}
    if bytecode:
        env["PYTHONPYCACHEPREFIX"] = str(cache)
    else:
        env["PYTHONDONTWRITEBYTECODE"] = "1"
    # gpl2py and gplrt of this checkout, whichever one the interpreter has installed
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), str(ROOT / "runtime")])
    return env


def wall(cmd: list[str], env: dict[str, str]) -> float:
    t0 = time.perf_counter()
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    seconds = time.perf_counter() - t0
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited with {done.returncode}")
    return seconds


def importtime(cmd: list[str], env: dict[str, str]) -> None:
    env = dict(env, PYTHONPROFILEIMPORTTIME="1")
    done = subprocess.run(cmd, env=env, capture_output=True, text=True)
    rows = []
    for line in done.stderr.splitlines():
        if not line.startswith("import time:") or "cumulative" in line:
            continue
        self_us, cum_us, name = line.split(":", 1)[1].split("|")
        rows.append((int(cum_us), int(self_us), name.rstrip()[1:]))
    top = [r for r in rows if not r[2].startswith(" ")]
    print(f"top-level imports of one check ({len(rows)} modules):")
    for cum, _, name in sorted(top, reverse=True)[:12]:
        print(f"  {cum / 1000:7.1f} ms  {name}")
    names = {r[2].strip() for r in rows}
    heavy = [h for h in HEAVY if h in names]
    print(f"heavy packages imported: {', '.join(heavy) if heavy else 'none'}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=21)
    ap.add_argument("--importtime", action="store_true")
    ap.add_argument("--no-bytecode-cache", action="store_true", help="both commands without cached bytecode")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        gpl_file = Path(tmp) / "Hello.gpl"
        py_file = Path(tmp) / "hello.py"
        gpl_file.write_text(GPL)
        py_file.write_text(PY)
        check = gpl2py_command() + ["check", str(gpl_file)]
        compile_ = [sys.executable, "-m", "py_compile", str(py_file)]
        env = environment(Path(tmp) / "pycache", not args.no_bytecode_cache)
        ref = Reference()
        for _ in range(2):  # fills the bytecode cache of both (if there is one)
            wall(check, env)
            wall(compile_, env)
            ref.run(record=False)
        ta: list[float] = []
        tb: list[float] = []
        for _ in range(args.runs):
            ta.append(wall(check, env))
            tb.append(wall(compile_, env))
            ref.run(match=ta[-1] + tb[-1])
        pair = Pair(Samples(ta), Samples(tb), Samples(ref.wall))
        print(f"gpl2py check, 5-line GPL file:         {pair.a.text()}  {pair.a_in_r.text(1, 'R', 2)}")
        print(f"python -m py_compile, 5-line Python:   {pair.b.text()}  {pair.b_in_r.text(1, 'R', 2)}")
        print(f"ratio check / py_compile:              {pair.ratio_text()} (target <= 4)")
        print(ref.line())
        print(HOW_TO_COMPARE)
        print("bytecode:", "never written (PYTHONDONTWRITEBYTECODE=1)" if args.no_bytecode_cache else "cached")
        if args.importtime:
            importtime(check, env)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
