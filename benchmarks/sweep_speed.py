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
The machine must be quiet: check ``uptime`` and say the load with the figures.

    python benchmarks/sweep_speed.py [--sets 200] [--runs 3]
"""

from __future__ import annotations

import argparse
import itertools
import os
import statistics
import time
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


def on_cluster(sweep: Sweep, workers: int) -> tuple[float, float, object]:
    """(sweep seconds, whole seconds, table) of one sweep on a fresh local cluster."""
    t0 = time.perf_counter()
    cluster = local_cluster(workers)
    client = Client(cluster)
    t1 = time.perf_counter()
    table = sweep.run(client=client)
    t2 = time.perf_counter()
    client.close()
    cluster.close()
    return t2 - t1, time.perf_counter() - t0, table


def line(name: str, values: list[float], refs: list[float]) -> str:
    lo, hi, mid = min(values), max(values), statistics.median(values)
    in_r = per_r(values, refs)
    return (f"  {name:<22} {mid:8.2f} s (spread {lo:.2f}-{hi:.2f})   in R: {statistics.median(in_r):8.1f} R "
            f"(spread {min(in_r):.1f}-{max(in_r):.1f})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sets", type=int, default=200, help="parameter sets (runs) per sweep (default 200)")
    parser.add_argument("--runs", type=int, default=3, help="turns: each side runs once per turn (default 3)")
    args = parser.parse_args()

    sweep = the_sweep(args.sets)
    sweep.run_in_process()  # warm-up: the package imported in this process, as a worker imports it
    times: dict[str, list[float]] = {s: [] for s in (*SIDES, "1 worker whole", "2 workers whole")}
    ref = Reference()
    tables = []
    for turn in range(args.runs):
        took = 0.0
        for side in SIDES[turn % 3:] + SIDES[:turn % 3]:
            if side == "loop":
                t0 = time.perf_counter()
                tables.append(sweep.run_in_process())
                times["loop"].append(time.perf_counter() - t0)
                took += times["loop"][-1]
            else:
                workers = int(side.split()[0])
                swept, whole, table = on_cluster(sweep, workers)
                tables.append(table)
                times[side].append(swept)
                times[f"{side} whole"].append(whole)
                took += whole
        ref.run(match=took)
    if any(not t.equals(tables[0]) for t in tables):
        raise SystemExit("the tables differ between the sides: the figures would compare different work")

    refs = ref.times(time.perf_counter)
    n = args.sets
    load = os.getloadavg()
    print(f"sweep of the pick-and-place sample: {n} runs (whole 8-part cell runs), {args.runs} turns; "
          f"load average before the last turn's end {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f}; "
          f"{os.cpu_count()} cores")
    print(ref.line())
    for name in ("loop", "1 worker", "2 workers"):
        print(line(f"{name} (sweep)" if name != "loop" else "loop (in process)", times[name], refs))
    for name in ("1 worker whole", "2 workers whole"):
        print(line(name.replace(" whole", " (whole)"), times[name], refs))
    speedup = [a / b for a, b in zip(times["1 worker"], times["2 workers"])]
    whole = [a / b for a, b in zip(times["1 worker whole"], times["2 workers whole"])]
    overhead = [(a - b) / n for a, b in zip(times["1 worker"], times["loop"])]
    per_run = [t / n for t in times["loop"]]
    print(f"speed-up, 2 workers over 1: sweep {statistics.median(speedup):.2f}x (spread {min(speedup):.2f}-"
          f"{max(speedup):.2f}), whole {statistics.median(whole):.2f}x (spread {min(whole):.2f}-{max(whole):.2f})")
    print(f"a run in the loop: {statistics.median(per_run) * 1e3:.1f} ms (spread {min(per_run) * 1e3:.1f}-"
          f"{max(per_run) * 1e3:.1f}), in R: {statistics.median(per_r(per_run, refs)) * 1e3:.1f} mR")
    print(f"Dask's overhead per run (1 worker's sweep - loop) / {n}: {statistics.median(overhead) * 1e3:.1f} ms "
          f"(spread {min(overhead) * 1e3:.1f}-{max(overhead) * 1e3:.1f}), in R: "
          f"{statistics.median(per_r(overhead, refs)) * 1e3:.1f} mR")
    print(HOW_TO_COMPARE)


if __name__ == "__main__":  # worker processes are spawned: they import this file without running it
    main()
