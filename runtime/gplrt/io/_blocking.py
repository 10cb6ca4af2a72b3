"""The one place where a GPL thread waits on the outside world.

Every blocking wait in ``gplrt.io`` (socket accept/receive/connect/send, a Modbus transaction, a
serial read) runs through :func:`blocking_call`.  Why one helper: the GPL scheduler
(``gplrt.threads.scheduler``) may run GPL threads one at a time, or advance a *virtual* clock when
every thread waits.  A thread blocked on a real socket must release the scheduler so other GPL
threads keep running, and must not count as "waiting on virtual time": the hook every wait runs in
is the scheduler's :func:`~gplrt.threads.scheduler.external_wait` (harmless outside GPL threads).
A test may put its own in its place:

    from gplrt.io import _blocking
    previous = _blocking.set_blocking_hook(my_hook)

``my_hook(timeout)`` must return a context manager; it is entered just before the wait and exited
right after it (also when the wait raises).  ``timeout`` is the real-time bound in seconds the
operation will wait at most, or ``None`` for "no bound" (e.g. ``AcceptSocket`` with no timeout).

Timeouts themselves stay real: sockets talk to real peers, so their deadlines are wall-clock
deadlines, enforced by the operation ``fn`` (socket timeouts), not by this helper.

Inside ``fn`` the wait itself goes through :func:`wait_ready`, which polls in slices of
:data:`POLL_SLICE` seconds.  Why not one long ``select``/``accept``: Python cannot interrupt a
thread blocked in one, and closing the socket from another thread does not wake it on Linux.  A
controller's ``Thread.Abort`` ends a thread wherever it waits, and a server that stops its
listener or closes a connection wakes the thread blocked on it; between slices :func:`wait_ready`
honours a pending Abort (``gplrt.threads.scheduler.abort_point``) and the caller's ``check``
(e.g. "the socket was closed meanwhile": -1707).  Data still arrives without delay: a slice ends
as soon as the descriptor is ready.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable
from typing import ContextManager, TypeVar

from gplrt.threads.scheduler import abort_point, external_wait, hold_real_time

T = TypeVar("T")

BlockingHook = Callable[[float | None], ContextManager[object]]


def _scheduler_hook(timeout: float | None) -> ContextManager[object]:
    """The calling GPL thread waits on the outside world (``external_wait``)."""
    return external_wait()


def _no_hook(timeout: float | None) -> ContextManager[object]:
    return contextlib.nullcontext()


_hook: BlockingHook = _scheduler_hook


def set_blocking_hook(hook: BlockingHook | None) -> BlockingHook:
    """Put ``hook`` in place of the scheduler's (``None``: a no-op); returns the hook it replaced,
    so that a test can put the scheduler's back."""
    global _hook
    previous, _hook = _hook, (hook if hook is not None else _no_hook)
    return previous


def blocking_call(fn: Callable[[], T], timeout: float | None) -> T:
    """Run ``fn()``, a call that may block for up to ``timeout`` seconds, inside the hook."""
    with _hook(timeout):
        return fn()


POLL_SLICE = 0.05  # seconds between looks at Abort requests and closed sockets while waiting


def wait_ready(ready: Callable[[float], bool], timeout: float | None,
               check: Callable[[], None] | None = None) -> bool:
    """Wait until ``ready(step)`` returns True (True) or ``timeout`` real seconds pass (False).

    ``ready(step)`` may itself block for up to ``step`` seconds (a ``select`` or a condition
    wait); ``timeout`` None waits forever and 0 looks once.  Before every slice a pending
    ``Thread.Abort`` of the calling GPL thread unwinds it, and ``check()`` may raise (a socket
    closed by another thread).
    """
    deadline = None if timeout is None else time.monotonic() + max(0.0, timeout)
    while True:
        abort_point()
        if check is not None:
            check()
        step = POLL_SLICE if deadline is None else max(0.0, min(POLL_SLICE, deadline - time.monotonic()))
        if ready(step):
            return True
        if deadline is not None and time.monotonic() >= deadline:
            return False


# -- open connections ------------------------------------------------------------------------------
#
# Besides blocking waits, the scheduler must know while the program holds a connection to the outside
# world open (a listening or connected socket): then virtual time must not run ahead of real time, even
# if no thread is blocked in a call (a server polling ``Pending()`` between sleeps).  ``opened()`` is
# called when such a connection opens and returns the function to call when it closes.

Release = Callable[[], None]
OpenHook = Callable[[], Release]


def _no_release() -> None:
    pass


def _no_open_hook() -> Release:
    return _no_release


_open_hook: OpenHook = hold_real_time  # the scheduler paces virtual time while it is open


def set_open_hook(hook: OpenHook | None) -> OpenHook:
    """Put ``hook`` in place of the scheduler's ``hold_real_time`` (``None``: a no-op); returns
    the hook it replaced."""
    global _open_hook
    previous, _open_hook = _open_hook, (hook if hook is not None else _no_open_hook)
    return previous


def opened() -> Release:
    """A connection to the outside world opened; call the result (once) when it closes."""
    return _open_hook()
