"""A sweep of the pick-and-place cell on Dask: one worker against two, and against a plain loop.

The sample's sweep (samples/sweep: the conveyor's interval and the fast Profiles' speed) over
``--sets`` parameter sets (default 200: 10 intervals x 20 speeds, every one a whole 8-part cell
run), three ways in each turn, in an order that turns round from one turn to the next so that no
side always runs first:

* ``loop``: ``Sweep.run_in_process``, each run in turn in this process (no Dask);
* ``1 worker`` and ``2 workers``: ``Sweep.run`` on a ``LocalCluster`` of that many worker
  processes, started for the turn.  Two times are taken: the **sweep** (from submitting the first
  run to the last row, on the started cluster: the workers' first imports are in it) and the
  **whole** (starting the cluster, the sweep, closing it: what ``gpl2py sweep`` costs).

Printed: the medians of ``--runs`` turns with their spread, the speed-up of two workers over one
(the median of the per-turn ratios), and Dask's overhead per run: (1 worker's sweep - loop) /
sets.  The project is translated once, before the turns.  After each turn the reference workload
R (``_reference``) runs for a quarter of the turn's time, and every time is printed once more in R.

CPU time, beside the wall time, says what the load of the machine took: the loop's is this
process's; a sweep's is the workers' (their processes' user + system time over the sweep, read on
each worker) and this process's ("this process": the client and, on a local cluster, the
scheduler).  The workers'
share of their cores, workers' CPU / (sweep wall x workers), is 1 on a machine with nothing else to
do; below it, something else had the cores (on 2 cores, the scheduler's own CPU is part of that).
The load average (1 minute) is read before every side.  The machine should be quiet: say the load
with the figures.

    python benchmarks/sweep_speed.py [--sets 200] [--runs 3]
"""

from __future__ import annotations

import argparse
import itertools
import os
import statistics
import time
from dataclasses import dataclass
from pathlib import Path

from _reference import HOW_TO_COMPARE, Reference, per_r

from gpl2py.sweep import Sweep
from gpl2py.sweep.cluster import Client, local_cluster

REPO = Path(__file__).resolve().parents[1]
SIDES = ("loop", "1 worker", "2 workers")


def the_sweep(sets: int) -> Sweep:
    """The sample's sweep with ``sets`` parameter sets (intervals and speeds as evenly as it goes)."""
    sweep = Sweep.from_file(REPO / "samples" / "pick_and_place", REPO / "samples" / "sweep" / "params.toml",
                            REPO / "samples" / "sweep" / "setup.py")
    intervals = [round(0.2 + 0.4 * i, 2) for i in range(10)]
    speeds = [5 * (k + 1) for k in range(20)]
    sweep.sets = [{"interval": i, "speed": s} for i, s in itertools.product(intervals, speeds)][:sets]
    return sweep


def _cpu_seconds() -> float:
    """This process's CPU time, user + system (run on each worker by ``Client.run``)."""
    import psutil  # a dependency of distributed

    times = psutil.Process().cpu_times()
    return float(times.user + times.system)


@dataclass
class Side:
    """One side of one turn: the sweep's wall time, its CPU time (this process; the workers), the
    whole time with the cluster's start and close, and the table."""

    wall: float
    cpu_here: float
    cpu_workers: float
    whole: float
    table: object


def in_loop(sweep: Sweep) -> Side:
    """The sweep as a plain loop in this process."""
    t0, c0 = time.perf_counter(), _cpu_seconds()
    table = sweep.run_in_process()
    wall, cpu = time.perf_counter() - t0, _cpu_seconds() - c0
    return Side(wall, cpu, 0.0, wall, table)


def on_cluster(sweep: Sweep, workers: int) -> Side:
    """One sweep on a fresh local cluster of ``workers`` processes."""
    t0 = time.perf_counter()
    cluster = local_cluster(workers)
    client = Client(cluster)
    before = client.run(_cpu_seconds)
    t1, c1 = time.perf_counter(), _cpu_seconds()
    table = sweep.run(client=client)
    t2, c2 = time.perf_counter(), _cpu_seconds()
    after = client.run(_cpu_seconds)
    if set(after) != set(before):
        raise SystemExit("a worker was replaced during the sweep: its CPU time would be lost")
    client.close()
    cluster.close()
    return Side(t2 - t1, c2 - c1, sum(after[w] - before[w] for w in after), time.perf_counter() - t0, table)


def line(name: str, values: list[float], refs: list[float]) -> str:
    lo, hi, mid = min(values), max(values), statistics.median(values)
    in_r = per_r(values, refs)
    return (f"  {name:<24} {mid:8.2f} s (spread {lo:.2f}-{hi:.2f})   in R: {statistics.median(in_r):8.1f} R "
            f"(spread {min(in_r):.1f}-{max(in_r):.1f})")


