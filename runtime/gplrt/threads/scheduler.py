"""Schedulers: who runs, who waits, and how controller time moves.

Every GPL thread runs on its own Python thread.  The scheduler decides when it may run.

VIRTUAL mode (:class:`VirtualScheduler`, the simulator's default) — a *token* scheduler:

* Exactly one GPL thread holds the token and runs; the others wait on their own ``Event``.  The
  token changes hands only at scheduling points: ``Thread.Sleep`` (``Sleep(0)`` included),
  ``WaitEvent``, ``Join``, clock waits (``sleep_until``, ``WaitForEOM``), thread start/end (the new
  thread queues; the starter keeps running), :func:`external_wait`, and :func:`checkpoint` — which
  every turn of a transpiled loop takes.
* Round-robin in a FIFO of runnable threads.  A thread gets a *slice* of ``slice_checkpoints``
  checkpoints (each turn of a transpiled loop takes one in C from ``ThreadCtx.turns``, see
  :func:`paced`; :func:`checkpoint` takes one from Python); when the slice is used up, virtual time
  advances by ``slice_time`` (the controller's 1 ms round-robin slice) and the thread moves to the
  back of the queue.  The remaining slice is kept across sleeps, as on the controller (D0 §17.2).
  Charging compute time is what lets ``While Controller.Timer < t0 + 1 : End While`` terminate.
* When no thread is runnable, time jumps to the earliest deadline; ties wake in the order the
  waits began.  A wait that nothing can overtake costs no thread switch: ``run_alone_until``
  moves time straight to its end when no other thread, deadline or timer callback comes first
  (``WaitForEOM`` and ``Thread.Sleep`` of a one-thread program), and a dispatch that picks the
  very thread that has just parked itself hands the token back without its ``Event``.  Either
  way the order of events is the one the ordinary wait gives.  Jumps happen only while someone
  outside drives the run (``run_main``, ``call``, ``run_for``, a blocking call from a
  notebook): between calls, a notebook's background threads freeze instead of racing virtual
  time ahead.  Timer callbacks (:meth:`call_at`, used by the I/O rules) fire in that same order.
* A thread in :func:`external_wait` (socket accept/receive, an operator dialog) is neither
  runnable nor a virtual waiter.  While one exists and nobody is runnable, virtual time advances
  no faster than real time: a real-time timer (the scheduler's one timer thread, see
  :mod:`gplrt.threads.pacer`) fires the earliest virtual deadline when it falls due, and when
  the external wait ends, time catches up with the real time spent idle.  So a server's timeout
  still means something to a real client, and no deadline is skipped.
* The same real-time pace holds while the program has a connection to the outside world open (a
  listening or connected socket: :func:`hold_real_time`), even when no thread is blocked in it: a
  server that polls ``listener.Pending()`` between ``Thread.Sleep(20)`` calls must not race virtual
  time (and the CPU) ahead of the clients it waits for.
* FAST mode (``VirtualScheduler(run_ahead=True)``, ``--clock fast``) relaxes the two rules above
  for the case a client session is made of: while some GPL thread waits *for the controller* — a
  motion to end (``WaitForEOM``, a full motion queue), homing, a power-up; the runtime marks such
  waits with :func:`controller_wait` and the controller time they end at — and no thread can run,
  time jumps to the next deadline instead of pacing, as long as that deadline is no later than
  the last of those controller waits ends.  Nothing else runs ahead: with no controller wait in
  progress (a server polling ``Pending()`` for a client that has not come, a client thinking
  between two requests) the paced rules apply unchanged, so the clock never races ahead of a
  client that has not asked for anything.  A motion nobody waits for keeps real-time pace too, so
  a client that queues moves or watches one still sees it take its time.  Every jump goes through
  the deadlines in order, as virtual time always does: each sleeping poller wakes at its own
  deadline on the way.  docs/design/clock.md says when this is safe.
* Code running on Python threads the scheduler does not know (a notebook, pytest) never holds the
  token, so it cannot deadlock the scheduler: ``checkpoint`` is a no-op there, and a blocking call
  (``Thread.Sleep``, ``WaitEvent``, ``clock.sleep``) *adopts* the thread for the duration of that
  call only.

Same program, same inputs ⇒ same interleaving ⇒ byte-identical output.

REAL mode (:class:`RealScheduler`): threads run preemptively, waits sleep for real time divided by
the clock's speed, ``TestAndSet`` is atomic under a lock, and ``checkpoint`` only services
Suspend/Abort requests.  Since Python may switch threads between any two bytecodes, every wait
re-tests its condition (``until``) under the scheduler lock as it registers, so a notification sent
in between is never lost.

Suspend and Abort are cooperative (Python threads cannot be killed): the target notices at its
next checkpoint or scheduling point; a blocked target is woken to notice.  Abort raises
:class:`ThreadAbort`, a ``BaseException`` so that GPL ``Catch`` blocks (``except GplException``)
do not swallow it while ``Finally`` blocks still run.
"""

from __future__ import annotations

import functools
import heapq
import itertools
import threading
import time
from collections import deque
from contextlib import contextmanager
from dataclasses import dataclass, field
from itertools import chain, repeat
from typing import TYPE_CHECKING, Callable, Iterable, Iterator, TypeAlias

from gplrt.controller.clock import RealClock, VirtualClock, to_ns
# current_ctx and bind_current: the rest of the runtime imports them from here
from gplrt.thread_binding import _tls, bind_current, current_ctx  # noqa: F401
from gplrt.threads.pacer import RealTimer, TimerHandle

