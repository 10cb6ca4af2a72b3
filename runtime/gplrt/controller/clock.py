"""The simulated controller's time: a VIRTUAL clock and a REAL clock, and the waits built on them.

Two time sources, one vocabulary (seconds as ``float``, counted from the simulated boot):

* :class:`VirtualClock` — time is a number that only the scheduler moves.  It jumps to the
  earliest pending deadline when every GPL thread is waiting (an hour of cell time runs in
  milliseconds) and it advances by one scheduling slice each time a thread computes for a whole
  slice (so a loop that polls ``Controller.Timer`` still sees time pass).  Runs are deterministic.
* :class:`RealClock` — wall-clock time (``time.monotonic``) scaled by ``speed``: ``speed=2`` makes a
  ``Thread.Sleep(1000)`` last half a real second.  For servers talking to real clients.

Who runs while someone waits is the scheduler's job (``gplrt.threads.scheduler``: ``sleep``,
``sleep_until``, ``wait``, ``notify_all``, ``call_at``): a clock only tells the time and, for the
virtual clock, is moved forward.  A session's clock is ``session.scheduler.clock``
(``gplrt.session``).
"""

from __future__ import annotations

import math
import time
from typing import Protocol


class Clock(Protocol):
    """A source of simulated-controller time in seconds since the simulated boot."""

    def now(self) -> float:
        """Current time in seconds."""
        ...

    def reached(self, t: float) -> bool:
        """Whether time ``t`` has come (the one comparison every wait loop uses)."""
        ...

    def real_seconds(self, dt: float) -> float:
        """Wall-clock seconds that ``dt`` clock seconds last (0 for a virtual clock)."""
        ...


def to_ns(t: float) -> int:
    """Seconds to whole nanoseconds: virtual time is an integer, so sums of sleeps are exact."""
    return round(t * 1e9)


class VirtualClock:
    """Time that moves only when the scheduler moves it: deterministic and as fast as possible.

    Kept as integer nanoseconds: ``1.0 + 200 × 0.01`` s of sleeps lands exactly on 3.0 s, where a
    rule scheduled for 3.0 s also fires, instead of one float ulp before it.
    """

    def __init__(self, start: float = 0.0) -> None:
        self.ns = to_ns(start)

    def now(self) -> float:
        return self.ns / 1e9

    def reached(self, t: float) -> bool:
        try:
            return self.ns >= to_ns(t)
        except OverflowError:  # beyond the nanoseconds: -inf (an empty motion queue's end) has
            return t < 0.0  # always come, +inf or a huge time never does

    def real_seconds(self, dt: float) -> float:
        return 0.0

    def advance_to_ns(self, ns: int) -> None:
        """Move time forward to ``ns`` (never backwards: a stale deadline leaves time unchanged)."""
        if ns > self.ns:
            self.ns = ns

    def advance_by(self, dt: float) -> None:
        self.advance_to_ns(self.ns + to_ns(dt))


class RealClock:
    """Wall-clock time, optionally sped up (``speed > 1``) or slowed down (``speed < 1``)."""

    def __init__(self, speed: float = 1.0, start: float = 0.0) -> None:
        if not speed > 0.0 or math.isinf(speed):
            raise ValueError(f"RealClock speed must be a positive finite number, not {speed!r}")
        self.speed = float(speed)
        self._origin_real = time.monotonic()
        self._origin = float(start)

    def now(self) -> float:
        return self._origin + (time.monotonic() - self._origin_real) * self.speed

    def reached(self, t: float) -> bool:
        return self.now() >= t

    def real_seconds(self, dt: float) -> float:
        return max(0.0, dt) / self.speed


# ---- time-of-day and quantisation (Controller.Timer) -------------------------------------------

TIMER_RESOLUTION = 1.0 / 8000.0
"""Controller.Timer is quantised to the 125 µs system tick (GPL Dictionary, timer.htm)."""


def quantise(t: float) -> float:
    """``t`` rounded down to the 125 µs tick.

    The tiny bias stops ``3600.0 * 8000`` computed as ``28799999.999…`` from losing a whole tick.
    """
    return math.floor(t * 8000.0 + 1e-6) / 8000.0