def spread(values: list[float], digits: int = 2, unit: str = "") -> str:
    """``median (spread low-high)``."""
    return (f"{statistics.median(values):.{digits}f}{unit} (spread {min(values):.{digits}f}-"
            f"{max(values):.{digits}f})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sets", type=int, default=200, help="parameter sets (runs) per sweep (default 200)")
    parser.add_argument("--runs", type=int, default=3, help="turns: each side runs once per turn (default 3)")
    args = parser.parse_args()

    sweep = the_sweep(args.sets)
    warm = the_sweep(1)  # the same package (the same digest: installed once per process)
    warm.run_in_process()  # warm-up: the package imported in this process, as a worker imports it
    sides: dict[str, list[Side]] = {s: [] for s in SIDES}
    loads: list[float] = []
    ref = Reference()
    for turn in range(args.runs):
        took = 0.0
        for side in SIDES[turn % 3:] + SIDES[:turn % 3]:
            loads.append(os.getloadavg()[0])
            done = in_loop(sweep) if side == "loop" else on_cluster(sweep, int(side.split()[0]))
            sides[side].append(done)
            took += done.whole
        ref.run(match=took)
    tables = [s.table for runs in sides.values() for s in runs]
    if any(not t.equals(tables[0]) for t in tables):  # type: ignore[attr-defined]
        raise SystemExit("the tables differ between the sides: the figures would compare different work")
    loads.append(os.getloadavg()[0])

    refs, cpu_refs = ref.times(time.perf_counter), ref.times(time.process_time)
    n = args.sets
    wall = {k: [s.wall for s in v] for k, v in sides.items()}
    print(f"sweep of the pick-and-place sample: {n} runs (whole 8-part cell runs), {args.runs} turns, "
          f"{os.cpu_count()} cores; load average (1 min) before each side {min(loads):.2f}-{max(loads):.2f} "
          f"(median {statistics.median(loads):.2f})")
    print(ref.line())
    print("wall time:")
    for name in SIDES:
        print(line(f"{name} (sweep)" if name != "loop" else "loop (in process)", wall[name], refs))
    for name in SIDES[1:]:
        print(line(f"{name} (whole)", [s.whole for s in sides[name]], refs))
    print("CPU time (user + system):")
    loop_cpu = [s.cpu_here for s in sides["loop"]]
    print(line("loop (in process)", loop_cpu, cpu_refs))
    for name in SIDES[1:]:
        print(line(f"{name}: the workers", [s.cpu_workers for s in sides[name]], cpu_refs))
        print(line(f"{name}: this process", [s.cpu_here for s in sides[name]], cpu_refs))
    for name in SIDES[1:]:
        workers = int(name.split()[0])
        share = [s.cpu_workers / (s.wall * workers) for s in sides[name]]
        print(f"  {name}: the workers' share of their cores {spread(share)}")
    speedup = [a / b for a, b in zip(wall["1 worker"], wall["2 workers"])]
    whole = [a.whole / b.whole for a, b in zip(sides["1 worker"], sides["2 workers"])]
    cpu_ratio = [b.cpu_workers / a.cpu_workers for a, b in zip(sides["1 worker"], sides["2 workers"])]
    overhead = [(a - b) / n for a, b in zip(wall["1 worker"], wall["loop"])]
    cpu_overhead = [(a.cpu_workers - b.cpu_here) / n for a, b in zip(sides["1 worker"], sides["loop"])]
    per_run = [t / n for t in wall["loop"]]
    print(f"speed-up, 2 workers over 1: sweep {spread(speedup, unit='x')}, whole {spread(whole, unit='x')}; "
          f"the workers' CPU time, 2 workers / 1: {spread(cpu_ratio)}")
    print(f"a run in the loop: {statistics.median(per_run) * 1e3:.1f} ms (spread {min(per_run) * 1e3:.1f}-"
          f"{max(per_run) * 1e3:.1f}), in R: {statistics.median(per_r(per_run, refs)) * 1e3:.1f} mR")
    print(f"Dask's overhead per run (1 worker's sweep - loop) / {n}: {statistics.median(overhead) * 1e3:.1f} ms "
          f"(spread {min(overhead) * 1e3:.1f}-{max(overhead) * 1e3:.1f}), in R: "
          f"{statistics.median(per_r(overhead, refs)) * 1e3:.1f} mR; in CPU time (the worker's - the loop's) / "
          f"{n}: {statistics.median(cpu_overhead) * 1e3:.1f} ms (spread {min(cpu_overhead) * 1e3:.1f}-"
          f"{max(cpu_overhead) * 1e3:.1f})")
    print(HOW_TO_COMPARE)


if __name__ == "__main__":  # worker processes are spawned: they import this file without running it
    main()
