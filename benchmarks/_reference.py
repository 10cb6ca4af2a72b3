"""The reference workload R: a fixed piece of pure-Python work whose time makes absolute figures
comparable between machines.

A benchmark's ratios (gpl2py against its Python baseline) hold on any machine, but its absolute
figures do not: the 200-part cell ran at 4,498 controller seconds per wall-clock second on one
machine and at 1,265 on another of the same kind, both at low load.  So every benchmark that
prints an absolute figure (a time, a rate, a factor against the clock) also runs R in the same
run, in turns with its own samples (so both see about the same load), times R with the same
clock under the same collector state, and prints each figure once more *normalised*:

* a time T is printed as T / R, in **R** (how many runs of R fit in it; mR and µR for short
  times);
* a rate or a factor F against the clock (lines per second, controller seconds per wall-clock
  second) is printed as F × R, **per R** (lines per R, controller seconds per R).

Each normalised figure is the median of the per-turn values (the figure of a turn against R of
the same turn), with their spread.  In each turn R runs for about a quarter (``SHARE``) of the
time the turn's samples took, at least once, and its time is the mean of those runs: a long
sample sees the machine's load over seconds, which a single run of R would catch at one moment.
For a continuous computation the machine's speed and most of its load cancel out, as long as the
two machines run the same Python minor version (R measures the interpreter); docs/design/
performance.md has the check (``load_check.py``) and its limits.

Why this workload: what the benchmarks time is CPython running generated or runtime code --
attribute reads and writes on small objects, method and function calls, int and float
arithmetic, dict and list operations, short strings built and split.  R is a loop of exactly
those, with no I/O, no threads and no imports beyond the standard library's ``time`` and ``gc``
(nothing like numpy whose build varies between installs).  It allocates few container objects,
so the collector's state (a benchmark may run with it on or off) hardly changes its time
(medians of 15 alternated runs: 38.6 ms of CPU time with it off, 41.1 ms on).  It
takes 36-76 ms of CPU time on the 2-core VM the figures in docs/design/performance.md come from
(the spread is the host's: on a busy KVM host the CPU time of the same work grows too): long
against the clock's resolution and the scheduler's time slices, short enough to run in every
turn.  It returns a checksum, checked at every run, so the work cannot change unnoticed.

**Never change the workload** (or ``ITERATIONS``) without bumping ``VERSION``: figures normalised
by two versions of R are not comparable.
"""

from __future__ import annotations

import gc
import platform
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass, field

VERSION = 1
ITERATIONS = 60_000
#: A turn's R runs for about this share of the turn's own samples (``Reference.run``'s ``match``).
SHARE = 0.25
#: What ``reference_workload()`` returns: any other value means the workload changed.
CHECKSUM = 4_755_748_119

#: The sentence each benchmark prints under its figures.
HOW_TO_COMPARE = (
    "To compare two machines, compare the figures in R (times divided by R) and per R (rates and "
    "factors multiplied by R), each taken turn by turn against R run in the same turn; the raw "
    "figures hold for this machine and its load only, and R itself for this Python version.")


class _Station:
    """A small object with a few attributes, as the runtime's and generated code's classes are."""

    def __init__(self, name: str, x: float, y: float) -> None:
        self.name = name
        self.x = x
        self.y = y
        self.visits = 0

    def visit(self, x: float, y: float) -> float:
        """Squared distance to (x, y); counts the visit (an attribute write)."""
        self.visits += 1
        dx, dy = self.x - x, self.y - y
        return dx * dx + dy * dy


def _mix(acc: int, i: int) -> int:
    """Integer arithmetic kept in 15 bits (a linear congruential step)."""
    return ((acc * 75 + i) & 0x7FFF) + (i // 3) - (i >> 2) % 7


def reference_workload() -> int:
    """R: ``ITERATIONS`` turns of attribute access, calls, int/float arithmetic, dict, list and
    str operations; returns a checksum (``CHECKSUM``)."""
    stations = [_Station(f"S{k}", k * 1.5, 10.0 - k) for k in range(8)]
    counts: dict[str, int] = {}
    log: list[str] = []
    acc, distance, words = 1, 0.0, 0
    for i in range(ITERATIONS):
        acc = _mix(acc, i)
        station = stations[acc & 7]
        distance += station.visit(i * 0.001, acc * 0.01)
        name = station.name
        counts[name] = counts.get(name, 0) + (acc & 15)
        if i % 8 == 0:
            log.append(f"{name}:{acc}")
            if len(log) >= 16:
                words += len(" ".join(log).split(":")) + len(log.pop(0))
                log.clear()
    return acc + words + sum(counts.values()) + int(distance) + sum(s.visits for s in stations)


def _check(result: int) -> None:
    if CHECKSUM and result != CHECKSUM:
        raise RuntimeError(f"the reference workload returned {result}, not {CHECKSUM}: it changed "
                           "(bump VERSION and set CHECKSUM)")


@dataclass
class Reference:
    """The times of R taken in one benchmark run, both clocks of every run: ``wall``
    (``time.perf_counter``) and ``cpu`` (``time.process_time``), in seconds."""

    wall: list[float] = field(default_factory=list)
    cpu: list[float] = field(default_factory=list)

    def run(self, record: bool = True, match: float = 0.0) -> None:
        """R's time in one turn, after a collection (the previous sample's garbage is not R's
        cost), as ``_sidebyside.timed`` times a sample; ``record=False`` for a warm-up.

        R runs once, or again and again until it has run for ``SHARE`` of ``match``, the seconds
        the turn's own samples took, and its time is the mean of those runs: a sample of seconds
        sees the machine's load over seconds, which one run of R (tens of milliseconds) would
        catch at a single moment."""
        gc.collect()
        runs, w0, c0 = 0, time.perf_counter(), time.process_time()
        while True:
            result = reference_workload()
            runs += 1
            if time.perf_counter() - w0 >= SHARE * match:
                break
        c1, w1 = time.process_time(), time.perf_counter()
        _check(result)
        if record:
            self.wall.append((w1 - w0) / runs)
            self.cpu.append((c1 - c0) / runs)

    def times(self, clock: Callable[[], float]) -> list[float]:
        """R's times on ``clock``: ``time.process_time`` is CPU time, any other clock wall time."""
        return self.cpu if clock is time.process_time else self.wall

    def line(self) -> str:
        """The line a benchmark prints: what R is and its median times with their spread."""
        def one(values: list[float], what: str) -> str:
            return (f"{statistics.median(values) * 1e3:.1f} ms {what} "
                    f"(spread {min(values) * 1e3:.1f}-{max(values) * 1e3:.1f})")

        if not self.wall:
            raise ValueError("R was never run")
        return (f"R, the reference workload (benchmarks/_reference.py v{VERSION}, "
                f"{platform.python_implementation()} {platform.python_version()}): "
                f"{one(self.wall, 'wall')}, {one(self.cpu, 'CPU')}, {len(self.wall)} runs in turns "
                f"with the samples")


def per_r(values: list[float], refs: list[float]) -> list[float]:
    """Times normalised: each divided by R of its turn (in R)."""
    return [v / r for v, r in zip(values, refs, strict=True)]


def times_r(values: list[float], refs: list[float]) -> list[float]:
    """Rates and factors against the clock normalised: each multiplied by R of its turn (per R)."""
    return [v * r for v, r in zip(values, refs, strict=True)]


__all__ = ["VERSION", "ITERATIONS", "CHECKSUM", "HOW_TO_COMPARE", "Reference", "reference_workload",
           "per_r", "times_r"]