if TYPE_CHECKING:
    from gplrt.session import Session
    from gplrt.threads.thread import Thread


class ThreadAbort(BaseException):
    """Unwinds a GPL thread stopped by ``Thread.Abort`` (not catchable by GPL ``Catch``)."""


class Phase:
    """Scheduler-level state of a :class:`ThreadCtx` (the GPL-visible ThreadState is derived)."""

    NEW = "new"
    READY = "ready"
    RUNNING = "running"
    BLOCKED = "blocked"
    EXTERNAL = "external"
    DONE = "done"


@dataclass(eq=False)
class ThreadCtx:
    """What the scheduler keeps about one thread that runs (or waits for) GPL code.

    The thread's slice is counted by :attr:`turns`, an endless iterator that the transpiled
    ``While``/``Do`` loops iterate directly (``for _ in paced():``, see :func:`paced`) and that
    :func:`checkpoint` advances by one: each item is one checkpoint of the slice.  It runs in C
    (a ``chain`` over list iterators) and calls back into Python only when the slice is used up
    (:meth:`_next_slice`), so a loop's scheduling point costs a few nanoseconds instead of a
    function call.  :attr:`budget` reads and sets the checkpoints left, as an integer.
    """

    name: str
    sched: "Scheduler"
    phase: str = Phase.NEW
    go: threading.Event = field(default_factory=threading.Event)
    wait_id: int = 0
    notified: bool = False
    timed_out: bool = False
    waiting_on: str = ""
    abort_requested: bool = False
    suspend_requested: bool = False
    saved_budget: int | None = None
    owner: Thread | None = None  # the GPL Thread object, if any
    # While the thread waits for the controller (controller_wait): when that work ends, in ns.
    busy_until: int | None = None
    resume_q: "WaitQueue" = field(default_factory=lambda: WaitQueue("resume"))

    def __post_init__(self) -> None:
        size = self.sched.slice_checkpoints
        # The items a slice hands out; a chunk is an iterator over it started at the right index.
        self._items = _slice_items(size)
        # The chunk being handed out, or None while the slice changes hands (_next_slice).
        self._chunk: Iterator[None] | None = None
        # The budget set while there is no chunk (inside _next_slice).
        self._pending: int | None = None
        # A budget set to 0 or below: the chunk is empty, and this is what ``budget`` reads.
        self._spent: int | None = None
        self.turns: Iterator[None] = self._new_turns(size)

    def _new_turns(self, budget: int) -> Iterator[None]:
        """The endless iterator of this thread's checkpoints, starting with ``budget`` left."""
        first = self._chunk_of(budget - 1)
        return chain.from_iterable(chain((first,), map(self._next_slice, repeat(None))))

    def _chunk_of(self, n: int) -> Iterator[None]:
        """A chunk that hands out ``n`` items; it becomes the current one."""
        chunk = iter(self._items)
        chunk.__setstate__(len(self._items) - max(0, min(n, len(self._items))))  # type: ignore[attr-defined]
        self._chunk = chunk
        return chunk

    @property
    def budget(self) -> int:
        """Checkpoints left in the slice: the one that brings it to 0 is a scheduling point."""
        chunk = self._chunk
        if chunk is None:
            return self._pending if self._pending is not None else 0
        left = chunk.__length_hint__()  # type: ignore[attr-defined]
        if left == 0 and self._spent is not None:
            return self._spent
        return left + 1

    @budget.setter
    def budget(self, n: int) -> None:
        chunk = self._chunk
        if chunk is None:
            self._pending = n
            return
        self._spent = n if n <= 0 else None
        chunk.__setstate__(len(self._items) - max(0, min(n - 1, len(self._items))))  # type: ignore[attr-defined]

    def _next_slice(self, _: None) -> Iterator[None]:
        """The checkpoint that used up the slice (or was forced to by a request): the scheduler's
        slow path, then the next slice's chunk.

        The pull that calls this is charged to the slice that ended; the chunk returned holds the
        new budget, of which ``chain`` takes one item for that pull, so ``budget`` reads the new
        budget afterwards, as :func:`checkpoint`'s integer decrement did.  If the slow path raises
        (an Abort), ``turns`` is rebuilt: ``chain`` is dead once its source raised, and the loops of
        the ``Finally`` blocks that run next must still get their checkpoints.
        """
        self._chunk = None
        self._pending = None
        self._spent = None
        try:
            self.sched._checkpoint_slow(self)
        except BaseException:
            budget = self._pending if self._pending is not None else self.sched.slice_checkpoints
            self._pending = None
            self.turns = self._new_turns(budget)
            raise
        budget = self._pending if self._pending is not None else self.sched.slice_checkpoints
        self._pending = None
        return self._chunk_of(budget)

    def force_slow_path(self) -> None:
        """Make the next :func:`checkpoint` take the slow path (to notice Suspend/Abort)."""
        if self.saved_budget is None:
            self.saved_budget = self.budget
        self.budget = 0


@functools.cache
def _slice_items(size: int) -> list[None]:
    """The list a slice's chunks iterate, one per slice size: only ever read, so all threads share it."""
    return [None] * (size + 1)


#: Who holds a robot or has one Selected: the GPL thread's record, or the Python thread for code
#: the scheduler does not run (a notebook).
ThreadKey: TypeAlias = "ThreadCtx | threading.Thread"


