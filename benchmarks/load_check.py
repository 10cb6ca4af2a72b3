"""Does dividing by the reference workload R make a figure travel?  The same figure measured with
0, 1, 2 ... extra CPU-bound processes running, raw and normalised by R.

Run::

    python benchmarks/load_check.py [--what cell|sample|tcs] [--spinners 0,1,2] [--rounds 2] [--runs 5]

A machine twice as slow and a machine twice as busy look alike to a benchmark: both stretch its
wall-clock figures.  Extra load is the one we can make here, so it stands in for a slower machine:
for each number of *spinners* (``python -c "while True: pass"``, started before the condition's
runs and ended after them, by their process ids) the script measures ``--runs`` turns of the
figure, each followed by one run of R (as the benchmarks do), and prints per condition the median
of the raw figure and of the normalised one (the median of the per-turn products, as the
benchmarks print it, and for comparison the product of the two medians), and how far each moved
from the first condition.
The conditions run in ``--rounds`` passes, every other pass in reverse order (0, 1, 2, 2, 1, 0),
so that a drift of the machine's own background load falls on all conditions alike.

The figures (``--what``):

* ``cell``: the 200-part cell of ``benchmarks/motion_speed.py`` (``--parts``), controller seconds
  per wall-clock second and per CPU second; normalised: controller seconds per R (wall, CPU);
* ``sample``: a 50-move session of ``benchmarks/client_session.py --server sample``, simulated
  motion seconds per wall-clock second and per CPU second; normalised: motion seconds per R
  (wall, CPU);
* ``tcs``: the same with the vendor's TCS and PyLabRobot (``--server tcs``: fixed ports, so run
  it in a network of its own: ``unshare --net sh -c 'ip link set lo up && python ...'``).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _reference import HOW_TO_COMPARE, Reference, times_r  # noqa: E402

@contextmanager
def spinners(count: int) -> Iterator[None]:
    """``count`` CPU-bound processes running for the block; each ended by its own process id."""
    procs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(count)]
    try:
        time.sleep(0.5 if count else 0.0)  # let the scheduler see them
        yield
    finally:
        for p in procs:
            p.kill()
            p.wait()


def cell_turns(parts: int) -> Callable[[int, Reference], dict[str, list[float]]]:
    from motion_speed import cell_factors

    def measure(runs: int, ref: Reference) -> dict[str, list[float]]:
        walls, cpus, _, _ = cell_factors(runs, ref, parts)
        return {"wall": walls, "cpu": cpus}

    return measure


def session_turns(server: str, moves: int) -> Callable[[int, Reference], dict[str, list[float]]]:
    from client_session import run_sample, run_tcs

    def measure(runs: int, ref: Reference) -> dict[str, list[float]]:
        factors: dict[str, list[float]] = {"wall": [], "cpu": []}
        ref.run(record=False)
        for _ in range(runs):
            with tempfile.TemporaryDirectory() as tmp:
                if server == "tcs":
                    session = run_tcs(moves, 50.0, False, Path(tmp), "fast")
                else:
                    session = run_sample(moves, 50.0, Path(tmp), "fast")
            ref.run(match=session.wall)
            factors["wall"].append(session.motion / session.wall)
            factors["cpu"].append(session.motion / session.cpu)
        return factors

    return measure


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--what", choices=("cell", "sample", "tcs"), default="cell")
    ap.add_argument("--spinners", default="0,1,2", help="extra CPU-bound processes per condition")
    ap.add_argument("--rounds", type=int, default=2, help="passes over the conditions (default 2)")
    ap.add_argument("--runs", type=int, default=5, help="turns per condition and pass (default 5)")
    ap.add_argument("--parts", type=int, default=200, help="cell: parts placed (default 200)")
    ap.add_argument("--moves", type=int, default=50, help="sample, tcs: moves per session (default 50)")
    args = ap.parse_args()
    measure = cell_turns(args.parts) if args.what == "cell" else session_turns(args.what, args.moves)
    counts = [int(s) for s in args.spinners.split(",")]
    raw: dict[int, dict[str, list[float]]] = {k: {} for k in counts}
    norm: dict[int, dict[str, list[float]]] = {k: {} for k in counts}
    refs: dict[int, Reference] = {k: Reference() for k in counts}
    loads: dict[int, list[float]] = {k: [] for k in counts}
    for rnd in range(args.rounds):
        for k in (counts if rnd % 2 == 0 else counts[::-1]):
            ref = Reference()
            with spinners(k):
                figures = measure(args.runs, ref)
                loads[k].append(os.getloadavg()[0])
            refs[k].wall += ref.wall
            refs[k].cpu += ref.cpu
            for clock, values in figures.items():
                raw[k].setdefault(clock, []).extend(values)
                norm[k].setdefault(clock, []).extend(times_r(values, ref.times(time.process_time if clock == "cpu"
                                                                                else time.perf_counter)))
    unit = "controller s" if args.what == "cell" else "motion s"
    print(f"{args.what}: {args.rounds} passes of {args.runs} turns per condition, on {os.cpu_count()} CPUs; "
          "median (spread); 'moved' is the median against the first condition's")
    base = counts[0]
    for k in counts:
        print(f"{k} extra CPU-bound processes (load average {min(loads[k]):.1f}-{max(loads[k]):.1f}):")
        print(refs[k].line())
        for clock in raw[k]:
            r, n = raw[k][clock], norm[k][clock]
            moved_r = statistics.median(r) / statistics.median(raw[base][clock])
            moved_n = statistics.median(n) / statistics.median(norm[base][clock])
            ref_k = refs[k].cpu if clock == "cpu" else refs[k].wall
            ref_0 = refs[base].cpu if clock == "cpu" else refs[base].wall
            of_medians = statistics.median(r) * statistics.median(ref_k)
            moved_m = of_medians / (statistics.median(raw[base][clock]) * statistics.median(ref_0))
            print(f"  {clock:4} raw {statistics.median(r):9,.1f} {unit} per s (spread {min(r):,.1f}-{max(r):,.1f}) "
                  f"moved {moved_r:5.2f}x   normalised {statistics.median(n):8.2f} {unit} per R "
                  f"(spread {min(n):.2f}-{max(n):.2f}) moved {moved_n:5.2f}x   "
                  f"median x median of R {of_medians:8.2f} moved {moved_m:5.2f}x")
    print(HOW_TO_COMPARE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
