"""One long-lived real-time timer thread per scheduler.

Why not ``threading.Timer``: the schedulers need a real-time wake-up for every idle spell of a
paced virtual run (a server polling ``listener.Pending()`` between ``Thread.Sleep(10)`` calls has
one every 10 ms) and for every ``call_at`` on the real clock.  A ``threading.Timer`` each time
started one OS thread per wake-up (734 for 400 requests of a polling server) and left the
superseded ones sleeping; a timer still pending at interpreter exit kept its callback — and
through it the scheduler, the simulation and its robots' Ruckig trajectories — alive, which
nanobind reports as "leaked" objects.

:class:`RealTimer` keeps a heap of (due time, callback) and a single daemon thread that sleeps on
a condition variable until the earliest one.  The thread starts on the first :meth:`schedule`,
ends by itself after ``linger`` seconds with nothing pending (so an idle session holds no thread,
and nothing of the session is reachable from a thread at exit), and ends at once on
:meth:`close`.  Callbacks run on the timer thread *without* the timer's lock held, so a callback
may take the scheduler lock while the scheduler, holding its own lock, schedules or cancels here.
"""

from __future__ import annotations

import heapq
import itertools
import sys
import threading
import time
from dataclasses import dataclass, field
from typing import Callable


@dataclass(order=True)
class TimerHandle:
    """A pending callback; pass it to :meth:`RealTimer.cancel`."""

    due: float
    seq: int
    callback: Callable[[], None] | None = field(compare=False)

    @property
    def cancelled(self) -> bool:
        return self.callback is None


class RealTimer:
    """Runs callbacks at real (``time.monotonic``) times on one reusable daemon thread."""

    def __init__(self, name: str = "gplrt-timer", linger: float = 1.0) -> None:
        self.name = name
        self.linger = linger
        self._cv = threading.Condition(threading.Lock())
        self._heap: list[TimerHandle] = []
        self._seq = itertools.count()
        self._thread: threading.Thread | None = None
        self._closing = False
        self.threads_started = 0  # how many OS threads this timer has started (a diagnostic)

    # -- public ------------------------------------------------------------------------------------

    def schedule(self, delay: float, callback: Callable[[], None]) -> TimerHandle:
        """Run ``callback`` on the timer thread after ``delay`` real seconds (0 or less: soon)."""
        handle = TimerHandle(time.monotonic() + max(0.0, delay), next(self._seq), callback)
        with self._cv:
            heapq.heappush(self._heap, handle)
            self._closing = False
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name=self.name, daemon=True)
                self.threads_started += 1
                self._thread.start()
            elif self._heap[0] is handle:
                self._cv.notify()  # earlier than what the thread sleeps towards
        return handle

    def cancel(self, handle: TimerHandle | None) -> None:
        """Forget ``handle`` (a no-op if it already ran or was cancelled)."""
        if handle is None:
            return
        with self._cv:
            handle.callback = None  # drops the reference at once; the entry is skipped when due
            self._cv.notify()

    def pending(self) -> int:
        """Callbacks still waiting to run."""
        with self._cv:
            return sum(1 for h in self._heap if not h.cancelled)

    def is_running(self) -> bool:
        with self._cv:
            return self._thread is not None

    def close(self, *, drop_pending: bool = True, timeout: float = 2.0) -> None:
        """End the timer thread.

        With ``drop_pending`` (the default) every pending callback is forgotten first; without it
        the thread is only ended when nothing is pending (a later :meth:`schedule` starts a new
        one either way).  Waits up to ``timeout`` for the thread to exit unless called from it.
        """
        with self._cv:
            if drop_pending:
                for h in self._heap:
                    h.callback = None
                self._heap.clear()
            else:
                self._drop_cancelled()
                if self._heap:
                    return
            thread = self._thread
            self._closing = True
            self._cv.notify()
        if thread is not None and thread is not threading.current_thread():
            thread.join(timeout)

    # -- the thread --------------------------------------------------------------------------------

    def _drop_cancelled(self) -> None:
        while self._heap and self._heap[0].cancelled:
            heapq.heappop(self._heap)

    def _run(self) -> None:
        idle_since: float | None = None
        while True:
            callback: Callable[[], None] | None = None
            with self._cv:
                self._drop_cancelled()
                now = time.monotonic()
                if self._closing and not self._heap:
                    self._thread = None
                    return
                if not self._heap:
                    if idle_since is None:
                        idle_since = now
                    left = idle_since + self.linger - now
                    if left <= 0:
                        self._thread = None
                        return
                    self._cv.wait(left)
                    continue
                idle_since = None
                head = self._heap[0]
                if head.due > now:
                    self._cv.wait(head.due - now)
                    continue
                heapq.heappop(self._heap)
                callback, head.callback = head.callback, None
            if callback is not None:
                try:
                    callback()
                except Exception:
                    # Reported like an exception in any thread, but the timer keeps serving.
                    threading.excepthook(threading.ExceptHookArgs((*sys.exc_info(), threading.current_thread())))
                finally:
                    callback = None  # keep nothing of the session alive in this frame