class WaitQueue:
    """Threads blocked until someone calls ``notify_all`` (a condition variable without a lock)."""

    def __init__(self, label: str = "") -> None:
        self.label = label
        self.waiters: list[tuple[ThreadCtx, int]] = []


def checkpoint() -> None:
    """A scheduling point: one checkpoint of the calling thread's slice.

    In virtual mode the thread hands the token on once its slice is used up; in both modes it is
    where a Suspend or Abort aimed at this thread takes effect.  The transpiled ``While``/``Do``
    loops take their checkpoints by iterating :func:`paced` instead (no call per iteration).
    """
    ctx = _tls.ctx
    if ctx is not None:
        next(ctx.turns)


#: The checkpoints of code the scheduler does not run (a notebook, pytest): endless and free.
_FREE_TURNS: Iterator[None] = repeat(None)


def paced() -> Iterator[None]:
    """The checkpoints of the calling thread, one per item: what a transpiled loop iterates.

    The transpiler writes ``While c ... End While`` as ``for _ in paced(): if not c: break ...``:
    each turn of the loop (each test of its condition) is one checkpoint of the thread's slice,
    taken by the ``for`` statement from :attr:`ThreadCtx.turns` in C, so a loop that waits on
    another thread or on ``Controller.Timer`` still lets time pass and the other threads run,
    without a Python call per iteration.  All the loops of a thread share its one iterator, as
    they share its slice.  Off the scheduler's threads it is an endless ``repeat``.
    """
    ctx = _tls.ctx
    return _FREE_TURNS if ctx is None else ctx.turns


#: Iterations of a :func:`paced_range` loop between two checkpoints.  A virtual slice is 1000
#: checkpoints, so a tight range loop runs ~1,000,000 iterations (~0.1 s) per slice; smaller chunks
#: cost measurably more per iteration (docs/design/lowering.md, "Loops and other threads").
PACE = 1024


def paced_range(start: int, stop: int, step: int = 1) -> Iterable[int]:
    """``range(start, stop, step)`` that calls :func:`checkpoint` every :data:`PACE` iterations.

    The transpiler writes a GPL ``For`` over Integers as ``for i in paced_range(a, b + 1):`` so
    that a long loop cannot starve the other GPL threads, without a call per iteration: a range of
    at most ``PACE`` values is returned as it is, a longer one as ``chain.from_iterable`` over its
    slices, with a checkpoint between slices.  The iteration itself runs in C (``chain`` over
    ``range`` objects): a few nanoseconds per step over a plain ``range``.  A fresh iterator per
    loop, so threads never share one.
    """
    r = range(start, stop, step)
    if len(r) <= PACE:
        return r
    return chain.from_iterable(map(_paced_slice, repeat(r), range(0, len(r), PACE)))


def _paced_slice(r: range, k: int) -> range:
    """The ``k``-th slice of a :func:`paced_range`; every slice after the first is a scheduling
    point."""
    if k:
        checkpoint()
    return r[k:k + PACE]


def abort_point() -> None:
    """Raise :class:`ThreadAbort` if an Abort is pending for the calling GPL thread.

    For waits the scheduler cannot wake (a ``select`` on a socket, a serial read): they poll in
    short slices and call this between slices, so ``Thread.Abort`` and ``Simulation.stop`` end
    a thread blocked on the outside world too.  A no-op on threads unknown to the scheduler.
    """
    ctx = _tls.ctx
    if ctx is not None and ctx.abort_requested:
        raise ThreadAbort()


@contextmanager
def external_wait() -> Iterator[None]:
    """Mark the calling GPL thread as blocked on the outside world for the ``with`` body.

    Every blocking call to the outside (socket accept/receive, a console prompt) goes through this,
    so the virtual scheduler lets other GPL threads run meanwhile and knows not to race virtual
    time ahead.  Harmless in real mode and on threads unknown to the scheduler.
    """
    ctx = _tls.ctx
    if ctx is None:
        yield
        return
    ctx.sched._enter_external(ctx)
    try:
        yield
    finally:
        ctx.sched._leave_external(ctx)


class controller_wait:  # noqa: N801 - used as a function, like contextlib's
    """Mark the calling GPL thread as waiting for the controller until controller time ``end``
    (``with controller_wait(end): ...``).

    The runtime wraps the waits whose end the controller, not the program or the outside world,
    decides — the end of the queued motions, homing, a power-up — so that the FAST scheduler may
    jump time to ``end`` even while sockets are open (see the module docstring).  Every other
    scheduler ignores the mark; so does a thread unknown to the scheduler.  An ``end`` beyond the
    clock's range (an infinite wait) marks nothing: there is no motion end to jump to.

    A class rather than a ``@contextmanager`` generator: every ``WaitForEOM`` that waits enters
    one, and a generator costs several times as much to enter and leave.
    """

    __slots__ = ("ctx", "end_ns", "previous")

    def __init__(self, end: float) -> None:
        self.ctx = _tls.ctx
        try:
            self.end_ns: int | None = to_ns(end)
        except (OverflowError, ValueError):
            self.end_ns = None
        self.previous: int | None = None

    def __enter__(self) -> None:
        ctx = self.ctx
        if ctx is not None and self.end_ns is not None:
            self.previous, ctx.busy_until = ctx.busy_until, self.end_ns

    def __exit__(self, *exc: object) -> None:
        ctx = self.ctx
        if ctx is not None and self.end_ns is not None:
            ctx.busy_until = self.previous


