"""Side-by-side timing for the benchmarks: both sides in turns, medians and their spread.

Every benchmark compares gpl2py (or generated code) with a Python baseline in one run.  The machine
is shared, so one side must never get the quiet moments and the other the busy ones: the two are
run in turns (A, B, A, B, ...), each sample after the same warm-up and under the same garbage
collector state, and what is reported is the median of the samples with their spread (lowest and
highest), never the best run.  The ratio is the median of the per-turn ratios, with its spread too.

Given a ``Reference``, each turn also runs the reference workload R (``_reference``), so that the
absolute times can be printed normalised by R of the same turn (``Pair.a_in_r``, ``Pair.b_in_r``)
and compared between machines.
"""

from __future__ import annotations

import gc
import statistics
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from _reference import Reference, per_r


@dataclass
class Samples:
    """Seconds per run of one side."""

    values: list[float]

    @property
    def median(self) -> float:
        return statistics.median(self.values)

    def text(self, unit: float = 1e-3, name: str = "ms", digits: int = 1) -> str:
        lo, hi = min(self.values), max(self.values)
        return f"{self.median / unit:9.{digits}f} {name} (spread {lo / unit:.{digits}f}-{hi / unit:.{digits}f})"


@dataclass
class Pair:
    """Two sides measured in turns; ``ratios[i] = a[i] / b[i]``; ``ref[i]``, R's time in turn
    ``i`` on the same clock, when a ``Reference`` was given."""

    a: Samples
    b: Samples
    ref: Samples | None = None

    def _in_r(self, side: Samples) -> Samples:
        if self.ref is None:
            raise ValueError("this pair was measured without the reference workload")
        return Samples(per_r(side.values, self.ref.values))

    @property
    def a_in_r(self) -> Samples:
        """Side a's times divided by R of the same turn (in R)."""
        return self._in_r(self.a)

    @property
    def b_in_r(self) -> Samples:
        """Side b's times divided by R of the same turn (in R)."""
        return self._in_r(self.b)

    @property
    def ratios(self) -> list[float]:
        return [x / y for x, y in zip(self.a.values, self.b.values)]

    @property
    def ratio(self) -> float:
        return statistics.median(self.ratios)

    def ratio_text(self) -> str:
        r = self.ratios
        return f"{self.ratio:.2f}x (spread {min(r):.2f}-{max(r):.2f}, {len(r)} runs each)"


@contextmanager
def collector(enabled: bool) -> Iterator[None]:
    """Run the block with the cyclic garbage collector on or off, restoring the previous state."""
    was = gc.isenabled()
    (gc.enable if enabled else gc.disable)()
    try:
        yield
    finally:
        (gc.enable if was else gc.disable)()


def timed(fn: Callable[[], object], clock: Callable[[], float] = time.perf_counter) -> float:
    gc.collect()  # the previous sample's garbage is not this sample's cost
    t0 = clock()
    fn()
    return clock() - t0


def side_by_side(a: Callable[[], object], b: Callable[[], object], runs: int, *, warmup: int = 1,
                 gc_enabled: bool = True, clock: Callable[[], float] = time.perf_counter,
                 reference: Reference | None = None) -> Pair:
    """``runs`` samples of each, in turns, after ``warmup`` untimed runs of each, both under the
    same collector state (``gc_enabled``); with a ``reference``, R runs in every turn too (A, B,
    R), under the same state, and its times on ``clock`` are the pair's ``ref``."""
    with collector(gc_enabled):
        for _ in range(warmup):
            a()
            b()
            if reference is not None:
                reference.run(record=False)
        ta: list[float] = []
        tb: list[float] = []
        for _ in range(runs):
            ta.append(timed(a, clock))
            tb.append(timed(b, clock))
            if reference is not None:
                reference.run(match=ta[-1] + tb[-1])
    ref = Samples(reference.times(clock)[-runs:]) if reference is not None else None
    return Pair(Samples(ta), Samples(tb), ref)


__all__ = ["Samples", "Pair", "collector", "timed", "side_by_side"]