def hold_real_time() -> Callable[[], None]:
    """Pace virtual time to real time until the returned function is called (once).

    The I/O layer calls this when a GPL thread opens a connection to the outside world and calls
    the result when it closes it (see the module docstring).  A no-op outside GPL threads and in
    real mode.
    """
    ctx = _tls.ctx
    if ctx is None:
        return _no_release
    return ctx.sched.hold_real_time()


def _no_release() -> None:
    pass


class Scheduler:
    """Common surface of both schedulers (see the module docstring for the policies)."""

    clock: VirtualClock | RealClock
    slice_checkpoints: int
    #: The session this scheduler runs (set when the session is composed; None for a scheduler
    #: used on its own, as the scheduler's tests do).
    session: Session | None = None

    def __init__(self) -> None:
        self._lock = threading.RLock()
        self._changed = threading.Condition(self._lock)  # signalled on idle / thread end
        self.live: list[ThreadCtx] = []
        self._seq = itertools.count()
        # Outside callers currently waiting on the program (run_main, call, an adopted Sleep...).
        # Virtual time only jumps while there is one: a notebook that started a background thread
        # and went idle does not see the cell run on to infinity behind its back.
        self.drivers = 0
        # Real-time wake-ups (virtual pacing, real-clock call_at): one reusable thread, see pacer.py.
        self._real_timer = RealTimer(name=f"gplrt-timer:{type(self).__name__}")

    # -- thread lifecycle --------------------------------------------------------------------------

    def new_ctx(self, name: str, owner: Thread | None = None) -> ThreadCtx:
        return ThreadCtx(name=name, sched=self, owner=owner)

    def spawn(self, ctx: ThreadCtx, body: Callable[[], None]) -> threading.Thread:
        """Start a Python thread that runs ``body`` as the GPL thread ``ctx``."""

        def run() -> None:
            bind_current(ctx)
            try:
                self._wait_first_turn(ctx)
                body()
            finally:
                bind_current(None)

        with self._lock:
            self.live.append(ctx)
            self._make_ready(ctx)
            self._kick()
        py = threading.Thread(target=run, name=f"gpl:{ctx.name}", daemon=True)
        py.start()
        return py

    @contextmanager
    def adopted(self) -> Iterator[ThreadCtx]:
        """Run the ``with`` body as a GPL thread; a no-op for threads that already are one."""
        ctx = _tls.ctx
        if ctx is not None:
            yield ctx
            return
        ctx = self.new_ctx("<external caller>")
        bind_current(ctx)
        with self._lock:
            self.drivers += 1
            self.live.append(ctx)
            self._make_ready(ctx)
            self._kick()
        try:
            self._wait_first_turn(ctx)
            yield ctx
        finally:
            bind_current(None)
            with self._lock:
                self.drivers -= 1
                self._driver_left()
            self.finish(ctx)

    def is_stalled(self) -> bool:
        """True when no GPL thread can ever run again without help from outside."""
        return False

    def hold_real_time(self) -> Callable[[], None]:
        """Pace virtual time to real time until the returned function is called (once): a
        connection of the program's (:func:`hold_real_time`) or a service of the controller's
        that the outside world reaches (the console, FTP).  A no-op in real mode."""
        self._hold_real_time(+1)
        released = False

        def release() -> None:
            nonlocal released
            if not released:
                released = True
                self._hold_real_time(-1)

        return release

    def wait_until_quiet(self, threads: list[ThreadCtx] | None, timeout: float | None) -> bool:
        """Block a non-GPL caller until ``threads`` (default: all) ended or the scheduler stalled.

        Returns True if they all ended.
        """
        end = None if timeout is None else time.monotonic() + timeout
        with self._changed:
            self.drivers += 1
            self._kick()
            try:
                while True:
                    pending = [c for c in (self.live if threads is None else threads) if c.phase != Phase.DONE]
                    if not pending:
                        return True
                    if self.is_stalled():
                        return False
                    remaining = None if end is None else end - time.monotonic()
                    if remaining is not None and remaining <= 0:
                        return False
                    self._changed.wait(0.05 if remaining is None else min(0.05, remaining))
            finally:
                self.drivers -= 1
                self._driver_left()

    # -- waits (public) ----------------------------------------------------------------------------

    def sleep(self, dt: float) -> None:
        if dt <= 0:
            self.yield_now()
        elif _tls.ctx is not None:
            self.sleep_until(self.clock.now() + dt)
        else:  # the time is read once the caller holds the token
            with self.adopted():
                self.sleep_until(self.clock.now() + dt)

    def sleep_until(self, t: float) -> None:
        ctx = _tls.ctx
        if ctx is None:  # (a GPL thread skips ``adopted``'s generator: every Sleep passes here)
            with self.adopted():
                self.sleep_until(t)
            return
        ctx.waiting_on = "sleep"
        while not self.clock.reached(t):
            if not self.run_alone_until(t):
                self.wait(None, t)

    def run_alone_until(self, t: float) -> bool:
        """The fast path of a wait for controller time ``t`` by the calling GPL thread: when
        nothing can happen before ``t`` but the caller's own wake-up, move time to ``t`` and
        return True; otherwise False, and the caller waits the ordinary way.

        Only the virtual scheduler has one (a real clock's time passes by itself)."""
        return False

    def wait(
        self,
        queue: WaitQueue | None,
        deadline: float | None,
        until: Callable[[], object] | None = None,
    ) -> bool:
        """Block until ``queue`` is notified (True) or controller time reaches ``deadline`` (False).

        ``until`` is the condition the caller waits for.  It is tested under the scheduler lock
        just before the thread registers on ``queue``; if it already holds, ``wait`` returns True
        at once.  Under the real clock another thread may make the condition true between the
        caller's own test and the registration, and its ``notify_all`` would then find nobody to
        wake: without ``until`` such a wakeup is lost (a ``Join`` of a thread that ends at that
        moment would wait forever).
        """
        ctx = _tls.ctx
        if ctx is None:  # (a GPL thread skips ``adopted``'s generator: every wait passes here)
            with self.adopted():
                return self.wait(queue, deadline, until)
        self._service_requests(ctx)
        notified = self._block(ctx, queue, deadline, until)
        self._service_requests(ctx)
        return notified

    def notify_all(self, queue: WaitQueue) -> None:
        with self._lock:
            waiters, queue.waiters = queue.waiters, []
            for ctx, wid in waiters:
                if ctx.wait_id == wid and ctx.phase == Phase.BLOCKED:
                    self._wake(ctx, timed_out=False)
            self._kick()

    def call_at(self, t: float, callback: Callable[[], None]) -> None:
        raise NotImplementedError

    def release_timers(self, *, drop_pending: bool = False) -> None:
        """End the scheduler's real-time timer thread (:meth:`Simulation.stop` / ``close``).

        Without ``drop_pending`` (stop) only what a later dispatch re-plans anyway is forgotten —
        the virtual scheduler's pacing wake-up — and the thread ends if nothing else is pending:
        a real-clock ``call_at`` (an I/O rule's delayed action) still fires.  With it (close),
        every pending real-time callback is dropped, so no thread is left that refers back to
        the session.  Must be called without the scheduler lock (it joins the timer thread,
        whose callback may be waiting for that lock).
        """
        self._real_timer.close(drop_pending=drop_pending)

    def real_time_callbacks_pending(self) -> int:
        """Callbacks waiting on the real-time timer thread (a diagnostic)."""
        return self._real_timer.pending()

    def timer_thread_alive(self) -> bool:
        """Whether the real-time timer thread is running (it ends when idle or released)."""
        return self._real_timer.is_running()

    def timer_threads_started(self) -> int:
        """How many OS threads the scheduler's real-time timer has started (a diagnostic)."""
        return self._real_timer.threads_started

    def yield_now(self) -> None:
        raise NotImplementedError

    # -- Suspend / Abort ---------------------------------------------------------------------------

    def request_abort(self, ctx: ThreadCtx) -> None:
        with self._lock:
            ctx.abort_requested = True
            ctx.force_slow_path()
            self._interrupt(ctx)
            self._kick()

    def request_suspend(self, ctx: ThreadCtx) -> None:
        with self._lock:
            ctx.suspend_requested = True
            ctx.force_slow_path()

    def request_resume(self, ctx: ThreadCtx) -> None:
        with self._lock:
            ctx.suspend_requested = False
        self.notify_all(ctx.resume_q)

    def _service_requests(self, ctx: ThreadCtx) -> None:
        """At a scheduling point: die if aborted, park while suspended."""
        if ctx.saved_budget is not None:  # the slice forced to 0 by a request: give it back
            ctx.budget, ctx.saved_budget = ctx.saved_budget, None
        while True:
            if ctx.abort_requested:
                raise ThreadAbort()
            if not ctx.suspend_requested:
                return
            ctx.waiting_on = "suspended"
            self._block(ctx, ctx.resume_q, None, lambda: ctx.abort_requested or not ctx.suspend_requested)

    def _interrupt(self, ctx: ThreadCtx) -> None:
        """Wake ``ctx`` from whatever it waits on so that it notices a request."""
        if ctx.phase == Phase.BLOCKED:
            self._wake(ctx, timed_out=False)

    # -- hooks for the concrete schedulers ----------------------------------------------------------

    def _wait_first_turn(self, ctx: ThreadCtx) -> None:
        raise NotImplementedError

    def _make_ready(self, ctx: ThreadCtx) -> None:
        raise NotImplementedError

    def _kick(self) -> None:
        """Called (lock held) after making threads ready: start one if nobody is running."""

    def _driver_left(self) -> None:
        """Called (lock held) after an outside caller stopped waiting on the program."""

    def _block(
        self,
        ctx: ThreadCtx,
        queue: WaitQueue | None,
        deadline: float | None,
        until: Callable[[], object] | None = None,
    ) -> bool:
        """Park ``ctx`` on ``queue`` until notified (True) or ``deadline`` (False); see :meth:`wait`."""
        raise NotImplementedError

    def _wake(self, ctx: ThreadCtx, timed_out: bool) -> None:
        raise NotImplementedError

    def finish(self, ctx: ThreadCtx) -> None:
        raise NotImplementedError

    def _checkpoint_slow(self, ctx: ThreadCtx) -> None:
        raise NotImplementedError

    def _enter_external(self, ctx: ThreadCtx) -> None:
        pass

    def _leave_external(self, ctx: ThreadCtx) -> None:
        pass

    def _hold_real_time(self, delta: int) -> None:
        pass


class VirtualScheduler(Scheduler):
    """Token scheduler on a :class:`VirtualClock` (deterministic; see module docstring)."""

    def __init__(
        self,
        clock: VirtualClock | None = None,
        slice_checkpoints: int = 1000,
        slice_time: float = 0.001,
        run_ahead: bool = False,
    ) -> None:
        super().__init__()
        self.clock: VirtualClock = clock if clock is not None else VirtualClock()
        # FAST mode: controller waits are not paced to real time (module docstring).
        self.run_ahead = run_ahead
        self.slice_checkpoints = slice_checkpoints
        self.slice_time = slice_time
        self.yield_cost = max(1, slice_checkpoints // 10)
        self._ready: deque[ThreadCtx] = deque()
        self._running: ThreadCtx | None = None
        # (deadline ns, sequence, waiting thread, its wait id, or a callback): a min-heap
        self._timers: list[tuple[int, int, ThreadCtx | None, int, Callable[[], None] | None]] = []
        self._external = 0
        self._connections = 0  # open connections to the outside world (hold_real_time)
        self._idle_real: float | None = None  # monotonic() when the token went idle
        self._idle_virtual = 0  # ns
        self._pacer_gen = 0
        self._pacer_handle: TimerHandle | None = None  # the one pending pacing wake-up
        self._in_dispatch = False

    # -- token handling (call with the lock held) ----------------------------------------------------

    def _make_ready(self, ctx: ThreadCtx) -> None:
        ctx.phase = Phase.READY
        self._ready.append(ctx)

    def _kick(self) -> None:
        if self._running is None and not self._in_dispatch:
            self._dispatch()

    def _fire_due(self) -> None:
        t_now = self.clock.ns
        while self._timers and self._timers[0][0] <= t_now:
            _, _, ctx, wid, callback = heapq.heappop(self._timers)
            if callback is not None:
                callback()
            elif ctx is not None and ctx.wait_id == wid and ctx.phase == Phase.BLOCKED:
                self._wake(ctx, timed_out=True)

    def _next_deadline(self) -> int | None:
        """Earliest live deadline in ns (stale entries are dropped on the way)."""
        while self._timers:
            _, _, ctx, wid, callback = self._timers[0]
            if callback is not None or (ctx is not None and ctx.wait_id == wid and ctx.phase == Phase.BLOCKED):
                return self._timers[0][0]
            heapq.heappop(self._timers)  # a wait that already ended
        return None

    def _catch_up_idle_time(self) -> None:
        """After an idle spell with external waiters, virtual time has run at real-time pace."""
        if self._idle_real is not None:
            elapsed = time.monotonic() - self._idle_real
            target = self._idle_virtual + to_ns(elapsed)
            nd = self._next_deadline()
            if nd is not None:
                target = min(target, nd)
            self.clock.advance_to_ns(target)
            self._idle_real = None
            self._fire_due()

    def _dispatch(self, caller: ThreadCtx | None = None) -> bool:
        """Give the token to the next runnable thread, jumping time forward if nobody is runnable.

        Timer callbacks fired from here may make threads ready; ``_in_dispatch`` stops them from
        dispatching recursively.  Returns True when the token went to ``caller`` — the thread
        that has just parked itself and is dispatching on its way out: its own wait is over
        already (nobody else could run before it), so it is not signalled through its ``go``
        event and keeps running without waiting for it (``_block``'s fast path).
        """
        self._in_dispatch = True
        try:
            self._catch_up_idle_time()
            self._fire_due()
            while not self._ready:
                nd = self._next_deadline()
                # With no GPL thread alive, or nobody outside driving the run, time stands still.
                if nd is None or not self.live or self.drivers == 0 or (self._paced() and not self._may_run_ahead(nd)):
                    self._go_idle(nd)
                    return False
                self.clock.advance_to_ns(nd)
                self._fire_due()
            nxt = self._ready.popleft()
            nxt.phase = Phase.RUNNING
            self._running = nxt
            if nxt is caller:
                return True
            nxt.go.set()
            return False
        finally:
            self._in_dispatch = False

    def _may_run_ahead(self, deadline: int) -> bool:
        """FAST mode, paced run: may time jump to ``deadline`` anyway (lock held)?

        Yes while some blocked thread waits for the controller and ``deadline`` comes no later
        than the last such wait ends: the controller's own work (a motion, homing, a power-up)
        is what the program waits for, and nothing from outside is awaited for longer than that.
        """
        if not self.run_ahead:
            return False
        horizon = max(
            (c.busy_until for c in self.live if c.busy_until is not None and c.phase == Phase.BLOCKED),
            default=None,
        )
        return horizon is not None and deadline <= horizon

    def _go_idle(self, next_deadline: int | None) -> None:
        self._running = None
        # Only external waits make idle time count: otherwise a stalled program stays frozen.
        if self._paced() and self._idle_real is None:
            self._idle_real = time.monotonic()
            self._idle_virtual = self.clock.ns
        self._cancel_pacing()  # a new idle spell supersedes the previous one's wake-up
        if next_deadline is not None and self._paced() and self.drivers > 0:
            gen = self._pacer_gen
            delay = max(0.0, (next_deadline - self.clock.ns) / 1e9)
            self._pacer_handle = self._real_timer.schedule(delay, lambda: self._pacer_fire(gen, next_deadline))
        self._changed.notify_all()

    def _driver_left(self) -> None:
        """With nobody outside driving the run, time stands still: drop the pacing wake-up.

        It would do nothing when it fires (see ``_pacer_fire``), but a wake-up planned for a far
        deadline (a thread sleeping for an hour when the notebook cell or test gave up on the
        run) would keep this scheduler — and its session's robots — reachable from the timer
        thread until then.  The next driver re-plans it (``_kick`` → ``_dispatch`` → ``_go_idle``).
        """
        if self.drivers == 0:
            self._cancel_pacing()

    def _cancel_pacing(self) -> None:
        """Forget the pending pacing wake-up (lock held).

        Bumping the generation also covers one that is already firing: ``_pacer_fire`` waits
        for the lock, then sees a newer generation and does nothing.
        """
        self._pacer_gen += 1
        self._real_timer.cancel(self._pacer_handle)
        self._pacer_handle = None

    def _pacer_fire(self, gen: int, deadline: int) -> None:
        with self._lock:
            if gen == self._pacer_gen:
                self._pacer_handle = None
            if gen != self._pacer_gen or self._running is not None or self.drivers == 0:
                return
            self._idle_real = None
            self.clock.advance_to_ns(deadline)
            self._dispatch()

    def _switch_away(self, ctx: ThreadCtx) -> bool:
        """``ctx`` (the token holder, lock held) has parked itself: pass the token on.  True when
        it came straight back to ``ctx`` (see ``_dispatch``): ``ctx`` must not wait for it."""
        self._running = None
        return self._dispatch(ctx)

    def _await_token(self, ctx: ThreadCtx) -> None:
        ctx.go.wait()
        ctx.go.clear()

    # -- scheduler hooks ---------------------------------------------------------------------------

    def _wait_first_turn(self, ctx: ThreadCtx) -> None:
        self._await_token(ctx)

    def _block(
        self,
        ctx: ThreadCtx,
        queue: WaitQueue | None,
        deadline: float | None,
        until: Callable[[], object] | None = None,
    ) -> bool:
        with self._lock:
            # As in RealScheduler._block: an Abort from outside the program (Simulation.stop on
            # Ctrl-C) may land after the caller's last look; _interrupt only wakes BLOCKED threads.
            if ctx.abort_requested or (until is not None and until()):
                return True
            ctx.wait_id += 1
            ctx.phase = Phase.BLOCKED
            ctx.timed_out = False
            if queue is not None:
                queue.waiters.append((ctx, ctx.wait_id))
            if deadline is not None:
                heapq.heappush(self._timers, (to_ns(deadline), next(self._seq), ctx, ctx.wait_id, None))
            if self._switch_away(ctx):
                # Fast path: nobody else could run before this wait ended (one GPL thread, as a
                # rule): time has moved on and the token is back, without a thread switch.
                if queue is not None:
                    queue.waiters = [w for w in queue.waiters if w[0] is not ctx]
                return not ctx.timed_out
        self._await_token(ctx)
        if queue is not None:
            with self._lock:
                queue.waiters = [w for w in queue.waiters if w[0] is not ctx]
        return not ctx.timed_out

    def run_alone_until(self, t: float) -> bool:
        """See :meth:`Scheduler.run_alone_until`.

        "Nothing can happen before ``t``": the caller holds the token, no other thread is
        runnable, no deadline or timer callback (an I/O rule) falls at or before ``t``, time may
        jump (someone drives the run, no connection to the outside world paces it), and no
        Suspend/Abort is pending for the caller.  Then the ordinary wait — register, dispatch,
        jump to ``t``, wake the caller, hand it the token — would end with nothing but time
        moved to ``t``, and that is all this does: no wait-queue entry, no timer, no Event.  A
        ``WaitForEOM`` or ``Thread.Sleep`` of a one-thread program takes it.  The lock is still
        taken, once: threads the scheduler does not run (a notebook's ``call_at``, the real-time
        pacer) change the timers under it."""
        ctx = _tls.ctx
        try:
            t_ns = to_ns(t)
        except (OverflowError, ValueError):
            return False
        with self._lock:
            if (ctx is None or self._running is not ctx or self._ready or self.drivers == 0 or self._paced()
                    or self._idle_real is not None or ctx.abort_requested or ctx.suspend_requested
                    or ctx.saved_budget is not None):
                return False
            deadline = self._next_deadline()
            if deadline is not None and deadline <= t_ns:
                return False
            self.clock.advance_to_ns(t_ns)
            return True

    def _wake(self, ctx: ThreadCtx, timed_out: bool) -> None:
        ctx.wait_id += 1  # invalidates the other half of the wait (timer or queue entry)
        ctx.timed_out = timed_out
        self._make_ready(ctx)

    def finish(self, ctx: ThreadCtx) -> None:
        with self._lock:
            ctx.phase = Phase.DONE
            if ctx in self.live:
                self.live.remove(ctx)
            self._running = None
            self._dispatch()
            self._changed.notify_all()

    def yield_now(self) -> None:
        """``Thread.Sleep(0)``: costs ``yield_cost`` checkpoints of the slice, then yields.

        Charging it keeps EX-31's ``While TestAndSet(...) <> 0 : Thread.Sleep(0)`` spin cheap in
        wall time and lets time pass for a thread that only yields.
        """
        with self.adopted() as ctx:
            self._service_requests(ctx)
            ctx.budget -= self.yield_cost
            if ctx.budget <= 0:
                self._end_slice(ctx)
            else:
                self._yield(ctx)
            self._service_requests(ctx)

    def _yield(self, ctx: ThreadCtx) -> None:
        with self._lock:
            if not self._ready:
                return
            ctx.phase = Phase.READY
            self._ready.append(ctx)
            if self._switch_away(ctx):
                return
        self._await_token(ctx)

    def _checkpoint_slow(self, ctx: ThreadCtx) -> None:
        if ctx.saved_budget is not None:  # forced by a Suspend/Abort request, not a used-up slice
            self._service_requests(ctx)
            return
        self._end_slice(ctx)
        self._service_requests(ctx)

    def _end_slice(self, ctx: ThreadCtx) -> None:
        """The slice is used up: charge its virtual time, go to the back of the queue."""
        ctx.budget = self.slice_checkpoints
        with self._lock:
            self.clock.advance_by(self.slice_time)
            self._fire_due()
        self._yield(ctx)

    def call_at(self, t: float, callback: Callable[[], None]) -> None:
        with self._lock:
            if self.clock.reached(t):
                callback()
                return
            heapq.heappush(self._timers, (to_ns(t), next(self._seq), None, 0, callback))
            if self._running is None and not self._in_dispatch:
                self._dispatch()  # idle: jump to it now, or re-arm the real-time pacer

    def release_timers(self, *, drop_pending: bool = False) -> None:
        """See :meth:`Scheduler.release_timers`; the pacing wake-up is always dropped here.

        Dropping it loses nothing: ``_go_idle`` plans a new one at the next idle spell, and the
        virtual ``call_at`` callbacks live in the virtual timer heap, not on the real-time thread.
        """
        with self._lock:
            self._cancel_pacing()
        self._real_timer.close(drop_pending=drop_pending)

    def _paced(self) -> bool:
        """Virtual time may not run ahead of real time: the outside world is involved."""
        return self._external > 0 or self._connections > 0

    def _hold_real_time(self, delta: int) -> None:
        with self._lock:
            self._connections += delta
            if delta < 0 and self._running is None and not self._in_dispatch:
                self._dispatch()  # free to jump again: re-plan the idle time

    def _enter_external(self, ctx: ThreadCtx) -> None:
        with self._lock:
            ctx.phase = Phase.EXTERNAL
            self._external += 1
            self._switch_away(ctx)

    def _leave_external(self, ctx: ThreadCtx) -> None:
        with self._lock:
            self._external -= 1
            self._make_ready(ctx)
            self._kick()
        self._await_token(ctx)

    def is_stalled(self) -> bool:
        with self._lock:
            return (
                self._running is None
                and not self._ready
                and self._external == 0
                and self._next_deadline() is None
                and any(c.phase == Phase.BLOCKED for c in self.live)
            )


class RealScheduler(Scheduler):
    """Preemptive scheduling on real (optionally scaled) time."""

    def __init__(self, clock: RealClock | None = None, slice_checkpoints: int = 1000) -> None:
        super().__init__()
        self.clock: RealClock = clock if clock is not None else RealClock()
        self.slice_checkpoints = slice_checkpoints

    def _make_ready(self, ctx: ThreadCtx) -> None:
        ctx.phase = Phase.RUNNING

    def _wait_first_turn(self, ctx: ThreadCtx) -> None:
        pass

    def _block(
        self,
        ctx: ThreadCtx,
        queue: WaitQueue | None,
        deadline: float | None,
        until: Callable[[], object] | None = None,
    ) -> bool:
        with self._changed:
            # An Abort requested after the caller's last look is noticed here, not after the wait:
            # _interrupt only wakes threads that are already BLOCKED.
            if ctx.abort_requested or (until is not None and until()):
                return True
            ctx.wait_id += 1
            ctx.phase = Phase.BLOCKED
            ctx.notified = False
            ctx.timed_out = False
            if queue is not None:
                queue.waiters.append((ctx, ctx.wait_id))
            while not ctx.notified:
                if deadline is None:
                    self._changed.wait()
                    continue
                remaining = self.clock.real_seconds(deadline - self.clock.now())
                if remaining <= 0:
                    ctx.timed_out = True
                    break
                self._changed.wait(remaining)
            ctx.wait_id += 1
            ctx.phase = Phase.RUNNING
            if queue is not None:
                queue.waiters = [w for w in queue.waiters if w[0] is not ctx]
            return not ctx.timed_out

    def _wake(self, ctx: ThreadCtx, timed_out: bool) -> None:
        ctx.notified = True
        self._changed.notify_all()

    def finish(self, ctx: ThreadCtx) -> None:
        with self._changed:
            ctx.phase = Phase.DONE
            if ctx in self.live:
                self.live.remove(ctx)
            self._changed.notify_all()

    def yield_now(self) -> None:
        ctx = _tls.ctx
        if ctx is not None:
            self._service_requests(ctx)
        time.sleep(0)

    def _checkpoint_slow(self, ctx: ThreadCtx) -> None:
        if ctx.saved_budget is not None:
            ctx.saved_budget = None
        ctx.budget = self.slice_checkpoints
        self._service_requests(ctx)
        time.sleep(0)  # let a preempted lock holder run

    def sleep_until(self, t: float) -> None:
        ctx = _tls.ctx
        if ctx is None:
            delay = self.clock.real_seconds(t - self.clock.now())
            if delay > 0:
                time.sleep(delay)
            return
        ctx.waiting_on = "sleep"
        while not self.clock.reached(t):
            self.wait(None, t)

    def call_at(self, t: float, callback: Callable[[], None]) -> None:
        def fire() -> None:
            with self._lock:
                callback()

        delay = self.clock.real_seconds(t - self.clock.now())
        if delay <= 0:
            fire()
            return
        self._real_timer.schedule(delay, fire)
